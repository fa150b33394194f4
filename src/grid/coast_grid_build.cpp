// CoastGrid::build: a grid made from a coastline, clipping each cell's segments with GEOS. Apart
// from coast_grid.cpp (the grid's queries) so that a program that only loads grid files (the
// `shoal` executable's probe of a .shoalgrid, a simulator through libshoal_c) need not link GEOS
// from a static library (docs/performance.md, "Start-up").
#include <shoal/grid/coast_grid.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>

#include "geo/geos_context.hpp"
#include "util/parse_util.hpp"
#include <shoal/util/error.hpp>

namespace shoal::grid {

using geo::XY;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }


/// Candidate reference points (fractions of a cell), tried in turn until none lies on a segment.
constexpr double ref_candidates[][2] = {
    {0.41421356237309515, 0.73205080756887719}, {0.61803398874989485, 0.32471795724474602},
    {0.25992104989487316, 0.58740105196819947}, {0.77976314968460610, 0.14869835499703500},
};

/// True when closed segment ab meets the closed box.
bool segment_meets_box(XY a, XY b, const geo::Box& r) {
    if (std::max(a.x, b.x) < r.minx || std::min(a.x, b.x) > r.maxx || std::max(a.y, b.y) < r.miny ||
        std::min(a.y, b.y) > r.maxy)
        return false;
    // Separating axis: the line ab separates the box when all four corners are strictly on one side.
    const double o1 = geo::orient(a, b, {r.minx, r.miny}), o2 = geo::orient(a, b, {r.maxx, r.miny});
    const double o3 = geo::orient(a, b, {r.maxx, r.maxy}), o4 = geo::orient(a, b, {r.minx, r.maxy});
    return !((o1 > 0 && o2 > 0 && o3 > 0 && o4 > 0) || (o1 < 0 && o2 < 0 && o3 < 0 && o4 < 0));
}

struct Incidence {
    std::uint32_t cell;
    std::uint32_t line;
    std::uint32_t seg;
};

}  // namespace

CoastGrid CoastGrid::build(const coast::Coastline& coast, geo::LocalFrame frame, double cell_m, BuildStats* stats) {
    const auto t0 = Clock::now();
    std::vector<coast::LocalPolyline> lines = coast::project(coast, frame);
    const double project_s = seconds_since(t0);
    CoastGrid g = build(lines, std::move(frame), cell_m, stats);
    if (stats) {
        stats->project_s = project_s;
        stats->total_s += project_s;
    }
    g.m_source.input_vertices = 0;
    for (const auto& l : coast.layers) {
        g.m_source.input_vertices += l.vertices;
        g.m_source.layers.push_back(l.file + ":" + l.layer);
        g.m_source.hazard_features += l.hazards;
        g.m_source.unknown_depth += l.unknown_depth;
        g.m_source.structure_features += l.structures;
    }
    return g;
}

