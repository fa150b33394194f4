#pragma once
// The hull at one pose in a frame aligned with the ship, and the two-lane arithmetic (SSE2 where
// there is one) that Detector::check's hot loops run on: private to src/check (detector.cpp).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include <shoal/check/placement.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/hull/hull.hpp>

#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
#include <emmintrin.h>
#endif

namespace shoal::check::hull_lanes {

using geo::XY;

// How a check stays near a microsecond (docs/performance.md has the figures):
// - every pruning test compares squared distances of boxes (no square roots);
// - the search starts with the clearance limit as its bound, so segments beyond the margin
//   are dropped by the first box test; the ring search reads only the cells of each ring
//   within the clearance found so far (or the limit);
// - a segment is first tested in local metres, on its stored coordinates, against the hull's
//   box grown by that bound; only the survivors are rotated into the ship-aligned frame and
//   tested against the tighter aligned box, then against boxes of chunks of hull edges and
//   of single edges, before any exact distance;
// - hull edges, their boxes and 1/|d|^2 are made only when a segment comes near their chunk;
// - each hull vertex is measured once per segment, not once per edge.

/// Edges are grouped in chunks of this many consecutive edges, each with its box in the
/// ship-aligned frame, so a coast segment is tested against few hull edges.
constexpr std::size_t chunk_edges = 6;

// The hot loops hold a point's x and y, or a box's minima and maxima, in the two lanes of a
// V2: an SSE2 register where there is one (every x86-64 CPU), else a pair of doubles. Each
// lane does the same IEEE operations as the scalar expressions in the comments (no fused
// multiply-add), so the results are the same numbers either way.
static_assert(sizeof(XY) == 2 * sizeof(double) && sizeof(geo::Box) == 4 * sizeof(double));

#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
struct V2 {
    __m128d v;
};
inline V2 v2(double lo, double hi) noexcept { return {_mm_set_pd(hi, lo)}; }
inline V2 splat(double a) noexcept { return {_mm_set1_pd(a)}; }
inline V2 load2(const double* p) noexcept { return {_mm_loadu_pd(p)}; }
inline void store2(double* p, V2 a) noexcept { _mm_storeu_pd(p, a.v); }
inline V2 operator+(V2 a, V2 b) noexcept { return {_mm_add_pd(a.v, b.v)}; }
inline V2 operator-(V2 a, V2 b) noexcept { return {_mm_sub_pd(a.v, b.v)}; }
inline V2 operator*(V2 a, V2 b) noexcept { return {_mm_mul_pd(a.v, b.v)}; }
inline V2 vmin(V2 a, V2 b) noexcept { return {_mm_min_pd(a.v, b.v)}; }  // a < b ? a : b, per lane
inline V2 vmax(V2 a, V2 b) noexcept { return {_mm_max_pd(a.v, b.v)}; }  // a > b ? a : b, per lane
inline V2 low_both(V2 a) noexcept { return {_mm_unpacklo_pd(a.v, a.v)}; }
inline V2 high_both(V2 a) noexcept { return {_mm_unpackhi_pd(a.v, a.v)}; }
inline V2 lows(V2 a, V2 b) noexcept { return {_mm_unpacklo_pd(a.v, b.v)}; }    // (a.lo, b.lo)
inline V2 highs(V2 a, V2 b) noexcept { return {_mm_unpackhi_pd(a.v, b.v)}; }   // (a.hi, b.hi)
inline double sum(V2 a) noexcept { return _mm_cvtsd_f64(_mm_add_sd(a.v, _mm_unpackhi_pd(a.v, a.v))); }  // lo + hi
/// True when a > b or c < d in either lane.
inline bool any_gt_or_lt(V2 a, V2 b, V2 c, V2 d) noexcept {
    return _mm_movemask_pd(_mm_or_pd(_mm_cmpgt_pd(a.v, b.v), _mm_cmplt_pd(c.v, d.v))) != 0;
}
/// 1 / a where a > 0, else 0, per lane.
inline V2 recip_or_zero(V2 a) noexcept {
    return {_mm_and_pd(_mm_cmpgt_pd(a.v, _mm_setzero_pd()), _mm_div_pd(_mm_set1_pd(1.0), a.v))};
}
#else
struct V2 {
    double lo, hi;
};
inline V2 v2(double lo, double hi) noexcept { return {lo, hi}; }
inline V2 splat(double a) noexcept { return {a, a}; }
inline V2 load2(const double* p) noexcept { return {p[0], p[1]}; }
inline void store2(double* p, V2 a) noexcept { p[0] = a.lo, p[1] = a.hi; }
inline V2 operator+(V2 a, V2 b) noexcept { return {a.lo + b.lo, a.hi + b.hi}; }
inline V2 operator-(V2 a, V2 b) noexcept { return {a.lo - b.lo, a.hi - b.hi}; }
inline V2 operator*(V2 a, V2 b) noexcept { return {a.lo * b.lo, a.hi * b.hi}; }
inline V2 vmin(V2 a, V2 b) noexcept { return {a.lo < b.lo ? a.lo : b.lo, a.hi < b.hi ? a.hi : b.hi}; }
inline V2 vmax(V2 a, V2 b) noexcept { return {a.lo > b.lo ? a.lo : b.lo, a.hi > b.hi ? a.hi : b.hi}; }
inline V2 low_both(V2 a) noexcept { return {a.lo, a.lo}; }
inline V2 high_both(V2 a) noexcept { return {a.hi, a.hi}; }
inline V2 lows(V2 a, V2 b) noexcept { return {a.lo, b.lo}; }
inline V2 highs(V2 a, V2 b) noexcept { return {a.hi, b.hi}; }
inline double sum(V2 a) noexcept { return a.lo + a.hi; }
inline bool any_gt_or_lt(V2 a, V2 b, V2 c, V2 d) noexcept { return a.lo > b.lo || a.hi > b.hi || c.lo < d.lo || c.hi < d.hi; }
inline V2 recip_or_zero(V2 a) noexcept { return {a.lo > 0 ? 1.0 / a.lo : 0.0, a.hi > 0 ? 1.0 / a.hi : 0.0}; }
#endif

inline V2 load(const XY& p) noexcept { return load2(&p.x); }
inline void store(XY& p, V2 a) noexcept { store2(&p.x, a); }
inline V2 load_min(const geo::Box& b) noexcept { return load2(&b.minx); }  // (minx, miny)
inline V2 load_max(const geo::Box& b) noexcept { return load2(&b.maxx); }  // (maxx, maxy)
inline void store_box(geo::Box& b, V2 lo, V2 hi) noexcept {
    store2(&b.minx, lo);
    store2(&b.maxx, hi);
}

/// Squared distance between two boxes given by their corners (0 when they overlap or touch):
/// dx = max(q.minx - p.maxx, p.minx - q.maxx, 0), likewise dy; dx^2 + dy^2. Squared, so that
/// the pruning tests, run for every segment read, need no square root.
inline double box_dist2(V2 pmin, V2 pmax, V2 qmin, V2 qmax) noexcept {
    const V2 d = vmax(vmax(qmin - pmax, pmin - qmax), splat(0.0));
    return sum(d * d);
}
inline double box_dist2(const geo::Box& p, const geo::Box& q) noexcept {
    return box_dist2(load_min(p), load_max(p), load_min(q), load_max(q));
}

/// Squared distance from p to the segment from `a` along `d`, given 1 / |d|^2 (0 for a
/// degenerate segment); writes the closest point.
inline double point_segment_d2(XY p, XY a, XY d, double inv_len2, XY* foot) noexcept {
    const double t = std::clamp(geo::dot(p - a, d) * inv_len2, 0.0, 1.0);
    *foot = a + t * d;
    return geo::norm2(p - *foot);
}

/// The box in local metres of the hull `c` (n points of the contour) placed by `m` at `origin`
/// (AlignedHull::local_box, Detector::covers).
inline geo::Box local_hull_box(const XY* c, std::size_t n, const Eigen::Matrix2d& m, XY origin) noexcept {
    const V2 mcol0 = v2(m(0, 0), m(1, 0)), mcol1 = v2(m(0, 1), m(1, 1));
    V2 lmin = splat(INFINITY), lmax = splat(-INFINITY);
    for (std::size_t i = 0; i < n; ++i) {
        const V2 w = mcol0 * splat(c[i].x) + mcol1 * splat(c[i].y);
        lmin = vmin(w, lmin);
        lmax = vmax(w, lmax);
    }
    geo::Box b;
    const V2 o = load(origin);
    store_box(b, o + lmin, o + lmax);
    return b;
}

/// The hull at one pose, in a frame aligned with the ship (origin at the reference point,
/// first axis along the ship's centreline). Rotation only: distances are metres.
struct AlignedHull {
    XY origin;
    XY u, v;  // unit axes in local metres
    std::size_t n = 0;
    std::vector<XY> pts;  // n + 1 points: the outline, first point repeated at the end
    // Per edge e (pts[e] -> pts[e + 1]), made on demand by chunks: direction, 1 / |d|^2, box.
    std::vector<XY> dir;
    std::vector<double> inv_len2;
    std::vector<geo::Box> edge_box;
    std::vector<geo::Box> chunk_box;
    std::vector<unsigned char> chunk_ready;  // per chunk: its edges made (ensure_chunk)
    bool edges_ready = false;
    geo::Box box;        // aligned frame
    geo::Box local_box;  // local metres

