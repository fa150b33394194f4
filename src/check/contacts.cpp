// Contact regions (include/shoal/check/contacts.hpp).
//
// The hazards' boundary near the hull is gathered as segments (the grid's, clipped to the
// hull's box grown by a reach G), cut where boundaries of different polylines cross, and each
// piece kept when water lies on its right (land is on the left of a boundary): a piece inside
// another hazard (a pier's root over land, a shallow area's edge along the shore) is not where
// the hull gets free, so it is not a boundary of the union. Then:
//  1. the hull outline is cut where it crosses those pieces; its pieces inside the hazards and
//     the boundary pieces inside the hull bound the overlap, and are joined into connected
//     regions where they meet (a union-find); a closed ring of boundary inside the hull is an
//     islet (its own region) or a pond (part of the region around it);
//  2. each region's deepest point: the distance to the boundary, d, is largest either on the
//     outline's pieces (a branch and bound along each) or at an interior point (a branch and
//     bound over square cells of the region's box cut to the hull). Bounds of a cell: d at its
//     centre plus its radius (d is 1-Lipschitz), and the exact maximum over the cell of the
//     lesser distance to the two nearest boundary pieces (at the cell's corners or where the
//     two distances are equal on its edges), which is tight along a straight boundary and on
//     the ridge between two (a pier across the hull); where that bound does not cut a cell off,
//     the point where it is reached (on the ridge between the two, the medial axis where the
//     deepest point lies) is tried as a deepest point, and the pairs of the two with the third
//     nearest piece bound the cell too (near a vertex of a pier's side the two nearest pieces
//     are the side's two segments, whose bound is loose by the cell's size);
//  3. when a depth reaches the reach G, a nearer boundary may lie beyond it: G is grown and the
//     search done again, so the answer is exact for a hull however deep in land.

#include <shoal/check/contacts.hpp>

#include "check/contact_geometry.hpp"
#include "check/contact_search.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>
#include <span>
#include <utility>

namespace shoal::check {

using geo::Box;
using geo::XY;

double local_scale(const LocalPose& pose) noexcept {
    const Eigen::Matrix2d& m = pose.ship_to_local;
    return std::sqrt(std::fabs(m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0)));
}

ShipFrameContact in_ship_frame(const ContactRegion& r, const LocalPose& pose, const geo::LocalFrame& frame, const grid::CoastGrid* grid) {
    const Eigen::Matrix2d& m = pose.ship_to_local;
    const double det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
    // The inverse map: local -> ship.
    auto to_ship = [&](double x, double y) {
        return XY{(m(1, 1) * x - m(0, 1) * y) / det, (-m(1, 0) * x + m(0, 0) * y) / det};
    };
    ShipFrameContact out;
    const XY p = to_ship(r.hull_point.x - pose.position.x, r.hull_point.y - pose.position.y);
    XY n = to_ship(r.normal.x, r.normal.y);
    const double len = std::sqrt(geo::norm2(n));
    if (len > 0) n = (1 / len) * n;
    out.x_m = p.x, out.y_m = p.y;
    out.nx = n.x, out.ny = n.y;
    out.depth_m = r.depth_m;
    out.point = frame.inverse(r.hull_point);
    out.coast_point = frame.inverse(r.coast_point);
    if (grid && r.polyline != grid::CoastGrid::no_polyline && r.polyline < grid->polyline_count()) out.hazard = &grid->hazard(r.polyline);
    return out;
}

namespace {

struct Region {
    std::vector<int> pieces;
    bool has_outline = false;
    Best best;
};


/// A stretch of a boundary segment between crossings (regions_of).
struct Piece0 {
    XY p, q;
    std::size_t seg;
    bool cut_start, cut_end;  // begins / ends at a crossing
};

/// An end of a stretch that is not a crossing (regions_of).
struct End {
    XY at;
    std::uint32_t polyline;
    int piece;
};

/// A crossing of the hull outline's edge and a site (regions_of).
struct Cross {
    int edge;
    double t;
    int site;
    double u;
};

/// A grid cell's land boundary segments met in the reach's box (their indices in the grid's
/// array): a path inside the box meets only those (contact_regions' winding numbers).
struct CellNear {
    int i, j;
    std::vector<std::uint32_t> near;
};

/// A point whose winding number is known, the first asked in its grid cell (contact_regions).
struct KnownWinding {
    int i, j;
    XY at;
    int w;
};

/// A cell of the interior search (regions_of): a cell carries its parent's centre, side and
/// distance to the boundary: a centre nearer the parent's than that distance is on the same
/// side (no winding number).
struct Cell {
    Box box;
    double bound;
    XY parent{};
    double parent_clear = 0;  // the parent centre's distance to the boundary (a lower bound)
    bool parent_inside = false;
    ConvexCutter::Edges edges = ConvexCutter::all_edges;  // the hull's edges that may cut it
    // The parent's polygon (its box cut to the hull): its first vertex in Scratch::cell_polys
    // and how many (0: none, a first cell).
    std::uint32_t parent_poly = 0, parent_poly_n = 0;
    bool operator<(const Cell& o) const noexcept { return bound < o.bound; }
};

/// The working lists of regions_of, kept between calls on each thread (cleared, not freed: an
/// allocation each was ~8 % of a call).
struct Scratch {
    std::vector<RawSegment> raw, bounds, lines;
    std::vector<Site> sites;
    std::vector<Box> site_boxes, edge_box;
    std::vector<ByX> site_by_x;
    std::vector<std::pair<std::size_t, double>> cut_at;
    std::vector<std::pair<double, double>> tu;
    std::vector<std::uint32_t> by_x;
    std::vector<Piece0> raw_pieces;
    std::vector<double> c;
    std::vector<int> same, uf;
    std::vector<End> ends;
    std::vector<signed char> buried;
    std::vector<Piece> pieces;
    std::vector<Cross> xs;
    std::vector<int> near_hull, edge_crossings, piece_at_cross_out, first_piece, last_piece, piece_at_cross_site;
    std::vector<std::pair<double, int>> ts, us;
    std::vector<ParamGroup> groups;
    std::vector<std::pair<int, int>> by_site;
    std::vector<int> order, region_of_root, merged_into, piece_region, live;
    std::vector<Interval> intervals;
    std::vector<double> piece_d2;
    std::vector<Cell> queue;  // a heap (std::push_heap, std::pop_heap: as std::priority_queue)
    std::vector<XY> poly, ring, cell_polys, clip_tmp;
    std::vector<XY> cut_buffers[2];  // ConvexCutter's
    std::vector<Region> regions;     // the first Regions::n in use, their lists kept
    // contact_regions:
    std::vector<CellNear> cells_near;  // the first `n_cells_near` are the focus's
    std::vector<KnownWinding> known;  // kept from call to call on one grid (known_grid)
    std::uint64_t known_grid = 0;     // CoastGrid::instance() of `known`
    std::size_t on_land = 0;          // the hull vertex tried first for land
};

/// The regions of an attempt: the first `n` of the kept list (their piece lists cleared, not
/// freed, when taken again).
struct Regions {
    std::vector<Region>& pool;
    std::size_t n = 0;
    std::size_t size() const noexcept { return n; }
    Region& operator[](std::size_t i) noexcept { return pool[i]; }
    Region* begin() noexcept { return pool.data(); }
    Region* end() noexcept { return pool.data() + n; }
    void emplace_back() {
        if (n == pool.size()) pool.emplace_back();
        else {
            Region& r = pool[n];
            r.pieces.clear(), r.has_outline = false, r.best = Best{};
        }
        ++n;
    }
};

/// (Not inlined: the callers then hold the lists by plain references. Inlined, GCC
/// propagated the thread-local's address into the callees and asked __tls_get_addr for it at
/// every use, 7 % of a call.)
[[gnu::noinline]] Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

}  // namespace

