// bench_import: what building and caching the grid costs, per coastline of the shared data.
//
// For every coast/gshhg/*_land.geojson and the S-57 cell US4MD81M: the import split into
// reading with OGR (coast::import_coastline), projecting, clipping (GEOSClipByRect per run
// of segments in a cell) and cell states (winding numbers); vertex, cell and segment counts;
// GEOSClipByRect calls; grid bytes per vertex; the cache file's size and the time to save
// and to load it (GridFile::load, median of several). At the default 500 m cell and at
// other cell sizes (250 m = 2.5 x a 100 m ship, 1000 m = 2.5 x a 400 m ship, 2000 m).
// Also the whole `shoal import` path (grid::build_grid: read, frame, scale check, build,
// source fingerprint) plus GridFile::save, at 500 m.
//
// Usage: bench_import [--data DIR] [--coast SUBSTRING]... [--cells M,M,...] [--reps N]
//                     [--loads N] [--benchmark_... (Google Benchmark mode)]
// DIR defaults to $SHOAL_SHARED_DATA, else ../shared/data next to the source tree.

#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench_data.hpp"
#include <shoal/coast/coastline.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_cache.hpp>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double s_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// CPU time of this thread, seconds (what the import costs when the machine is shared).
double thread_cpu_s() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

struct Options {
    std::string data;
    std::vector<std::string> coast_filter;
    std::vector<double> cells{250, 500, 1000, 2000};
    int reps = 3;   // imports per coastline and cell size (medians)
    int loads = 9;  // cache loads per grid (median)
    bool gbench = false;
};

using shoal::bench::CoastFile;
using shoal::bench::default_data_dir;
using shoal::bench::find_coasts;

shoal::geo::LocalFrame frame_for(const shoal::coast::Coastline& c) {
    return shoal::geo::LocalFrame::transverse_mercator({(c.min.lon + c.max.lon) / 2, (c.min.lat + c.max.lat) / 2});
}

/// Medians over the repetitions of one (coastline, cell size).
struct CellRow {
    double cell = 0;
    double read_s = 0, project_s = 0, clip_s = 0, state_s = 0, build_s = 0;
    double build_cpu_s = 0;  // thread CPU time of the build
    std::size_t cells = 0, coast_cells = 0, land_cells = 0, segments = 0;
    std::uint64_t clip_calls = 0;
    std::size_t memory = 0, file_bytes = 0;
    double save_s = 0, load_s = 0, load_min_s = 0;
    bool reloaded_equal = false;
};

struct CoastRow {
    CoastFile file;
    std::uint64_t vertices = 0;
    std::size_t polylines = 0;
    double read_s = 0;          // OGR read (median)
    double read_cpu_s = 0;      // its thread CPU time (median)
    double import_path_s = 0;   // build_grid + save at 500 m (median)
    std::vector<CellRow> cells;
};

std::string fmt(double v, const char* f) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

