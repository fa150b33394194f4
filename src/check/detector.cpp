#include <shoal/check/detector.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "check/hull_lanes.hpp"
#include "grid/outward.hpp"

namespace shoal::check {

using geo::XY;
using grid::visit_chunks;
using namespace hull_lanes;

namespace {

/// Contact::covered: the hull's local box inside the grid's extent.
bool inside_extent(const geo::Box& lb, const geo::Box& ext) noexcept {
    return lb.minx >= ext.minx && lb.miny >= ext.miny && lb.maxx <= ext.maxx && lb.maxy <= ext.maxy;
}

/// State of one check while cells are read.
struct Search {
    AlignedHull& hull;
    double best2 = INFINITY;  // squared clearance so far, or the squared search limit
    bool found = false;        // best2 is a distance found (hull_pt, coast_pt are set)
    XY hull_pt, coast_pt;      // aligned frame
    bool crossing = false;
    std::size_t crossing_edge = 0;  // the hull edge that crosses (when crossing)
    std::vector<XY>& inside_candidates;  // coast vertices (aligned) that may lie inside the hull
    const grid::Segment* seg = nullptr;       // the segment being measured
    const grid::Segment* best_seg = nullptr;  // the segment realising best2 (when found)

    std::vector<grid::ChunkRun>& runs;        // chunks gathered, not read yet
    std::vector<std::pair<double, std::size_t>>& order;  // edges(): the hull's chunks to read, nearest first

    double best() const noexcept { return std::sqrt(best2); }

    /// Adds the chunks of `segs` (one cell of `grid`) nearer the hull's box than the distance
    /// found so far to those read by the next drain().
    void gather(const grid::CoastGrid& grid, std::span<const grid::Segment> segs) {
        const geo::Box& lb = hull.local_box;
        grid::gather_chunks(grid, segs, [&](const geo::Box& cb) { return box_dist2(cb, lb); }, best2, runs);
    }

    /// Reads the chunks gathered, nearest first, so that the bound shrinks before the far ones
    /// are looked at (a search for the unlimited clearance starts with no bound at all): each
    /// segment is moved to the aligned frame and tested against the hull's box at the distance
    /// found so far; only those that pass meet the edges. `collect`: keep the coast vertices
    /// that may lie inside the hull (the block under the hull).
    void drain(bool collect) {
        // First tests in local metres, on the segments as stored: the box of a chunk of
        // segments, then of each segment, against the hull's local box grown by the clearance
        // found so far (r). Only the segments that pass are moved to the aligned frame,
        // a' = (dot(a - o, u), dot(a - o, v)), and tested against the (tighter) aligned box.
        const V2 o = load(hull.origin);
        const V2 ux = v2(hull.u.x, hull.v.x), uy = v2(hull.u.y, hull.v.y);
        const V2 hmin = load_min(hull.box), hmax = load_max(hull.box);
        const V2 lmin = load_min(hull.local_box), lmax = load_max(hull.local_box);
        V2 r = splat(std::sqrt(best2));
        V2 qmin = lmin - r, qmax = lmax + r;
        // After a crossing nothing more is read (the rest of its chunk is passed over).
        grid::visit_nearest_first(runs, [&] { return best2; }, [&] { return crossing; }, [&](const grid::Segment& sg) {
            const V2 la = load(sg.a), lb = load(sg.b);
            if (any_gt_or_lt(vmin(la, lb), qmax, vmax(la, lb), qmin)) return;
            const V2 da = la - o, db = lb - o;
            const V2 a = low_both(da) * ux + high_both(da) * uy;
            const V2 b = low_both(db) * ux + high_both(db) * uy;
            const V2 smin = vmin(a, b), smax = vmax(a, b);
            const double d2 = box_dist2(hmin, hmax, smin, smax);
            if (d2 >= best2) return;  // best2 > 0 here: a crossing ends the search
            XY pa, pb;
            geo::Box sb;
            store(pa, a);
            store(pb, b);
            store_box(sb, smin, smax);
            seg = &sg;
            edges(pa, pb, sb);
            if (crossing) return;
            if (collect && d2 == 0 && hull.in_box(pa)) inside_candidates.push_back(pa);
            r = splat(std::sqrt(best2));
            qmin = lmin - r;
            qmax = lmax + r;
        });
    }

