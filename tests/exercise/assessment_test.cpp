// Scored criteria (assessment.hpp): the assessment file, and trainees scored on constructed
// tracks whose breaches, times and penalties are derived by hand below:
// - a ship passing 300 m from an island against a 500 m land clearance limit;
// - the same ship crossing a speed limit area (and a no-entry area) at a known speed and times;
// - its CPA to a target on the reciprocal course 300 m abeam;
// - time in close quarters of two ships sailing side by side;
// - under-keel clearance on the real S-57 test chart (US4MD81M_hazard_cut.000), the entry
//   into the 3.6 m depth area found independently by OGR on the chart's own polygons.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include <shoal/exercise/assessment.hpp>
#include <shoal/audit/audit.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/util/error.hpp>

#include "test_support.hpp"

namespace shoal::audit {
namespace {

using geo::LonLat;
using geo::XY;
using ::testing::HasSubstr;

constexpr double t0 = 1714557600;  // 2024-05-01T10:00:00Z
// The run's frame, given to the grid as its CRS: the test places everything in these metres.
const char* const crs = "+proj=tmerc +lat_0=55 +lon_0=5 +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs";

const geo::LocalFrame& frame() {
    static const geo::LocalFrame f = geo::LocalFrame::from_user_crs(crs);
    return f;
}

/// A GeoJSON polygon feature of the rectangle [x0, x1] x [y0, y1] (local metres).
std::string rect_feature(double x0, double y0, double x1, double y1) {
    std::string ring;
    for (const XY& p : {XY{x0, y0}, XY{x1, y0}, XY{x1, y1}, XY{x0, y1}, XY{x0, y0}}) {
        const LonLat q = frame().inverse(p);
        char b[96];
        std::snprintf(b, sizeof b, "%s[%.12f, %.12f]", ring.empty() ? "" : ", ", q.lon, q.lat);
        ring += b;
    }
    return R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[)" + ring + "]]}}";
}

/// The assessment area of the rectangle, as [[lon, lat], ...].
std::string rect_area(double x0, double y0, double x1, double y1) {
    std::string ring;
    for (const XY& p : {XY{x0, y0}, XY{x1, y0}, XY{x1, y1}, XY{x0, y1}}) {
        const LonLat q = frame().inverse(p);
        char b[96];
        std::snprintf(b, sizeof b, "%s[%.12f, %.12f]", ring.empty() ? "" : ", ", q.lon, q.lat);
        ring += b;
    }
    return "[" + ring + "]";
}

/// A ship at speed `v_ms` from (x_from, y) eastward (or westward when x_to < x_from), a fix
/// every 10 s; SOG as given (knots).
track::Track straight(const std::string& id, double x_from, double x_to, double y, double v_ms, double sog_kn) {
    track::Track t;
    t.id = id;
    t.file = "ex/" + id + ".csv";
    const double heading = x_to > x_from ? 90 : 270;
    const double duration = std::fabs(x_to - x_from) / v_ms;
    for (int i = 0; i * 10.0 <= duration + 1e-9; ++i) {
        track::Fix f;
        f.time_s = t0 + 10.0 * i;
        const double x = x_from + (x_to > x_from ? 1 : -1) * v_ms * 10.0 * i;
        f.position = frame().inverse({x, y});
        f.heading_deg = f.cog_deg = heading;
        f.sog_kn = sog_kn;
        f.line = static_cast<std::size_t>(i) + 2;
        t.fixes.push_back(f);
    }
    return t;
}

/// A box hull: 50 m ahead of the reference point, 10 m astern, 5 m each side.
hull::Hull box_hull() { return hull::Hull::from_contour({{50, -5}, {50, 5}, {-10, 5}, {-10, -5}}, "box"); }

class Scored : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_dir = new test::TempDir;
        // The island: x -500..500, y 0..400; two far islets make the chart's extent cover the run.
        const std::string coast = s_dir->file("coast.geojson");
        std::ofstream(coast) << R"({"type": "FeatureCollection", "features": [)" << rect_feature(-500, 0, 500, 400) << ", "
                             << rect_feature(-3100, 3000, -3000, 3100) << ", " << rect_feature(3000, -3100, 3100, -3000) << "]}";
        grid::BuildRequest req;
        req.crs = crs;
        req.cell_m = 250;
        s_grid = new grid::CoastGrid(grid::build_grid({coast}, req, nullptr));
    }
    static void TearDownTestSuite() {
        delete s_grid;
        delete s_dir;
    }
    static test::TempDir* s_dir;
    static grid::CoastGrid* s_grid;

    AuditResult run(std::vector<track::Track> tracks, const Assessment& a, const Roles* roles = nullptr, double ship_margin_m = 20) const {
        AuditOptions o;
        o.jobs = 2;
        o.encounters = true;
        o.exercise_by = ExerciseBy::folder;
        o.roles = roles;
        o.assessment = &a;
        o.encounter.ship_margin_m = ship_margin_m;
        return audit_tracks(std::move(tracks), *s_grid, box_hull(), "box", o);
    }
};
test::TempDir* Scored::s_dir = nullptr;
grid::CoastGrid* Scored::s_grid = nullptr;

