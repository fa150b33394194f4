#pragma once
/// A whole audit: read every track file, sweep every track (in parallel), gather the results
/// in a deterministic order (input order, then track order in the file), so the report does
/// not depend on the number of jobs.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <shoal/exercise/assessment.hpp>
#include <shoal/exercise/colreg.hpp>
#include <shoal/exercise/encounters.hpp>
#include <shoal/sweep/evidence.hpp>
#include <shoal/exercise/exercise.hpp>
#include <shoal/shard/shard.hpp>
#include <shoal/sweep/sweep.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/track/reader.hpp>
#include <shoal/track/vessels_table.hpp>

namespace shoal::audit {

struct AuditOptions {
    SweepOptions sweep;
    /// Whether the chart is the world (a simulator exercise) or a model of it (real traffic:
    /// the vessel's motion and the run's traffic decide a contact's kind, evidence.hpp). The
    /// library's default is the simulator's; `shoal check` and the Python module choose real
    /// outside exercise mode.
    World world = World::simulated;
    EvidenceOptions evidence;  ///< the real world's rules
    unsigned jobs = 0;  ///< worker threads; 0 = all cores
    track::ReadOptions read;
    /// Called on the calling thread about ten times a second: fixes swept so far, fixes in all.
    std::function<void(std::size_t done, std::size_t total)> progress;
    /// Exercise mode: the tracks of the run are one exercise; find ship-to-ship encounters.
    bool encounters = false;
    EncounterOptions encounter;  ///< step and max gap are taken from `sweep`
    /// Exercise mode: how tracks are grouped into exercises (exercise.hpp); encounters are
    /// found within an exercise only. ExerciseBy::column takes each track's Track::exercise,
    /// read from the column read.exercise_column (which run_audit requires then).
    ExerciseBy exercise_by = ExerciseBy::run;
    /// Exercise mode: roles of tracks (exercise.hpp), with the role column's values
    /// (read.role_column, Track::role) as audit::role_of combines them; neither: every track is
    /// a trainee. Pairs of two targets are not reported. Must outlive the run.
    const Roles* roles = nullptr;
    /// Exercise mode: scored criteria (assessment.hpp); null: not assessed. Needs `encounters`;
    /// the sweep then follows clearance up to its largest land clearance limit. Must outlive the run.
    const Assessment* assessment = nullptr;
    /// Exercise mode: COLREG situations of the pairs that come within colreg.range_m (colreg.hpp).
    ColregOptions colreg;
    /// Exercise mode: each ship lists at most this many other ships, the ones it came closest
    /// to (worst_pairs.hpp), with their collisions, close quarters, closest approach and
    /// situation; the others are counted (AuditResult::unlisted), not listed. 0: no limit.
    std::size_t max_encounters_per_ship = 20;
    track::WildFixOptions wild;  ///< what makes a fix an outlier
    /// Areas where contact is expected, and shore constructions; may be null. Must outlive the run.
    const coast::ExpectedAreas* areas = nullptr;
    /// Static data by vessel id (track::read_vessels: name, A,B,C,D, draught), may be null. What
    /// it gives wins over what the track's own file says (the analyst's table over what a
    /// vessel broadcast); what it lacks, the track keeps.
    const std::map<std::string, track::VesselInfo>* vessels = nullptr;
    /// Limiting depth for every vessel (`--hazard-depth`); none: each vessel's own
    /// (grid::plan_vessel_depth: its draught + ukc_m, else the default hull's draught + ukc_m,
    /// else the grid's default, else land only).
    std::optional<double> hazard_depth_m;
    std::optional<double> ukc_m;  ///< under-keel clearance added to a draught (`--ukc`; none: 0)
    /// Only the tracks of this shard (shard_of(shard_key(id, exercise in exercise mode)) == shard.index) are
    /// audited; every file is still read (one vessel in several files is one track first).
    /// count 0: every track.
    Shard shard;
};

/// One input file: how it read.
struct FileResult {
    std::string file;
    std::string format;
    track::ReadReport read;
    std::string error;  ///< non-empty when the file could not be read at all (the batch went on)
    std::size_t tracks = 0;
    /// The file's size and fingerprint when already known (read_partition: taken where the file
    /// was read); size -1 and "": the report computes them from the file when it needs them.
    long long size = -1;
    std::string fingerprint{};
};

/// A track that could not be audited (the batch went on).
struct TrackError {
    std::string file, track, message;
};

struct AuditResult {
    std::vector<TrackResult> tracks;
    std::vector<FileResult> files;
    std::vector<TrackError> errors;
    std::size_t fixes = 0, poses = 0, uncovered_fixes = 0, skipped_rows = 0;
    std::size_t groundings = 0, close_passes = 0;
    std::size_t alongside = 0, contacts_at_start = 0, expected_contacts = 0;
    std::size_t chart_disagreements = 0;  ///< real world: contacts the traffic contradicts
    World world = World::simulated;       ///< the world the kinds were decided in
    double chart_tolerance_m = NAN;       ///< EvidenceOptions::chart_tolerance_m used
    /// Real world: what the run's traffic taught (learned berths, water the chart lacks),
    /// learned from every track read (all shards alike).
    std::vector<LearnedPlace> places;
    std::size_t wild_fixes = 0, jumps = 0, unknown_heading_fixes = 0;
    /// What the user should hear about the run as a whole: most fixes uncovered (swapped
    /// latitude and longitude?), tracks broken into lone fixes by jumps.
    std::vector<std::string> warnings;
    double first_fix_s = NAN, last_fix_s = NAN;
    double read_s = 0, sweep_s = 0;  ///< wall-clock seconds of the two phases
    /// Exercise mode: encounters between the audited tracks; ShipAt::track and
    /// ClosestApproach::a/b index `tracks` above.
    bool has_encounters = false;
    EncounterResult encounters;
    /// Exercise mode: every pair of an exercise (not two targets) that came within
    /// AuditOptions::colreg.range_m, by (a, b) (indices in `tracks`). Each also has an entry in
    /// encounters.approaches: one with a NaN clearance when the pair never came within the
    /// hull-to-hull threshold (the time, distance and positions are then those of the least
    /// distance between the reference points).
    std::vector<ColregEncounter> situations;
    std::size_t exercises = 0;  ///< exercise mode: exercises with at least one audited track
    std::size_t collisions = 0, close_quarters = 0;  ///< every one found, listed or not
    /// Exercise mode: what AuditOptions::max_encounters_per_ship left out of `encounters` and
    /// `situations` (counted in `collisions`, `close_quarters` and situations_found).
    struct Unlisted {
        std::size_t pairs = 0, collisions = 0, close_quarters = 0, situations = 0;
        std::size_t approached = 0;  ///< of `pairs`, those that came within the hull-to-hull threshold
    } unlisted;
    std::size_t situations_found() const noexcept { return situations.size() + unlisted.situations; }
    double encounters_s = 0;
    /// `--assess`: the trainees' scores and their breaches (has_assessment false: not asked).
    bool has_assessment = false;
    AssessmentResult assessment;
    /// The shard audited (count 0: the whole run), and for merging shards back in the order of
    /// one run: each track's (and each failed track's) position among all the tracks read, in
    /// file order before sharding; aligned with `tracks` and `errors`.
    Shard shard;
    std::vector<std::size_t> track_positions, error_positions;
};

/// The tracks of `inputs` (files or folders, see track::expand_inputs) read in parallel on
/// `jobs` threads (0: all cores). A file that cannot be read (InputError) is reported in its
/// FileResult and the others are read; any other failure is thrown.
struct ReadResult {
    std::vector<FileResult> files;           ///< in input order
    std::vector<track::PackedTrack> tracks;  ///< every file's tracks, in file order
    std::vector<std::string> warnings;       ///< files given twice, folder entries skipped
    double read_s = 0;                       ///< wall-clock seconds
};
ReadResult read_inputs(const std::vector<std::string>& inputs, const track::ReadOptions& options, unsigned jobs = 0);

/// Audits tracks: outliers dropped, motion and headings resolved, each swept with its own AIS
/// hull (Track::dims) or `default_hull`, whose origin `hull_label` names ("ship file",
/// "--dims ..."); in exercise mode, the encounters between them. A track whose input is bad
/// (InputError) is listed in AuditResult::errors and the others are audited; any other failure
/// (a bug, a GEOS or PROJ failure) is thrown once every worker has finished.
AuditResult audit_tracks(std::vector<track::Track> tracks, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                         const std::string& hull_label, const AuditOptions& options);

/// The same for tracks read by read_inputs (unpacked one at a time, freed once swept); the
/// result carries the files read.
AuditResult audit_tracks(ReadResult read, const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                         const AuditOptions& options);

/// A track made ready for its sweep, as audit_tracks does: the static data of
/// AuditOptions::vessels joined, wild fixes dropped (returned), motion and headings resolved.
std::vector<track::WildFix> prepare_track(track::Track& t, const AuditOptions& options);

/// A track made ready for its traffic only (sweep::traffic_of, of another shard's or another
/// partition's vessel): prepare_track without the headings, which the traffic does not read
/// (it reads positions, times, jumps, navigational status, the speed used and the stops), so
/// its traffic is that of prepare_track's, for less work.
void prepare_traffic(track::Track& t, const AuditOptions& options);

/// read_inputs, then audit_tracks.
AuditResult run_audit(const std::vector<std::string>& inputs, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                      const std::string& hull_label, const AuditOptions& options);

}  // namespace shoal::audit
