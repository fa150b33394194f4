// The C API (include/shoal/shoal.h, libshoal_c) against `shoal probe` on thousands of poses,
// and its error handling: NULL results with a message, never an exception across C.

#include <gtest/gtest.h>

#include <shoal/shoal.h>
#include <shoal/version.hpp>

#include <shoal/check/detector.hpp>
#include <shoal/check/surroundings.hpp>
#include <shoal/geo/jacobian_field.hpp>
#include <shoal/grid/grid_file.hpp>
#include <shoal/hull/hull.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

/// A folder for this run's files, removed when the tests end.
fs::path temp_dir() {
    static const shoal::test::TempDir d;
    return d.path();
}

int run(const std::string& cmd) {
    const int st = std::system(cmd.c_str());
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/// A grid of the Solent, built once with the shoal executable.
const std::string& solent_grid() {
    static const std::string path = [] {
        const std::string g = (temp_dir() / "solent.shoalgrid").string();
        EXPECT_EQ(run("'" SHOAL_BINARY "' import '" SHOAL_TEST_DATA "coast/uk_solent_land.geojson' -o '" + g + "' > /dev/null"), 0);
        return g;
    }();
    return path;
}

TEST(CApi, VersionIsTheHeadersVersion) { EXPECT_STREQ(shoal_version(), SHOAL_VERSION_STRING); }

TEST(CApi, AgreesWithShoalProbeOnThousandsOfPoses) {
    shoal_grid* grid = shoal_grid_load(solent_grid().c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    EXPECT_EQ(shoal_last_error(), nullptr);
    shoal_detector* det = shoal_detector_new(grid, 100, 20, 8, 8);
    ASSERT_NE(det, nullptr) << shoal_last_error();
    shoal_grid_free(grid);  // the detector keeps it alive
    // Poses over the Solent and a little beyond the chart (uncovered ones too).
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> lat(50.50, 51.00), lon(-1.85, -0.85), hdg(0, 360);
    const fs::path poses = temp_dir() / "poses.csv";
    std::vector<std::array<double, 3>> p;
    {
        std::ofstream out(poses);
        out << "lat,lon,heading\n";
        char row[96];
        for (int k = 0; k < 3000; ++k) {
            p.push_back({lat(rng), lon(rng), std::round(hdg(rng) * 10) / 10});
            std::snprintf(row, sizeof row, "%.7f,%.7f,%.1f\n", p.back()[0], p.back()[1], p.back()[2]);
            out << row;
        }
    }
    const fs::path probed = temp_dir() / "probed.csv";
    ASSERT_EQ(run("'" SHOAL_BINARY "' probe --coast '" + solent_grid() + "' --dims 100,20,8,8 '" + poses.string() + "' -o '" +
                  probed.string() + "' 2> /dev/null"),
              0);
    std::ifstream in(probed);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "lat,lon,heading,collision,clearance_m,covered");
    std::size_t contacts = 0, clear = 0, uncovered = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
        ASSERT_TRUE(std::getline(in, line));
        // Read back the pose as probe printed it, so that both check the same numbers.
        double la = 0, lo = 0, h = 0;
        ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &la, &lo, &h), 3) << line;
        shoal_contact c{};
        ASSERT_EQ(shoal_check(det, la, lo, h, INFINITY, &c), 0) << shoal_last_error();
        char mine[160];
        if (c.covered || c.contact)
            std::snprintf(mine, sizeof mine, "%.7f,%.7f,%.1f,%d,%.3f,%d", la, lo, h, c.contact, c.clearance_m, c.covered);
        else
            std::snprintf(mine, sizeof mine, "%.7f,%.7f,%.1f,,,0", la, lo, h);
        ASSERT_EQ(line, mine);
        (c.contact ? contacts : !c.covered ? uncovered : clear) += 1;
        // The clearance is capped at the search limit asked for.
        if (c.covered && !c.contact) {
            shoal_contact capped{};
            ASSERT_EQ(shoal_check(det, la, lo, h, 10.0, &capped), 0);
            EXPECT_LE(capped.clearance_m, 10.0);
            EXPECT_DOUBLE_EQ(capped.clearance_m, std::min(10.0, c.clearance_m));
        }
    }
    EXPECT_GT(contacts, 100u);
    EXPECT_GT(clear, 100u);
    EXPECT_GT(uncovered, 10u);
    shoal_detector_free(det);
}

