#pragma once
// The geometry under the contact regions (contacts.cpp, the only file that includes this one:
// its names stay in an anonymous namespace, so the compiler sees them as that file's own):
// boundary segments and sites, clipping and crossings, point in polygon, collinear sites merged,
// the convex cutter of the interior search's cells, the nearest-site search with its bounds
// (Search), and the branch and bound along an outline piece (along).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include <shoal/check/contacts.hpp>

#include "check/contact_search.hpp"

namespace shoal::check {

using geo::Box;
using geo::XY;

namespace {

constexpr std::uint32_t no_polyline = grid::CoastGrid::no_polyline;

struct RawSegment {
    XY a, b;
    std::uint32_t polyline = no_polyline;
    bool boundary = true;  // land on the left
};

/// A callable `f` referred to, not owned (std::function allocated for each of a call's two
/// lambdas, whose captures are larger than its small buffer): `f` outlives the reference.
template <class Sig>
class CallableRef;
template <class R, class... A>
class CallableRef<R(A...)> {
public:
    template <class F>
        requires(!std::is_same_v<std::remove_cv_t<F>, CallableRef>)  // (a copy is a copy, not a reference to a reference)
    CallableRef(F& f) noexcept  // NOLINT(google-explicit-constructor): as std::function
        : m_f(&f), m_call([](void* o, A... a) -> R { return (*static_cast<F*>(o))(std::forward<A>(a)...); }) {}
    R operator()(A... a) const { return m_call(m_f, std::forward<A>(a)...); }

private:
    void* m_f;
    R (*m_call)(void*, A...);
};

/// What the hull must not overlap: its boundary segments in a box, and membership.
struct Obstacle {
    CallableRef<void(const Box&, std::vector<RawSegment>&)> collect;
    CallableRef<bool(XY)> inside;
};

/// A piece of the union's boundary, land on its left.
struct Site {
    XY a, b;
    std::uint32_t polyline = no_polyline;
};

double dist2_to(XY p, XY a, XY b, XY* foot) noexcept {
    double t;
    const double d2 = geo::point_segment_dist2(p, a, b, &t);
    if (foot) *foot = a + t * (b - a);
    return d2;
}

/// Two slabs, lo[k] <= n[k] . p <= hi[k] for unit normals n[k]: with the box, where a
/// convex hull's reach lies (regions_of).
struct Slabs {
    XY n[2];
    double lo[2], hi[2];
};

/// Liang-Barsky: clips segment ab to `box` and, when given, to `slabs`; false when nothing is
/// left.
bool clip_to(XY& a, XY& b, const Box& box, const Slabs* slabs = nullptr) noexcept {
    if (slabs)  // both ends beyond one side of a slab (most segments left out): nothing left
        for (int k = 0; k < 2; ++k) {
            const double an = geo::dot(slabs->n[k], a), bn = geo::dot(slabs->n[k], b);
            if ((an < slabs->lo[k] && bn < slabs->lo[k]) || (an > slabs->hi[k] && bn > slabs->hi[k])) return false;
        }
    double t0 = 0, t1 = 1;
    const XY d = b - a;
    const double p[4] = {-d.x, d.x, -d.y, d.y};
    const double q[4] = {a.x - box.minx, box.maxx - a.x, a.y - box.miny, box.maxy - a.y};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0) {
            if (q[k] < 0) return false;
            continue;
        }
        const double r = q[k] / p[k];
        if (p[k] < 0) t0 = std::max(t0, r);
        else t1 = std::min(t1, r);
        if (t0 > t1) return false;
    }
    if (slabs) {
        for (int k = 0; k < 2; ++k) {
            const double an = geo::dot(slabs->n[k], a), dn = geo::dot(slabs->n[k], d);
            if (dn == 0) {
                if (an < slabs->lo[k] || an > slabs->hi[k]) return false;
                continue;
            }
            const double r0 = (slabs->lo[k] - an) / dn, r1 = (slabs->hi[k] - an) / dn;
            t0 = std::max(t0, std::min(r0, r1));
            t1 = std::min(t1, std::max(r0, r1));
            if (t0 > t1) return false;
        }
    }
    const XY a0 = a;
    if (t0 > 0) a = a0 + t0 * d;
    if (t1 < 1) b = a0 + t1 * d;
    return true;
}

