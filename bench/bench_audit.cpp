// End-to-end throughput of a track audit (issue: "fixes per second of shoal check on the
// largest AIS set, near-coast and open-water, with the time split between reading, sweeping
// and writing"). The shared AIS sets are small (a few thousand fixes), so this harness
// generates synthetic AIS exports from a real coastline, interleaved by time across vessels
// the way a daily export is, writes them as CSV, and runs the library's audit on them.
//
//   bench_audit [--data DIR] [--vessels N] [--fixes N] [--jobs N]
//
// Open water: random walks started at least 3 km from land in the Gulf of Finland area of
// coast/gshhg/gof_helsinki_land.geojson, 12-20 kn, a fix every 10 s, kept only while more
// than 1.5 km from land. Near coast: vessels following the coastline 30-300 m off it (sailing
// along the coast's own vertices offset to seaward), so most poses need segment work.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include <shoal/audit/audit.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/report/geojson_report.hpp>

namespace fs = std::filesystem;
using namespace shoal;
using Clock = std::chrono::steady_clock;

namespace {

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Row {
    double t;
    int vessel;
    geo::LonLat p;
    double sog, cog;
};

/// Writes rows (sorted by time, vessels interleaved) in the MarineCadastre AIS layout.
void write_csv(const fs::path& path, std::vector<Row>& rows) {
    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.t < b.t || (a.t == b.t && a.vessel < b.vessel); });
    std::ofstream out(path);
    out << "MMSI,BaseDateTime,LAT,LON,SOG,COG,Heading,VesselName\n";
    char line[200];
    for (const Row& r : rows) {
        const std::string t = report::iso_time(r.t);
        std::snprintf(line, sizeof line, "%d,%s,%.6f,%.6f,%.1f,%.1f,%.0f,\n", 200000000 + r.vessel, t.substr(0, 19).c_str(), r.p.lat,
                      r.p.lon, r.sog, r.cog, r.cog);
        out << line;
    }
}

std::vector<Row> open_water(const grid::CoastGrid& grid, int vessels, int fixes, std::mt19937_64& rng) {
    const hull::Hull probe_hull = hull::Hull::from_dimensions({100, 20, 8, 8});
    const check::Detector det(grid, probe_hull);
    std::uniform_real_distribution<double> unit(0, 1);
    const geo::Box e = grid.extent();
    std::vector<Row> rows;
    for (int v = 0; v < vessels; ++v) {
        geo::XY p;
        for (;;) {  // a start at least 3 km from land
            p = {e.minx + unit(rng) * (e.maxx - e.minx), e.miny + unit(rng) * (e.maxy - e.miny)};
            if (det.nearest_coast(p, 3000, nullptr) == INFINITY && !grid.is_land(p)) break;
        }
        double cog = 360 * unit(rng), sog = 12 + 8 * unit(rng);
        const double t0 = 1.7e9 + 600 * unit(rng);
        for (int k = 0; k < fixes; ++k) {
            rows.push_back({t0 + 10.0 * k, v, grid.frame().inverse(p), sog, cog});
            geo::XY next;
            for (int tries = 0;; ++tries) {  // stay 1.5 km off land: turn away when needed
                const double h = cog * std::numbers::pi / 180;
                next = p + (sog * 0.5144 * 10.0) * geo::XY{std::sin(h), std::cos(h)};
                if ((det.nearest_coast(next, 1500, nullptr) == INFINITY && !grid.is_land(next) && grid.col_of(next.x) > 0 &&
                     grid.row_of(next.y) > 0 && grid.col_of(next.x) < grid.nx() - 1 && grid.row_of(next.y) < grid.ny() - 1) ||
                    tries > 50)
                    break;
                cog = std::fmod(cog + 40 + 60 * unit(rng), 360);
            }
            cog = std::fmod(cog + (unit(rng) - 0.5) * 4 + 360, 360);
            p = next;
        }
    }
    return rows;
}

