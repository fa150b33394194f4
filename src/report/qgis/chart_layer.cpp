#include "report/qgis/chart_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <system_error>
#include <tuple>

#include "geo/geos_context.hpp"
#include "util/parallel.hpp"
#include <shoal/geo/local_frame.hpp>
#include <shoal/util/error.hpp>

namespace shoal::report {

namespace {

constexpr int col_offset = 3600, row_offset = 1800;

double signed_area(const std::vector<geo::LonLat>& r) {
    double a = 0;
    for (std::size_t i = 1; i < r.size(); ++i) a += r[i - 1].lon * r[i].lat - r[i].lon * r[i - 1].lat;
    return a / 2;
}

struct Ring {
    const coast::Polyline* line;
    double area;  ///< signed: > 0 a shell, < 0 a hole
    geo::LonLat min, max;
    geo::GeomPtr polygon = {};  ///< the ring as a valid polygon (repaired if need be), made at its first tile
};

/// What a feature groups: kind, danger, depth (NaN compares equal to NaN here, and last).
struct Group {
    coast::HazardKind kind;
    coast::DangerKind danger;
    double depth;
    bool operator<(const Group& o) const {
        if (kind != o.kind) return kind < o.kind;
        if (danger != o.danger) return danger < o.danger;
        const bool a = std::isnan(depth), b = std::isnan(o.depth);
        if (a || b) return !a && b;
        return depth < o.depth;
    }
};

}  // namespace

std::string tile_key(ChartTile t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "R%04dC%04d", t.row, t.col);
    return buf;
}

std::optional<ChartTile> parse_tile_key(const std::string& key) {
    ChartTile t;
    int used = 0;
    if (std::sscanf(key.c_str(), "R%dC%d%n", &t.row, &t.col, &used) != 2 || used != static_cast<int>(key.size())) return std::nullopt;
    return t;
}

ChartTile tile_of(geo::LonLat p) {
    return {static_cast<int>(std::floor(p.lon / chart_tile_deg)) + col_offset, static_cast<int>(std::floor(p.lat / chart_tile_deg)) + row_offset};
}

void add_tiles_near(std::set<ChartTile>& out, const std::vector<geo::LonLat>& line, double margin_m) {
    ChartTile last_a{0, 0}, last_b{-1, -1};  // the tiles marked last (none yet)
    // The margin in degrees at least and at most over the whole line (a degree of latitude is
    // 110,574-111,694 m; one of longitude shrinks away from the equator). A tile's edge is a
    // monotonic function of the point's coordinate, and the sums are too: when the bounds give
    // the same tiles, so does the point's own margin, which then needs no metres_per_degree.
    double least_lat = 90, most_lat = 0, last_lat = NAN;
    for (const geo::LonLat& p : line)
        if (std::isfinite(p.lat)) {
            least_lat = std::min(least_lat, std::fabs(p.lat));
            most_lat = std::max(most_lat, std::fabs(p.lat));
            if ((p.lat < 0) != (last_lat < 0) && !std::isnan(last_lat)) least_lat = 0;  // the points between cross the equator
            last_lat = p.lat;
        }
    const double dlat_most = margin_m / 110500.0, dlat_least = margin_m / 111800.0;
    const double dlon_most = margin_m / std::max(1.0, geo::metres_per_degree(std::min(most_lat, 89.0)).x()) * 1.001;
    const double dlon_least = margin_m / std::max(1.0, geo::metres_per_degree(std::min(least_lat, 89.0)).x()) * 0.999;
    auto mark = [&](geo::LonLat p) {
        if (!std::isfinite(p.lon) || !std::isfinite(p.lat)) return;
        ChartTile a = tile_of({p.lon - dlon_most, std::max(-90.0, p.lat - dlat_most)});
        ChartTile b = tile_of({p.lon + dlon_most, std::min(89.999999, p.lat + dlat_most)});
        // The point's own tiles lie within these, which are all in `out` when they are the
        // tiles marked last (every tile of a marked box is in): nothing to add.
        if (a == last_a && b == last_b) return;
        if (!(a == tile_of({p.lon - dlon_least, std::max(-90.0, p.lat - dlat_least)}) &&
              b == tile_of({p.lon + dlon_least, std::min(89.999999, p.lat + dlat_least)}))) {  // the point's own margin
            const Eigen::Vector2d m = geo::metres_per_degree(std::clamp(p.lat, -89.0, 89.0));
            const double dlat = margin_m / m.y();
            const double dlon = margin_m / std::max(1.0, m.x());
            a = tile_of({p.lon - dlon, std::max(-90.0, p.lat - dlat)});
            b = tile_of({p.lon + dlon, std::min(89.999999, p.lat + dlat)});
        }
        if (a == last_a && b == last_b) return;  // the tiles of the point before
        for (int r = a.row; r <= b.row; ++r)
            for (int c = a.col; c <= b.col; ++c)
                if (r < last_a.row || r > last_b.row || c < last_a.col || c > last_b.col) out.insert({c, r});  // not in already
        last_a = a;
        last_b = b;
    };
    for (std::size_t i = 0; i < line.size(); ++i) {
        mark(line[i]);
        if (i == 0) continue;
        // Points along the segment no further apart than a quarter of a tile.
        const geo::LonLat a = line[i - 1], b = line[i];
        const double span = std::max(std::fabs(b.lon - a.lon), std::fabs(b.lat - a.lat));
        const int n = static_cast<int>(std::min(1e5, std::ceil(span / (chart_tile_deg / 4))));
        for (int k = 1; k < n; ++k) {
            const double f = static_cast<double>(k) / n;
            mark({a.lon + f * (b.lon - a.lon), a.lat + f * (b.lat - a.lat)});
        }
    }
}

