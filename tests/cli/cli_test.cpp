// The `shoal` executable as a user runs it: help for every command, exit statuses, one clear
// line on stderr for bad input, and whole runs whose outputs are read back independently
// (OGR for reports, the JSON Schema through Debian's Python for the report's structure).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <ogrsf_frmts.h>
#include <sys/wait.h>

#include "run_shoal.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;

/// A folder for this run's files, removed when the tests end.
fs::path temp_dir() {
    static const shoal::test::TempDir d;
    return d.path();
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

using shoal::test::Outcome;

/// Runs shoal with `args` (a shell-quoted string); the grid cache goes to a temp folder.
Outcome shoal(const std::string& args) { return shoal::test::run_shoal(args, temp_dir() / "cache", temp_dir() / "stderr.txt"); }

std::string source_root() { return fs::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().string(); }

std::string data(const std::string& rel) { return "'" + std::string(SHOAL_TEST_DATA) + rel + "'"; }

std::size_t lines_of(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

TEST(Cli, EveryCommandHasHelpWithUsage) {
    // The commands are those the top-level help lists (not a list kept here), and each command
    // the README's usage shows is among them.
    const Outcome top = shoal("--help");
    EXPECT_EQ(top.status, 0);
    EXPECT_NE(top.out.find("Exit status"), std::string::npos);
    const std::size_t from = top.out.find("Subcommands:\n");
    ASSERT_NE(from, std::string::npos) << top.out;
    std::set<std::string> commands;
    std::istringstream listed(top.out.substr(from + 13));
    for (std::string line; std::getline(listed, line) && !line.empty();) {
        std::istringstream words(line);
        std::string name;
        words >> name;
        commands.insert(name);
    }
    std::ifstream readme(source_root() + "/README.md");
    std::set<std::string> documented;
    for (std::string line; std::getline(readme, line);)
        if (line.rfind("shoal ", 0) == 0) documented.insert(line.substr(6, line.find(' ', 6) - 6));
    EXPECT_GE(documented.size(), 5u) << "the README's usage lines";
    for (const std::string& d : documented) EXPECT_TRUE(commands.count(d)) << "the README shows 'shoal " << d << "', the help does not list it";
    for (const std::string& cmd : commands) {
        const Outcome r = shoal(cmd + " --help");
        EXPECT_EQ(r.status, 0) << cmd;
        EXPECT_NE(r.out.find("Usage: shoal " + cmd), std::string::npos) << cmd << ":\n" << r.out;
    }
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

// Issue 39: `shoal chek` said "A subcommand is required", hiding the typo. The unknown command is
// named, with the nearest one when it is near enough; nothing is run.
TEST(Cli, AMisspeltCommandIsNamedWithTheNearestOne) {
    const std::string list = "; the commands are import, info, probe, check, merge (see shoal --help)\n";
    const struct {
        std::string args, expect;
    } cases[] = {
        {"chek --coast x", "unknown command 'chek' (did you mean 'check'?)"},
        {"chekc", "unknown command 'chekc' (did you mean 'check'?)"},  // two letters swapped: one edit
        {"imprt x", "unknown command 'imprt' (did you mean 'import'?)"},
        {"Merge a b", "unknown command 'Merge' (did you mean 'merge'?)"},
        {"audit tracks.csv", "unknown command 'audit'"},  // nothing near: no guess
    };
    for (const auto& c : cases) {
        const Outcome r = shoal(c.args);
        EXPECT_EQ(r.status, 2) << c.args;
        EXPECT_EQ(r.err, "shoal: usage error: " + c.expect + list) << c.args;
        EXPECT_TRUE(r.out.empty()) << c.args;
    }
    // A command rightly spelt is as before; no command at all names the commands too.
    EXPECT_EQ(shoal("info --help").status, 0);
    const Outcome none = shoal("");
    EXPECT_EQ(none.status, 2);
    EXPECT_EQ(none.err, "shoal: usage error: no command given" + list);
}

TEST(Cli, ProbeWritesOneRowPerPoseAndSkipsBadRows) {
    const fs::path poses = temp_dir() / "poses.csv";
    std::ofstream(poses) << "lat,lon,heading\n50.7600,-1.3000,45\n50.7000,-1.1000,90\nbad,row,here\n50.7900,-1.1100,180\n";
    const Outcome r = shoal("probe --coast " + data("coast/uk_solent_land.geojson") + " --dims 100,20,8,8 '" + poses.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lines_of(r.out), 4u) << r.out;  // header + 3 poses
    EXPECT_EQ(r.out.rfind("lat,lon,heading,collision,clearance_m,covered\n", 0), 0u);
    EXPECT_NE(r.err.find("line 4"), std::string::npos) << r.err;
    // 50.76N 1.30W is inland on the Isle of Wight: a collision with clearance 0.
    EXPECT_NE(r.out.find("50.7600000,-1.3000000,45.0,1,0.000,1\n"), std::string::npos) << r.out;
    // Outside the chart nothing is claimed: collision and clearance empty, covered 0.
    std::ofstream(poses) << "lat,lon,heading\n10.0,10.0,0\n";
    const Outcome out = shoal("probe --coast " + data("coast/uk_solent_land.geojson") + " --dims 100,20,8,8 '" + poses.string() + "'");
    ASSERT_EQ(out.status, 0) << out.err;
    EXPECT_NE(out.out.find("10.0000000,10.0000000,0.0,,,0\n"), std::string::npos) << out.out;
    EXPECT_NE(out.err.find("outside the chart"), std::string::npos) << out.err;
}

TEST(Cli, ProbeOnSeveralThreadsWritesWhatOneThreadWrites) {
    // 13,000 poses over the Solent (land, shore, water, some partly off the chart): more than
    // three blocks of poses placed and checked at once. --jobs 1, 2 and 3 write the same bytes,
    // one row per pose in input order; the rows of a random sample are the single poses'.
    const fs::path poses = temp_dir() / "many-poses.csv";
    std::vector<std::string> rows;
    {
        std::mt19937_64 rng(15);
        std::uniform_real_distribution<double> unit(0, 1);
        std::ofstream out(poses);
        out << "lat,lon,heading\n";
        for (int k = 0; k < 13000; ++k) {
            char row[96];
            std::snprintf(row, sizeof row, "%.7f,%.7f,%.1f\n", 50.55 + 0.4 * unit(rng), -1.8 + 0.9 * unit(rng), 360 * unit(rng));
            rows.push_back(row);
            out << row;
        }
    }
    const std::string grid = (temp_dir() / "solent-many.shoalgrid").string();
    ASSERT_EQ(shoal("import " + data("coast/uk_solent_land.geojson") + " -o '" + grid + "'").status, 0);
    std::string first;
    for (const char* jobs : {"1", "2", "3"}) {
        const Outcome r = shoal("probe --coast '" + grid + "' --dims 100,20,8,8 --jobs " + std::string(jobs) + " '" + poses.string() + "'");
        ASSERT_EQ(r.status, 0) << r.err;
        ASSERT_EQ(lines_of(r.out), 13001u) << jobs << " threads";
        if (first.empty()) first = r.out;
        else ASSERT_EQ(r.out, first) << jobs << " threads: not the bytes of one thread";
    }
    const fs::path one = temp_dir() / "one-pose.csv";
    for (int k : {0, 4095, 4096, 8191, 8192, 12287, 12288, 12999}) {
        std::ofstream(one) << rows[static_cast<std::size_t>(k)];
        const Outcome r = shoal("probe --coast '" + grid + "' --dims 100,20,8,8 --jobs 1 '" + one.string() + "'");
        ASSERT_EQ(r.status, 0) << r.err;
        const std::string answer = r.out.substr(r.out.find('\n') + 1);
        std::size_t at = 0;
        for (int line = 0; line <= k; ++line) at = first.find('\n', at) + 1;
        EXPECT_EQ(first.substr(at, first.find('\n', at) + 1 - at), answer) << "pose " << k;
    }
}

/// Runs `command` (a shell command line) with stderr in `err_file`.
Outcome run_command(const std::string& command, const fs::path& err_file) {
    Outcome r;
    FILE* p = ::popen((command + " 2>'" + err_file.string() + "'").c_str(), "r");
    std::array<char, 4096> buf;
    for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) r.out.append(buf.data(), n);
    const int st = ::pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    r.err = slurp(err_file);
    return r;
}

TEST(Cli, ProbeOfAGridRunsWithoutGdalAndWritesWhatTheFullFrontEndWrites) {
    // The `shoal` executable probes a .shoalgrid itself, with no GDAL (docs/performance.md,
    // "Start-up"); the same poses gzipped are read through GDAL by the full front end (the module
    // it loads): the same rows, the same bad-row warning, the same exit status.
    const std::string grid = (temp_dir() / "solent-alone.shoalgrid").string();
    ASSERT_EQ(shoal("import " + data("coast/uk_solent_land.geojson") + " -o '" + grid + "'").status, 0);
    const fs::path poses = temp_dir() / "alone-poses.csv";
    std::ofstream(poses) << "lat,lon,heading\n50.70,-1.20,90\n50.76,-1.30,45\nnot,a,pose\n50.60,-1.29,200\n10,10,0\n";
    const Outcome plain = shoal("probe --coast '" + grid + "' --dims 100,20,8,8 '" + poses.string() + "'");
    ASSERT_EQ(plain.status, 0) << plain.err;
    EXPECT_EQ(lines_of(plain.out), 5u) << plain.out;
    ASSERT_EQ(std::system(("gzip -c '" + poses.string() + "' > '" + poses.string() + ".gz'").c_str()), 0);
    const Outcome gzipped = shoal("probe --coast '" + grid + "' --dims 100,20,8,8 '" + poses.string() + ".gz'");
    ASSERT_EQ(gzipped.status, 0) << gzipped.err;
    EXPECT_EQ(gzipped.out, plain.out);
    EXPECT_NE(plain.err.find("line 4: latitude 'not'"), std::string::npos) << plain.err;
    EXPECT_NE(gzipped.err.find("line 4: latitude 'not'"), std::string::npos) << gzipped.err;
    // Standard input, plain and gzipped (read by the module, as a track file would be).
    for (const std::string& in : {poses.string(), poses.string() + ".gz"}) {
        const Outcome piped = shoal("probe --coast '" + grid + "' --dims 100,20,8,8 - < '" + in + "'");
        ASSERT_EQ(piped.status, 0) << piped.err;
        EXPECT_EQ(piped.out, plain.out) << in;
        EXPECT_NE(piped.err.find("line 4: latitude 'not'"), std::string::npos) << piped.err;
    }
    // The ship and the poses both from standard input: refused before either is read (the ship
    // read first would leave the poses an empty stream, and the probe an empty answer).
    const Outcome twice = shoal("probe --coast '" + grid + "' --ship - - < '" + poses.string() + "'");
    EXPECT_EQ(twice.status, 2);
    EXPECT_TRUE(twice.out.empty()) << twice.out;
    EXPECT_NE(twice.err.find("standard input can be read once, and both the poses ('-') and --ship ('-') name it"), std::string::npos) << twice.err;

    // The dynamic loader's own account: no GDAL for the grid's probe; GDAL for a coastline's
    // (read by the module), so the check can fail.
    const std::string env = "SHOAL_CACHE_DIR='" + (temp_dir() / "cache").string() + "' LD_DEBUG=libs '" + SHOAL_BINARY + "' ";
    const fs::path err = temp_dir() / "ld-debug.txt";
    const Outcome grid_run = run_command(env + "probe --coast '" + grid + "' --dims 100,20,8,8 '" + poses.string() + "'", err);
    ASSERT_EQ(grid_run.status, 0) << grid_run.err;
    EXPECT_EQ(grid_run.out, plain.out);
    EXPECT_EQ(grid_run.err.find("libgdal"), std::string::npos) << "a probe of a grid loaded GDAL";
    EXPECT_EQ(grid_run.err.find("libshoal_cli_full"), std::string::npos) << "a probe of a grid loaded the full module";
    EXPECT_EQ(grid_run.err.find("libproj"), std::string::npos) << "a probe of a grid in shoal's own frame loaded PROJ";
    // A grid in a user's CRS needs PROJ: the module probes it (the executable has no PROJ).
    const std::string utm_grid = (temp_dir() / "solent-utm.shoalgrid").string();
    ASSERT_EQ(shoal("import " + data("coast/uk_solent_land.geojson") + " --crs EPSG:32630 -o '" + utm_grid + "'").status, 0);
    const Outcome utm_run = run_command(env + "probe --coast '" + utm_grid + "' --dims 100,20,8,8 '" + poses.string() + "'", err);
    ASSERT_EQ(utm_run.status, 0) << utm_run.err;
    EXPECT_NE(utm_run.err.find("libshoal_cli_full"), std::string::npos) << "the executable probed a grid in a user's CRS";
    const Outcome utm_gzipped = shoal("probe --coast '" + utm_grid + "' --dims 100,20,8,8 '" + poses.string() + ".gz'");
    ASSERT_EQ(utm_gzipped.status, 0) << utm_gzipped.err;
    EXPECT_EQ(utm_run.out, utm_gzipped.out);
    EXPECT_EQ(lines_of(utm_run.out), 5u) << utm_run.out;
    // (A cache of its own, empty: a grid cached by an earlier test of this process would need no
    // GDAL at all, the module loading it only to read a source: src/util/lazy_libraries.hpp.)
    const fs::path fresh_cache = temp_dir() / "cache-probe-coast";
    fs::remove_all(fresh_cache);
    const std::string fresh_env = "SHOAL_CACHE_DIR='" + fresh_cache.string() + "' LD_DEBUG=libs '" + SHOAL_BINARY + "' ";
    const Outcome coast_run = run_command(fresh_env + "probe --coast " + data("coast/uk_solent_land.geojson") + " --dims 100,20,8,8 '" + poses.string() + "'", err);
    ASSERT_EQ(coast_run.status, 0) << coast_run.err;
    EXPECT_EQ(coast_run.out, plain.out);
    EXPECT_NE(coast_run.err.find("libgdal"), std::string::npos);

    // The executable copied alone: it still probes the grid; every other command says which
    // module it could not load, as an internal error (exit status 3).
    const fs::path alone = temp_dir() / "alone" / "bin";
    fs::create_directories(alone);
    fs::copy_file(SHOAL_BINARY, alone / "shoal", fs::copy_options::overwrite_existing);
    const Outcome copy = run_command("'" + (alone / "shoal").string() + "' probe --coast '" + grid + "' --dims 100,20,8,8 '" + poses.string() + "'", err);
    ASSERT_EQ(copy.status, 0) << copy.err;
    EXPECT_EQ(copy.out, plain.out);
    const Outcome info = run_command("'" + (alone / "shoal").string() + "' info '" + grid + "'", err);
    EXPECT_EQ(info.status, 3);
    EXPECT_TRUE(info.out.empty());
    EXPECT_EQ(info.err.rfind("shoal: internal error: cannot load shoal's command module '" + alone.string() + "/", 0), 0u) << info.err;
    EXPECT_NE(info.err.find("/libshoal_cli_full.so' ("), std::string::npos) << info.err;
    EXPECT_EQ(lines_of(info.err), 1u) << info.err;
}

}  // namespace

namespace {

/// Two vessels in the Solent: A sails from the Solent south across the Isle of Wight (it must
/// ground), B stays in open water east of the island; one bad row in between.
fs::path solent_tracks() {
    const fs::path p = temp_dir() / "solent-tracks.csv";
    std::ofstream out(p);
    out << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
    for (int i = 0; i <= 20; ++i) {  // A: 50.78N -> 50.58N along 1.30W, 1 min apart (~11.9 kn)
        char row[160];
        std::snprintf(row, sizeof row, "111111111,2024-05-01T10:%02d:00Z,%.4f,-1.3000,11.9,180,511\n", i, 50.78 - 0.01 * i);
        out << row;
        if (i == 5) out << "111111111,2024-05-01T10:05:30Z,95.0,-1.3000,11.9,180,511\n";  // latitude 95: skipped
    }
    for (int i = 0; i <= 10; ++i) {  // B: east of the island, far from land
        char row[160];
        std::snprintf(row, sizeof row, "222222222,2024-05-01T10:%02d:00Z,50.7400,%.4f,8,90,90\n", i, -1.05 + 0.002 * i);
        out << row;
    }
    return p;
}

bool validates_against_schema(const fs::path& report) {
    const std::string schema = source_root() + "/schemas/report.schema.json";
    const std::string cmd = "/usr/bin/python3 -c \"import json,sys,jsonschema; "
                            "jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))\" '" +
                            report.string() + "' '" + schema + "' 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    std::string out;
    for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) out.append(buf.data(), n);
    const int st = ::pclose(p);
    if (st != 0) ADD_FAILURE() << "schema validation failed:\n" << out;
    return st == 0;
}

TEST(CliCheck, GroundingGivesExitOneAndAReportThatValidatesAndReadsBack) {
    const fs::path tracks = solent_tracks();
    const fs::path report = temp_dir() / "solent.geojson";
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + tracks.string() +
                            "' -o '" + report.string() + "' --jobs 2");
    EXPECT_EQ(r.status, 1) << r.err << r.out;
    EXPECT_NE(r.err.find("line 8"), std::string::npos) << "the bad row is reported with its line: " << r.err;
    EXPECT_TRUE(fs::exists(temp_dir() / "solent.qml")) << "QGIS style beside the GeoJSON";
    EXPECT_TRUE(validates_against_schema(report));

    // Read back through OGR, independently of our writer.
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(report.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    OGRLayer* layer = ds->GetLayer(0);
    int groundings_a = 0, events_b = 0;
    for (auto& f : *layer) {
        const std::string track = f->GetFieldAsString("track");
        if (track == "111111111" && std::string(f->GetFieldAsString("kind")) == "grounding") {
            ++groundings_a;
            const OGRPoint* pt = f->GetGeometryRef()->toPoint();
            EXPECT_NEAR(pt->getX(), -1.30, 0.01);  // on the track's meridian, within the hull's beam
            EXPECT_GT(pt->getY(), 50.58);
            EXPECT_LT(pt->getY(), 50.78);
            EXPECT_EQ(f->GetFieldAsDouble("min_clearance_m"), 0.0);
        }
        if (track == "222222222") ++events_b;
    }
    EXPECT_GE(groundings_a, 1);
    EXPECT_EQ(events_b, 0);
    const auto doc = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(doc["shoal"]["summary"]["tracks"], 2);
    EXPECT_EQ(doc["shoal"]["summary"]["skipped_rows"], 1);
    EXPECT_EQ(doc["shoal"]["summary"]["fixes"], 32);
}

// Issue 39: on a day of AIS the table listed every track (1,261 lines for a 30 s stream). The
// counts of each kind of event come first, then only the tracks with events; --verbose lists
// every track; --quiet prints nothing but errors. Three ships: A runs aground on the Isle of
// Wight, B passes clear, C lies off Copenhagen, outside the chart (uncovered, no event).
TEST(CliCheck, TheSummaryCountsKindsFirstAndListsTracksWithEventsUnlessVerboseOrQuiet) {
    const fs::path tracks = temp_dir() / "three.csv";
    {
        std::ofstream f(tracks);
        f << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
        for (int i = 0; i <= 20; ++i) f << "111111111,2024-05-01T10:" << (i < 10 ? "0" : "") << i << ":00Z," << 50.78 - 0.01 * i << ",-1.3,11.9,180,180\n";
        for (int i = 0; i <= 10; ++i) f << "222222222,2024-05-01T10:" << (i < 10 ? "0" : "") << i << ":00Z,50.74," << -1.05 + 0.002 * i << ",8,90,90\n";
        for (int i = 0; i <= 10; ++i) f << "333333333,2024-05-01T10:" << (i < 10 ? "0" : "") << i << ":00Z,55.7," << 12.7 + 0.002 * i << ",8,90,90\n";
    }
    const std::string args = "check --world simulated --coast " + data("coast/uk_solent_land.geojson") + " --dims 50,10,5,5 '" + tracks.string() + "' -o '" +
                             (temp_dir() / "three.gpkg").string() + "' --no-project";
    const auto rows_of = [](const std::string& out) {  // the ids at the start of the table's rows
        std::vector<std::string> ids;
        std::istringstream in(out);
        for (std::string l; std::getline(in, l);)
            if (l.size() > 9 && std::all_of(l.begin(), l.begin() + 9, ::isdigit)) ids.push_back(l.substr(0, 9));
        return ids;
    };
    const Outcome normal = shoal(args);
    ASSERT_EQ(normal.status, 1) << normal.err;
    // Line 2 (after the world): the counts of each kind; the table only A; B and C counted below it.
    std::istringstream in(normal.out);
    std::string world, kinds;
    std::getline(in, world);
    std::getline(in, kinds);
    EXPECT_EQ(world.rfind("world: simulated", 0), 0u) << normal.out;
    EXPECT_EQ(kinds.rfind("events: 1 grounding, 0 alongside, 0 in_contact_at_start, 0 expected_contact, 0 chart_disagrees, ", 0), 0u) << normal.out;
    EXPECT_EQ(rows_of(normal.out), std::vector<std::string>{"111111111"}) << normal.out;
    EXPECT_NE(normal.out.find("(2 more tracks without events, 1 of them with fixes outside the chart, 0 with wild fixes: --verbose lists every track)"),
              std::string::npos)
        << normal.out;
    const Outcome verbose = shoal(args + " --verbose");
    EXPECT_EQ(verbose.status, 1);
    EXPECT_EQ(rows_of(verbose.out), (std::vector<std::string>{"111111111", "222222222", "333333333"})) << verbose.out;
    EXPECT_EQ(verbose.out.find("more track"), std::string::npos) << verbose.out;
    const Outcome quiet = shoal(args + " --quiet");
    EXPECT_EQ(quiet.status, 1) << "the exit status still says there was a grounding";
    EXPECT_EQ(quiet.out, "");
    EXPECT_EQ(quiet.err, "");
    EXPECT_TRUE(fs::exists(temp_dir() / "three.gpkg"));
    // Errors are still said with --quiet (a track file that is no track file); -q with -v is a usage error.
    const Outcome bad = shoal("check --quiet --coast " + data("coast/uk_solent_land.geojson") + " --dims 50,10,5,5 " + data("coast/not_a_dataset.txt") +
                              " -o '" + (temp_dir() / "bad.gpkg").string() + "'");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("shoal: error: "), std::string::npos) << bad.err;
    EXPECT_EQ(bad.out, "");
    EXPECT_EQ(shoal(args + " -q -v").status, 2);
}

