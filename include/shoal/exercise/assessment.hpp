#pragma once
/// Scored criteria for the instructor's debrief: an assessment file (JSON,
/// schemas/assessment.schema.json) lists criteria, each with a limit and a penalty; assess()
/// turns an exercise-mode audit into a score per trainee and the breaches behind it.
/// Targets are never scored (their groundings are reported as events, as ever).
///
/// What each kind measures, and where from:
/// - land_clearance: the hull-to-land (or hazard) clearance the sweep found along the track
///   (SweepOptions::watch_clearance_m makes it follow clearance up to the largest limit);
///   between two checked poses (at most `step_m` of hull motion apart near the limit) the
///   crossing of the limit is interpolated linearly.
/// - under_keel_clearance: charted depth under the ship's reference point minus the vessel's
///   draught (its own, else the default ship's; a vessel with neither is not assessed, and
///   said so); the depth is the least depth of the depth areas and dangers of the grid that
///   hold the point (land: 0), sampled every `step_m` along the track, the crossings bisected.
///   Water the grid holds no depth area for is deeper than every limit.
/// - cpa: the distance between the reference points of the trainee and every other ship of
///   its exercise, both moving straight between fixes (exact: the least distance and the
///   crossings of the limit are solved, not sampled); no ship is paired across a gap.
/// - speed_limit, no_entry: the track's straight segments between fixes intersected with the
///   area by GEOS (in local metres), entry and exit times interpolated along the segment;
///   speed over ground (SOG, else from positions) linear between fixes.
/// - close_quarters_time: each close-quarters encounter (hull-to-hull clearance under the ship
///   margin, encounters.hpp) of the trainee lasting longer than `limit` seconds.
/// - colreg: the trainee's conduct under COLREG rules 8 and 13-17 in every situation with
///   another ship of its exercise (colreg_conduct.hpp, with the criterion's ConductOptions):
///   each rule not met is a breach (Breach::rule), charged `penalty` once. No limit; a breach's
///   value is the closest approach in that situation (m) against ConductOptions::cpa_m.
///
/// A breach is one contiguous interval over the limit. Its penalty: `penalty` once (per
/// breach), times the seconds it lasted (per second; close_quarters_time: the seconds over
/// the time allowed), or times how far beyond the limit its worst moment was (per metre;
/// per knot for a speed limit).

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <shoal/exercise/colreg_conduct.hpp>
#include <shoal/exercise/encounters.hpp>
#include <shoal/sweep/sweep.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::geo { class LocalFrame; }
namespace shoal::grid { class CoastGrid; }
namespace shoal::track { struct Track; }

namespace shoal::audit {

enum class CriterionKind {
    land_clearance,       ///< clearance of the hull to land or hazards at least `limit` metres
    under_keel_clearance, ///< under-keel clearance at least `limit` metres
    cpa,                  ///< closest approach to another ship of the exercise at least `limit` metres
    speed_limit,          ///< speed over ground inside `area` at most `limit` knots
    no_entry,             ///< never inside `area`
    close_quarters_time,  ///< at most `limit` seconds in close quarters (per encounter)
    colreg,               ///< conduct under COLREG rules 8 and 13-17 (no limit; per breach)
};
const char* to_string(CriterionKind k) noexcept;
/// The unit of a criterion's limit and of its breaches' values: "m", "kn" or "s".
const char* unit_of(CriterionKind k) noexcept;

/// How a breach is charged: `penalty` once per breach, per second over the limit, or per metre
/// (per knot for a speed limit) beyond it at the worst moment.
enum class PenaltyPer { breach, second, metre };
const char* to_string(PenaltyPer p) noexcept;

struct Criterion {
    std::string id;  ///< as the file names it (or "<kind>-<n>", n from 1 in file order), unique
    CriterionKind kind = CriterionKind::land_clearance;
    double limit = 0;   ///< unit_of(kind); no_entry: 0
    double penalty = 0; ///< >= 0, at most max_penalty
    PenaltyPer per = PenaltyPer::breach;
    /// The largest penalty a file may give (a score stays a finite number however long or far
    /// a breach goes).
    static constexpr double max_penalty = 1e6;
    /// The widest area (degrees of longitude or latitude): areas are scored in the run's local
    /// metres, true over a few hundred kilometres.
    static constexpr double max_area_span_deg = 5;
    /// The largest limit of a criterion of kind `k`, in unit_of(k): 10 km of clearance to land
    /// (the sweep searches that far around every pose), 2 km under the keel, 100 km of CPA,
    /// 100 kn, a week in close quarters.
    static double max_limit(CriterionKind k) noexcept;
    std::vector<geo::LonLat> area;  ///< speed_limit and no_entry: the polygon's outer ring, lon/lat, closed
    std::string area_name;
    ConductOptions colreg;  ///< colreg: how each rule is read (the file's parameters, else the defaults)
};

struct Assessment {
    std::vector<Criterion> criteria;
    /// `pass_mark`: a trainee passes when her penalty is at most this (NaN: no pass mark).
    double pass_mark = NAN;
    std::string source;  ///< the file read (load), or the name parse() was given

    /// The largest assessment file read (16 MiB); a larger one, or an endless source such as
    /// /dev/zero, is refused at that limit.
    static constexpr std::size_t max_file_bytes = std::size_t{16} << 20;

