#pragma once
/// Sweeping a ship's hull along a track: poses every <= step metres of hull motion between
/// fixes (position and heading interpolated, heading by the shorter turn), each checked,
/// and the results gathered into events (grounding, close pass) with the first contact
/// time refined by bisection.

#include <cstddef>
#include <string>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/sweep/role.hpp>
#include <shoal/track/kinematics.hpp>
#include <shoal/track/track.hpp>
#include <shoal/track/wild_fixes.hpp>

namespace shoal::coast { class ExpectedAreas; }

namespace shoal::audit {

/// The smallest SweepOptions::step_m front ends accept: a centimetre (a sweep finer than
/// that never ends on a long voyage).
inline constexpr double min_step_m = 0.01;
/// Throws UsageError naming SweepOptions::step_m when `step_m` is under min_step_m (or NaN):
/// what front ends call before any work.
void check_step(double step_m);

struct SweepOptions {
    double step_m = 5.0;          ///< no hull point moves more than this between two checks
    double margin_m = 50.0;       ///< clearance under this (and no contact) is a close pass
    double max_gap_s = 600.0;     ///< a longer gap between fixes splits the track: nothing is swept across it
    double time_tolerance_s = 0.01;  ///< bisection stops when the contact time is known this well
    /// The clearance search reaches this far beyond the margin; a pose found clear by d metres
    /// lets the sweep skip checks for the next d - margin metres of hull motion (they cannot
    /// come within the margin). Fixes are checked unless carry_over proves them as below.
    double lookahead_m = 500.0;
    /// Answers that carry over, with the same events, poses and figures as every pose checked.
    /// How far a pose is from a checked one bounds how far every hull point is from its place
    /// there (the translation plus the change of placement on the hull's radius, whatever the
    /// path between), and penetration and clearance move no more than the hull's points. So: a
    /// fix found in contact with penetration p proves in contact every pose less than p from
    /// it (a hull point p deep in land, or a coast vertex p inside the hull, cannot have left),
    /// and those swept are not checked (a vessel crossing land or lying alongside); a later
    /// fix so proved is not checked either when it cannot be deeper than the contact's deepest
    /// so far (it adds nothing to its event; the checked fix stays the reference); and within
    /// the margin, a pose whose clearance is known to lie between the last checked one's plus
    /// or minus that distance, all of it under the margin and over the least clearance of the
    /// pass so far (it cannot be the pass's nearest), is not checked either (unless
    /// watch_clearance_m keeps every value); and a fix's check searches past the lookahead by
    /// the hull's motion over the next fixes, so that a later fix whose pose cannot have come
    /// within the search since gets its check's answer, nothing within it, unchecked.
    /// False: every pose swept and every fix is checked.
    bool carry_over = true;
    /// Assessment (assessment.hpp): clearance is followed up to this (metres) as it is up to
    /// the margin, and every checked pose under it is kept in TrackResult::clearance (with the
    /// pose before and after, for the crossings). 0 (default): nothing kept, as before.
    double watch_clearance_m = 0.0;
    /// A contact that begins under this speed (knots) is a vessel berthing or lying alongside,
    /// not a grounding (berthing approaches are 0.1-0.3 m/s, 0.2-0.6 kn). At most
    /// max_berthing_speed_kn.
    double berthing_speed_kn = 1.0;
    /// The largest berthing_speed_kn front ends accept (knots): berthing is done at well under
    /// 1-2 kn, and a contact that begins faster is no berthing (a larger value would call every
    /// grounding alongside).
    static constexpr double max_berthing_speed_kn = 5.0;
    /// Speed from positions and stops (MotionOptions::max_gap_s is taken from max_gap_s above).
    double speed_window_s = 120.0;
    double stop_diameter_m = 50.0;
    double stop_duration_s = 120.0;
    track::MotionOptions motion() const noexcept { return {speed_window_s, stop_diameter_m, stop_duration_s, max_gap_s}; }
    /// The poses kept for the report's `poses` layer (the hull at a fix, for replaying the
    /// voyage): a fix is kept when at least pose_interval_s have passed and the reference
    /// point has moved pose_distance_m since the last kept one, or pose_max_interval_s have
    /// passed (a ship lying still is still seen), and always at the first and last fix of
    /// each piece and at every fix where the hull's state (clear, within the margin, in
    /// contact) changes. pose_interval_s <= 0: every fix.
    double pose_interval_s = 120.0;
    double pose_distance_m = 300.0;
    double pose_max_interval_s = 900.0;
    /// Keep those poses at all (TrackResult::poses). False: none kept, their outlines never
    /// projected back to lon/lat (a run whose report has no poses layer, no picture and no
    /// debrief: `check --no-project`); everything else the same.
    bool keep_poses = true;
};

/// What an event is, decided at the first contact of each interval from what was observed.
enum class EventKind {
    grounding,          ///< contact began under way (at or over the berthing speed, not stopped), seen clear before
    alongside,          ///< contact began while stopped or under the berthing speed (moored, berthing)
    contact_at_start,   ///< already in contact at the first fix of a track or of a piece (after a gap or jump): not seen
    expected_contact,   ///< contact inside an area where contact is expected (berth, harbour, anchorage)
    close_pass,         ///< clearance under the margin, never contact
    /// Real world (evidence.hpp): a contact the traffic contradicts: the vessel sailed on
    /// through it, it exists only on the straight line between fixes minutes apart, or it is
    /// deeper than the hull could go. A place where the chart lacks water, not a grounding.
    chart_disagrees,
};
/// "grounding", "alongside", "in_contact_at_start", "expected_contact", "close_pass", "chart_disagrees".
const char* to_string(EventKind k) noexcept;
/// A contact of any kind (every kind but close_pass).
constexpr bool is_contact(EventKind k) noexcept { return k != EventKind::close_pass; }

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
    /// (a depth area under the limiting depth), a danger or a structure.
    coast::HazardKind hit = coast::HazardKind::land;
    double charted_depth_m = NAN;   ///< its charted depth (least depth of the area, danger's sounding); NaN unknown or land
    coast::DangerKind danger = coast::DangerKind::none;  ///< the danger's kind (rock, wreck, obstruction)
    std::string hit_name;           ///< the name of what was hit (coast::Hazard::name: "Pier 25"); "" when it has none