TEST(CliCheck, PlotIsAnSvgWithTheEvents) {
    const fs::path svg = temp_dir() / "run.svg";
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" +
                            solent_tracks().string() + "' -o '" + (temp_dir() / "plot.geojson").string() + "' --plot '" + svg.string() + "'");
    ASSERT_EQ(r.status, 1) << r.err;
    const std::string text = slurp(svg);
    EXPECT_NE(text.find("<svg"), std::string::npos);
    EXPECT_NE(text.find("http://www.w3.org/2000/svg"), std::string::npos);
    EXPECT_NE(text.find("event grounding"), std::string::npos);
    EXPECT_NE(text.find("grade 4"), std::string::npos) << "each contact's grade (the simulated world: 4) in its panel and tooltip";
}

TEST(CliCheck, EncountersFindTwoShipsCrossingAtTheSameSpot) {
    // East of the Isle of Wight, far from land: C sails east along 50.74N, D north along
    // 1.04W; both reach (50.74N, 1.04W) at 10:05.
    const fs::path tracks = temp_dir() / "exercise.csv";
    {
        std::ofstream out(tracks);
        out << "mmsi,timestamp,lat,lon,heading\n";
        for (int i = 0; i <= 10; ++i) {
            char row[160];
            std::snprintf(row, sizeof row, "333333333,2024-05-01T10:%02d:00Z,50.7400,%.5f,90\n", i, -1.05 + 0.002 * i);
            out << row;
            std::snprintf(row, sizeof row, "444444444,2024-05-01T10:%02d:00Z,%.5f,-1.0400,0\n", i, 50.7335 + 0.0013 * i);
            out << row;
        }
    }
    const fs::path report = temp_dir() / "exercise.geojson";
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + tracks.string() +
                            "' -o '" + report.string() + "' --encounters");
    EXPECT_EQ(r.status, 1) << "a collision counts like a grounding: " << r.err << r.out;
    EXPECT_TRUE(validates_against_schema(report));
    const auto doc = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(doc["shoal"]["summary"]["groundings"], 0);
    EXPECT_EQ(doc["shoal"]["summary"]["collisions"], 1);
    bool found = false;
    for (const auto& f : doc["features"])
        if (f["properties"]["kind"] == "collision") {
            found = true;
            EXPECT_EQ(f["properties"]["track"], "333333333");
            EXPECT_EQ(f["properties"]["other_track"], "444444444");
            EXPECT_NEAR(f["geometry"]["coordinates"][0].get<double>(), -1.04, 0.002);
            EXPECT_NEAR(f["geometry"]["coordinates"][1].get<double>(), 50.74, 0.002);
        }
    EXPECT_TRUE(found);
    EXPECT_EQ(doc["shoal"]["closest_approaches"].size(), 1u);
}

