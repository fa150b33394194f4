// `check --shard I/N` over every shard, then `merge`: the report of one run, byte for byte;
// and merge refusing parts that are not one run's complete set.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <nlohmann/json.hpp>

#include "build_kind.hpp"
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
using shoal::test::under_sanitizer;

Outcome shoal(const std::string& args) { return shoal::test::run_shoal(args, temp_dir() / "cache", temp_dir() / "stderr.txt"); }

std::string source_root() { return fs::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().string(); }
std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

const std::string helsinki = "--coast '" + source_root() + "/examples/data/gof_helsinki_land.geojson' --dims 100,20,8,8 --no-progress";

/// The hand-made AIS cases (groundings, alongside, wild fixes) and one vessel split over two
/// files (one run merges it into one track), a file with bad rows and one that cannot be read
/// (problems of files).
std::string case_files() {
    static const std::string files = [] {
        const std::string dir = std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/";
        std::string list;
        for (const char* f : {"aground_at_speed.csv", "berthing_sideways.csv", "jump_and_null_island.csv", "still_no_heading.csv",
                              "passes_clear.csv", "aground_at_speed_no_sog.csv"})
            list += " '" + dir + f + "'";
        // moored_then_leaves.csv cut in two files after its 40th fix.
        std::ifstream in(dir + "moored_then_leaves.csv");
        std::ofstream a(temp_dir() / "moored_a.csv"), b(temp_dir() / "moored_b.csv");
        std::string header, line;
        std::getline(in, header);
        a << header << "\n";
        b << header << "\n";
        for (int i = 0; std::getline(in, line); ++i) (i < 40 ? a : b) << line << "\n";
        std::ofstream bad(temp_dir() / "bad_rows.csv");
        bad << "mmsi,timestamp,lat,lon,sog,cog,heading\n"
               "230990009,2024-05-01T10:00:00Z,60.10,24.90,5,0,0\n"
               "230990009,2024-05-01T10:01:00Z,not-a-latitude,24.90,5,0,0\n"
               "230990009,2024-05-01T10:02:00Z,60.103,24.90,5,0,0\n";
        return list + " " + q(temp_dir() / "moored_a.csv") + " " + q(temp_dir() / "moored_b.csv") + " " + q(temp_dir() / "bad_rows.csv") +
               " '" + SHOAL_TEST_DATA + "tracks/unknown_format.txt'";  // a file that cannot be read: a problem of the run
    }();
    return files;
}

/// Where run `name` writes its report: REPORT.EXT in a folder of its own, so that the reports
/// of a single run and of a merge have the same file name (a GeoPackage's QGIS project names
/// its file).
fs::path report_of(const std::string& name, const std::string& ext) {
    fs::create_directories(temp_dir() / name);
    return temp_dir() / name / ("report." + ext);
}

/// One run over `files`; the report's bytes.
std::string single_run(const std::string& name, const std::string& extra = "", const std::string& ext = "geojson",
                       const std::string& files = case_files()) {
    const fs::path out = report_of(name, ext);
    const Outcome r = shoal("check " + helsinki + extra + " " + files + " -o " + q(out));
    EXPECT_EQ(r.status, 1) << r.err;
    return slurp(out);
}

/// Every shard of N, then merge (parts shuffled when `shuffle`); the merged report's bytes.
std::string sharded_run(unsigned n, const std::string& name, const std::string& extra = "", bool shuffle = false,
                        const std::string& ext = "geojson", const std::string& files = case_files()) {
    std::vector<std::string> parts;
    for (unsigned i = 0; i < n; ++i) {
        const fs::path part = temp_dir() / (name + "-part" + std::to_string(i) + "." + ext);
        const Outcome r = shoal("check " + helsinki + extra + " --jobs 1 --shard " + std::to_string(i) + "/" + std::to_string(n) + " " + files +
                                " -o " + q(part));
        EXPECT_TRUE(r.status == 0 || r.status == 1) << r.err;
        parts.push_back(q(part));
    }
    if (shuffle) std::shuffle(parts.begin(), parts.end(), std::mt19937(n));
    std::string list;
    for (const auto& p : parts) list += " " + p;
    const fs::path out = report_of(name + "-merged", ext);
    const Outcome m = shoal("merge" + list + " -o " + q(out));
    EXPECT_EQ(m.status, 1) << "a grounding in the merged report: " << m.err << m.out;
    EXPECT_EQ(fs::exists(temp_dir() / (name + "-merged") / "report.qml"), ext == "geojson") << "a QGIS style beside a GeoJSON report, as check writes";
    return slurp(out);
}

TEST(ShardMerge, EveryShardThenMergeIsTheSingleRunByteForByte) {
    const std::string one = single_run("single");
    ASSERT_NE(one.find("\"grounding\""), std::string::npos);
    ASSERT_NE(one.find("moored_a.csv + "), std::string::npos) << "the split vessel is one track";
    ASSERT_NE(one.find("dropped as an outlier"), std::string::npos);
    ASSERT_NE(one.find("not-a-latitude"), std::string::npos) << "a file's problem";
    ASSERT_NE(one.find("unknown_format.txt"), std::string::npos) << "a file that cannot be read";
    for (unsigned n : {1u, 2u, 3u, 5u}) EXPECT_EQ(sharded_run(n, "n" + std::to_string(n)), one) << n << " shards";
    EXPECT_EQ(sharded_run(4, "shuffled", "", true), one) << "parts in any order";
}

TEST(ShardMerge, AShardHoldsOnlyItsTracksAndSaysWhichShardItIs) {
    const fs::path part = temp_dir() / "say.geojson";
    const Outcome r = shoal("check " + helsinki + " --shard 1/3 " + case_files() + " -o " + q(part));
    ASSERT_TRUE(r.status == 0 || r.status == 1) << r.err;
    const std::string text = slurp(part);
    EXPECT_NE(text.find("\"shard\": \"1/3\""), std::string::npos);
    EXPECT_LT(text.find("\"track\": \""), text.size());
}

TEST(ShardMerge, AnExerciseIsNeverSplit) {
    const std::string one = single_run("exercise", " --encounters");
    EXPECT_EQ(sharded_run(3, "exercise", " --encounters"), one);
}

/// Exercises one file each (--exercise-by file): in file x, two ships cross (a collision and
/// close quarters) at 10:05 + (4 - x) * 20 s, so that one run's encounters, sorted by time,
/// are in the reverse order of the files and of their tracks.
std::string exercise_files() {
    static const std::string files = [] {
        std::string list;
        for (int x = 0; x < 5; ++x) {
            const fs::path f = temp_dir() / ("exercise" + std::to_string(x) + ".csv");
            std::ofstream out(f);
            out << "mmsi,timestamp,lat,lon,heading\n";
            for (int i = 0; i <= 10; ++i) {
                const int t = i * 60 + (4 - x) * 20;
                char row[160];
                std::snprintf(row, sizeof row, "23099%04d,2024-05-01T10:%02d:%02dZ,60.1000,%.5f,90\n", 10 * x, t / 60, t % 60, 24.90 + 0.002 * i);
                out << row;
                std::snprintf(row, sizeof row, "23099%04d,2024-05-01T10:%02d:%02dZ,%.5f,24.9100,0\n", 10 * x + 1, t / 60, t % 60, 60.0955 + 0.0009 * i);
                out << row;
            }
            list += " " + q(f);
        }
        return list;
    }();
    return files;
}

