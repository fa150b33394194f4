// probe::Probe, the one face for checking poses: against the brute-force traversal on random
// poses (near the coast, in open water, on land, outside the chart, and not valid), the same
// answers on any number of threads, and the same answers through its three renderings: `shoal
// probe`, the C API's shoal_check (and Python's Detector.check: tests/python/test_detector.py).
#include <gtest/gtest.h>

#include <shoal/shoal.h>

#include <shoal/check/brute_force.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/grid/grid_file.hpp>
#include <shoal/probe/probe.hpp>
#include <shoal/util/error.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>

namespace shoal::probe {
namespace {

namespace fs = std::filesystem;
using geo::XY;

/// The Solent's coast, its grid (500 m cells) in a frame centred on it, and random poses over
/// the coast's box grown by a fifth each way: a part of them lies outside the chart.
struct Solent {
    coast::Coastline coast = coast::import_coastline({SHOAL_TEST_DATA "coast/uk_solent_land.geojson"});
    geo::LocalFrame frame =
        geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
    std::vector<coast::LocalPolyline> lines = coast::project(coast, frame);
    grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
    hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18});

    std::vector<check::Pose> poses(std::size_t n, std::uint64_t seed) const {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> unit(0, 1);
        const double w = coast.max.lon - coast.min.lon, h = coast.max.lat - coast.min.lat;
        std::vector<check::Pose> out;
        for (std::size_t k = 0; k < n; ++k) {
            geo::LonLat p;
            if (k % 10 == 1) {  // 20 m inside an edge of the chart: the hull reaches out of it
                const geo::Box e = grid.extent();
                const double t = unit(rng);
                const XY q = k % 40 == 1   ? XY{e.minx + 20, e.miny + t * (e.maxy - e.miny)}
                             : k % 40 == 11 ? XY{e.maxx - 20, e.miny + t * (e.maxy - e.miny)}
                             : k % 40 == 21 ? XY{e.minx + t * (e.maxx - e.minx), e.miny + 20}
                                            : XY{e.minx + t * (e.maxx - e.minx), e.maxy - 20};
                p = frame.inverse(q);
            } else if (k % 3 == 0) {  // anywhere over the grown box: open water, land, outside the chart
                p = {coast.min.lon - 0.2 * w + 1.4 * w * unit(rng), coast.min.lat - 0.2 * h + 1.4 * h * unit(rng)};
            } else {  // within a hull's reach of a coast vertex
                const auto& l = lines[rng() % lines.size()];
                const XY on = l.points[rng() % l.points.size()];
                const double r = 2.5 * hull.radius() * unit(rng), a = 2 * std::numbers::pi * unit(rng);
                p = frame.inverse(on + XY{r * std::cos(a), r * std::sin(a)});
            }
            out.push_back({p, -720 + 1440 * unit(rng)});
        }
        return out;
    }
};

const Solent& setup() {
    static const Solent s;
    return s;
}