TEST(CliCheck, ExercisesByFolderAreAuditedApartWithRolesAndSituations) {
    // Two exercises, one folder each, sailed at the same time on the same water: in each, C
    // sails east along 50.74N and D north along 1.04W, both reaching the crossing at 10:05.
    const fs::path root = temp_dir() / "morning";
    std::string ids[2][2] = {{"333333333", "444444444"}, {"555555555", "666666666"}};
    for (int x = 0; x < 2; ++x) {
        fs::create_directories(root / ("ex" + std::to_string(x + 1)));
        std::ofstream out(root / ("ex" + std::to_string(x + 1)) / "bridges.csv");
        out << "mmsi,timestamp,lat,lon,heading\n";
        for (int i = 0; i <= 10; ++i) {
            char row[160];
            std::snprintf(row, sizeof row, "%s,2024-05-01T10:%02d:00Z,50.7400,%.5f,90\n", ids[x][0].c_str(), i, -1.05 + 0.002 * i);
            out << row;
            std::snprintf(row, sizeof row, "%s,2024-05-01T10:%02d:00Z,%.5f,-1.0400,0\n", ids[x][1].c_str(), i, 50.7335 + 0.0013 * i);
            out << row;
        }
    }
    const fs::path roles = temp_dir() / "roles.json";
    {
        std::ofstream out(roles);
        out << R"({"default_role": "target", "tracks": [{"track": "333333333", "role": "trainee"}, {"track": "555555555", "role": "own ship"}]})";
    }
    const fs::path report = temp_dir() / "morning.geojson";
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + (root / "ex1").string() + "' '" +
                            (root / "ex2").string() + "' -o '" + report.string() + "' --exercise-by folder --roles '" + roles.string() + "'");
    EXPECT_EQ(r.status, 1) << r.err << r.out;  // a collision in each exercise
    EXPECT_TRUE(validates_against_schema(report));
    EXPECT_NE(r.out.find("situations: 2 pairs came within the encounter range"), std::string::npos) << r.out;
    const auto doc = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(doc["shoal"]["exercise_by"], "folder");
    EXPECT_EQ(doc["shoal"]["summary"]["exercises"], 2);
    EXPECT_EQ(doc["shoal"]["summary"]["collisions"], 2);  // never C of ex1 against C of ex2
    for (const auto& t : doc["shoal"]["tracks"]) {
        const std::string id = t["track"];
        EXPECT_EQ(t["role"], id == "333333333" || id == "555555555" ? "trainee" : "target") << id;
        EXPECT_EQ(t["exercise"], (root / (id == "333333333" || id == "444444444" ? "ex1" : "ex2")).string()) << id;
    }
    ASSERT_EQ(doc["shoal"]["closest_approaches"].size(), 2u);
    for (const auto& a : doc["shoal"]["closest_approaches"]) {
        // D comes from C's starboard side: C gives way (rule 15).
        EXPECT_EQ(a["situation"], "crossing");
        EXPECT_EQ(a["give_way"], a["track"]);
        EXPECT_EQ(a["stand_on"], a["other_track"]);
        EXPECT_EQ(a["clearance_m"], 0.0);
    }
    for (const auto& f : doc["features"])
        if (f["properties"]["kind"] == "collision") {
            EXPECT_EQ(f["properties"]["situation"], "crossing");
            EXPECT_EQ(f["properties"]["give_way"], f["properties"]["track"]);
        }

    // A bad exercise file: exit 2, the file and the entry named.
    std::ofstream(temp_dir() / "bad_roles.json") << R"({"tracks": [{"track": "333333333", "role": "pilot"}]})";
    const Outcome bad = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + (root / "ex1").string() +
                              "' -o '" + (temp_dir() / "bad.geojson").string() + "' --roles '" + (temp_dir() / "bad_roles.json").string() + "'");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.err.find("bad_roles.json"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("tracks[0] (track '333333333')"), std::string::npos) << bad.err;
}