TEST(ShardMerge, ExercisesByFileInShuffledShardsMergeToTheSingleRun) {
    const std::string by_file = " --encounters --exercise-by file";
    const std::string one = single_run("exercises", by_file, "geojson", exercise_files());
    const auto doc = nlohmann::json::parse(one);
    ASSERT_EQ(doc["shoal"]["summary"]["exercises"], 5);
    ASSERT_GE(doc["shoal"]["summary"]["collisions"], 5) << "a collision in each exercise";
    ASSERT_GE(doc["shoal"]["closest_approaches"].size(), 5u);
    EXPECT_EQ(sharded_run(3, "exercises3", by_file, true, "geojson", exercise_files()), one);
    const std::string gpkg = single_run("exercises-gpkg", by_file, "gpkg", exercise_files());
    EXPECT_EQ(sharded_run(3, "exercises3-gpkg", by_file, true, "gpkg", exercise_files()), gpkg) << "GeoPackage parts";
}

/// The exercises of exercise_files() in one file, the exercise in a column: every exercise
/// has the same two vessels (so each vessel is five tracks, one per exercise).
std::string exercise_column_file() {
    static const std::string file = [] {
        const fs::path f = temp_dir() / "exercise_column.csv";
        std::ofstream out(f);
        out << "mmsi,exercise,timestamp,lat,lon,heading\n";
        for (int x = 0; x < 5; ++x)
            for (int i = 0; i <= 10; ++i) {
                const int t = i * 60 + (4 - x) * 20;
                char row[160];
                std::snprintf(row, sizeof row, "230990000,ex%d,2024-05-01T10:%02d:%02dZ,60.1000,%.5f,90\n", x, t / 60, t % 60, 24.90 + 0.002 * i);
                out << row;
                std::snprintf(row, sizeof row, "230990001,ex%d,2024-05-01T10:%02d:%02dZ,%.5f,24.9100,0\n", x, t / 60, t % 60, 60.0955 + 0.0009 * i);
                out << row;
            }
        return " " + q(f);
    }();
    return file;
}

TEST(ShardMerge, ExercisesByAColumnShardAsWholeExercisesAndMergeToTheSingleRun) {
    const std::string by_column = " --exercise-by column:exercise";
    const std::string one = single_run("column", by_column, "geojson", exercise_column_file());
    const auto doc = nlohmann::json::parse(one);
    ASSERT_EQ(doc["shoal"]["summary"]["exercises"], 5);
    ASSERT_EQ(doc["shoal"]["tracks"].size(), 10u) << "each vessel one track per exercise";
    ASSERT_GE(doc["shoal"]["summary"]["collisions"], 5) << "a collision in each exercise";
    EXPECT_EQ(sharded_run(3, "column3", by_column, true, "geojson", exercise_column_file()), one);
}

TEST(ShardMerge, AnExerciseWhoseShipsListOnlyTheirClosestPairsMergesToTheSingleRun) {
    // The ten ships of the five files as one exercise, each listing the one other ship it came
    // closest to: the summary's counts of what is not listed merge like the others.
    const std::string capped = " --encounters --max-encounters-per-ship 1";
    const std::string one = single_run("capped", capped, "geojson", exercise_files());
    const auto doc = nlohmann::json::parse(one);
    ASSERT_GT(doc["shoal"]["summary"]["pairs_not_listed"].get<int>(), 0) << "the cap leaves pairs out";
    ASSERT_LE(doc["shoal"]["closest_approaches"].size(), 10u);
    EXPECT_EQ(sharded_run(3, "capped3", capped, true, "geojson", exercise_files()), one);
    const std::string gpkg = single_run("capped-gpkg", capped, "gpkg", exercise_files());
    EXPECT_EQ(sharded_run(3, "capped3-gpkg", capped, true, "gpkg", exercise_files()), gpkg) << "GeoPackage parts";
}

/// Whether `gpkg` (a GeoPackage) has a layer or table `name`: GDAL's answer.
bool has_table(const fs::path& gpkg, const std::string& name) {
    GDALAllRegister();
    const GDALDatasetUniquePtr ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    return ds && ds->GetLayerByName(name.c_str()) != nullptr;
}

TEST(ShardMerge, AssessedExercisesInShuffledShardsMergeToTheSingleRun) {
    // --assess: every exercise's two ships cross (CPA under 300 m) inside a 1 kn speed limit;
    // scores and breaches of the parts go back in the single run's order (by trainee).
    const fs::path assessment = temp_dir() / "assessment.json";
    std::ofstream(assessment) << R"({"criteria": [
        {"id": "cpa", "kind": "cpa", "limit": 300, "penalty": 10},
        {"id": "slow", "kind": "speed_limit", "limit": 1, "penalty": 1, "per": "metre",
         "area": [[24.89, 60.09], [24.93, 60.09], [24.93, 60.11], [24.89, 60.11]]},
        {"id": "land", "kind": "land_clearance", "limit": 2000, "penalty": 1, "per": "second"}]})";
    const std::string assessed = " --exercise-by file --assess " + q(assessment);
    const std::string one = single_run("assessed", assessed, "geojson", exercise_files());
    const auto doc = nlohmann::json::parse(one);
    ASSERT_EQ(doc["shoal"]["assessment"]["scores"].size(), 10u) << "every ship a trainee";
    std::size_t breaches = 0;
    for (const auto& f : doc["features"]) breaches += f["properties"]["kind"] == "breach";
    ASSERT_GE(breaches, 20u) << "a CPA and a speed breach for every ship";
    EXPECT_EQ(doc["shoal"]["summary"]["breaches"], breaches);
    EXPECT_EQ(sharded_run(3, "assessed3", assessed, true, "geojson", exercise_files()), one);
    const std::string gpkg = single_run("assessed-gpkg", assessed, "gpkg", exercise_files());
    EXPECT_TRUE(has_table(report_of("assessed-gpkg", "gpkg"), "breaches"));
    EXPECT_TRUE(has_table(report_of("assessed-gpkg", "gpkg"), "scores"));
    EXPECT_EQ(sharded_run(3, "assessed3-gpkg", assessed, true, "gpkg", exercise_files()), gpkg) << "GeoPackage parts";
}