CoastRow run_coast(const CoastFile& f, const Options& opt, const fs::path& tmp) {
    CoastRow row;
    row.file = f;
    std::vector<double> reads, read_cpus;
    std::unique_ptr<shoal::coast::Coastline> coast;
    for (int r = 0; r < opt.reps; ++r) {
        const auto t0 = Clock::now();
        const double c0 = thread_cpu_s();
        auto c = std::make_unique<shoal::coast::Coastline>(shoal::coast::import_coastline({f.path}));
        read_cpus.push_back(thread_cpu_s() - c0);
        reads.push_back(s_since(t0));
        coast = std::move(c);
    }
    row.read_s = median(reads);
    row.read_cpu_s = median(read_cpus);
    row.vertices = coast->vertex_count();
    row.polylines = coast->polylines.size();
    for (double cell : opt.cells) {
        CellRow cr;
        cr.cell = cell;
        cr.read_s = row.read_s;
        std::vector<double> proj, clip, state, total, cpu, saves, loads;
        std::unique_ptr<shoal::grid::CoastGrid> grid;
        for (int r = 0; r < opt.reps; ++r) {
            shoal::grid::BuildStats st;
            const double c0 = thread_cpu_s();
            grid = std::make_unique<shoal::grid::CoastGrid>(shoal::grid::CoastGrid::build(*coast, frame_for(*coast), cell, &st));
            cpu.push_back(thread_cpu_s() - c0);
            proj.push_back(st.project_s);
            clip.push_back(st.clip_s);
            state.push_back(st.state_s);
            total.push_back(st.total_s);
            cr.clip_calls = st.clip_calls;
        }
        cr.project_s = median(proj);
        cr.clip_s = median(clip);
        cr.state_s = median(state);
        cr.build_s = median(total);
        cr.build_cpu_s = median(cpu);
        cr.cells = grid->cell_count();
        cr.coast_cells = grid->coast_cell_count();
        cr.land_cells = grid->land_cell_count();
        cr.segments = grid->segment_count();
        cr.memory = grid->memory_bytes();
        const std::string path = (tmp / (f.name + "_" + fmt(cell, "%.0f") + ".shoalgrid")).string();
        for (int r = 0; r < opt.reps; ++r) {
            const auto t0 = Clock::now();
            shoal::grid::GridFile::save(*grid, path);
            saves.push_back(s_since(t0));
        }
        cr.file_bytes = static_cast<std::size_t>(fs::file_size(path));
        for (int r = 0; r < opt.loads; ++r) {
            const auto t0 = Clock::now();
            shoal::grid::CoastGrid g = shoal::grid::GridFile::load(path);
            loads.push_back(s_since(t0));
            if (r == 0) cr.reloaded_equal = (g == *grid);
            benchmark::DoNotOptimize(g);
        }
        cr.save_s = median(saves);
        cr.load_s = median(loads);
        cr.load_min_s = *std::min_element(loads.begin(), loads.end());
        fs::remove(path);
        row.cells.push_back(cr);
        std::fprintf(stderr, "  %s cell %.0f m: build %.3f s, %zu cells, load %.1f ms\n", f.name.c_str(), cell, cr.build_s, cr.cells,
                     cr.load_s * 1e3);
    }
    // The whole `shoal import` path at the default cell.
    std::vector<double> paths;
    for (int r = 0; r < opt.reps; ++r) {
        const auto t0 = Clock::now();
        shoal::grid::BuildRequest req;
        req.cell_m = 500;
        std::vector<std::string> warnings;
        const shoal::grid::CoastGrid g = shoal::grid::build_grid({f.path}, req, &warnings);
        shoal::grid::GridFile::save(g, (tmp / "import_path.shoalgrid").string());
        paths.push_back(s_since(t0));
    }
    fs::remove(tmp / "import_path.shoalgrid");
    row.import_path_s = median(paths);
    return row;
}

// Google Benchmark mode: loading each coastline's 500 m cache, building at each cell size.
void register_gbench(const std::vector<CoastFile>& files, const Options& opt, const fs::path& tmp) {
    for (const CoastFile& f : files) {
        auto coast = std::make_shared<shoal::coast::Coastline>(shoal::coast::import_coastline({f.path}));
        const std::string path = (tmp / (f.name + ".shoalgrid")).string();
        shoal::grid::GridFile::save(shoal::grid::CoastGrid::build(*coast, frame_for(*coast), 500), path);
        benchmark::RegisterBenchmark(("load/" + f.name).c_str(), [path](benchmark::State& st) {
            for (auto _ : st) benchmark::DoNotOptimize(shoal::grid::GridFile::load(path));
        })->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("read/" + f.name).c_str(), [f](benchmark::State& st) {
            for (auto _ : st) benchmark::DoNotOptimize(shoal::coast::import_coastline({f.path}));
        })->Unit(benchmark::kMillisecond);
        for (double cell : opt.cells)
            benchmark::RegisterBenchmark(("build/" + f.name + "/" + fmt(cell, "%.0f")).c_str(), [coast, cell](benchmark::State& st) {
                for (auto _ : st) benchmark::DoNotOptimize(shoal::grid::CoastGrid::build(*coast, frame_for(*coast), cell));
            })->Unit(benchmark::kMillisecond);
    }
}