const Breach& breach_of(const AuditResult& r, const std::string& criterion) {
    for (const Breach& b : r.assessment.breaches)
        if (b.criterion == criterion) return b;
    throw std::runtime_error("no breach of " + criterion);
}

TEST_F(Scored, LandClearanceSpeedLimitNoEntryAndCpaOfAConstructedPassage) {
    // A (trainee) sails east along y = -305 from x = -2000 to 2000 at 5 m/s (SOG 9.72 kn), a
    // fix every 10 s: x(t) = -2000 + 5 (t - t0). Its box hull's port side is at y = -300, 300 m
    // from the island's south edge (y = 0, x -500..500).
    // - Land clearance under 500 m: while the hull overlaps x -500..500 the clearance is 300 m;
    //   west of it, the bow (x + 50) is sqrt((-500 - x - 50)^2 + 300^2) from the corner: under
    //   500 m once -500 - x - 50 < 400, x > -950, t > t0 + 210; east of it the stern
    //   (x - 10) leaves 500 m at x - 10 - 500 = 400, x = 910, t = t0 + 582. Least 300 m.
    //   Per metre, 2: (500 - 300) x 2 = 400.
    // - Speed limit 8 kn in the area x 0..1000, y -600..-100: inside from x = 0 (t0 + 400) to
    //   x = 1000 (t0 + 600), at 9.72 kn. Per knot over, 5: 1.72 x 5 = 8.6.
    // - No entry in the same area, per second 0.5: 200 s, 100.
    // - CPA 926 m to B (target), sailing west along y = -605 from x = 2000 at 5 m/s: relative
    //   distance sqrt((4000 - 10 (t - t0))^2 + 300^2) under 926 m while |4000 - 10 (t - t0)|
    //   < sqrt(926^2 - 300^2) = 876.0571 m: t0 + 312.3943 to t0 + 487.6057, least 300 m at
    //   t0 + 400. Per breach 10.
    // Score: 400 + 8.6 + 100 + 10 = 518.6. B is a target: not scored.
    const std::string area = rect_area(0, -600, 1000, -100);
    const Assessment a = Assessment::parse(R"({"criteria": [
        {"id": "land-500", "kind": "land_clearance", "limit": 500, "penalty": 2, "per": "metre"},
        {"id": "speed-8", "kind": "speed_limit", "limit": 8, "penalty": 5, "per": "metre", "area": )" + area + R"(, "area_name": "narrows"},
        {"id": "keep-out", "kind": "no_entry", "penalty": 0.5, "per": "second", "area": )" + area + R"(},
        {"id": "cpa-926", "kind": "cpa", "limit": 926, "penalty": 10}]})",
                                           "a.json");
    const Roles roles = Roles::parse(R"({"tracks": [{"track": "A", "role": "trainee"}]})", "roles.json");
    const AuditResult r = run({straight("A", -2000, 2000, -305, 5, 9.72), straight("B", 2000, -2000, -605, 5, 9.72)}, a, &roles);
    ASSERT_TRUE(r.errors.empty());
    ASSERT_TRUE(r.has_assessment);
    ASSERT_EQ(r.assessment.breaches.size(), 4u);

    const Breach& land = breach_of(r, "land-500");
    EXPECT_EQ(land.track, "A");
    EXPECT_EQ(land.kind, CriterionKind::land_clearance);
    EXPECT_NEAR(land.start_s - t0, 210, 0.1);
    EXPECT_NEAR(land.end_s - t0, 582, 0.1);
    EXPECT_NEAR(land.value, 300, 0.05);
    EXPECT_EQ(land.limit, 500);
    EXPECT_NEAR(land.penalty, 400, 0.1);
    EXPECT_GE(land.worst_s - t0, 290 - 1);  // the hull abreast the island: x -550..510
    EXPECT_LE(land.worst_s - t0, 502 + 1);
    EXPECT_NEAR(frame().forward({land.lon, land.lat}).y, -305, 0.01);

    const Breach& speed = breach_of(r, "speed-8");
    EXPECT_NEAR(speed.start_s - t0, 400, 1e-6);
    EXPECT_NEAR(speed.end_s - t0, 600, 1e-6);
    EXPECT_NEAR(speed.value, 9.72, 1e-9);
    EXPECT_NEAR(speed.penalty, 8.6, 1e-9);
    EXPECT_THAT(speed.detail, HasSubstr("narrows"));

    const Breach& out = breach_of(r, "keep-out");
    EXPECT_NEAR(out.start_s - t0, 400, 1e-6);
    EXPECT_NEAR(out.end_s - t0, 600, 1e-6);
    EXPECT_NEAR(out.value, 200, 1e-6);
    EXPECT_NEAR(out.penalty, 100, 1e-6);
    EXPECT_NEAR(frame().forward({out.lon, out.lat}).x, 0, 0.01);  // at the entry

    const Breach& cpa = breach_of(r, "cpa-926");
    EXPECT_EQ(cpa.other, "B");
    EXPECT_NEAR(cpa.start_s - t0, 400 - 87.60571, 1e-3);
    EXPECT_NEAR(cpa.end_s - t0, 400 + 87.60571, 1e-3);
    EXPECT_NEAR(cpa.worst_s - t0, 400, 1e-6);
    EXPECT_NEAR(cpa.value, 300, 1e-6);
    EXPECT_EQ(cpa.penalty, 10);

    // In time order: land (210), cpa (312.4), then speed and no entry (400, in file order).
    std::vector<std::string> order;
    for (const Breach& b : r.assessment.breaches) order.push_back(b.criterion);
    EXPECT_EQ(order, (std::vector<std::string>{"land-500", "cpa-926", "speed-8", "keep-out"}));
    ASSERT_EQ(r.assessment.scores.size(), 1u);  // B is a target
    EXPECT_EQ(r.assessment.scores[0].track, "A");
    EXPECT_EQ(r.assessment.scores[0].exercise, "ex");
    EXPECT_EQ(r.assessment.scores[0].breaches, 4u);
    EXPECT_NEAR(r.assessment.scores[0].penalty, 518.6, 0.1);

    // Without the roles both are trainees: B is scored too, with the same CPA breach (other A).
    const AuditResult both = run({straight("A", -2000, 2000, -305, 5, 9.72), straight("B", 2000, -2000, -605, 5, 9.72)}, a);
    ASSERT_EQ(both.assessment.scores.size(), 2u);
    EXPECT_EQ(both.assessment.scores[1].track, "B");
    EXPECT_EQ(both.assessment.scores[1].breaches, 1u);  // B's reference point never enters the area (y -605)
    EXPECT_EQ(both.assessment.breaches.back().other, "A");
    EXPECT_NEAR(both.assessment.breaches.back().value, 300, 1e-6);
}

