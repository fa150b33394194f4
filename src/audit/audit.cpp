#include <shoal/audit/audit.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include <shoal/audit/partition.hpp>
#include "exercise/worst_pairs.hpp"
#include <shoal/grid/limiting_depth.hpp>
#include "track/merge.hpp"
#include <shoal/track/vessels_table.hpp>
#include <shoal/util/error.hpp>

#include "util/parallel.hpp"
#include "read_files.hpp"
#include "run_totals.hpp"

namespace shoal::audit {

namespace {

using Clock = std::chrono::steady_clock;

using detail::parallel_for;
using detail::thread_count;

/// The first exception a worker met that is not bad input (a bug, a library failure): the
/// workers go on, and it is thrown again on the calling thread once they have all finished.
class FirstFailure {
public:
    void keep(std::exception_ptr e) {
        const std::lock_guard lock(m_mutex);
        if (!m_first) m_first = std::move(e);
    }
    void rethrow() {
        if (m_first) std::rethrow_exception(m_first);
    }

private:
    std::mutex m_mutex;
    std::exception_ptr m_first;
};

}  // namespace

void read_track_files(const std::vector<std::string>& files, const track::ReadOptions& options, unsigned jobs,
                      std::vector<track::PackedTrackFile>& read, std::vector<FileResult>& results,
                      const std::function<void(std::size_t)>& after) {
    read.resize(files.size());
    results.resize(files.size());
    FirstFailure failure;
    const unsigned threads = thread_count(jobs);
    const std::size_t spare = threads > files.size() ? threads - files.size() : 0;
    parallel_for(
        files.size(), threads,
        [&](std::size_t k, unsigned) {
            FileResult& fr = results[k];
            fr.file = files[k];
            try {
                try {
                    track::ReadOptions per_file = options;
                    if (k < spare) per_file.threads = std::max(per_file.threads, 2u);
                    read[k] = track::read_tracks_packed(files[k], per_file);
                    fr.format = read[k].format;
                    fr.read = read[k].report;
                    fr.tracks = read[k].tracks.size();
                } catch (const InputError& e) {  // bad input costs this file; anything else is a bug
                    fr.error = e.what();
                } catch (const std::bad_alloc&) {
                    fr.error = files[k] + ": out of memory reading it";
                }
                if (after) after(k);
            } catch (...) {
                failure.keep(std::current_exception());
            }
        },
        {});
    failure.rethrow();
}

namespace {

/// Tracks to audit, taken one by one (a packed track is unpacked when taken, then freed).
struct TrackSource {
    std::size_t count = 0;
    std::function<std::size_t(std::size_t)> fixes;  ///< fixes of track k, for the progress
    std::function<track::Track(std::size_t)> take;  ///< track k, once
    std::function<std::size_t(std::size_t)> position;  ///< position of track k among the run's (null: k)
    /// The run's other tracks (another shard's): not audited, but their traffic is evidence
    /// in the real world. take_other(k) gives track k of them, once.
    std::size_t others = 0;
    std::function<track::Track(std::size_t)> take_other;
    /// The traffic of the run's other tracks computed elsewhere (audit_partition: by the tasks of
    /// the other partitions), learned from after `others`; null: none.
    const std::vector<TrackResult>* traffic = nullptr;
};

AuditResult audit(const TrackSource& source, const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                  const AuditOptions& options);

/// A packed track, unpacked for its sweep and its packed fixes freed (taken once).
track::Track take(track::PackedTrack& packed) {
    track::Track t = packed.unpack();
    packed.release_fixes();
    return t;
}

/// `result` with what reading found: the files, the read time, the rows skipped, the read's
/// warnings first. (`read` by reference: its tracks are still being swept while the call's
/// other argument, the audit, is evaluated.)
AuditResult with_read(AuditResult result, ReadResult& read) {
    result.files = std::move(read.files);
    result.read_s = read.read_s;
    for (const auto& f : result.files) result.skipped_rows += f.read.skipped;
    result.warnings.insert(result.warnings.begin(), read.warnings.begin(), read.warnings.end());
    return result;
}

/// A vessels table's static data over the track's own: name, A,B,C,D, draught, ship type.
void join_static_data(track::Track& t, const std::map<std::string, track::VesselInfo>& vessels) {
    auto it = vessels.find(t.id);
    if (it == vessels.end()) it = vessels.find(track::integral_id(t.id));  // a track's id written 230035780.0
    if (it == vessels.end()) return;
    const track::VesselInfo& v = it->second;
    if (!v.name.empty()) t.name = v.name;
    if (v.dims && hull::Hull::plausible(*v.dims)) {  // a ship over 500 m by 100 m is a typo: the track's own stay
        t.dims = v.dims;
        t.dims_source = v.dims_source.empty() ? v.source : v.dims_source;
    }
    if (std::isfinite(v.draught_m)) {
        t.draught_m = v.draught_m;
        t.draught_source = v.draught_source.empty() ? v.source : v.draught_source;
    }
    if (v.ship_type > 0) {
        t.ship_type = v.ship_type;
        t.ship_type_source = v.ship_type_source.empty() ? v.source : v.ship_type_source;
    }
}

/// A track's hull length for its traffic: its AIS dimensions', else the default hull's.
double traffic_length(const track::Track& t, const hull::Hull& default_hull) {
    return t.dims && hull::Hull::plausible(*t.dims) ? t.dims->a + t.dims->b : default_hull.length();
}

std::string dims_label(const hull::Dimensions& d) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "AIS dimensions %g,%g,%g,%g", d.a, d.b, d.c, d.d);
    return buf;
}

}  // namespace