namespace {

/// `ring` := `outline` (open or closed) as a closed counter-clockwise ring; empty for fewer
/// than 3 points.
void ccw_closed(const std::vector<XY>& outline, std::vector<XY>& ring) {
    ring.reserve(outline.size() + 1);  // (the closing point without a second allocation)
    ring.assign(outline.begin(), outline.end());
    if (ring.size() >= 2 && ring.front() == ring.back()) ring.pop_back();
    if (ring.size() < 3) {
        ring.clear();
        return;
    }
    double area2 = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) area2 += geo::cross(ring[i], ring[(i + 1) % ring.size()]);
    if (area2 < 0) std::reverse(ring.begin(), ring.end());
    ring.push_back(ring.front());
}

std::vector<XY> ccw_closed(const std::vector<XY>& outline) {
    std::vector<XY> ring;
    ccw_closed(outline, ring);
    return ring;
}

/// The regions of hull outline `outline` (open or closed) against `obstacle`; depths in metres
/// on the ground (local metres / `scale`).
std::vector<ContactRegion> regions_of(const std::vector<XY>& outline, const Obstacle& obstacle, double scale, const detail::ContactSearch& how) {
    Scratch& sc = scratch();
    std::vector<XY>& ring = sc.ring;
    ccw_closed(outline, ring);
    if (ring.empty()) return {};
    const std::size_t n_edges = ring.size() - 1;
    bool convex = true;
    for (std::size_t i = 0; i < n_edges && convex; ++i) {  // (collinear points: rounding either way)
        const XY a = ring[i], b = ring[i + 1], c = ring[(i + 2) % n_edges];
        convex = geo::orient(a, b, c) >= -1e-9 * std::sqrt(geo::norm2(b - a) * geo::norm2(c - b));
    }

    Box hbox;
    for (XY p : ring) hbox.extend(p);
    const double extent = std::max(hbox.maxx - hbox.minx, hbox.maxy - hbox.miny);
    const double magnitude = std::max({std::fabs(hbox.minx), std::fabs(hbox.maxx), std::fabs(hbox.miny), std::fabs(hbox.maxy)});
    const double tol = 1e-6 + 1e-12 * magnitude;  // local metres
    const double eps = 1e-6 + 1e-11 * magnitude;  // offset for side tests

    // The reach: small at first (a contact is usually shallow), grown while a depth reaches it.
    // 2 m by default (detail::ContactSearch): on the Tacoma bench a third of the contacts are
    // deeper than 1 m, and an attempt done again cost more than a reach of 2 m gathers.
    double reach = std::max(how.first_reach_m, 1e-3 * extent);
    std::vector<Box>& edge_box = sc.edge_box;
    edge_box.clear();
    for (std::size_t e = 0; e < n_edges; ++e)
        edge_box.push_back({std::min(ring[e].x, ring[e + 1].x), std::min(ring[e].y, ring[e + 1].y), std::max(ring[e].x, ring[e + 1].x), std::max(ring[e].y, ring[e + 1].y)});
    // A convex hull's slabs along and across its longest edge (every point within the reach of
    // the hull lies in them grown by the reach; the margin covers the normals' rounding).
    Slabs slabs{};
    bool use_slabs = convex && how.hull_slabs;
    if (use_slabs) {
        std::size_t longest = 0;
        for (std::size_t e = 1; e < n_edges; ++e)
            if (geo::norm2(ring[e + 1] - ring[e]) > geo::norm2(ring[longest + 1] - ring[longest])) longest = e;
        const XY d = ring[longest + 1] - ring[longest];
        const double len = std::sqrt(geo::norm2(d));
        use_slabs = len > 0;
        slabs.n[0] = (len > 0 ? 1 / len : 0.0) * d, slabs.n[1] = XY{-slabs.n[0].y, slabs.n[0].x};
        for (int k = 0; k < 2; ++k) {
            slabs.lo[k] = INFINITY, slabs.hi[k] = -INFINITY;
            for (XY p : ring) slabs.lo[k] = std::min(slabs.lo[k], geo::dot(slabs.n[k], p)), slabs.hi[k] = std::max(slabs.hi[k], geo::dot(slabs.n[k], p));
        }
    }
    for (int attempt = 0; attempt < 64; ++attempt) {
        const Box box = hbox.grown(reach);
        Slabs reach_slabs = slabs;
        for (int k = 0; k < 2; ++k) reach_slabs.lo[k] -= reach + tol, reach_slabs.hi[k] += reach + tol;
        std::vector<RawSegment>& raw = sc.raw;
        raw.clear();
        obstacle.collect(box, raw);
        std::vector<RawSegment>&bounds = sc.bounds, &lines = sc.lines;
        bounds.clear(), lines.clear();
        for (const RawSegment& whole : raw) {
            RawSegment r = whole;
            if (!clip_to(r.a, r.b, box, use_slabs ? &reach_slabs : nullptr)) continue;
            if (r.a == r.b) continue;
            // A line is kept whole: where it crosses the hull must not depend on the reach.
            if (r.boundary) bounds.push_back(r);
            else lines.push_back(whole);
        }
        // Cut where boundaries of different polylines cross; keep pieces with water on the right.
        std::vector<Site>& sites = sc.sites;
        sites.clear();
        {
            // (boundary segment, parameter) of every crossing, in one list (not a list per segment:
            // most segments have none), sorted by segment.
            std::vector<std::pair<std::size_t, double>>& cut_at = sc.cut_at;
            std::vector<std::pair<double, double>>& tu = sc.tu;
            cut_at.clear();
            // A sweep along x: only pairs whose x-ranges meet are tried (a pier's harbour holds
            // hundreds of segments; the list is sorted below, so the order found does not matter).
            std::vector<std::uint32_t>& by_x = sc.by_x;
            by_x.resize(bounds.size());
            std::iota(by_x.begin(), by_x.end(), 0u);
            auto lo_x = [&](std::uint32_t k) { return std::min(bounds[k].a.x, bounds[k].b.x); };
            std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t x, std::uint32_t y) { return lo_x(x) < lo_x(y) || (lo_x(x) == lo_x(y) && x < y); });
            for (std::size_t ii = 0; ii < by_x.size(); ++ii) {
                const std::uint32_t p = by_x[ii];
                const double hi = std::max(bounds[p].a.x, bounds[p].b.x);
                for (std::size_t jj = ii + 1; jj < by_x.size() && lo_x(by_x[jj]) <= hi; ++jj) {
                    const std::size_t i = std::min(p, by_x[jj]), j = std::max(p, by_x[jj]);
                    if (bounds[i].polyline == bounds[j].polyline || boxes_apart(bounds[i].a, bounds[i].b, bounds[j].a, bounds[j].b)) continue;
                    tu.clear();
                    crossings_of_near(bounds[i].a, bounds[i].b, bounds[j].a, bounds[j].b, tu);
                    for (auto [t, u] : tu) cut_at.emplace_back(i, t), cut_at.emplace_back(j, u);
                }
            }
            std::sort(cut_at.begin(), cut_at.end());
            // Pieces between cuts. Whether a piece is buried (water side inside another hazard)
            // can change only where another boundary crosses: pieces joined end to end
            // without a crossing between them share the answer, found with one winding test.
            std::vector<Piece0>& raw_pieces = sc.raw_pieces;
            std::vector<double>& c = sc.c;
            raw_pieces.clear();
            for (std::size_t i = 0, next = 0; i < bounds.size(); ++i) {
                c.clear();
                for (; next < cut_at.size() && cut_at[next].first == i; ++next) c.push_back(cut_at[next].second);
                const XY a = bounds[i].a, d = bounds[i].b - bounds[i].a;
                const double len = std::sqrt(geo::norm2(d));
                const double slack = tol / len;
                bool cut_at_a = false, cut_at_b = false;
                for (double t : c) cut_at_a = cut_at_a || t <= slack, cut_at_b = cut_at_b || t >= 1 - slack;
                c.push_back(0), c.push_back(1);
                std::sort(c.begin(), c.end());
                for (std::size_t k = 0; k + 1 < c.size(); ++k) {
                    if (!((c[k + 1] - c[k]) * len > tol)) continue;
                    raw_pieces.push_back({a + c[k] * d, a + c[k + 1] * d, i, c[k] > slack || cut_at_a, c[k + 1] < 1 - slack || cut_at_b});
                }
            }
            UnionFind same(sc.same, raw_pieces.size());
            {
                // Ends that are not crossings, joined when they meet (within the clip slack).
                std::vector<End>& ends = sc.ends;
                ends.clear();
                for (std::size_t k = 0; k < raw_pieces.size(); ++k) {
                    const std::uint32_t pl = bounds[raw_pieces[k].seg].polyline;
                    if (!raw_pieces[k].cut_start) ends.push_back({raw_pieces[k].p, pl, static_cast<int>(k)});
                    if (!raw_pieces[k].cut_end) ends.push_back({raw_pieces[k].q, pl, static_cast<int>(k)});
                }
                std::sort(ends.begin(), ends.end(), [](const End& x, const End& y) { return x.at.x < y.at.x; });
                const double join = 1e3 * tol;
                for (std::size_t x = 0; x < ends.size(); ++x)
                    for (std::size_t y = x + 1; y < ends.size() && ends[y].at.x - ends[x].at.x <= join; ++y)
                        if (ends[x].polyline == ends[y].polyline && std::fabs(ends[y].at.y - ends[x].at.y) <= join)
                            same.join(ends[x].piece, ends[y].piece);
            }
            std::vector<signed char>& buried = sc.buried;
            buried.assign(raw_pieces.size(), -1);
            for (std::size_t k = 0; k < raw_pieces.size(); ++k) {
                const int root = same.find(static_cast<int>(k));
                if (buried[root] < 0) {
                    const Piece0& rp = raw_pieces[root];
                    const XY d = rp.q - rp.p;
                    const double len = std::sqrt(geo::norm2(d));
                    const XY right{d.y / len, -d.x / len};
                    buried[root] = obstacle.inside(0.5 * (rp.p + rp.q) + eps * right) ? 1 : 0;
                }
                if (buried[root] == 0) sites.push_back({raw_pieces[k].p, raw_pieces[k].q, bounds[raw_pieces[k].seg].polyline});
            }
        }
        merge_collinear(sites, tol);
        Search search(sites, sc.site_boxes, sc.site_by_x, obstacle, tol);
        search.set_reach(reach);
        const std::vector<Site>& S = search.sites();

        // 1. Pieces of the overlap's boundary, and where they meet.
        std::vector<Piece>& pieces = sc.pieces;
        std::vector<Cross>& xs = sc.xs;
        pieces.clear(), xs.clear();
        {
            // Only the sites whose box meets the hull's can cross an edge (most of the reach's
            // do not): listed once, in their order, so the crossings are found in the same order.
            // (The boxes of the edges and of the sites once: the same test as boxes_apart.)
            std::vector<int>& near_hull = sc.near_hull;
            near_hull.clear();
            const std::vector<Box>& site_box = search.boxes();
            for (std::size_t k = 0; k < S.size(); ++k)
                if (!boxes_apart(XY{hbox.minx, hbox.miny}, XY{hbox.maxx, hbox.maxy}, S[k].a, S[k].b)) near_hull.push_back(static_cast<int>(k));
            std::vector<std::pair<double, double>>& tu = sc.tu;
            for (std::size_t e = 0; e < n_edges; ++e) {
                const Box& eb = edge_box[e];
                for (const int k : near_hull) {
                    const Box& sb = site_box[k];
                    if (eb.maxx < sb.minx || sb.maxx < eb.minx || eb.maxy < sb.miny || sb.maxy < eb.miny) continue;
                    tu.clear();
                    crossings_of_near(ring[e], ring[e + 1], S[k].a, S[k].b, tu);
                    for (auto [t, u] : tu) xs.push_back({static_cast<int>(e), t, static_cast<int>(k), u});
                }
            }
        }
        // Outline pieces inside, per edge; remember which piece ends at each crossing.
        std::vector<int>& piece_at_cross_out = sc.piece_at_cross_out;  // outline piece before / after crossing
        piece_at_cross_out.assign(xs.size() * 2, -1);
        std::vector<int>&first_piece = sc.first_piece, &last_piece = sc.last_piece;
        first_piece.assign(n_edges, -1), last_piece.assign(n_edges, -1);
        std::vector<std::pair<double, int>>& ts = sc.ts;
        std::vector<ParamGroup>& groups = sc.groups;
        int known = -1;  // whether the outline is in the hazards here: -1 not known
        std::vector<int>& edge_crossings = sc.edge_crossings;  // how many crossings each edge has
        edge_crossings.assign(n_edges, 0);
        for (const Cross& x : xs) ++edge_crossings[x.edge];
        for (std::size_t e = 0; e < n_edges; ++e) {
            const XY a = ring[e], d = ring[e + 1] - ring[e];
            const double len = std::sqrt(geo::norm2(d));
            if (edge_crossings[e] == 0) {
                // No crossing (most edges): the parameters 0 and 1 alone, as below without the
                // lists: one stretch, or none when the edge is shorter than the tolerance.
                if (!((1.0 - 0.0) * len > tol)) continue;
                const XY p = a + 0.0 * d, q = a + 1.0 * d;
                if (known < 0) known = search.inside(0.5 * (p + q)) ? 1 : 0;
                if (known != 1) continue;
                const int id = static_cast<int>(pieces.size());
                pieces.push_back({ring[e], ring[e + 1], true});
                first_piece[e] = last_piece[e] = id;
                continue;
            }
            ts.clear();
            ts.emplace_back(0.0, -1);
            ts.emplace_back(1.0, -1);
            for (std::size_t x = 0; x < xs.size(); ++x)
                if (xs[x].edge == static_cast<int>(e)) ts.emplace_back(xs[x].t, static_cast<int>(x));
            std::sort(ts.begin(), ts.end());
            group_params(ts, len, tol, groups);
            if (groups.size() == 1) {  // an edge shorter than the tolerance
                if (groups[0].has_crossing) known = -1;
                continue;
            }
            for (std::size_t k = 0; k + 1 < groups.size(); ++k) {
                const XY p = a + groups[k].t * d, q = a + groups[k + 1].t * d;
                // The outline is in or out of the hazards from one crossing to the next: one
                // test per stretch between crossings.
                if (known < 0 || groups[k].has_crossing) known = search.inside(0.5 * (p + q)) ? 1 : 0;
                const bool in = known == 1;
                if (groups[k + 1].has_crossing) known = -1;
                if (!in) continue;
                const int id = static_cast<int>(pieces.size());
                pieces.push_back({groups[k].start ? ring[e] : p, groups[k + 1].end ? ring[e + 1] : q, true});
                if (groups[k].start) first_piece[e] = id;
                if (groups[k + 1].end) last_piece[e] = id;
                for (std::size_t i = groups[k].from; i < groups[k].to; ++i)
                    if (ts[i].second >= 0) piece_at_cross_out[2 * ts[i].second + 1] = id;
                for (std::size_t i = groups[k + 1].from; i < groups[k + 1].to; ++i)
                    if (ts[i].second >= 0) piece_at_cross_out[2 * ts[i].second] = id;
            }
        }
        const std::size_t n_outline = pieces.size();
        // in_polygon, with a point beyond the hull's box answered at once: below its least y or
        // from its greatest up, no edge has ends on both sides; right of its greatest x (by more
        // than rounding), no edge's crossing is right of it. The same answers.
        const double right_of = hbox.maxx + 1e-9 * (1 + std::fabs(hbox.maxx));
        auto in_ring = [&ring, &hbox, right_of](XY m) {
            if (m.y < hbox.miny || m.y >= hbox.maxy || m.x > right_of) return false;
            return in_polygon(ring, m);
        };
        // Boundary pieces inside the hull.
        std::vector<int>& piece_at_cross_site = sc.piece_at_cross_site;
        piece_at_cross_site.assign(xs.size() * 2, -1);
        std::vector<std::pair<int, int>>& by_site = sc.by_site;  // (site, crossing), sorted
        by_site.clear();
        for (std::size_t x = 0; x < xs.size(); ++x) by_site.emplace_back(xs[x].site, static_cast<int>(x));
        std::sort(by_site.begin(), by_site.end());
        std::vector<std::pair<double, int>>& us = sc.us;  // a site's parameters, as ts an edge's
        for (std::size_t k = 0, next = 0; k < S.size(); ++k) {
            us.clear();
            for (; next < by_site.size() && by_site[next].first == static_cast<int>(k); ++next)
                us.emplace_back(xs[by_site[next].second].u, by_site[next].second);
            us.emplace_back(0.0, -1);
            us.emplace_back(1.0, -1);
            std::sort(us.begin(), us.end());
            const XY a = S[k].a, d = S[k].b - S[k].a;
            const double len = std::sqrt(geo::norm2(d));
            group_params(us, len, tol, groups);
            for (std::size_t c = 0; c + 1 < groups.size(); ++c) {
                const XY p = c == 0 ? a : a + groups[c].t * d;
                const XY q = c + 2 == groups.size() ? S[k].b : a + groups[c + 1].t * d;
                if (!in_ring(0.5 * (p + q))) continue;
                const int id = static_cast<int>(pieces.size());
                pieces.push_back({p, q, false});
                for (std::size_t i = groups[c].from; i < groups[c].to; ++i)
                    if (us[i].second >= 0) piece_at_cross_site[2 * us[i].second + 1] = id;
                for (std::size_t i = groups[c + 1].from; i < groups[c + 1].to; ++i)
                    if (us[i].second >= 0) piece_at_cross_site[2 * us[i].second] = id;
            }
        }
        UnionFind uf(sc.uf, pieces.size());
        // Outline pieces meeting at a vertex.
        for (std::size_t e = 0; e < n_edges; ++e) {
            const int a = last_piece[e], b = first_piece[(e + 1) % n_edges];
            if (a >= 0 && b >= 0) uf.join(a, b);
        }
        // Pieces meeting at a crossing.
        for (std::size_t x = 0; x < xs.size(); ++x) {
            int ids[4] = {piece_at_cross_out[2 * x], piece_at_cross_out[2 * x + 1], piece_at_cross_site[2 * x],
                          piece_at_cross_site[2 * x + 1]};
            int first = -1;
            for (int id : ids)
                if (id >= 0) {
                    if (first < 0) first = id;
                    else uf.join(first, id);
                }
        }
        // Boundary pieces meeting end to end (along a polyline, across a cell border, where
        // two hazards' boundaries cross).
        {
            const double join = 1e3 * tol;
            std::vector<int>& order = sc.order;
            order.clear();
            for (std::size_t i = n_outline; i < pieces.size(); ++i) order.push_back(static_cast<int>(i));
            for (std::size_t ii = 0; ii < order.size(); ++ii)
                for (std::size_t jj = ii + 1; jj < order.size(); ++jj) {
                    const Piece& p = pieces[order[ii]];
                    const Piece& q = pieces[order[jj]];
                    if (uf.find(order[ii]) == uf.find(order[jj])) continue;
                    const double j2 = join * join;
                    if (dist2_to(p.a, q.a, q.b, nullptr) <= j2 || dist2_to(p.b, q.a, q.b, nullptr) <= j2 ||
                        dist2_to(q.a, p.a, p.b, nullptr) <= j2 || dist2_to(q.b, p.a, p.b, nullptr) <= j2)
                        uf.join(order[ii], order[jj]);
                }
            // Crossing points shared by outline pieces of neighbouring crossings at one point
            // (a boundary vertex on the outline) are joined through the crossings above.
        }
        // The hull wholly inside the hazards: the whole outline is one piece chain (joined above).
        Regions regions{sc.regions};
        std::vector<int>& region_of_root = sc.region_of_root;
        region_of_root.assign(pieces.size(), -1);
        for (std::size_t i = 0; i < pieces.size(); ++i) {
            const int r = uf.find(static_cast<int>(i));
            if (region_of_root[r] < 0) {
                region_of_root[r] = static_cast<int>(regions.size());
                regions.emplace_back();
            }
            Region& g = regions[region_of_root[r]];
            g.pieces.push_back(static_cast<int>(i));
            g.has_outline = g.has_outline || pieces[i].outline;
        }
        // A closed ring inside the hull: an islet (counter-clockwise: land inside) is a region;
        // a pond (clockwise) belongs to the region around it.
        std::vector<int>& merged_into = sc.merged_into;
        merged_into.assign(regions.size(), -1);
        for (std::size_t g = 0; g < regions.size(); ++g) {
            if (regions[g].has_outline) continue;
            double a2 = 0;
            for (int i : regions[g].pieces) a2 += geo::cross(pieces[i].a, pieces[i].b);
            if (a2 >= 0) continue;
            // A point just inside the hazards beside the pond: its nearest other piece's region.
            const Piece& p = pieces[regions[g].pieces.front()];
            const XY d = p.b - p.a;
            const double len = std::sqrt(geo::norm2(d));
            const XY probe = 0.5 * (p.a + p.b) + (eps / len) * XY{-d.y, d.x};
            double best2 = INFINITY;
            int into = -1;
            for (std::size_t h = 0; h < regions.size(); ++h) {
                if (h == g || merged_into[h] >= 0) continue;
                for (int i : regions[h].pieces) {
                    const double d2 = dist2_to(probe, pieces[i].a, pieces[i].b, nullptr);
                    if (d2 < best2) best2 = d2, into = static_cast<int>(h);
                }
            }
            if (into >= 0) merged_into[g] = into;
        }
        for (std::size_t g = 0; g < regions.size(); ++g)
            if (merged_into[g] >= 0) {
                int to = merged_into[g];
                while (merged_into[to] >= 0) to = merged_into[to];
                for (int i : regions[g].pieces) regions[to].pieces.push_back(i);
                regions[g].pieces.clear();
            }
        std::vector<int>& piece_region = sc.piece_region;
        piece_region.assign(pieces.size(), -1);
        for (std::size_t g = 0; g < regions.size(); ++g)
            for (int i : regions[g].pieces) piece_region[i] = static_cast<int>(g);

        // 2. Deepest points: along the outline pieces, then inside.
        // A region whose depth reaches the reach (less the slack of step 3) makes this attempt
        // one to do again with a longer reach (step 3: a depth only grows as the search goes
        // on), and nothing else of it is kept: the search stops there (`deep`).
        const double stop = reach < 1e8 ? reach - 2 * tol : INFINITY;
        bool deep = false;
        for (Region& g : regions)
            for (int i : g.pieces)
                if (pieces[i].outline && !deep) {
                    along(search, pieces[i].a, pieces[i].b, g.best, sc.intervals, stop, how.ridge_candidates);
                    deep = g.best.d >= stop;
                }
        std::vector<int>& live = sc.live;
        live.clear();
        for (std::size_t g = 0; g < regions.size(); ++g)
            if (!regions[g].pieces.empty()) live.push_back(static_cast<int>(g));
        if (!live.empty() && !S.empty() && !deep) {
            // Islets: a start at their boundary (depth 0).
            for (int g : live)
                if (regions[g].best.d < 0) {
                    const Piece& p = pieces[regions[g].pieces.front()];
                    regions[g].best = {0, p.a, p.a, -1};
                }
            // Both scan the pieces' distances to a cell's centre: region_at keeps them for
            // least_best_near at the same centre (`kept`).
            std::vector<double>& piece_d2 = sc.piece_d2;
            piece_d2.resize(pieces.size());
            bool kept = false;
            auto region_at = [&](XY q) {
                if (live.size() == 1) return live.front();
                double best2 = INFINITY;
                int r = -1;
                for (std::size_t i = 0; i < pieces.size(); ++i) {
                    if (piece_region[i] < 0 || regions[piece_region[i]].pieces.empty()) continue;
                    const double d2 = piece_d2[i] = dist2_to(q, pieces[i].a, pieces[i].b, nullptr);
                    if (d2 < best2) best2 = d2, r = piece_region[i];
                }
                kept = true;
                return r;
            };
            auto least_best_near = [&](XY q, double r, int own) {
                if (live.size() == 1) return regions[live.front()].best.d;
                double least = own >= 0 ? regions[own].best.d : INFINITY;
                const double r2 = r * r;
                for (std::size_t i = 0; i < pieces.size(); ++i) {
                    const int g = piece_region[i];
                    if (g < 0 || regions[g].pieces.empty()) continue;
                    if ((kept ? piece_d2[i] : dist2_to(q, pieces[i].a, pieces[i].b, nullptr)) <= r2) least = std::min(least, regions[g].best.d);
                }
                return least;
            };
            Box rbox;
            for (int g : live)
                for (int i : regions[g].pieces) rbox.extend(pieces[i].a), rbox.extend(pieces[i].b);
            const double side = std::max(std::max(rbox.maxx - rbox.minx, rbox.maxy - rbox.miny), tol);
            // Best first: the cell of the highest bound is cut next (a cell's bound is its parent's
            // until it is looked at), so the search ends when no cell can beat what was found.
            // A cell carries its parent's centre, side and distance to the boundary: a centre
            // nearer the parent's than that distance is on the same side (no winding number).
            std::vector<Cell>& queue = sc.queue;  // a heap: as std::priority_queue<Cell>
            queue.clear();
            auto push = [&queue](const Cell& cl) {
                queue.push_back(cl);
                std::push_heap(queue.begin(), queue.end());
            };
            for (double x = rbox.minx; x < rbox.maxx || x == rbox.minx; x += side)
                for (double y = rbox.miny; y < rbox.maxy || y == rbox.miny; y += side)
                    push({{x, y, x + side, y + side}, INFINITY, {}, 0.0, false, ConvexCutter::all_edges});
            int steps = 0;
            std::vector<XY>& poly = sc.poly;
            ConvexCutter cutter(ring, sc.cut_buffers);
            ConvexCutter::Edges edges = ConvexCutter::all_edges;
            std::vector<XY>& cell_polys = sc.cell_polys;
            cell_polys.clear();
            while (!queue.empty() && ++steps < 100000) {
                std::pop_heap(queue.begin(), queue.end());
                const Cell cell = queue.back();
                queue.pop_back();
                if (live.size() == 1 && cell.bound <= regions[live.front()].best.d + tol) break;
                if (cell.box.minx > hbox.maxx || cell.box.maxx < hbox.minx || cell.box.miny > hbox.maxy || cell.box.maxy < hbox.miny)
                    continue;
                if (convex) {  // cut to the hull
                    if (how.cut_from_parent && cell.parent_poly_n > 0)
                        clip_to_box(std::span<const XY>(cell_polys).subspan(cell.parent_poly, cell.parent_poly_n), cell.box, poly, sc.clip_tmp);
                    else if (how.cut_from_parent)  // a first cell: the hull cut to its box
                        clip_to_box(std::span<const XY>(ring).first(n_edges), cell.box, poly, sc.clip_tmp);
                    else
                        edges = cutter.cut(cell.box, cell.edges, poly);
                    if (poly.size() < 3) continue;
                } else {
                    poly = {{cell.box.minx, cell.box.miny}, {cell.box.maxx, cell.box.miny},
                            {cell.box.maxx, cell.box.maxy}, {cell.box.minx, cell.box.maxy}};
                }
                kept = false;  // (region_at's distances are for another centre)
                XY c{0, 0};
                for (XY p : poly) c = c + p;
                c = (1.0 / static_cast<double>(poly.size())) * c;
                double r2 = 0;  // (the root of the greatest square: the same number as the greatest root)
                for (XY p : poly) r2 = std::max(r2, geo::norm2(p - c));
                const double r = std::sqrt(r2);
                Search::Near n;
                n = search.nearest(c);
                const bool in_hazard = cell.parent_clear > 0 && geo::distance(c, cell.parent) < cell.parent_clear
                                           ? cell.parent_inside
                                           : search.inside(c, n);
                const double sd = in_hazard ? n.d : -n.d;
                int own = -1;
                const bool in_hull = convex || in_polygon(ring, c);
                if (sd > 0 && in_hull) {
                    own = region_at(c);
                    if (own >= 0 && sd > regions[own].best.d) regions[own].best = {sd, c, n.foot, n.site};
                    if (own >= 0 && regions[own].best.d >= stop) {
                        deep = true;
                        break;
                    }
                }
                if (r <= tol || sd < -r) continue;  // small enough, or all water
                if (!in_hull) {  // outside the hull: does the cell reach it?
                    double near2 = INFINITY;
                    for (std::size_t e = 0; e < n_edges; ++e) near2 = std::min(near2, dist2_to(c, ring[e], ring[e + 1], nullptr));
                    if (near2 > r * r) continue;
                }
                // One boundary piece nearest all over the cell (the next one farther by more
                // than the cell's diameter): d is a distance to one segment there, with no
                // maximum inside; the region's deepest point is on the outline (searched
                // above) or at a maximum of d in another cell.
                // (The bounds without a second site first: a cell they cut off needs no second
                // site nor the two-site bound.)
                const double least = least_best_near(c, r, own);
                double b = search.bound(poly, n, -1, sd, r);
                if (b <= least + tol) continue;
                const int j = n.site >= 0 ? search.second(c, n) : -1;
                if (j < 0 || search.dist_to_site(c, j) - n.d > 2 * r) continue;
                XY at;
                const double two = search.two_site_bound(poly, n.site, j, &at);
                if (how.ridge_candidates && two < b && two > least + tol && (convex || in_polygon(ring, at))) {
                    // The two-site bound's maximum is a candidate: on the ridge between the two
                    // sites (the medial axis, where the deepest point lies); when no other site
                    // is nearer there, it meets the bound and the cell is done.
                    const Search::Near na = search.nearest(at);
                    if (na.d > 0 && search.inside(at, na)) {
                        const int own_at = region_at(at);
                        if (own_at >= 0 && na.d > regions[own_at].best.d) {
                            regions[own_at].best = {na.d, at, na.foot, na.site};
                            if (regions[own_at].best.d >= stop) {
                                deep = true;
                                break;
                            }
                        }
                        kept = false;
                    }
                    b = two;
                    if (b <= least_best_near(c, r, own) + tol) continue;
                }
                b = std::min(b, two);
                if (b <= least + tol) continue;
                // Near a vertex of the boundary the two nearest sites are often the two
                // segments meeting there, on the same side of the region (a pier's side), and
                // the bound of that pair is loose by about the cell's size all along their
                // ridge: the pairs with a third site, the nearest whose nearest point is neither
                // of theirs (the pier's other side), each bound it as well. Not when the third
                // is farther than the nearest all over the cell (it changes nothing there).
                const int k3 = how.third_site ? search.third(c, n, j) : -1;
                if (k3 >= 0 && search.dist_to_site(c, k3) - n.d <= 2 * r) {
                    b = std::min({b, search.two_site_bound(poly, n.site, k3), search.two_site_bound(poly, j, k3)});
                    if (b <= least + tol) continue;
                }
                const double hx = (cell.box.minx + cell.box.maxx) / 2, hy = (cell.box.miny + cell.box.maxy) / 2;
                const double clear_c = std::min(n.d, reach);
                std::uint32_t at_poly = 0, n_poly = 0;
                if (convex && how.cut_from_parent) {
                    at_poly = static_cast<std::uint32_t>(cell_polys.size()), n_poly = static_cast<std::uint32_t>(poly.size());
                    cell_polys.insert(cell_polys.end(), poly.begin(), poly.end());
                }
                push({{cell.box.minx, cell.box.miny, hx, hy}, b, c, clear_c, in_hazard, edges, at_poly, n_poly});
                push({{hx, cell.box.miny, cell.box.maxx, hy}, b, c, clear_c, in_hazard, edges, at_poly, n_poly});
                push({{cell.box.minx, hy, hx, cell.box.maxy}, b, c, clear_c, in_hazard, edges, at_poly, n_poly});
                push({{hx, hy, cell.box.maxx, cell.box.maxy}, b, c, clear_c, in_hazard, edges, at_poly, n_poly});
            }
        }
        // 3. A depth at the reach: a nearer boundary may lie beyond it.
        bool again = deep;
        for (int g : live)
            if (regions[g].best.d >= reach - 2 * tol) again = true;
        if (S.empty() && !live.empty()) again = true;  // inside everything within reach
        if (S.empty() && live.empty() && lines.empty()) {
            // Nothing within reach: the hull overlaps nothing, or lies wholly inside.
            if (!obstacle.inside(ring.front())) return {};
            again = true;
        }
        if (again && reach < 1e8) {
            reach *= 4;
            continue;
        }

        std::vector<ContactRegion> out;
        for (int g : live) {
            const Best& b = regions[g].best;
            if (!(b.d >= 0)) continue;
            ContactRegion cr;
            cr.hull_point = b.point;
            cr.coast_point = b.foot;
            cr.depth_m = b.d / scale;
            cr.polyline = b.site >= 0 ? S[b.site].polyline : no_polyline;
            const XY v = b.foot - b.point;
            const double len = std::sqrt(geo::norm2(v));
            if (len > 0) {
                cr.normal = (1 / len) * v;
            } else if (b.site >= 0) {
                const XY d = S[b.site].b - S[b.site].a;
                const double l = std::sqrt(geo::norm2(d));
                cr.normal = {d.y / l, -d.x / l};  // towards the water side
            } else {
                cr.normal = {1, 0};
            }
            out.push_back(cr);
        }
        // Lines without a land side crossing the hull: a region of depth 0 each (per polyline).
        std::vector<std::uint32_t> seen;
        for (const RawSegment& l : lines) {
            if (std::find(seen.begin(), seen.end(), l.polyline) != seen.end()) continue;
            XY at;
            bool hit = in_polygon(ring, l.a) ? (at = l.a, true) : in_polygon(ring, l.b) ? (at = l.b, true) : false;
            for (std::size_t e = 0; e < n_edges && !hit; ++e) {
                std::vector<std::pair<double, double>>& tu = sc.tu;
                tu.clear();
                crossings(ring[e], ring[e + 1], l.a, l.b, tu);
                if (!tu.empty()) at = ring[e] + tu.front().first * (ring[e + 1] - ring[e]), hit = true;
            }
            // A line met where it crosses the hazards' boundary (a coastline drawn on the land
            // area's edge) touches the hull where the hazards do: that contact is theirs, and
            // whether the crossing is in or out of them is a matter of rounding.
            if (!hit || obstacle.inside(at) || search.nearest(at).d <= tol) continue;
            seen.push_back(l.polyline);
            const XY d = l.b - l.a;
            const double len = std::sqrt(geo::norm2(d));
            ContactRegion cr;
            cr.hull_point = cr.coast_point = at;
            cr.normal = {d.y / len, -d.x / len};
            cr.polyline = l.polyline;
            out.push_back(cr);
        }
        std::stable_sort(out.begin(), out.end(), [](const ContactRegion& a, const ContactRegion& b) { return a.depth_m > b.depth_m; });
        return out;
    }
    return {};
}

}  // namespace