TEST_F(Scored, LandClearanceIsNotBreachedAlongsideOnlyOnceOffTheBerth) {
    // A lies at the island's south edge (y = 0, x -500..500) heading east, reference point at
    // y = -4: her port side (y + 5) is 1 m into the land, still for 50 s (SOG 0), then she
    // moves off south at 1 m/s: y(t) = -4 - (t - t0 - 50). In contact until the side leaves
    // the edge, y < -5, t0 + 51: a contact from the first fix, not a grounding, so no breach
    // there. Under 500 m of clearance from then until the side is 500 m off, y = -505,
    // t0 + 551: one breach, from the end of the contact to t0 + 551.
    track::Track t;
    t.id = "A";
    t.file = "ex/A.csv";
    for (int i = 0; i <= 60; ++i) {
        track::Fix f;
        f.time_s = t0 + 10.0 * i;
        const double y = i <= 5 ? -4.0 : -4.0 - (10.0 * i - 50);
        f.position = frame().inverse({0, y});
        f.heading_deg = 90;
        f.sog_kn = i <= 5 ? 0 : 1.944;
        f.line = static_cast<std::size_t>(i) + 2;
        t.fixes.push_back(f);
    }
    const Assessment a = Assessment::parse(R"({"criteria": [{"id": "land-500", "kind": "land_clearance", "limit": 500, "penalty": 1}]})", "a.json");
    const AuditResult r = run({t}, a);
    ASSERT_TRUE(r.errors.empty());
    ASSERT_EQ(r.tracks.size(), 1u);
    ASSERT_EQ(r.tracks[0].events.size(), 1u);
    const Event& contact = r.tracks[0].events[0];
    ASSERT_NE(contact.kind, EventKind::grounding);
    EXPECT_NEAR(contact.end_s, t0 + 51, 0.5);
    ASSERT_EQ(r.assessment.breaches.size(), 1u) << "one breach, off the berth";
    const Breach& b = r.assessment.breaches[0];
    EXPECT_GE(b.start_s, contact.end_s - 0.5) << "no breach while alongside";
    // It starts at the first clearance sample after the contact (not interpolated across it):
    // samples are at most --step (5 m) of hull motion apart, 5 s at 1 m/s.
    EXPECT_LE(b.start_s, contact.end_s + 5.0 + 0.5);
    EXPECT_NEAR(b.end_s, t0 + 551, 1.0);
    EXPECT_DOUBLE_EQ(b.penalty, 1);
}

TEST_F(Scored, TimeInCloseQuartersOverTheTimeAllowed) {
    // Two trainees side by side 40 m apart (reference points), same course and speed for
    // 800 s: hulls 30 m apart, under a ship margin of 50 m the whole time, one close-quarters
    // encounter of 800 s. Allowed 600 s, per second over 1: 200 each.
    const Assessment a = Assessment::parse(R"({"criteria": [{"kind": "close_quarters_time", "limit": 600, "penalty": 1, "per": "second"}]})", "a.json");
    const AuditResult r = run({straight("A", -2000, 2000, -1305, 5, 9.72), straight("C", -2000, 2000, -1345, 5, 9.72)}, a, nullptr, 50);
    ASSERT_EQ(r.close_quarters, 1u);
    ASSERT_EQ(r.assessment.breaches.size(), 2u);
    for (const Breach& b : r.assessment.breaches) {
        EXPECT_EQ(b.criterion, "close_quarters_time-1");
        EXPECT_NEAR(b.value, 800, 0.05);
        EXPECT_NEAR(b.penalty, 200, 0.05);
        EXPECT_NEAR(b.start_s - t0, 0, 0.05);
    }
    EXPECT_EQ(r.assessment.breaches[0].other, "C");
    EXPECT_EQ(r.assessment.breaches[1].other, "A");
    // 800 s allowed: no breach, scores 0.
    const Assessment lenient = Assessment::parse(R"({"criteria": [{"kind": "close_quarters_time", "limit": 800, "penalty": 1}]})", "a.json");
    const AuditResult ok = run({straight("A", -2000, 2000, -1305, 5, 9.72), straight("C", -2000, 2000, -1345, 5, 9.72)}, lenient, nullptr, 50);
    EXPECT_TRUE(ok.assessment.breaches.empty());
    ASSERT_EQ(ok.assessment.scores.size(), 2u);
    EXPECT_EQ(ok.assessment.scores[0].penalty, 0);
}