/// Whether the boxes of segments ab and cd are apart (then they do not cross).
inline bool boxes_apart(XY a, XY b, XY c, XY d) noexcept {
    return std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) || std::max(a.y, b.y) < std::min(c.y, d.y) ||
           std::max(c.y, d.y) < std::min(a.y, b.y);
}

/// crossings() of two segments whose boxes meet (the callers in loops test the boxes first).
void crossings_of_near(XY a, XY b, XY c, XY d, std::vector<std::pair<double, double>>& out) {
    if (!geo::segments_intersect(a, b, c, d)) return;
    const XY r = b - a, s = d - c;
    const double den = geo::cross(r, s);
    if (den != 0) {
        const double t = std::clamp(geo::cross(c - a, s) / den, 0.0, 1.0);
        const double u = std::clamp(geo::cross(c - a, r) / den, 0.0, 1.0);
        out.emplace_back(t, u);
        return;
    }
    // Collinear: the ends of either segment that lie on the other.
    const double rr = geo::norm2(r), ss = geo::norm2(s);
    auto param = [](XY p, XY o, XY v, double vv) { return vv > 0 ? geo::dot(p - o, v) / vv : 0.0; };
    for (XY p : {c, d}) {
        const double t = param(p, a, r, rr);
        if (t >= 0 && t <= 1) out.emplace_back(t, param(p, c, s, ss));
    }
    for (XY p : {a, b}) {
        const double u = param(p, c, s, ss);
        if (u >= 0 && u <= 1) out.emplace_back(param(p, a, r, rr), u);
    }
}

/// Parameters of the crossing of segments ab and cd (touching counts): t on ab, u on cd.
/// Collinear overlaps give the overlap's ends that lie on the other segment.
void crossings(XY a, XY b, XY c, XY d, std::vector<std::pair<double, double>>& out) {
    // Most pairs are far apart: their boxes say so for less than the orientation tests.
    if (boxes_apart(a, b, c, d)) return;
    crossings_of_near(a, b, c, d, out);
}

/// Even-odd point in polygon (closed ring, last point = first).
bool in_polygon(const std::vector<XY>& ring, XY p) noexcept {
    bool in = false;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        const XY a = ring[i], b = ring[i + 1];
        if ((a.y > p.y) != (b.y > p.y)) {
            const double x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if (p.x < x) in = !in;
        }
    }
    return in;
}

/// Joins the pieces of one straight segment that the grid's cells cut apart (they overlap by
/// the clip slack): one site each, so that a point near a cell border has one nearest site.
void merge_collinear(std::vector<Site>& sites, double tol) {
    if (sites.size() > 512) return;
    for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < sites.size(); ++i)
            for (std::size_t j = i + 1; j < sites.size(); ++j) {
                Site& a = sites[i];
                const Site& b = sites[j];
                if (a.polyline != b.polyline) continue;
                // b within tol of a's line and overlapping a's span within tol has a point within
                // 2 tol of a: boxes farther apart than that (with room for rounding) never merge.
                const double gap = 4 * tol;
                if (std::max(b.a.x, b.b.x) < std::min(a.a.x, a.b.x) - gap || std::min(b.a.x, b.b.x) > std::max(a.a.x, a.b.x) + gap ||
                    std::max(b.a.y, b.b.y) < std::min(a.a.y, a.b.y) - gap || std::min(b.a.y, b.b.y) > std::max(a.a.y, a.b.y) + gap)
                    continue;
                const XY d = a.b - a.a;
                const double len = std::sqrt(geo::norm2(d));
                if (!(len > 0)) continue;
                const XY u = (1 / len) * d;
                // b on a's line, in the same direction, and touching or overlapping a.
                if (std::fabs(geo::cross(u, b.a - a.a)) > tol || std::fabs(geo::cross(u, b.b - a.a)) > tol) continue;
                const double t0 = geo::dot(b.a - a.a, u), t1 = geo::dot(b.b - a.a, u);
                if (!(t1 > t0)) continue;
                if (t0 > len + tol || t1 < -tol) continue;
                const double lo = std::min(0.0, t0), hi = std::max(len, t1);
                const XY origin = a.a;
                a.a = lo < 0 ? b.a : origin;
                a.b = hi > len ? b.b : a.b;
                sites.erase(sites.begin() + static_cast<std::ptrdiff_t>(j));
                merged = true;
                --j;
            }
    }
}

