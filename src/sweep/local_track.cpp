// A track in the local frame (see local_track.hpp).
#include "sweep/local_track.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include <shoal/util/error.hpp>

namespace shoal::audit {

namespace {
constexpr double deg = std::numbers::pi / 180.0;
}  // namespace

Eigen::Matrix2d ship_to_en(double heading_deg) {
    const double h = heading_deg * deg;
    Eigen::Matrix2d m;
    m << std::sin(h), std::cos(h), std::cos(h), -std::sin(h);
    return m;
}

double turn(double a, double b) {
    double d = std::fmod(b - a, 360.0);
    if (d > 180) d -= 360;
    if (d <= -180) d += 360;
    return d;
}

double wrap_360(double a) noexcept {
    a = std::fmod(a, 360.0);
    if (a < 0) a += 360.0;
    return a >= 360.0 ? 0.0 : a;  // -1e-17 + 360 rounds to 360
}

namespace {

/// The frame's Jacobian (central differences over 1 m) at several lon/lat points in one batch.
std::vector<Eigen::Matrix2d> jacobians(const std::vector<geo::LonLat>& at, const geo::LocalFrame& frame) {
    std::vector<double> xs, ys;
    xs.reserve(4 * at.size());
    ys.reserve(4 * at.size());
    for (const geo::LonLat& p : at) {
        const Eigen::Vector2d mpd = geo::metres_per_degree(p.lat);
        const double dlon = 1.0 / mpd.x(), dlat = 1.0 / mpd.y();
        for (const auto& [lx, ly] : {std::pair{p.lon + dlon, p.lat}, {p.lon - dlon, p.lat}, {p.lon, p.lat + dlat}, {p.lon, p.lat - dlat}}) {
            xs.push_back(lx);
            ys.push_back(ly);
        }
    }
    std::size_t bad = 0;
    if (!frame.forward(xs, ys, &bad)) throw InputError("a point near a fix cannot be projected into the coastline's frame (" + frame.description() + ")");
    std::vector<Eigen::Matrix2d> out(at.size());
    for (std::size_t i = 0; i < at.size(); ++i) {
        const double* x = &xs[4 * i];
        const double* y = &ys[4 * i];
        out[i] << (x[0] - x[1]) / 2, (x[2] - x[3]) / 2, (y[0] - y[1]) / 2, (y[2] - y[3]) / 2;
    }
    return out;
}

/// Fixes within this many metres of an anchor take their Jacobian from the anchor's linear
/// model: the Jacobian's second derivatives are ~1/R^2, so the error is ~(2 km)^2/R^2 ~ 1e-7,
/// far under the 2.5e-5 that would move a 400 m ship's bow by 1 cm.
constexpr double anchor_spacing_m = 2000.0;
constexpr double anchor_arm_m = 1000.0;

}  // namespace

namespace {

/// Every fix of `t` in `frame` (one batch through PROJ) into xs, ys; InputError naming the
/// track, the file and the line of the first fix that cannot be projected.
void project_positions(const track::Track& t, const geo::LocalFrame& frame, std::vector<double>& xs, std::vector<double>& ys) {
    const std::size_t n = t.fixes.size();
    xs.resize(n);
    ys.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        xs[i] = t.fixes[i].position.lon;
        ys[i] = t.fixes[i].position.lat;
    }
    std::size_t bad = 0;
    if (!frame.forward(xs, ys, &bad)) {
        const track::Fix& f = t.fixes[bad];
        char buf[160];
        std::snprintf(buf, sizeof buf, "fix at line %zu (lat %.6f, lon %.6f) cannot be projected into the coastline's frame (%s)",
                      f.line, f.position.lat, f.position.lon, frame.description().c_str());
        throw InputError("track '" + t.id + "' in '" + t.file + "': " + buf);
    }
}

}  // namespace