/// A ship from (x, y) on `heading` at `v_ms` for `duration` s, a fix every 10 s, turning `turn`
/// degrees (to starboard when positive) at `turn_at` s; heading, COG and SOG as a simulator logs them.
track::Track leg(const std::string& id, XY from, double heading, double v_ms, double duration, double turn_at = INFINITY, double turn = 0) {
    track::Track t;
    t.id = id;
    t.file = "ex/" + id + ".csv";
    XY p = from;
    for (int i = 0; i * 10.0 <= duration + 1e-9; ++i) {
        const double h = std::fmod((i * 10.0 >= turn_at ? heading + turn : heading) + 360, 360);
        track::Fix f;
        f.time_s = t0 + 10.0 * i;
        f.position = frame().inverse(p);
        f.heading_deg = f.cog_deg = h;
        f.sog_kn = v_ms * 3600 / 1852;
        f.line = static_cast<std::size_t>(i) + 2;
        t.fixes.push_back(f);
        const double a = h * std::numbers::pi / 180;
        p = p + (10 * v_ms) * XY{std::sin(a), std::cos(a)};
    }
    return t;
}

TEST_F(Scored, ColregCrossingGiveWayHeldOnAndTheStandOnShipThatKeptOn) {
    // A heads north from (1000, -3000), C west from (3000, -1000), both at 5 m/s: they would meet
    // at (1000, -1000) at 400 s; C is on A's starboard bow (45 degrees), so A gives way (rule 15)
    // and C stands on. With range 2000 m the situation starts at 400 - 2000 / 7.07 = 117 s; CPA 0.
    const Assessment a = Assessment::parse(R"({"pass_mark": 40, "criteria": [
        {"id": "cpa", "kind": "cpa", "limit": 100, "penalty": 10},
        {"id": "rules", "kind": "colreg", "penalty": 50, "range_m": 2000, "early_range_m": 1000, "cpa_m": 400}]})", "rules.json");
    EXPECT_EQ(a.source, "rules.json");
    EXPECT_EQ(a.pass_mark, 40);
    const AuditResult r = run({leg("A", {1000, -3000}, 0, 5, 800), leg("C", {3000, -1000}, 270, 5, 800)}, a);
    // Both held on: A breaches rule 15 (and its CPA); C, the stand-on ship, kept her course and speed: nothing.
    std::vector<const Breach*> rules;
    for (const Breach& b : r.assessment.breaches)
        if (b.kind == CriterionKind::colreg) rules.push_back(&b);
    ASSERT_EQ(rules.size(), 1u);
    EXPECT_EQ(rules[0]->track, "A");
    EXPECT_EQ(rules[0]->rule, "15");
    EXPECT_EQ(rules[0]->other, "C");
    EXPECT_EQ(rules[0]->penalty, 50);
    EXPECT_NEAR(rules[0]->start_s - t0, 400 - 2000 / std::sqrt(50.0), 1);
    EXPECT_NEAR(rules[0]->worst_s - t0, 400, 1);  // held on: the moment is the closest approach
    EXPECT_NEAR(rules[0]->value, 0, 1);
    EXPECT_THAT(rules[0]->asked, HasSubstr("rule 15"));
    EXPECT_THAT(rules[0]->did, HasSubstr("A kept her course (000) and speed (9.7 kn)"));
    EXPECT_THAT(rules[0]->detail, HasSubstr("rules: rule 15, crossing with C (give-way)"));
    ASSERT_EQ(r.assessment.scores.size(), 2u);
    EXPECT_EQ(r.assessment.scores[0].track, "A");
    EXPECT_NEAR(r.assessment.scores[0].penalty, 60, 1e-9);
    ASSERT_EQ(r.assessment.scores[0].by_criterion.size(), 2u);
    EXPECT_NEAR(r.assessment.scores[0].by_criterion[0], 10, 1e-9);
    EXPECT_NEAR(r.assessment.scores[0].by_criterion[1], 50, 1e-9);
    EXPECT_FALSE(r.assessment.scores[0].passed);
    EXPECT_NEAR(r.assessment.scores[1].penalty, 10, 1e-9);  // C: only the CPA
    EXPECT_TRUE(r.assessment.scores[1].passed);
    EXPECT_EQ(r.assessment.pass_mark, 40);
    EXPECT_EQ(r.assessment.source, "rules.json");
    // A turns 40 degrees to starboard at 150 s (1768 m off): closest (1250, 1250) + 183 s x
    // (-8.21, -3.83) = 604 m, over 400: no colreg breach for either, no CPA breach.
    const AuditResult ok = run({leg("A", {1000, -3000}, 0, 5, 800, 150, 40), leg("C", {3000, -1000}, 270, 5, 800)}, a);
    EXPECT_TRUE(ok.assessment.breaches.empty()) << ok.assessment.breaches[0].detail;
    EXPECT_TRUE(ok.assessment.scores[0].passed);
    // Every situation is listed with the rules that applied, met or not: A's and C's crossing,
    // in the trainees' order (A then C), each naming the other ship.
    for (const AuditResult* res : {&r, &ok}) {
        const auto& c = res->assessment.conduct;
        ASSERT_EQ(c.size(), 2u);
        EXPECT_EQ(c[0].track, "A");
        EXPECT_EQ(c[0].other, "C");
        EXPECT_EQ(c[0].other_index, 1u);
        EXPECT_EQ(c[0].criterion, "rules");
        EXPECT_EQ(c[0].situation, "crossing");
        EXPECT_EQ(c[0].role, "give-way");
        EXPECT_EQ(c[0].rules, (std::vector<std::string>{"15", "16", "8"}));
        EXPECT_NEAR(c[0].start_s - t0, 400 - 2000 / std::sqrt(50.0), 1);
        EXPECT_EQ(c[1].track, "C");
        EXPECT_EQ(c[1].other, "A");
        EXPECT_EQ(c[1].role, "stand-on");
        EXPECT_EQ(c[1].rules, (std::vector<std::string>{"15", "17"}));
        EXPECT_TRUE(c[1].breached.empty()) << "C kept her course and speed";
        EXPECT_THAT(c[1].did, HasSubstr("C kept her course (270) and speed"));
    }
    EXPECT_EQ(r.assessment.conduct[0].breached, (std::vector<std::string>{"15"}));
    EXPECT_THAT(r.assessment.conduct[0].did, HasSubstr("A kept her course (000)"));
    EXPECT_TRUE(ok.assessment.conduct[0].breached.empty()) << "A's early, large turn met rules 15, 16 and 8";
    EXPECT_THAT(ok.assessment.conduct[0].did, HasSubstr("A altered course 40 degrees to starboard from "));
}