    /// Coast segment ab (aligned frame, box sb) against the hull's edges: lowers best2, sets
    /// crossing. Pruned by the boxes of chunks of edges and of edges at the distance found so
    /// far; the intersection test runs only for an edge whose box meets the segment's box.
    void edges(XY a, XY b, const geo::Box& sb) {
        hull.ensure_edges();
        const XY sd = b - a;
        const double slen2 = geo::norm2(sd);
        const double s_inv = slen2 > 0 ? 1.0 / slen2 : 0.0;
        const std::size_t n_chunks = hull.chunk_box.size();
        const std::size_t n = hull.n;
        std::size_t vertex_done = n + 1;  // hull vertex whose distance to ab is already counted
        auto vertex = [&](std::size_t i) {  // hull vertex i to the coast segment
            if (i == vertex_done) return;
            vertex_done = i;
            XY f;
            const XY p = hull.pt(i);
            const double dd = point_segment_d2(p, a, sd, s_inv, &f);
            if (dd < best2) { best2 = dd; hull_pt = p; coast_pt = f; found = true; best_seg = seg; }
        };
        // Chunks nearest first while nothing is found (the bound is the search limit): the
        // first segment of a search would otherwise meet every edge. Later ones, in order.
        order.clear();
        for (std::size_t c = 0; c < n_chunks; ++c) {
            const double cd2 = box_dist2(hull.chunk_box[c], sb);
            if (cd2 < best2) order.push_back({cd2, c});
        }
        if (!found) std::sort(order.begin(), order.end());  // ties by chunk: the order read otherwise
        for (const auto& [cd2, c] : order) {
            if (cd2 >= best2) continue;
            hull.ensure_chunk(c);
            const std::size_t e_end = std::min(n, (c + 1) * chunk_edges);
            for (std::size_t e = c * chunk_edges; e < e_end; ++e) {
                const double de2 = box_dist2(hull.edge_box[e], sb);
                if (de2 >= best2) continue;
                const XY ea = hull.pt(e), eb = hull.pt(e + 1);
                if (de2 == 0 && geo::segments_intersect(ea, eb, a, b)) {
                    XY on_hull, on_coast;
                    geo::segment_segment_dist2(ea, eb, a, b, &on_hull, &on_coast);
                    best2 = 0;
                    found = true;
                    best_seg = seg;
                    hull_pt = on_hull;
                    coast_pt = on_coast;
                    crossing = true;
                    crossing_edge = e;
                    return;
                }
                // Disjoint: the nearest pair has an end of one segment. Each hull vertex is
                // measured once for the two edges that share it.
                vertex(e);
                vertex(e + 1);
                const XY ed = hull.dir[e];
                XY f;
                double dd = point_segment_d2(a, ea, ed, hull.inv_len2[e], &f);
                if (dd < best2) { best2 = dd; hull_pt = f; coast_pt = a; found = true; best_seg = seg; }
                dd = point_segment_d2(b, ea, ed, hull.inv_len2[e], &f);
                if (dd < best2) { best2 = dd; hull_pt = f; coast_pt = b; found = true; best_seg = seg; }
            }
        }
    }
};

struct Scratch {
    AlignedHull hull;
    std::vector<XY> inside_candidates;
    std::vector<grid::ChunkRun> runs;
    std::vector<std::pair<double, std::size_t>> order;
    /// The hull point found deepest by this thread's last penetration: the next one starts
    /// there (a hull moves little between the poses of a track, and its deepest point found
    /// first lets the rest be skipped). The order changes only which points are searched.
    std::size_t deepest = 0;
    /// The hull point this thread last found on land (or nearest the land side of a crossing):
    /// tried first when the contact point is not asked for (CheckOptions::want_contact_point).
    std::size_t on_land = 0;
};

/// (Not inlined: a check then holds its scratch by a plain reference. Inlined, GCC recomputed
/// the thread-local's address at each use, which in a shared library (the CLI's module,
/// libshoal_c) is a call to __tls_get_addr: 43 a check, 4 % of a day of AIS.)
[[gnu::noinline]] Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

}  // namespace

namespace {
std::optional<double> default_limit(const grid::CoastGrid& grid) {
    const double d = grid.source().limiting_depth_m;
    return std::isnan(d) ? std::nullopt : std::optional<double>(d);
}
}  // namespace

Detector::Detector(const grid::CoastGrid& grid, const hull::Hull& hull) : Detector(grid, hull, default_limit(grid)) {}

Detector::Detector(const grid::CoastGrid& grid, const hull::Hull& hull, std::optional<double> limiting_depth_m)
    : m_grid(grid.for_depth(limiting_depth_m)), m_hull(hull) {}

Contact Detector::check(const Pose& pose, const CheckOptions& options) const {
    return check(place(m_grid.frame(), pose), options);
}

Contact Detector::check(const LocalPose& pose, const CheckOptions& options) const {
    Scratch& s = scratch();
    AlignedHull& h = s.hull;
    h.build(m_hull, pose);
    s.inside_candidates.clear();
    // Segments farther than the clearance limit are pruned like those farther than the
    // clearance found so far (the limit grown by a hair, so that one exactly at it counts).
    const double limit = options.max_clearance_m;
    const double bound = std::isfinite(limit) ? limit * (1 + 1e-9) + 1e-9 : INFINITY;
    // CheckOptions::clearance_hint_m: the search's first bound when it is under the limit's
    // (grown by the same hair); searched again without it when nothing lies within.
    const double hint = options.clearance_hint_m;
    const double hint_bound = hint > 0 && std::isfinite(hint) ? std::min(bound, hint * (1 + 1e-9) + 1e-9) : bound;
    Search search{h, hint_bound * hint_bound, false, {}, {}, false, 0, s.inside_candidates, nullptr, nullptr, s.runs, s.order};
    Contact out;
    const geo::Box ext = m_grid.extent();
    const geo::Box& lb = h.local_box;
    out.covered = inside_extent(lb, ext);

    const int nx = m_grid.nx(), ny = m_grid.ny();
    // The block of cells under the hull's box: every segment that could touch the hull.
    const int i0 = std::max(0, m_grid.col_of(lb.minx)), i1 = std::min(nx - 1, m_grid.col_of(lb.maxx));
    const int j0 = std::max(0, m_grid.row_of(lb.miny)), j1 = std::min(ny - 1, m_grid.row_of(lb.maxy));
    const bool block_valid = i0 <= i1 && j0 <= j1;
    // A hull point on land is a collision, whatever else the hull meets: when where is not
    // asked, the point this thread last found on land is tried first (one cell's winding).
    bool found_on_land = false;
    if (!options.want_contact_point && !options.want_polyline) {
        const XY q = h.to_local(h.pt(s.on_land < h.n ? s.on_land : 0));
        if (m_grid.winding(q) > 0) {
            found_on_land = true;
            out.collision = true;
            out.hull_point = out.coast_point = q;
        }
    }
    if (block_valid && !found_on_land) {  // the block's chunks together, nearest first
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) search.gather(m_grid, m_grid.segments(i, j));
        search.drain(true);
    }
    if (found_on_land) {
        // Nothing more to find: where does not matter.
    } else if (!search.crossing) {
        // No edge crossing: the hull is wholly in water, wholly in land, or holds an islet.
        bool on_boundary = false;
        const XY p0 = h.to_local(h.pt(0));
        if (m_grid.winding(p0, &on_boundary) > 0) {
            out.collision = true;
            out.hull_point = p0;
            out.coast_point = p0;
            if (options.want_polyline) out.polyline = m_grid.enclosing_polyline(p0);
        } else {
            for (const XY& q : s.inside_candidates)  // each lies in the hull's box
                if (h.contains(q)) {
                    out.collision = true;
                    out.hull_point = out.coast_point = h.to_local(q);
                    if (options.want_polyline) out.polyline = m_grid.nearest_polyline(out.coast_point);
                    break;
                }
        }
    } else {
        out.collision = true;
        out.hull_point = h.to_local(search.hull_pt);
        out.coast_point = h.to_local(search.coast_pt);
        out.polyline = m_grid.polyline_of(*search.best_seg);
        // The end of the crossed hull edge on the land side of the coast segment (land lies on
        // its left): the next pose's first try.
        const XY a = h.to_aligned(search.best_seg->a), b = h.to_aligned(search.best_seg->b);
        s.on_land = geo::orient(a, b, h.pt(search.crossing_edge)) > 0 ? search.crossing_edge : (search.crossing_edge + 1) % h.n;
    }
    if (out.collision) {
        out.clearance_m = 0;
        if (options.want_penetration) {
            double depth = 0;
            // Hull points on land: how far inside. A point nearer than d to a point found d
            // deep lies on land too (no winding test), and is at most as deep as it is far
            // from that point's nearest coast point: it is not searched when that cannot raise
            // the depth, else searched within it (the bounds a hair loose: the same depth
            // comes out as from a search of each point).
            struct Known {
                XY p;
                double d;
                XY coast;  ///< the nearest coast point of p
            };
            std::array<Known, 8> known;
            std::size_t n_known = 0, next_known = 0;
            const std::size_t first = s.deepest < h.n ? s.deepest : 0;
            for (std::size_t step = 0; step < h.n; ++step) {
                const std::size_t i = first + step < h.n ? first + step : first + step - h.n;
                const XY p = h.to_local(h.pt(i));
                // (One square root for the bound: the rounded root and the hair added rise with
                // their argument, so the least of them is that of the least square. A point at
                // least d away, squared, is no nearer with the hair either: not on land by it.)
                double most2 = INFINITY;
                bool on_land = false;
                for (std::size_t k = 0; k < n_known; ++k) {
                    const double gap2 = geo::norm2(p - known[k].p);
                    on_land = on_land || (gap2 < known[k].d * known[k].d && std::sqrt(gap2) * (1 + 1e-9) + 1e-9 < known[k].d * (1 - 1e-9));
                    most2 = std::min(most2, geo::norm2(p - known[k].coast));
                }
                const double most = n_known > 0 ? std::sqrt(most2) * (1 + 1e-9) + 1e-9 : INFINITY;
                if (most <= depth) continue;
                // Each from its cell's reference point: counted from another hull point, an
                // error of rounding at one lying on the coast would carry on to the next.
                if (!on_land && m_grid.winding(p) <= 0) continue;
                XY coast{INFINITY, INFINITY};  // none found: no bound from this point
                double d = nearest_coast(p, most, &coast);
                if (std::isinf(d)) d = nearest_coast(p, INFINITY, &coast);
                if (d > depth) {
                    depth = d;
                    s.deepest = i;
                    s.on_land = i;
                }
                known[next_known++ % known.size()] = {p, d, coast};
                n_known = std::min(n_known + 1, known.size());
            }
            const std::size_t n = h.n;
            // Coast vertices inside the hull: how far from its outline.
            auto coast_depth = [&](int i, int j) {
                // The hull's local box grown by a micrometre: a vertex on the outline up to
                // rounding is still looked at (it adds no depth, but is counted as before).
                const geo::Box hb{lb.minx - 1e-6, lb.miny - 1e-6, lb.maxx + 1e-6, lb.maxy + 1e-6};
                auto meets_hull_box = [&](const geo::Box& b) {
                    return b.minx <= hb.maxx && b.maxx >= hb.minx && b.miny <= hb.maxy && b.maxy >= hb.miny;
                };
                visit_chunks(m_grid, m_grid.segments(i, j), meets_hull_box, [&](const grid::Segment& sg) {
                    if (sg.a.x < hb.minx || sg.a.x > hb.maxx || sg.a.y < hb.miny || sg.a.y > hb.maxy) return;
                    const XY q = h.to_aligned(sg.a);
                    if (!h.in_box(q) || !h.contains(q)) return;
                    double d2 = INFINITY;
                    for (std::size_t e = 0; e < n; ++e) d2 = std::min(d2, geo::point_segment_dist2(q, h.pt(e), h.pt(e + 1)));
                    depth = std::max(depth, std::sqrt(d2));
                });
            };
            if (block_valid)
                for (int j = j0; j <= j1; ++j)
                    for (int i = i0; i <= i1; ++i) coast_depth(i, j);
            out.penetration_m = depth;
        }
        return out;
    }

