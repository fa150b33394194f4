#include <shoal/grid/coast_grid.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
#include <emmintrin.h>
#endif

#include "util/parse_util.hpp"
#include "grid/outward.hpp"
#include <shoal/util/error.hpp>

namespace shoal::grid {

std::string fingerprint_hex(std::uint64_t fingerprint) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(fingerprint));
    return buf;
}

using geo::XY;

const char* to_string(CellState s) noexcept {
    switch (s) {
    case CellState::water: return "water";
    case CellState::land: return "land";
    case CellState::coast: return "coast";
    case CellState::outside: return "outside";
    }
    return "?";
}

CellState CoastGrid::state(int i, int j) const noexcept {
    if (!valid_cell(i, j)) return CellState::outside;
    const std::uint32_t s = slot(i, j);
    return s == water_slot ? CellState::water : s == land_slot ? CellState::land : CellState::coast;
}

std::span<const Segment> CoastGrid::segments(int i, int j) const noexcept {
    if (!valid_cell(i, j)) return {};
    const std::uint32_t s = slot(i, j);
    if (s >= land_slot) return {};
    return {m_segments.data() + m_seg_offset[s], m_seg_offset[s + 1] - m_seg_offset[s]};
}

bool CoastGrid::segment_is_boundary(int i, int j, std::size_t k) const noexcept {
    const std::uint32_t s = slot(i, j);
    return (m_seg_info[m_seg_offset[s] + k] & boundary_bit) != 0;
}

XY CoastGrid::reference_point(int i, int j) const noexcept {
    return {m_x0 + (i + m_ref_fx) * m_cell, m_y0 + (j + m_ref_fy) * m_cell};
}

std::size_t CoastGrid::land_cell_count() const noexcept {
    return static_cast<std::size_t>(std::count(m_slot.begin(), m_slot.end(), land_slot));
}

std::size_t CoastGrid::memory_bytes() const noexcept {
    return m_slot.size() * sizeof(std::uint32_t) + m_seg_offset.size() * sizeof(std::uint32_t) +
           m_ref_winding.size() * sizeof(std::int32_t) + m_segments.size() * sizeof(Segment) +
           m_seg_info.size() * sizeof(std::uint32_t) + m_hazards.size() * sizeof(coast::Hazard) +
           (m_chunk_box.size() + m_block_box.size()) * sizeof(geo::Box) + m_level_depth.size() * sizeof(double) +
           m_lw_offset.size() * sizeof(std::uint32_t) + m_lw_level.size() * sizeof(std::uint16_t) +
           m_lw_winding.size() * sizeof(std::int32_t) + (m_land_level.size() + m_poly_level.size()) * sizeof(std::uint16_t);
}

// --- levels: one grid, each vessel's own limiting depth ---

struct CoastGrid::Levels {
    std::mutex mutex;
    std::map<std::size_t, std::unique_ptr<CoastGrid>> grids;  // by level; nodes stay put
};
namespace {
std::atomic<std::uint64_t> next_instance{1};
}  // namespace
CoastGrid::InstanceNumber::InstanceNumber() noexcept : number(next_instance.fetch_add(1, std::memory_order_relaxed)) {}
CoastGrid::InstanceNumber::InstanceNumber(const InstanceNumber&) noexcept : InstanceNumber() {}
CoastGrid::InstanceNumber& CoastGrid::InstanceNumber::operator=(const InstanceNumber&) noexcept {
    number = next_instance.fetch_add(1, std::memory_order_relaxed);
    return *this;
}

CoastGrid::LevelCache::LevelCache() : p(std::make_unique<Levels>()) {}
CoastGrid::LevelCache::LevelCache(const LevelCache&) : p(std::make_unique<Levels>()) {}
CoastGrid::LevelCache& CoastGrid::LevelCache::operator=(const LevelCache&) {
    p = std::make_unique<Levels>();
    return *this;
}
CoastGrid::LevelCache::LevelCache(LevelCache&&) noexcept = default;
CoastGrid::LevelCache& CoastGrid::LevelCache::operator=(LevelCache&&) noexcept = default;
CoastGrid::LevelCache::~LevelCache() = default;

namespace {
/// Depth keys compare with unknown (NaN) first, then ascending.
bool depth_before(double a, double b) { return std::isnan(a) ? !std::isnan(b) : !std::isnan(b) && a < b; }
}  // namespace