    XY pt(std::size_t i) const noexcept { return pts[i]; }
    XY to_aligned(XY p) const noexcept {
        const XY d = p - origin;
        return {geo::dot(d, u), geo::dot(d, v)};
    }
    XY to_local(XY q) const noexcept { return origin + q.x * u + q.y * v; }

    void build(const hull::Hull& hull, const LocalPose& pose) {
        origin = pose.position;
        const Eigen::Matrix2d& m = pose.ship_to_local;
        const double m00 = m(0, 0), m01 = m(0, 1), m10 = m(1, 0), m11 = m(1, 1);
        const double len = std::sqrt(m00 * m00 + m10 * m10);
        u = {m00 / len, m10 / len};
        v = {-u.y, u.x};
        // Ship -> aligned: [u v]^T * m.
        const double a00 = u.x * m00 + u.y * m10, a01 = u.x * m01 + u.y * m11;
        const double a10 = v.x * m00 + v.y * m10, a11 = v.x * m01 + v.y * m11;
        const XY* c = hull.contour().data();
        n = hull.contour().size();
        pts.resize(n + 1);
        // p = (a00 cx + a01 cy, a10 cx + a11 cy).
        const V2 col0 = v2(a00, a10), col1 = v2(a01, a11);
        V2 bmin = splat(INFINITY), bmax = splat(-INFINITY);
        for (std::size_t i = 0; i < n; ++i) {
            const V2 p = col0 * splat(c[i].x) + col1 * splat(c[i].y);
            store(pts[i], p);
            bmin = vmin(p, bmin);
            bmax = vmax(p, bmax);
        }
        pts[n] = pts[0];
        store_box(box, bmin, bmax);
        local_box = local_hull_box(c, n, m, origin);
        edges_ready = false;
    }

