// bench_pathological: what the pathological shapes of tests/pathological_shapes.hpp cost, so
// docs/performance.md can say they do not blow up. No data files: every shape is generated.
//
//   million   a coastline of 1,000,000 vertices in one ring (r = 20 km, 0.13 m apart), written
//             to a GeoPackage and taken through the real import, projection, grid build and
//             cache save + load; then poses near it checked.
//   comb      a cell crossed by thousands of segments: 5,000 near-vertical segments 0.1 m
//             apart across 500 m; poses just above the teeth.
//   hull1000  a 1,000-point hull (against the generated 36 points) near the million ring.
//   anchored  a track standing still for a day at 1 Hz (86,400 fixes) off the million ring:
//             still, and swinging (heading +-30 degrees per fix, 3 m of GPS jitter).
//
// For each pose set the detector, the brute-force traversal (the paper's method) and GEOS
// (a prepared polygon: GEOSPreparedIntersects, then GEOSPreparedDistance when clear) check the
// same poses; their answers are compared (a disagreement makes the exit status 1). Times are
// wall-clock on this process; peak memory is the process's maximum resident set so far.
//
// Usage: bench_pathological [--poses N] [--brute-seconds S]

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <shoal/sweep/sweep.hpp>
#include <shoal/check/brute_force.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>
#include "util/gdal_support.hpp"
#include "geo/geos_context.hpp"
#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_cache.hpp>
#include "pathological_shapes.hpp"

namespace {

using shoal::geo::XY;
namespace check = shoal::check;
namespace geo = shoal::geo;
namespace grid = shoal::grid;
namespace hull = shoal::hull;

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double peak_rss_mb() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

int disagreements = 0;

/// GEOS on the same land polygon: prepared once, then intersects (and distance when clear).
class GeosLand {
public:
    explicit GeosLand(const std::vector<XY>& ring) {
        m_land = geo::make_polygon(m_ctx, {ring});
        m_prepared = geo::PreparedPtr(GEOSPrepare_r(m_ctx, m_land.get()), {m_ctx.get()});
    }
    GeosLand(const GeosLand&) = delete;
    GeosLand& operator=(const GeosLand&) = delete;
    check::Contact check(std::vector<XY> outline) const {
        outline.push_back(outline.front());
        const geo::GeomPtr hull = geo::make_polygon(m_ctx, {outline});
        check::Contact c;
        c.collision = GEOSPreparedIntersects_r(m_ctx, m_prepared.get(), hull.get()) == 1;
        c.clearance_m = 0;
        if (!c.collision) GEOSPreparedDistance_r(m_ctx, m_prepared.get(), hull.get(), &c.clearance_m);
        return c;
    }

private:
    geo::GeosContext m_ctx;
    geo::GeomPtr m_land{nullptr, {m_ctx.get()}};
    geo::PreparedPtr m_prepared{nullptr, {m_ctx.get()}};
};

bool same(const check::Contact& a, const check::Contact& b) {
    return a.collision == b.collision && (a.collision || std::fabs(a.clearance_m - b.clearance_m) <= 1e-3);
}

/// Checks `poses` with the detector, GEOS and (within `brute_s` seconds) brute force; prints
/// one table row of microseconds per pose.
void time_poses(const char* label, const grid::CoastGrid& g, const std::vector<shoal::coast::LocalPolyline>& lines,
                const std::vector<XY>& land_ring, const hull::Hull& h, const std::vector<check::LocalPose>& poses,
                double brute_s) {
    const check::Detector det(g, h);
    std::vector<check::Contact> ours(poses.size());
    auto t = Clock::now();
    for (std::size_t k = 0; k < poses.size(); ++k) ours[k] = det.check(poses[k], {INFINITY, false});
    const double det_us = since(t) * 1e6 / static_cast<double>(poses.size());

    const GeosLand geos(land_ring);
    t = Clock::now();
    int hits = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
        const check::Contact c = geos.check(check::hull_outline(h, poses[k]));
        hits += c.collision;
        if (!same(c, ours[k])) ++disagreements;
    }
    const double geos_us = since(t) * 1e6 / static_cast<double>(poses.size());