void CoastGrid::assign_levels() {
    m_level_depth.clear();
    for (const coast::Hazard& h : m_hazards)
        if (!coast::for_every_vessel(h.kind)) m_level_depth.push_back(h.depth_m);
    std::sort(m_level_depth.begin(), m_level_depth.end(), depth_before);
    m_level_depth.erase(std::unique(m_level_depth.begin(), m_level_depth.end(),
                                    [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }),
                        m_level_depth.end());
    if (m_level_depth.size() >= 0xFFFFu)
        throw UsageError("the depth areas and dangers have " + std::to_string(m_level_depth.size()) +
                         " distinct charted depths, more than 65534: round the depth field (ImportOptions::depth_field)");
    m_poly_level.clear();
    if (m_level_depth.empty()) return;
    m_poly_level.reserve(m_hazards.size());
    for (const coast::Hazard& h : m_hazards) {
        if (coast::for_every_vessel(h.kind)) {  // land and structures: level 0, for every vessel
            m_poly_level.push_back(0);
            continue;
        }
        const auto it = std::lower_bound(m_level_depth.begin(), m_level_depth.end(), h.depth_m, depth_before);
        m_poly_level.push_back(static_cast<std::uint16_t>(it - m_level_depth.begin() + 1));
    }
}

std::size_t CoastGrid::level_of(std::optional<double> limit_m) const noexcept {
    if (!limit_m) return 0;
    // Unknown depth is a hazard for any limit; a charted depth when it is under the limit.
    std::size_t n = 0;
    for (double d : m_level_depth)
        if (std::isnan(d) || d < *limit_m) ++n;
    return n;
}

std::int32_t CoastGrid::level_winding(std::uint32_t s, std::size_t level) const noexcept {
    std::int32_t w = 0;
    for (std::uint32_t k = m_lw_offset[s]; k < m_lw_offset[s + 1] && m_lw_level[k] <= level; ++k) w = m_lw_winding[k];
    return w;
}

const CoastGrid& CoastGrid::for_depth(std::optional<double> limit_m) const {
    const std::size_t level = level_of(limit_m);
    if (level >= m_level_depth.size()) return *this;  // every hazard held (or none held)
    Levels& cache = *m_levels.p;
    const std::lock_guard<std::mutex> lock(cache.mutex);
    std::unique_ptr<CoastGrid>& g = cache.grids[level];
    if (!g) g = std::make_unique<CoastGrid>(make_level(level));
    return *g;
}

CoastGrid CoastGrid::make_level(std::size_t level) const {
    CoastGrid v(m_frame);
    v.m_cell = m_cell;
    v.m_x0 = m_x0;
    v.m_y0 = m_y0;
    v.m_nx = m_nx;
    v.m_ny = m_ny;
    v.m_clip_slack = m_clip_slack;
    v.m_ref_fx = m_ref_fx;
    v.m_ref_fy = m_ref_fy;
    v.m_has_land_side = m_has_land_side;
    v.m_hazards = m_hazards;
    v.m_source = m_source;
    v.m_source.limiting_depth_m = NAN;
    v.m_slot.assign(m_slot.size(), water_slot);
    v.m_seg_offset.push_back(0);
    for (std::size_t c = 0; c < m_slot.size(); ++c) {
        const std::uint32_t s = m_slot[c];
        if (s == water_slot) continue;
        if (s == land_slot) {
            if (m_land_level[c] <= level) v.m_slot[c] = land_slot;
            continue;
        }
        const std::size_t before = v.m_segments.size();
        for (std::uint32_t k = m_seg_offset[s]; k < m_seg_offset[s + 1]; ++k)
            if (m_poly_level[m_seg_info[k] & ~boundary_bit] <= level) {
                v.m_segments.push_back(m_segments[k]);
                v.m_seg_info.push_back(m_seg_info[k]);
            }
        const std::int32_t w = level_winding(s, level);
        if (v.m_segments.size() > before) {
            v.m_slot[c] = static_cast<std::uint32_t>(v.m_ref_winding.size());
            v.m_ref_winding.push_back(w);
            v.m_seg_offset.push_back(static_cast<std::uint32_t>(v.m_segments.size()));
        } else if (w > 0) {
            v.m_slot[c] = land_slot;
        }
    }
    v.compute_chunk_boxes();
    return v;
}

