// Exercises and roles (exercise.hpp): the exercise key of a track, the exercise file, and an
// audit of two exercises in one run: encounters and COLREG situations within an exercise only,
// never across two, none between two targets, every track / approach / event with its exercise.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <shoal/audit/audit.hpp>
#include <shoal/audit/exercise.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/util/error.hpp>

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
    EXPECT_THROW(parse_exercise_by("column"), UsageError);
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
    static void SetUpTestSuite() {
        grid::BuildRequest req;
        req.cell_m = 500;
        s_grid = new grid::CoastGrid(grid::build_grid({test::data_path("coast/uk_solent_land.geojson")}, req, nullptr));
    }
    static void TearDownTestSuite() {
        delete s_grid;
        s_grid = nullptr;
    }
    static grid::CoastGrid* s_grid;
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
grid::CoastGrid* ExerciseAudit::s_grid = nullptr;

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
}  // namespace shoal::audit
