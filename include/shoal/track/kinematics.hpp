#pragma once
/// How a vessel moves at each fix: its speed (SOG when the source gives it, else from the
/// displacement over a window of time, which GPS jitter of a few metres cannot fake) and
/// whether it is stopped: it has stayed within a small diameter for a minimum time (the stop
/// of MovingPandas' TrajectoryStopDetector and MobilityDB's stops(), judged here from the
/// fix and the fixes before it only, so that a vessel that stops *after* touching land is not
/// taken for one that was lying still when it touched).

#include <cstddef>
#include <optional>

#include <shoal/track/track.hpp>

namespace shoal::track {

struct MotionOptions {
    /// Speed from positions: the displacement from the latest fix at least this many seconds
    /// earlier, divided by the time between them; near a piece's start, from its first fix to
    /// the first fix this long after it. Over 120 s, GPS jitter of 5 m (sigma) reads as 0.45 kn at most.
    double speed_window_s = 120.0;
    /// A stop: every fix of a time window lies in a box whose diagonal is at most this (metres)...
    double stop_diameter_m = 50.0;
    /// ... and the window lasts at least this long (seconds).
    double stop_duration_s = 120.0;
    /// Fixes further apart in time than this are in different pieces of track (the sweep's --max-gap).
    double max_gap_s = 600.0;
};

/// Fills speed_used_kn, speed_source and stopped for every fix of `track` (fixes sorted by
/// time, wild fixes dropped). Pieces of track (split at gaps over max_gap_s and at
/// Fix::jump_before) are treated separately: no window reaches across a break.
void resolve_motion(Track& track, const MotionOptions& options = {});

/// Index of the first fix of the piece that holds fix `i` (gaps over max_gap_s and jumps split pieces).
std::size_t piece_start(const Track& track, std::size_t i, double max_gap_s) noexcept;

/// When the vessel came to a stop at or after `time_s` (fix `from` being the first at or after
/// it): the first stopped fix from `from` on, within the piece, gives the start of its stay,
/// taken no earlier than fix `from` (nor `time_s`). None when it never stopped. Needs
/// resolve_motion(); costs the fixes until that stop.
std::optional<double> stopped_after(const Track& track, std::size_t from, double time_s, const MotionOptions& options);

}  // namespace shoal::track