bool CoastGrid::compute_chunk_boxes() {
    // A chunk's bounds in registers, stored once (the same numbers as extending its box by
    // each end: min and max are exact; two lanes, x and y, where SSE2 is there).
    const std::size_t n = m_segments.size(), chunks = (n + chunk_segments - 1) / chunk_segments;
    m_chunk_box.resize(chunks);
    // x - x is 0 for a finite x and NaN for an infinite or NaN one: their sum is 0 when every
    // coordinate is finite.
#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
    __m128d finite = _mm_setzero_pd();
#else
    double finite = 0;
#endif
    for (std::size_t c = 0; c < chunks; ++c) {
        const std::size_t from = c * chunk_segments, to = std::min(n, from + chunk_segments);
#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
        __m128d lo = _mm_set1_pd(INFINITY), hi = _mm_set1_pd(-INFINITY);
        for (std::size_t k = from; k < to; ++k) {
            const __m128d a = _mm_loadu_pd(&m_segments[k].a.x), b = _mm_loadu_pd(&m_segments[k].b.x);
            lo = _mm_min_pd(lo, _mm_min_pd(a, b)), hi = _mm_max_pd(hi, _mm_max_pd(a, b));
            finite = _mm_add_pd(finite, _mm_add_pd(_mm_sub_pd(a, a), _mm_sub_pd(b, b)));
        }
        double l[2], h[2];
        _mm_storeu_pd(l, lo), _mm_storeu_pd(h, hi);
        m_chunk_box[c] = {l[0], l[1], h[0], h[1]};
#else
        geo::Box box;
        for (std::size_t k = from; k < to; ++k) {
            const Segment& sg = m_segments[k];
            box.extend(sg.a), box.extend(sg.b);
            finite += (sg.a.x - sg.a.x) + (sg.a.y - sg.a.y) + (sg.b.x - sg.b.x) + (sg.b.y - sg.b.y);
        }
        m_chunk_box[c] = box;
#endif
    }
    static_assert(block_segments % chunk_segments == 0);
    m_block_box.assign((m_segments.size() + block_segments - 1) / block_segments, geo::Box{});
    for (std::size_t c = 0; c < m_chunk_box.size(); ++c)
        if (!m_chunk_box[c].empty()) m_block_box[c * chunk_segments / block_segments].extend(m_chunk_box[c]);
#if (defined(__SSE2__) || defined(_M_X64)) && !defined(SHOAL_NO_SSE2)
    double f[2];
    _mm_storeu_pd(f, finite);
    return f[0] == 0 && f[1] == 0;
#else
    return finite == 0;
#endif
}

namespace {

/// The nearest point of segment ab to p: squared distance, and where it lies (-1: at a,
/// 0: inside, 1: at b). At an end the distance is measured to the end itself, so the two
/// segments meeting there give the same number.
double nearest_on(XY p, XY a, XY b, int* where) {
    const XY ab = b - a;
    const double len2 = geo::norm2(ab);
    const double t = len2 > 0 ? geo::dot(p - a, ab) / len2 : 0.0;
    if (t <= 0) { *where = -1; return geo::norm2(p - a); }
    if (t >= 1) { *where = 1; return geo::norm2(p - b); }
    *where = 0;
    return geo::norm2(p - (a + t * ab));
}

/// The nearest point of one boundary ring to p, and the segments there.
struct RingNear {
    std::uint32_t polyline = 0;
    double d2 = INFINITY;
    int where = 0;                   // of the segment found nearest: -1 / 1 at its start / end, 0 inside
    const Segment* seg = nullptr;    // that segment
    const Segment* in = nullptr;     // at a vertex: the segment ending there
    const Segment* out = nullptr;    // and the one starting there

    void add(const Segment& s, XY p) {
        int w;
        const double d = nearest_on(p, s.a, s.b, &w);
        if (d < d2) {
            d2 = d;
            where = w;
            seg = &s;
            in = w == 1 ? &s : nullptr;
            out = w == -1 ? &s : nullptr;
        } else if (d == d2 && w != 0 && where != 0) {  // the other segment at that vertex
            if (w == 1 && !in) in = &s;
            if (w == -1 && !out) out = &s;
        }
    }
    /// Whether p lies on the ring's land (left) side at its nearest point: inside a segment,
    /// left of it; at a convex corner left of both segments, at a reflex corner of either.
    bool holds(XY p) const {
        if (!seg) return false;
        if (where == 0 || !in || !out) return geo::orient(seg->a, seg->b, p) > 0;
        const bool l_in = geo::orient(in->a, in->b, p) > 0, l_out = geo::orient(out->a, out->b, p) > 0;
        return geo::orient(in->a, in->b, out->b) > 0 ? (l_in && l_out) : (l_in || l_out);
    }
};

}  // namespace