std::vector<ContactRegion> contact_regions(const Detector& detector, const LocalPose& pose) { return detail::contact_regions(detector, pose, {}); }

std::vector<ContactRegion> detail::contact_regions(const Detector& detector, const LocalPose& pose, const ContactSearch& how) {
    const grid::CoastGrid& g = detector.grid();
    Scratch& sc = scratch();
    // The reach's box of the attempt under way: every point asked then lies in it, but for
    // a few a micrometre out (winding numbers below).
    // And, per cell, the land boundary segments met in it (their indices in the grid's array):
    // a path inside the focus meets only those (winding numbers below).
    Box focus;
    std::vector<CellNear>& cells_near = sc.cells_near;  // the first `n_cells_near` are the focus's
    std::size_t n_cells_near = 0;
    auto collect = [&g, &focus, &cells_near, &n_cells_near](const Box& box, std::vector<RawSegment>& out) {
        focus = box, n_cells_near = 0;
        const geo::Box ext = g.extent();
        const int i0 = std::max(0, g.col_of(std::max(box.minx, ext.minx))), i1 = std::min(g.nx() - 1, g.col_of(std::min(box.maxx, ext.maxx)));
        const int j0 = std::max(0, g.row_of(std::max(box.miny, ext.miny))), j1 = std::min(g.ny() - 1, g.row_of(std::min(box.maxy, ext.maxy)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const auto segs = g.segments(i, j);
                if (segs.empty()) continue;
                // Whole chunks of segments whose box misses the box are skipped (a harbour
                // cell holds ~760 segments; a chunk's box holds its segments' boxes).
                const std::size_t first = g.index_of(segs);
                if (n_cells_near == cells_near.size()) cells_near.emplace_back();
                CellNear& cn = cells_near[n_cells_near++];
                cn.i = i, cn.j = j, cn.near.clear();
                const std::span<const Box> chunks = g.chunk_boxes(), blocks = g.block_boxes();
                constexpr std::size_t chunk = grid::CoastGrid::chunk_segments, block = grid::CoastGrid::block_segments;
                for (std::size_t k = 0; k < segs.size(); ++k) {
                    if ((first + k) % block == 0 && k + block <= segs.size()) {  // a block of chunks first
                        const Box& c = blocks[(first + k) / block];
                        if (c.maxx < box.minx || c.minx > box.maxx || c.maxy < box.miny || c.miny > box.maxy) {
                            k += block - 1;
                            continue;
                        }
                    }
                    if ((first + k) % chunk == 0 && k + chunk <= segs.size()) {
                        const Box& c = chunks[(first + k) / chunk];
                        if (c.maxx < box.minx || c.minx > box.maxx || c.maxy < box.miny || c.miny > box.maxy) {
                            k += chunk - 1;
                            continue;
                        }
                    }
                    const grid::Segment& s = segs[k];
                    if (std::max(s.a.x, s.b.x) < box.minx || std::min(s.a.x, s.b.x) > box.maxx ||
                        std::max(s.a.y, s.b.y) < box.miny || std::min(s.a.y, s.b.y) > box.maxy)
                        continue;
                    const bool boundary = g.segment_is_boundary(i, j, k);
                    out.push_back({s.a, s.b, g.polyline_of(s), boundary});
                    if (boundary) cn.near.push_back(static_cast<std::uint32_t>(first + k));
                }
            }
    };
    // Winding numbers: the first point asked in a grid cell counts from the cell's reference
    // point; later points of the same cell count from it, along a path as short as the hull
    // (a harbour's coast cell holds ~760 segments, and the long path met many of them).
    // And a path inside the reach's box meets only the cell's segments whose box meets it:
    // listed by the gathering above, each point tries those only (~14, not ~760).
    // Points whose windings are known, the first asked in their grid cells, kept from the calls
    // before on this grid (a ship moves little from one frame to the next: counted from them,
    // a winding crosses a short path, not one from the cell's reference point).
    std::vector<KnownWinding>& known = sc.known;
    if (sc.known_grid != g.instance() || known.size() > 16) known.clear();
    sc.known_grid = g.instance();
    auto holds = [](const Box& b, XY p) { return p.x >= b.minx && p.x <= b.maxx && p.y >= b.miny && p.y <= b.maxy; };
    auto inside = [&g, &known, &focus, &cells_near, &n_cells_near, holds](XY p) {
        const int i = g.col_of(p.x), j = g.row_of(p.y);
        for (const KnownWinding& k : known)
            if (k.i == i && k.j == j) {
                if (!holds(focus, p) || !holds(focus, k.at)) return g.winding_from(k.at, k.w, p) > 0;
                for (std::size_t c = 0; c < n_cells_near; ++c)
                    if (cells_near[c].i == i && cells_near[c].j == j) return g.winding_along(k.at, k.w, p, cells_near[c].near) > 0;
                return g.winding_along(k.at, k.w, p, {}) > 0;  // a cell without segments
            }
        bool on_boundary = false;
        const int w = g.winding(p, &on_boundary);
        if (!on_boundary && g.valid_cell(i, j)) known.push_back({i, j, p, w});
        return w > 0;
    };
    const Obstacle o{collect, inside};
    // No contact, no region: the pose check answers that in a microsecond. (Its penetration,
    // as a first reach, cost more on a harbour chart than the reach's growing saves.)
    // A hull vertex on land is a contact: the one this thread last found deepest is tried
    // first, as the check would try its own (one winding number), counted from its cell's known
    // point when the cell has one, else kept as that point (the search below then counts from
    // it, not from the cell's reference point again). Else the check, without that first try.
    const std::vector<XY> outline = hull_outline(detector.hull(), pose);
    std::size_t& try_first = sc.on_land;
    bool q_on_boundary = false;
    const XY q = outline.empty() ? pose.position : outline[try_first < outline.size() ? try_first : 0];
    const int q_i = g.col_of(q.x), q_j = g.row_of(q.y);
    KnownWinding* q_known = nullptr;
    for (KnownWinding& k : known)
        if (k.i == q_i && k.j == q_j) q_known = &k;
    // A point kept is one whose winding was counted from its cell's reference point, never one
    // counted from another kept point (an error of rounding in one count, at a point within
    // rounding of a boundary, would be carried on to every later count from it). One kept
    // farther than an eighth of a cell from q (the ship has moved on) is replaced by q, counted
    // from the reference point: the paths counted from it stay short.
    const double eighth = g.cell_size() / 8;
    if (q_known && geo::norm2(q - q_known->at) > eighth * eighth) {
        *q_known = known.back();
        known.pop_back();
        q_known = nullptr;
    }
    const int q_w = outline.empty() ? 0 : q_known ? g.winding_from(q_known->at, q_known->w, q, &q_on_boundary) : g.winding(q, &q_on_boundary);
    if (!outline.empty() && !q_on_boundary && !q_known && g.valid_cell(q_i, q_j)) known.push_back({q_i, q_j, q, q_w});
    if (q_w <= 0 && !detector.check(pose, {.max_clearance_m = 0, .want_penetration = false, .want_polyline = false, .want_contact_point = true}).collision)
        return {};
    std::vector<ContactRegion> out = regions_of(outline, o, local_scale(pose), how);
    if (q_w <= 0 && !out.empty() && out.front().depth_m > 0) {
        // The next pose's first try: the vertex nearest the deepest region's point (on land as
        // a rule: only which vertex is tried first depends on it).
        double best2 = INFINITY;
        for (std::size_t k = 0; k < outline.size(); ++k) {
            const double d2 = geo::norm2(outline[k] - out.front().hull_point);
            if (d2 < best2) best2 = d2, try_first = k;
        }
    }
    if (out.empty()) {
        // A touch the search above cannot see as a region (a hull vertex exactly on the
        // boundary): the check's contact point, depth 0.
        const Contact c = detector.check(pose, {.max_clearance_m = 0, .want_penetration = false});
        {
            ContactRegion cr;
            cr.hull_point = c.hull_point;
            cr.coast_point = c.coast_point;
            cr.polyline = c.polyline;
            const XY centre = pose.position;
            const XY v = c.hull_point - centre;
            const double len = std::sqrt(geo::norm2(v));
            cr.normal = len > 0 ? (-1 / len) * v : XY{1, 0};
            out.push_back(cr);
        }
    }
    return out;
}

std::vector<ContactRegion> hull_contact_regions(const std::vector<XY>& a, const std::vector<XY>& b, double scale) {
    const std::vector<XY> ring = ccw_closed(b);
    if (ring.empty()) return {};
    auto collect = [&ring](const Box&, std::vector<RawSegment>& out) {
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) out.push_back({ring[i], ring[i + 1], 0, true});
    };
    auto inside = [&ring](XY p) { return in_polygon(ring, p); };
    const Obstacle o{collect, inside};
    std::vector<ContactRegion> out = regions_of(a, o, scale, {});
    for (ContactRegion& r : out) r.polyline = no_polyline;
    return out;
}

}  // namespace shoal::check
