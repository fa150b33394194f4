// `shoal import`, `check` and `probe` on the Tacoma S-57 cut (tests/data/coast/
// US5WA22M_tacoma_cut.000) with the two harbour tracks made by
// tests/data/tracks/make_tacoma_tracks.py, whose docstring gives the moments derived from the
// chart with OGR/GEOS, independently of shoal. A ship lying alongside the wharf touches the
// wharf; a ship running into Pier 23 hits "pier 'Pier 23'" when the script says it does. The
// kinds of these contacts (grounding, alongside, ...) are the contact rules' business, not
// asserted here.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include <shoal/track/time.hpp>
#include "run_shoal.hpp"
#include "test_support.hpp"

namespace shoal {
namespace {

using ::testing::HasSubstr;
using json = nlohmann::json;

std::string data(const std::string& rel) { return "'" + test::data_path(rel) + "'"; }

test::Outcome shoal(const test::TempDir& dir, const std::string& args) {
    return test::run_shoal(args, dir.file("cache"), dir.file("stderr.txt"));
}

json read_json(const std::string& path) {
    const std::vector<char> bytes = test::read_bytes(path);
    return json::parse(std::string(bytes.data(), bytes.size()));
}

double seconds(const json& iso) {
    const auto t = track::parse_iso8601(iso.get<std::string>());
    if (!t) throw std::runtime_error("not a time: " + iso.dump());
    return *t;
}

/// The contact events of a report (every event feature but close passes).
std::vector<json> contacts(const json& report) {
    std::vector<json> out;
    for (const json& f : report["features"])
        if (f["properties"].contains("hit") && f["properties"]["kind"] != "close_pass") out.push_back(f["properties"]);
    return out;
}

const std::string check_args = "check --coast " + data("coast/US5WA22M_tacoma_cut.000") + " --hull-from-length-width --dims 60,60,10,10 ";

TEST(HarbourCli, ImportAndInfoSayHowManyStructures) {
    test::TempDir dir;
    const std::string grid = dir.file("tacoma.shoalgrid");
    const test::Outcome imp = shoal(dir, "import " + data("coast/US5WA22M_tacoma_cut.000") + " --cell 100 -o '" + grid + "'");
    ASSERT_EQ(imp.status, 0) << imp.err;
    EXPECT_THAT(imp.out, HasSubstr("structures:     84 piers, wharves, pontoons, dolphins, hulks ... ("));
    EXPECT_THAT(imp.out, HasSubstr("lines as 2.0 m wide bands, points as 2.5 m circles"));
    EXPECT_THAT(imp.out, HasSubstr(":SLCONS, ")) << "the layers read";
    const test::Outcome info = shoal(dir, "info '" + grid + "'");
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_THAT(info.out, HasSubstr("structures:     84 "));
    EXPECT_THAT(info.out, HasSubstr("format version 4"));
}

TEST(HarbourCli, TheBerthedShipTouchesTheWharf) {
    test::TempDir dir;
    const std::string report = dir.file("berthing.geojson");
    const test::Outcome r = shoal(dir, check_args + data("tracks/tacoma_berthing.csv") + " -o '" + report + "'");
    // The real world (the default): slowing from 8 kn to lie 2 h at the wharf is berthing,
    // never a grounding, however the fenders' metre touches the charted face.
    EXPECT_EQ(r.status, 0) << r.err << r.out;
    const std::vector<json> ev = contacts(read_json(report));
    ASSERT_FALSE(ev.empty()) << "the hull lies 0.8 m off the charted face, inside its 1 m band";
    for (const json& e : ev) EXPECT_EQ(e["kind"], "alongside") << e.dump();
    for (const json& e : ev) {
        EXPECT_EQ(e["hit"], "structure") << e.dump();
        EXPECT_EQ(e["structure"], "wharf") << e.dump();
        EXPECT_EQ(e["hit_name"], "") << "the wharf has no name";
        EXPECT_THAT(e["label"].get<std::string>(), HasSubstr(" wharf ")) << e.dump();
    }
    // make_tacoma_tracks.py: the first written fix whose hull touches anything is line 42
    // (06:06:40Z), the one before it (06:06:30Z) is clear; the contact begins between them.
    const double first = seconds(ev.front()["start"]);
    EXPECT_GT(first, *track::parse_iso8601("2023-07-14T06:06:30Z"));
    EXPECT_LE(first, *track::parse_iso8601("2023-07-14T06:06:40Z"));
    // And the ship is in contact at berth until it leaves (08:09:00Z): one arrival, its touches
    // on the way in (seconds apart, coming to rest in the same stay) and its 2 h at the wharf
    // one event (three before: two touches, then the stay).
    EXPECT_EQ(ev.size(), 1u);
    EXPECT_GE(seconds(ev.back()["end"]), *track::parse_iso8601("2023-07-14T08:00:00Z"));
}

TEST(HarbourCli, TheShipRunningIntoPier23HitsItWhenTheChartSaysSo) {
    test::TempDir dir;
    const std::string report = dir.file("collision.geojson");
    const test::Outcome r = shoal(dir, check_args + data("tracks/tacoma_pier_collision.csv") + " -o '" + report + "'");
    // The real world: 9.5 kn into the pier's side, at rest within its length in seconds, lying
    // there an hour: a grounding (an allision with a structure), seen abruptly by the fixes.
    EXPECT_EQ(r.status, 1) << r.err << r.out;
    const json doc = read_json(report);
    const std::vector<json> ev = contacts(doc);
    ASSERT_EQ(ev.size(), 1u) << "it stops in contact and lies there";
    const json& e = ev[0];
    EXPECT_EQ(e["kind"], "grounding") << e.dump();
    // The chart's tolerance from its own compilation scale (DSPM CSCALE 1:15,000): 0.5 mm, 7.5 m.
    EXPECT_EQ(doc["shoal"]["world"], "real");
    EXPECT_DOUBLE_EQ(doc["shoal"]["chart_tolerance_m"].get<double>(), 7.5);
    EXPECT_GE(e["grade"].get<int>(), 3) << e.dump();
    EXPECT_THAT(e["reason"].get<std::string>(), HasSubstr("stopped abruptly")) << e.dump();
    EXPECT_EQ(e["hit"], "structure");
    EXPECT_EQ(e["structure"], "pier");
    EXPECT_EQ(e["hit_name"], "Pier 23");
    EXPECT_THAT(e["label"].get<std::string>(), HasSubstr("pier 'Pier 23'"));
    // make_tacoma_tracks.py: first contact on the written fixes at 280.485 s after the first
    // fix (14:04:40.485Z; the Length x Width rectangle 279.994 s), between lines 30 and 31.
    EXPECT_NEAR(seconds(e["start"]), *track::parse_iso8601("2023-07-14T14:04:40.485Z"), 0.05);
    EXPECT_EQ(e["fix_line"], 30);
    EXPECT_NEAR(e["speed_kn"].get<double>(), 9.5, 0.05);
    EXPECT_LT(e["stopped_after_s"].get<double>(), 60.0) << "it stops within about its own length";
    // The contact point lies on Pier 23's side (the script: 47.284332 N, 122.413629 W, the
    // middle of the overlap a moment later; the first touch is within a few metres of it).
    json xy;
    for (const json& f : doc["features"])
        if (f["properties"].contains("hit") && xy.is_null()) xy = f["geometry"]["coordinates"];
    ASSERT_TRUE(xy.is_array());
    EXPECT_NEAR(xy[1].get<double>(), 47.284332, 5e-5);
    EXPECT_NEAR(xy[0].get<double>(), -122.413629, 7e-5);
}

TEST(HarbourCli, ProbeSeesPiersAndDolphinsAtEveryDraught) {
    test::TempDir dir;
    const std::string poses = dir.file("poses.csv");
    // Pier 23's north-west end (a vertex of its outline); a dolphin (MORFAC CATMOR 1); open water
    // 250 m north-west of the pier.
    std::ofstream(poses) << "lat,lon,heading\n47.2847665,-122.4143010,56\n47.2810473,-122.4049607,0\n47.2870,-122.4150,0\n";
    for (const char* depth : {"", "--hazard-depth 0.1 ", "--hazard-depth 30 "}) {
        SCOPED_TRACE(depth);
        const test::Outcome r = shoal(dir, "probe --coast " + data("coast/US5WA22M_tacoma_cut.000") + " --dims 30,30,6,6 " + depth + "'" + poses + "'");
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_THAT(r.out, HasSubstr("47.2847665,-122.4143010,56.0,1,0.000,1\n"));
        EXPECT_THAT(r.out, HasSubstr("47.2810473,-122.4049607,0.0,1,0.000,1\n"));
        if (std::string(depth) != "--hazard-depth 30 ") {  // at 30 m every depth area of the cut is a hazard
            EXPECT_THAT(r.out, HasSubstr("47.2870000,-122.4150000,0.0,0,"));
        }
    }
}

}  // namespace
}  // namespace shoal