namespace {

/// prepare_track and prepare_traffic: the headings resolved or not.
std::vector<track::WildFix> prepare_for(track::Track& t, const AuditOptions& options, bool headings) {
    if (options.vessels) join_static_data(t, *options.vessels);
    track::WildFixOptions wo = options.wild;
    wo.max_gap_s = options.sweep.max_gap_s;
    std::vector<track::WildFix> wild = track::drop_wild_fixes(t, wo);
    track::resolve_motion(t, options.sweep.motion());
    if (headings) track::resolve_headings(t, 0.5, options.sweep.max_gap_s, options.world != World::real);
    return wild;
}

}  // namespace

std::vector<track::WildFix> prepare_track(track::Track& t, const AuditOptions& options) { return prepare_for(t, options, true); }

void prepare_traffic(track::Track& t, const AuditOptions& options) { prepare_for(t, options, false); }

namespace {

/// read_inputs, one vessel met in several files merged into one track within one exercise of
/// `exercise_by` only: by file, never; by folder, within a folder; by column, within the
/// column's value.
ReadResult read_exercises(const std::vector<std::string>& inputs, const track::ReadOptions& options, unsigned jobs, ExerciseBy exercise_by) {
    ReadResult result;
    const std::vector<std::string> files = track::expand_inputs(inputs, &result.warnings);
    // 1. Read every file (a file that cannot be read is reported; the batch goes on). Fixes
    // stay packed (32 bytes each) until their track is swept, and are freed after it.
    const auto t0 = Clock::now();
    std::vector<track::PackedTrackFile> read(files.size());
    read_track_files(files, options, jobs, read, result.files);
    for (auto& f : read)
        for (auto& t : f.tracks) result.tracks.push_back(std::move(t));
    // One vessel in several files is one track, within an exercise only.
    const auto exercise_of = [&](const track::PackedTrack& t) {
        return exercise_by == ExerciseBy::run ? std::string() : exercise_key(exercise_by, t.file, t.exercise);  // "": the message names none
    };
    for (std::string& m : track::merge_same_vessels(result.tracks, exercise_of)) result.warnings.push_back(std::move(m));
    result.read_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return result;
}

}  // namespace

ReadResult read_inputs(const std::vector<std::string>& inputs, const track::ReadOptions& options, unsigned jobs) {
    return read_exercises(inputs, options, jobs, ExerciseBy::run);
}

AuditResult run_audit(const std::vector<std::string>& inputs, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                      const std::string& hull_label, const AuditOptions& options) {
    if (options.exercise_by == ExerciseBy::column && options.read.exercise_column.empty())
        throw UsageError("AuditOptions::exercise_by column needs the column's name (ReadOptions::exercise_column)");
    // In exercise mode a vessel of two exercises stays two tracks (read_inputs would merge them).
    const ExerciseBy by = options.encounters ? options.exercise_by : ExerciseBy::run;
    return audit_tracks(read_exercises(inputs, options.read, options.jobs, by), grid, default_hull, hull_label, options);
}

