// The real world's contact rules (`shoal check --world real`, the default outside exercise mode)
// on hand-made AIS tracks against the real Helsinki coast: a contact is a grounding when the
// vessel's own motion says so (it came to rest where it touched, a touch and go, a gap after
// which it lies in contact), the chart's error when the vessel sailed on through, alongside when
// it berthed. The tracks and what a correct audit reports are in tests/data/tracks/ais_cases
// (make_cases.py there derives the geometry independently with OGR; expected.json holds each
// case's `args`, `expect` and `geometry`). `--world simulated` keeps the old rule: a contact that
// begins under way after the vessel was seen clear is a grounding.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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

Outcome shoal(const std::string& args) { return shoal::test::run_shoal(args, temp_dir() / "cache", temp_dir() / "stderr.txt"); }

std::string source_root() { return fs::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().string(); }

std::string data(const std::string& rel) { return "'" + std::string(SHOAL_TEST_DATA) + rel + "'"; }

/// Seconds since the epoch of an ISO 8601 UTC time (fractions kept).
double epoch_of(const std::string& iso) {
    std::tm tm{};
    int y = 0, mo = 0, d = 0, h = 0, mi = 0;
    double sec = 0;
    EXPECT_EQ(std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%lf", &y, &mo, &d, &h, &mi, &sec), 6) << iso;
    tm.tm_year = y - 1900, tm.tm_mon = mo - 1, tm.tm_mday = d, tm.tm_hour = h, tm.tm_min = mi;
    return static_cast<double>(::timegm(&tm)) + sec;
}

double epoch_of(const nlohmann::json& v) { return v.is_string() ? epoch_of(v.get<std::string>()) : NAN; }

/// A property as text or a number; "" and -1 when it is absent or null.
std::string str_of(const nlohmann::json& p, const char* key) { return p.contains(key) && p[key].is_string() ? p[key].get<std::string>() : ""; }
int int_of(const nlohmann::json& p, const char* key) { return p.contains(key) && p[key].is_number() ? p[key].get<int>() : -1; }

const nlohmann::json& cases() {
    static const nlohmann::json expected =
        nlohmann::json::parse(slurp(std::string(SHOAL_TEST_DATA) + "tracks/ais_cases/expected.json"));
    return expected["cases"];
}

/// One `shoal check` of a case, with the case's own options (`args` in expected.json).
struct CaseRun {
    std::string file;
    Outcome outcome;
    nlohmann::json report, expect, geometry;

    std::vector<nlohmann::json> features() const {
        std::vector<nlohmann::json> v;
        if (report.is_object() && report.contains("features"))
            for (const auto& f : report["features"]) v.push_back(f["properties"]);
        return v;
    }
    std::vector<nlohmann::json> of_kind(const std::string& kind) const {
        std::vector<nlohmann::json> v;
        for (const auto& p : features())
            if (str_of(p, "kind") == kind) v.push_back(p);
        return v;
    }
    /// Events of contact: every kind but close_pass.
    std::vector<nlohmann::json> contacts() const {
        std::vector<nlohmann::json> v;
        for (const auto& p : features())
            if (str_of(p, "kind") != "close_pass") v.push_back(p);
        return v;
    }
    /// What the run reported, for failure messages.
    std::string describe() const {
        std::ostringstream o;
        o << file << ": exit " << outcome.status << ", " << features().size() << " feature(s)";
        for (const auto& p : features()) {
            o << "\n  " << str_of(p, "kind");
            for (const char* k : {"grade", "reason", "disagreement", "start", "start_not_before", "start_uncertainty_s", "speed_kn",
                                  "speed_before_kn", "speed_after_kn", "deceleration_kn_s", "stay_s", "stop_distance_m", "berth_stays",
                                  "pieces", "penetration_m", "nav_status"})
                if (p.contains(k) && !p[k].is_null()) o << " " << k << "=" << p[k].dump();
        }
        if (!outcome.err.empty()) o << "\n  stderr: " << outcome.err.substr(0, 600);
        return o.str();
    }
};

CaseRun run(const std::string& file, const std::string& world = "") {
    CaseRun r;
    r.file = file;
    const nlohmann::json& c = cases().at(file);
    r.expect = c["expect"];
    r.geometry = c["geometry"];
    const fs::path out = temp_dir() / (file + (world.empty() ? "" : "." + world) + ".geojson");
    std::error_code ec;
    fs::remove(out, ec);
    r.outcome = shoal("check --coast '" + source_root() + "/examples/data/gof_helsinki_land.geojson' " + c["args"].get<std::string>() + " " +
                      data("tracks/ais_cases/" + file) + (world.empty() ? "" : " --world " + world) + " -o '" + out.string() +
                      "' --no-progress");
    if (fs::exists(out)) r.report = nlohmann::json::parse(slurp(out), nullptr, false);
    return r;
}

std::string world_of(const CaseRun& r) {
    if (!r.report.is_object() || !r.report.contains("shoal") || !r.report["shoal"].contains("world")) return "(none)";
    return r.report["shoal"]["world"].dump();
}

/// `start` of an event within [earliest, latest] (ISO times of expected.json).
void expect_start_within(const nlohmann::json& event, const nlohmann::json& earliest, const nlohmann::json& latest, const std::string& what) {
    ASSERT_TRUE(event.contains("start") && event["start"].is_string()) << what;
    const double s = epoch_of(event["start"]);
    EXPECT_GE(s, epoch_of(earliest) - 1e-3) << what << ": start " << event["start"] << " before " << earliest;
    EXPECT_LE(s, epoch_of(latest) + 1e-3) << what << ": start " << event["start"] << " after " << latest;
}

// ------------------------------------------------------------------------------------------------

TEST(CliRealWorld, AgroundSeenOnlyEveryTenMinutesWithNeitherHeadingNorCogIsAGroundingOfGradeThree) {
    const CaseRun r = run("aground_sparse.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    EXPECT_EQ(world_of(r), "\"real\"");
    const auto g = r.of_kind("grounding");
    ASSERT_EQ(g.size(), e["groundings"].get<std::size_t>()) << r.describe();
    EXPECT_EQ(r.features().size(), e["events"].get<std::size_t>()) << "lying aground 3 h is one event\n" << r.describe();
    expect_start_within(g[0], e["start_earliest"], e["start_latest"], r.describe());
    ASSERT_TRUE(g[0].contains("start_not_before") && g[0]["start_not_before"].is_string()) << r.describe();
    EXPECT_NEAR(epoch_of(g[0]["start_not_before"]), epoch_of(e["start_not_before"]), e["start_not_before_tolerance_s"].get<double>())
        << "the last clear fix\n" << r.describe();
    ASSERT_TRUE(g[0].contains("start_uncertainty_s") && g[0]["start_uncertainty_s"].is_number()) << r.describe();
    EXPECT_NEAR(g[0]["start_uncertainty_s"].get<double>(), epoch_of(g[0]["start"]) - epoch_of(g[0]["start_not_before"]),
                e["uncertainty_tolerance_s"].get<double>())
        << r.describe();
    EXPECT_EQ(int_of(g[0], "grade"), e["grade"].get<int>()) << "sparse fixes, no berth\n" << r.describe();
    ASSERT_TRUE(g[0].contains("speed_before_kn") && g[0]["speed_before_kn"].is_number()) << r.describe();
    EXPECT_GE(g[0]["speed_before_kn"].get<double>(), e["speed_before_kn"][0].get<double>()) << r.describe();
    EXPECT_LE(g[0]["speed_before_kn"].get<double>(), e["speed_before_kn"][1].get<double>()) << r.describe();
}

TEST(CliRealWorld, AgroundFirstSeenAfterAGapLongerThanMaxGapIsAGroundingInsideTheGap) {
    const CaseRun r = run("aground_sparse_gap.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    EXPECT_TRUE(r.of_kind("in_contact_at_start").empty()) << r.describe();
    const auto g = r.of_kind("grounding");
    ASSERT_EQ(g.size(), e["groundings"].get<std::size_t>()) << r.describe();
    EXPECT_EQ(r.features().size(), e["events"].get<std::size_t>()) << r.describe();
    ASSERT_TRUE(g[0]["start"].is_string()) << r.describe();
    EXPECT_NEAR(epoch_of(g[0]["start"]), epoch_of(e["start"]), e["start_tolerance_s"].get<double>()) << "the first fix in contact\n"
                                                                                                       << r.describe();
    ASSERT_TRUE(g[0].contains("start_not_before") && g[0]["start_not_before"].is_string()) << r.describe();
    EXPECT_NEAR(epoch_of(g[0]["start_not_before"]), epoch_of(e["start_not_before"]), e["start_not_before_tolerance_s"].get<double>())
        << "the last clear fix\n" << r.describe();
    ASSERT_TRUE(g[0].contains("start_uncertainty_s") && g[0]["start_uncertainty_s"].is_number()) << r.describe();
    EXPECT_NEAR(g[0]["start_uncertainty_s"].get<double>(), e["start_uncertainty_s"].get<double>(), e["uncertainty_tolerance_s"].get<double>())
        << r.describe();
    ASSERT_TRUE(g[0].contains("speed_before_kn") && g[0]["speed_before_kn"].is_number()) << r.describe();
    EXPECT_GE(g[0]["speed_before_kn"].get<double>(), e["speed_before_kn"][0].get<double>()) << r.describe();
    EXPECT_LE(g[0]["speed_before_kn"].get<double>(), e["speed_before_kn"][1].get<double>()) << r.describe();
}

TEST(CliRealWorld, FerryCallingHourlyAtAPierTheChartDrawsAsLandIsAlongsideAtEveryCall) {
    const CaseRun r = run("ferry_hourly.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    EXPECT_TRUE(r.of_kind("grounding").empty()) << r.describe();
    const auto c = r.contacts();
    EXPECT_EQ(c.size(), e["contact_events"].get<std::size_t>()) << "one event per call\n" << r.describe();
    const auto kinds = e["kinds"].get<std::vector<std::string>>();
    for (const auto& p : c) EXPECT_NE(std::find(kinds.begin(), kinds.end(), str_of(p, "kind")), kinds.end()) << r.describe();
    for (const auto& call : e["calls"]) {
        std::size_t n = 0;
        for (const auto& p : c)
            if (p["start"].is_string() && epoch_of(p["start"]) >= epoch_of(call[0]) && epoch_of(p["start"]) <= epoch_of(call[1])) ++n;
        EXPECT_EQ(n, 1u) << "the call " << call.dump() << "\n" << r.describe();
    }
}

TEST(CliRealWorld, TransitStraightThroughChartedLandIsTheChartsErrorButASimulatedGrounding) {
    const CaseRun r = run("canal_transit.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    EXPECT_EQ(world_of(r), "\"real\"");
    EXPECT_TRUE(r.of_kind("grounding").empty()) << r.describe();
    const auto c = r.contacts();
    ASSERT_EQ(c.size(), e["contact_events"].get<std::size_t>()) << r.describe();
    EXPECT_EQ(str_of(c[0], "kind"), e["kind"].get<std::string>()) << r.describe();
    EXPECT_EQ(str_of(c[0], "disagreement"), e["disagreement"].get<std::string>()) << r.describe();
    ASSERT_TRUE(c[0]["start"].is_string()) << r.describe();
    EXPECT_NEAR(epoch_of(c[0]["start"]), epoch_of(e["start"]), e["start_tolerance_s"].get<double>()) << r.describe();

    const CaseRun s = run("canal_transit.csv", "simulated");
    const auto& es = e["simulated"];
    EXPECT_EQ(s.outcome.status, es["exit_status"].get<int>()) << s.describe();
    ASSERT_TRUE(s.report.is_object()) << s.describe();
    EXPECT_EQ(world_of(s), "\"simulated\"");
    EXPECT_EQ(s.of_kind("grounding").size(), es["groundings"].get<std::size_t>()) << s.describe();
    EXPECT_EQ(s.contacts().size(), es["contact_events"].get<std::size_t>()) << s.describe();
}

TEST(CliRealWorld, BowClippingACornerWithAnAbruptSlowdownIsATouchAndGoGroundingOfGradeTwo) {
    const CaseRun r = run("touch_and_go.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    const auto g = r.of_kind("grounding");
    ASSERT_EQ(g.size(), e["groundings"].get<std::size_t>()) << r.describe();
    EXPECT_EQ(r.contacts().size(), e["contact_events"].get<std::size_t>()) << r.describe();
    EXPECT_EQ(int_of(g[0], "grade"), e["grade"].get<int>()) << r.describe();
    EXPECT_NE(str_of(g[0], "reason").find(e["reason_contains"].get<std::string>()), std::string::npos) << r.describe();
    expect_start_within(g[0], e["start_earliest"], e["start_latest"], r.describe());
    // The clip reaches no fix: its penetration is the deepest swept pose's (the poses a step
    // apart: within half a metre of the written track's, derived with OGR).
    EXPECT_NEAR(g[0]["penetration_m"].get<double>(), r.geometry["written_track_penetration_m"].get<double>(), 0.5) << r.describe();
}

TEST(CliRealWorld, PilotBoatSlowingToRestAgainstTheShoreIsAlongsideAndOneEvent) {
    const CaseRun r = run("pilot_berthing.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    EXPECT_TRUE(r.of_kind("grounding").empty()) << r.describe();
    const auto c = r.contacts();
    EXPECT_EQ(c.size(), e["contact_events"].get<std::size_t>()) << "lying 1 h in one place is one event\n" << r.describe();
    const auto kinds = e["kinds"].get<std::vector<std::string>>();
    for (const auto& p : c) EXPECT_NE(std::find(kinds.begin(), kinds.end(), str_of(p, "kind")), kinds.end()) << r.describe();
}

TEST(CliRealWorld, StraightLineBetweenSparseFixesCuttingAnIsletIsBetweenFixesButASimulatedGrounding) {
    const CaseRun r = run("skerry_sparse.csv");
    const auto& e = r.expect;
    EXPECT_EQ(r.outcome.status, e["exit_status"].get<int>()) << r.describe();
    ASSERT_TRUE(r.report.is_object()) << r.describe();
    EXPECT_TRUE(r.of_kind("grounding").empty()) << r.describe();
    const auto c = r.contacts();
    ASSERT_EQ(c.size(), e["contact_events"].get<std::size_t>()) << r.describe();
    EXPECT_EQ(str_of(c[0], "kind"), e["kind"].get<std::string>()) << r.describe();
    EXPECT_EQ(str_of(c[0], "disagreement"), e["disagreement"].get<std::string>()) << r.describe();
    expect_start_within(c[0], e["start_earliest"], e["start_latest"], r.describe());
    // No fix lies in the contact: the deepest swept pose gives its penetration (OGR on the
    // straight line between the written fixes: 26.96 m).
    EXPECT_NEAR(c[0]["penetration_m"].get<double>(), r.geometry["straight_line_penetration_m"].get<double>(), 0.5) << r.describe();

    const CaseRun s = run("skerry_sparse.csv", "simulated");
    const auto& es = e["simulated"];
    EXPECT_EQ(s.outcome.status, es["exit_status"].get<int>()) << s.describe();
    ASSERT_TRUE(s.report.is_object()) << s.describe();
    EXPECT_EQ(s.of_kind("grounding").size(), es["groundings"].get<std::size_t>()) << s.describe();
    EXPECT_EQ(s.contacts().size(), es["contact_events"].get<std::size_t>()) << s.describe();
}

}  // namespace