TEST(Probe, AgreesWithBruteForceAndClaimsNothingOutsideTheChart) {
    const Solent& s = setup();
    const Probe probe(s.grid, s.hull);
    const check::BruteForce brute(s.lines, s.hull);
    std::vector<check::Pose> poses = s.poses(3000, 41);
    // Not valid: each refused, the first one named.
    poses[100].position.lat = NAN;
    poses[2000].position.lat = 95;
    poses[2500].position.lon = -181;
    poses[2999].heading_deg = INFINITY;
    const Batch batch = probe.check(poses, {}, 3);
    ASSERT_EQ(batch.answers.size(), poses.size());
    EXPECT_EQ(batch.invalid, 4u);
    EXPECT_EQ(batch.first_invalid, 100u);
    EXPECT_EQ(batch.first_problem, "latitude nan is not a number");
    std::size_t collisions = 0, outside = 0, outside_collisions = 0;
    const geo::Box ext = s.grid.extent();
    for (std::size_t k = 0; k < poses.size(); ++k) {
        const Answer& a = batch.answers[k];
        if (k == 100 || k == 2000 || k == 2500 || k == 2999) {
            EXPECT_FALSE(a.valid) << k;
            EXPECT_FALSE(a.claimed()) << k;
            EXPECT_TRUE(std::isnan(a.clearance_m)) << k;
            continue;
        }
        ASSERT_TRUE(a.valid) << k;
        const check::LocalPose local = probe.place(poses[k]);
        const check::Contact b = brute.check(local);
        // Covered, independently: the outline's box inside the grid's extent (a pose within a
        // micrometre of the edge is left out: rounding may put it either side).
        geo::Box box;
        for (const XY& q : check::hull_outline(s.hull, local)) box.extend(q);
        const double in = std::min({box.minx - ext.minx, box.miny - ext.miny, ext.maxx - box.maxx, ext.maxy - box.maxy});
        if (std::fabs(in) > 1e-6) {
            EXPECT_EQ(a.covered, in > 0) << k;
        }
        EXPECT_EQ(a.collision, b.collision) << "pose " << k;
        collisions += a.collision;
        outside += !a.covered;
        outside_collisions += !a.covered && a.collision;
        // The rule: inside the chart, or a collision found, the answer is claimed.
        EXPECT_EQ(a.claimed(), a.covered || a.collision) << k;
        if (a.collision) {
            EXPECT_EQ(a.clearance_m, 0.0) << k;
        } else if (a.covered) {
            EXPECT_NEAR(a.clearance_m, b.clearance_m, 1e-6) << k;
        } else {
            EXPECT_TRUE(std::isnan(a.clearance_m)) << k;
        }
        EXPECT_TRUE(std::isnan(a.penetration_m)) << k;  // not asked
    }
    EXPECT_EQ(batch.uncovered, outside);
    // The poses reach every case.
    EXPECT_GT(collisions, 300u);
    EXPECT_GT(outside, 200u);
    EXPECT_GT(outside_collisions, 5u);
    EXPECT_GT(poses.size() - collisions - outside, 300u);

    // One pose at a time: the same; a pose not valid is an InputError naming it.
    for (std::size_t k = 0; k < poses.size(); k += 7) {
        if (!batch.answers[k].valid) continue;
        const Answer one = probe.check(poses[k]);
        EXPECT_EQ(one.covered, batch.answers[k].covered) << k;
        EXPECT_EQ(one.collision, batch.answers[k].collision) << k;
        EXPECT_EQ(std::isnan(one.clearance_m) ? -1.0 : one.clearance_m,
                  std::isnan(batch.answers[k].clearance_m) ? -1.0 : batch.answers[k].clearance_m) << k;
    }
    try {
        (void)probe.check(poses[2000]);
        ADD_FAILURE() << "no error for latitude 95";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "latitude 95 is outside [-90, 90]");
    }
}

TEST(Probe, TheSameAnswersOnAnyNumberOfThreads) {
    const Solent& s = setup();
    const Probe probe(s.grid, s.hull);
    const std::vector<check::Pose> poses = s.poses(3 * check::placement_block + 17, 7);
    const Ask ask{.max_clearance_m = 800, .want_penetration = true};
    const Batch one = probe.check(poses, ask, 1);
    for (unsigned jobs : {2u, 5u}) {
        const Batch many = probe.check(poses, ask, jobs);
        EXPECT_EQ(many.uncovered, one.uncovered);
        for (std::size_t k = 0; k < poses.size(); ++k) {
            const Answer &a = one.answers[k], &b = many.answers[k];
            ASSERT_EQ(a.collision, b.collision) << k;
            ASSERT_EQ(a.covered, b.covered) << k;
            ASSERT_TRUE(a.clearance_m == b.clearance_m || (std::isnan(a.clearance_m) && std::isnan(b.clearance_m))) << k;
            ASSERT_TRUE(a.penetration_m == b.penetration_m || (std::isnan(a.penetration_m) && std::isnan(b.penetration_m))) << k;
            if (a.collision) {
                EXPECT_GE(a.penetration_m, 0) << k;
            }
            if (a.claimed() && !a.collision) {
                EXPECT_TRUE(a.clearance_m > 0 && (a.clearance_m <= 800 || std::isinf(a.clearance_m))) << k;
            }
        }
    }
}

