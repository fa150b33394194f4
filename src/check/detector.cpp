#include "check/detector.hpp"

#include <algorithm>
#include <array>
#include <numbers>

namespace shoal::check {

using geo::XY;

LocalPose place(const geo::LocalFrame& frame, const Pose& pose) {
    const double h = pose.heading_deg * std::numbers::pi / 180.0;
    // Columns: the ship's forward and starboard unit vectors in (east, north) metres.
    Eigen::Matrix2d ship_to_en;
    ship_to_en << std::sin(h), std::cos(h), std::cos(h), -std::sin(h);
    return {frame.forward(pose.position), frame.jacobian(pose.position) * ship_to_en};
}

std::vector<XY> hull_outline(const hull::Hull& hull, const LocalPose& pose) {
    std::vector<XY> out;
    out.reserve(hull.contour().size());
    const Eigen::Matrix2d& m = pose.ship_to_local;
    for (const XY& c : hull.contour())
        out.push_back({pose.position.x + m(0, 0) * c.x + m(0, 1) * c.y, pose.position.y + m(1, 0) * c.x + m(1, 1) * c.y});
    return out;
}

namespace {

/// Edges are grouped in chunks of this many consecutive edges, each with its box in the
/// ship-aligned frame, so a coast segment is tested against few hull edges.
constexpr std::size_t chunk_edges = 6;

/// The hull at one pose, in a frame aligned with the ship (origin at the reference point,
/// first axis along the ship's centreline). Rotation only: distances are metres.
struct AlignedHull {
    XY origin;
    XY u, v;  // unit axes in local metres
    std::vector<XY> pts;
    std::vector<geo::Box> chunk_box;
    geo::Box box;        // aligned frame
    geo::Box local_box;  // local metres

    XY to_aligned(XY p) const noexcept {
        const XY d = p - origin;
        return {geo::dot(d, u), geo::dot(d, v)};
    }
    XY to_local(XY q) const noexcept { return origin + q.x * u + q.y * v; }

    void build(const hull::Hull& hull, const LocalPose& pose) {
        origin = pose.position;
        const Eigen::Matrix2d& m = pose.ship_to_local;
        const double len = std::hypot(m(0, 0), m(1, 0));
        u = {m(0, 0) / len, m(1, 0) / len};
        v = {-u.y, u.x};
        const auto& c = hull.contour();
        pts.resize(c.size());
        box = {};
        local_box = {};
        for (std::size_t i = 0; i < c.size(); ++i) {
            const XY w{m(0, 0) * c[i].x + m(0, 1) * c[i].y, m(1, 0) * c[i].x + m(1, 1) * c[i].y};
            pts[i] = {geo::dot(w, u), geo::dot(w, v)};
            box.extend(pts[i]);
            local_box.extend(origin + w);
        }
        const std::size_t n = pts.size();
        chunk_box.assign((n + chunk_edges - 1) / chunk_edges, geo::Box{});
        for (std::size_t e = 0; e < n; ++e) {
            chunk_box[e / chunk_edges].extend(pts[e]);
            chunk_box[e / chunk_edges].extend(pts[(e + 1) % n]);
        }
    }

    /// Crossing-number point-in-polygon in the aligned frame (boundary counts as inside).
    bool contains(XY q) const noexcept {
        bool inside = false;
        const std::size_t n = pts.size();
        for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
            const XY a = pts[j], b = pts[i];
            if ((a.y > q.y) != (b.y > q.y)) {
                const double o = geo::orient(a, b, q);
                if (o == 0) return true;
                if ((o > 0) == (b.y > a.y)) inside = !inside;
            } else if (geo::point_segment_dist2(q, a, b) == 0) {
                return true;
            }
        }
        return inside;
    }
};

/// State of one check while cells are read.
struct Search {
    const AlignedHull& hull;
    double best2 = INFINITY;  // squared clearance so far
    double best = INFINITY;
    XY hull_pt, coast_pt;      // aligned frame
    bool crossing = false;
    std::vector<XY>& inside_candidates;  // coast vertices (aligned) that may lie inside the hull

