// The C API (include/shoal/shoal.h, libshoal_c) against `shoal probe` on thousands of poses,
// and its error handling: NULL results with a message, never an exception across C.

#include <gtest/gtest.h>

#include <shoal/shoal.h>
#include <shoal/version.hpp>

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

namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
    static const fs::path d = [] {
        fs::path p = fs::temp_directory_path() / ("shoal-c-api-test-" + std::to_string(::getpid()));
        fs::create_directories(p);
        return p;
    }();
    return d;
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

}  // namespace
