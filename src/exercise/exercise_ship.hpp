#pragma once
/// A ship of an exercise (internal to src/exercise): its track in the local frame, its hull
/// prepared for contact checks, bounds on how fast and how far any of its hull points moves,
/// and its pose at the current instant (placed when first asked for, once an instant).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <shoal/geo/local_frame.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/track/track.hpp>
#include "check/hull_shape.hpp"
#include "sweep/local_track.hpp"

namespace shoal::audit::detail {

struct ExerciseShip {
    ExerciseShip() = default;
    ExerciseShip(const ExerciseShip&) = delete;  // placed once an instant: one copy
    ExerciseShip& operator=(const ExerciseShip&) = delete;

    std::optional<LocalTrack> local;  ///< broken at gaps over max_gap_s (not at jumps)
    const hull::Hull* hull = nullptr;
    check::detail::HullShape shape;
    double sigma_max = 1;       ///< largest stretch of the frame over the track's fixes
    double reach = 0;           ///< sigma_max * hull radius + slack: a circle around the position holds the hull
    std::vector<double> speed;  ///< per fix interval: bound on any hull point's speed, m/s; < 0 across a gap
    /// Per fix: bound on how far any hull point has moved since the first fix (gaps count 0).
    /// Between two moments, the difference bounds the motion of every hull point.
    std::vector<double> odometer;

    // At the current instant (while present).
    Where at;             ///< the last fix at or before it, and the fraction of its interval
    geo::XY pos;          ///< reference point
    double odometer_now() const { return local->interpolate(odometer, at); }
    std::uint64_t posed_at = UINT64_MAX;     ///< instant of placed's pose and chunks
    std::uint64_t outlined_at = UINT64_MAX;  ///< instant of placed's outline
    check::detail::Placed placed;

    /// The pose and chunk capsules at instant `now`.
    const check::detail::Placed& posed(std::uint64_t now) {
        if (posed_at != now) {
            check::detail::place_chunks(shape, local->pose(at), placed);
            posed_at = now;
        }
        return placed;
    }
    /// The hull at instant `now`.
    const check::detail::Placed& outlined(std::uint64_t now) {
        posed(now);
        if (outlined_at != now) {
            check::detail::place_outline(shape, placed);
            outlined_at = now;
        }
        return placed;
    }
};

/// Prepares `s` for `track` (fixes checked: times strictly increasing, headings resolved) with
/// `hull` in `frame`; a fix interval longer than `max_gap_s` is a gap (speed < 0, no motion).
void prepare_ship(ExerciseShip& s, const track::Track& track, const hull::Hull& hull, const geo::LocalFrame& frame, double max_gap_s);

}  // namespace shoal::audit::detail
