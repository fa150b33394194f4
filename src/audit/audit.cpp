#include <shoal/audit/audit.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include <shoal/util/error.hpp>

namespace shoal::audit {

namespace {

using Clock = std::chrono::steady_clock;

/// Runs `work(k, worker)` for k in [0, n) on `jobs` threads (work must not throw); calls
/// `tick` on this thread about ten times a second meanwhile, and once at the end.
template <typename Work>
void parallel_for(std::size_t n, unsigned jobs, Work work, const std::function<void()>& tick) {
    std::atomic<std::size_t> next{0};
    std::atomic<unsigned> finished{0};
    const auto threads = static_cast<unsigned>(std::clamp<std::size_t>(n, 1, std::max(1u, jobs)));
    auto worker = [&](unsigned w) {
        for (std::size_t k; (k = next.fetch_add(1)) < n;) work(k, w);
        finished.fetch_add(1);
    };
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < threads; ++w) pool.emplace_back(worker, w);
    for (int i = 0; tick && finished.load() < threads; ++i) {
        if (i % 5 == 0) tick();
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    for (auto& t : pool) t.join();
    if (tick) tick();
}

std::string dims_label(const hull::Dimensions& d) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "AIS dimensions %g,%g,%g,%g", d.a, d.b, d.c, d.d);
    return buf;
}

}  // namespace