    const check::BruteForce brute(lines, h);
    t = Clock::now();
    std::size_t n_brute = 0;
    for (; n_brute < poses.size() && (n_brute < 3 || since(t) < brute_s); ++n_brute)
        if (!same(brute.check(poses[n_brute]), ours[n_brute])) ++disagreements;
    const double brute_us = since(t) * 1e6 / static_cast<double>(n_brute);
    std::printf("| %s | %zu | %d | %.2f | %.1f | %.0f (%zu poses) | %.0fx |\n", label, poses.size(), hits, det_us, geos_us,
                brute_us, n_brute, geos_us / det_us);
}

void write_gpkg(const std::string& path, const std::vector<XY>& ring, const geo::LocalFrame& frame) {
    shoal::detail::register_drivers();
    GDALDatasetUniquePtr ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    OGRLayer* layer = ds->CreateLayer("land", &wgs84, wkbPolygon, nullptr);
    auto* lr = new OGRLinearRing;
    lr->setNumPoints(static_cast<int>(ring.size()), false);
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const geo::LonLat ll = frame.inverse(ring[i]);
        lr->setPoint(static_cast<int>(i), ll.lon, ll.lat);
    }
    OGRPolygon poly;
    poly.addRingDirectly(lr);
    OGRFeature f(layer->GetLayerDefn());
    f.SetGeometry(&poly);
    if (layer->CreateFeature(&f) != OGRERR_NONE) std::exit(2);
}

std::vector<check::LocalPose> poses_near(const std::vector<XY>& ring, double reach, std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<check::LocalPose> out;
    for (std::size_t k = 0; k < n; ++k) {
        const XY on = ring[rng() % (ring.size() - 1)];
        const double r = reach * unit(rng), a = 2 * std::numbers::pi * unit(rng);
        out.push_back(check::LocalPose::at(on + XY{r * std::cos(a), r * std::sin(a)}, 360 * unit(rng)));
    }
    return out;
}