    // The evidence for the kind (contacts; for close passes the speed and heading at the least clearance).
    double speed_kn = NAN;          ///< speed at first contact: SOG of the last fix before it (else the next), else from positions
    track::SpeedSource speed_source = track::SpeedSource::none;
    bool stopped_before = false;    ///< the vessel was stopped (a stay within the stop diameter) at the last fix before contact
    double stopped_after_s = NAN;   ///< seconds from first contact until the vessel was stopped; NaN: it did not stop (in this piece)
    /// How deep the ship's reference point lies inside the hazard at first contact, metres;
    /// negative: outside it, in water, by that much (a bow touching has a large negative value).
    double reference_inside_m = NAN;
    std::uint8_t nav_status = track::nav_status_unknown;  ///< AIS navigational status at the last fix before contact
    bool reported_aground = false;  ///< a fix of the contact reported AIS status 6 "aground"
    bool orientation_unknown = false;  ///< no heading was known: contact judged by the hull's circle (at some heading)
    std::string unseen_after;       ///< contact_at_start: "track start", "gap" or "jump"
    std::string area_kind, area_name;  ///< expected_contact: the area ("berth", "harbour", "anchorage", "area") and its name
    std::string structure;          ///< the contact point is on a shore construction (S-57 SLCONS): its kind ("pier", "wharf", ...)

    /// Real world (evidence.hpp): what the vessel's own motion and the run's traffic say.
    struct Evidence {
        int grade = 0;                   ///< 1-4: how strong the evidence for the kind is (4 strongest); 0: not graded (close passes)
        std::string reason;              ///< what decided the kind, in words
        std::string disagreement;        ///< chart_disagrees: "sailed_through", "between_fixes", "deeper_than_hull"
        double start_not_before_s = NAN; ///< the last fix at which the vessel was seen clear before the contact
        double speed_before_kn = NAN, speed_before_age_s = NAN;  ///< the fix before the contact: its speed, how long before
        double speed_after_kn = NAN, speed_after_age_s = NAN;    ///< the first fix at or after it
        double stop_distance_m = NAN;    ///< from the ship at first contact to where it came to rest (NaN: it did not)
        double stay_s = NAN;             ///< how long it then lay there, across gaps
        double deceleration_kn_s = NAN;  ///< from the fix before to the first fix at rest, when both lie within the abrupt window
        std::size_t berth_stays = 0;     ///< other vessels' stays (or this one's other stays) at that place in the run
        std::size_t pieces = 1;          ///< pieces of track (after gaps) this one stay spans
        bool within_chart_tolerance = false;  ///< penetration within the chart's positional tolerance
        // What the rules read (evidence.cpp), not reported as such.
        bool seen_clear_before = false;  ///< the fix before was clear (also across a gap, not a jump)
        std::size_t stay = static_cast<std::size_t>(-1);  ///< index of the stay that follows, in TrackResult::stays
        bool prompt_stop = false;        ///< that stay begins at the first fix after the contact or within the abrupt window
        bool rests_in_contact = false;   ///< that stay begins before the vessel is next seen clear (across gaps)
        bool bracket_dense = false;      ///< the fixes around the contact both lie within the abrupt window of it
        bool between_fixes_only = false; ///< no fix lies in the contact, and the fixes around it are far apart
        bool left_contact = false;       ///< the contact ended before the track did (the vessel came clear again)
        bool moored_at_stay = false;     ///< AIS status moored or at anchor during the stay
        bool aground_at_stay = false;    ///< AIS status aground during the stay
        double gap_distance_m = NAN;     ///< from the fix before to the first fix after
    } evidence;
};

