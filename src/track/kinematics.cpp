#include <shoal/track/kinematics.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace shoal::track {

namespace {

constexpr double metres_per_nm = 1852.0;
constexpr double earth_radius_m = 6371008.8;
constexpr double deg = std::numbers::pi / 180.0;

bool breaks_before(const Track& t, std::size_t i, double max_gap_s) noexcept {
    return i == 0 || t.fixes[i].jump_before || t.fixes[i].time_s - t.fixes[i - 1].time_s > max_gap_s;
}

/// Monotonic queue of indices giving the least (or, with `greater`, the largest) value of a
/// sliding window whose start only moves forward.
class WindowExtreme {
public:
    explicit WindowExtreme(bool greater) : m_greater(greater) {}
    void push(std::size_t i, const std::vector<double>& v) {
        while (m_head < m_q.size() && (m_greater ? v[m_q.back()] <= v[i] : v[m_q.back()] >= v[i])) m_q.pop_back();
        m_q.push_back(i);
    }
    void drop_before(std::size_t start) {
        while (m_head < m_q.size() && m_q[m_head] < start) ++m_head;
        if (m_head >= 16 && 2 * m_head >= m_q.size()) {  // what left the front, let go of (amortised)
            m_q.erase(m_q.begin(), m_q.begin() + static_cast<std::ptrdiff_t>(m_head));
            m_head = 0;
        }
    }
    double value(const std::vector<double>& v) const { return v[m_q[m_head]]; }

private:
    bool m_greater;
    /// The queue is m_q[m_head ..] (a vector: a deque's blocks cost more to come and go).
    std::vector<std::size_t> m_q;
    std::size_t m_head = 0;
};

/// Per fix of a piece [b, e): the start of the longest window ending at it whose fixes fit in
/// a box of diagonal <= diameter (metres, equirectangular about the piece's first fix).
std::vector<std::size_t> stay_starts(const Track& t, std::size_t b, std::size_t e, double diameter_m) {
    const std::size_t n = e - b;
    std::vector<double> x(n), y(n);
    const double lat0 = t.fixes[b].position.lat, lon0 = t.fixes[b].position.lon;
    const double kx = earth_radius_m * deg * std::cos(lat0 * deg), ky = earth_radius_m * deg;
    for (std::size_t k = 0; k < n; ++k) {
        double dlon = t.fixes[b + k].position.lon - lon0;
        if (dlon > 180) dlon -= 360;
        if (dlon < -180) dlon += 360;
        x[k] = dlon * kx;
        y[k] = (t.fixes[b + k].position.lat - lat0) * ky;
    }
    std::vector<std::size_t> start(n);
    WindowExtreme xmin(false), xmax(true), ymin(false), ymax(true);
    std::size_t s = 0;
    for (std::size_t k = 0; k < n; ++k) {
        xmin.push(k, x); xmax.push(k, x); ymin.push(k, y); ymax.push(k, y);
        while (s < k && std::hypot(xmax.value(x) - xmin.value(x), ymax.value(y) - ymin.value(y)) > diameter_m) {
            ++s;
            xmin.drop_before(s); xmax.drop_before(s); ymin.drop_before(s); ymax.drop_before(s);
        }
        start[k] = b + s;
    }
    return start;
}

}  // namespace

std::size_t piece_start(const Track& t, std::size_t i, double max_gap_s) noexcept {
    while (i > 0 && !breaks_before(t, i, max_gap_s)) --i;
    return i;
}

void resolve_motion(Track& t, const MotionOptions& o) {
    const std::size_t n = t.fixes.size();
    for (std::size_t b = 0; b < n;) {
        std::size_t e = b + 1;
        while (e < n && !breaks_before(t, e, o.max_gap_s)) ++e;
        // Speed: SOG, else the displacement over the window.
        for (std::size_t i = b; i < e; ++i) {
            Fix& f = t.fixes[i];
            if (std::isfinite(f.sog_kn)) {
                f.speed_used_kn = f.sog_kn;
                f.speed_source = SpeedSource::sog;
                continue;
            }
            std::size_t j = i, k = i;
            // The latest fix at least a window earlier, else the piece's first; near the
            // piece's start, the window reaches forward until it is a window long.
            while (j > b && f.time_s - t.fixes[j].time_s < o.speed_window_s) --j;
            while (k + 1 < e && t.fixes[k].time_s - t.fixes[j].time_s < o.speed_window_s) ++k;
            const double dt = t.fixes[k].time_s - t.fixes[j].time_s;
            if (dt > 0) {
                f.speed_used_kn = distance_m(t.fixes[j].position, t.fixes[k].position) / dt * 3600.0 / metres_per_nm;
                f.speed_source = SpeedSource::positions;
            } else {
                f.speed_used_kn = NAN;
                f.speed_source = SpeedSource::none;
            }
        }
        // Stops, from this fix and the ones before it.
        const std::vector<std::size_t> start = stay_starts(t, b, e, o.stop_diameter_m);
        for (std::size_t i = b; i < e; ++i) {
            t.fixes[i].stay_since_s = t.fixes[start[i - b]].time_s;
            t.fixes[i].stopped = t.fixes[i].time_s - t.fixes[i].stay_since_s >= o.stop_duration_s;
        }
        b = e;
    }
}

std::optional<double> stopped_after(const Track& t, std::size_t from, double time_s, const MotionOptions& o) {
    const std::size_t n = t.fixes.size();
    // The first stopped fix from `from` on, within the piece (resolve_motion() set the stays).
    for (std::size_t i = from; i < n; ++i) {
        if (i > from && breaks_before(t, i, o.max_gap_s)) break;
        const Fix& f = t.fixes[i];
        if (!f.stopped) continue;
        // The stay began at its first fix, but not before the first fix seen at or after the
        // contact (the stay's first fix may be the last one of the approach, within the diameter).
        return std::max({time_s, f.stay_since_s, t.fixes[from].time_s});
    }
    return std::nullopt;
}

}  // namespace shoal::track