TEST(ShardMerge, GeoPackageShardsMergeToTheSingleRunsGeoPackageByteForByte) {
    const std::string one = single_run("single-gpkg", "", "gpkg");
    ASSERT_EQ(one.compare(0, 15, "SQLite format 3"), 0);
    EXPECT_EQ(single_run("single-gpkg-again", " --jobs 2", "gpkg"), one) << "two runs write the same bytes";
    for (const char* table : {"events", "tracks", "hulls", "poses", "coast", "problems", "run", "summary"})
        EXPECT_TRUE(has_table(report_of("single-gpkg", "gpkg"), table)) << table;
    EXPECT_FALSE(has_table(report_of("single-gpkg", "gpkg"), "part"));
    for (unsigned n : {1u, 2u, 3u}) EXPECT_EQ(sharded_run(n, "gpkg" + std::to_string(n), "", false, "gpkg"), one) << n << " shards";
    EXPECT_EQ(sharded_run(4, "gpkg-shuffled", "", true, "gpkg"), one) << "parts in any order";
    EXPECT_TRUE(has_table(temp_dir() / "gpkg-shuffled-part0.gpkg", "part")) << "a part says where its rows go";
}

TEST(ShardMerge, OneRunPerFileMergesToTheSingleRunWhenNoVesselSpansFiles) {
    const std::string dir = std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/";
    std::string all, parts;
    int k = 0;
    for (const char* f : {"aground_at_speed.csv", "jump_and_null_island.csv", "berthing_sideways.csv"}) {
        all += " '" + dir + f + "'";
        const fs::path part = temp_dir() / ("file" + std::to_string(k++) + ".geojson");
        const Outcome r = shoal("check " + helsinki + " --shard 0/1 '" + dir + f + "' -o " + q(part));
        ASSERT_TRUE(r.status == 0 || r.status == 1) << r.err;
        parts += " " + q(part);
    }
    const fs::path single = temp_dir() / "files-single.geojson", merged = temp_dir() / "files-merged.geojson";
    EXPECT_EQ(shoal("check " + helsinki + all + " -o " + q(single)).status, 1);
    const Outcome m = shoal("merge" + parts + " -o " + q(merged));
    EXPECT_EQ(m.status, 1) << m.err;
    EXPECT_EQ(slurp(merged), slurp(single));
}

/// `shoal check` of the Helsinki coast with `args`, its report at temp_dir()/FILE (quoted for the shell).
std::string checked_part(const std::string& file, const std::string& args) {
    const fs::path p = temp_dir() / file;
    const Outcome r = shoal("check " + helsinki + " " + args + " -o " + q(p));
    EXPECT_TRUE(r.status == 0 || r.status == 1) << r.err;
    return q(p);
}

TEST(ShardMerge, MismatchedIncompleteOrForeignPartsAreRefusedNamingWhy) {
    const auto part = [](const std::string& name, const std::string& args) { return checked_part(name + ".geojson", args); };
    const std::string a = part("r0", "--shard 0/2 " + case_files());
    const std::string b = part("r1", "--shard 1/2 " + case_files());
    const std::string b_step = part("r1step", "--step 2 --shard 1/2 " + case_files());
    const std::string c3 = part("r1of3", "--shard 1/3 " + case_files());
    const std::string whole = part("whole", case_files());
    const fs::path out = temp_dir() / "refused.geojson";
    struct Case {
        std::string parts, says;
    };
    const std::string dir = std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/";
    const std::string split_a = part("split_a", "--shard 0/1 " + q(temp_dir() / "moored_a.csv"));
    const std::string split_b = part("split_b", "--shard 0/1 " + q(temp_dir() / "moored_b.csv"));
    for (const Case& c : std::vector<Case>{
             {a + " " + b_step, "'step_m' is 5.0"},
             {a + " " + b_step, "but 2.0 in"},
             {a, "shard 1/2 is missing"},
             {a + " " + b + " " + b, "shard 1/2 is given twice"},
             {a + " " + c3, "different shard counts"},
             {a + " " + b + " " + whole, "not the report of a shard"},
             {split_a + " " + split_b, "vessel 230990003 has tracks in"},
             {a + " " + b + " " + a, "given twice"},
             {q(temp_dir() / "no-such.geojson"), "no-such.geojson: cannot be read"},
             {q(temp_dir() / "part.gpkg"), "part.gpkg: cannot be read (no such file)"},
         }) {
        fs::remove(out);
        const Outcome r = shoal("merge " + c.parts + " -o " + q(out));
        EXPECT_EQ(r.status, 2) << c.parts << "\n" << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << "wanted '" << c.says << "' in: " << r.err;
        EXPECT_FALSE(fs::exists(out)) << "nothing written";
    }
    const Outcome gpkg = shoal("merge " + a + " " + b + " -o " + q(temp_dir() / "merged.gpkg"));
    EXPECT_EQ(gpkg.status, 2) << gpkg.err;
    EXPECT_NE(gpkg.err.find("a GeoJSON part; a GeoPackage report (-o REPORT.gpkg) is merged from GeoPackage parts"), std::string::npos) << gpkg.err;
    EXPECT_FALSE(fs::exists(temp_dir() / "merged.gpkg"));
    // A part given as the output would be destroyed.
    const Outcome self = shoal("merge " + a + " " + b + " -o " + a);
    EXPECT_EQ(self.status, 2) << self.err;
    EXPECT_NE(self.err.find("would destroy the input"), std::string::npos) << self.err;
}