/// Figures of one swept track.
struct TrackSummary {
    std::string id, name, file;
    std::string hull;                 ///< "ship file", "--dims" or "AIS dimensions a,b,c,d (their source)"
    double draught_m = NAN;           ///< the vessel's own draught (AIS, vessels file), NaN when not known
    std::string draught_source;       ///< where it came from
    int ship_type = -1;               ///< the vessel's AIS ship type (track/ship_type.hpp), -1 when not known
    std::string ship_type_source;     ///< where it came from
    /// The limiting depth the track was checked at (metres; NaN: land only) and where it came
    /// from (grid::to_string(DepthPlan::Source): vessel_draught, ship_draught, hazard_depth,
    /// grid_default, land_only).
    double limiting_depth_m = NAN;
    std::string limiting_depth_source;
    std::size_t fixes = 0;            ///< fixes in the track
    std::size_t uncovered_fixes = 0;  ///< fixes whose hull is (partly) outside the coastline's area
    std::size_t segments = 0;         ///< pieces after splitting at gaps
    std::size_t gaps = 0;             ///< gaps longer than max_gap_s
    std::size_t poses = 0;            ///< poses checked (fixes and swept poses between them)
    std::size_t groundings = 0, close_passes = 0;
    std::size_t alongside = 0, contacts_at_start = 0, expected_contacts = 0;
    std::size_t chart_disagreements = 0;  ///< real world: contacts the traffic contradicts (EventKind::chart_disagrees)
    double cadence_s = NAN;           ///< the track's own fix interval: the median time between fixes
    double hull_length_m = NAN;       ///< the length of the hull it was checked with
    std::vector<track::WildFix> wild_fixes;  ///< fixes dropped as outliers (never swept)
    std::size_t jumps = 0;            ///< persistent jumps (each starts a new piece)
    std::size_t unknown_heading_fixes = 0;  ///< fixes checked by the hull's circle: no heading known yet
    double min_clearance_m = INFINITY;  ///< least clearance over covered poses (0 on grounding; INFINITY: never within the search limit)
    double start_s = NAN, end_s = NAN;
    double distance_m = 0;            ///< length sailed (local metres, gaps excluded)
    std::vector<std::vector<geo::LonLat>> lines;  ///< the swept pieces, for the report's tracks layer
    std::vector<std::vector<double>> line_times;  ///< the times of the fixes of `lines` (epoch seconds), aligned with them
    std::string exercise;             ///< exercise mode: the track's exercise (exercise.hpp)
    Role role = Role::trainee;        ///< exercise mode: trainee or target
};

/// Adds a contact of kind `k` to the summary's count of its kind (close passes are counted
/// where they are made).
void count_contact(TrackSummary& summary, EventKind k) noexcept;

/// The hull at a fix, kept for the report's `poses` layer (thinned: SweepOptions::pose_interval_s).
struct Pose {
    double time_s = 0;
    double until_s = 0;             ///< time of the next kept pose of the piece (its own time for the last)
    double speed_kn = NAN;          ///< the speed used at the fix (SOG, else from positions)
    double heading_deg = NAN;       ///< the heading the hull was placed at; NaN: unknown (the hull's circle)
    double clearance_m = INFINITY;  ///< the detector's clearance at the fix (0 in contact; INFINITY: beyond the search limit)
    bool contact = false;           ///< the hull touched land or a hazard at the fix
    bool covered = true;            ///< the hull lay inside the coastline's area
    std::size_t fix_index = 0, fix_line = 0;
    std::vector<geo::LonLat> hull;  ///< hull outline as drawn (closed ring): its corners kept by the simplification of sweep/pose_outline.hpp
};

/// A checked pose's clearance, kept when SweepOptions::watch_clearance_m asks for it.
struct ClearanceSample {
    double time_s = 0;
    double clearance_m = INFINITY;  ///< 0 in contact; INFINITY: beyond the search limit
    geo::LonLat ship;               ///< reference point
    bool covered = true;            ///< the hull lay inside the coastline's area
    /// Not joined to the sample before: the first of a piece of track, or the one after poses
    /// that were not kept (clearance over the watch between them).
    bool after_break = false;
};