shoal::track::Track anchored(XY where, double heading, const geo::LocalFrame& frame, double jitter, double swing,
                             std::size_t fixes) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    shoal::track::Track t;
    t.id = "anchored";
    double hdg = heading;
    for (std::size_t i = 0; i < fixes; ++i) {
        shoal::track::Fix f;
        f.time_s = 1.7e9 + static_cast<double>(i);
        f.position = frame.inverse(where + XY{jitter * unit(rng), jitter * unit(rng)});
        f.heading_used_deg = hdg;
        f.heading_source = shoal::track::HeadingSource::heading;
        f.line = i + 2;
        t.fixes.push_back(f);
        hdg = std::fmod(hdg + swing * unit(rng) + 360, 360);
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t n_poses = 2000;
    double brute_s = 2;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--poses") n_poses = std::stoul(argv[i + 1]);
        else if (a == "--brute-seconds") brute_s = std::stod(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: bench_pathological [--poses N] [--brute-seconds S]\n");
            return 2;
        }
    }
    const auto dir = std::filesystem::temp_directory_path() / ("shoal-bench-pathological-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);

    // --- a million vertices in one ring, through the real import ---------------------------
    const geo::LocalFrame made_in = geo::LocalFrame::transverse_mercator({10.0, 55.0});
    const std::vector<XY> ring = shoal::test::star_ring(1'000'000, 20'000, 0.05);
    const std::string gpkg = (dir / "million.gpkg").string();
    write_gpkg(gpkg, ring, made_in);
    std::printf("## A coastline of a million vertices in one ring\n\n| step | time | |\n|---|---:|---|\n");
    auto t = Clock::now();
    const shoal::coast::Coastline coast = shoal::coast::import_coastline({gpkg});
    std::printf("| import (OGR read, validity check) | %.2f s | %.1f MB GeoPackage |\n", since(t),
                static_cast<double>(std::filesystem::file_size(gpkg)) / 1e6);
    t = Clock::now();
    const auto lines = shoal::coast::project(coast, made_in);
    std::printf("| project | %.2f s | |\n", since(t));
    grid::BuildStats stats;
    t = Clock::now();
    const grid::CoastGrid g = grid::CoastGrid::build(lines, made_in, 500, &stats);
    std::size_t most = 0;
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) most = std::max(most, g.segments(i, j).size());
    std::printf("| grid build, 500 m cells | %.2f s | %zu coast cells, %zu segments, up to %zu in a cell, %.1f MB |\n",
                since(t), g.coast_cell_count(), g.segment_count(), most, static_cast<double>(g.memory_bytes()) / 1e6);
    const std::string cache = (dir / "million.shoalgrid").string();
    t = Clock::now();
    grid::GridFile::save(g, cache);
    const double save_s = since(t);
    t = Clock::now();
    const grid::CoastGrid loaded = grid::GridFile::load(cache);
    std::printf("| cache save / load | %.3f s / %.3f s | %.1f MB file |\n", save_s, since(t),
                static_cast<double>(std::filesystem::file_size(cache)) / 1e6);
    if (!(loaded == g)) ++disagreements;
    std::printf("\npeak memory so far: %.0f MB\n\n", peak_rss_mb());

    const hull::Hull ship = hull::Hull::from_dimensions({150, 40, 14, 18});
    const hull::Hull big = hull::Hull::from_contour(shoal::test::wavy_hull(1000), "1000 points");
    std::printf("## Pose checks (microseconds per pose; GEOS: prepared polygon)\n\n"
                "| case | poses | touching | detector | GEOS | brute force | GEOS / detector |\n"
                "|---|---:|---:|---:|---:|---:|---:|\n");
    time_poses("million ring, 36-point hull", g, lines, ring, ship, poses_near(ring, 2.5 * ship.radius(), n_poses, 1), brute_s);
    time_poses("million ring, 1,000-point hull", g, lines, ring, big, poses_near(ring, 2.5 * big.radius(), n_poses, 1), brute_s);

    // --- a cell crossed by thousands of segments -------------------------------------------
    const std::vector<XY> comb = shoal::test::comb_ring(5000, 500, 4000);
    const std::vector<shoal::coast::LocalPolyline> comb_lines{{comb, true}};
    t = Clock::now();
    const grid::CoastGrid cg = grid::CoastGrid::build(comb_lines, made_in, 500);
    const double comb_build = since(t);
    most = 0;
    for (int j = 0; j < cg.ny(); ++j)
        for (int i = 0; i < cg.nx(); ++i) most = std::max(most, cg.segments(i, j).size());
    std::vector<check::LocalPose> above;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(0, 1);
    for (std::size_t k = 0; k < n_poses; ++k)
        above.push_back(check::LocalPose::at({-300 + 1100 * unit(rng), 1800 + 500 * unit(rng)}, 360 * unit(rng)));
    time_poses("comb (up to thousands of segments per cell), 36-point hull", cg, comb_lines, comb, ship, above, brute_s);
    std::printf("\nComb grid: built in %.3f s, up to %zu segments in a cell.\n\n", comb_build, most);

    // --- a day at anchor at 1 Hz --------------------------------------------------------------
    std::printf("## A track standing still for a day (86,400 fixes at 1 Hz, 150 m off the million ring, along it)\n\n"
                "| case | sweep | poses checked | groundings | close passes |\n|---|---:|---:|---:|---:|\n");
    const shoal::audit::DetectorChecker checker(g, ship);
    // 150 m seaward of the crest of a bulge (t = pi / 74), lying along the coast.
    const XY crest = ring[1'000'000 / 148];
    const XY off = (1 + 150 / std::hypot(crest.x, crest.y)) * crest;
    const double along = 360 - 180.0 / 74;
    for (const auto& [label, jitter, swing] : {std::tuple{"still", 0.0, 0.0}, std::tuple{"swinging, 3 m jitter", 3.0, 30.0}}) {
        const shoal::track::Track tr = anchored(off, along, made_in, jitter, swing, 86'400);
        t = Clock::now();
        const shoal::audit::TrackResult r = shoal::audit::sweep_track(tr, made_in, checker, {});
        std::printf("| %s | %.2f s | %zu | %zu | %zu |\n", label, since(t), r.summary.poses, r.summary.groundings,
                    r.summary.close_passes);
    }
    std::printf("\npeak memory of the whole run: %.0f MB\n", peak_rss_mb());
    std::filesystem::remove_all(dir);
    if (disagreements) std::fprintf(stderr, "bench_pathological: %d disagreements\n", disagreements);
    return disagreements ? 1 : 0;
}