CoastGrid CoastGrid::build(const std::vector<coast::LocalPolyline>& lines, geo::LocalFrame frame, double cell_m,
                           BuildStats* stats) {
    if (!(cell_m > 0) || !(cell_m <= max_cell_m)) throw UsageError("cell size must be > 0 and at most " + track::detail::fmt(max_cell_m) + " metres");
    const auto t0 = Clock::now();
    CoastGrid g(std::move(frame));
    g.m_cell = cell_m;
    geo::Box ext;
    std::uint64_t vertices = 0;
    if (lines.size() >= boundary_bit) throw UsageError("too many coastline polylines for one grid");
    g.m_hazards.reserve(lines.size());
    for (const auto& l : lines) {
        for (const XY& p : l.points) ext.extend(p);
        vertices += l.points.size();
        g.m_has_land_side = g.m_has_land_side || l.land_left;
        g.m_source.land_polylines += l.land_left ? 1 : 0;
        g.m_source.shallow_polylines += l.hazard.kind == coast::HazardKind::shallow ? 1 : 0;
        g.m_source.danger_polylines += l.hazard.kind == coast::HazardKind::danger ? 1 : 0;
        g.m_source.structure_polylines += l.hazard.kind == coast::HazardKind::structure ? 1 : 0;
        g.m_hazards.push_back(l.hazard);
    }
    g.m_source.polylines = lines.size();
    g.m_source.input_vertices = vertices;
    if (ext.empty()) throw InputError("the coastline has no vertices");
    const double pad = 1e-6 * cell_m + 1e-6;
    g.m_x0 = ext.minx - pad;
    g.m_y0 = ext.miny - pad;
    const double fnx = std::floor((ext.maxx + pad - g.m_x0) / cell_m) + 1;
    const double fny = std::floor((ext.maxy + pad - g.m_y0) / cell_m) + 1;
    if (fnx * fny > static_cast<double>(max_cells)) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "a %.3g m cell over this %.0f x %.0f km extent needs %.3g cells, more than the limit of %llu; choose a larger BuildRequest::cell_m",
                      cell_m, (ext.maxx - ext.minx) / 1000, (ext.maxy - ext.miny) / 1000, fnx * fny,
                      static_cast<unsigned long long>(max_cells));
        throw UsageError(buf);
    }
    g.m_nx = static_cast<int>(fnx);
    g.m_ny = static_cast<int>(fny);
    // Cells are clipped with their rectangle grown by a few units in the last place of the
    // largest coordinate, so that a segment lying exactly on a cell border (which
    // GEOSClipByRect drops) is kept by both neighbours, and little else is doubled.
    const double mag = std::max({std::fabs(g.m_x0), std::fabs(g.m_y0), std::fabs(g.m_x0 + fnx * cell_m),
                                 std::fabs(g.m_y0 + fny * cell_m)});
    g.m_clip_slack = std::max(1e-12, 16 * (std::nextafter(mag, INFINITY) - mag));
    const double clip_slack_m = g.m_clip_slack;

    // 1. Walk the data: which cells does each segment touch? Only those are clipped.
    std::vector<Incidence> inc;
    inc.reserve(vertices * 2);
    for (std::uint32_t li = 0; li < lines.size(); ++li) {
        const auto& pts = lines[li].points;
        for (std::uint32_t k = 0; k + 1 < pts.size(); ++k) {
            const XY a = pts[k], b = pts[k + 1];
            const int i0 = std::max(0, g.col_of(std::min(a.x, b.x) - clip_slack_m));
            const int i1 = std::min(g.m_nx - 1, g.col_of(std::max(a.x, b.x) + clip_slack_m));
            const int j0 = std::max(0, g.row_of(std::min(a.y, b.y) - clip_slack_m));
            const int j1 = std::min(g.m_ny - 1, g.row_of(std::max(a.y, b.y) + clip_slack_m));
            const bool single = (i0 == i1) || (j0 == j1);  // a row or column of cells: all are met
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i)
                    if (single || segment_meets_box(a, b, g.cell_box(i, j).grown(clip_slack_m)))
                        inc.push_back({static_cast<std::uint32_t>(j * g.m_nx + i), li, k});
        }
    }
    std::sort(inc.begin(), inc.end(), [](const Incidence& x, const Incidence& y) {
        return std::tie(x.cell, x.line, x.seg) < std::tie(y.cell, y.line, y.seg);
    });

    // 2. Clip each touched cell's runs of consecutive segments with GEOS, order kept.
    geo::GeosContext geos;
    g.m_slot.assign(static_cast<std::size_t>(g.m_nx) * static_cast<std::size_t>(g.m_ny), water_slot);
    g.m_seg_offset.push_back(0);
    std::uint64_t clip_calls = 0;
    std::vector<std::vector<XY>> pieces;
    for (std::size_t s = 0; s < inc.size();) {
        const std::uint32_t cell = inc[s].cell;
        const int ci = static_cast<int>(cell % static_cast<std::uint32_t>(g.m_nx));
        const int cj = static_cast<int>(cell / static_cast<std::uint32_t>(g.m_nx));
        const geo::Box r = g.cell_box(ci, cj).grown(clip_slack_m);
        const std::size_t before = g.m_segments.size();
        while (s < inc.size() && inc[s].cell == cell) {
            const std::uint32_t li = inc[s].line;
            const std::uint32_t first = inc[s].seg;
            std::uint32_t last = first;
            ++s;
            while (s < inc.size() && inc[s].cell == cell && inc[s].line == li && inc[s].seg == last + 1) last = inc[s++].seg;
            const auto& pts = lines[li].points;
            geo::GeomPtr run = geo::make_linestring(geos, pts.data() + first, last - first + 2);
            geo::GeomPtr clipped =
                geo::own(geos, GEOSClipByRect_r(geos, run.get(), r.minx, r.miny, r.maxx, r.maxy), "clipping a cell");
            ++clip_calls;
            pieces.clear();
            geo::collect_lines(geos, clipped.get(), pieces);
            const std::uint32_t info = li | (lines[li].land_left ? boundary_bit : 0u);
            for (const auto& piece : pieces)
                for (std::size_t k = 0; k + 1 < piece.size(); ++k)
                    if (!(piece[k] == piece[k + 1])) {
                        g.m_segments.push_back({piece[k], piece[k + 1]});
                        g.m_seg_info.push_back(info);
                    }
        }
        if (g.m_segments.size() > before) {
            g.m_slot[cell] = static_cast<std::uint32_t>(g.m_seg_offset.size() - 1);
            g.m_seg_offset.push_back(static_cast<std::uint32_t>(g.m_segments.size()));
        }
    }
    const double clip_s = seconds_since(t0);

    // 3. Land or water: winding numbers along each row of reference points, from the west
    //    edge (outside every ring), counting signed crossings of land boundary segments;
    //    with depth areas and dangers, at every level of charted depth.
    const auto t1 = Clock::now();
    g.assign_levels();
    g.m_ref_winding.assign(g.m_seg_offset.size() - 1, 0);
    bool settled = false;
    for (const auto& cand : ref_candidates) {
        g.m_ref_fx = cand[0];
        g.m_ref_fy = cand[1];
        g.assign_windings(lines);
        if (g.reference_points_clear()) {
            settled = true;
            break;
        }
    }
    if (!settled) throw LibraryError("no reference point of a coast cell is clear of the coastline");
    g.compute_chunk_boxes();
    if (stats) {
        stats->clip_s = clip_s;
        stats->state_s = seconds_since(t1);
        stats->total_s = seconds_since(t0);
        stats->incidences = inc.size();
        stats->clip_calls = clip_calls;
    }
    return g;
}