/// A stay: consecutive fixes of one vessel lying within a small box (evidence.hpp), across
/// gaps but not across a jump.
struct Stay {
    std::size_t first = 0, last = 0;  ///< fix indices
    double start_s = 0, end_s = 0;
    geo::XY local;                    ///< the first fix, local metres
    bool moored = false, aground = false;  ///< AIS status moored / at anchor, aground at a fix of it
    /// Which visit of the vessel it belongs to: stays of one visit follow each other without
    /// the vessel going away (further than the berth radius) between them (a stay broken by
    /// GPS jitter or a shift along the quay is one visit).
    std::size_t visit = 0;
};

struct TrackResult {
    TrackSummary summary;
    std::vector<Event> events;
    /// Real world (evidence.hpp): the track's stays and the local positions of fixes under way
    /// whose reference point lies on charted land (the run's traffic learns from both).
    std::vector<Stay> stays;
    std::vector<geo::XY> over_land;
    std::vector<Pose> poses;  ///< in time order
    /// SweepOptions::watch_clearance_m > 0: the checked poses under it and their neighbours, in time order.
    std::vector<ClearanceSample> clearance;
};

/// Anything that checks a pose: the grid Detector, or the brute-force traversal in tests.
class PoseChecker {
public:
    virtual ~PoseChecker() = default;
    virtual check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const = 0;
    virtual const hull::Hull& hull() const = 0;
    /// The grid whose polylines Contact::polyline indexes (what a contact hit), if any.
    virtual const grid::CoastGrid* grid() const { return nullptr; }
    /// How deep local point `p` lies inside land or a hazard (metres; negative: in water, by
    /// its distance to the nearest coast, at most `max_m`); NaN when not known.
    virtual double inside_depth(geo::XY /*p*/, double /*max_m*/) const { return NAN; }
    /// Contact::covered of check(pose, ...), possibly without the check.
    virtual bool covered(const check::LocalPose& pose) const {
        return check(pose, {.max_clearance_m = 0, .want_penetration = false, .want_polyline = false}).covered;
    }
};

class DetectorChecker final : public PoseChecker {
public:
    /// At the grid's default limiting depth (check::Detector(grid, hull)).
    DetectorChecker(const grid::CoastGrid& grid, const hull::Hull& hull) : m_detector(grid, hull) {}
    /// At the vessel's limiting depth (none: land only).
    DetectorChecker(const grid::CoastGrid& grid, const hull::Hull& hull, std::optional<double> limiting_depth_m)
        : m_detector(grid, hull, limiting_depth_m) {}
    check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const override {
        return m_detector.check(pose, options);
    }
    const hull::Hull& hull() const override { return m_detector.hull(); }
    const grid::CoastGrid* grid() const override { return &m_detector.grid(); }
    double inside_depth(geo::XY p, double max_m) const override {
        const double d = m_detector.nearest_coast(p, max_m, nullptr);
        return m_detector.grid().is_land(p) ? d : -d;
    }
    bool covered(const check::LocalPose& pose) const override { return m_detector.covers(pose); }

private:
    check::Detector m_detector;
};

/// What the sweep may use besides the track and the hull.
struct SweepContext {
    /// Checks poses whose heading is unknown (HeadingSource::none): the hull's circle, a hull
    /// that holds the ship at any heading (see circle_hull). Null: the hull at heading 0.
    const PoseChecker* unknown_heading = nullptr;
    /// Areas where contact is expected (berths, harbours, anchorages) and shore constructions.
    const coast::ExpectedAreas* areas = nullptr;
    /// When set, receives the fixes' local positions as the sweep projected them (one per fix;
    /// gather_evidence takes them instead of projecting every fix again).
    std::vector<geo::XY>* positions = nullptr;
};

/// The hull's circle: a 36-gon circumscribed about the circle of the hull's radius around the
/// reference point, which holds the hull at every heading. Contact of the circle means contact
/// at some heading; its clearance is the least clearance over all headings.
hull::Hull circle_hull(const hull::Hull& hull);

/// Sweeps `track` (wild fixes dropped, motion and headings resolved) with `checker` in `frame`.
/// A pose equal to the one checked just before (a vessel standing still) is not checked again:
/// the last answer stands. Pieces of track split at gaps over max_gap_s and at Fix::jump_before.
TrackResult sweep_track(const track::Track& track, const geo::LocalFrame& frame, const PoseChecker& checker,
                        const SweepOptions& options, const SweepContext& context = {});

}  // namespace shoal::audit