TEST(CliCheck, ExercisesByAColumnOfOneFileAreAuditedApartWithRolesFromAColumn) {
    // One file, two exercises (column "Exercise"), roles in column "role". Vessel 333333333 is
    // the trainee of both: in exercise 1 it sails east along 50.74N and reaches 1.04W at 10:05;
    // in exercise 2 along 50.75N. 555555555, exercise 2's target, sails north along 1.04W and
    // is at 50.74N at 10:05: it would hit exercise 1's trainee, were they one exercise.
    // 444444444, exercise 1's target, crosses 1.03W well after 333333333 has passed.
    const fs::path tracks = temp_dir() / "column_exercises.csv";
    {
        std::ofstream out(tracks);
        out << "mmsi,Exercise,role,timestamp,lat,lon,heading\n";
        out << "333333333,,trainee,2024-05-01T09:59:00Z,50.7400,-1.0520,90\n";  // line 2: no exercise
        for (int i = 0; i <= 10; ++i) {
            char row[200];
            std::snprintf(row, sizeof row, "333333333,1,own ship,2024-05-01T10:%02d:00Z,50.7400,%.5f,90\n", i, -1.05 + 0.002 * i);
            out << row;
            std::snprintf(row, sizeof row, "444444444,1,target,2024-05-01T10:%02d:00Z,%.5f,-1.0300,0\n", i, 50.7200 + 0.0013 * i);
            out << row;
            std::snprintf(row, sizeof row, "333333333,2,trainee,2024-05-01T10:%02d:00Z,50.7500,%.5f,90\n", i, -1.05 + 0.002 * i);
            out << row;
            std::snprintf(row, sizeof row, "555555555,2,Target,2024-05-01T10:%02d:00Z,%.5f,-1.0400,0\n", i, 50.7335 + 0.0013 * i);
            out << row;
        }
    }
    const fs::path report = temp_dir() / "column_exercises.geojson";
    const std::string check = "check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + tracks.string() + "' -o '" +
                              report.string() + "' --exercise-by column:exercise --role-column ROLE";
    const Outcome r = shoal(check);
    EXPECT_EQ(r.status, 0) << "no collision within an exercise: " << r.err << r.out;
    EXPECT_TRUE(validates_against_schema(report));
    EXPECT_NE(r.err.find("column_exercises.csv line 2: no exercise (column 'exercise' is empty); row skipped"), std::string::npos) << r.err;
    const auto doc = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(doc["shoal"]["exercise_by"], "column:exercise");
    EXPECT_EQ(doc["shoal"]["role_column"], "ROLE");
    EXPECT_EQ(doc["shoal"]["summary"]["exercises"], 2);
    EXPECT_EQ(doc["shoal"]["summary"]["collisions"], 0);
    std::vector<std::string> seen;
    for (const auto& t : doc["shoal"]["tracks"])
        seen.push_back(t["exercise"].get<std::string>() + "/" + t["track"].get<std::string>() + "/" + t["role"].get<std::string>());
    EXPECT_EQ(seen, (std::vector<std::string>{"1/333333333/trainee", "1/444444444/target", "2/333333333/trainee", "2/555555555/target"}));
    ASSERT_EQ(doc["shoal"]["closest_approaches"].size(), 2u) << "one situation in each exercise";
    for (const auto& a : doc["shoal"]["closest_approaches"]) {
        const std::string pair = a["exercise"].get<std::string>() + ":" + a["track"].get<std::string>() + "-" + a["other_track"].get<std::string>();
        EXPECT_TRUE(pair == "1:333333333-444444444" || pair == "2:333333333-555555555") << pair;
    }
    // Each vessel's exercise in the events too.
    for (const auto& f : doc["features"]) {
        if (f["properties"].contains("exercise")) {
            EXPECT_TRUE(f["properties"]["exercise"] == "1" || f["properties"]["exercise"] == "2");
        }
    }

    // A file without the column: exit 2, the file and the column named.
    const Outcome missing = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + tracks.string() + "' -o '" +
                                  (temp_dir() / "missing.geojson").string() + "' --exercise-by column:drill");
    EXPECT_EQ(missing.status, 2) << missing.err;
    EXPECT_NE(missing.err.find("column_exercises.csv: the header has no column 'drill', the exercise column (--exercise-by column:NAME)"),
              std::string::npos)
        << missing.err;
    const Outcome nameless = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + tracks.string() + "' -o '" +
                                   (temp_dir() / "nameless.geojson").string() + "' --exercise-by column:");
    EXPECT_EQ(nameless.status, 2);
    EXPECT_NE(nameless.err.find("--exercise-by 'column:' names no column"), std::string::npos) << nameless.err;

    // An exercise file beside the column: its entry for exercise 2's target makes it a trainee.
    std::ofstream(temp_dir() / "column_roles.json") << R"({"tracks": [{"track": "555555555", "exercise": "2", "role": "trainee"}]})";
    const Outcome both = shoal(check + " --roles '" + (temp_dir() / "column_roles.json").string() + "'");
    EXPECT_EQ(both.status, 0) << both.err;
    const auto doc2 = nlohmann::json::parse(slurp(report));
    ASSERT_EQ(doc2["shoal"]["tracks"].size(), 4u);
    EXPECT_EQ(doc2["shoal"]["tracks"][3]["role"], "trainee");
    EXPECT_EQ(doc2["shoal"]["tracks"][1]["role"], "target");
}