TEST_F(Scored, APenaltyThatSumsToThePassMarkPassesWhateverTheRoundingOfItsSum) {
    // Our hostile round on issue 42's pass mark: A (held on, crossing) is charged 0.1 for her CPA
    // and 0.2 for rule 15; 0.1 + 0.2 is 0.30000000000000004 in doubles, and against a pass mark
    // of 0.3 ("the largest penalty that passes") she failed. A penalty over the mark by more
    // than the sum's rounding still fails.
    const auto crossing = [&](const char* mark) {
        const Assessment a = Assessment::parse(std::string(R"({"pass_mark": )") + mark + R"(, "criteria": [
            {"id": "cpa", "kind": "cpa", "limit": 100, "penalty": 0.1},
            {"id": "rules", "kind": "colreg", "penalty": 0.2, "range_m": 2000, "early_range_m": 1000, "cpa_m": 400}]})", "rules.json");
        return run({leg("A", {1000, -3000}, 0, 5, 800), leg("C", {3000, -1000}, 270, 5, 800)}, a);
    };
    const AuditResult r = crossing("0.3");
    ASSERT_EQ(r.assessment.scores.size(), 2u);
    EXPECT_EQ(r.assessment.scores[0].track, "A");
    EXPECT_EQ(r.assessment.scores[0].breaches, 2u);
    EXPECT_NE(r.assessment.scores[0].penalty, 0.3);  // the sum's rounding, which the pass mark must forgive
    EXPECT_NEAR(r.assessment.scores[0].penalty, 0.3, 1e-15);
    EXPECT_TRUE(r.assessment.scores[0].passed);
    EXPECT_TRUE(crossing("0.30000000000000004").assessment.scores[0].passed);
    EXPECT_FALSE(crossing("0.29999999").assessment.scores[0].passed);
    EXPECT_FALSE(crossing("0.2").assessment.scores[0].passed);
}

TEST_F(Scored, NeedsExerciseModeAndAVesselWithoutDraughtIsNotAssessedForUnderKeelClearance) {
    const Assessment a = Assessment::parse(R"({"criteria": [{"kind": "under_keel_clearance", "limit": 1, "penalty": 1}]})", "a.json");
    AuditOptions o;
    o.assessment = &a;
    EXPECT_THROW(audit_tracks({straight("A", -2000, 2000, -1305, 5, 9.72)}, *s_grid, box_hull(), "box", o), UsageError);
    const AuditResult r = run({straight("A", -2000, 2000, -1305, 5, 9.72)}, a);
    EXPECT_TRUE(r.assessment.breaches.empty());
    ASSERT_EQ(r.assessment.warnings.size(), 2u);
    EXPECT_THAT(r.assessment.warnings[0], HasSubstr("the grid holds no depth areas or dangers, so under_keel_clearance-1"));
    EXPECT_THAT(r.assessment.warnings[1], HasSubstr("track 'A' has no draught"));
    EXPECT_THAT(r.warnings, ::testing::Contains(r.assessment.warnings[1])) << "the run's warnings say it too";
}