/// Parameters along a segment, each with the crossing it comes from (-1: an end), sorted, in
/// groups closer than the tolerance: one point of the segment each, a range of the parameters.
struct ParamGroup {
    double t;               // the group's first parameter
    std::size_t from, to;   // its range of the parameters
    bool has_crossing = false;
    bool start = false, end = false;  // holds the segment's start (0) or end (1)
};

void group_params(const std::vector<std::pair<double, int>>& ts, double len, double tol, std::vector<ParamGroup>& groups) {
    groups.clear();
    for (std::size_t i = 0; i < ts.size(); ++i) {
        const auto [t, x] = ts[i];
        if (groups.empty() || (t - groups.back().t) * len > tol) groups.push_back({t, i, i});
        ParamGroup& g = groups.back();
        g.to = i + 1;
        g.has_crossing = g.has_crossing || x >= 0;
        g.start = g.start || t == 0.0;
        g.end = g.end || t == 1.0;
    }
}

struct UnionFind {
    std::vector<int>& parent;  // (storage kept between calls)
    UnionFind(std::vector<int>& storage, std::size_t n) : parent(storage) {
        parent.resize(n);
        std::iota(parent.begin(), parent.end(), 0);
    }
    int find(int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void join(int a, int b) { parent[find(a)] = find(b); }
};

/// Boxes cut to a convex ring (counter-clockwise, closed) by Sutherland-Hodgman. An edge whose
/// inner side holds the whole box by a margin is skipped: its pass would keep every vertex, and
/// a cell of the search is near few of the hull's edges (a rounded bow has dozens). An edge that
/// holds a box holds every box inside it: the cells' search hands the edges that did not hold a
/// cell to its quarters (a bit each for the first 64 edges; the others are always tried).
class ConvexCutter {
public:
    using Edges = std::uint64_t;
    static constexpr Edges all_edges = ~Edges{0};

    /// `buffers`: two working lists, kept by the caller between cutters.
    ConvexCutter(const std::vector<XY>& ccw, std::vector<XY> (&buffers)[2]) : m_ring(ccw), m_buf(buffers) {}

    /// `poly` := `box` cut to the ring (fewer than 3 points: they do not overlap), trying the
    /// edges of `edges` (those that did not hold a box around this one); returns those that do
    /// not hold this box.
    Edges cut(const Box& box, Edges edges, std::vector<XY>& poly) {
        // Two buffers passed back and forth (no push_back: their sizes are checked once a pass,
        // a pass at most doubling the vertices), the answer copied to `poly` at the end.
        const std::size_t n = m_ring.size() - 1;
        if (m_buf[0].size() < 16) m_buf[0].resize(16), m_buf[1].resize(16);
        int cur = 0;
        std::size_t m = 4;
        {
            XY* v = m_buf[0].data();
            v[0] = {box.minx, box.miny}, v[1] = {box.maxx, box.miny}, v[2] = {box.maxx, box.maxy}, v[3] = {box.minx, box.maxy};
        }
        Edges unheld = 0;
        for (std::size_t i = next_edge(edges, 0, n); i < n && m > 0; i = next_edge(edges, i + 1, n)) {
            const Edges bit = i < 64 ? Edges{1} << i : 0;
            const XY a = m_ring[i], b = m_ring[i + 1];
            if (holds(a, b, box)) continue;
            unheld |= bit;
            if (m_buf[1 - cur].size() < 2 * m) m_buf[1 - cur].resize(2 * m);
            const XY* in = m_buf[cur].data();
            XY* out = m_buf[1 - cur].data();
            std::size_t k2 = 0;
            // Each vertex's side once (it is p of one step and q of the one before), the last
            // step back to the first vertex.
            const double o_first = geo::orient(a, b, in[0]);
            double op = o_first;
            for (std::size_t k = 0; k < m; ++k) {
                const XY p = in[k], q = k + 1 < m ? in[k + 1] : in[0];
                const double oq = k + 1 < m ? geo::orient(a, b, q) : o_first;
                if (op >= 0) out[k2++] = p;
                if ((op > 0 && oq < 0) || (op < 0 && oq > 0)) out[k2++] = p + (op / (op - oq)) * (q - p);
                op = oq;
            }
            cur = 1 - cur;
            m = k2;
        }
        poly.assign(m_buf[cur].data(), m_buf[cur].data() + m);
        return unheld;
    }

private:
    /// The first edge from `i` on that is in `edges` (or past the 64 of the mask), n if none.
    static std::size_t next_edge(Edges edges, std::size_t i, std::size_t n) noexcept {
        if (i >= 64) return std::min(i, n);
        const Edges rest = edges >> i;
        const std::size_t next = rest ? i + static_cast<std::size_t>(std::countr_zero(rest)) : 64;
        return std::min(next, n);
    }