TEST(CliCheck, ReportIsTheSameWhateverTheNumberOfJobs) {
    const fs::path tracks = solent_tracks();
    std::string reports[2];
    for (int jobs : {1, 2}) {
        const fs::path report = temp_dir() / ("jobs" + std::to_string(jobs) + ".geojson");
        shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + tracks.string() + "' '" +
              tracks.string() + "' -o '" + report.string() + "' --jobs " + std::to_string(jobs));
        reports[jobs - 1] = slurp(report);
    }
    EXPECT_FALSE(reports[0].empty());
    EXPECT_EQ(reports[0], reports[1]);
}

/// A day of 60 vessels past the island on two threads: the report and every file beside it
/// (the chart's tiles are cut on the run's threads) are those of --jobs 1; and when the
/// chart's files have gone, both say so the same way and write the same report without it.
/// (Reading the chart on a thread of its own while the audit ran was tried: 0.2 s of 7.9 s on
/// a 10 M-row day, but 59 MB more at the peak: GDAL's parse of the chart beside the rows read.)
TEST(CliCheck, TheReportAndItsChartAreTheSameOnAnyNumberOfThreads) {
    const fs::path dir = temp_dir() / "chart-on-threads";
    fs::create_directories(dir);
    const fs::path coast = dir / "solent.geojson";
    fs::copy_file(std::string(SHOAL_TEST_DATA) + "coast/uk_solent_land.geojson", coast, fs::copy_options::overwrite_existing);
    const fs::path grid = dir / "solent.shoalgrid";
    ASSERT_EQ(shoal("import '" + coast.string() + "' -o '" + grid.string() + "'").status, 0);
    const fs::path tracks = dir / "day.csv";
    {
        std::ofstream out(tracks);
        out << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
        for (int v = 0; v < 60; ++v)  // 60 vessels past the island's shores, a fix every 10 s
            for (int i = 0; i < 400; ++i) {
                char row[160];
                std::snprintf(row, sizeof row, "%d,2024-05-01T%02d:%02d:%02dZ,%.5f,%.5f,9.5,90,90\n", 300000000 + v, 10 + i / 360, i / 6 % 60, i % 6 * 10,
                              50.60 + 0.004 * v, -1.60 + 0.0009 * i);
                out << row;
            }
    }
    ASSERT_GT(fs::file_size(tracks), std::uintmax_t{1} << 20);
    // Each run writes r.geojson and the files beside it (which name it), then they are moved to a folder of the run's.
    const char* beside[] = {".geojson", ".coast.geojson", ".poses.geojson", ".tracks.geojson", ".qgz"};
    auto run = [&](int jobs, const std::string& name) {
        const Outcome o = shoal("check --coast '" + grid.string() + "' --dims 50,10,5,5 '" + tracks.string() + "' -o '" + (dir / "r.geojson").string() +
                                "' --jobs " + std::to_string(jobs));
        EXPECT_NE(o.status, 2) << o.err;
        fs::create_directories(dir / name);
        for (const char* ext : beside)
            if (fs::exists(dir / (std::string("r") + ext))) fs::rename(dir / (std::string("r") + ext), dir / name / (std::string("r") + ext));
        return o;
    };
    auto file = [&](const std::string& run_name, const char* ext) { return slurp(dir / run_name / (std::string("r") + ext)); };
    const Outcome one = run(1, "one"), two = run(2, "two");
    for (const char* ext : beside) {
        EXPECT_FALSE(file("one", ext).empty()) << ext;
        EXPECT_TRUE(file("one", ext) == file("two", ext)) << "r" << ext << " differs";
    }
    EXPECT_GT(file("two", ".coast.geojson").size(), 10000u) << "the coast layer holds the chart near the tracks";
    EXPECT_EQ(one.err, two.err);
    fs::remove(coast);
    const Outcome gone1 = run(1, "gone1"), gone2 = run(2, "gone2");
    EXPECT_NE(gone2.err.find("the report has no coast layer: the coast files the grid"), std::string::npos) << gone2.err;
    EXPECT_EQ(gone1.err, gone2.err);
    for (const char* ext : {".geojson", ".poses.geojson", ".tracks.geojson", ".qgz"}) EXPECT_TRUE(file("gone1", ext) == file("gone2", ext)) << ext;
    for (const char* name : {"gone1", "gone2"})
        EXPECT_FALSE(fs::exists(dir / "r.coast.geojson") || fs::exists(dir / name / "r.coast.geojson"))
            << name << ": no coast layer without its chart";
}

