#include "audit/motion.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "util/error.hpp"

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

std::vector<LocalFix> project_fixes(const track::Track& t, const geo::LocalFrame& frame) {
    const std::size_t n = t.fixes.size();
    // Five points per fix in one batch: the fix and 1 m east, west, north, south of it.
    std::vector<double> xs(5 * n), ys(5 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const geo::LonLat p = t.fixes[i].position;
        const Eigen::Vector2d mpd = geo::metres_per_degree(p.lat);
        const double dlon = 1.0 / mpd.x(), dlat = 1.0 / mpd.y();
        const double lx[5] = {p.lon, p.lon + dlon, p.lon - dlon, p.lon, p.lon};
        const double ly[5] = {p.lat, p.lat, p.lat, p.lat + dlat, p.lat - dlat};
        for (int k = 0; k < 5; ++k) {
            xs[5 * i + static_cast<std::size_t>(k)] = lx[k];
            ys[5 * i + static_cast<std::size_t>(k)] = ly[k];
        }
    }
    std::size_t bad = 0;
    if (!frame.forward(xs, ys, &bad)) {
        const track::Fix& f = t.fixes[bad / 5];
        char buf[160];
        std::snprintf(buf, sizeof buf, "fix at line %zu (lat %.6f, lon %.6f) cannot be projected into the coastline's frame (%s)",
                      f.line, f.position.lat, f.position.lon, frame.description().c_str());
        throw InputError("track '" + t.id + "' in '" + t.file + "': " + buf);
    }
    std::vector<LocalFix> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double* x = &xs[5 * i];
        const double* y = &ys[5 * i];
        out[i].position = {x[0], y[0]};
        out[i].jacobian << (x[1] - x[2]) / 2, (x[3] - x[4]) / 2, (y[1] - y[2]) / 2, (y[3] - y[4]) / 2;
    }
    return out;
}

check::LocalPose Motion::pose(std::size_t i, double f) const {
    const track::Fix& a = m_track.fixes[i];
    if (f == 0 || i + 1 >= m_track.fixes.size()) return {m_local[i].position, m_local[i].jacobian * ship_to_en(a.heading_used_deg)};
    const track::Fix& b = m_track.fixes[i + 1];
    const double h = a.heading_used_deg + f * turn(a.heading_used_deg, b.heading_used_deg);
    const Eigen::Matrix2d j = (1 - f) * m_local[i].jacobian + f * m_local[i + 1].jacobian;
    return {m_local[i].position + f * (m_local[i + 1].position - m_local[i].position), j * ship_to_en(h)};
}

double Motion::time(std::size_t i, double f) const {
    if (f == 0 || i + 1 >= m_track.fixes.size()) return m_track.fixes[i].time_s;
    return m_track.fixes[i].time_s + f * (m_track.fixes[i + 1].time_s - m_track.fixes[i].time_s);
}

double Motion::heading(std::size_t i, double f) const {
    const track::Fix& a = m_track.fixes[i];
    if (f == 0 || i + 1 >= m_track.fixes.size()) return a.heading_used_deg;
    const double h = a.heading_used_deg + f * turn(a.heading_used_deg, m_track.fixes[i + 1].heading_used_deg);
    return std::fmod(h + 360.0, 360.0);
}

}  // namespace shoal::audit