    void segment(XY a, XY b, bool collect) {
        geo::Box sb;
        sb.extend(a);
        sb.extend(b);
        const double d = hull.box.distance_to(sb);
        if (d > 0 && d >= best) return;
        const std::size_t n = hull.pts.size();
        for (std::size_t c = 0; c < hull.chunk_box.size(); ++c) {
            const double dc = hull.chunk_box[c].distance_to(sb);
            if (dc > 0 && dc >= best) continue;
            const std::size_t e_end = std::min(n, (c + 1) * chunk_edges);
            for (std::size_t e = c * chunk_edges; e < e_end; ++e) {
                XY on_hull, on_coast;
                const double d2 = geo::segment_segment_dist2(hull.pts[e], hull.pts[(e + 1) % n], a, b, &on_hull, &on_coast);
                if (d2 < best2) {
                    best2 = d2;
                    best = std::sqrt(d2);
                    hull_pt = on_hull;
                    coast_pt = on_coast;
                    if (d2 == 0) {
                        crossing = true;
                        return;
                    }
                }
            }
        }
        if (collect && d == 0) inside_candidates.push_back(a);
    }
};

struct Scratch {
    AlignedHull hull;
    std::vector<XY> inside_candidates;
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

}  // namespace

Detector::Detector(const grid::CoastGrid& grid, const hull::Hull& hull) : m_grid(grid), m_hull(hull) {}

Contact Detector::check(const Pose& pose, const CheckOptions& options) const {
    return check(place(m_grid.frame(), pose), options);
}

Contact Detector::check(const LocalPose& pose, const CheckOptions& options) const {
    Scratch& s = scratch();
    AlignedHull& h = s.hull;
    h.build(m_hull, pose);
    s.inside_candidates.clear();
    Search search{h, INFINITY, INFINITY, {}, {}, false, s.inside_candidates};
    Contact out;
    const geo::Box ext = m_grid.extent();
    const geo::Box& lb = h.local_box;
    out.covered = lb.minx >= ext.minx && lb.miny >= ext.miny && lb.maxx <= ext.maxx && lb.maxy <= ext.maxy;

    const int nx = m_grid.nx(), ny = m_grid.ny();
    const double cell = m_grid.cell_size();
    // The block of cells under the hull's box: every segment that could touch the hull.
    int i0 = std::max(0, m_grid.col_of(lb.minx)), i1 = std::min(nx - 1, m_grid.col_of(lb.maxx));
    int j0 = std::max(0, m_grid.row_of(lb.miny)), j1 = std::min(ny - 1, m_grid.row_of(lb.maxy));
    auto read_cell = [&](int i, int j, bool collect) {
        for (const grid::Segment& sg : m_grid.segments(i, j)) {
            search.segment(h.to_aligned(sg.a), h.to_aligned(sg.b), collect);
            if (search.crossing) return;
        }
    };
    const bool block_valid = i0 <= i1 && j0 <= j1;
    if (block_valid) {
        for (int j = j0; j <= j1 && !search.crossing; ++j)
            for (int i = i0; i <= i1 && !search.crossing; ++i) read_cell(i, j, true);
    }
    if (!search.crossing) {
        // No edge crossing: the hull is wholly in water, wholly in land, or holds an islet.
        bool on_boundary = false;
        const XY p0 = h.to_local(h.pts[0]);
        if (m_grid.winding(p0, &on_boundary) > 0) {
            out.collision = true;
            out.hull_point = p0;
            out.coast_point = p0;
        } else {
            for (const XY& q : s.inside_candidates)
                if (h.contains(q)) {
                    out.collision = true;
                    out.hull_point = out.coast_point = h.to_local(q);
                    break;
                }
        }
    } else {
        out.collision = true;
        out.hull_point = h.to_local(search.hull_pt);
        out.coast_point = h.to_local(search.coast_pt);
    }
    if (out.collision) {
        out.clearance_m = 0;
        if (options.want_penetration) {
            double depth = 0;
            for (const XY& q : h.pts) {  // hull points on land: how far inside
                const XY p = h.to_local(q);
                if (m_grid.winding(p) > 0) depth = std::max(depth, nearest_coast(p, INFINITY, nullptr));
            }
            const std::size_t n = h.pts.size();
            // Coast vertices inside the hull: how far from its outline.
            auto coast_depth = [&](int i, int j) {
                for (const grid::Segment& sg : m_grid.segments(i, j)) {
                    const XY q = h.to_aligned(sg.a);
                    if (!h.contains(q)) continue;
                    double d2 = INFINITY;
                    for (std::size_t e = 0; e < n; ++e) d2 = std::min(d2, geo::point_segment_dist2(q, h.pts[e], h.pts[(e + 1) % n]));
                    depth = std::max(depth, std::sqrt(d2));
                }
            };
            if (block_valid)
                for (int j = j0; j <= j1; ++j)
                    for (int i = i0; i <= i1; ++i) coast_depth(i, j);
            out.penetration_m = depth;
        }
        return out;
    }

    // Clearance: rings of cells outward until no cell can hold a nearer segment.
    if (!block_valid) {  // the hull is wholly outside the grid: start from the nearest cells
        i0 = std::clamp(m_grid.col_of(lb.minx), 0, nx - 1);
        i1 = std::clamp(m_grid.col_of(lb.maxx), 0, nx - 1);
        j0 = std::clamp(m_grid.row_of(lb.miny), 0, ny - 1);
        j1 = std::clamp(m_grid.row_of(lb.maxy), 0, ny - 1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) read_cell(i, j, false);
    }
    const XY org = m_grid.origin();
    for (;;) {
        // Distance from the hull's box to the nearest point outside the block read so far.
        const double gap = std::min({i0 > 0 ? lb.minx - (org.x + i0 * cell) : INFINITY,
                                     i1 < nx - 1 ? (org.x + (i1 + 1) * cell) - lb.maxx : INFINITY,
                                     j0 > 0 ? lb.miny - (org.y + j0 * cell) : INFINITY,
                                     j1 < ny - 1 ? (org.y + (j1 + 1) * cell) - lb.maxy : INFINITY});
        if (gap >= search.best || gap > options.max_clearance_m || !std::isfinite(gap)) break;
        const int ni0 = std::max(0, i0 - 1), ni1 = std::min(nx - 1, i1 + 1);
        const int nj0 = std::max(0, j0 - 1), nj1 = std::min(ny - 1, j1 + 1);
        for (int j = nj0; j <= nj1; ++j) {
            const bool edge_row = j < j0 || j > j1;
            for (int i = ni0; i <= ni1; ++i)
                if (edge_row || i < i0 || i > i1) read_cell(i, j, false);
        }
        i0 = ni0, i1 = ni1, j0 = nj0, j1 = nj1;
    }
    if (search.best <= options.max_clearance_m) {
        out.clearance_m = search.best;
        out.hull_point = h.to_local(search.hull_pt);
        out.coast_point = h.to_local(search.coast_pt);
    }
    return out;
}

double Detector::nearest_coast(XY p, double max_m, XY* on_coast) const {
    const int nx = m_grid.nx(), ny = m_grid.ny();
    const double cell = m_grid.cell_size();
    int i0 = std::clamp(m_grid.col_of(p.x), 0, nx - 1), i1 = i0;
    int j0 = std::clamp(m_grid.row_of(p.y), 0, ny - 1), j1 = j0;
    double best2 = INFINITY;
    XY best_pt{};
    auto read_cell = [&](int i, int j) {
        for (const grid::Segment& sg : m_grid.segments(i, j)) {
            double t;
            const double d2 = geo::point_segment_dist2(p, sg.a, sg.b, &t);
            if (d2 < best2) {
                best2 = d2;
                best_pt = sg.a + t * (sg.b - sg.a);
            }
        }
    };
    read_cell(i0, j0);
    const XY org = m_grid.origin();
    for (;;) {
        const double gap = std::min({i0 > 0 ? p.x - (org.x + i0 * cell) : INFINITY,
                                     i1 < nx - 1 ? (org.x + (i1 + 1) * cell) - p.x : INFINITY,
                                     j0 > 0 ? p.y - (org.y + j0 * cell) : INFINITY,
                                     j1 < ny - 1 ? (org.y + (j1 + 1) * cell) - p.y : INFINITY});
        if (gap * gap >= best2 || gap > max_m || !std::isfinite(gap)) break;
        const int ni0 = std::max(0, i0 - 1), ni1 = std::min(nx - 1, i1 + 1);
        const int nj0 = std::max(0, j0 - 1), nj1 = std::min(ny - 1, j1 + 1);
        for (int j = nj0; j <= nj1; ++j)
            for (int i = ni0; i <= ni1; ++i)
                if (j < j0 || j > j1 || i < i0 || i > i1) read_cell(i, j);
        i0 = ni0, i1 = ni1, j0 = nj0, j1 = nj1;
    }
    const double d = std::sqrt(best2);
    if (d > max_m) return INFINITY;
    if (on_coast) *on_coast = best_pt;
    return d;
}

}  // namespace shoal::check