    /// Reads an assessment file (a file, a pipe, standard input `-`; gzip read decompressed);
    /// throws InputError naming the file and the criterion (index and id) that is wrong.
    static Assessment load(const std::string& path);
    /// Parses the JSON text of an assessment file (`source` names it in messages).
    static Assessment parse(const std::string& text, const std::string& source);

    /// The largest land_clearance limit (metres; 0: none): what the sweep must follow
    /// clearance up to (SweepOptions::watch_clearance_m).
    double watch_clearance_m() const noexcept;
};

/// One breach of one criterion by one trainee: from `start_s` to `end_s` (epoch seconds; equal
/// for an instantaneous one), at its worst moment `worst_s` at (lon, lat) with `value` against `limit`.
struct Breach {
    std::string exercise, track, criterion;
    std::size_t track_index = 0;  ///< the trainee's index in AuditResult::tracks
    CriterionKind kind = CriterionKind::land_clearance;
    double start_s = NAN, end_s = NAN, worst_s = NAN;
    double lon = NAN, lat = NAN;
    double value = NAN, limit = NAN;  ///< unit_of(kind); no_entry: seconds inside against 0
    double penalty = 0;
    std::string other;   ///< cpa, close_quarters_time, colreg: the other ship's track id
    std::string rule;    ///< colreg: the rule not met, "8", "13" ... "17" (else empty)
    std::string asked;   ///< what the criterion (for colreg: the rule) asked, in words
    std::string did;     ///< what the ship did, in words
    std::string detail;  ///< one line a person reads
};

/// A trainee's conduct in one situation with another ship, as a `colreg` criterion read it:
/// which rules applied and whether each was met (met or not: the debrief lists every situation,
/// not only the breaches).
struct ConductRecord {
    std::string exercise, track, criterion;
    std::size_t track_index = 0;  ///< the trainee's index in AuditResult::tracks
    std::string other;            ///< the other ship's track id
    std::size_t other_index = 0;  ///< its index in AuditResult::tracks
    std::string situation;        ///< to_string(Situation) at the start: "head-on", "crossing", "overtaking"
    std::string role;             ///< "give-way", "stand-on" or "" (no duty)
    double start_s = NAN;         ///< when the situation began (the pair came within range)
    double closest_m = NAN;       ///< the closest approach between the reference points
    std::vector<std::string> rules;     ///< the rules that applied ("13" ... "17", "8"); empty: none
    std::vector<std::string> breached;  ///< those not met (each a Breach), in Conduct::breaches' order
    std::string did;              ///< what the ship did (Conduct::did)
};

/// A trainee's score: the sum of the penalties of her breaches (0: none).
struct Score {
    std::string exercise, track;
    double penalty = 0;
    std::size_t breaches = 0;
    std::size_t track_index = 0;  ///< index in AuditResult::tracks
    std::vector<double> by_criterion = {};  ///< the penalty per criterion, in AssessmentResult::criteria's order
    /// Against the pass mark: penalty <= pass_mark (false when there is none).
    bool passed = false;
};

struct AssessmentResult {
    std::vector<Criterion> criteria;  ///< the assessment's, as read
    double pass_mark = NAN;           ///< Assessment::pass_mark
    std::string source;               ///< Assessment::source
    std::vector<Score> scores;      ///< every trainee, in the order of AuditResult::tracks
    /// In the order of AuditResult::tracks (the trainee's), then by start, then criterion
    /// (file order), then the other ship's track order.
    std::vector<Breach> breaches;
    /// Every `colreg` criterion's reading of every situation of every trainee, breached or not:
    /// in the order of AuditResult::tracks (the trainee's), then criterion (file order), then
    /// the situation's start, then the other ship's track order.
    std::vector<ConductRecord> conduct;
    std::vector<std::string> warnings;  ///< what could not be assessed (a vessel without a draught)
};

/// What assess() needs besides the audit: the swept tracks (resolved motion), aligned with
/// `result.tracks` (null: the track is not assessed), and how the run was swept.
struct AssessInput {
    const std::vector<TrackResult>& swept;  ///< every track of the run as swept (AuditResult::tracks)
    const EncounterResult& encounters;     ///< the run's encounters (AuditResult::encounters)
    std::vector<const track::Track*> tracks;
    const grid::CoastGrid& grid;
    const geo::LocalFrame& frame;
    double default_draught_m = 0;  ///< the default ship's draught (0: none)
    double step_m = 5.0;           ///< under-keel clearance samples this far apart
    double max_gap_s = 600.0;      ///< a longer gap between fixes: nothing is assessed across it
    double time_tolerance_s = 0.01;
    /// A trainee's cpa breaches are listed against the ships it came closest to, at most this
    /// many (AuditOptions::max_encounters_per_ship); its score counts every breach. 0: no limit.
    std::size_t max_others_per_trainee = 0;
};

/// Scores every trainee of `in.result` (exercise mode) against `assessment`. Land clearance
/// comes from TrackResult::clearance (swept with watch_clearance_m() or more), close quarters
/// from the encounters; the rest from `in.tracks`.
AssessmentResult assess(const Assessment& assessment, const AssessInput& in);

}  // namespace shoal::audit