    /// Whether the box lies left of a->b by more than rounding (its corner least left of it, by
    /// a margin far above the error of orient at the box's corners or at points cut from it).
    static bool holds(XY a, XY b, const Box& box) noexcept {
        const XY d = b - a;
        const XY p{d.y > 0 ? box.maxx : box.minx, d.x > 0 ? box.miny : box.maxy};
        const XY v = p - a;
        const double margin = 1e-9 * (std::fabs(d.x) + std::fabs(d.y)) * (std::fabs(v.x) + std::fabs(v.y) + 1);
        return geo::cross(d, v) > margin;
    }

    const std::vector<XY>& m_ring;
    std::vector<XY> (&m_buf)[2];
};

/// `out` := convex polygon `in` cut to `box` (as ConvexCutter::cut, one side of the box at a
/// time, only the sides the polygon crosses; a cut point lies on the side exactly). `tmp`: a
/// working list. (A polygon convex only to rounding may gain two vertices at a side: the
/// lists are grown to twice the vertices before each side, as ConvexCutter's.)
inline void clip_to_box(std::span<const XY> in, const Box& box, std::vector<XY>& out, std::vector<XY>& tmp) {
    std::vector<XY>* cur = &out;
    std::vector<XY>* next = &tmp;
    if (cur->size() < in.size()) cur->resize(in.size());
    std::copy(in.begin(), in.end(), cur->begin());
    std::size_t m = in.size();
    Box pb;
    for (XY p : in) pb.extend(p);
    for (int side = 0; side < 4 && m > 0; ++side) {
        const bool along_x = side < 2;
        const double at = side == 0 ? box.minx : side == 1 ? box.maxx : side == 2 ? box.miny : box.maxy;
        // Wholly inside this side: nothing to cut.
        if (side == 0 ? pb.minx >= at : side == 1 ? pb.maxx <= at : side == 2 ? pb.miny >= at : pb.maxy <= at) continue;
        if (next->size() < 2 * m) next->resize(2 * m);
        const XY* in_v = cur->data();
        XY* out_v = next->data();
        const double sign = side % 2 == 0 ? 1.0 : -1.0;
        auto dist = [along_x, at, sign](XY p) { return sign * ((along_x ? p.x : p.y) - at); };
        std::size_t k2 = 0;
        double dp = dist(in_v[0]);
        const double d_first = dp;
        for (std::size_t k = 0; k < m; ++k) {
            const XY p = in_v[k], q = k + 1 < m ? in_v[k + 1] : in_v[0];
            const double dq = k + 1 < m ? dist(q) : d_first;
            if (dp >= 0) out_v[k2++] = p;
            if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) {
                XY x = p + (dp / (dp - dq)) * (q - p);
                (along_x ? x.x : x.y) = at;
                out_v[k2++] = x;
            }
            dp = dq;
        }
        std::swap(cur, next);
        m = k2;
    }
    if (cur != &out) {
        if (out.size() < m) out.resize(m);
        std::copy(cur->begin(), cur->begin() + static_cast<std::ptrdiff_t>(m), out.begin());
    }
    out.resize(m < 3 ? 0 : m);
}

/// A site in the order of its box's least x, with the greatest x of the boxes up to it.
struct ByX {
    double minx, max_maxx;
    int site;
};

/// The search over one set of boundary pieces.
class Search {
public:
    static constexpr std::size_t sorted_from = 24;  // sites: fewer are scanned in index order

    /// `sites`, `boxes` and `by_x` are storage kept between calls: `boxes` and `by_x` are
    /// filled here.
    Search(const std::vector<Site>& sites, std::vector<Box>& boxes, std::vector<ByX>& by_x, const Obstacle& obstacle, double tol)
        : m_sites(sites), m_boxes(boxes), m_by_x(by_x), m_obstacle(obstacle), m_tol(tol), m_slack2((100 * tol) * (100 * tol)) {
        m_boxes.clear();
        for (const Site& st : m_sites)
            m_boxes.push_back({std::min(st.a.x, st.b.x), std::min(st.a.y, st.b.y), std::max(st.a.x, st.b.x), std::max(st.a.y, st.b.y)});
        // Many sites (a pier's harbour: 150-300 within a few metres): the scans take them in
        // the order of their boxes' least x, from the first whose boxes so far reach near the
        // point to the first whose box begins too far right of it.
        m_by_x.clear();
        if (m_sites.size() >= sorted_from) {
            for (std::size_t k = 0; k < m_boxes.size(); ++k) m_by_x.push_back({m_boxes[k].minx, 0.0, static_cast<int>(k)});
            std::sort(m_by_x.begin(), m_by_x.end(), [](const ByX& x, const ByX& y) { return x.minx < y.minx || (x.minx == y.minx && x.site < y.site); });
            double reach_x = -INFINITY;
            for (ByX& b : m_by_x) b.max_maxx = reach_x = std::max(reach_x, m_boxes[b.site].maxx);
        }
    }