AuditResult run_audit(const std::vector<std::string>& inputs, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                      const std::string& hull_label, const AuditOptions& options) {
    AuditResult result;
    // Threads: all cores by default; never more than 4 per core (each holds a PROJ context and
    // buffers: -j 100000 would start 100,000 threads), nor more than there is work (below).
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned jobs = std::clamp(options.jobs ? options.jobs : cores, 1u, 4 * cores);
    const std::vector<std::string> files = track::expand_inputs(inputs);

    // 1. Read every file (a file that cannot be read is reported; the batch goes on). Fixes
    // stay packed (32 bytes each) until their track is swept, and are freed after it.
    const auto t0 = Clock::now();
    std::vector<track::PackedTrackFile> read(files.size());
    result.files.resize(files.size());
    parallel_for(
        files.size(), jobs,
        [&](std::size_t k, unsigned) {
            FileResult& fr = result.files[k];
            fr.file = files[k];
            try {
                read[k] = track::read_tracks_packed(files[k], options.read);
                fr.format = read[k].format;
                fr.read = read[k].report;
                fr.tracks = read[k].tracks.size();
            } catch (const std::exception& e) {
                fr.error = e.what();
            }
        },
        {});
    result.read_s = std::chrono::duration<double>(Clock::now() - t0).count();

    // 2. Sweep every track.
    std::vector<track::PackedTrack*> tracks;
    for (auto& f : read)
        for (auto& t : f.tracks) tracks.push_back(&t);
    std::size_t total_fixes = 0;
    for (const auto* t : tracks) total_fixes += t->size();
    std::vector<TrackResult> swept(tracks.size());
    std::vector<std::string> errors(tracks.size());
    // Exercise mode keeps every track (headings resolved) and its hull for the encounters.
    std::vector<track::Track> kept(options.encounters ? tracks.size() : 0);
    std::vector<std::optional<hull::Hull>> kept_hulls(kept.size());
    std::vector<std::unique_ptr<geo::LocalFrame>> frames;  // PROJ transformations are per thread
    for (unsigned w = 0; w < jobs; ++w) frames.push_back(std::make_unique<geo::LocalFrame>(grid.frame()));
    std::atomic<std::size_t> done{0};
    const auto t1 = Clock::now();
    std::function<void()> tick;
    if (options.progress) tick = [&] { options.progress(done.load(), total_fixes); };
    parallel_for(
        tracks.size(), jobs,
        [&](std::size_t k, unsigned w) {
            track::Track t = tracks[k]->unpack();
            tracks[k]->release_fixes();
            try {
                track::WildFixOptions wo = options.wild;
                wo.max_gap_s = options.sweep.max_gap_s;
                std::vector<track::WildFix> wild = track::drop_wild_fixes(t, wo);
                track::resolve_motion(t, options.sweep.motion());
                track::resolve_headings(t, 0.5, options.sweep.max_gap_s);
                std::string label = hull_label;
                hull::Hull hull = default_hull;
                if (t.dims) {
                    hull = hull::Hull::from_dimensions(*t.dims, t.name);
                    label = dims_label(*t.dims);
                }
                const DetectorChecker detector(grid, hull);
                const DetectorChecker circle(grid, circle_hull(hull));
                SweepContext context;
                context.unknown_heading = &circle;
                context.areas = options.areas;
                swept[k] = sweep_track(t, *frames[w], detector, options.sweep, context);
                swept[k].summary.fixes += wild.size();  // fixes read, the wild ones among them
                swept[k].summary.wild_fixes = std::move(wild);
                swept[k].summary.hull = label;
                if (options.encounters) {
                    kept[k] = t;
                    kept_hulls[k] = hull;
                }
                for (auto& line : swept[k].summary.lines) line.shrink_to_fit();  // held until the report is written
            } catch (const std::exception& e) {
                errors[k] = e.what();
                swept[k].summary.id = t.id;
                swept[k].summary.file = t.file;
            }
            done.fetch_add(t.fixes.size());
        },
        tick);
    result.sweep_s = std::chrono::duration<double>(Clock::now() - t1).count();

    std::vector<const track::Track*> exercise;
    std::vector<std::size_t> exercise_index;  // exercise position -> index in result.tracks
    std::vector<hull::Hull> exercise_hulls;
    for (std::size_t k = 0; k < tracks.size(); ++k) {
        if (!errors[k].empty()) {
            result.errors.push_back({tracks[k]->file, tracks[k]->id, errors[k]});
            continue;
        }
        if (options.encounters && kept_hulls[k] && !kept[k].fixes.empty()) {
            exercise.push_back(&kept[k]);
            exercise_hulls.push_back(*kept_hulls[k]);
            exercise_index.push_back(result.tracks.size());
        }
        const TrackSummary& s = swept[k].summary;
        result.fixes += s.fixes;
        result.poses += s.poses;
        result.uncovered_fixes += s.uncovered_fixes;
        result.groundings += s.groundings;
        result.close_passes += s.close_passes;
        result.alongside += s.alongside;
        result.contacts_at_start += s.contacts_at_start;
        result.expected_contacts += s.expected_contacts;
        result.wild_fixes += s.wild_fixes.size();
        result.jumps += s.jumps;
        result.unknown_heading_fixes += s.unknown_heading_fixes;
        if (s.fixes) {
            result.first_fix_s = std::isnan(result.first_fix_s) ? s.start_s : std::min(result.first_fix_s, s.start_s);
            result.last_fix_s = std::isnan(result.last_fix_s) ? s.end_s : std::max(result.last_fix_s, s.end_s);
        }
        result.tracks.push_back(std::move(swept[k]));
    }
    for (const auto& f : result.files) result.skipped_rows += f.read.skipped;
    if (result.fixes >= 10 && 2 * result.uncovered_fixes > result.fixes)
        result.warnings.push_back(std::to_string(result.uncovered_fixes) + " of " + std::to_string(result.fixes) +
                                  " fixes lie outside the chart's area (uncovered: nothing is claimed there). Are latitude and "
                                  "longitude swapped, or is it the wrong coast?");
    for (const auto& t : result.tracks) {
        const TrackSummary& s = t.summary;
        if (s.jumps > 0 && s.fixes >= 4 && 2 * s.segments > s.fixes)
            result.warnings.push_back("track '" + s.id + "' in '" + s.file + "': " + std::to_string(s.segments) + " pieces of " +
                                      std::to_string(s.fixes) + " fixes: jumps over --max-speed between most fixes, so almost nothing "
                                      "of it was swept (two vessels on one id, or a --max-speed too low for it?)");
    }

    // 3. Exercise mode: ship-to-ship encounters over all audited tracks, on one clock.
    if (options.encounters) {
        const auto t2 = Clock::now();
        EncounterOptions eo = options.encounter;
        eo.step_m = options.sweep.step_m;
        eo.max_gap_s = options.sweep.max_gap_s;
        result.encounters = find_encounters(exercise, exercise_hulls, *frames[0], eo);
        // Indices into the exercise become indices into result.tracks.
        for (auto& e : result.encounters.events) {
            e.a.track = exercise_index[e.a.track];
            e.b.track = exercise_index[e.b.track];
            (e.kind == EncounterKind::collision ? result.collisions : result.close_quarters) += 1;
        }
        for (auto& a : result.encounters.approaches) {
            a.a = exercise_index[a.a];
            a.b = exercise_index[a.b];
        }
        result.has_encounters = true;
        result.encounters_s = std::chrono::duration<double>(Clock::now() - t2).count();
    }
    return result;
}

}  // namespace shoal::audit