[[noreturn]] void usage(const char* msg) {
    std::fprintf(stderr,
                 "bench_import: %s\nusage: bench_import [--data DIR] [--coast SUBSTRING]... [--cells M,M,...] [--reps N] "
                 "[--loads N] [--benchmark_...]\n",
                 msg);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    opt.data = default_data_dir();
    std::vector<char*> gargs{argv[0]};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(("missing value after " + a).c_str());
            return argv[++i];
        };
        try {
            if (a == "--data") opt.data = value();
            else if (a == "--coast") opt.coast_filter.push_back(value());
            else if (a == "--reps") opt.reps = std::max(1, std::stoi(value()));
            else if (a == "--loads") opt.loads = std::max(1, std::stoi(value()));
            else if (a == "--cells") {
                opt.cells.clear();
                std::stringstream ss(value());
                for (std::string item; std::getline(ss, item, ',');) opt.cells.push_back(std::stod(item));
                if (opt.cells.empty()) usage("--cells needs at least one size");
            } else if (a.rfind("--benchmark_", 0) == 0) {
                opt.gbench = true;
                gargs.push_back(argv[i]);
            } else if (a == "--help" || a == "-h") usage("cost of building and caching the grid");
            else usage(("unknown argument " + a).c_str());
        } catch (const std::logic_error&) {
            usage(("bad value for " + a).c_str());
        }
    }
    std::vector<CoastFile> files = find_coasts(opt.data);
    if (files.empty()) {
        std::fprintf(stderr,
                     "bench_import: no shared data at '%s' (expected coast/gshhg/*_land.geojson and "
                     "coast/s57/US4MD81M/US4MD81M.000); pass --data DIR or set SHOAL_SHARED_DATA. Nothing measured.\n",
                     opt.data.c_str());
        return 2;
    }
    if (!opt.coast_filter.empty())
        std::erase_if(files, [&](const CoastFile& f) {
            return std::none_of(opt.coast_filter.begin(), opt.coast_filter.end(),
                                [&](const std::string& s) { return f.name.find(s) != std::string::npos; });
        });
    if (files.empty()) {
        std::fprintf(stderr, "%s: no coastline in '%s' matches --coast. Nothing measured.\n", "bench_import", opt.data.c_str());
        return 2;
    }
    const fs::path tmp = fs::temp_directory_path() / ("shoal-bench-import-" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    struct Cleanup {
        fs::path dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{tmp};

    if (opt.gbench) {
        int gargc = static_cast<int>(gargs.size());
        benchmark::Initialize(&gargc, gargs.data());
        register_gbench(files, opt, tmp);
        benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        return 0;
    }

    std::vector<CoastRow> rows;
    for (const CoastFile& f : files) {
        std::fprintf(stderr, "importing %s ...\n", f.name.c_str());
        rows.push_back(run_coast(f, opt, tmp));
    }

    std::printf("# bench_import\n\ndata: %s; medians of %d imports and saves, %d loads; wall-clock seconds unless marked "
                "((CPU): thread CPU time of read + build)\n\n",
                opt.data.c_str(), opt.reps, opt.loads);
    std::printf("## Default cell (500 m)\n\n"
                "| coastline | vertices | polylines | read (OGR) | project | clip | cell states | read + build | (CPU) | `shoal import` path | cells | "
                "coast cells | segments | GEOSClipByRect calls | grid bytes / vertex | cache file KB | save ms | load ms (min) |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    bool all_equal = true;
    for (const CoastRow& r : rows)
        for (const CellRow& c : r.cells) {
            all_equal = all_equal && c.reloaded_equal;
            if (c.cell != 500) continue;
            std::printf("| %s | %llu | %zu | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %zu | %zu | %zu | %llu | %.1f | %.0f | %.1f | %.2f (%.2f) |\n",
                        r.file.name.c_str(), static_cast<unsigned long long>(r.vertices), r.polylines, r.read_s, c.project_s, c.clip_s,
                        c.state_s, r.read_s + c.build_s, r.read_cpu_s + c.build_cpu_s, r.import_path_s, c.cells, c.coast_cells, c.segments,
                        static_cast<unsigned long long>(c.clip_calls), static_cast<double>(c.memory) / static_cast<double>(r.vertices),
                        static_cast<double>(c.file_bytes) / 1024.0, c.save_s * 1e3, c.load_s * 1e3, c.load_min_s * 1e3);
        }
    std::printf("\n## Cell sizes (build = project + clip + cell states, after the OGR read)\n\n"
                "| coastline | cell m | cells | coast cells | land cells | segments | GEOSClipByRect calls | "
                "build s | clip s | grid bytes / vertex | cache file KB | load ms |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const CoastRow& r : rows)
        for (const CellRow& c : r.cells)
            std::printf("| %s | %.0f | %zu | %zu | %zu | %zu | %llu | %.3f | %.3f | %.1f | %.0f | %.2f |\n", r.file.name.c_str(), c.cell,
                        c.cells, c.coast_cells, c.land_cells, c.segments, static_cast<unsigned long long>(c.clip_calls), c.build_s, c.clip_s,
                        static_cast<double>(c.memory) / static_cast<double>(r.vertices), static_cast<double>(c.file_bytes) / 1024.0,
                        c.load_s * 1e3);
    std::printf("\nevery loaded grid equal to the grid saved: %s\n", all_equal ? "yes" : "NO");
    return all_equal ? 0 : 1;
}