AuditResult audit_tracks(ReadResult read, const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                         const AuditOptions& options) {
    std::vector<track::PackedTrack>& packed = read.tracks;
    // Every entry of the exercise file names a track of the run (all shards': every track read).
    if (options.encounters && options.roles) {
        std::vector<std::pair<std::string, std::string>> ids;
        for (const auto& t : packed) ids.emplace_back(t.id, exercise_key(options.exercise_by, t.file, t.exercise));
        options.roles->check_entries_name_tracks(ids);
    }
    // A vessels table none of whose vessels is a track read (all shards': every track) is said.
    if (options.vessels) {
        std::vector<std::string> ids;
        for (const auto& t : packed) ids.push_back(t.id);
        for (std::string& w : track::unmatched_vessels_tables(*options.vessels, ids)) read.warnings.push_back(std::move(w));
    }
    // --shard: the tracks of this shard, by their position among all the tracks read.
    std::vector<std::size_t> chosen;
    for (std::size_t k = 0; k < packed.size(); ++k)
        if (!options.shard.active() ||
            shard_of(shard_key(packed[k].id, options.encounters ? std::optional<std::string>(exercise_key(options.exercise_by, packed[k].file, packed[k].exercise))
                                                                : std::nullopt),
                     options.shard.count) == options.shard.index)
            chosen.push_back(k);
    // The others are never swept. In the real world their traffic is evidence (every shard
    // learns from every track read, as one run does); else they are freed now.
    std::vector<std::size_t> others;
    for (std::size_t k = 0, c = 0; k < packed.size(); ++k) {
        if (c < chosen.size() && chosen[c] == k) ++c;
        else if (options.world == World::real) others.push_back(k);
        else packed[k].release_fixes();
    }
    TrackSource source{chosen.size(), [&](std::size_t k) { return packed[chosen[k]].size(); },
                       [&](std::size_t k) { return take(packed[chosen[k]]); }, [&](std::size_t k) { return chosen[k]; },
                       others.size(), [&](std::size_t k) { return take(packed[others[k]]); }};
    return with_read(audit(source, grid, default_hull, hull_label, options), read);
}

AuditResult audit_tracks(std::vector<track::Track> tracks, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                         const std::string& hull_label, const AuditOptions& options) {
    if (options.encounters && options.roles) {
        std::vector<std::pair<std::string, std::string>> ids;
        for (const auto& t : tracks) ids.emplace_back(t.id, exercise_key(options.exercise_by, t));
        options.roles->check_entries_name_tracks(ids);
    }
    TrackSource source{tracks.size(), [&](std::size_t k) { return tracks[k].fixes.size(); },
                       [&](std::size_t k) { return std::move(tracks[k]); }, {}, 0, {}};
    return audit(source, grid, default_hull, hull_label, options);
}