    struct Near {
        double d = INFINITY;
        XY foot;
        int site = -1;
    };

    /// The nearest site: the least (squared distance, index), as a scan in index order finds
    /// it. A site is tried first (the last answer: queries come in runs close together), and a
    /// site whose box is farther than the best so far by more than rounding is not looked at.
    Near nearest(XY p) const noexcept {
        Near n;
        double best2 = INFINITY;
        int best = -1;
        double limit = INFINITY;  // beyond(best2)
        auto consider = [&](int k) {
            XY f;
            const double d2 = dist2_to(p, m_sites[k].a, m_sites[k].b, &f);
            if (d2 < best2 || (d2 == best2 && k < best)) best2 = d2, n.foot = f, best = k, limit = beyond(best2);
        };
        const int count = static_cast<int>(m_sites.size());
        const int hint = m_hint < count ? m_hint : -1;
        if (hint >= 0) consider(hint);
        scan(p, limit, [&](int k) {
            if (k != hint) consider(k);
        });
        n.site = best;
        n.d = std::sqrt(best2);
        if (best >= 0) m_hint = best;
        return n;
    }

    /// The nearest site whose nearest point is not `first`'s (a second site for the bound):
    /// the least (squared distance, index) among them, as nearest().
    int second(XY p, const Near& first) const noexcept {
        int best = -1;
        double best2 = INFINITY;
        const double apart2 = (100 * m_tol) * (100 * m_tol);
        double limit = INFINITY;  // beyond(best2)
        auto consider = [&](int k) {
            XY f;
            const double d2 = dist2_to(p, m_sites[k].a, m_sites[k].b, &f);
            if ((d2 < best2 || (d2 == best2 && k < best)) && geo::norm2(f - first.foot) > apart2)
                best2 = d2, best = k, limit = beyond(best2);
        };
        const int count = static_cast<int>(m_sites.size());
        const int hint = m_second_hint < count && m_second_hint != first.site ? m_second_hint : -1;
        if (hint >= 0) consider(hint);
        scan(p, limit, [&](int k) {
            if (k != first.site && k != hint) consider(k);
        });
        if (best >= 0) m_second_hint = best;
        return best;
    }

    /// The nearest site whose nearest point is neither `first`'s nor that of site `other` (a
    /// third site for the bound, `other` a second()): the least (squared distance, index)
    /// among them, as second().
    int third(XY p, const Near& first, int other) const noexcept {
        XY other_foot;
        dist2_to(p, m_sites[other].a, m_sites[other].b, &other_foot);
        int best = -1;
        double best2 = INFINITY;
        const double apart2 = (100 * m_tol) * (100 * m_tol);
        double limit = INFINITY;  // beyond(best2)
        scan(p, limit, [&](int k) {
            if (k == first.site || k == other) return;
            XY f;
            const double d2 = dist2_to(p, m_sites[k].a, m_sites[k].b, &f);
            if ((d2 < best2 || (d2 == best2 && k < best)) && geo::norm2(f - first.foot) > apart2 && geo::norm2(f - other_foot) > apart2)
                best2 = d2, best = k, limit = beyond(best2);
        });
        return best;
    }

    double dist_to_site(XY p, int k) const noexcept { return std::sqrt(dist2_to(p, m_sites[k].a, m_sites[k].b, nullptr)); }

