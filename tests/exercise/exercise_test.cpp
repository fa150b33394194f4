// Exercises and roles (exercise.hpp): the exercise key of a track, the exercise file, and an
// audit of two exercises in one run: encounters and COLREG situations within an exercise only,
// never across two, none between two targets, every track / approach / event with its exercise.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <shoal/audit/audit.hpp>
#include <shoal/exercise/exercise.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/util/error.hpp>

#include "audit/solent_grid.hpp"
#include "test_support.hpp"

namespace shoal::audit {
namespace {

TEST(Exercise, KeyByRunFileOrFolder) {
    EXPECT_EQ(exercise_key(ExerciseBy::run, "morning/ex1/own.csv"), "run");
    EXPECT_EQ(exercise_key(ExerciseBy::file, "morning/ex1/own.csv"), "morning/ex1/own.csv");
    EXPECT_EQ(exercise_key(ExerciseBy::folder, "morning/ex1/own.csv"), "morning/ex1");
    EXPECT_EQ(exercise_key(ExerciseBy::folder, "own.csv"), ".");
    track::Track t;
    t.file = "ex2/target.gpx";
    EXPECT_EQ(exercise_key(ExerciseBy::folder, t), "ex2");
    EXPECT_EQ(parse_exercise_by("folder"), ExerciseBy::folder);
    // By a column: the column's value is the exercise, whatever the file.
    const ExerciseGrouping g = parse_exercise_grouping("column:Exercise");
    EXPECT_EQ(g.by, ExerciseBy::column);
    EXPECT_EQ(g.column, "Exercise");
    EXPECT_EQ(exercise_by_text(g.by, g.column), "column:Exercise");
    EXPECT_EQ(exercise_by_text(ExerciseBy::folder, ""), "folder");
    EXPECT_EQ(exercise_key(ExerciseBy::column, "morning/all.csv", "ex 2"), "ex 2");
    t.exercise = "night";
    EXPECT_EQ(exercise_key(ExerciseBy::column, t), "night");
    EXPECT_EQ(exercise_key(ExerciseBy::folder, t), "ex2");
    EXPECT_THROW(parse_exercise_by("column"), UsageError);
    EXPECT_THROW(parse_exercise_by("column:"), UsageError);
    EXPECT_THROW(parse_exercise_by("column: "), UsageError);
    EXPECT_THROW(parse_exercise_by("columns:x"), UsageError);
}

TEST(Exercise, TheExerciseFileWinsOverTheRoleColumnWhichWinsOverTheDefault) {
    const Roles r = Roles::parse(R"({"default_role": "target", "tracks": [{"track": "a", "role": "target"},
        {"track": "b", "exercise": "ex1", "role": "trainee"}]})",
                                 "ex.json");
    track::Track t;
    t.id = "a";
    t.role = "trainee";  // the column says trainee; the file's entry says target
    EXPECT_EQ(role_of(&r, "ex1", t), Role::target);
    EXPECT_EQ(role_of(nullptr, "ex1", t), Role::trainee);
    t.id = "b";
    t.role = "target";
    EXPECT_EQ(role_of(&r, "ex1", t), Role::trainee);  // the exercise's entry
    EXPECT_EQ(role_of(&r, "ex2", t), Role::target);   // no entry there: the column
    t.role = "trainee";
    EXPECT_EQ(role_of(&r, "ex2", t), Role::trainee);  // the column over the file's default_role
    t.role.clear();
    EXPECT_EQ(role_of(&r, "ex2", t), Role::target);   // no column: the file's default
    EXPECT_EQ(role_of(nullptr, "ex2", t), Role::trainee);
    EXPECT_EQ(r.entry_role("ex2", "b"), std::nullopt);
}