TEST(ShardMerge, MismatchedIncompleteOrForeignGeoPackagePartsAreRefusedNamingWhy) {
    const auto part = [](const std::string& name, const std::string& args) { return checked_part(name + ".gpkg", args); };
    const std::string a = part("g0", "--shard 0/2 " + case_files());
    const std::string b = part("g1", "--shard 1/2 " + case_files());
    const std::string b_step = part("g1step", "--step 2 --shard 1/2 " + case_files());
    const std::string c3 = part("g1of3", "--shard 1/3 " + case_files());
    const std::string whole = part("gwhole", case_files());
    const fs::path geojson_b = temp_dir() / "g1.geojson";
    ASSERT_LE(shoal("check " + helsinki + " --shard 1/2 " + case_files() + " -o " + q(geojson_b)).status, 1);
    const fs::path text = temp_dir() / "notes.gpkg";
    std::ofstream(text) << "not a report\n";
    // A GeoPackage that is not shoal's: GDAL's own, with one layer.
    const fs::path foreign = temp_dir() / "foreign.gpkg";
    {
        GDALAllRegister();
        GDALDatasetUniquePtr ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(foreign.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        ASSERT_TRUE(ds && ds->CreateLayer("roads", nullptr, wkbLineString, nullptr));
    }
    struct Case {
        std::string parts, output, says;
    };
    const std::string out_gpkg = q(temp_dir() / "refused.gpkg"), out_geojson = q(temp_dir() / "refused.geojson");
    for (const Case& c : std::vector<Case>{
             {a + " " + b_step, out_gpkg, "'step_m' is 5.0"},
             {a + " " + b_step, out_gpkg, "but 2.0 in"},
             {a, out_gpkg, "shard 1/2 is missing"},
             {a + " " + b + " " + b, out_gpkg, "shard 1/2 is given twice"},
             {a + " " + c3, out_gpkg, "different shard counts"},
             {a + " " + b + " " + whole, out_gpkg, "gwhole.gpkg: not the report of a shard (no table part)"},
             {a + " " + q(foreign), out_gpkg, "foreign.gpkg: not the report of a shard (no table part)"},
             {a + " " + q(text), out_gpkg, "notes.gpkg: not a GeoPackage (not an SQLite file)"},
             {a + " " + q(geojson_b), out_gpkg, "g1.geojson: a GeoJSON part; a GeoPackage report"},
             {a + " " + b, out_geojson, "g0.gpkg: a GeoPackage part; a GeoJSON report is merged from GeoJSON parts"},
         }) {
        fs::remove(temp_dir() / "refused.gpkg");
        fs::remove(temp_dir() / "refused.geojson");
        const Outcome r = shoal("merge " + c.parts + " -o " + c.output);
        EXPECT_EQ(r.status, 2) << c.parts << "\n" << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << "wanted '" << c.says << "' in: " << r.err;
        EXPECT_FALSE(fs::exists(temp_dir() / "refused.gpkg")) << "nothing written";
        EXPECT_FALSE(fs::exists(temp_dir() / "refused.geojson")) << "nothing written";
        for (const auto& e : fs::directory_iterator(temp_dir()))
            EXPECT_EQ(e.path().filename().string().find(".shoal.tmp"), std::string::npos) << "a temporary left: " << e.path();
    }
    // A refused merge leaves a report already there as it was.
    const fs::path kept = temp_dir() / "kept.gpkg";
    fs::copy_file(foreign, kept, fs::copy_options::overwrite_existing);
    const std::string before = slurp(kept);
    EXPECT_EQ(shoal("merge " + a + " -o " + q(kept)).status, 2);
    EXPECT_EQ(slurp(kept), before);
    const Outcome self = shoal("merge " + a + " " + b + " -o " + a);
    EXPECT_EQ(self.status, 2) << self.err;
    EXPECT_NE(self.err.find("would destroy the input"), std::string::npos) << self.err;
}

TEST(ShardMerge, PartsScoredAgainstOtherCriteriaAreRefusedInEitherFormat) {
    // The same assessment file, edited between two shards: the path is the same, the criteria
    // are not; the run header's assessment_fingerprint tells them apart.
    const fs::path file = temp_dir() / "edited-assessment.json";
    for (const char* ext : {".gpkg", ".geojson"}) {
        std::ofstream(file) << R"({"criteria": [{"id": "cpa", "kind": "cpa", "limit": 300, "penalty": 10}]})";
        const std::string a = checked_part(std::string("crit0") + ext, "--exercise-by file --assess " + q(file) + " --shard 0/2" + exercise_files());
        std::ofstream(file) << R"({"criteria": [{"id": "cpa", "kind": "cpa", "limit": 100, "penalty": 1000}]})";
        const std::string b = checked_part(std::string("crit1") + ext, "--exercise-by file --assess " + q(file) + " --shard 1/2" + exercise_files());
        const Outcome r = shoal("merge " + a + " " + b + " -o " + q(temp_dir() / (std::string("crit-merged") + ext)));
        EXPECT_EQ(r.status, 2) << ext << "\n" << r.err;
        EXPECT_NE(r.err.find("'assessment_fingerprint' is"), std::string::npos) << ext << "\n" << r.err;
    }
}

TEST(ShardMerge, ShardsOfAFileThatGainedABadRowBetweenThemAreRefusedInEitherOrderAndFormat) {
    // The day file gained a bad row between the two shard runs: the second part lists one more
    // problem of the files than the first. Before: SIGSEGV (exit 139, no report) when the part
    // listing fewer came first (merge read the first part's problems past their end).
    const fs::path grown = temp_dir() / "grown_day.csv";
    const std::string rows = "mmsi,timestamp,lat,lon,sog,cog,heading\n"
                             "230990019,2024-05-01T10:00:00Z,60.10,24.90,5,0,0\n"
                             "230990019,2024-05-01T10:02:00Z,60.103,24.90,5,0,0\n";
    const std::string dir = std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/";
    const std::string files = q(dir + "aground_at_speed.csv") + " " + q(dir + "passes_clear.csv") + " " + q(grown);
    for (const char* ext : {".geojson", ".gpkg"}) {
        std::ofstream(grown) << rows;  // no problem at all in the first shard's run
        const std::string none = checked_part(std::string("grown0") + ext, "--shard 0/2 " + files);
        std::ofstream(grown) << rows << "230990019,2024-05-01T10:03:00Z,60.104,east,5,0,0\n";
        const std::string more = checked_part(std::string("grown1") + ext, "--shard 1/2 " + files);
        // ...and parts that both list problems, the second one more.
        std::ofstream(grown) << rows << "230990019,2024-05-01T10:03:00Z,60.104,east,5,0,0\n";
        const std::string one = checked_part(std::string("grown2") + ext, "--shard 0/2 " + files);
        std::ofstream(grown) << rows << "230990019,2024-05-01T10:03:00Z,60.104,east,5,0,0\n230990019,2024-05-01T10:04:00Z,north,24.9,5,0,0\n";
        const std::string two = checked_part(std::string("grown3") + ext, "--shard 1/2 " + files);
        for (const std::string& parts : {none + " " + more, more + " " + none, one + " " + two, two + " " + one}) {
            const fs::path out = temp_dir() / (std::string("grown-merged") + ext);
            const Outcome r = shoal("merge " + parts + " -o " + q(out));
            EXPECT_EQ(r.status, 2) << ext << " " << parts << "\n" << r.err;
            // The file's size and fingerprint differ (before the problems are compared).
            EXPECT_NE(r.err.find("grown_day.csv' is "), std::string::npos) << ext << " " << parts << "\n" << r.err;
            EXPECT_NE(r.err.find("the file changed between the shards' runs"), std::string::npos) << ext << " " << parts << "\n" << r.err;
            EXPECT_FALSE(fs::exists(out)) << "nothing written";
        }
    }
}

TEST(ShardMerge, PartsThatDifferInAnInputsBytesOrAnyOptionAreRefusedInEitherOrderNamingWhatDiffers) {
    // Before: the run header held the inputs' names only, and not --vessels, --date,
    // --hull-from-length-width, --berth-tolerance: shards of a file that grew between their runs
    // merged into a report of neither (47 tracks and 198 fixes instead of 54 and 299), and parts
    // with and without --vessels merged.
    const std::string dir = std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/";
    const fs::path day = temp_dir() / "growing_day.csv", vessels = temp_dir() / "identity_vessels.csv", ship = temp_dir() / "identity_ship.json";
    const fs::path roles = temp_dir() / "identity_roles.json", berths = temp_dir() / "identity_berths.geojson";
    const std::string head = "mmsi,timestamp,lat,lon,sog,cog,heading\n";
    const std::string first = "230990029,2024-05-01T10:00:00Z,60.10,24.90,5,0,0\n230990029,2024-05-01T10:02:00Z,60.103,24.90,5,0,0\n";
    const std::string later = "230990039,2024-05-01T11:00:00Z,60.10,24.95,5,0,0\n230990039,2024-05-01T11:02:00Z,60.103,24.95,5,0,0\n";
    const std::string files = q(dir + "aground_at_speed.csv") + " " + q(dir + "passes_clear.csv") + " " + q(day);
    std::ofstream(day) << head << first;
    const fs::path piped = temp_dir() / "identity_piped.csv";
    const std::string table = "mmsi,name,draught_m\n230990001,AGROUND AT SPEED,7\n";
    const std::string berth = R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
        "geometry": {"type": "Polygon", "coordinates": [[[24.0, 60.0], [24.01, 60.0], [24.01, 60.01], [24.0, 60.0]]]}}]})";
    const std::string ship_text = R"({"name": "identity", "length": 100, "beam": 16, "a": 80, "b": 20, "c": 8, "d": 8})";
    std::ofstream(vessels) << table;
    std::ofstream(ship) << ship_text;
    std::ofstream(berths) << berth;
    std::ofstream(roles) << R"({"tracks": [{"track": "230990001", "role": "trainee"}]})";
    // --coast a grid file: its chart sources are read again at check time (berths, shore
    // constructions, the scale, the coast layer); before, an edited source beside an unchanged
    // grid merged (the GeoPackage took the first part's coast layer).
    const fs::path land = temp_dir() / "identity_land.geojson", grid = temp_dir() / "identity_land.shoalgrid";
    const auto reset_land = [&] { fs::copy_file(source_root() + "/examples/data/gof_helsinki_land.geojson", land, fs::copy_options::overwrite_existing); };
    reset_land();
    ASSERT_EQ(shoal("import " + q(land) + " -o " + q(grid)).status, 0);
    // --berths a Shapefile: its .prj (and .dbf, .shx) are the source too, not only the .shp given.
    const fs::path berths_shp = temp_dir() / "identity_berths.shp", berths_prj = temp_dir() / "identity_berths.prj";
    {
        GDALAllRegister();
        const GDALDatasetUniquePtr src(GDALDataset::Open(berths.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
        ASSERT_TRUE(src);
        const char* argv[] = {"-f", "ESRI Shapefile", nullptr};
        GDALVectorTranslateOptions* o = GDALVectorTranslateOptionsNew(const_cast<char**>(argv), nullptr);
        GDALDatasetH in = GDALDataset::ToHandle(src.get());
        GDALDatasetH out = GDALVectorTranslate(berths_shp.c_str(), nullptr, 1, &in, o, nullptr);
        GDALVectorTranslateOptionsFree(o);
        ASSERT_TRUE(out);
        GDALClose(out);
    }
    const std::string prj_text = slurp(berths_prj);
    ASSERT_FALSE(prj_text.empty());
    // --assess with a colreg criterion: its parameters (new) are the run's too.
    const fs::path assess = temp_dir() / "identity_assessment.json";
    const std::string colreg = R"({"criteria": [{"id": "rules", "kind": "colreg", "penalty": 10}]})";
    std::ofstream(assess) << colreg;
    struct Case {
        std::string name, a, b, says;
        std::function<void()> between;  ///< what changes between the two shards' runs
    };
    const std::string v = " --vessels " + q(vessels), s = " --ship " + q(ship), e = " --encounters --roles " + q(roles);
    const std::string bt = " --berths " + q(berths);
    const std::string bs = " --berths " + q(berths_shp);
    const std::string g = " --coast " + q(grid), as = " --encounters --assess " + q(assess);
    const std::vector<Case> cases = {
        {"grown", "", "", "growing_day.csv' is ", [&] { std::ofstream(day) << head << first << later; }},
        {"vessels", v, "", "'vessels' is ", [] {}},
        {"vessels-edited", v, v, "'vessels_fingerprint' is ", [&] { std::ofstream(vessels) << table << "230990007,PASSES CLEAR,3\n"; }},
        {"date", " --date 2024-05-01", "", "'date' is ", [] {}},
        {"date-other", " --date 2024-05-01", " --date 2024-05-02", "'date' is ", [] {}},
        {"length-width", " --hull-from-length-width", "", "'hull_from_length_width' is ", [] {}},
        {"berth-tolerance", " --berth-tolerance 20", "", "'berth_tolerance_m' is ", [] {}},
        {"ship-edited", s, s, "'ship_fingerprint' is ", [&] { std::ofstream(ship) << R"({"name": "identity", "length": 140, "beam": 16, "a": 120, "b": 20, "c": 8, "d": 8})"; }},
        {"berths-edited", bt, bt, "'berths_fingerprint' is ", [&] { std::ofstream(berths) << berth << "\n"; }},
        {"roles-edited", e, e, "'roles_fingerprint' is ", [&] { std::ofstream(roles) << R"({"tracks": [{"track": "230990001", "role": "target"}]})"; }},
        {"berths-prj-edited", bs, bs, "'berths_fingerprint' is ", [&] { std::ofstream(berths_prj, std::ios::app) << " "; }},
        // The exercise file from standard input: its entries as read (its name "-" says nothing).
        {"roles-stdin", " --encounters --roles - <" + q(roles), " --encounters --roles - <" + q(roles), "'roles_fingerprint' is ",
         [&] { std::ofstream(roles) << R"({"tracks": [{"track": "230990001", "role": "target"}]})"; }},
        {"vessels-stdin", " --vessels - <" + q(vessels), " --vessels - <" + q(vessels), "'vessels_fingerprint' is ",
         [&] { std::ofstream(vessels) << "mmsi,name,draught_m\n230990001,AGROUND AT SPEED,2\n"; }},
        {"ship-stdin", " --ship - <" + q(ship), " --ship - <" + q(ship), "'ship_fingerprint' is ",
         [&] { std::ofstream(ship) << R"({"name": "identity", "length": 140, "beam": 16, "a": 120, "b": 20, "c": 8, "d": 8})"; }},
        {"chart-edited", g, g, "'chart_fingerprint' is ", [&] { std::ofstream(land, std::ios::app) << "\n"; }},
        // A track file from standard input: its content as read (before: the name '-' alone, and
        // shards fed other days merged into a report of neither).
        {"tracks-stdin", " - <" + q(piped), " - <" + q(piped), "input '-' is ", [&] { std::ofstream(piped) << head << later; }},
        {"colreg-edited", as, as, "'assessment_fingerprint' is ",
         [&] { std::ofstream(assess) << R"({"criteria": [{"id": "rules", "kind": "colreg", "penalty": 10, "cpa_m": 500}]})"; }},
    };
    for (const char* ext : {".geojson", ".gpkg"})
        for (const Case& c : cases) {
            // Under a sanitizer the GeoPackage parts of the first three cases only: merge reads
            // both formats' run headers into one record and compares that (the plain build
            // tries every case in both).
            if (under_sanitizer && std::string(ext) == ".gpkg" && &c - cases.data() >= 3) continue;
            // Every input as it was at the start, then shard 0, the change, shard 1.
            std::ofstream(day) << head << first;
            std::ofstream(piped) << head << first;
            std::ofstream(vessels) << table;
            std::ofstream(ship) << ship_text;
            std::ofstream(berths) << berth;
            std::ofstream(roles) << R"({"tracks": [{"track": "230990001", "role": "trainee"}]})";
            reset_land();
            std::ofstream(assess) << colreg;
            std::ofstream(berths_prj) << prj_text;
            // A part with --ship instead of helsinki's --dims when the case gives one.
            const auto part = [&](const std::string& name, const std::string& args) {
                const fs::path path = temp_dir() / name;
                std::string base = helsinki;
                if (args.find("--coast ") != std::string::npos) base = base.substr(base.find(" --dims"));  // the case's own coast
                if (args.find("--ship ") != std::string::npos) base.replace(base.find("--dims 100,20,8,8"), 17, "");
                const Outcome r = shoal("check " + base + " " + args + " -o " + q(path));
                EXPECT_TRUE(r.status == 0 || r.status == 1) << r.err;
                return q(path);
            };
            const std::string a = part("id-" + c.name + "-0" + ext, c.a + " --shard 0/2 " + files);
            c.between();
            const std::string b = part("id-" + c.name + "-1" + ext, c.b + " --shard 1/2 " + files);
            for (const std::string& parts : {a + " " + b, b + " " + a}) {
                const fs::path out = temp_dir() / (std::string("id-merged") + ext);
                fs::remove(out);
                const Outcome r = shoal("merge " + parts + " -o " + q(out));
                EXPECT_EQ(r.status, 2) << c.name << ext << " " << parts << "\n" << r.err;
                EXPECT_NE(r.err.find("the parts are not of one run: "), std::string::npos) << c.name << ext << "\n" << r.err;
                EXPECT_NE(r.err.find(c.says), std::string::npos) << c.name << ext << ": wanted '" << c.says << "' in: " << r.err;
                EXPECT_FALSE(fs::exists(out)) << c.name << ext << ": nothing written";
            }
        }
    {  // Parts checked against a grid file whose sources did not change still merge.
        reset_land();
        std::string parts;
        for (const char* k : {"0/2", "1/2"}) {
            const fs::path path = temp_dir() / ("id-grid-" + std::string(k, 1) + ".gpkg");
            const Outcome r = shoal("check" + helsinki.substr(helsinki.find(" --dims")) + g + " --shard " + k + " " + files + " -o " + q(path));
            EXPECT_LE(r.status, 1) << r.err;
            parts += " " + q(path);
        }
        const Outcome m = shoal("merge" + parts + " -o " + q(temp_dir() / "id-grid-merged.gpkg"));
        EXPECT_LE(m.status, 1) << m.err;
    }
    {  // Shards fed the same content on standard input still merge, to the report of one such run;
       // the content is what the readers saw (shard 1 is fed it gzipped).
        std::ofstream(piped) << head << first << later;
        ASSERT_EQ(std::system(("gzip -c " + q(piped) + " >" + q(piped.string() + ".gz")).c_str()), 0);
        std::string parts;
        for (const char* k : {"0/2", "1/2"}) {
            const fs::path path = temp_dir() / ("id-piped-" + std::string(k, 1) + ".geojson");
            const std::string fed = k[0] == '0' ? q(piped) : q(piped.string() + ".gz");
            const Outcome r = shoal("check " + helsinki + " --shard " + k + " " + files + " - <" + fed + " -o " + q(path));
            EXPECT_LE(r.status, 1) << r.err;
            parts += " " + q(path);
        }
        const fs::path merged = temp_dir() / "id-piped-merged.geojson", single = temp_dir() / "id-piped-single.geojson";
        const Outcome m = shoal("merge" + parts + " -o " + q(merged));
        EXPECT_LE(m.status, 1) << m.err;
        const Outcome one = shoal("check " + helsinki + " " + files + " - <" + q(piped) + " -o " + q(single));
        EXPECT_LE(one.status, 1) << one.err;
        EXPECT_EQ(slurp(merged), slurp(single));
    }
    // The same inputs and options in every shard still merge to the single run (the header's new
    // fields are the single run's too).
    std::ofstream(day) << head << first << later;
    const std::string opts = v + " --date 2024-05-01 --berth-tolerance 20" + bt;
    EXPECT_EQ(sharded_run(2, "identity-same", opts, true, "geojson", files), single_run("identity-single", opts, "geojson", files));
}

TEST(ShardMerge, AGeoJsonPartWithoutASummaryIsRefusedWhereverItComes) {
    // A hand-edited part whose run header lost its summary: refused, not read through a missing key.
    const std::string a = checked_part("nosum0.geojson", "--shard 0/2 " + case_files());
    checked_part("nosum1.geojson", "--shard 1/2 " + case_files());
    const fs::path edited = temp_dir() / "nosum1-edited.geojson";
    nlohmann::ordered_json doc = nlohmann::ordered_json::parse(slurp(temp_dir() / "nosum1.geojson"));
    doc["shoal"].erase("summary");
    std::ofstream(edited) << doc.dump();
    for (const std::string& parts : {a + " " + q(edited), q(edited) + " " + a}) {
        const Outcome r = shoal("merge " + parts + " -o " + q(temp_dir() / "nosum-merged.geojson"));
        EXPECT_EQ(r.status, 2) << parts << "\n" << r.err;
        EXPECT_NE(r.err.find("nosum1-edited.geojson: not the report of a shard (no summary in its run header)"), std::string::npos) << r.err;
    }
}

TEST(ShardMerge, ADebriefOrAPictureWithShardIsRefusedBeforeAnyWorkNotWrittenByEveryShard) {
    // Before: each shard wrote the same debrief pages over the others' (the last one's: 21 of
    // 54 tracks, 0 of 1 grounding) while the merged report was complete. A shard writes its
    // debrief record beside its part instead (--debrief-record), and merge the pages.
    const fs::path debrief = temp_dir() / "shard-debrief", picture = temp_dir() / "shard-picture.svg", part = temp_dir() / "shard-out.geojson";
    struct Case {
        std::string option, says;
    };
    for (const Case& c : std::vector<Case>{{"--debrief " + q(debrief), "--debrief with --shard: --debrief writes the whole run's outputs"},
                                           {"--plot " + q(picture), "--plot with --shard: --plot writes the whole run's outputs"}})
        for (const char* shard : {"0/2", "1/2", "0/1"}) {
            for (const char* record : {"", " --debrief-record"}) {
                const Outcome r = shoal("check " + helsinki + " --encounters " + c.option + record + " --shard " + shard + " " + case_files() + " -o " + q(part));
                EXPECT_EQ(r.status, 2) << c.option << " " << shard << "\n" << r.err;
                EXPECT_NE(r.err.find("shoal: usage error: " + c.says), std::string::npos) << r.err;
                EXPECT_NE(r.err.find("give each shard --debrief-record"), std::string::npos) << "says what to do: " << r.err;
                EXPECT_NE(r.err.find("without --shard"), std::string::npos) << "says what to do: " << r.err;
                EXPECT_FALSE(fs::exists(debrief)) << "no debrief folder";
                EXPECT_FALSE(fs::exists(picture)) << "no picture";
                EXPECT_FALSE(fs::exists(part)) << "no part either: refused before any work";
                EXPECT_FALSE(fs::exists(part.string() + ".debrief.cbor")) << "no record";
            }
        }
    // --debrief-record is a shard's; a whole run writes its pages itself.
    const Outcome whole = shoal("check " + helsinki + " --debrief-record " + case_files() + " -o " + q(part));
    EXPECT_EQ(whole.status, 2) << whole.err;
    EXPECT_NE(whole.err.find("--debrief-record goes with --shard I/N"), std::string::npos) << whole.err;
    const Outcome piped = shoal("check " + helsinki + " --shard 0/2 --debrief-record " + case_files() + " -o -");
    EXPECT_EQ(piped.status, 2) << piped.err;
    EXPECT_NE(piped.err.find("--debrief-record goes beside the part: give -o a file"), std::string::npos) << piped.err;
    EXPECT_FALSE(fs::exists(part));
    // Writing partitions audits nothing: no record to write.
    const fs::path partitions = temp_dir() / "record-partitions";
    const Outcome split = shoal("check " + helsinki + " --partitions 2 --debrief-record -o " + q(partitions) + " '" + std::string(SHOAL_TEST_DATA) +
                                "tracks/ais_cases/passes_clear.csv'");
    EXPECT_EQ(split.status, 2) << split.err;
    EXPECT_NE(split.err.find("--partitions writes partitions: it goes without --from-partitions, --shard, --traffic, --traffic-only and --debrief-record"),
              std::string::npos) << split.err;
    EXPECT_FALSE(fs::exists(partitions));
}

/// The debrief pages in `dir` (file name -> bytes) and the picture at `svg`.
struct Pages {
    std::map<std::string, std::string> pages;
    std::string svg;
};
Pages pages_in(const fs::path& dir, const fs::path& svg) {
    Pages p;
    for (const auto& e : fs::directory_iterator(dir)) p.pages[e.path().filename().string()] = slurp(e.path());
    p.svg = slurp(svg);
    return p;
}

/// One check of the whole run over `files` with --debrief and --plot: its pages and picture.
Pages single_pages(const std::string& name, const std::string& extra, const std::string& ext, const std::string& files) {
    const fs::path dir = temp_dir() / (name + "-debrief"), svg = temp_dir() / (name + ".svg");
    const Outcome r = shoal("check " + helsinki + extra + " " + files + " -o " + q(report_of(name, ext)) + " --debrief " + q(dir) + " --plot " + q(svg));
    EXPECT_EQ(r.status, 1) << r.err;
    return pages_in(dir, svg);
}

/// Every shard of N with --debrief-record, then merge --debrief --plot (parts shuffled): the
/// pages and the picture merge writes. `tracks` gets each part's count of tracks.
Pages sharded_pages(unsigned n, const std::string& name, const std::string& extra, const std::string& ext, const std::string& files,
                    std::vector<std::size_t>* tracks = nullptr) {
    std::vector<std::string> parts;
    for (unsigned i = 0; i < n; ++i) {
        const fs::path part = temp_dir() / (name + "-part" + std::to_string(i) + "." + ext);
        const Outcome r = shoal("check " + helsinki + extra + " --jobs 1 --shard " + std::to_string(i) + "/" + std::to_string(n) +
                                " --debrief-record " + files + " -o " + q(part));
        EXPECT_TRUE(r.status == 0 || r.status == 1) << r.err;
        EXPECT_TRUE(fs::exists(part.string() + ".debrief.cbor")) << "the record beside its part";
        if (tracks && ext == "geojson") tracks->push_back(nlohmann::json::parse(slurp(part))["shoal"]["tracks"].size());
        parts.push_back(q(part));
    }
    std::shuffle(parts.begin(), parts.end(), std::mt19937(n));
    std::string list;
    for (const auto& p : parts) list += " " + p;
    const fs::path dir = temp_dir() / (name + "-debrief"), svg = temp_dir() / (name + ".svg");
    const Outcome m = shoal("merge" + list + " -o " + q(report_of(name + "-merged", ext)) + " --debrief " + q(dir) + " --plot " + q(svg));
    EXPECT_EQ(m.status, 1) << m.err << m.out;
    EXPECT_NE(m.out.find("debrief: "), std::string::npos) << m.out;
    return pages_in(dir, svg);
}

/// An exercise run with roles (a trainee and a target in most exercises, two trainees in one)
/// scored against an assessment (CPA, a speed limit, land clearance, the rules of the road).
std::string assessed_exercise_options() {
    static const std::string options = [] {
        const fs::path assessment = temp_dir() / "pages_assessment.json", roles = temp_dir() / "pages_roles.json";
        std::ofstream(assessment) << R"({"pass_mark": 40, "criteria": [
            {"id": "cpa", "kind": "cpa", "limit": 300, "penalty": 10},
            {"id": "slow", "kind": "speed_limit", "limit": 1, "penalty": 1, "per": "metre", "area_name": "Slow zone",
             "area": [[24.89, 60.09], [24.93, 60.09], [24.93, 60.11], [24.89, 60.11]]},
            {"id": "land", "kind": "land_clearance", "limit": 2000, "penalty": 1, "per": "second"},
            {"id": "rules", "kind": "colreg", "penalty": 5}]})";
        std::ofstream(roles) << R"({"tracks": [{"track": "230990000", "role": "trainee"}, {"track": "230990011", "role": "trainee"},
            {"track": "230990020", "role": "trainee"}, {"track": "230990031", "role": "trainee"},
            {"track": "230990040", "role": "trainee"}, {"track": "230990041", "role": "trainee"}]})";
        return " --exercise-by file --roles " + q(roles) + " --assess " + q(assessment);
    }();
    return options;
}

