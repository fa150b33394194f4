#include <shoal/check/brute_force.hpp>

#include <algorithm>

namespace shoal::check {

using geo::XY;

BruteForce::BruteForce(std::vector<coast::LocalPolyline> lines, const hull::Hull& hull)
    : m_lines(std::move(lines)), m_hull(hull) {}

int BruteForce::winding(XY p) const {
    int w = 0;  // signed crossings of the ray from p towards -x
    for (const auto& l : m_lines) {
        if (!l.land_left) continue;
        for (std::size_t k = 0; k + 1 < l.points.size(); ++k) {
            const XY a = l.points[k], b = l.points[k + 1];
            if ((a.y <= p.y) == (b.y <= p.y)) continue;
            const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x < p.x) w += b.y < a.y ? 1 : -1;
        }
    }
    return w;
}

Contact BruteForce::check(const LocalPose& pose) const {
    const std::vector<XY> h = hull_outline(m_hull, pose);
    const std::size_t n = h.size();
    Contact out;
    double best2 = INFINITY;
    for (std::size_t li = 0; li < m_lines.size(); ++li) {
        const auto& l = m_lines[li];
        for (std::size_t k = 0; k + 1 < l.points.size(); ++k)
            for (std::size_t e = 0; e < n; ++e) {
                XY on_hull, on_coast;
                const double d2 =
                    geo::segment_segment_dist2(h[e], h[(e + 1) % n], l.points[k], l.points[k + 1], &on_hull, &on_coast);
                if (d2 < best2) {
                    best2 = d2;
                    out.hull_point = on_hull;
                    out.coast_point = on_coast;
                    out.polyline = static_cast<std::uint32_t>(li);
                }
            }
    }
    out.clearance_m = std::sqrt(best2);
    if (best2 == 0) out.collision = true;
    if (!out.collision && winding(h[0]) > 0) out.collision = true;
    if (!out.collision) {
        // A coastline vertex inside the hull (an islet or a pier end between hull points).
        auto inside = [&](XY q) {
            bool in = false;
            for (std::size_t i = 0, j = n - 1; i < n; j = i++)
                if ((h[j].y > q.y) != (h[i].y > q.y) &&
                    q.x < h[j].x + (q.y - h[j].y) * (h[i].x - h[j].x) / (h[i].y - h[j].y))
                    in = !in;
            return in;
        };
        for (const auto& l : m_lines)
            if (!l.points.empty() && inside(l.points[0])) out.collision = true;
    }
    if (out.collision) out.clearance_m = 0;
    return out;
}

}  // namespace shoal::check