    /// The chunks' boxes: made on the first segment that comes near (open-water poses never
    /// need them), from the points (a chunk's box is its edges' boxes' box). Each chunk's
    /// edges are made when a segment first comes near that chunk (ensure_chunk).
    void ensure_edges() {
        if (edges_ready) return;
        edges_ready = true;
        dir.resize(n);
        inv_len2.resize(n);
        edge_box.resize(n);
        const std::size_t n_chunks = (n + chunk_edges - 1) / chunk_edges;
        chunk_box.resize(n_chunks);
        chunk_ready.assign(n_chunks, 0);
        for (std::size_t c = 0; c < n_chunks; ++c) {
            V2 cmin = splat(INFINITY), cmax = splat(-INFINITY);
            for (std::size_t k = c * chunk_edges, k_end = std::min(n, k + chunk_edges); k <= k_end; ++k) {
                const V2 p = load(pts[k]);
                cmin = vmin(p, cmin);
                cmax = vmax(p, cmax);
            }
            store_box(chunk_box[c], cmin, cmax);
        }
    }

    /// Chunk c's edges: direction, box and 1 / |d|^2 (0 for a degenerate edge), two edges
    /// per division. After ensure_edges().
    void ensure_chunk(std::size_t c) {
        if (chunk_ready[c]) return;
        chunk_ready[c] = 1;
        const std::size_t e0 = c * chunk_edges, e_end = std::min(n, e0 + chunk_edges);
        for (std::size_t e = e0; e < e_end; ++e) {
            const V2 a = load(pts[e]), b = load(pts[e + 1]);
            store(dir[e], b - a);
            store_box(edge_box[e], vmin(a, b), vmax(a, b));
        }
        std::size_t e = e0;
        for (; e + 1 < e_end; e += 2) {
            const V2 d0 = load(dir[e]), d1 = load(dir[e + 1]);
            const V2 s0 = d0 * d0, s1 = d1 * d1;
            store2(&inv_len2[e], recip_or_zero(lows(s0, s1) + highs(s0, s1)));
        }
        for (; e < e_end; ++e) {
            const double len2 = geo::norm2(dir[e]);
            inv_len2[e] = len2 > 0 ? 1.0 / len2 : 0.0;
        }
    }

    bool in_box(XY q) const noexcept { return q.x >= box.minx && q.x <= box.maxx && q.y >= box.miny && q.y <= box.maxy; }

    /// Crossing-number point-in-polygon in the aligned frame (boundary counts as inside).
    bool contains(XY q) const noexcept {
        bool inside = false;
        for (std::size_t i = 0; i < n; ++i) {
            const XY a = pts[i], b = pts[i + 1];
            if ((a.y > q.y) != (b.y > q.y)) {
                const double o = geo::orient(a, b, q);
                if (o == 0) return true;
                if ((o > 0) == (b.y > a.y)) inside = !inside;
            } else if ((a.y == q.y || b.y == q.y) && geo::point_segment_dist2(q, a, b) == 0) {
                return true;  // on an edge that does not straddle q's row: only at its height
            }
        }
        return inside;
    }
};

}  // namespace shoal::check::hull_lanes