namespace {

/// The chart's closed land-left rings by group, largest first.
std::map<Group, std::vector<Ring>> chart_rings(const coast::Coastline& coast) {
    std::map<Group, std::vector<Ring>> groups;
    for (const auto& pl : coast.polylines) {
        if (!pl.land_left || pl.points.size() < 4 || !(pl.points.front() == pl.points.back())) continue;
        Ring r{&pl, signed_area(pl.points), pl.points[0], pl.points[0]};
        if (r.area == 0) continue;
        for (const auto& p : pl.points) {
            r.min = {std::min(r.min.lon, p.lon), std::min(r.min.lat, p.lat)};
            r.max = {std::max(r.max.lon, p.lon), std::max(r.max.lat, p.lat)};
        }
        groups[{pl.hazard.kind, pl.hazard.danger, pl.hazard.depth_m}].push_back(std::move(r));
    }
    for (auto& [g, rings] : groups)
        std::stable_sort(rings.begin(), rings.end(), [](const Ring& a, const Ring& b) { return std::fabs(a.area) > std::fabs(b.area); });
    return groups;
}

/// One thread's share of the work: its GEOS context and its own rings (no GEOS geometry is
/// read by two threads at once: GEOS promises that only of separate objects), each made a
/// polygon at the first of this thread's tiles it crosses.
struct TileWorker {
    geo::GeosContext ctx;
    std::map<Group, std::vector<Ring>> groups;
};

/// The chart's features of tile `t`, group by group.
void tile_features(TileWorker& w, const ChartTile& t, std::vector<ChartFeature>& out) {
    const geo::GeosContext& ctx = w.ctx;
    auto own = [&](GEOSGeometry* g, const char* what) { return geo::own(ctx, g, what); };
    const double x0 = (t.col - col_offset) * chart_tile_deg, y0 = (t.row - row_offset) * chart_tile_deg;
    const double x1 = x0 + chart_tile_deg, y1 = y0 + chart_tile_deg;
    for (auto& [g, rings] : w.groups) {
        geo::GeomPtr acc;
        // Runs of rings of one sign are unioned together, then added to or taken from the result.
        std::vector<geo::GeomPtr> run;
        int run_sign = 0;
        auto flush = [&] {
            if (run.empty()) return;
            std::vector<GEOSGeometry*> parts;
            for (auto& p : run) parts.push_back(p.release());  // the collection takes them
            run.clear();
            geo::GeomPtr coll = own(GEOSGeom_createCollection_r(ctx, GEOS_GEOMETRYCOLLECTION, parts.data(), static_cast<unsigned>(parts.size())),
                                    "collecting chart rings");
            geo::GeomPtr u = own(GEOSUnaryUnion_r(ctx, coll.get()), "union of chart rings");
            if (run_sign > 0) acc = acc ? own(GEOSUnion_r(ctx, acc.get(), u.get()), "union of chart areas") : std::move(u);
            else if (acc) acc = own(GEOSDifference_r(ctx, acc.get(), u.get()), "holes of chart areas");
        };
        for (Ring& r : rings) {
            if (r.max.lon < x0 || r.min.lon > x1 || r.max.lat < y0 || r.min.lat > y1) continue;
            const int sign = r.area > 0 ? 1 : -1;
            if (sign != run_sign) {
                flush();
                run_sign = sign;
            }
            if (!r.polygon) {  // once, not at every tile it crosses (a mainland's ring crosses many)
                std::vector<geo::XY> pts;
                pts.reserve(r.line->points.size());
                for (const auto& p : r.line->points) pts.push_back({p.lon, p.lat});
                r.polygon = geo::make_polygon(ctx, {pts});
                if (!GEOSisValid_r(ctx, r.polygon.get())) r.polygon = own(GEOSMakeValid_r(ctx, r.polygon.get()), "repairing a chart ring");
            }
            geo::GeomPtr clipped = own(GEOSClipByRect_r(ctx, r.polygon.get(), x0, y0, x1, y1), "clipping a chart ring");
            if (GEOSisEmpty_r(ctx, clipped.get())) continue;
            run.push_back(std::move(clipped));
        }
        flush();
        if (!acc || GEOSisEmpty_r(ctx, acc.get())) continue;
        // Only the areas: the clip and the holes may leave lines or points on the tile's edge.
        acc = own(GEOSClipByRect_r(ctx, acc.get(), x0, y0, x1, y1), "clipping chart areas");
        std::vector<std::vector<std::vector<geo::XY>>> polys;
        geo::collect_polygons(ctx, acc.get(), polys);
        ChartFeature f{t, g.kind, g.danger, g.depth, {}};
        for (auto& poly : polys) {
            auto& dst = f.polygons.emplace_back();
            for (std::size_t k = 0; k < poly.size(); ++k) {
                auto& ring = dst.emplace_back();
                for (const auto& p : poly[k]) ring.push_back({p.x, p.y});
                // Shells counter-clockwise, holes clockwise (as GeoJSON and QGIS expect).
                if ((signed_area(ring) > 0) != (k == 0)) std::reverse(ring.begin(), ring.end());
            }
            if (dst.empty() || std::fabs(signed_area(dst[0])) == 0) f.polygons.pop_back();
        }
        if (!f.polygons.empty()) out.push_back(std::move(f));
    }
}

}  // namespace