TEST(ShardMerge, TheDebriefAndThePictureOfAnAssessedExerciseRunAreMadeAtTheMergeAsOneCheckWritesThem) {
    const std::string opts = assessed_exercise_options();
    const Pages one = single_pages("pages-ex", opts, "geojson", exercise_files());
    ASSERT_EQ(one.pages.size(), 5u) << "a page per exercise (file)";
    const std::string& page = one.pages.begin()->second;
    EXPECT_NE(page.find("<tr class=\"score\">"), std::string::npos) << "scores";
    EXPECT_NE(page.find("<tr class=\"breach\""), std::string::npos) << "breaches";
    EXPECT_NE(page.find("<tr class=\"encounter\">"), std::string::npos) << "encounters";
    EXPECT_NE(page.find("data-kind=\"collision\""), std::string::npos) << "a collision";
    EXPECT_NE(one.svg.find("class=\"cpa\""), std::string::npos) << "closest approaches in the picture";
    for (const std::string ext : {"geojson", "gpkg"})
        for (unsigned n : {2u, 3u}) {
            if (under_sanitizer && (n == 3 || ext == "gpkg")) continue;  // one of each path is enough there
            const Pages merged = sharded_pages(n, "pages-ex" + std::to_string(n) + ext, opts, ext, exercise_files());
            EXPECT_EQ(merged.pages.size(), one.pages.size()) << n << " " << ext;
            for (const auto& [file, bytes] : one.pages) EXPECT_EQ(merged.pages.count(file) ? merged.pages.at(file) : "", bytes) << file << " " << n << " " << ext;
            EXPECT_EQ(merged.svg, one.svg) << n << " " << ext;
        }
}