TEST(CApi, HugeFiniteHeadingsAreNormalisedAsShoalProbeNormalisesThem) {
    // A heading of 5.72e307 or more once overflowed to infinity inside the check: a pose on
    // land was "no contact, covered, clear" while probe, which normalises it, said collision.
    shoal_grid* grid = shoal_grid_load(solent_grid().c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    shoal_detector* det = shoal_detector_new(grid, 100, 20, 8, 8);
    ASSERT_NE(det, nullptr) << shoal_last_error();
    shoal_grid_free(grid);
    const std::vector<double> headings{5.72e307, 1e308, -1e308, 1.7976931348623157e308, -1.7976931348623157e308, 3.6e12 + 45, -90, 720.5, 359.9999999};
    const std::vector<std::array<double, 2>> places{{50.67, -1.30}, {50.76, -1.30}, {50.7735, -1.303}};  // inland on Wight, open water, the shore
    const fs::path poses = temp_dir() / "huge-headings.csv", probed = temp_dir() / "huge-headings-probed.csv";
    {
        std::ofstream out(poses);
        out << "lat,lon,heading\n";
        char row[128];
        for (const auto& p : places)
            for (const double h : headings) {
                std::snprintf(row, sizeof row, "%.7f,%.7f,%.17g\n", p[0], p[1], h);
                out << row;
            }
    }
    ASSERT_EQ(run("'" SHOAL_BINARY "' probe --coast '" + solent_grid() + "' --dims 100,20,8,8 '" + poses.string() + "' -o '" + probed.string() +
                  "' 2> /dev/null"),
              0);
    std::ifstream in(probed);
    std::string line;
    std::getline(in, line);
    std::size_t inland_contacts = 0;
    for (std::size_t i = 0; i < places.size(); ++i)
        for (const double h : headings) {
            ASSERT_TRUE(std::getline(in, line));
            const std::string answer = line.substr(line.find(',', line.find(',', line.find(',') + 1) + 1) + 1);  // collision,clearance_m,covered
            shoal_contact c{};
            ASSERT_EQ(shoal_check(det, places[i][0], places[i][1], h, INFINITY, &c), 0) << shoal_last_error();
            char mine[96];
            if (c.covered || c.contact) std::snprintf(mine, sizeof mine, "%d,%.3f,%d", c.contact, c.clearance_m, c.covered);
            else std::snprintf(mine, sizeof mine, ",,0");
            EXPECT_EQ(answer, mine) << "heading " << h << " at " << places[i][0] << "," << places[i][1];
            if (i == 0) inland_contacts += c.contact;
            // The heading normalised as probe does it gives the same answer, bit for bit.
            double n = std::fmod(h, 360.0);
            if (n < 0) n += 360.0;
            shoal_contact d{};
            ASSERT_EQ(shoal_check(det, places[i][0], places[i][1], n, INFINITY, &d), 0);
            EXPECT_EQ(c.contact, d.contact);
            EXPECT_EQ(c.covered, d.covered);
            EXPECT_EQ(c.clearance_m, d.clearance_m) << h;
        }
    EXPECT_EQ(inland_contacts, headings.size()) << "inland every heading is a contact";
    shoal_detector_free(det);
}

// The header promises that one detector may serve several threads at once. PROJ objects may
// not be shared between threads, so this is true only because each thread projects with its
// own copy: four threads checking at once give, pose for pose, what one thread gives alone.
TEST(CApi, ThreadsShareOneDetector) {
    shoal_grid* grid = shoal_grid_load(solent_grid().c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    shoal_detector* det = shoal_detector_new(grid, 100, 20, 8, 8);
    ASSERT_NE(det, nullptr) << shoal_last_error();
    constexpr int threads = 4, per_thread = 3000;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> lat(50.60, 50.85), lon(-1.60, -1.00), hdg(0, 360);
    struct Query {
        double lat, lon, hdg;
        shoal_contact alone;
    };
    std::vector<Query> queries(threads * per_thread);
    for (Query& q : queries) {
        q = {lat(rng), lon(rng), hdg(rng), {}};
        ASSERT_EQ(shoal_check(det, q.lat, q.lon, q.hdg, 500, &q.alone), 0) << shoal_last_error();
    }
    std::vector<int> mismatches(threads, 0), failures(threads, 0);
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (int i = t * per_thread; i < (t + 1) * per_thread; ++i) {
                const Query& q = queries[i];
                shoal_contact c{};
                if (shoal_check(det, q.lat, q.lon, q.hdg, 500, &c) != 0) {
                    ++failures[t];
                    continue;
                }
                if (c.covered != q.alone.covered || c.contact != q.alone.contact || c.clearance_m != q.alone.clearance_m)
                    ++mismatches[t];
            }
        });
    for (std::thread& th : pool) th.join();
    for (int t = 0; t < threads; ++t) {
        EXPECT_EQ(failures[t], 0) << "thread " << t;
        EXPECT_EQ(mismatches[t], 0) << "thread " << t;
    }
    int contacts = 0;
    for (const Query& q : queries) contacts += q.alone.contact;
    EXPECT_GT(contacts, 100);  // the poses reach land, not only open water
    EXPECT_LT(contacts, threads * per_thread - 100);
    shoal_detector_free(det);
    shoal_grid_free(grid);
}