NearestSegment CoastGrid::nearest_segment(XY p, double max_m) const noexcept {
    // Cells outward from p while one not read yet may be nearer than the segment found (and
    // within max_m); inside a cell, a chunk is skipped only when its box is farther by a clear
    // margin: a segment's distance as computed may lie a few ulps under its box's.
    struct Visit {
        const CoastGrid& g;
        XY p;
        double max_m;
        NearestSegment best{};
        void operator()(std::span<const Segment> segs) {
            visit_chunks(g, segs, [&](const geo::Box& b) { return box_point_dist2(b, p) * (1 - 1e-9) < best.dist2; },
                         [&](const Segment& sg) {
                             double t;
                             const double d2 = geo::point_segment_dist2(p, sg.a, sg.b, &t);
                             if (d2 < best.dist2) {
                                 best.dist2 = d2;
                                 best.point = sg.a + t * (sg.b - sg.a);
                                 best.segment = &sg;
                             }
                         });
        }
        bool wants(double gap) const { return gap <= 0 || (gap * gap < best.dist2 && gap <= max_m); }
        double reach() const { return std::min(std::sqrt(best.dist2), max_m); }
    } visit{*this, p, max_m};
    // Nothing farther than max_m is wanted: chunks beyond it (by more than rounding) are
    // skipped from the first cell on.
    if (std::isfinite(max_m)) visit.best.dist2 = std::pow(max_m * (1 + 1e-9) + 1e-9, 2);
    visit_outward(*this, point_box(p), visit);
    if (visit.best.segment) visit.best.polyline = polyline_of(*visit.best.segment);
    else visit.best.dist2 = INFINITY;  // none found
    return visit.best;
}

std::uint32_t CoastGrid::nearest_polyline(XY p) const noexcept { return nearest_segment(p).polyline; }

std::uint32_t CoastGrid::enclosing_polyline(XY p) const {
    // A ring holds p exactly when p lies on its land side at the ring's nearest point. Rings
    // are read outward until the nearest one found to hold p is nearer than any cell not
    // read yet (every ring nearer than the gap has then been seen whole near p).
    struct Visit {
        const CoastGrid& g;
        XY p;
        std::vector<RingNear> rings;
        void operator()(std::span<const Segment> segs) {
            for (std::size_t k = g.index_of(segs), end = k + segs.size(); k < end; ++k) {
                if (!(g.m_seg_info[k] & boundary_bit)) continue;
                const std::uint32_t poly = g.m_seg_info[k] & ~boundary_bit;
                auto it = std::find_if(rings.begin(), rings.end(), [&](const RingNear& r) { return r.polyline == poly; });
                if (it == rings.end()) it = rings.insert(rings.end(), RingNear{poly});
                it->add(g.m_segments[k], p);
            }
        }
        const RingNear* best() const {
            const RingNear* b = nullptr;
            for (const RingNear& r : rings)
                if ((!b || r.d2 < b->d2) && r.holds(p)) b = &r;
            return b;
        }
        bool wants(double gap) const {
            const RingNear* b = best();
            return gap <= 0 || !b || gap * gap < b->d2;
        }
        double reach() const { return INFINITY; }  // whole rings: a ring's nearest point decides
    } visit{*this, p, {}};
    visit_outward(*this, point_box(p), visit);
    const RingNear* b = visit.best();
    return b ? b->polyline : nearest_polyline(p);
}

int CoastGrid::winding(XY p, bool* on_boundary) const noexcept {
    if (on_boundary) *on_boundary = false;
    int i = col_of(p.x), j = row_of(p.y);
    if (!valid_cell(i, j)) return 0;
    const std::uint32_t s = slot(i, j);
    if (s == water_slot) return 0;
    if (s == land_slot) return 1;
    return winding_in_cell(s, reference_point(i, j), m_ref_winding[s], p, on_boundary);
}

int CoastGrid::winding_from(XY from, int w_from, XY p, bool* on_boundary) const noexcept {
    const int i = col_of(p.x), j = row_of(p.y);
    if (!valid_cell(i, j) || col_of(from.x) != i || row_of(from.y) != j) return winding(p, on_boundary);
    if (on_boundary) *on_boundary = false;
    const std::uint32_t s = slot(i, j);
    if (s == water_slot) return 0;
    if (s == land_slot) return 1;
    return winding_in_cell(s, from, w_from, p, on_boundary);
}