TEST(ShardMerge, TheDebriefAndThePictureOfARealWorldRunWhoseOnePageSpansShardsAreMadeAtTheMerge) {
    // The AIS cases and the exercises' vessels, in the real world: one page, run.html, whose
    // tracks every shard holds some of.
    const std::string files = case_files() + exercise_files();
    const Pages one = single_pages("pages-rw", "", "geojson", files);
    ASSERT_EQ(one.pages.size(), 1u);
    ASSERT_TRUE(one.pages.count("run.html"));
    const std::size_t total = nlohmann::json::parse(slurp(report_of("pages-rw", "geojson")))["shoal"]["tracks"].size();
    ASSERT_GE(total, 15u);
    EXPECT_NE(one.pages.at("run.html").find("data-kind=\"grounding\""), std::string::npos);
    for (const std::string ext : {"geojson", "gpkg"})
        for (unsigned n : {2u, 3u}) {
            if (under_sanitizer && (n == 3 || ext == "gpkg")) continue;
            std::vector<std::size_t> tracks;
            const Pages merged = sharded_pages(n, "pages-rw" + std::to_string(n) + ext, "", ext, files, &tracks);
            for (std::size_t t : tracks) EXPECT_TRUE(t > 0 && t < total) << "every shard holds a part of the one page's tracks: " << t << " of " << total;
            EXPECT_EQ(merged.pages, one.pages) << n << " " << ext;
            EXPECT_EQ(merged.svg, one.svg) << n << " " << ext;
        }
}