std::vector<Row> near_coast(const std::vector<coast::LocalPolyline>& lines, const grid::CoastGrid& grid, int vessels, int fixes,
                            std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<Row> rows;
    for (int v = 0; v < vessels; ++v) {
        // Coastal passages: straight legs of 100 fixes (10 s apart, 10 kn: ~5 km) started
        // 30-300 m to seaward of a random coastline vertex, heading along the coast there,
        // with a small random drift in course; some run into land, most pass close.
        double t = 1.7e9 + 600 * unit(rng);
        for (int k = 0; k < fixes;) {
            const coast::LocalPolyline* l = nullptr;
            while (!l || l->points.size() < 20) l = &lines[rng() % lines.size()];
            const std::size_t i = rng() % (l->points.size() - 1);
            const geo::XY d = l->points[i + 1] - l->points[i];
            const double len = std::max(1e-6, std::hypot(d.x, d.y));
            geo::XY p = l->points[i] + (30 + 270 * unit(rng)) * geo::XY{d.y / len, -d.x / len};
            double cog = std::fmod(std::atan2(d.x, d.y) * 180 / std::numbers::pi + 360, 360);
            for (int leg = 0; leg < 100 && k < fixes; ++leg, ++k) {
                rows.push_back({t, v, grid.frame().inverse(p), 10.0, cog});
                const double h = cog * std::numbers::pi / 180;
                p = p + (10.0 * 0.5144 * 10.0) * geo::XY{std::sin(h), std::cos(h)};
                cog = std::fmod(cog + (unit(rng) - 0.5) * 2 + 360, 360);
                t += 10;
            }
            t += 700;  // a gap between passages (split by --max-gap)
        }
    }
    return rows;
}

void run(const char* label, const fs::path& csv, const grid::CoastGrid& grid, unsigned jobs) {
    const hull::Hull hull = hull::Hull::from_dimensions({150, 35, 14, 14});
    audit::AuditOptions opt;
    opt.jobs = jobs;
    const auto t0 = Clock::now();
    const audit::AuditResult r = audit::run_audit({csv.string()}, grid, hull, "bench", opt);
    const double audit_s = since(t0);
    const auto t1 = Clock::now();
    const fs::path out = fs::temp_directory_path() / "shoal-bench-report.geojson";
    report::write_geojson(out.string(), r, {});
    const double write_s = since(t1);
    const double total = audit_s + write_s;
    std::printf("%-11s %9zu fixes %5zu tracks %10zu poses | read %6.3f s  sweep %6.3f s  write %6.3f s | total %6.3f s = %5.2f M fixes/s"
                " (sweep alone %5.2f M/s, read alone %5.2f M/s) | %zu groundings %zu close passes\n",
                label, r.fixes, r.tracks.size(), r.poses, r.read_s, r.sweep_s, write_s, total, static_cast<double>(r.fixes) / total / 1e6,
                static_cast<double>(r.fixes) / r.sweep_s / 1e6, static_cast<double>(r.fixes) / r.read_s / 1e6, r.groundings, r.close_passes);
}

}  // namespace

int main(int argc, char** argv) {
    std::string data = std::getenv("SHOAL_SHARED_DATA") ? std::getenv("SHOAL_SHARED_DATA") : std::string(SHOAL_SOURCE_DIR) + "/../shared/data";
    int vessels = 500, fixes = 2000;
    unsigned jobs = 0;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--data") data = argv[i + 1];
        else if (a == "--vessels") vessels = std::atoi(argv[i + 1]);
        else if (a == "--fixes") fixes = std::atoi(argv[i + 1]);
        else if (a == "--jobs") jobs = static_cast<unsigned>(std::atoi(argv[i + 1]));
    }
    const fs::path coast = fs::path(data) / "coast/gshhg/gof_helsinki_land.geojson";
    if (!fs::exists(coast)) {
        std::fprintf(stderr, "bench_audit: %s not found: give the shared data folder with --data DIR or $SHOAL_SHARED_DATA\n", coast.c_str());
        return 2;
    }
    const coast::Coastline c = coast::import_coastline({coast.string()});
    const geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({(c.min.lon + c.max.lon) / 2, (c.min.lat + c.max.lat) / 2});
    const auto lines = coast::project(c, frame);
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
    std::mt19937_64 rng(2026);
    const fs::path dir = fs::temp_directory_path() / "shoal-bench-audit";
    fs::create_directories(dir);
    std::printf("coast %s (%zu polylines), %d vessels x %d fixes each, jobs %u (0 = all cores)\n", coast.filename().c_str(), lines.size(),
                vessels, fixes, jobs);
    auto rows = open_water(grid, vessels, fixes, rng);
    write_csv(dir / "open.csv", rows);
    rows = near_coast(lines, grid, vessels, fixes, rng);
    write_csv(dir / "near.csv", rows);
    if (std::getenv("SHOAL_BENCH_KEEP")) std::printf("kept the CSVs in %s\n", dir.c_str());
    std::printf("CSV sizes: open water %.1f MB, near coast %.1f MB\n", static_cast<double>(fs::file_size(dir / "open.csv")) / 1e6,
                static_cast<double>(fs::file_size(dir / "near.csv")) / 1e6);
    run("open water", dir / "open.csv", grid, jobs);
    run("near coast", dir / "near.csv", grid, jobs);
    if (!std::getenv("SHOAL_BENCH_KEEP")) fs::remove_all(dir);
    return 0;
}