TEST(Exercise, RolesFromTheExerciseFile) {
    const Roles r = Roles::parse(R"({"default_role": "target", "tracks": [
        {"track": "own1", "role": "Own Ship"}, {"track": "x", "role": "trainee"},
        {"track": "x", "exercise": "ex2", "role": "target"}]})",
                                 "ex.json");
    EXPECT_EQ(r.role_of("ex1", "own1"), Role::trainee);
    EXPECT_EQ(r.role_of("ex1", "other"), Role::target);
    EXPECT_EQ(r.role_of("ex1", "x"), Role::trainee);
    EXPECT_EQ(r.role_of("ex2", "x"), Role::target);  // the exercise's entry wins
    const Roles d = Roles::parse(R"({"tracks": []})", "ex.json");
    EXPECT_EQ(d.role_of("run", "any"), Role::target);
    // Bad files name the file and the entry.
    auto message = [](const std::string& text) {
        try {
            Roles::parse(text, "ex.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("{").find("ex.json"), std::string::npos);
    EXPECT_NE(message(R"({"tracks": [{"track": "a", "role": "pilot"}]})").find("tracks[0] (track 'a')"), std::string::npos);
    EXPECT_NE(message(R"({"tracks": [{"role": "target"}]})").find("tracks[0]: no \"track\""), std::string::npos);
    EXPECT_NE(message(R"({"trainees": []})").find("unknown member 'trainees'"), std::string::npos);
    EXPECT_NE(message(R"({"tracks": [], "default_role": 3})").find("default_role"), std::string::npos);
    // A number too large for a double is nlohmann's out_of_range, not a parse_error: still bad input.
    EXPECT_NE(message(R"({"tracks": [{"track": 1e999, "role": "target"}]})").find("ex.json': not JSON: "), std::string::npos);
}

constexpr double t0 = 1714557600;  // 2024-05-01T10:00:00Z
constexpr double lat0 = 50.70;     // open water east of the Isle of Wight
constexpr double m_per_deg_lat = 111195.0;

/// A ship on a parallel `north_m` north of lat0, from `lon_from` to `lon_to`, a fix every 10 s
/// over 1200 s (about 5 m/s).
track::Track along(const std::string& id, const std::string& file, double north_m, double lon_from, double lon_to) {
    track::Track t;
    t.id = id;
    t.file = file;
    const double heading = lon_to > lon_from ? 90 : 270;
    for (int i = 0; i <= 120; ++i) {
        track::Fix f;
        f.time_s = t0 + 10 * i;
        f.position = {lon_from + (lon_to - lon_from) * i / 120.0, lat0 + north_m / m_per_deg_lat};
        f.heading_deg = f.cog_deg = heading;
        f.sog_kn = 9.7;
        f.line = static_cast<std::size_t>(i) + 2;
        t.fixes.push_back(f);
    }
    return t;
}

class ExerciseAudit : public ::testing::Test {
protected:
    static void SetUpTestSuite() { s_grid = &test::solent_grid(); }
    static const grid::CoastGrid* s_grid;
    const hull::Hull m_hull = hull::Hull::from_dimensions({50, 10, 5, 5});

    /// Two exercises of the same scenario at the same time: in each the own ship meets a target
    /// head-on (300 m apart); in ex1 a second target sails 300 m beside the first. own1 and own2
    /// sail the same line at the same time: one exercise would make them collide.
    std::vector<track::Track> tracks() const {
        return {along("own1", "ex1/own.csv", 0, -1.02, -0.935), along("tgt1", "ex1/target.csv", 300, -0.935, -1.02),
                along("tgt1b", "ex1/target.csv", 600, -0.935, -1.02), along("own2", "ex2/own.csv", 0, -1.02, -0.935),
                along("tgt2", "ex2/target.csv", 300, -0.935, -1.02)};
    }
};
const grid::CoastGrid* ExerciseAudit::s_grid = nullptr;

/// One CSV file of two exercises (column `exercise`), roles in column `role`: A and B sail the
/// same water at the same time. Vessel 235000001 is the trainee of both (two tracks). In A it
/// sails east and its target 235000002 west 300 m north of it; in B it sails east on that
/// line, and its target 235000003 west on A's trainee's line. So each exercise is a head-on
/// pass at 300 m, but had the two been one, each trainee would have collided head-on with the
/// other exercise's target. Lines 2 and 3 are bad rows.
std::string two_exercises_csv(const std::string& path) {
    struct Ship {
        const char* id;
        const char* exercise;
        const char* role;
        track::Track track;
    };
    const std::vector<Ship> ships = {{"235000001", "A", "Own Ship", along("a", "", 0, -1.02, -0.935)},
                                     {"235000002", "A", "target", along("b", "", 300, -0.935, -1.02)},
                                     {"235000001", "B", "trainee", along("c", "", 300, -1.02, -0.935)},
                                     {"235000003", "B", "TARGET", along("d", "", 0, -0.935, -1.02)}};
    std::string text = "mmsi,exercise,role,timestamp,lat,lon,heading,sog\n";
    text += "235000002,,target,1714557600,50.70,-1.00,90,9.7\n";    // line 2: no exercise
    text += "235000002,A,pilot,1714557600,50.70,-1.00,90,9.7\n";    // line 3: no role shoal knows
    for (std::size_t i = 0; i < ships.front().track.fixes.size(); ++i)
        for (const Ship& s : ships) {
            const track::Fix& f = s.track.fixes[i];
            char row[200];
            std::snprintf(row, sizeof row, "%s,%s,%s,%.0f,%.7f,%.7f,%.0f,%.1f\n", s.id, s.exercise, s.role, f.time_s, f.position.lat,
                          f.position.lon, f.heading_deg, f.sog_kn);
            text += row;
        }
    std::ofstream(path) << text;
    return path;
}

TEST_F(ExerciseAudit, AnExerciseColumnSplitsOneFileIntoExercisesAuditedApart) {
    const test::TempDir dir;
    const std::string file = two_exercises_csv(dir.file("morning.csv"));
    AuditOptions o;
    o.jobs = 2;
    o.encounters = true;
    o.exercise_by = ExerciseBy::column;
    o.read.exercise_column = "exercise";
    o.read.role_column = "role";
    const AuditResult r = run_audit({file}, *s_grid, m_hull, "test hull", o);
    ASSERT_EQ(r.files.size(), 1u);
    ASSERT_TRUE(r.files[0].error.empty()) << r.files[0].error;
    EXPECT_EQ(r.files[0].read.skipped, 2u);
    ASSERT_EQ(r.files[0].read.messages.size(), 2u);
    EXPECT_NE(r.files[0].read.messages[0].find("morning.csv line 2: no exercise"), std::string::npos) << r.files[0].read.messages[0];
    EXPECT_NE(r.files[0].read.messages[1].find("morning.csv line 3: role 'pilot'"), std::string::npos) << r.files[0].read.messages[1];
    ASSERT_TRUE(r.errors.empty());
    ASSERT_EQ(r.tracks.size(), 4u);
    EXPECT_EQ(r.exercises, 2u);
    std::vector<std::string> tracks;
    for (const auto& t : r.tracks)
        tracks.push_back(t.summary.exercise + "/" + t.summary.id + "/" + to_string(t.summary.role) + "/" + std::to_string(t.summary.fixes));
    EXPECT_EQ(tracks, (std::vector<std::string>{"A/235000001/trainee/121", "A/235000002/target/121", "B/235000001/trainee/121",
                                                "B/235000003/target/121"}));
    EXPECT_EQ(r.collisions, 0u) << "a trainee never meets the other exercise's target";
    EXPECT_EQ(r.close_quarters, 0u);
    std::vector<std::string> pairs;
    for (const auto& c : r.situations) {
        const auto& a = r.tracks[c.a].summary;
        const auto& b = r.tracks[c.b].summary;
        EXPECT_EQ(a.exercise, b.exercise);
        pairs.push_back(a.exercise + ":" + a.id + "-" + b.id);
        EXPECT_EQ(c.at_start.situation, Situation::head_on) << pairs.back();
        EXPECT_NEAR(c.closest_m, 300, 2) << pairs.back();
    }
    EXPECT_EQ(pairs, (std::vector<std::string>{"A:235000001-235000002", "B:235000001-235000003"}));

    // The control: A's trainee and B's target in one exercise collide.
    AuditOptions one;
    one.encounters = true;
    const AuditResult mixed = audit_tracks({along("235000001", "", 0, -1.02, -0.935), along("235000003", "", 0, -0.935, -1.02)}, *s_grid,
                                           m_hull, "test hull", one);
    EXPECT_GE(mixed.collisions, 1u);

    // An exercise file beside the column: its entries win for the tracks they name.
    const Roles roles = Roles::parse(R"({"default_role": "trainee", "tracks": [{"track": "235000003", "exercise": "B", "role": "trainee"}]})", "ex.json");
    AuditOptions with_file = o;
    with_file.roles = &roles;
    const AuditResult both = run_audit({file}, *s_grid, m_hull, "test hull", with_file);
    ASSERT_EQ(both.tracks.size(), 4u);
    EXPECT_EQ(both.tracks[3].summary.role, Role::trainee);
    EXPECT_EQ(both.tracks[1].summary.role, Role::target) << "the column, not the file's default";

    // Shards hold whole exercises: every track of an exercise in the shard its exercise hashes to.
    std::map<std::string, std::set<unsigned>> shards_of;
    std::size_t audited = 0;
    for (unsigned i = 0; i < 3; ++i) {
        AuditOptions part = o;
        part.shard = {i, 3};
        const AuditResult p = run_audit({file}, *s_grid, m_hull, "test hull", part);
        audited += p.tracks.size();
        for (const auto& t : p.tracks) {
            shards_of[t.summary.exercise].insert(i);
            EXPECT_EQ(shard_of(t.summary.exercise, 3), i) << t.summary.exercise;
        }
    }
    EXPECT_EQ(audited, 4u);
    for (const auto& [exercise, shards] : shards_of) EXPECT_EQ(shards.size(), 1u) << exercise;

    // Without the column's name the run is refused; a file without the column is a file error.
    AuditOptions nameless = o;
    nameless.read.exercise_column.clear();
    EXPECT_THROW(run_audit({file}, *s_grid, m_hull, "test hull", nameless), UsageError);
    AuditOptions wrong = o;
    wrong.read.exercise_column = "drill";
    const AuditResult missing = run_audit({file}, *s_grid, m_hull, "test hull", wrong);
    ASSERT_EQ(missing.files.size(), 1u);
    EXPECT_NE(missing.files[0].error.find("morning.csv: the header has no column 'drill', the exercise column"), std::string::npos)
        << missing.files[0].error;
    EXPECT_TRUE(missing.tracks.empty());
}

TEST_F(ExerciseAudit, OneVesselInTwoFoldersIsOneTrackPerExerciseByFolderAndOneTrackOtherwise) {
    // The bridge 235000001 sailed ex1 and then ex2: one file in each folder.
    const test::TempDir dir;
    std::filesystem::create_directories(dir.path() / "ex1");
    std::filesystem::create_directories(dir.path() / "ex2");
    for (const char* ex : {"ex1", "ex2"}) {
        track::Track t = along("x", "", ex[2] == '1' ? 0 : 300, -1.02, -0.935);
        std::string text = "mmsi,timestamp,lat,lon\n";
        for (auto& f : t.fixes) {
            if (ex[2] == '2') f.time_s += 3600;
            char row[120];
            std::snprintf(row, sizeof row, "235000001,%.0f,%.7f,%.7f\n", f.time_s, f.position.lat, f.position.lon);
            text += row;
        }
        std::ofstream((dir.path() / ex / "bridge.csv").string()) << text;
    }
    const std::vector<std::string> inputs = {dir.file("ex1"), dir.file("ex2")};
    AuditOptions o;
    o.encounters = true;
    o.exercise_by = ExerciseBy::folder;
    const AuditResult by_folder = run_audit(inputs, *s_grid, m_hull, "test hull", o);
    ASSERT_EQ(by_folder.tracks.size(), 2u);
    EXPECT_EQ(by_folder.tracks[0].summary.exercise, dir.file("ex1"));
    EXPECT_EQ(by_folder.tracks[1].summary.exercise, dir.file("ex2"));
    EXPECT_EQ(by_folder.tracks[0].summary.fixes, 121u);
    EXPECT_EQ(by_folder.exercises, 2u);
    o.exercise_by = ExerciseBy::file;
    EXPECT_EQ(run_audit(inputs, *s_grid, m_hull, "test hull", o).tracks.size(), 2u);
    // One exercise (and outside exercise mode): one vessel, one track of both files.
    o.exercise_by = ExerciseBy::run;
    const AuditResult one = run_audit(inputs, *s_grid, m_hull, "test hull", o);
    ASSERT_EQ(one.tracks.size(), 1u);
    EXPECT_EQ(one.tracks[0].summary.fixes, 242u);
}

TEST_F(ExerciseAudit, EncountersAreFoundWithinAnExerciseOnlyAndNeverBetweenTwoTargets) {
    const Roles roles = Roles::parse(R"({"tracks": [{"track": "own1", "role": "trainee"}, {"track": "own2", "role": "trainee"}]})", "ex.json");
    AuditOptions o;
    o.jobs = 2;
    o.encounters = true;
    o.exercise_by = ExerciseBy::folder;
    o.roles = &roles;
    const AuditResult r = audit_tracks(tracks(), *s_grid, m_hull, "test hull", o);
    ASSERT_EQ(r.tracks.size(), 5u);
    ASSERT_TRUE(r.errors.empty());
    EXPECT_EQ(r.groundings, 0u);
    EXPECT_EQ(r.exercises, 2u);
    EXPECT_EQ(r.collisions, 0u);  // own1 and own2 are in different exercises
    for (const auto& t : r.tracks) {
        EXPECT_EQ(t.summary.exercise, t.summary.id.back() == '2' ? "ex2" : "ex1") << t.summary.id;
        EXPECT_EQ(t.summary.role, t.summary.id.rfind("own", 0) == 0 ? Role::trainee : Role::target) << t.summary.id;
    }
    auto id = [&](std::size_t k) { return r.tracks.at(k).summary.id; };
    // ex1: own1 x tgt1 (head-on), own1 x tgt1b; never tgt1 x tgt1b. ex2: own2 x tgt2.
    std::vector<std::string> pairs;
    for (const auto& c : r.situations) {
        EXPECT_EQ(r.tracks[c.a].summary.exercise, r.tracks[c.b].summary.exercise);
        pairs.push_back(id(c.a) + "-" + id(c.b));
    }
    std::sort(pairs.begin(), pairs.end());
    EXPECT_EQ(pairs, (std::vector<std::string>{"own1-tgt1", "own1-tgt1b", "own2-tgt2"}));
    for (const auto& c : r.situations) {
        if (id(c.b) == "tgt1b") continue;
        EXPECT_EQ(c.at_start.situation, Situation::head_on) << id(c.a) << "-" << id(c.b);
        EXPECT_NEAR(c.closest_m, 300, 2) << id(c.a);
        EXPECT_NEAR(c.closest_s - t0, 600, 5) << id(c.a);
    }
    // Every situation has its closest approach, within its exercise.
    EXPECT_EQ(r.encounters.approaches.size(), r.situations.size());
    for (const auto& a : r.encounters.approaches) EXPECT_EQ(r.tracks[a.a].summary.exercise, r.tracks[a.b].summary.exercise);

    // The same run as one exercise (the default): own1 and own2 collide; tgt1 x tgt1b are
    // still not reported (two targets).
    AuditOptions one = o;
    one.exercise_by = ExerciseBy::run;
    const AuditResult all = audit_tracks(tracks(), *s_grid, m_hull, "test hull", one);
    EXPECT_EQ(all.exercises, 1u);
    EXPECT_GE(all.collisions, 1u);
    for (const auto& e : all.encounters.events)
        EXPECT_FALSE(all.tracks[e.a.track].summary.role == Role::target && all.tracks[e.b.track].summary.role == Role::target);
    for (const auto& c : all.situations)
        EXPECT_FALSE(all.tracks[c.a].summary.role == Role::target && all.tracks[c.b].summary.role == Role::target);
    EXPECT_GT(all.situations.size(), r.situations.size());
}

}  // namespace
TEST(Exercise, AnEntryNamingNoTrackOfTheRunIsAnErrorNamingTheFileTheEntryAndWhatItWouldHaveDone) {
    const Roles r = Roles::parse(R"({"tracks": [{"track": "a", "role": "target"}, {"track": "b", "exercise": "ex1", "role": "trainee"}]})", "ex.json");
    EXPECT_NO_THROW(r.check_entries_name_tracks({{"a", "ex2"}, {"b", "ex1"}}));
    try {
        r.check_entries_name_tracks({{"a", "ex1"}, {"b", "ex2"}});
        ADD_FAILURE() << "b is in ex2 only";
    } catch (const shoal::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("exercise file 'ex.json': tracks[1] names track 'b' in exercise 'ex1', which that exercise has no track of (it "
                                             "would make it a trainee"),
                  std::string::npos)
            << e.what();
    }
    try {
        r.check_entries_name_tracks({{"b", "ex1"}});
        ADD_FAILURE() << "no track a";
    } catch (const shoal::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("tracks[0] names track 'a', which no track read has (it would make it a target; tracks read: 'b')"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace shoal::audit