    /// Exact max over polygon `v` (or segment, 2 points) of min(dist to site i, dist to site j);
    /// `at` (if given): a point of `v` where it is reached.
    double two_site_bound(std::span<const XY> v, int i, int j, XY* at = nullptr) const {
        double best = 0;
        XY best_at = v[0];
        const Site* s[2] = {&m_sites[i], &m_sites[j]};
        // Each site's direction, squared length and its inverse length, once (the same values
        // as computed where they are used).
        XY ab[2];
        double ll[2], inv[2];
        for (int w = 0; w < 2; ++w) {
            ab[w] = s[w]->b - s[w]->a;
            ll[w] = geo::norm2(ab[w]);
            inv[w] = ll[w] > 0 ? 1 / std::sqrt(ll[w]) : 0.0;
        }
        // The lesser distance: the square root of the lesser square (the same number).
        auto consider = [&](XY p) {
            const double f = std::sqrt(std::min(dist2_to(p, s[0]->a, s[0]->b, nullptr), dist2_to(p, s[1]->a, s[1]->b, nullptr)));
            if (f > best) best = f, best_at = p;
        };
        // The vertices, and each one's squared distances to the two sites (for up to 64).
        constexpr std::size_t kept = 64;
        double v2[2][kept];
        for (std::size_t k = 0; k < v.size(); ++k) {
            const double a2 = dist2_to(v[k], s[0]->a, s[0]->b, nullptr), b2 = dist2_to(v[k], s[1]->a, s[1]->b, nullptr);
            if (k < kept) v2[0][k] = a2, v2[1][k] = b2;
            const double f = std::sqrt(std::min(a2, b2));
            if (f > best) best = f, best_at = v[k];
        }
        const std::size_t edges = v.size() == 2 ? 1 : v.size();
        for (std::size_t e = 0; e < edges; ++e) {
            const std::size_t e1 = e + 1 < v.size() ? e + 1 : 0;
            if (e1 < kept && e < kept) {
                // A distance to a segment is convex along a line: on this edge each is at most
                // its greater value at the ends, so the lesser of the two is at most the lesser
                // of those; an edge that cannot beat the best (by more than rounding) is passed.
                const double ub2 = std::min(std::max(v2[0][e], v2[0][e1]), std::max(v2[1][e], v2[1][e1]));
                if (std::sqrt(ub2) * (1 + 1e-12) <= best) continue;
            }
            const XY p = v[e], d = v[e1] - p;
            double breaks[6] = {0, 1};
            int nb = 2;
            // Per site along this edge: u(t) = ((p - a) + t d) . ab / |ab|^2, linear in t; and
            // the signed distance to its line, (alpha + beta t).
            double alpha[2], beta[2];
            for (int w = 0; w < 2; ++w) {
                alpha[w] = beta[w] = 0;
                if (ll[w] == 0) continue;
                const double u0 = geo::dot(p - s[w]->a, ab[w]) / ll[w], du = geo::dot(d, ab[w]) / ll[w];
                if (du != 0)
                    for (double target : {0.0, 1.0}) {
                        const double t = (target - u0) / du;
                        if (t > 0 && t < 1 && nb < 6) breaks[nb++] = t;
                    }
                alpha[w] = geo::cross(ab[w], p - s[w]->a) * inv[w], beta[w] = geo::cross(ab[w], d) * inv[w];
            }
            for (int a = 1; a < nb; ++a)  // insertion sort (std::sort on 6 doubles trips GCC 12's -Warray-bounds)
                for (int b = a; b > 0 && breaks[b - 1] > breaks[b]; --b) std::swap(breaks[b - 1], breaks[b]);
            const double dd = geo::norm2(d);
            for (int k = 0; k + 1 < nb; ++k) {
                const double t0 = breaks[k], t1 = breaks[k + 1];
                if (!(t1 > t0)) continue;
                const double tm = (t0 + t1) / 2;
                // Each squared distance as A t^2 + B t + C on [t0, t1].
                double A = 0, B = 0, C = 0;
                for (int w = 0; w < 2; ++w) {
                    const double um = ll[w] > 0 ? geo::dot(p + tm * d - s[w]->a, ab[w]) / ll[w] : 0.0;
                    double a2, b1, c0;
                    if (ll[w] == 0 || um <= 0 || um >= 1) {
                        const XY e0 = p - (ll[w] == 0 || um <= 0 ? s[w]->a : s[w]->b);
                        a2 = dd, b1 = 2 * geo::dot(e0, d), c0 = geo::norm2(e0);
                    } else {
                        a2 = beta[w] * beta[w], b1 = 2 * alpha[w] * beta[w], c0 = alpha[w] * alpha[w];
                    }
                    if (w == 0) A += a2, B += b1, C += c0;
                    else A -= a2, B -= b1, C -= c0;
                }
                double roots[2];
                int nr = 0;
                const double scale = std::fabs(A) + std::fabs(B) + std::fabs(C);
                if (std::fabs(A) > 1e-14 * scale) {
                    const double disc = B * B - 4 * A * C;
                    if (disc >= 0) {
                        const double sq = std::sqrt(disc);
                        const double q = -0.5 * (B + (B >= 0 ? sq : -sq));
                        roots[nr++] = q / A;
                        if (q != 0) roots[nr++] = C / q;
                    }
                } else if (std::fabs(B) > 1e-14 * scale) {
                    roots[nr++] = -C / B;
                }
                for (int r = 0; r < nr; ++r)
                    if (roots[r] >= t0 && roots[r] <= t1) consider(p + roots[r] * d);
            }
        }
        if (at) *at = best_at;
        return best;
    }