/// The fraction along the straight line from `a` to `b` (lon/lat) where it enters a polygon of
/// `layer` with DRVAL1 under `depth`, found with OGR alone (bisection between a point outside
/// and one inside); NaN when `b` is not inside any.
double entry_fraction(const std::string& chart, LonLat a, LonLat b, double depth) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(chart.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    std::vector<std::unique_ptr<OGRGeometry>> shallow;
    for (const char* layer : {"DEPARE", "DRGARE"}) {
        OGRLayer* l = ds->GetLayerByName(layer);
        if (!l) continue;
        for (auto& f : *l) {
            const OGRGeometry* g = f->GetGeometryRef();
            const int i = f->GetFieldIndex("DRVAL1");
            if (g && i >= 0 && f->IsFieldSetAndNotNull(i) && f->GetFieldAsDouble(i) < depth &&
                wkbFlatten(g->getGeometryType()) == wkbPolygon)
                shallow.emplace_back(g->clone());
        }
    }
    const auto inside = [&](double f) {
        OGRPoint p(a.lon + f * (b.lon - a.lon), a.lat + f * (b.lat - a.lat));
        for (const auto& g : shallow)
            if (g->Contains(&p)) return true;
        return false;
    };
    if (inside(0) || !inside(1)) return NAN;
    double lo = 0, hi = 1;
    for (int k = 0; k < 60; ++k) (inside(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    return hi;
}

TEST(UnderKeelClearance, OnARealChartFromADeepAreaIntoTheShallowOne) {
    // The S-57 cut off Annapolis: from inside the DEPARE 5.4-9.1 m into the DEPARE 3.6-5.4 m
    // (hazard_test.cpp's places), in 600 s. Draught 3.0 m, limit 1.0 m: water under 4.0 m
    // breaches, i.e. the 3.6 m area: from its entry (found by OGR) to the end, UKC 0.6 m. Per
    // metre, 10: (1.0 - 0.6) x 10 = 4.
    const std::string chart = test::data_path("coast/US4MD81M_hazard_cut.000");
    const LonLat from{-76.44027, 38.92116}, to{-76.45138, 38.92249};
    grid::BuildRequest req;
    req.cell_m = 300;
    const grid::CoastGrid g = grid::build_grid({chart}, req, nullptr);
    track::Track t;
    t.id = "own";
    t.file = "own.csv";
    for (int i = 0; i <= 60; ++i) {
        track::Fix f;
        f.time_s = t0 + 10.0 * i;
        const XY a = g.frame().forward(from), b = g.frame().forward(to);
        f.position = g.frame().inverse({a.x + (b.x - a.x) * i / 60.0, a.y + (b.y - a.y) * i / 60.0});
        f.line = static_cast<std::size_t>(i) + 2;
        t.fixes.push_back(f);
    }
    const hull::Hull ship = hull::Hull::parse(R"({"name": "test ship", "a": 45, "b": 15, "c": 5, "d": 5, "draught": 3.0})", "test ship");
    const Assessment a = Assessment::parse(R"({"criteria": [{"id": "ukc-1m", "kind": "under_keel_clearance", "limit": 1.0, "penalty": 10, "per": "metre"}]})", "a.json");
    AuditOptions o;
    o.encounters = true;
    o.assessment = &a;
    const AuditResult r = audit_tracks({t}, g, ship, "test ship", o);
    ASSERT_EQ(r.assessment.breaches.size(), 1u) << (r.assessment.warnings.empty() ? "" : r.assessment.warnings[0]);
    const Breach& b = r.assessment.breaches[0];
    const double f = entry_fraction(chart, from, to, 4.0);
    ASSERT_TRUE(std::isfinite(f));
    EXPECT_NEAR(b.start_s - t0, f * 600, 0.05);
    EXPECT_NEAR(b.end_s - t0, 600, 1e-6);
    EXPECT_NEAR(b.value, 0.6, 1e-9);
    EXPECT_NEAR(b.penalty, 4.0, 1e-9);
    // A draught of 2.5 m: 3.6 - 2.5 = 1.1 m, not under 1.0: no breach.
    const hull::Hull light = hull::Hull::parse(R"({"name": "light", "a": 45, "b": 15, "c": 5, "d": 5, "draught": 2.5})", "light");
    EXPECT_TRUE(audit_tracks({t}, g, light, "light", o).assessment.breaches.empty());
}

std::string message_of(const std::string& text) {
    try {
        Assessment::parse(text, "bad.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(AssessmentFile, ReadsEveryKindAndItsDefaults) {
    const Assessment a = Assessment::parse(R"({"$schema": "x", "description": "d", "criteria": [
        {"kind": "land_clearance", "limit": 926, "penalty": 1},
        {"id": "ukc", "kind": "under_keel_clearance", "limit": 2, "penalty": 3, "per": "metre"},
        {"kind": "cpa", "limit": 1852, "penalty": 5, "per": "second"},
        {"kind": "speed_limit", "limit": 6, "penalty": 1, "area": [[0, 0], [1, 0], [1, 1]], "area_name": "harbour"},
        {"kind": "no_entry", "penalty": 2, "area": [[0, 0], [1, 0], [1, 1], [0, 0]]},
        {"kind": "close_quarters_time", "limit": 0, "penalty": 1}]})",
                                           "a.json");
    ASSERT_EQ(a.criteria.size(), 6u);
    EXPECT_EQ(a.criteria[0].id, "land_clearance-1");
    EXPECT_EQ(a.criteria[0].per, PenaltyPer::breach);
    EXPECT_EQ(a.criteria[1].id, "ukc");
    EXPECT_EQ(a.criteria[1].per, PenaltyPer::metre);
    EXPECT_EQ(a.criteria[2].per, PenaltyPer::second);
    EXPECT_EQ(a.criteria[3].area.size(), 4u);  // closed
    EXPECT_EQ(a.criteria[3].area_name, "harbour");
    EXPECT_EQ(a.criteria[4].area.size(), 4u);
    EXPECT_EQ(a.criteria[4].limit, 0);
    EXPECT_EQ(a.criteria[5].id, "close_quarters_time-6");
    EXPECT_EQ(a.watch_clearance_m(), 926);
}

TEST(AssessmentFile, BadFilesNameTheFileTheCriterionAndWhatIsWrong) {
    EXPECT_THAT(message_of("{"), HasSubstr("assessment file 'bad.json': not JSON"));
    EXPECT_THAT(message_of("[]"), HasSubstr("not a JSON object"));
    EXPECT_THAT(message_of(R"({"criteria": [], "rules": 1})"), HasSubstr("unknown member 'rules'"));
    EXPECT_THAT(message_of(R"({"criteria": []})"), HasSubstr("\"criteria\" is empty"));
    EXPECT_THAT(message_of(R"({})"), HasSubstr("no \"criteria\" array"));
    EXPECT_THAT(message_of(R"({"criteria": [3]})"), HasSubstr("criteria[0]: not an object"));
    EXPECT_THAT(message_of(R"({"criteria": [{"id": "x", "kind": "depth", "limit": 1, "penalty": 1}]})"),
                HasSubstr("criteria[0] (id 'x'): \"kind\" must be one of"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "penalty": 1}]})"), HasSubstr("criteria[0] (id 'cpa-1'): \"limit\" must be a number (m)"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 1, "penalty": 1}, {"kind": "cpa", "limit": -1, "penalty": 1}]})"),
                HasSubstr("criteria[1] (id 'cpa-2'): \"limit\" must be >= 0 (got -1)"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 1, "penalty": -2}]})"), HasSubstr("\"penalty\" must be >= 0"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 1, "penalty": 1, "per": "hour"}]})"),
                HasSubstr("\"per\" must be \"breach\", \"second\" or \"metre\""));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 1, "penalty": 1, "colour": "red"}]})"),
                HasSubstr("criteria[0]: unknown member 'colour'"));
    EXPECT_THAT(message_of(R"({"criteria": [{"id": "a", "kind": "cpa", "limit": 1, "penalty": 1}, {"id": "a", "kind": "cpa", "limit": 2, "penalty": 1}]})"),
                HasSubstr("criteria[1] (id 'a'): id 'a' is given twice"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "speed_limit", "limit": 5, "penalty": 1}]})"), HasSubstr("needs an \"area\""));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 5, "penalty": 1, "area": [[0, 0], [1, 0], [1, 1]]}]})"),
                HasSubstr("a cpa criterion has no \"area\""));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "no_entry", "penalty": 1, "area": [[0, 0], [1, 0]]}]})"), HasSubstr("at least 3"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "no_entry", "penalty": 1, "area": [[0, 0], [1, 0], [0, 1], [1, 1]]}]})"),
                HasSubstr("\"area\" is not a valid polygon (Self-intersection"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "no_entry", "penalty": 1, "area": [[0, 0], [200, 0], [1, 1]]}]})"),
                HasSubstr("area[1] [200, 0] is outside"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "no_entry", "penalty": 1, "per": "metre", "area": [[0, 0], [1, 0], [1, 1]]}]})"),
                HasSubstr("means nothing for no_entry"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "no_entry", "limit": 5, "penalty": 1, "area": [[0, 0], [1, 0], [1, 1]]}]})"),
                HasSubstr("a no_entry criterion has no \"limit\""));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "land_clearance", "limit": 0, "penalty": 1}]})"), HasSubstr("can never be breached"));
    // A number too large for a double is nlohmann's out_of_range, not a parse_error: still bad input.
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 1e999, "penalty": 1}]})"), HasSubstr("'bad.json': not JSON: "));
    // Bounds: a penalty that would make a score infinite, a limit beyond what is searched, an
    // area wider than the local frame holds, a default id another criterion gives.
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 926, "penalty": 1e308}]})"),
                HasSubstr("\"penalty\" must be at most 1e+06 (got 1e+308)"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "land_clearance", "limit": 20000, "penalty": 1}]})"),
                HasSubstr("\"limit\" must be at most 10000 m (got 20000)"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "no_entry", "penalty": 1, "area": [[-90, 0], [140, 0], [140, 89], [-90, 89]]}]})"),
                HasSubstr("\"area\" spans 230 degrees: at most 5"));
    EXPECT_THAT(message_of(R"({"criteria": [{"id": "cpa-2", "kind": "cpa", "limit": 1, "penalty": 1}, {"kind": "cpa", "limit": 2, "penalty": 1}]})"),
                HasSubstr("criteria[1] (id 'cpa-2'): its default id 'cpa-2' (kind-position) is the id another criterion gives"));
}

