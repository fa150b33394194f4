#include <shoal/check/detector.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <cmath>
#include <numbers>
#include <span>

#include "util/parallel.hpp"
#include "grid/outward.hpp"

#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
#include <emmintrin.h>
#endif

namespace shoal::check {

using geo::XY;
using grid::visit_chunks;

namespace {
/// Columns: the ship's forward and starboard unit vectors in (east, north) metres. (The
/// audit's audit::ship_to_en rounds the heading's radians otherwise; each keeps its own.)
Eigen::Matrix2d ship_to_en(double heading_deg) {
    // Any finite heading, normalised to [0, 360) as `shoal probe` reads it (io/pose_csv.cpp):
    // the same pose whoever asks (C API, Python, probe). Unnormalised, a heading of 5.72e307 or
    // more overflowed to infinity in the product below and every sine was NaN: "no contact".
    if (!(heading_deg >= 0.0 && heading_deg < 360.0)) {
        heading_deg = std::fmod(heading_deg, 360.0);
        if (heading_deg < 0) heading_deg += 360.0;
    }
    const double h = heading_deg * std::numbers::pi / 180.0;
    Eigen::Matrix2d m;
    m << std::sin(h), std::cos(h), std::cos(h), -std::sin(h);
    return m;
}
}  // namespace

LocalPose place(const geo::LocalFrame& frame, const Pose& pose) {
    return {frame.forward(pose.position), frame.jacobian(pose.position) * ship_to_en(pose.heading_deg)};
}

namespace {
LocalPose place_at(const geo::LocalFrame& frame, const geo::JacobianField& field, XY p, const Pose& pose) {
    const Eigen::Matrix2d j = field.covers(p) ? field.at(p) : frame.jacobian(pose.position);
    return {p, j * ship_to_en(pose.heading_deg)};
}
}  // namespace

LocalPose place(const geo::LocalFrame& frame, const geo::JacobianField& field, const Pose& pose) {
    return place_at(frame, field, frame.forward(pose.position), pose);
}

std::vector<LocalPose> place(const geo::LocalFrame& frame, const geo::JacobianField& field, std::span<const Pose> poses) {
    std::vector<double> xs(poses.size()), ys(poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) {
        xs[k] = poses[k].position.lon;
        ys[k] = poses[k].position.lat;
    }
    std::size_t bad = 0;
    std::vector<LocalPose> out(poses.size());
    if (!frame.forward(xs, ys, &bad)) {
        // Pose by pose, as one by one: the first that fails throws its own message.
        for (std::size_t k = 0; k < poses.size(); ++k) out[k] = place(frame, field, poses[k]);
        return out;
    }
    for (std::size_t k = 0; k < poses.size(); ++k) out[k] = place_at(frame, field, {xs[k], ys[k]}, poses[k]);
    return out;
}

void place_in_blocks(const geo::LocalFrame& frame, const geo::JacobianField& field, std::size_t n,
                     const std::function<Pose(std::size_t)>& pose_of, unsigned jobs,
                     const std::function<void(std::size_t from, std::span<const LocalPose> placed, unsigned worker)>& use) {
    constexpr std::size_t block = placement_block;
    const std::size_t blocks = (n + block - 1) / block;
    // The first block (in input order) that failed, and what it threw: the blocks after it
    // are not started, those before it still are (one of them may fail first).
    std::atomic<std::size_t> first_failed{blocks};
    std::vector<std::exception_ptr> failures(blocks);
    detail::parallel_for(blocks, detail::thread_count(jobs), [&](std::size_t b, unsigned worker) {
        if (b > first_failed.load()) return;
        try {
            const std::size_t from = b * block, to = std::min(n, from + block);
            std::vector<Pose> todo;
            todo.reserve(to - from);
            for (std::size_t k = from; k < to; ++k) todo.push_back(pose_of(k));
            const std::vector<LocalPose> placed = place(frame, field, todo);
            use(from, placed, worker);
        } catch (...) {
            failures[b] = std::current_exception();
            for (std::size_t seen = first_failed.load(); b < seen && !first_failed.compare_exchange_weak(seen, b);) {
            }
        }
    });
    if (first_failed.load() < blocks) std::rethrow_exception(failures[first_failed.load()]);
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

// How a check stays near a microsecond (docs/performance.md has the figures):
// - every pruning test compares squared distances of boxes (no square roots);
// - the search starts with the clearance limit as its bound, so segments beyond the margin
//   are dropped by the first box test; the ring search reads only the cells of each ring
//   within the clearance found so far (or the limit);
// - a segment is first tested in local metres, on its stored coordinates, against the hull's
//   box grown by that bound; only the survivors are rotated into the ship-aligned frame and
//   tested against the tighter aligned box, then against boxes of chunks of hull edges and
//   of single edges, before any exact distance;
// - hull edges, their boxes and 1/|d|^2 are built only when a segment comes near;
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
geo::Box local_hull_box(const XY* c, std::size_t n, const Eigen::Matrix2d& m, XY origin) noexcept {
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
    // Per edge e (pts[e] -> pts[e + 1]), built on demand: direction, 1 / |d|^2, box.
    std::vector<XY> dir;
    std::vector<double> inv_len2;
    std::vector<geo::Box> edge_box;
    std::vector<geo::Box> chunk_box;
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

    /// Edges and chunk boxes: built on the first segment that comes near (open-water poses
    /// never need them).
    void ensure_edges() {
        if (edges_ready) return;
        edges_ready = true;
        dir.resize(n);
        inv_len2.resize(n);
        edge_box.resize(n);
        chunk_box.resize((n + chunk_edges - 1) / chunk_edges);
        for (std::size_t e = 0; e < n; ++e) {
            const V2 a = load(pts[e]), b = load(pts[e + 1]);
            store(dir[e], b - a);
            store_box(edge_box[e], vmin(a, b), vmax(a, b));
        }
        // 1 / |d|^2 (0 for a degenerate edge), two edges per division.
        std::size_t e = 0;
        for (; e + 1 < n; e += 2) {
            const V2 d0 = load(dir[e]), d1 = load(dir[e + 1]);
            const V2 s0 = d0 * d0, s1 = d1 * d1;
            store2(&inv_len2[e], recip_or_zero(lows(s0, s1) + highs(s0, s1)));
        }
        for (; e < n; ++e) {
            const double len2 = geo::norm2(dir[e]);
            inv_len2[e] = len2 > 0 ? 1.0 / len2 : 0.0;
        }
        for (std::size_t c = 0; c < chunk_box.size(); ++c) {
            V2 cmin = splat(INFINITY), cmax = splat(-INFINITY);
            for (std::size_t k = c * chunk_edges, k_end = std::min(n, k + chunk_edges); k < k_end; ++k) {
                cmin = vmin(load_min(edge_box[k]), cmin);
                cmax = vmax(load_max(edge_box[k]), cmax);
            }
            store_box(chunk_box[c], cmin, cmax);
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

Scratch& scratch() {
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
                double most = INFINITY;
                bool on_land = false;
                for (std::size_t k = 0; k < n_known; ++k) {
                    const double gap = std::sqrt(geo::norm2(p - known[k].p)) * (1 + 1e-9) + 1e-9;
                    on_land = on_land || gap < known[k].d * (1 - 1e-9);
                    most = std::min(most, std::sqrt(geo::norm2(p - known[k].coast)) * (1 + 1e-9) + 1e-9);
                }
                if (most <= depth) continue;
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
