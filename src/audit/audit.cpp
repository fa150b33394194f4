#include "audit/audit.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "util/error.hpp"

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
    const unsigned jobs = options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
    const std::vector<std::string> files = track::expand_inputs(inputs);

    // 1. Read every file (a file that cannot be read is reported; the batch goes on).
    const auto t0 = Clock::now();
    std::vector<track::TrackFile> read(files.size());
    result.files.resize(files.size());
    parallel_for(
        files.size(), jobs,
        [&](std::size_t k, unsigned) {
            FileResult& fr = result.files[k];
            fr.file = files[k];
            try {
                read[k] = track::read_tracks(files[k], options.read);
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
    std::vector<track::Track*> tracks;
    for (auto& f : read)
        for (auto& t : f.tracks) tracks.push_back(&t);
    std::size_t total_fixes = 0;
    for (const auto* t : tracks) total_fixes += t->fixes.size();
    std::vector<TrackResult> swept(tracks.size());
    std::vector<std::string> errors(tracks.size());
    std::vector<std::unique_ptr<geo::LocalFrame>> frames;  // PROJ transformations are per thread
    for (unsigned w = 0; w < jobs; ++w) frames.push_back(std::make_unique<geo::LocalFrame>(grid.frame()));
    std::atomic<std::size_t> done{0};
    const auto t1 = Clock::now();
    std::function<void()> tick;
    if (options.progress) tick = [&] { options.progress(done.load(), total_fixes); };
    parallel_for(
        tracks.size(), jobs,
        [&](std::size_t k, unsigned w) {
            track::Track& t = *tracks[k];
            try {
                track::resolve_headings(t);
                std::string label = hull_label;
                hull::Hull hull = default_hull;
                if (t.dims) {
                    hull = hull::Hull::from_dimensions(*t.dims, t.name);
                    label = dims_label(*t.dims);
                }
                const DetectorChecker checker(grid, hull);
                swept[k] = sweep_track(t, *frames[w], checker, options.sweep);
                swept[k].summary.hull = label;
            } catch (const std::exception& e) {
                errors[k] = e.what();
                swept[k].summary.id = t.id;
                swept[k].summary.file = t.file;
            }
            done.fetch_add(t.fixes.size());
        },
        tick);
    result.sweep_s = std::chrono::duration<double>(Clock::now() - t1).count();

    for (std::size_t k = 0; k < tracks.size(); ++k) {
        if (!errors[k].empty()) {
            result.errors.push_back({tracks[k]->file, tracks[k]->id, errors[k]});
            continue;
        }
        const TrackSummary& s = swept[k].summary;
        result.fixes += s.fixes;
        result.poses += s.poses;
        result.uncovered_fixes += s.uncovered_fixes;
        result.groundings += s.groundings;
        result.close_passes += s.close_passes;
        if (s.fixes) {
            result.first_fix_s = std::isnan(result.first_fix_s) ? s.start_s : std::min(result.first_fix_s, s.start_s);
            result.last_fix_s = std::isnan(result.last_fix_s) ? s.end_s : std::max(result.last_fix_s, s.end_s);
        }
        result.tracks.push_back(std::move(swept[k]));
    }
    for (const auto& f : result.files) result.skipped_rows += f.read.skipped;
    return result;
}

}  // namespace shoal::audit