    /// Signed distance: > 0 inside the hazards.
    double signed_d(XY p, Near* n) const {
        *n = nearest(p);
        return inside(p, *n) ? n->d : -n->d;
    }

    /// Whether p is in the hazards, from its nearest boundary piece when that piece's nearest
    /// point is inside it (p lies on the piece's land side, the left, or not), within the
    /// reach; else from the obstacle (a winding number of the grid).
    bool inside(XY p, const Near& n) const {
        if (n.site >= 0 && n.d > 0 && n.d < m_reach) {
            const Site& st = m_sites[n.site];
            const XY ab = st.b - st.a;
            const double ll = geo::norm2(ab), t = geo::dot(p - st.a, ab) / ll;
            const double margin = 1e-9;
            if (t > margin && t < 1 - margin) return geo::orient(st.a, st.b, p) > 0;
        }
        return m_obstacle.inside(p);
    }
    bool inside(XY p) const { return inside(p, nearest(p)); }
    void set_reach(double r) noexcept { m_reach = r; }

    const std::vector<Site>& sites() const noexcept { return m_sites; }
    /// Each site's box (min and max of its ends).
    const std::vector<Box>& boxes() const noexcept { return m_boxes; }

    /// Upper bound of d over polygon `v` around `c` (a point of it, with its nearest `n` and
    /// signed distance `sd`; `r` the farthest vertex from c).
    double bound(const std::vector<XY>& v, const Near& n, int second_site, double sd, double r) const {
        double b = sd + r;
        if (n.site < 0) return b;
        // (The root of the greatest square: the same number as the greatest root.)
        double single2 = 0;
        for (XY p : v) single2 = std::max(single2, dist2_to(p, m_sites[n.site].a, m_sites[n.site].b, nullptr));
        b = std::min(b, std::sqrt(single2));
        if (second_site >= 0) b = std::min(b, two_site_bound(v, n.site, second_site));
        return b;
    }

    double tol() const noexcept { return m_tol; }

private:
    /// Calls `f(k)` for every site k whose box's squared distance to p is at most `limit`
    /// (which f may lower as it goes), in index order or, with many sites, in the order of
    /// their boxes' least x. The scans' answer is the least (squared distance, index) of the
    /// sites f considers, whatever the order; a site is skipped only when its box is beyond
    /// the limit of that moment, which only falls, as in the scan in index order. The window:
    /// before it, every box's greatest x (so far in this order) is left of p by more than the
    /// limit allows, so each box's x gap alone exceeds it (p.x - maxx, rounded, is no less
    /// than p.x - max_maxx, and the box distance adds a square to it); from its end on, every
    /// box's least x is right of p by more than that.
    template <class F>
    void scan(XY p, const double& limit, F&& f) const {
        const int count = static_cast<int>(m_sites.size());
        if (m_by_x.empty()) {
            for (int k = 0; k < count; ++k)
                if (box_dist2(p, k) <= limit) f(k);
            return;
        }
        const auto first = std::partition_point(m_by_x.begin(), m_by_x.end(), [&](const ByX& b) {
            const double gap = p.x - b.max_maxx;
            return gap > 0 && gap * gap > limit;
        });
        for (auto it = first; it != m_by_x.end(); ++it) {
            const double gap = it->minx - p.x;
            if (gap > 0 && gap * gap > limit) break;
            if (box_dist2(p, it->site) <= limit) f(it->site);
        }
    }