std::vector<LocalFix> project_fixes(const track::Track& t, const geo::LocalFrame& frame) {
    const std::size_t n = t.fixes.size();
    // One projected point per fix; the Jacobian (scale and meridian convergence) from a linear
    // model around anchors every ~2 km: at the anchor, 1 km east and 1 km north of it.
    std::vector<double> xs, ys;
    project_positions(t, frame, xs, ys);
    std::size_t bad = 0;
    std::vector<std::size_t> anchor_of(n);
    std::vector<std::size_t> anchors;
    for (std::size_t i = 0; i < n; ++i) {
        if (anchors.empty() || std::hypot(xs[i] - xs[anchors.back()], ys[i] - ys[anchors.back()]) > anchor_spacing_m) anchors.push_back(i);
        anchor_of[i] = anchors.size() - 1;
    }
    std::vector<geo::LonLat> at;
    for (std::size_t a : anchors) {
        const geo::LonLat p = t.fixes[a].position;
        const Eigen::Vector2d mpd = geo::metres_per_degree(p.lat);
        at.push_back(p);
        at.push_back({p.lon + anchor_arm_m / mpd.x(), p.lat});
        at.push_back({p.lon, p.lat + anchor_arm_m / mpd.y()});
    }
    const std::vector<Eigen::Matrix2d> js = jacobians(at, frame);
    // Local positions of the arms, for the model's coordinates.
    std::vector<double> axs(at.size()), ays(at.size());
    for (std::size_t k = 0; k < at.size(); ++k) {
        axs[k] = at[k].lon;
        ays[k] = at[k].lat;
    }
    if (!frame.forward(axs, ays, &bad)) throw InputError("track '" + t.id + "' in '" + t.file + "': a point near a fix cannot be projected");
    std::vector<LocalFix> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t k = 3 * anchor_of[i];
        const geo::XY pa{axs[k], ays[k]}, pe{axs[k + 1], ays[k + 1]}, pn{axs[k + 2], ays[k + 2]};
        Eigen::Matrix2d basis;
        basis << pe.x - pa.x, pn.x - pa.x, pe.y - pa.y, pn.y - pa.y;
        const Eigen::Vector2d uv = basis.inverse() * Eigen::Vector2d(xs[i] - pa.x, ys[i] - pa.y);
        out[i].position = {xs[i], ys[i]};
        out[i].jacobian = js[k] + uv.x() * (js[k + 1] - js[k]) + uv.y() * (js[k + 2] - js[k]);
    }
    return out;
}

LocalTrack::LocalTrack(const track::Track& t, const geo::LocalFrame& frame, Breaks breaks, Placing placing) : m_track(t) {
    const std::size_t n = t.fixes.size();
    if (placing == Placing::poses) {
        for (const LocalFix& l : project_fixes(t, frame)) {
            m_position.push_back(l.position);
            m_jacobian.push_back(l.jacobian);
        }
    } else {
        std::vector<double> xs, ys;
        project_positions(t, frame, xs, ys);
        m_position.reserve(n);
        for (std::size_t i = 0; i < n; ++i) m_position.push_back({xs[i], ys[i]});
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
        m_sailed.push_back(!(t.fixes[i + 1].time_s - t.fixes[i].time_s > breaks.max_gap_s) && !(breaks.at_jumps && t.fixes[i + 1].jump_before));
    for (const geo::XY& p : m_position) {
        m_lo = {std::min(m_lo.x, p.x), std::min(m_lo.y, p.y)};
        m_hi = {std::max(m_hi.x, p.x), std::max(m_hi.y, p.y)};
    }
}

namespace {
/// The last fix at or before t (0 before the first).
std::size_t fix_at_or_before(const std::vector<track::Fix>& fx, double t) {
    const auto it = std::upper_bound(fx.begin(), fx.end(), t, [](double v, const track::Fix& x) { return v < x.time_s; });
    return it == fx.begin() ? 0 : static_cast<std::size_t>(it - fx.begin()) - 1;
}
}  // namespace

Where LocalTrack::at(double t) const {
    if (m_track.fixes.empty() || t < time(0)) return {};
    const std::size_t i = fix_at_or_before(m_track.fixes, t);
    return {i, fraction(i, t)};
}

std::size_t LocalTrack::interval(double t) const { return std::min(fix_at_or_before(m_track.fixes, t), size() - 2); }

bool LocalTrack::present(double t) const {
    if (m_track.fixes.empty() || t < time(0) || t > time(size() - 1)) return false;
    const std::size_t i = fix_at_or_before(m_track.fixes, t);
    return time(i) == t || sailed(i);
}

check::LocalPose LocalTrack::pose(Where w) const {
    if (m_jacobian.size() != size()) throw UsageError("LocalTrack::pose: the track was projected for positions only (Placing::positions)");
    if (w.f == 0 || w.i + 1 >= size()) return {m_position[w.i], m_jacobian[w.i] * ship_to_en(m_track.fixes[w.i].heading_used_deg)};
    const double h = heading(w);
    const Eigen::Matrix2d j = (1 - w.f) * m_jacobian[w.i] + w.f * m_jacobian[w.i + 1];
    return {position(w), j * ship_to_en(h)};
}

}  // namespace shoal::audit