std::vector<ChartFeature> chart_features(const coast::Coastline& coast, const std::set<ChartTile>& tiles, unsigned jobs) {
    // Each tile on its own (GEOS gives the same geometry on any thread), gathered in tile order;
    // each thread takes one run of neighbouring tiles (a ring crossing many is made a polygon
    // by as few threads as can be), and stops at its first failing tile (the first of all is
    // the one a single thread would meet).
    if (tiles.empty()) return {};  // no GEOS context either (a run that needs none may not load GEOS)
    const std::vector<ChartTile> list(tiles.begin(), tiles.end());
    std::vector<std::vector<ChartFeature>> per_tile(list.size());
    const std::size_t runs = std::min<std::size_t>(detail::thread_count(jobs), std::max<std::size_t>(1, list.size()));
    detail::parallel_blocks(runs, static_cast<unsigned>(runs), [&](std::size_t b, unsigned) {
        TileWorker w;
        w.groups = chart_rings(coast);
        for (std::size_t k = b * list.size() / runs, end = (b + 1) * list.size() / runs; k < end; ++k) tile_features(w, list[k], per_tile[k]);
    });
    std::vector<ChartFeature> out;
    for (auto& features : per_tile)
        for (auto& f : features) out.push_back(std::move(f));
    return out;
}

}  // namespace shoal::report