    // Clearance: rings of cells outward until no cell can hold a nearer segment, each ring
    // cut to the cells nearer the hull's box than the clearance found so far (or the limit),
    // and its chunks read together, nearest first. A hull wholly outside the grid starts
    // from the nearest cells.
    struct Clearance {
        Search& search;
        const grid::CoastGrid& grid;
        double max_m;
        void operator()(std::span<const grid::Segment> segs) { search.gather(grid, segs); }
        void ring_done() { search.drain(false); }
        bool wants(double gap) const { return !(gap * gap >= search.best2 || gap > max_m); }
        double reach() const { return std::min(search.best(), max_m); }
    } clearance{search, m_grid, options.max_clearance_m};
    grid::visit_outward(m_grid, lb, clearance, block_valid ? grid::FirstBlock::skip : grid::FirstBlock::read);
    if (!search.found && hint_bound < bound) {
        // The hint was too small: the whole search again, at the limit. (The hull's block was
        // read at the hint's bound: its far segments were passed over.)
        search.best2 = bound * bound;
        grid::visit_outward(m_grid, lb, clearance, grid::FirstBlock::read);
    }
    if (search.found && search.best() <= options.max_clearance_m) {
        out.clearance_m = search.best();
        out.hull_point = h.to_local(search.hull_pt);
        out.coast_point = h.to_local(search.coast_pt);
        out.polyline = m_grid.polyline_of(*search.best_seg);
    }
    return out;
}

bool Detector::covers(const LocalPose& pose) const noexcept {
    // Most poses lie well inside: then so does the square around the position that holds the
    // hull at any heading (its radius stretched by the placement, at most by the matrix's
    // Frobenius norm; grown by far more than rounding), and the hull's box is not needed.
    const geo::Box ext = m_grid.extent();
    const double r = m_hull.radius() * std::sqrt(pose.ship_to_local.squaredNorm()) * (1 + 1e-9) + 1e-6;
    const XY p = pose.position;
    if (p.x - r >= ext.minx && p.y - r >= ext.miny && p.x + r <= ext.maxx && p.y + r <= ext.maxy) return true;
    const std::vector<XY>& c = m_hull.contour();
    return inside_extent(local_hull_box(c.data(), c.size(), pose.ship_to_local, pose.position), m_grid.extent());
}

double Detector::nearest_coast(XY p, double max_m, XY* on_coast) const {
    const grid::NearestSegment n = m_grid.nearest_segment(p, max_m);
    const double d = std::sqrt(n.dist2);
    if (d > max_m) return INFINITY;
    if (on_coast) *on_coast = n.point;
    return d;
}

}  // namespace shoal::check