int run(const std::string& cmd) {
    const int st = std::system(cmd.c_str());
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

std::string fixed(double v, int decimals) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

TEST(Probe, ShoalProbeAndTheCApiRenderItsAnswers) {
    const Solent& s = setup();
    const fs::path dir = fs::temp_directory_path() / ("shoal-probe-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string grid_path = (dir / "solent.shoalgrid").string();
    grid::GridFile::save(s.grid, grid_path);
    const grid::CoastGrid loaded = grid::GridFile::load(grid_path);
    const Probe probe(loaded, s.hull);
    // The poses as `shoal probe` reads them back (7 decimals; the heading in [0, 360) to 0.1°).
    std::vector<check::Pose> poses = s.poses(2000, 99);
    std::ostringstream csv;
    csv << "lat,lon,heading\n";
    for (check::Pose& p : poses) {
        p.heading_deg = std::fmod(std::fmod(p.heading_deg, 360.0) + 360.0, 360.0);
        csv << fixed(p.position.lat, 7) << ',' << fixed(p.position.lon, 7) << ',' << fixed(p.heading_deg, 1) << '\n';
        p = {{std::stod(fixed(p.position.lon, 7)), std::stod(fixed(p.position.lat, 7))}, std::stod(fixed(p.heading_deg, 1))};
    }
    std::ofstream((dir / "poses.csv").string()) << csv.str();
    ASSERT_EQ(run("'" SHOAL_BINARY "' probe --coast '" + grid_path + "' --dims 150,40,14,18 '" + (dir / "poses.csv").string() + "' -o '" +
                  (dir / "out.csv").string() + "' 2> /dev/null"),
              0);
    const Batch batch = probe.check(poses);
    std::ifstream in((dir / "out.csv").string());
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "lat,lon,heading,collision,clearance_m,covered");

    shoal_grid* cg = shoal_grid_load(grid_path.c_str());
    ASSERT_NE(cg, nullptr) << shoal_last_error();
    shoal_detector* cd = shoal_detector_new(cg, 150, 40, 14, 18);
    ASSERT_NE(cd, nullptr) << shoal_last_error();
    std::size_t outside = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
        const Answer& a = batch.answers[k];
        ASSERT_TRUE(a.valid) << k;
        ASSERT_TRUE(std::getline(in, line)) << k;
        const std::string head = fixed(poses[k].position.lat, 7) + ',' + fixed(poses[k].position.lon, 7) + ',' + fixed(poses[k].heading_deg, 1);
        const std::string want = !a.claimed() ? ",,,0" : std::string(a.collision ? ",1," : ",0,") + fixed(a.clearance_m, 3) + (a.covered ? ",1" : ",0");
        EXPECT_EQ(line, head + want) << "pose " << k;
        shoal_contact c{};
        ASSERT_EQ(shoal_check(cd, poses[k].position.lat, poses[k].position.lon, poses[k].heading_deg, INFINITY, &c), 0) << shoal_last_error();
        EXPECT_EQ(c.covered, a.covered ? 1 : 0) << k;
        EXPECT_EQ(c.contact, a.collision ? 1 : 0) << k;
        EXPECT_EQ(c.clearance_m, a.claimed() ? a.clearance_m : -1.0) << k;
        outside += !a.claimed();
    }
    EXPECT_FALSE(std::getline(in, line)) << "a row more: " << line;
    EXPECT_GT(outside, 100u);
    // Not valid: the C API's own words.
    shoal_contact c{};
    EXPECT_EQ(shoal_check(cd, 95, 0, 0, INFINITY, &c), 1);
    EXPECT_STREQ(shoal_last_error(), "shoal_check: lat must be in [-90, 90], lon in [-180, 180] and the heading finite");
    shoal_detector_free(cd);
    shoal_grid_free(cg);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace shoal::probe