TEST(CliCheck, GeoPackageHasStyledLayersInWgs84) {
    const fs::path report = temp_dir() / "solent.gpkg";
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" +
                            solent_tracks().string() + "' -o '" + report.string() + "'");
    ASSERT_EQ(r.status, 1) << r.err;
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(report.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    struct Expect {
        const char* name;
        OGRwkbGeometryType type;
        std::vector<const char*> fields;
    } layers[] = {
        {"events", wkbPoint, {"track", "kind", "start", "end", "duration_s", "min_clearance_m", "penetration_m", "ship_lat", "ship_lon", "heading", "fix_index", "label"}},
        {"tracks", wkbMultiLineString, {"track", "fixes", "skipped_rows", "uncovered_fixes", "groundings", "close_passes", "min_clearance_m"}},
        {"hulls", wkbPolygon, {"track", "kind", "start"}},
    };
    for (const auto& e : layers) {
        OGRLayer* l = ds->GetLayerByName(e.name);
        ASSERT_TRUE(l) << e.name;
        EXPECT_EQ(wkbFlatten(l->GetGeomType()), e.type) << e.name;
        ASSERT_TRUE(l->GetSpatialRef()) << e.name;
        EXPECT_STREQ(l->GetSpatialRef()->GetAuthorityCode(nullptr), "4326") << e.name;
        for (const char* f : e.fields) EXPECT_GE(l->GetLayerDefn()->GetFieldIndex(f), 0) << e.name << "." << f;
        EXPECT_GT(l->GetFeatureCount(), 0) << e.name;
    }
    OGRLayer* styles = ds->ExecuteSQL("SELECT f_table_name, f_table_schema, f_geometry_column, useAsDefault, styleQML FROM layer_styles", nullptr, nullptr);
    ASSERT_TRUE(styles);
    std::set<std::string> styled;
    for (auto& f : *styles) {
        styled.insert(f->GetFieldAsString(0));
        EXPECT_STREQ(f->GetFieldAsString(1), "");
        EXPECT_STREQ(f->GetFieldAsString(2), ds->GetLayerByName(f->GetFieldAsString(0))->GetGeometryColumn());
        EXPECT_EQ(f->GetFieldAsInteger(3), 1);
        EXPECT_NE(std::string(f->GetFieldAsString(4)).find("<renderer-v2"), std::string::npos);
    }
    ds->ReleaseResultSet(styles);
    EXPECT_EQ(styled, (std::set<std::string>{"events", "tracks", "hulls", "poses", "coast"}));
}

TEST(CliCheck, UnreadableTrackFileIsReportedAndTheBatchGoesOn) {
    const fs::path bad = temp_dir() / "garbage.csv";
    std::ofstream(bad) << "this,is,not\na,track,file\n";
    const fs::path report = temp_dir() / "batch.geojson";
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" + bad.string() + "' '" +
                            solent_tracks().string() + "' -o '" + report.string() + "'");
    EXPECT_EQ(r.status, 1) << r.err;  // the good file still grounds
    EXPECT_NE(r.err.find("garbage.csv"), std::string::npos) << r.err;
    const auto doc = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(doc["shoal"]["summary"]["tracks"], 2);
}

TEST(CliCheck, MissingReportFolderIsAClearErrorBeforeAnyWork) {
    const Outcome r = shoal("check --coast " + data("coast/uk_solent_land.geojson") + " --world simulated --dims 50,10,5,5 '" +
                            solent_tracks().string() + "' -o /nonexistent/dir/r.geojson");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
}


// ---------------------------------------------------------------- what kind of contact
// Hand-made AIS tracks in the MarineCadastre layout with GPS jitter, against the real Helsinki
// coast (tests/data/tracks/ais_cases, made by make_cases.py there, which derives the first
// contact time independently with OGR). The expectations are read from its expected.json.

struct CaseRun {
    Outcome outcome;
    nlohmann::json report;
    nlohmann::json expect;
    std::vector<nlohmann::json> of_kind(const std::string& kind) const {
        std::vector<nlohmann::json> v;
        for (const auto& f : report["features"])
            if (f["properties"]["kind"] == kind) v.push_back(f["properties"]);
        return v;
    }
};