TEST(CApi, ErrorsAreNullWithAMessageOfThisThread) {
    EXPECT_EQ(shoal_grid_load("/nonexistent/x.shoalgrid"), nullptr);
    ASSERT_NE(shoal_last_error(), nullptr);
    EXPECT_NE(std::string(shoal_last_error()).find("/nonexistent/x.shoalgrid"), std::string::npos) << shoal_last_error();
    EXPECT_EQ(shoal_grid_load(nullptr), nullptr);
    shoal_grid* grid = shoal_grid_load(solent_grid().c_str());
    ASSERT_NE(grid, nullptr);
    EXPECT_EQ(shoal_last_error(), nullptr) << "a success clears the message";
    EXPECT_EQ(shoal_detector_new(grid, -1, 20, 8, 8), nullptr);
    EXPECT_NE(shoal_last_error(), nullptr);
    EXPECT_EQ(shoal_detector_new(nullptr, 100, 20, 8, 8), nullptr);
    EXPECT_EQ(shoal_detector_from_ship_file(grid, "/nonexistent/ship.json"), nullptr);
    EXPECT_NE(std::string(shoal_last_error()).find("ship.json"), std::string::npos);
    shoal_detector* det = shoal_detector_from_ship_file(grid, SHOAL_TEST_DATA "../../examples/ship.json");
    ASSERT_NE(det, nullptr) << shoal_last_error();
    shoal_contact c{};
    EXPECT_NE(shoal_check(det, 91, 0, 0, 100, &c), 0);
    EXPECT_NE(shoal_check(det, 50.7, -1.3, NAN, 100, &c), 0);
    EXPECT_NE(shoal_check(det, 50.7, -1.3, 0, 0, &c), 0);
    EXPECT_NE(shoal_check(det, 50.7, -1.3, 0, 100, nullptr), 0);
    EXPECT_NE(shoal_check(nullptr, 50.7, -1.3, 0, 100, &c), 0);
    EXPECT_EQ(shoal_check(det, 50.76, -1.30, 45, 100, &c), 0);
    EXPECT_EQ(c.contact, 1) << "inland on the Isle of Wight";
    shoal_detector_free(det);
    shoal_grid_free(grid);
    shoal_grid_free(nullptr);
    shoal_detector_free(nullptr);
}

