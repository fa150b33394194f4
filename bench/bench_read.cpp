// Reading one track file as the audit reads it (track::read_tracks_packed), on one thread and on
// two (ReadOptions::threads), runs interleaved, best of N: rows per second of the read alone,
// for telling the reader's stages apart. The user's figure is the `time: read` line of
// `shoal check -v` (docs/performance.md).
//
//   bench_read FILE [RUNS]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <shoal/track/reader.hpp>

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_read FILE [RUNS]\n");
        return 2;
    }
    const std::string path = argv[1];
    const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
    double best[3] = {1e30, 1e30, 1e30};
    std::size_t rows = 0, fixes = 0;
    for (int r = 0; r < runs; ++r) {
        for (const unsigned threads : {1u, 2u}) {
            shoal::track::ReadOptions options;
            options.threads = threads;
            const auto t0 = std::chrono::steady_clock::now();
            const shoal::track::PackedTrackFile f = shoal::track::read_tracks_packed(path, options);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            best[threads] = std::min(best[threads], s);
            rows = f.report.rows;
            fixes = 0;
            for (const auto& t : f.tracks) fixes += t.size();
        }
    }
    std::printf("%s: %zu rows, %zu fixes\n", path.c_str(), rows, fixes);
    for (const unsigned threads : {1u, 2u})
        std::printf("  threads %u: best of %d %.3f s = %.2f M rows/s\n", threads, runs, best[threads], static_cast<double>(rows) / best[threads] / 1e6);
    return 0;
}
