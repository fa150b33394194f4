// The exercise clock (see exercise_clock.hpp).
#include "exercise/exercise_clock.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

namespace shoal::audit::detail {

ExerciseClock::ExerciseClock(std::vector<Ship> ships, double step_m) : m_ships(std::move(ships)), m_state(m_ships.size()), m_step_m(step_m) {}

void ExerciseClock::step(double t, const std::function<void(double)>& at_instant) {
    for (const std::uint32_t k : m_present) m_state[k].f = m_ships[k].track->fraction(m_state[k].cur, t);
    at_instant(t);
    ++m_instant;
    m_joined = false;
}

void ExerciseClock::run(const std::function<void(double)>& at_instant) {
    // Every fix of every ship, in time order.
    std::vector<std::pair<double, std::uint32_t>> fixes;
    for (std::uint32_t k = 0; k < m_ships.size(); ++k)
        for (const track::Fix& f : m_ships[k].track->track().fixes) fixes.push_back({f.time_s, k});
    std::sort(fixes.begin(), fixes.end());
    std::multiset<double> speeds;  // of the moving ships
    for (std::size_t e = 0; e < fixes.size();) {
        const double t = fixes[e].first;
        std::size_t end = e;
        while (end < fixes.size() && fixes[end].first == t) ++end;
        for (std::size_t k = e; k < end; ++k) {
            State& s = m_state[fixes[k].second];
            const std::vector<double>& speed = *m_ships[fixes[k].second].speed;
            if (s.moving) speeds.erase(speeds.find(speed[s.cur]));
            s.cur = s.next_fix++;
            if (!s.present) {
                s.present = true;
                s.entered = m_instant;
                s.slot = m_present.size();
                m_present.push_back(fixes[k].second);
                m_joined = true;
            }
        }
        step(t, at_instant);
        for (std::size_t k = e; k < end; ++k) {
            State& s = m_state[fixes[k].second];
            const std::vector<double>& speed = *m_ships[fixes[k].second].speed;
            s.moving = s.cur < speed.size() && speed[s.cur] >= 0;
            if (s.moving) {
                speeds.insert(speed[s.cur]);
            } else {
                s.present = false;
                m_state[m_present.back()].slot = s.slot;
                m_present[s.slot] = m_present.back();
                m_present.pop_back();
            }
        }
        e = end;
        if (e == fixes.size() || m_present.size() < 2) continue;
        // Instants between this fix time and the next: relative motion <= step between them.
        const double next = fixes[e].first, dt = next - t;
        const double v = *speeds.rbegin() + *std::next(speeds.rbegin());
        const double n = std::max(1.0, std::ceil(v * dt / m_step_m));
        for (double j = 1; j < n; ++j) {
            const double ti = t + dt * j / n;
            if (ti > t && ti < next) step(ti, at_instant);
        }
    }
}

}  // namespace shoal::audit::detail