    /// The squared distance from p to site k's box: no more than its squared distance to the
    /// site, but for rounding.
    double box_dist2(XY p, int k) const noexcept {
        const Box& b = m_boxes[k];
        const double dx = std::max(std::max(b.minx - p.x, p.x - b.maxx), 0.0), dy = std::max(std::max(b.miny - p.y, p.y - b.maxy), 0.0);
        return dx * dx + dy * dy;
    }
    /// A squared box distance above which a site's squared distance exceeds best2 even after
    /// rounding (a margin of a millionth and (100 tol)^2, far above it): it is not looked at.
    double beyond(double best2) const noexcept { return best2 * (1 + 1e-6) + m_slack2; }

    const std::vector<Site>& m_sites;
    std::vector<Box>& m_boxes;  // each site's
    std::vector<ByX>& m_by_x;   // the sites by their boxes' least x (empty: fewer than sorted_from)
    const Obstacle& m_obstacle;
    double m_tol;
    double m_slack2;
    double m_reach = 0;
    mutable int m_hint = -1, m_second_hint = -1;  // the last answers of nearest() and second()
};

struct Best {
    double d = -INFINITY;
    XY point, foot;
    int site = -1;
};

/// A piece of the overlap's boundary: of the hull outline (edge, params) or of a site.
struct Piece {
    XY a, b;
    bool outline = false;
};

struct Interval {
    double t0, t1, f0, f1;
    Search::Near n0, n1;
};

/// Branch and bound of d along segment pa-pb (an outline piece inside the hazards); `stack`
/// is storage kept between calls. Ends as soon as `best` reaches `stop` (the attempt is then
/// done again with a longer reach, whatever else is found).
void along(const Search& s, XY pa, XY pb, Best& best, std::vector<Interval>& stack, double stop, bool ridge_candidates) {
    const XY d = pb - pa;
    const double len = std::sqrt(geo::norm2(d));
    auto eval = [&](double t, Search::Near& n) {
        const XY p = pa + t * d;
        n = s.nearest(p);
        const double f = n.d;  // the piece lies in the hazards: d >= 0
        if (f > best.d) best = {f, p, n.foot, n.site};
        return f;
    };
    Interval root{0, 1, 0, 0, {}, {}};
    root.f0 = eval(0, root.n0);
    root.f1 = eval(1, root.n1);
    stack.assign(1, root);
    int steps = 0;
    while (!stack.empty() && ++steps < 100000 && !(best.d >= stop)) {
        const Interval iv = stack.back();
        stack.pop_back();
        const double h = (iv.t1 - iv.t0) * len;
        if (h <= s.tol()) continue;
        const double tm = (iv.t0 + iv.t1) / 2;
        Search::Near nm;
        const double fm = eval(tm, nm);
        for (int side = 0; side < 2; ++side) {
            const double a = side == 0 ? iv.t0 : tm, b = side == 0 ? tm : iv.t1;
            const double fa = side == 0 ? iv.f0 : fm, fb = side == 0 ? fm : iv.f1;
            const Search::Near& na = side == 0 ? iv.n0 : nm;
            const Search::Near& nb = side == 0 ? nm : iv.n1;
            const XY qa = pa + a * d, qb = pa + b * d;
            double bnd = (fa + fb + (b - a) * len) / 2;  // Lipschitz tent
            for (const Search::Near* n : {&na, &nb})
                if (n->site >= 0) bnd = std::min(bnd, std::max(s.dist_to_site(qa, n->site), s.dist_to_site(qb, n->site)));
            // (The two-site bound only when the others do not already cut the interval off.)
            if (bnd > best.d + s.tol() && na.site >= 0 && nb.site >= 0 && na.site != nb.site) {
                // The two-site bound's maximum is a candidate itself: on the ridge between the
                // two sites, where the deepest point of a pier across the hull lies; when no
                // other site is nearer there, it meets the bound and the interval is done.
                XY at;
                const double two = s.two_site_bound(std::array<XY, 2>{qa, qb}, na.site, nb.site, &at);
                if (two < bnd) {
                    bnd = two;
                    if (ridge_candidates) {
                        const double lenq = geo::norm2(qb - qa);
                        const double tq = lenq > 0 ? std::clamp(a + (b - a) * geo::dot(at - qa, qb - qa) / lenq, a, b) : a;
                        Search::Near nq;
                        eval(tq, nq);
                    }
                }
            }
            if (bnd > best.d + s.tol()) stack.push_back({a, b, fa, fb, na, nb});
        }
    }
}

}  // namespace

}  // namespace shoal::check