namespace {

// The batch's stages, in the order audit() runs them: prepare each vessel and sweep it (on
// threads), grade the contacts by the run's world, tally the run, the exercises, the assessment.

/// A vessel ready to sweep: its wild fixes (dropped from the track), its hull and what labels
/// it, its limiting depth.
struct Vessel {
    std::vector<track::WildFix> wild;
    std::optional<hull::Hull> hull;
    std::string hull_label;
    grid::DepthPlan depth;
};

/// Stage "prepare each vessel": static data joined, outliers dropped, motion and headings
/// resolved (prepare_track: the real world holds no heading for a vessel at rest with neither
/// heading nor COG, it may have swung); the hull from its AIS dimensions when plausible, else
/// the default; its own limiting depth (what is a hazard for it).
Vessel prepare_vessel(track::Track& t, const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                      const AuditOptions& options) {
    Vessel v;
    v.wild = prepare_track(t, options);
    v.hull_label = hull_label;
    v.hull = default_hull;
    if (t.dims && hull::Hull::plausible(*t.dims)) {
        v.hull = hull::Hull::from_dimensions(*t.dims, t.name);
        v.hull_label = dims_label(*t.dims) + (t.dims_source.empty() ? "" : " (" + t.dims_source + ")");
    }
    v.depth = grid::plan_vessel_depth(options.hazard_depth_m, t.draught_m, default_hull.draught(), options.ukc_m, grid);
    return v;
}

/// Stage "sweep", one vessel: its hull (and, for fixes with no heading known, the hull's circle)
/// along its track at its limiting depth; in the real world the evidence its contacts are judged
/// by, else its stays merged into one event each (the real world's decide_kinds does that);
/// its summary completed. Throws InputError for a track of no exercise when exercises are by column.
TrackResult sweep_vessel(const track::Track& t, Vessel& v, const grid::CoastGrid& grid, const geo::LocalFrame& frame,
                         const SweepOptions& sweep_options, const AuditOptions& options) {
    const DetectorChecker detector(grid, *v.hull, v.depth.depth_m);
    const DetectorChecker circle(grid, circle_hull(*v.hull), v.depth.depth_m);
    SweepContext context;
    context.unknown_heading = &circle;
    context.areas = options.areas;
    std::vector<geo::XY> positions;  // the fixes as the sweep projected them, for the evidence
    if (options.world == World::real) context.positions = &positions;
    TrackResult r = sweep_track(t, frame, detector, sweep_options, context);
    if (options.world == World::real) gather_evidence(t, positions, v.hull->length(), frame, grid, sweep_options, options.evidence, r);
    else {
        ground_inside_gaps(r, t, sweep_options, options.evidence, v.hull->length());
        merge_stays(r, t, sweep_options, options.evidence.under_way_kn);
    }
    TrackSummary& s = r.summary;
    s.fixes += v.wild.size();  // fixes read, the wild ones among them
    s.wild_fixes = std::move(v.wild);
    s.hull = v.hull_label;
    s.draught_m = t.draught_m;
    s.draught_source = t.draught_source;
    s.ship_type = t.ship_type;
    s.ship_type_source = t.ship_type_source;
    s.limiting_depth_m = v.depth.depth_m.value_or(NAN);
    s.limiting_depth_source = grid::to_string(v.depth.source);
    if (options.encounters) {
        s.exercise = exercise_key(options.exercise_by, t);
        if (options.exercise_by == ExerciseBy::column && s.exercise.empty())
            throw InputError("no exercise: AuditOptions::exercise_by is column, and the track's rows gave none");
        s.role = role_of(options.roles, s.exercise, t);
    }
    return r;
}

/// The sweep stage's output, per track of the source.
struct Swept {
    std::vector<TrackResult> results;
    std::vector<std::string> errors;         ///< non-empty: the track's bad input (it costs the track)
    std::vector<track::Track> kept;          ///< exercise mode: every track, headings resolved
    std::vector<std::optional<hull::Hull>> kept_hulls;  ///< exercise mode: its hull
};

/// Stage "sweep": every track of the source prepared and swept on the frames' threads (one
/// frame per thread: PROJ transformations are per thread), with the progress callback.
Swept sweep_tracks(const TrackSource& source, const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                   const SweepOptions& sweep_options, const AuditOptions& options, const std::vector<std::unique_ptr<geo::LocalFrame>>& frames) {
    const unsigned jobs = static_cast<unsigned>(frames.size());
    std::size_t total_fixes = 0;
    for (std::size_t k = 0; k < source.count; ++k) total_fixes += source.fixes(k);
    Swept out;
    out.results.resize(source.count);
    out.errors.resize(source.count);
    out.kept.resize(options.encounters ? source.count : 0);
    out.kept_hulls.resize(out.kept.size());
    std::atomic<std::size_t> done{0};
    FirstFailure failure;
    std::function<void()> tick;
    if (options.progress) tick = [&] { options.progress(done.load(), total_fixes); };
    parallel_for(
        source.count, jobs,
        [&](std::size_t k, unsigned w) {
            track::Track t = source.take(k);
            TrackResult& r = out.results[k];
            r.summary.id = t.id;
            r.summary.file = t.file;
            try {
                Vessel v = prepare_vessel(t, grid, default_hull, hull_label, options);
                r = sweep_vessel(t, v, grid, *frames[w], sweep_options, options);
                if (options.encounters) {
                    out.kept[k] = t;
                    out.kept_hulls[k] = v.hull;
                }
                // Held until the report is written: no room to spare (a vector grown by doubling
                // holds up to twice what it needs; 40 MB of poses on a 10 M-row day).
                for (auto& line : r.summary.lines) line.shrink_to_fit();
                for (auto& times : r.summary.line_times) times.shrink_to_fit();
                r.poses.shrink_to_fit();
                r.events.shrink_to_fit();
            } catch (const InputError& e) {  // bad input costs this track; anything else is a bug
                out.errors[k] = e.what();
            } catch (...) {
                failure.keep(std::current_exception());
            }
            done.fetch_add(t.fixes.size());
        },
        tick);
    failure.rethrow();
    return out;
}

/// Stage "grade": what kind each contact is. In the real world by the run's traffic (every track
/// read: this shard's, the others' (TrackSource::take_other), those learned elsewhere
/// (TrackSource::traffic)); in a simulated one by the sweep alone. The evidence is freed after.
void grade_contacts(const TrackSource& source, Swept& swept, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                    const SweepOptions& sweep_options, const AuditOptions& options,
                    const std::vector<std::unique_ptr<geo::LocalFrame>>& frames, AuditResult& result) {
    FirstFailure failure;
    if (options.world == World::real) {
        // The run's traffic: every track read, this shard's and the others'.
        std::vector<TrackResult> other(source.others);
        parallel_for(
            source.others, static_cast<unsigned>(frames.size()),
            [&](std::size_t k, unsigned w) {
                try {
                    track::Track t = source.take_other(k);
                    prepare_traffic(t, options);
                    other[k] = traffic_of(t, traffic_length(t, default_hull), *frames[w], grid, sweep_options, options.evidence);
                } catch (const InputError&) {  // that shard reports it
                } catch (...) {
                    failure.keep(std::current_exception());
                }
            },
            {});
        failure.rethrow();
        std::vector<const TrackResult*> all;
        std::vector<std::string> ids;
        for (std::size_t k = 0; k < source.count; ++k)
            if (swept.errors[k].empty()) {
                all.push_back(&swept.results[k]);
                ids.push_back(swept.results[k].summary.id);
            }
        for (const TrackResult& o : other) {
            all.push_back(&o);
            ids.push_back(o.summary.id);
        }
        if (source.traffic)
            for (const TrackResult& o : *source.traffic) {
                all.push_back(&o);
                ids.push_back(o.summary.id);
            }
        const Traffic traffic = learn_traffic(all, ids, *frames[0], options.evidence);
        for (std::size_t k = 0, m = 0; k < source.count; ++k)
            if (swept.errors[k].empty()) {
                decide_kinds(swept.results[k], traffic.berth_stays[m], traffic.own_visits[m], options.evidence);
                ++m;
            }
        result.places = traffic.places;
    } else {
        for (auto& r : swept.results) grade_simulated(r);
    }
    for (auto& r : swept.results) {  // what the evidence needed, no longer
        std::vector<Stay>().swap(r.stays);
        std::vector<geo::XY>().swap(r.over_land);
    }
}

/// The exercises' tracks, as the tally leaves them (exercise mode).
struct ExerciseTracks {
    std::vector<const track::Track*> tracks;  ///< with a hull and fixes, in the order of result.tracks
    std::vector<std::size_t> index;           ///< position in `tracks` -> index in result.tracks
    std::vector<hull::Hull> hulls;            ///< by position in `tracks`
    std::vector<const track::Track*> kept_of;  ///< index in result.tracks -> its kept track (assessment)
};

/// Stage "tally": the swept tracks into `result` in the source's order (a track of bad input
/// into its errors), the run's totals, and the warnings the whole run gives cause for: most
/// fixes off the chart, vessels with and without draughts on a grid with or without depths,
/// tracks broken into pieces by jumps.
ExerciseTracks tally(const TrackSource& source, Swept& swept, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                     const AuditOptions& options, AuditResult& result) {
    ExerciseTracks ex;
    const auto position = [&](std::size_t k) { return source.position ? source.position(k) : k; };
    for (std::size_t k = 0; k < source.count; ++k) {
        if (!swept.errors[k].empty()) {
            result.errors.push_back({swept.results[k].summary.file, swept.results[k].summary.id, swept.errors[k]});
            result.error_positions.push_back(position(k));
            continue;
        }
        if (options.encounters && swept.kept_hulls[k] && !swept.kept[k].fixes.empty()) {
            ex.tracks.push_back(&swept.kept[k]);
            ex.hulls.push_back(*swept.kept_hulls[k]);
            ex.index.push_back(result.tracks.size());
        }
        add_to_totals(result, swept.results[k].summary);
        result.tracks.push_back(std::move(swept.results[k]));
        result.track_positions.push_back(position(k));
        if (options.encounters) ex.kept_of.push_back(swept.kept[k].fixes.empty() ? nullptr : &swept.kept[k]);
    }
    if (result.fixes >= 10 && 2 * result.uncovered_fixes > result.fixes)
        result.warnings.push_back(std::to_string(result.uncovered_fixes) + " of " + std::to_string(result.fixes) +
                                  " fixes lie outside the chart's area (uncovered: nothing is claimed there). Are latitude and "
                                  "longitude swapped, or is it the wrong coast?");
    // Vessels without a draught of their own: say what they were checked against.
    if (grid.charted_depths().empty()) {
        std::size_t own = 0;
        for (const auto& t : result.tracks)
            own += t.summary.limiting_depth_source == grid::to_string(grid::DepthPlan::Source::vessel_draught);
        if (own > 0)
            result.warnings.push_back(std::to_string(own) + " tracks have a draught of their own, but the grid holds land only (no depth "
                                      "areas or dangers): shallow water was not checked for them");
    } else {
        std::size_t own = 0, fallback = 0;
        std::string fallback_source;
        for (const auto& t : result.tracks) {
            if (t.summary.limiting_depth_source == grid::to_string(grid::DepthPlan::Source::vessel_draught)) {
                ++own;
            } else if (t.summary.limiting_depth_source != grid::to_string(grid::DepthPlan::Source::hazard_depth)) {
                ++fallback;
                fallback_source = t.summary.limiting_depth_source;
            }
        }
        if (fallback > 0) {
            const std::string what = fallback_source == grid::to_string(grid::DepthPlan::Source::land_only)
                                         ? "were checked against land only: shallow water and dangers were not checked for them "
                                           "(give the default ship a draught, AuditOptions::hazard_depth_m, or their draughts in a vessels table)"
                                         : "were checked at the default limiting depth (" + fallback_source + ")";
            result.warnings.push_back(std::to_string(fallback) + " of " + std::to_string(own + fallback) +
                                      " tracks have no draught of their own and " + what);
        }
        if (options.ukc_m && !options.hazard_depth_m && own == 0 && !(default_hull.draught() > 0))
            result.warnings.push_back("AuditOptions::ukc_m needs a draught (a vessel's own, or the default ship's): no track had one");
    }
    for (const auto& t : result.tracks) {
        const TrackSummary& s = t.summary;
        if (s.jumps > 0 && s.fixes >= 4 && 2 * s.segments > s.fixes)
            result.warnings.push_back("track '" + s.id + "' in '" + s.file + "': " + std::to_string(s.segments) + " pieces of " +
                                      std::to_string(s.fixes) + " fixes: jumps over WildFixOptions::max_speed_kn between most fixes, so almost nothing "
                                      "of it was swept (two vessels on one id, or a WildFixOptions::max_speed_kn too low for it?)");
    }
    return ex;
}

/// Stage "exercises" (exercise mode): ship-to-ship encounters and COLREG situations, each
/// exercise on its own clock; pairs of two targets are not reported; each ship lists its worst
/// pairs, the summary counts every one.
void run_exercises(const ExerciseTracks& ex, const AuditOptions& options, const geo::LocalFrame& frame, AuditResult& result) {
    const auto start = Clock::now();
    EncounterOptions eo = options.encounter;
    eo.step_m = options.sweep.step_m;
    eo.max_gap_s = options.sweep.max_gap_s;
    std::map<std::string, std::vector<std::size_t>> by_exercise;  // exercise -> positions in ex.tracks
    for (std::size_t k = 0; k < ex.tracks.size(); ++k) by_exercise[result.tracks[ex.index[k]].summary.exercise].push_back(k);
    std::set<std::string> named;
    for (const auto& t : result.tracks) named.insert(t.summary.exercise);
    result.exercises = named.size();
    auto is_target = [&](std::size_t track_index) { return result.tracks[track_index].summary.role == Role::target; };
    for (const auto& [name, members] : by_exercise) {
        std::vector<const track::Track*> tracks;
        std::vector<hull::Hull> hulls;
        std::vector<std::size_t> index;  // position in this exercise -> index in result.tracks
        for (const std::size_t k : members) {
            tracks.push_back(ex.tracks[k]);
            hulls.push_back(ex.hulls[k]);
            index.push_back(ex.index[k]);
        }
        auto wanted = [&](std::size_t a, std::size_t b) { return !(is_target(index[a]) && is_target(index[b])); };
        EncounterResult er = find_encounters(tracks, hulls, frame, eo);
        // Each ship lists its worst pairs (worst_pairs.hpp); the situations of the others are
        // dropped as they are found (a crowd has one for nearly every pair of ships).
        WorstPairs worst(options.max_encounters_per_ship);
        std::map<WorstPairs::Pair, ClosestApproach> approached;
        for (auto& a : er.approaches) {
            a.a = index[a.a];
            a.b = index[a.b];
            if (is_target(a.a) && is_target(a.b)) continue;
            worst.offer(a.a, a.b, a.clearance_m, a.distance_m);
            approached.emplace(WorstPairs::Pair{a.a, a.b}, a);
        }
        std::map<WorstPairs::Pair, std::pair<ColregEncounter, std::optional<ClosestApproach>>> situated;
        std::size_t situations = 0;
        const auto forget_unlisted = [&] {
            for (auto it = situated.begin(); it != situated.end();)
                it = worst.listed(it->first.first, it->first.second) ? std::next(it) : situated.erase(it);
        };
        for_each_situation(tracks, frame, options.colreg, options.sweep.max_gap_s, wanted, [&](ColregEncounter& c) {
            ++situations;
            c.a = index[c.a];
            c.b = index[c.b];
            std::optional<ClosestApproach> own;
            if (!approached.count({c.a, c.b})) {  // never within the hull-to-hull threshold
                ClosestApproach a;
                a.a = c.a;
                a.b = c.b;
                a.time_s = c.closest_s;
                a.clearance_m = NAN;
                a.distance_m = c.closest_m;
                a.a_position = c.a_closest;
                a.b_position = c.b_closest;
                worst.offer(a.a, a.b, a.clearance_m, a.distance_m);
                own = a;
            }
            if (!worst.listed(c.a, c.b)) return;
            situated.emplace(WorstPairs::Pair{c.a, c.b}, std::make_pair(c, own));
            if (options.max_encounters_per_ship > 0 && situated.size() > 2 * worst.size() + 1024) forget_unlisted();
        });
        forget_unlisted();
        AuditResult::Unlisted here;
        for (auto& e : er.events) {
            e.a.track = index[e.a.track];
            e.b.track = index[e.b.track];
            if (is_target(e.a.track) && is_target(e.b.track)) continue;
            const bool collision = e.kind == EncounterKind::collision;
            (collision ? result.collisions : result.close_quarters) += 1;
            if (worst.listed(e.a.track, e.b.track)) result.encounters.events.push_back(std::move(e));
            else (collision ? here.collisions : here.close_quarters) += 1;
        }
        for (const auto& entry : approached) {
            if (worst.listed(entry.first.first, entry.first.second)) result.encounters.approaches.push_back(entry.second);
            else ++here.approached;
        }
        for (auto& entry : situated) {
            if (entry.second.second) result.encounters.approaches.push_back(*entry.second.second);
            result.situations.push_back(entry.second.first);
        }
        here.pairs = options.max_encounters_per_ship == 0 ? 0 : worst.offered() - worst.size();
        here.situations = situations - situated.size();
        result.unlisted.pairs += here.pairs;
        result.unlisted.collisions += here.collisions;
        result.unlisted.close_quarters += here.close_quarters;
        result.unlisted.situations += here.situations;
        result.unlisted.approached += here.approached;
        if (here.pairs > 0)
            result.warnings.push_back("exercise '" + name + "': " + std::to_string(here.pairs) + " of " + std::to_string(worst.offered()) +
                                      " pairs of ships not listed (" + std::to_string(here.collisions) + " collisions, " +
                                      std::to_string(here.close_quarters) + " close quarters among them), each ship listing the " +
                                      std::to_string(options.max_encounters_per_ship) +
                                      " it came closest to (AuditOptions::max_encounters_per_ship); the summary counts every one");
        result.encounters.instants += er.instants;
        result.encounters.pairs_checked += er.pairs_checked;
        result.encounters.hull_checks += er.hull_checks;
        result.encounters.rebuilds += er.rebuilds;
        result.encounters.threshold_m = std::max(result.encounters.threshold_m, er.threshold_m);
        result.encounters.setup_s += er.setup_s;
        result.encounters.sweep_s += er.sweep_s;
    }
    std::sort(result.encounters.approaches.begin(), result.encounters.approaches.end(),
              [](const ClosestApproach& x, const ClosestApproach& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
    std::sort(result.situations.begin(), result.situations.end(),
              [](const ColregEncounter& x, const ColregEncounter& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
    std::stable_sort(result.encounters.events.begin(), result.encounters.events.end(), [](const Encounter& x, const Encounter& y) {
        return std::tie(x.start_s, x.a.track, x.b.track, x.kind) < std::tie(y.start_s, y.a.track, y.b.track, y.kind);
    });
    result.has_encounters = true;
    result.encounters_s = std::chrono::duration<double>(Clock::now() - start).count();
}

/// Stage "assessment": every trainee scored against the criteria.
void assess_trainees(const ExerciseTracks& ex, const grid::CoastGrid& grid, const hull::Hull& default_hull, const AuditOptions& options,
                     const geo::LocalFrame& frame, AuditResult& result) {
    AssessInput in{result.tracks, result.encounters, ex.kept_of, grid, frame, default_hull.draught(), options.sweep.step_m, options.sweep.max_gap_s,
                   options.sweep.time_tolerance_s, options.max_encounters_per_ship};
    result.assessment = assess(*options.assessment, in);
    result.has_assessment = true;
    result.warnings.insert(result.warnings.end(), result.assessment.warnings.begin(), result.assessment.warnings.end());
    // Time in close quarters is scored from the listed encounters: say when the cap left some out.
    const auto& criteria = options.assessment->criteria;
    const bool scores_close_quarters = std::any_of(criteria.begin(), criteria.end(), [](const Criterion& c) {
        return c.kind == CriterionKind::close_quarters_time;
    });
    if (scores_close_quarters && result.unlisted.close_quarters > 0)
        result.warnings.push_back(std::to_string(result.unlisted.close_quarters) +
                                  " close-quarters encounters were not listed (AuditOptions::max_encounters_per_ship), so their time "
                                  "in close quarters was not scored: raise the limit, or 0 for none, to score every one");
}

AuditResult audit(const TrackSource& source, const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                  const AuditOptions& options) {
    AuditResult result;
    result.shard = options.shard;
    if (options.assessment && !options.encounters)
        throw UsageError("AuditOptions::assessment needs exercise mode (AuditOptions::encounters): trainees are scored per exercise");
    SweepOptions sweep_options = options.sweep;
    if (options.assessment) sweep_options.watch_clearance_m = std::max(sweep_options.watch_clearance_m, options.assessment->watch_clearance_m());
    std::vector<std::unique_ptr<geo::LocalFrame>> frames;  // PROJ transformations are per thread
    for (unsigned w = 0, jobs = thread_count(options.jobs); w < jobs; ++w) frames.push_back(std::make_unique<geo::LocalFrame>(grid.frame()));
    result.world = options.world;
    result.chart_tolerance_m = options.evidence.chart_tolerance_m;
    const auto t1 = Clock::now();
    Swept swept = sweep_tracks(source, grid, default_hull, hull_label, sweep_options, options, frames);
    grade_contacts(source, swept, grid, default_hull, sweep_options, options, frames, result);
    result.sweep_s = std::chrono::duration<double>(Clock::now() - t1).count();
    const ExerciseTracks exercises = tally(source, swept, grid, default_hull, options, result);
    if (options.encounters) run_exercises(exercises, options, *frames[0], result);
    if (options.assessment) assess_trainees(exercises, grid, default_hull, options, *frames[0], result);
    return result;
}

}  // namespace

std::vector<TrackResult> traffic_of_partition(ReadResult& read, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                                              const AuditOptions& options) {
    if (options.world != World::real) return {};
    std::vector<TrackResult> out(read.tracks.size());
    std::vector<char> ok(read.tracks.size(), 0);
    const unsigned jobs = thread_count(options.jobs);
    std::vector<std::unique_ptr<geo::LocalFrame>> frames;
    for (unsigned w = 0; w < jobs; ++w) frames.push_back(std::make_unique<geo::LocalFrame>(grid.frame()));
    FirstFailure failure;
    parallel_for(
        read.tracks.size(), jobs,
        [&](std::size_t k, unsigned w) {
            try {
                track::Track t = take(read.tracks[k]);
                prepare_traffic(t, options);
                out[k] = traffic_of(t, traffic_length(t, default_hull), *frames[w], grid, options.sweep, options.evidence);
                ok[k] = 1;
            } catch (const InputError&) {  // the audit of this partition reports it
            } catch (...) {
                failure.keep(std::current_exception());
            }
        },
        {});
    failure.rethrow();
    std::vector<TrackResult> kept;
    for (std::size_t k = 0; k < out.size(); ++k)
        if (ok[k]) kept.push_back(std::move(out[k]));
    return kept;
}

AuditResult audit_partition(ReadResult read, std::vector<std::size_t> positions, std::vector<TrackResult> traffic,
                            const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                            const AuditOptions& options) {
    if (options.encounters) throw UsageError("AuditOptions::encounters: an exercise is checked whole (its shard), not by partitions of vessels");
    std::vector<track::PackedTrack>& packed = read.tracks;
    TrackSource source{packed.size(), [&](std::size_t k) { return packed[k].size(); }, [&](std::size_t k) { return take(packed[k]); },
                       [&](std::size_t k) { return positions[k]; }, 0, {}};
    if (options.world == World::real) source.traffic = &traffic;
    return with_read(audit(source, grid, default_hull, hull_label, options), read);
}

}  // namespace shoal::audit