CaseRun run_case(const std::string& file) {
    static const nlohmann::json expected =
        nlohmann::json::parse(slurp(std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/expected.json"));
    CaseRun c;
    c.expect = expected["cases"][file]["expect"];
    const fs::path out = temp_dir() / (file + ".geojson");
    c.outcome = shoal("check --coast '" + source_root() + "/examples/data/gof_helsinki_land.geojson' --dims 100,20,8,8 " +
                      data("tracks/ais_cases/" + file) + " -o '" + out.string() + "' --no-progress");
    c.report = nlohmann::json::parse(slurp(out));
    return c;
}

double epoch_of(const std::string& iso) {
    std::tm tm{};
    int y = 0, mo = 0, d = 0, h = 0, mi = 0;
    double sec = 0;
    EXPECT_EQ(std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%lf", &y, &mo, &d, &h, &mi, &sec), 6) << iso;
    tm.tm_year = y - 1900, tm.tm_mon = mo - 1, tm.tm_mday = d, tm.tm_hour = h, tm.tm_min = mi;
    return static_cast<double>(::timegm(&tm)) + sec;
}

TEST(CliContactKinds, ShipThatRunsAgroundAtSpeedAndLiesThereIsOneGrounding) {
    for (const char* file : {"aground_at_speed.csv", "aground_at_speed_no_sog.csv"}) {
        const CaseRun c = run_case(file);
        EXPECT_EQ(c.outcome.status, 1) << file << c.outcome.err;
        const auto g = c.of_kind("grounding");
        ASSERT_EQ(g.size(), 1u) << file << "\n" << c.outcome.out;
        EXPECT_EQ(c.report["features"].size(), 1u) << "lying aground for 30 min is the same event";
        const double want = epoch_of(c.expect["grounding_start"].get<std::string>());
        EXPECT_NEAR(epoch_of(g[0]["start"].get<std::string>()), want, c.expect["start_tolerance_s"].get<double>()) << file;
        EXPECT_GE(g[0]["speed_kn"].get<double>(), c.expect["speed_kn"][0].get<double>()) << file;
        EXPECT_LE(g[0]["speed_kn"].get<double>(), c.expect["speed_kn"][1].get<double>()) << file;
        if (c.expect.contains("speed_source")) EXPECT_EQ(g[0]["speed_source"], c.expect["speed_source"]) << file;
        else EXPECT_EQ(g[0]["speed_source"], "sog");
        // It stopped dead at the first fix in contact, within 10 s of the first contact.
        ASSERT_TRUE(g[0]["stopped_after_s"].is_number()) << file;
        EXPECT_LT(g[0]["stopped_after_s"].get<double>(), 10.0) << file;
        EXPECT_EQ(g[0]["stopped_before"], false);
        EXPECT_NE(c.outcome.out.find("grounding 2024-05-0"), std::string::npos) << c.outcome.out;
    }
    EXPECT_EQ(run_case("aground_at_speed.csv").of_kind("grounding")[0]["reported_aground"], true) << "AIS status 6 after a few minutes";
}

TEST(CliContactKinds, MooredAlongsideThenLeavingIsNoGrounding) {
    const CaseRun c = run_case("moored_then_leaves.csv");
    EXPECT_EQ(c.outcome.status, 0) << c.outcome.out << c.outcome.err;
    EXPECT_TRUE(c.of_kind("grounding").empty());
    const auto along = c.of_kind("alongside");
    ASSERT_FALSE(along.empty()) << "the jitter makes the hull touch and clear the shore: each touch is alongside";
    for (const auto& e : along) {
        EXPECT_LT(e["speed_kn"].get<double>(), 1.0);
        EXPECT_EQ(e["nav_status"], 5);
        EXPECT_EQ(e["nav_status_text"], "moored");
    }
}

TEST(CliContactKinds, BerthingSidewaysAtAFewTenthsOfAKnotIsAlongside) {
    const CaseRun c = run_case("berthing_sideways.csv");
    EXPECT_EQ(c.outcome.status, 0) << c.outcome.out;
    EXPECT_TRUE(c.of_kind("grounding").empty());
    const auto along = c.of_kind("alongside");
    ASSERT_FALSE(along.empty());
    EXPECT_NEAR(along[0]["speed_kn"].get<double>(), 0.3, 0.05);
}

TEST(CliContactKinds, JumpOntoLandAndAFixAtZeroZeroAreDroppedAndListed) {
    const CaseRun c = run_case("jump_and_null_island.csv");
    EXPECT_EQ(c.outcome.status, 0) << c.outcome.out << c.outcome.err;
    EXPECT_TRUE(c.report["features"].empty()) << c.report["features"].dump();
    EXPECT_EQ(c.report["shoal"]["summary"]["wild_fixes"], c.expect["outliers"]["count"]);
    std::vector<std::size_t> lines;
    for (const auto& p : c.report["shoal"]["problems"])
        if (p.contains("line")) lines.push_back(p["line"].get<std::size_t>());
    EXPECT_EQ(lines, c.expect["outliers"]["lines"].get<std::vector<std::size_t>>());
    for (const auto& l : lines) EXPECT_NE(c.outcome.err.find("line " + std::to_string(l) + ": fix at"), std::string::npos) << c.outcome.err;
    EXPECT_NE(c.outcome.err.find("position 0,0"), std::string::npos) << c.outcome.err;
}

TEST(CliContactKinds, LyingStillWithNoHeadingIsNoGroundingAndSaysTheHeadingIsUnknown) {
    const CaseRun c = run_case("still_no_heading.csv");
    EXPECT_EQ(c.outcome.status, 0) << c.outcome.out;
    EXPECT_TRUE(c.of_kind("grounding").empty());
    ASSERT_FALSE(c.report["features"].empty()) << "at some headings the hull overlaps land";
    for (const auto& f : c.report["features"]) {
        EXPECT_TRUE(f["properties"]["heading"].is_null()) << f.dump();
        EXPECT_EQ(f["properties"]["heading_source"], "none");
        EXPECT_EQ(f["properties"]["orientation"], "unknown (hull circle)");
    }
    EXPECT_GT(c.report["shoal"]["summary"]["unknown_heading_fixes"].get<std::size_t>(), 0u);
}

TEST(CliContactKinds, APassClearOfLandHasNoEvent) {
    const CaseRun c = run_case("passes_clear.csv");
    EXPECT_EQ(c.outcome.status, 0);
    EXPECT_TRUE(c.report["features"].empty());
}


/// A harbour polygon (0.004 degrees square) around a point, written as GeoJSON.
fs::path harbour_around(double lat, double lon, const std::string& name) {
    const fs::path berths = temp_dir() / (name + ".geojson");
    std::ofstream f(berths);
    char ring[512];
    std::snprintf(ring, sizeof ring, "[[%.7f,%.7f],[%.7f,%.7f],[%.7f,%.7f],[%.7f,%.7f],[%.7f,%.7f]]", lon - 0.002, lat - 0.002, lon + 0.002,
                  lat - 0.002, lon + 0.002, lat + 0.002, lon - 0.002, lat + 0.002, lon - 0.002, lat - 0.002);
    f << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":")" << name << R"("},)"
      << R"("geometry":{"type":"Polygon","coordinates":[)" << ring << "]}}]}";
    return berths;
}

TEST(CliContactKinds, InsideABerthsAreaSlowContactsAreExpectedAndContactsUnderWayStayGroundings) {
    const std::string coast = "'" + source_root() + "/examples/data/gof_helsinki_land.geojson' --dims 100,20,8,8 ";
    // Moored alongside inside a harbour area: every touch is expected_contact, exit 0.
    const CaseRun moored = run_case("moored_then_leaves.csv");
    const auto along = moored.of_kind("alongside");
    ASSERT_FALSE(along.empty());
    const fs::path basin = harbour_around(along[0]["ship_lat"].get<double>(), along[0]["ship_lon"].get<double>(), "Test basin");
    const fs::path out = temp_dir() / "berthed.geojson";
    const Outcome r = shoal("check --coast " + coast + data("tracks/ais_cases/moored_then_leaves.csv") + " --berths '" + basin.string() +
                            "' -o '" + out.string() + "' --no-progress");
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    nlohmann::json rep = nlohmann::json::parse(slurp(out));
    ASSERT_EQ(rep["features"].size(), along.size());
    for (const auto& f : rep["features"]) {
        EXPECT_EQ(f["properties"]["kind"], "expected_contact");
        EXPECT_EQ(f["properties"]["area"], "area");
        EXPECT_EQ(f["properties"]["area_name"], "Test basin");
    }
    EXPECT_EQ(rep["shoal"]["berths"], basin.string());
    EXPECT_NE(r.err.find("1 expected-contact areas"), std::string::npos) << r.err;
    // Running aground at 10 kn inside such an area is still a grounding; the area is evidence.
    const auto g = run_case("aground_at_speed.csv").of_kind("grounding");
    ASSERT_EQ(g.size(), 1u);
    const fs::path harbour = harbour_around(g[0]["ship_lat"].get<double>(), g[0]["ship_lon"].get<double>(), "Test harbour");
    const Outcome fast = shoal("check --coast " + coast + data("tracks/ais_cases/aground_at_speed.csv") + " --berths '" + harbour.string() +
                               "' -o '" + out.string() + "' --no-progress");
    EXPECT_EQ(fast.status, 1) << fast.out << fast.err;
    rep = nlohmann::json::parse(slurp(out));
    ASSERT_EQ(rep["features"].size(), 1u);
    EXPECT_EQ(rep["features"][0]["properties"]["kind"], "grounding");
    EXPECT_EQ(rep["features"][0]["properties"]["area_name"], "Test harbour");
    EXPECT_EQ(rep["features"][0]["properties"]["start"], g[0]["start"]) << "the same contact";
    // A berths file that is not there is a clear error, and no report is written.
    const Outcome missing = shoal("check --coast " + coast + data("tracks/ais_cases/aground_at_speed.csv") +
                                  " --berths /nonexistent/berths.gpkg -o '" + (temp_dir() / "never.geojson").string() + "'");
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.err.find("/nonexistent/berths.gpkg"), std::string::npos) << missing.err;
    EXPECT_FALSE(fs::exists(temp_dir() / "never.geojson"));
}

TEST(CliContactKinds, NonFiniteRuleOptionsAreRefused) {
    for (const char* opt : {"--berthing-speed nan", "--stop-diameter nan", "--stop-time 0", "--stop-time nan", "--max-speed nan",
                            "--margin nan", "--step nan", "--max-gap inf", "--berth-tolerance nan"}) {
        const Outcome r = shoal("check --coast '" + source_root() + "/examples/data/gof_helsinki_land.geojson' --dims 100,20,8,8 " +
                                data("tracks/ais_cases/aground_at_speed.csv") + " " + opt + " -o '" + (temp_dir() / "never.geojson").string() + "'");
        EXPECT_EQ(r.status, 2) << opt << "\n" << r.err;
        EXPECT_FALSE(fs::exists(temp_dir() / "never.geojson")) << opt;
    }
}

// The command module is linked without GDAL, GEOS and PROJ and loads each when a run first needs
// it (src/util/lazy_libraries.hpp; docs/performance.md): a check of a file without tracks against
// a grid whose source is GeoJSON loads none of them; tracks reported with a QGIS project need
// the chart (GDAL) and geometry (GEOS). Where lazy binding is turned off (LD_BIND_NOW), the
// executable loads all three before the module, which then binds every symbol at once (a
// symbol in none of its libraries fails there): the same report files, byte for byte.
TEST(Cli, TheModuleLoadsGdalGeosAndProjOnlyWhenARunNeedsThem) {
    const std::string grid = (temp_dir() / "lazy-solent.shoalgrid").string();
    ASSERT_EQ(shoal("import " + data("coast/uk_solent_land.geojson") + " -o '" + grid + "'").status, 0);
    const fs::path module = fs::path(SHOAL_BINARY).parent_path() / "libshoal_cli_full.so";
    ASSERT_TRUE(fs::exists(module));
    const fs::path err = temp_dir() / "lazy-err.txt";
    const Outcome needed = run_command("readelf -d '" + module.string() + "'", err);
    ASSERT_EQ(needed.status, 0) << needed.err;
    EXPECT_NE(needed.out.find("(NEEDED)"), std::string::npos) << needed.out;
    if (needed.out.find("libgdal") != std::string::npos)  // SHOAL_LAZY_LIBRARIES off (a SHOAL_SANITIZE build: CMakeLists.txt)
        GTEST_SKIP() << "the module links GDAL, GEOS and PROJ in this build (SHOAL_LAZY_LIBRARIES off)";
    for (const char* lib : {"libgdal", "libgeos", "libproj"}) EXPECT_EQ(needed.out.find(lib), std::string::npos) << lib << " in\n" << needed.out;

    const fs::path none = temp_dir() / "lazy-no-tracks.csv";
    std::ofstream(none) << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
    const fs::path tracks = solent_tracks();
    struct Case {
        fs::path input;
        std::vector<const char*> loaded;  // what the dynamic loader says the run loaded (PROJ with GDAL, which links it)
    };
    for (const Case& c : {Case{none, {}}, Case{tracks, {"libgdal.so", "libgeos_c.so", "libproj.so"}}}) {
        const std::string name = c.input.stem().string();
        const fs::path lazy = temp_dir() / ("lazy-" + name), eager = temp_dir() / ("eager-" + name);
        fs::remove_all(lazy);
        fs::remove_all(eager);
        fs::create_directories(lazy);
        fs::create_directories(eager);
        const std::string args = " check --coast '" + grid + "' --dims 50,10,5,5 '" + c.input.string() + "' -o ";
        const Outcome l = run_command("LD_DEBUG=libs '" + std::string(SHOAL_BINARY) + "'" + args + "'" + (lazy / "r.geojson").string() + "'", err);
        ASSERT_LE(l.status, 2) << l.err;  // 2 for the file with no fix (skipped), 1 for the grounding
        ASSERT_TRUE(fs::exists(lazy / "r.geojson")) << name;
        for (const char* lib : {"libgdal.so", "libgeos_c.so", "libproj.so"}) {
            const bool want = std::find_if(c.loaded.begin(), c.loaded.end(), [&](const char* w) { return std::string(w) == lib; }) != c.loaded.end();
            EXPECT_EQ(l.err.find(std::string("/") + lib) != std::string::npos, want) << name << ": " << lib;
        }
        const Outcome e = run_command("LD_BIND_NOW=1 '" + std::string(SHOAL_BINARY) + "'" + args + "'" + (eager / "r.geojson").string() + "'", err);
        ASSERT_EQ(e.status, l.status) << e.err;
        std::vector<std::string> files;
        for (const auto& f : fs::directory_iterator(lazy)) files.push_back(f.path().filename().string());
        EXPECT_GE(files.size(), 10u) << name;  // the report, its layer files and styles, the QGIS project
        for (const std::string& f : files) EXPECT_EQ(slurp(lazy / f), slurp(eager / f)) << name << ": " << f;
    }
}

// A grid written to a device (-o /dev/null: to see an import's account without keeping the
// grid) has no size to tell: the account names it without one, not an internal error.
TEST(Cli, ImportToADeviceSaysWhatItWroteWithoutASize) {
    const Outcome r = shoal("import " + data("coast/uk_solent_land.geojson") + " -o /dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("wrote:          /dev/null\n"), std::string::npos) << r.out;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

}  // namespace