namespace {

/// Segment ab's part of the winding at p counted from r (winding_in_cell's test): +1 or -1
/// where it crosses the path r-p, 0 elsewhere; 2 when p lies on it.
inline int crossing_of(XY r, XY p, XY a, XY b) noexcept {
    const bool sa = geo::orient(r, p, a) >= 0, sb = geo::orient(r, p, b) >= 0;
    if (sa == sb) return 0;
    const double o_r = geo::orient(a, b, r), o_p = geo::orient(a, b, p);
    if (o_p == 0) return 2;
    if ((o_r < 0 && o_p > 0) || (o_r > 0 && o_p < 0)) return o_p > 0 ? 1 : -1;
    return 0;
}

}  // namespace

int CoastGrid::winding_along(XY from, int w_from, XY p, std::span<const std::uint32_t> segs, bool* on_boundary) const noexcept {
    if (on_boundary) *on_boundary = false;
    int w = w_from;
    // A segment whose box misses the path's box neither crosses the path nor holds p.
    const double x0 = std::min(from.x, p.x), x1 = std::max(from.x, p.x), y0 = std::min(from.y, p.y), y1 = std::max(from.y, p.y);
    for (const std::uint32_t k : segs) {
        const Segment& sg = m_segments[k];
        if (std::max(sg.a.x, sg.b.x) < x0 || std::min(sg.a.x, sg.b.x) > x1 || std::max(sg.a.y, sg.b.y) < y0 || std::min(sg.a.y, sg.b.y) > y1)
            continue;
        const int c = crossing_of(from, p, sg.a, sg.b);
        if (c == 2) {
            if (on_boundary) *on_boundary = true;
            return std::max(w, 1);
        }
        w += c;
    }
    return w;
}

int CoastGrid::winding_in_cell(std::uint32_t s, XY r, int w, XY p, bool* on_boundary) const noexcept {
    // Signed crossings of the path from R (the cell's reference point, or another point of the
    // cell with its winding) to p with the cell's land boundary. A vertex on the line Rp
    // counts on the left side (a half-open rule), so a chain through it crosses once or not at
    // all. The cell's chains end outside it, so any path inside it counts the same.
    // A chunk of segments whose box the path from r to p does not touch holds no crossing
    // (a harbour's coast cell holds thousands of segments; the path meets a few chunks).
    const double px0 = std::min(r.x, p.x), px1 = std::max(r.x, p.x), py0 = std::min(r.y, p.y), py1 = std::max(r.y, p.y);
    auto path_misses = [&](const geo::Box& b) {
        if (b.minx > px1 || b.maxx < px0 || b.miny > py1 || b.maxy < py0) return true;
        // The line through r and p leaves the whole box on one side.
        const double o1 = geo::orient(r, p, {b.minx, b.miny}), o2 = geo::orient(r, p, {b.maxx, b.miny});
        const double o3 = geo::orient(r, p, {b.maxx, b.maxy}), o4 = geo::orient(r, p, {b.minx, b.maxy});
        return (o1 > 0 && o2 > 0 && o3 > 0 && o4 > 0) || (o1 < 0 && o2 < 0 && o3 < 0 && o4 < 0);
    };
    const std::uint32_t k_end = m_seg_offset[s + 1];
    for (std::uint32_t k = m_seg_offset[s]; k < k_end; ++k) {
        // A block of chunks first: its box holds theirs, so a path that misses it misses them.
        if (k % block_segments == 0 && k + block_segments <= k_end && path_misses(m_block_box[k / block_segments])) {
            k += block_segments - 1;
            continue;
        }
        if (k % chunk_segments == 0 && k + chunk_segments <= k_end && path_misses(m_chunk_box[k / chunk_segments])) {
            k += chunk_segments - 1;
            continue;
        }
        if (!(m_seg_info[k] & boundary_bit)) continue;
        // A segment whose box misses the path's box neither crosses the path nor holds p
        // (winding_along's test): a short path, from a point near p, meets few of the cell's.
        const Segment& sg = m_segments[k];
        if (std::max(sg.a.x, sg.b.x) < px0 || std::min(sg.a.x, sg.b.x) > px1 || std::max(sg.a.y, sg.b.y) < py0 || std::min(sg.a.y, sg.b.y) > py1)
            continue;
        const int c = crossing_of(r, p, sg.a, sg.b);
        if (c == 2) {
            if (on_boundary) *on_boundary = true;
            return std::max(w, 1);
        }
        w += c;
    }
    return w;
}