TEST(AssessmentFile, ColregParametersTheirDefaultsAndThePassMark) {
    const Assessment a = Assessment::parse(R"({"criteria": [{"kind": "colreg", "penalty": 20},
        {"id": "strict", "kind": "colreg", "penalty": 5, "head_on_deg": 6, "cpa_m": 1852, "early_range_m": 3000, "range_m": 5556,
         "min_course_deg": 25, "min_speed_change": 0.4, "action_course_deg": 8, "action_speed_change": 0.1, "sustain_s": 60}]})",
                                           "a.json");
    ASSERT_EQ(a.criteria.size(), 2u);
    EXPECT_EQ(a.criteria[0].id, "colreg-1");
    EXPECT_EQ(a.criteria[0].per, PenaltyPer::breach);
    EXPECT_EQ(a.criteria[0].colreg.head_on_deg, 5);
    EXPECT_EQ(a.criteria[0].colreg.cpa_m, 926);
    EXPECT_EQ(a.criteria[0].colreg.early_range_m, 1852);
    EXPECT_EQ(a.criteria[0].colreg.min_course_deg, 30);
    EXPECT_EQ(a.criteria[0].colreg.min_speed_change, 0.5);
    EXPECT_TRUE(std::isnan(a.pass_mark));
    const ConductOptions& o = a.criteria[1].colreg;
    EXPECT_EQ(o.head_on_deg, 6);
    EXPECT_EQ(o.cpa_m, 1852);
    EXPECT_EQ(o.early_range_m, 3000);
    EXPECT_EQ(o.range_m, 5556);
    EXPECT_EQ(o.min_course_deg, 25);
    EXPECT_EQ(o.min_speed_change, 0.4);
    EXPECT_EQ(o.action_course_deg, 8);
    EXPECT_EQ(o.action_speed_change, 0.1);
    EXPECT_EQ(o.sustain_s, 60);
    EXPECT_EQ(Assessment::parse(R"({"pass_mark": 0, "criteria": [{"kind": "colreg", "penalty": 1}]})", "a.json").pass_mark, 0);
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "colreg", "limit": 1, "penalty": 1}]})"), HasSubstr("a colreg criterion has no \"limit\""));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "colreg", "penalty": 1, "per": "second"}]})"), HasSubstr("charged per breach"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "cpa", "limit": 1, "penalty": 1, "cpa_m": 5}]})"),
                HasSubstr("\"cpa_m\" is a parameter of a colreg criterion only"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "colreg", "penalty": 1, "head_on_deg": 30}]})"),
                HasSubstr("\"head_on_deg\" must be >= 0 and <= 22.4 (got 30)"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "colreg", "penalty": 1, "cpa_m": "far"}]})"), HasSubstr("\"cpa_m\" must be a number"));
    EXPECT_THAT(message_of(R"({"criteria": [{"kind": "colreg", "penalty": 1, "early_range_m": 5000}]})"),
                HasSubstr("\"early_range_m\" (5000) is beyond \"range_m\" (3704)"));
    EXPECT_THAT(message_of(R"({"pass_mark": -1, "criteria": [{"kind": "colreg", "penalty": 1}]})"), HasSubstr("\"pass_mark\" must be >= 0"));
    EXPECT_THAT(message_of(R"({"pass_mark": "B", "criteria": [{"kind": "colreg", "penalty": 1}]})"), HasSubstr("\"pass_mark\" must be a number"));
}

TEST(AssessmentFile, LoadReadsWithTheBoundedReaderAndNamesTheFile) {
    test::TempDir dir;
    const std::string path = dir.file("a.json");
    std::ofstream(path) << R"({"criteria": [{"kind": "cpa", "limit": 926, "penalty": 1}]})";
    EXPECT_EQ(Assessment::load(path).criteria.size(), 1u);
    EXPECT_THAT([&] { Assessment::load(dir.file("missing.json")); },
                ::testing::ThrowsMessage<InputError>(HasSubstr("assessment file '" + dir.file("missing.json") + "': cannot be read")));
    std::ofstream(dir.file("text.json")) << "criteria: none";
    EXPECT_THAT([&] { Assessment::load(dir.file("text.json")); }, ::testing::ThrowsMessage<InputError>(HasSubstr("not JSON")));
}

}  // namespace
}  // namespace shoal::audit
