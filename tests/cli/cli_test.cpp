// The `shoal` executable as a user runs it: help for every command, exit statuses, one clear
// line on stderr for bad input, and whole runs whose outputs are read back independently
// (OGR for reports, the JSON Schema through Debian's Python for the report's structure).

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ogrsf_frmts.h>
#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;

struct Outcome {
    int status = -1;
    std::string out, err;
};

fs::path temp_dir() {
    static const fs::path d = [] {
        fs::path p = fs::temp_directory_path() / ("shoal-cli-test-" + std::to_string(::getpid()));
        fs::create_directories(p);
        return p;
    }();
    return d;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Runs shoal with `args` (a shell-quoted string); the grid cache goes to a temp folder.
Outcome shoal(const std::string& args) {
    const fs::path err = temp_dir() / "stderr.txt";
    const std::string cmd = "SHOAL_CACHE_DIR='" + (temp_dir() / "cache").string() + "' '" + SHOAL_BINARY + "' " + args +
                            " 2>'" + err.string() + "'";
    Outcome r;
    FILE* p = ::popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) r.out.append(buf.data(), n);
    const int st = ::pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    r.err = slurp(err);
    return r;
}

std::string data(const std::string& rel) { return "'" + std::string(SHOAL_TEST_DATA) + rel + "'"; }

std::size_t lines_of(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

TEST(Cli, EveryCommandHasHelpWithUsage) {
    for (const char* cmd : {"import", "info", "probe", "check"}) {
        const Outcome r = shoal(std::string(cmd) + " --help");
        EXPECT_EQ(r.status, 0) << cmd;
        EXPECT_NE(r.out.find("Usage: shoal " + std::string(cmd)), std::string::npos) << cmd << ":\n" << r.out;
    }
    const Outcome top = shoal("--help");
    EXPECT_EQ(top.status, 0);
    EXPECT_NE(top.out.find("Exit status"), std::string::npos);
}

TEST(Cli, ImportThenInfoTellsWhatTheGridHolds) {
    const fs::path grid = temp_dir() / "solent.shoalgrid";
    const Outcome imp = shoal("import " + data("coast/uk_solent_land.geojson") + " --cell 400 -o '" + grid.string() + "'");
    ASSERT_EQ(imp.status, 0) << imp.err;
    EXPECT_NE(imp.out.find("1977 vertices"), std::string::npos) << imp.out;  // README of the shared data: 1,977 vertices
    const Outcome info = shoal("info '" + grid.string() + "'");
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_NE(info.out.find("cell size:      400.0 m"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("uk_solent_land"), std::string::npos);
    EXPECT_TRUE(info.err.empty()) << info.err;
}

TEST(Cli, BadInputExitsWithStatusTwoAndOneClearLine) {
    const std::string out = "-o '" + (temp_dir() / "x.shoalgrid").string() + "'";
    struct Case {
        std::string args, expect;
    } cases[] = {
        {"import /nonexistent/coast.shp " + out, "nonexistent"},
        {"import " + data("coast/not_a_dataset.txt") + " " + out, "not_a_dataset.txt"},
        {"import " + data("coast/uk_solent_land.geojson") + " --layer NOPE " + out, "NOPE"},
        {"import " + data("coast/empty_collection.geojson") + " " + out, "no features"},
        {"import " + data("coast/projected_no_crs.shp") + " " + out, "no CRS"},
        {"info " + data("coast/uk_solent_land.geojson"), "not a shoal grid"},
        {"probe --coast " + data("coast/uk_solent_land.geojson") + " --dims 1,2,3 " + data("coast/uk_solent_land.geojson"), "--dims"},
    };
    for (const auto& c : cases) {
        const Outcome r = shoal(c.args);
        EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
        EXPECT_EQ(lines_of(r.err), 1u) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
    }
}

TEST(Cli, ProbeWritesOneRowPerPoseAndSkipsBadRows) {
    const fs::path poses = temp_dir() / "poses.csv";
    std::ofstream(poses) << "lat,lon,heading\n50.7600,-1.3000,45\n50.7000,-1.1000,90\nbad,row,here\n50.7900,-1.1100,180\n";
    const Outcome r = shoal("probe --coast " + data("coast/uk_solent_land.geojson") + " --dims 100,20,8,8 '" + poses.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lines_of(r.out), 4u) << r.out;  // header + 3 poses
    EXPECT_EQ(r.out.rfind("lat,lon,heading,collision,clearance_m\n", 0), 0u);
    EXPECT_NE(r.err.find("line 4"), std::string::npos) << r.err;
    // 50.76N 1.30W is inland on the Isle of Wight: a collision with clearance 0.
    EXPECT_NE(r.out.find("50.7600000,-1.3000000,45.0,1,0.000"), std::string::npos) << r.out;
}

}  // namespace