bool CoastGrid::is_land(XY p) const noexcept { return winding(p) > 0; }

bool CoastGrid::reference_points_clear() const {
    const double tol2 = std::pow(1e-7 * m_cell + 1e-9, 2);
    for (int j = 0; j < m_ny; ++j)
        for (int i = 0; i < m_nx; ++i) {
            const std::uint32_t s = slot(i, j);
            if (s >= land_slot) continue;
            const XY r = reference_point(i, j);
            for (std::uint32_t k = m_seg_offset[s]; k < m_seg_offset[s + 1]; ++k)
                if (geo::point_segment_dist2(r, m_segments[k].a, m_segments[k].b) <= tol2) return false;
        }
    return true;
}

bool operator==(const CoastGrid& a, const CoastGrid& b) {
    return a.m_frame.definition() == b.m_frame.definition() && a.m_cell == b.m_cell && a.m_x0 == b.m_x0 &&
           a.m_y0 == b.m_y0 && a.m_nx == b.m_nx && a.m_ny == b.m_ny && a.m_ref_fx == b.m_ref_fx &&
           a.m_ref_fy == b.m_ref_fy && a.m_clip_slack == b.m_clip_slack && a.m_has_land_side == b.m_has_land_side && a.m_slot == b.m_slot &&
           a.m_seg_offset == b.m_seg_offset && a.m_ref_winding == b.m_ref_winding &&
           a.m_level_depth.size() == b.m_level_depth.size() &&
           std::equal(a.m_level_depth.begin(), a.m_level_depth.end(), b.m_level_depth.begin(),
                      [](double p, double q) { return p == q || (std::isnan(p) && std::isnan(q)); }) &&
           a.m_lw_offset == b.m_lw_offset && a.m_lw_level == b.m_lw_level && a.m_lw_winding == b.m_lw_winding &&
           a.m_land_level == b.m_land_level &&
           a.m_seg_info == b.m_seg_info && a.m_segments.size() == b.m_segments.size() &&
           std::equal(a.m_hazards.begin(), a.m_hazards.end(), b.m_hazards.begin(), b.m_hazards.end(),
                      [](const coast::Hazard& p, const coast::Hazard& q) {
                          return p.kind == q.kind && p.danger == q.danger && p.structure == q.structure && p.name == q.name &&
                                 (p.depth_m == q.depth_m || (std::isnan(p.depth_m) && std::isnan(q.depth_m)));
                      }) &&
           std::equal(a.m_segments.begin(), a.m_segments.end(), b.m_segments.begin(),
                      [](const Segment& p, const Segment& q) { return p.a == q.a && p.b == q.b; }) &&
           a.m_source.fingerprint == b.m_source.fingerprint && a.m_source.inputs == b.m_source.inputs &&
           (a.m_source.limiting_depth_m == b.m_source.limiting_depth_m ||
            (std::isnan(a.m_source.limiting_depth_m) && std::isnan(b.m_source.limiting_depth_m)));
}

double choose_cell_size(double cell_m, double ship_length_m, const geo::Box& extent, std::string* note) {
    auto say = [&](const std::string& s) { if (note) *note = s; };
    char buf[200];
    if (cell_m > 0) {
        std::snprintf(buf, sizeof buf, "cell %.1f m (BuildRequest::cell_m)", cell_m);
        say(buf);
        return cell_m;
    }
    if (ship_length_m > 0) {
        std::snprintf(buf, sizeof buf, "cell %.1f m (2.5 x BuildRequest::ship_length_m %.1f m)", 2.5 * ship_length_m, ship_length_m);
        say(buf);
        return 2.5 * ship_length_m;
    }
    double cell = 500.0;
    const double area = (extent.maxx - extent.minx) * (extent.maxy - extent.miny);
    const double limit = static_cast<double>(CoastGrid::max_cells) / 4;  // keep the default grid well under the cap
    if (area / (cell * cell) > limit) cell = std::ceil(std::sqrt(area / limit) / 100) * 100;
    std::snprintf(buf, sizeof buf, "cell %.1f m (default: 2.5 x a 200 m ship%s; set BuildRequest::cell_m or BuildRequest::ship_length_m)", cell,
                  cell > 500 ? ", raised to keep the grid small for this extent" : "");
    say(buf);
    return cell;
}

}  // namespace shoal::grid