void CoastGrid::assign_windings(const std::vector<coast::LocalPolyline>& lines) {
    struct Crossing {
        double x;
        int sign;
        std::uint16_t level;
    };
    const std::size_t top = m_level_depth.size();  // the level of every hazard
    std::vector<std::int32_t> per_level(top + 1, 0), prefix(top + 1, 0);
    m_lw_offset.assign(top ? m_ref_winding.size() + 1 : 0, 0);
    m_lw_level.clear();
    m_lw_winding.clear();
    m_land_level.assign(top ? m_slot.size() : 0, 0);

    std::vector<std::uint32_t> row_start(static_cast<std::size_t>(m_ny) + 1, 0);
    auto row_y = [&](int j) { return m_y0 + (j + m_ref_fy) * m_cell; };
    // Rows j whose line y_j satisfies min(ya,yb) <= y_j < max(ya,yb) (half-open rule).
    auto rows_of = [&](XY a, XY b, int& j0, int& j1) {
        const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
        j0 = std::max(0, static_cast<int>(std::ceil((lo - m_y0) / m_cell - m_ref_fy)) - 1);
        j1 = std::min(m_ny - 1, static_cast<int>(std::floor((hi - m_y0) / m_cell - m_ref_fy)) + 1);
        while (j0 <= j1 && row_y(j0) < lo) ++j0;
        while (j1 >= j0 && !(row_y(j1) < hi)) --j1;
    };
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<Crossing> crossings(pass ? row_start.back() : 0);
        std::vector<std::uint32_t> fill(row_start.begin(), row_start.end() - 1);
        for (std::size_t li = 0; li < lines.size(); ++li) {
            const auto& l = lines[li];
            if (!l.land_left) continue;
            const std::uint16_t level = polyline_level(static_cast<std::uint32_t>(li));
            for (std::size_t k = 0; k + 1 < l.points.size(); ++k) {
                const XY a = l.points[k], b = l.points[k + 1];
                if (a.y == b.y) continue;
                int j0, j1;
                rows_of(a, b, j0, j1);
                for (int j = j0; j <= j1; ++j) {
                    if (pass == 0) {
                        ++row_start[static_cast<std::size_t>(j) + 1];
                    } else {
                        const double y = row_y(j);
                        const double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                        crossings[fill[static_cast<std::size_t>(j)]++] = {x, b.y < a.y ? 1 : -1, level};
                    }
                }
            }
        }
        if (pass == 0) {
            std::partial_sum(row_start.begin(), row_start.end(), row_start.begin());
            continue;
        }
        for (int j = 0; j < m_ny; ++j) {
            auto first = crossings.begin() + row_start[static_cast<std::size_t>(j)];
            auto last = crossings.begin() + row_start[static_cast<std::size_t>(j) + 1];
            std::sort(first, last, [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
            int w = 0;
            std::fill(per_level.begin(), per_level.end(), 0);
            auto it = first;
            for (int i = 0; i < m_nx; ++i) {
                const double rx = m_x0 + (i + m_ref_fx) * m_cell;
                for (; it != last && it->x < rx; ++it) {
                    w += it->sign;
                    if (top) per_level[it->level] += it->sign;
                }
                const std::size_t c = static_cast<std::size_t>(j) * static_cast<std::size_t>(m_nx) + static_cast<std::size_t>(i);
                std::uint32_t& s = m_slot[c];
                if (s < land_slot)
                    m_ref_winding[s] = w;
                else
                    s = w > 0 ? land_slot : water_slot;
                if (!top || (s >= land_slot && w <= 0)) continue;
                // The winding at each level: the crossings of polylines of that level or below.
                std::partial_sum(per_level.begin(), per_level.end(), prefix.begin());
                if (s < land_slot) {  // coast cells come in row order: their levels are appended
                    std::int32_t last_w = 0;
                    for (std::size_t lv = 0; lv < top; ++lv)
                        if (prefix[lv] != last_w) {
                            m_lw_level.push_back(static_cast<std::uint16_t>(lv));
                            m_lw_winding.push_back(prefix[lv]);
                            last_w = prefix[lv];
                        }
                    m_lw_offset[s + 1] = static_cast<std::uint32_t>(m_lw_level.size());
                } else {
                    std::size_t lv = 0;
                    while (lv < top && prefix[lv] <= 0) ++lv;
                    m_land_level[c] = static_cast<std::uint16_t>(lv);
                }
            }
        }
    }
}

}  // namespace shoal::grid