/// One grid of the S-57 cut (depth areas kept with their depths, no default limit): detectors
/// at two limiting depths off it. The 3.6 m depth area at (-76.45138, 38.92249) is water at
/// 3.5 m and a hazard at 4.5 m (tests/grid/hazard_test.cpp checks the same against GEOS).
TEST(CApi, DetectorsAtTheirOwnLimitingDepthShareOneGrid) {
    const std::string g = (temp_dir() / "cut.shoalgrid").string();
    ASSERT_EQ(run("'" SHOAL_BINARY "' import '" SHOAL_TEST_DATA "coast/US4MD81M_hazard_cut.000' --cell 300 -o '" + g + "' > /dev/null"), 0);
    shoal_grid* grid = shoal_grid_load(g.c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    shoal_detector* shallow = shoal_detector_new_at_depth(grid, 45, 15, 5, 5, 3.5);
    shoal_detector* deep = shoal_detector_new_at_depth(grid, 45, 15, 5, 5, 4.5);
    shoal_detector* land = shoal_detector_new_at_depth(grid, 45, 15, 5, 5, NAN);
    shoal_detector* dflt = shoal_detector_new(grid, 45, 15, 5, 5);
    shoal_detector* ship = shoal_detector_from_ship_file_at_depth(grid, SHOAL_TEST_DATA "../../examples/ship.json", 4.5);
    ASSERT_TRUE(shallow && deep && land && dflt && ship) << shoal_last_error();
    shoal_contact c{};
    ASSERT_EQ(shoal_check(shallow, 38.92249, -76.45138, 30, 500, &c), 0);
    EXPECT_EQ(c.contact, 0);
    EXPECT_GT(c.clearance_m, 100);
    ASSERT_EQ(shoal_check(deep, 38.92249, -76.45138, 30, 500, &c), 0);
    EXPECT_EQ(c.contact, 1);
    ASSERT_EQ(shoal_check(ship, 38.92249, -76.45138, 30, 500, &c), 0);
    EXPECT_EQ(c.contact, 1);
    ASSERT_EQ(shoal_check(land, 38.92249, -76.45138, 30, 500, &c), 0);
    EXPECT_EQ(c.contact, 0);
    ASSERT_EQ(shoal_check(dflt, 38.92249, -76.45138, 30, 500, &c), 0);
    EXPECT_EQ(c.contact, 0) << "a grid without a default limiting depth: land only";
    EXPECT_EQ(shoal_detector_new_at_depth(grid, 45, 15, 5, 5, INFINITY), nullptr);
    EXPECT_NE(std::string(shoal_last_error()).find("finite"), std::string::npos);
    for (shoal_detector* d : {shallow, deep, land, dflt, ship}) shoal_detector_free(d);
    shoal_grid_free(grid);
}

/// NaN equal to NaN, else the same double.
bool same(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

/// shoal_surroundings_at on the S-57 cut (depth areas, dangers, land) at random poses: the
/// same numbers as check::surroundings on the same grid file, detector and placement, and
/// the same again from two threads at once.
TEST(CApi, SurroundingsEqualTheLibrarys) {
    const std::string g = (temp_dir() / "cut-surroundings.shoalgrid").string();
    ASSERT_EQ(run("'" SHOAL_BINARY "' import '" SHOAL_TEST_DATA "coast/US4MD81M_hazard_cut.000' --cell 300 -o '" + g + "' > /dev/null"), 0);
    shoal_grid* grid = shoal_grid_load(g.c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    shoal_detector* det = shoal_detector_new_at_depth(grid, 45, 15, 5, 5, 4.5);
    ASSERT_NE(det, nullptr) << shoal_last_error();
    const shoal::grid::CoastGrid base = shoal::grid::GridFile::load(g);
    const shoal::check::Detector cpp(base, shoal::hull::Hull::from_dimensions({45, 15, 5, 5}), 4.5);
    const shoal::geo::JacobianField field(base.frame(), base.extent());
    const shoal::geo::Box ext = base.extent();
    const shoal::geo::LonLat sw = base.frame().inverse({ext.minx, ext.miny}), ne = base.frame().inverse({ext.maxx, ext.maxy});
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> lat(sw.lat, ne.lat), lon(sw.lon, ne.lon), hdg(0, 360);
    struct Query {
        double lat, lon, hdg, max_m;
        shoal_surroundings alone;
    };
    std::vector<Query> queries(1200);
    int on_land = 0, known = 0, unknown = 0, contact = 0, covered = 0;
    for (std::size_t k = 0; k < queries.size(); ++k) {
        Query& q = queries[k];
        q = {lat(rng), lon(rng), hdg(rng), k % 3 == 0 ? INFINITY : 300.0 + static_cast<double>(k), {}};
        ASSERT_EQ(shoal_surroundings_at(det, q.lat, q.lon, q.hdg, q.max_m, &q.alone), 0) << shoal_last_error();
        EXPECT_EQ(shoal_last_error(), nullptr);
        const shoal::check::Surroundings want =
            shoal::check::surroundings(cpp, base, shoal::check::place(base.frame(), field, {{q.lon, q.lat}, q.hdg}), q.max_m);
        const shoal_surroundings& r = q.alone;
        const std::string where = "pose " + std::to_string(k);
        EXPECT_EQ(r.covered, want.covered ? 1 : 0) << where;
        EXPECT_EQ(r.port_m, want.port_m) << where;
        EXPECT_EQ(r.starboard_m, want.starboard_m) << where;
        EXPECT_EQ(r.ahead_m, want.ahead_m) << where;
        EXPECT_EQ(r.astern_m, want.astern_m) << where;
        EXPECT_TRUE(same(r.least_depth_m, want.least_depth_m)) << where << ": " << r.least_depth_m << " vs " << want.least_depth_m;
        on_land += r.least_depth_m == 0;
        known += r.least_depth_m > 0 || r.least_depth_m < 0;
        unknown += std::isnan(r.least_depth_m);
        contact += r.port_m == 0 && r.starboard_m == 0 && r.ahead_m == 0 && r.astern_m == 0;
        covered += r.covered;
    }
    std::printf("%zu poses: least depth 0 (land) %d, known %d, NaN %d; in contact %d; covered %d\n", queries.size(), on_land, known,
                unknown, contact, covered);
    EXPECT_GT(on_land, 20);
    EXPECT_GT(known, 200);
    EXPECT_GT(contact, 20);
    EXPECT_GT(covered, 100);
    // Two threads at once: the same answers.
    std::vector<int> mismatches(2, 0);
    std::vector<std::thread> pool;
    for (int t = 0; t < 2; ++t)
        pool.emplace_back([&, t] {
            for (std::size_t k = static_cast<std::size_t>(t); k < queries.size(); k += 2) {
                const Query& q = queries[k];
                shoal_surroundings r{};
                if (shoal_surroundings_at(det, q.lat, q.lon, q.hdg, q.max_m, &r) != 0 || r.covered != q.alone.covered ||
                    r.port_m != q.alone.port_m || r.starboard_m != q.alone.starboard_m || r.ahead_m != q.alone.ahead_m ||
                    r.astern_m != q.alone.astern_m || !same(r.least_depth_m, q.alone.least_depth_m))
                    ++mismatches[static_cast<std::size_t>(t)];
            }
        });
    for (std::thread& th : pool) th.join();
    EXPECT_EQ(mismatches[0] + mismatches[1], 0);
    shoal_detector_free(det);
    shoal_grid_free(grid);
}

TEST(CApi, SurroundingsRefuseBadArgumentsWithAMessage) {
    shoal_grid* grid = shoal_grid_load(solent_grid().c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    shoal_detector* det = shoal_detector_new(grid, 100, 20, 8, 8);
    ASSERT_NE(det, nullptr) << shoal_last_error();
    shoal_surroundings r{};
    auto refused = [&](const shoal_detector* d, double la, double lo, double h, double max_m, shoal_surroundings* out, const char* says) {
        const int rc = shoal_surroundings_at(d, la, lo, h, max_m, out);
        const char* msg = shoal_last_error();
        return rc != 0 && msg && std::string(msg).find("shoal_surroundings_at") != std::string::npos &&
               std::string(msg).find(says) != std::string::npos;
    };
    EXPECT_TRUE(refused(nullptr, 50.7, -1.3, 0, 100, &r, "NULL"));
    EXPECT_TRUE(refused(det, 50.7, -1.3, 0, 100, nullptr, "NULL"));
    EXPECT_TRUE(refused(det, 91, -1.3, 0, 100, &r, "lat"));
    EXPECT_TRUE(refused(det, NAN, -1.3, 0, 100, &r, "lat"));
    EXPECT_TRUE(refused(det, 50.7, -181, 0, 100, &r, "lon"));
    EXPECT_TRUE(refused(det, 50.7, -1.3, NAN, 100, &r, "heading"));
    EXPECT_TRUE(refused(det, 50.7, -1.3, INFINITY, 100, &r, "heading"));
    EXPECT_TRUE(refused(det, 50.7, -1.3, 0, 0, &r, "max_m"));
    EXPECT_TRUE(refused(det, 50.7, -1.3, 0, -5, &r, "max_m"));
    EXPECT_TRUE(refused(det, 50.7, -1.3, 0, NAN, &r, "max_m"));
    // INFINITY is allowed; a good call clears the message.
    ASSERT_EQ(shoal_surroundings_at(det, 50.76, -1.30, 45, INFINITY, &r), 0) << shoal_last_error();
    EXPECT_EQ(shoal_last_error(), nullptr);
    EXPECT_EQ(r.ahead_m, 0) << "inland on the Isle of Wight";
    EXPECT_EQ(r.least_depth_m, 0) << "on land";
    // Open water in the Solent, east of Cowes: clear some way in every direction.
    ASSERT_EQ(shoal_surroundings_at(det, 50.78, -1.20, 90, 5000, &r), 0) << shoal_last_error();
    EXPECT_EQ(r.covered, 1);
    EXPECT_GT(r.port_m, 0);
    EXPECT_GT(r.ahead_m, 0);
    EXPECT_TRUE(std::isnan(r.least_depth_m)) << "a grid of land only charts no depth";
    shoal_detector_free(det);
    shoal_grid_free(grid);
}

}  // namespace

// ---- contacts (shoal_contacts, shoal_ship_contacts) ----

namespace {

/// A quay: land south of latitude 60.1 (a rectangle 0.02 x 0.04 degrees), imported once.
const std::string& quay_grid() {
    static const std::string path = [] {
        // The edge along 60.1 N with a vertex every 0.0005 degrees: a parallel is curved in the
        // local frame (a chord of 0.04 degrees would lie 0.17 m north of it at its middle).
        const fs::path geojson = temp_dir() / "quay.geojson";
        std::ostringstream ring;
        ring << "[24.98,60.08],[25.02,60.08]";
        for (int k = 80; k >= 0; --k) ring << ",[" << 24.98 + 0.0005 * k << ",60.1]";
        ring << ",[24.98,60.08]";
        std::ofstream(geojson) << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"Test Quay"},)"
                               << R"("geometry":{"type":"Polygon","coordinates":[[)" << ring.str() << "]]}}]}";
        const std::string g = (temp_dir() / "quay.shoalgrid").string();
        EXPECT_EQ(run("'" SHOAL_BINARY "' import '" + geojson.string() + "' --cell 200 -o '" + g + "' > /dev/null"), 0);
        return g;
    }();
    return path;
}

constexpr double metres_per_degree_lat = 111'412.0;  // at 60 N (WGS84: 111,412 m)

}  // namespace

TEST(CApiContacts, BowIntoAStraightQuayFromTheNorth) {
    shoal_grid* grid = shoal_grid_load(quay_grid().c_str());
    ASSERT_NE(grid, nullptr) << shoal_last_error();
    shoal_detector* d = shoal_detector_new(grid, 100, 20, 8, 8);
    ASSERT_NE(d, nullptr);
    // Heading south, the bow (100 m ahead of the reference point) 2 m past the quay's edge.
    const double lat = 60.1 + (100 - 2) / metres_per_degree_lat;
    std::array<shoal_contact_point, 4> pts{};
    ASSERT_EQ(shoal_contacts(d, lat, 25.0, 180.0, pts.data(), 4), 1) << (shoal_last_error() ? shoal_last_error() : "");
    const shoal_contact_point& p = pts[0];
    EXPECT_NEAR(p.depth_m, 2.0, 0.02);
    EXPECT_NEAR(p.x_m, 100, 0.05);   // the bow
    EXPECT_NEAR(p.y_m, 0, 0.05);
    EXPECT_NEAR(p.nx, -1, 1e-3);     // astern frees it
    EXPECT_NEAR(p.ny, 0, 1e-3);
    EXPECT_NEAR(p.coast_lat, 60.1, 1e-7);
    EXPECT_NEAR(p.lat, 60.1 - 2 / metres_per_degree_lat, 1e-6);
    EXPECT_EQ(p.hazard, SHOAL_HAZARD_LAND);
    EXPECT_TRUE(std::isnan(p.charted_depth_m));
    ASSERT_NE(p.name, nullptr);
    // Count only: capacity 0 and no array.
    EXPECT_EQ(shoal_contacts(d, lat, 25.0, 180.0, nullptr, 0), 1);
    // Clear of the quay: none.
    EXPECT_EQ(shoal_contacts(d, lat + 10 / metres_per_degree_lat, 25.0, 180.0, pts.data(), 4), 0);
    shoal_detector_free(d);
    shoal_grid_free(grid);
}

TEST(CApiContacts, EveryCheckedContactHasARegionAndNoOtherPoseHasOne) {
    shoal_grid* grid = shoal_grid_load(solent_grid().c_str());
    ASSERT_NE(grid, nullptr);
    shoal_detector* d = shoal_detector_new(grid, 150, 35, 14, 15);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> lat(50.70, 50.85), lon(-1.45, -1.05), hdg(0, 360);
    int contacts = 0;
    std::array<shoal_contact_point, 8> pts{};
    for (int i = 0; i < 1500; ++i) {
        const double la = lat(rng), lo = lon(rng), h = hdg(rng);
        shoal_contact c{};
        ASSERT_EQ(shoal_check(d, la, lo, h, 1.0, &c), 0);
        const int n = shoal_contacts(d, la, lo, h, pts.data(), 8);
        ASSERT_GE(n, 0) << shoal_last_error();
        EXPECT_EQ(n > 0, c.contact == 1) << la << " " << lo << " " << h;
        for (int k = 0; k < std::min(n, 8); ++k) {
            EXPECT_GE(pts[k].depth_m, 0);
            EXPECT_NEAR(std::hypot(pts[k].nx, pts[k].ny), 1, 1e-9);
            if (k > 0) {
                EXPECT_GE(pts[k - 1].depth_m, pts[k].depth_m);  // deepest first
            }
        }
        contacts += n > 0;
    }
    EXPECT_GT(contacts, 100);
    shoal_detector_free(d);
    shoal_grid_free(grid);
}

TEST(CApiContacts, AHarbourStructureIsNamedAndKindOfStructure) {
    // The allision track of the Tacoma chart: its fixes walked until the hull touches a pier.
    const std::string g = (temp_dir() / "tacoma.shoalgrid").string();
    ASSERT_EQ(run("'" SHOAL_BINARY "' import '" SHOAL_TEST_DATA "coast/US5WA22M_tacoma_cut.000' -o '" + g + "' > /dev/null"), 0);
    shoal_grid* grid = shoal_grid_load(g.c_str());
    ASSERT_NE(grid, nullptr);
    shoal_detector* d = shoal_detector_new(grid, 48, 12, 6, 6);
    std::ifstream in(SHOAL_TEST_DATA "tracks/tacoma_pier_collision.csv");
    std::string line;
    std::getline(in, line);
    bool structure = false;
    std::array<shoal_contact_point, 8> pts{};
    while (std::getline(in, line) && !structure) {
        std::stringstream ss(line);
        std::vector<std::string> f;
        for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
        const double la = std::stod(f[2]), lo = std::stod(f[3]), h = std::stod(f[6]);
        const int n = shoal_contacts(d, la, lo, h, pts.data(), 8);
        ASSERT_GE(n, 0);
        for (int k = 0; k < std::min(n, 8); ++k)
            if (pts[k].hazard == SHOAL_HAZARD_STRUCTURE) {
                structure = true;
                EXPECT_TRUE(std::isnan(pts[k].charted_depth_m));
                ASSERT_NE(pts[k].name, nullptr);
            }
    }
    EXPECT_TRUE(structure) << "the allision track never touches a structure";
    shoal_detector_free(d);
    shoal_grid_free(grid);
}

TEST(CApiContacts, TwoShipsSideBySideAndBowIntoSide) {
    shoal_grid* grid = shoal_grid_load(quay_grid().c_str());
    shoal_detector* a = shoal_detector_new(grid, 60, 20, 5, 5);
    shoal_detector* b = shoal_detector_new(grid, 60, 20, 5, 5);
    const double lat = 60.2, lon = 25.0;
    const double m_per_deg_lon = 55'463.0;  // at 60.2 N (WGS84: N cos(lat) pi / 180)
    shoal_ship_contact sc{};
    std::array<shoal_contact_point, 4> pts{};
    // Both heading north, 30 m apart east-west: 20 m between their sides.
    ASSERT_EQ(shoal_ship_contacts(a, lat, lon, 0, b, lat, lon + 30 / m_per_deg_lon, 0, &sc, pts.data(), 4), 0);
    EXPECT_EQ(sc.contact, 0);
    EXPECT_NEAR(sc.clearance_m, 20, 0.2);
    // 9 m apart: a's starboard side 1 m inside b's port side; a's point there is freed by 1 m to port.
    const int n = shoal_ship_contacts(a, lat, lon, 0, b, lat, lon + 9 / m_per_deg_lon, 0, &sc, pts.data(), 4);
    ASSERT_EQ(n, 1) << (shoal_last_error() ? shoal_last_error() : "");
    EXPECT_EQ(sc.contact, 1);
    EXPECT_EQ(sc.clearance_m, 0);
    EXPECT_EQ(pts[0].hazard, SHOAL_HAZARD_SHIP);
    EXPECT_NEAR(pts[0].y_m, 5, 0.02);      // on a's starboard side
    EXPECT_NEAR(pts[0].depth_m, 1, 0.02);
    EXPECT_NEAR(pts[0].nx, 0, 1e-3);
    EXPECT_NEAR(pts[0].ny, -1, 1e-3);      // to port
    shoal_detector_free(a);
    shoal_detector_free(b);
    shoal_grid_free(grid);
}

TEST(CApiContacts, BadArgumentsAreMinusOneWithAMessage) {
    shoal_grid* grid = shoal_grid_load(quay_grid().c_str());
    shoal_detector* d = shoal_detector_new(grid, 100, 20, 8, 8);
    shoal_contact_point p{};
    EXPECT_EQ(shoal_contacts(nullptr, 60, 25, 0, &p, 1), -1);
    EXPECT_NE(shoal_last_error(), nullptr);
    EXPECT_EQ(shoal_contacts(d, 91, 25, 0, &p, 1), -1);
    EXPECT_EQ(shoal_contacts(d, 60, 25, NAN, &p, 1), -1);
    EXPECT_EQ(shoal_contacts(d, 60, 25, 0, &p, -1), -1);
    EXPECT_EQ(shoal_contacts(d, 60, 25, 0, nullptr, 3), -1);
    EXPECT_NE(std::string(shoal_last_error()).find("NULL"), std::string::npos);
    shoal_ship_contact sc{};
    EXPECT_EQ(shoal_ship_contacts(d, 60, 25, 0, nullptr, 60, 25, 0, &sc, nullptr, 0), -1);
    EXPECT_EQ(shoal_ship_contacts(d, 60, 25, 0, d, 60, 25, 0, nullptr, nullptr, 0), -1);
    EXPECT_EQ(shoal_contacts(d, 60.2, 25, 0, &p, 1), 0);
    EXPECT_EQ(shoal_last_error(), nullptr);
    shoal_detector_free(d);
    shoal_grid_free(grid);
}