#include <shoal/grid/grid_builder.hpp>
#include <shoal/grid/grid_file.hpp>
#include <shoal/report/run_info.hpp>

namespace shoal::report {

std::optional<coast::Coastline> read_chart(const std::vector<std::string>& coast, const grid::CoastGrid& g, const audit::AuditResult& run,
                                           std::string& warning) {
    const bool any_line = std::any_of(run.tracks.begin(), run.tracks.end(), [](const audit::TrackResult& t) {
        return std::any_of(t.summary.lines.begin(), t.summary.lines.end(), [](const auto& line) { return !line.empty(); });
    });
    if (!any_line) return coast::Coastline{};
    const grid::GridSource& src = g.source();
    const std::vector<std::string> paths = grid::coast_sources(coast, g);
    const bool from_grid = coast.size() == 1 && grid::looks_like_grid(coast[0]);
    if (paths.empty() || (from_grid && paths.size() != src.inputs.size())) {
        warning = "the report has no coast layer: the coast files the grid '" + (coast.empty() ? std::string() : coast[0]) +
                  "' was imported from are not there any more (give them as --coast to have the chart in the report)";
        return std::nullopt;
    }
    coast::ImportOptions o;
    o.layers = src.layer_option;
    o.source_crs = src.source_crs;
    if (std::isfinite(src.limiting_depth_m)) {
        o.limiting_depth_m = src.limiting_depth_m;
        o.danger_radius_m = src.danger_radius_m;
    }
    o.depth_field = src.depth_field;
    try {
        return coast::import_coastline(paths, o);
    } catch (const InputError& e) {
        warning = std::string("the report has no coast layer: reading the chart again failed: ") + e.what();
        return std::nullopt;
    }
}

ChartRead::ChartRead(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const audit::AuditResult& run, bool meanwhile) {
    if (meanwhile) {
        try {
            m_thread = std::jthread([this, &coast, &grid, &run] {
                try {
                    m_chart = read_chart(coast, grid, run, m_warning);
                    m_read.set_value(m_chart ? &*m_chart : nullptr);
                } catch (...) {
                    m_read.set_exception(std::current_exception());
                }
            });
            m_later = m_read.get_future().share();
            return;
        } catch (const std::system_error&) {  // no thread to be had: read here
        }
    }
    m_chart = read_chart(coast, grid, run, m_warning);
}

void ChartRead::give(RunInfo& info) const {
    if (meanwhile()) info.chart_later = m_later;
    else info.chart = m_chart ? &*m_chart : nullptr;
}

const std::string& ChartRead::warning() const {
    if (meanwhile()) m_later.wait();
    return m_warning;
}

std::set<ChartTile> tiles_near(const audit::AuditResult& r, unsigned jobs) {
    // The tracks' lines are read where they are (a copy would be 16 bytes a fix), in runs of
    // tracks of about equal fixes, a run's tiles in a set of its own: the union is the same
    // on any number of threads.
    std::vector<std::size_t> fixes;
    for (const auto& t : r.tracks) {
        std::size_t n = 0;
        for (const auto& line : t.summary.lines) n += line.size();
        fixes.push_back(n);
    }
    const std::size_t runs = std::min<std::size_t>(detail::thread_count(jobs), std::max<std::size_t>(1, r.tracks.size()));
    const std::vector<std::size_t> start = detail::weighted_runs(fixes, runs);
    std::vector<std::set<ChartTile>> found(runs);
    detail::parallel_blocks(runs, static_cast<unsigned>(runs), [&](std::size_t b, unsigned) {
        for (std::size_t k = start[b]; k < start[b + 1]; ++k)
            for (const auto& line : r.tracks[k].summary.lines) add_tiles_near(found[b], line);
    });
    std::set<ChartTile> tiles = std::move(found[0]);
    for (std::size_t b = 1; b < runs; ++b) tiles.merge(found[b]);
    return tiles;
}

std::vector<ChartFeature> chart_features_near(const audit::AuditResult& r, const coast::Coastline& chart, unsigned jobs) {
    return chart_features(chart, tiles_near(r, jobs), jobs);
}

}  // namespace shoal::report
