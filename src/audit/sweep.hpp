#pragma once
/// Sweeping a ship's hull along a track: poses every <= step metres of hull motion between
/// fixes (position and heading interpolated, heading by the shorter turn), each checked,
/// and the results gathered into events (grounding, close pass) with the first contact
/// time refined by bisection.

#include <cstddef>
#include <string>
#include <vector>

#include "check/detector.hpp"
#include "track/track.hpp"

namespace shoal::audit {

struct SweepOptions {
    double step_m = 5.0;          ///< no hull point moves more than this between two checks
    double margin_m = 50.0;       ///< clearance under this (and no contact) is a close pass
    double max_gap_s = 600.0;     ///< a longer gap between fixes splits the track: nothing is swept across it
    double time_tolerance_s = 0.01;  ///< bisection stops when the contact time is known this well
    /// The clearance search reaches this far beyond the margin; a pose found clear by d metres
    /// lets the sweep skip checks for the next d - margin metres of hull motion (they cannot
    /// come within the margin). Fixes are always checked.
    double lookahead_m = 500.0;
};

enum class EventKind { grounding, close_pass };
const char* to_string(EventKind k) noexcept;

/// A grounding (an interval of contact) or a close pass (an interval with clearance under the
/// margin that never reaches contact).
struct Event {
    EventKind kind = EventKind::grounding;
    double start_s = 0, end_s = 0;  ///< epoch seconds; start of a grounding is the refined first contact
    double min_clearance_m = 0;     ///< least clearance (0 for a grounding)
    double penetration_m = 0;       ///< deepest reach past the coastline seen (groundings)
    geo::LonLat point;              ///< grounding: first contact point; close pass: nearest coast point at least clearance
    geo::LonLat ship;               ///< reference point of the ship at that moment
    double heading_deg = 0;         ///< heading used at that moment
    track::HeadingSource heading_source = track::HeadingSource::none;
    std::size_t fix_index = 0;      ///< index (0-based) of the last fix at or before that moment
    std::size_t fix_line = 0;       ///< its line (or point number) in the file
    std::vector<geo::LonLat> hull;  ///< hull outline at that moment (closed ring)
    /// What the hull touched (grounding) or came nearest to (close pass): land, shallow water
    /// (a depth area under the limiting depth) or a danger.
    coast::HazardKind hit = coast::HazardKind::land;
    double charted_depth_m = NAN;   ///< its charted depth (least depth of the area, danger's sounding); NaN unknown or land
    coast::DangerKind danger = coast::DangerKind::none;  ///< the danger's kind (rock, wreck, obstruction)
};

/// Figures of one swept track.
struct TrackSummary {
    std::string id, name, file;
    std::string hull;                 ///< "ship file", "--dims" or "AIS dimensions a,b,c,d"
    std::size_t fixes = 0;            ///< fixes in the track
    std::size_t uncovered_fixes = 0;  ///< fixes whose hull is (partly) outside the coastline's area
    std::size_t segments = 0;         ///< pieces after splitting at gaps
    std::size_t gaps = 0;             ///< gaps longer than max_gap_s
    std::size_t poses = 0;            ///< poses checked (fixes and swept poses between them)
    std::size_t groundings = 0, close_passes = 0;
    double min_clearance_m = INFINITY;  ///< least clearance over covered poses (0 on grounding; INFINITY: never within the search limit)
    double start_s = NAN, end_s = NAN;
    double distance_m = 0;            ///< length sailed (local metres, gaps excluded)
    std::vector<std::vector<geo::LonLat>> lines;  ///< the swept pieces, for the report's tracks layer
};

struct TrackResult {
    TrackSummary summary;
    std::vector<Event> events;
};

/// Anything that checks a pose: the grid Detector, or the brute-force traversal in tests.
class PoseChecker {
public:
    virtual ~PoseChecker() = default;
    virtual check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const = 0;
    virtual const hull::Hull& hull() const = 0;
    /// The grid whose polylines Contact::polyline indexes (what a contact hit), if any.
    virtual const grid::CoastGrid* grid() const { return nullptr; }
};

class DetectorChecker final : public PoseChecker {
public:
    DetectorChecker(const grid::CoastGrid& grid, const hull::Hull& hull) : m_detector(grid, hull) {}
    check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const override {
        return m_detector.check(pose, options);
    }
    const hull::Hull& hull() const override { return m_detector.hull(); }
    const grid::CoastGrid* grid() const override { return &m_detector.grid(); }

private:
    check::Detector m_detector;
};

/// Sweeps `track` (headings resolved) with `checker` in `frame`. A pose equal to the one
/// checked just before (a vessel standing still) is not checked again: the last answer stands.
TrackResult sweep_track(const track::Track& track, const geo::LocalFrame& frame, const PoseChecker& checker,
                        const SweepOptions& options);

}  // namespace shoal::audit
