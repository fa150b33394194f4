// A ship of an exercise (see exercise_ship.hpp): the bounds on its hull points' motion.
#include "exercise/exercise_ship.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace shoal::audit::detail {

using check::detail::bound_slack_m;
using check::detail::spectral_norm;

namespace {
constexpr double deg = std::numbers::pi / 180.0;
}  // namespace

void prepare_ship(ExerciseShip& s, const track::Track& track, const hull::Hull& hull, const geo::LocalFrame& frame, double max_gap_s) {
    s.hull = &hull;
    s.shape = check::detail::prepare(hull.contour());
    s.local.emplace(track, frame, Breaks{.max_gap_s = max_gap_s});
    const LocalTrack& local = *s.local;
    for (std::size_t i = 0; i < local.size(); ++i) {
        const Eigen::Matrix2d& j = local.jacobian(i);
        s.sigma_max = std::max(s.sigma_max, spectral_norm(j(0, 0), j(0, 1), j(1, 0), j(1, 1)));
    }
    s.sigma_max *= 1 + 1e-9;
    s.reach = s.sigma_max * s.shape.radius + bound_slack_m;
    const auto& fx = track.fixes;
    s.odometer.assign(1, 0.0);
    for (std::size_t i = 0; i + 1 < fx.size(); ++i) {
        const double dt = fx[i + 1].time_s - fx[i].time_s;
        if (!s.local->sailed(i)) {
            s.speed.push_back(-1);
            s.odometer.push_back(s.odometer.back());
            continue;
        }
        const double rot = std::fabs(turn(fx[i].heading_used_deg, fx[i + 1].heading_used_deg)) * deg;
        // Any hull point: the reference point's move, the turn, and the change of the
        // frame's local map (scale and convergence) over the hull's radius.
        const Eigen::Matrix2d dj = local.jacobian(i + 1) - local.jacobian(i);
        const double moved = geo::distance(local.position(i), local.position(i + 1)) + s.sigma_max * s.shape.radius * rot +
                             spectral_norm(dj(0, 0), dj(0, 1), dj(1, 0), dj(1, 1)) * s.shape.radius;
        s.speed.push_back(moved / dt);
        s.odometer.push_back(s.odometer.back() + moved);
    }
}

}  // namespace shoal::audit::detail