TEST(ShardMerge, TheMergesPagesNeedEveryPartsOwnRecordOfOneRun) {
    const std::string files = case_files();
    const auto part = [&](const std::string& name, const std::string& args) { return checked_part(name, args + " " + files); };
    const std::string a0 = part("rec-a0.geojson", "--shard 0/2 --debrief-record"), a1 = part("rec-a1.geojson", "--shard 1/2 --debrief-record");
    const fs::path dir = temp_dir() / "rec-pages", svg = temp_dir() / "rec.svg", out = temp_dir() / "rec-merged.geojson";
    const auto merge = [&](const std::string& parts, const std::string& more = "") {
        return shoal("merge " + parts + " -o " + q(out) + " --debrief " + q(dir) + " --plot " + q(svg) + more);
    };
    const auto nothing_written = [&] { return !fs::exists(dir) && !fs::exists(svg) && !fs::exists(out); };
    ASSERT_EQ(merge(a0 + " " + a1).status, 1);
    ASSERT_TRUE(fs::exists(dir / "run.html"));
    fs::remove_all(dir);
    fs::remove(svg);
    fs::remove(out);
    const fs::path rec0 = temp_dir() / "rec-a0.geojson.debrief.cbor", rec1 = temp_dir() / "rec-a1.geojson.debrief.cbor";
    const std::string saved0 = slurp(rec0);
    {  // A part without a record: a usage error naming it and saying how to write one.
        fs::remove(rec0);
        const Outcome r = merge(a1 + " " + a0);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_NE(r.err.find("the part '" + (temp_dir() / "rec-a0.geojson").string() + "' has no debrief record"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--debrief-record"), std::string::npos) << r.err;
        EXPECT_TRUE(nothing_written());
        const Outcome plain = shoal("merge " + a0 + " " + a1 + " -o " + q(out));
        EXPECT_EQ(plain.status, 1) << "the report alone needs no record: " << plain.err;
        fs::remove(out);
    }
    {  // Another shard's record beside a part: not its part's.
        fs::copy_file(rec1, rec0, fs::copy_options::overwrite_existing);
        const Outcome r = merge(a0 + " " + a1);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_NE(r.err.find("is not the record of the part '" + (temp_dir() / "rec-a0.geojson").string() + "'"), std::string::npos) << r.err;
        EXPECT_TRUE(nothing_written());
    }
    {  // The record of another run's shard 0 (--margin 80), beside this run's shard 0.
        part("rec-b0.geojson", "--shard 0/2 --margin 80 --debrief-record");
        fs::copy_file(temp_dir() / "rec-b0.geojson.debrief.cbor", rec0, fs::copy_options::overwrite_existing);
        const Outcome r = merge(a0 + " " + a1);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_NE(r.err.find("is not the record of the part"), std::string::npos) << r.err;
        EXPECT_TRUE(nothing_written());
    }
    {  // A damaged record: said so.
        const std::string good = slurp(rec0);
        std::ofstream(rec0, std::ios::binary) << good.substr(0, good.size() / 2);
        const Outcome r = merge(a0 + " " + a1);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_NE(r.err.find("a damaged debrief record"), std::string::npos) << r.err;
        EXPECT_TRUE(nothing_written());
        // A file of that name that shoal did not write is not replaced by the shard.
        std::ofstream(rec0) << "my notes\n";
        const Outcome kept = shoal("check " + helsinki + " --shard 0/2 --debrief-record " + files + " -o " + a0);
        EXPECT_EQ(kept.status, 2) << kept.err;
        EXPECT_NE(kept.err.find("is not a debrief record shoal wrote"), std::string::npos) << kept.err;
        EXPECT_EQ(slurp(rec0), "my notes\n");
        fs::remove(rec0);
        part("rec-a0.geojson", "--shard 0/2 --debrief-record");
    }
    {  // The grid: merge --coast another chart is refused by its fingerprint; the run's own is taken.
        const fs::path other = temp_dir() / "rec-other-coast.geojson";
        std::ofstream(other) << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
            "geometry": {"type": "Polygon", "coordinates": [[[24.0, 60.0], [24.5, 60.0], [24.5, 60.05], [24.0, 60.0]]]}}]})";
        const Outcome r = merge(a0 + " " + a1, " --coast " + q(other));
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_NE(r.err.find("gives the grid"), std::string::npos) << r.err;
        EXPECT_TRUE(nothing_written());
        const Outcome ok = merge(a0 + " " + a1, " --coast '" + source_root() + "/examples/data/gof_helsinki_land.geojson'");
        EXPECT_EQ(ok.status, 1) << ok.err;
        EXPECT_TRUE(fs::exists(dir / "run.html"));
        const Outcome alone = shoal("merge " + a0 + " " + a1 + " -o " + q(temp_dir() / "rec-alone.geojson") + " --coast " + q(other));
        EXPECT_EQ(alone.status, 2) << alone.err;
        EXPECT_NE(alone.err.find("merge --coast goes with --debrief or --plot"), std::string::npos) << alone.err;
        EXPECT_FALSE(fs::exists(temp_dir() / "rec-alone.geojson"));
    }
}

TEST(ShardMerge, BadShardTextIsAUsageErrorNamingTheOption) {
    for (const char* bad : {"2/2", "x/3", "1"}) {
        const Outcome r = shoal("check " + helsinki + " --shard " + bad + " " + case_files() + " -o " + q(temp_dir() / "bad.geojson"));
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_NE(r.err.find("--shard '" + std::string(bad) + "'"), std::string::npos) << r.err;
    }
}

}  // namespace
