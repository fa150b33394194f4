// COLREG situations (colreg.hpp): constructed encounters of each kind classified as rules
// 13-15 say, the borderline bearings either side of 22.5 degrees abaft the beam, random cases
// against a classification written with vector algebra (no angles), and find_situations on
// straight tracks against hand-derived start, CPA/TCPA, closest approach and action times.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <shoal/exercise/colreg.hpp>
#include <shoal/exercise/colreg_conduct.hpp>
#include <shoal/util/error.hpp>

namespace shoal::audit {
namespace {

using geo::XY;
constexpr double t0 = 1.7e9;
constexpr double pi = std::numbers::pi;

const geo::LocalFrame& frame() {
    static const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({0.0, 0.0});
    return f;
}

XY unit(double heading_deg) { return {std::sin(heading_deg * pi / 180), std::cos(heading_deg * pi / 180)}; }

VesselAt ship(XY p, double heading_deg, double speed_ms) { return {p, heading_deg, speed_ms * unit(heading_deg)}; }

/// Ship b placed at `range` on relative bearing `bearing_deg` from a (at the origin on `heading_a`).
XY on_bearing(double heading_a, double bearing_deg, double range) { return range * unit(heading_a + bearing_deg); }

TEST(Colreg, HeadOnBothGiveWay) {
    const Classification c = classify(ship({0, 0}, 10, 5), ship(on_bearing(10, 2, 3000), 190 + 3, 6));
    EXPECT_EQ(c.situation, Situation::head_on);
    EXPECT_EQ(c.give_way, Party::both);
    EXPECT_EQ(c.stand_on, Party::neither);
    EXPECT_STREQ(to_string(c.situation), "head-on");
    // Headings 7 degrees off reciprocal: no longer head-on (tolerance 6), a crossing.
    EXPECT_EQ(classify(ship({0, 0}, 0, 5), ship({0, 3000}, 187, 5)).situation, Situation::crossing);
}

TEST(Colreg, CrossingFromStarboardTheOwnShipGivesWay) {
    // b comes from a's starboard bow on a collision course: a has b to starboard.
    const Classification c = classify(ship({0, 0}, 0, 5), ship({1000, 1000}, 270, 5));
    EXPECT_EQ(c.situation, Situation::crossing);
    EXPECT_EQ(c.give_way, Party::a);
    EXPECT_EQ(c.stand_on, Party::b);
    EXPECT_NEAR(c.bearing_of_b_deg, 45, 1e-9);
    EXPECT_NEAR(c.bearing_of_a_deg, 315, 1e-9);
}

TEST(Colreg, CrossingFromPortTheOtherGivesWay) {
    const Classification c = classify(ship({0, 0}, 0, 5), ship({-1000, 1000}, 90, 5));
    EXPECT_EQ(c.situation, Situation::crossing);
    EXPECT_EQ(c.give_way, Party::b);
    EXPECT_EQ(c.stand_on, Party::a);
}

TEST(Colreg, OvertakingTheShipComingUpFromAstern) {
    const Classification c = classify(ship({0, 0}, 30, 3), ship(on_bearing(30, 180, 1000), 30, 6));
    EXPECT_EQ(c.situation, Situation::overtaking);
    EXPECT_EQ(c.give_way, Party::b);
    EXPECT_EQ(c.stand_on, Party::a);
    // The same seen the other way round: a is the one coming up.
    const Classification d = classify(ship(on_bearing(30, 180, 1000), 30, 6), ship({0, 0}, 30, 3));
    EXPECT_EQ(d.give_way, Party::a);
    EXPECT_EQ(d.stand_on, Party::b);
}

TEST(Colreg, BorderlineBearingsEitherSideOfTwentyTwoAndAHalfDegreesAbaftTheBeam) {
    for (const double h : {0.0, 77.0, 200.0, 359.0}) {
        // Starboard quarter: 112.4 is forward of the limit (a crossing, and a has b to starboard),
        // 112.6 abaft it (b is overtaking).
        Classification c = classify(ship({0, 0}, h, 5), ship(on_bearing(h, 112.4, 2000), h, 8));
        EXPECT_EQ(c.situation, Situation::crossing) << h;
        EXPECT_EQ(c.give_way, Party::a) << h;
        EXPECT_EQ(c.stand_on, Party::b) << h;
        c = classify(ship({0, 0}, h, 5), ship(on_bearing(h, 112.6, 2000), h, 8));
        EXPECT_EQ(c.situation, Situation::overtaking) << h;
        EXPECT_EQ(c.give_way, Party::b) << h;
        // Port quarter: 247.6 is forward of the limit (a crossing: b has a to starboard, b
        // gives way), 247.4 abaft it (b is overtaking).
        c = classify(ship({0, 0}, h, 5), ship(on_bearing(h, 247.6, 2000), h, 8));
        EXPECT_EQ(c.situation, Situation::crossing) << h;
        EXPECT_EQ(c.give_way, Party::b) << h;
        EXPECT_EQ(c.stand_on, Party::a) << h;
        c = classify(ship({0, 0}, h, 5), ship(on_bearing(h, 247.4, 2000), h, 8));
        EXPECT_EQ(c.situation, Situation::overtaking) << h;
        EXPECT_EQ(c.give_way, Party::b) << h;
    }
}

TEST(Colreg, CpaAndTcpaOfConstantVelocities) {
    // a north at 5 m/s from the origin, b west at 5 m/s from (1000, 1200): relative motion
    // (-5, -5) from (1000, 1200); closest when (1000 - 5t) + (1200 - 5t) = 0, t = 220 s, at
    // (-100, 100): 141.42 m.
    const Cpa c = cpa(ship({0, 0}, 0, 5), ship({1000, 1200}, 270, 5));
    EXPECT_NEAR(c.time_s, 220, 1e-9);
    EXPECT_NEAR(c.distance_m, std::sqrt(2.0) * 100, 1e-9);
    const Cpa opening = cpa(ship({0, 0}, 180, 5), ship({0, 1000}, 0, 5));
    EXPECT_NEAR(opening.time_s, -100, 1e-9);  // met 100 s ago (had they sailed so), now opening
    EXPECT_NEAR(opening.distance_m, 0, 1e-9);
    const Cpa still = cpa(ship({0, 0}, 0, 5), ship({300, 400}, 0, 5));  // same velocity: the distance now
    EXPECT_EQ(still.time_s, 0);
    EXPECT_NEAR(still.distance_m, 500, 1e-9);
}

/// The rules written with vectors: f the heading's unit vector, s its starboard normal, r the
/// direction to the other. Abaft 22.5 degrees past the beam: f.r < -sin(22.5) |r|; starboard:
/// s.r > 0; head-on: f_a.f_b < -cos(tol) and each sees the other within tol: f.r > cos(tol) |r|.
struct Expected {
    Situation situation;
    Party give_way, stand_on;
};
bool near_boundary(double v, double limit) { return std::abs(v - limit) < 1e-7; }

TEST(Colreg, RandomCasesAgreeWithVectorAlgebra) {
    std::mt19937_64 rng(18);
    std::uniform_real_distribution<double> pos(-3000, 3000), heading(0, 360), speed(0.5, 10), small(-8, 8);
    const double tol = 6;
    const double sin_abaft = std::sin(22.5 * pi / 180), cos_tol = std::cos(tol * pi / 180);
    int kinds[3] = {0, 0, 0}, checked = 0;
    for (int n = 0; n < 20000; ++n) {
        VesselAt a = ship({pos(rng), pos(rng)}, heading(rng), speed(rng));
        VesselAt b = ship({pos(rng), pos(rng)}, heading(rng), speed(rng));
        if (n % 4 == 0) {  // nearly head-on cases, so that the head-on branch is exercised
            const XY d = b.position - a.position;
            a.heading_deg = std::fmod(std::atan2(d.x, d.y) * 180 / pi + small(rng) + 360, 360);
            b.heading_deg = std::fmod(a.heading_deg + 180 + small(rng) + 360, 360);
            a.velocity = 5.0 * unit(a.heading_deg);
            b.velocity = 5.0 * unit(b.heading_deg);
        }
        const XY fa = unit(a.heading_deg), fb = unit(b.heading_deg);
        const XY sa{fa.y, -fa.x}, sb{fb.y, -fb.x};  // starboard normals
        const XY r = b.position - a.position;
        const double len = std::sqrt(geo::norm2(r));
        const XY u = (1 / len) * r;
        const double a_fwd = geo::dot(fa, u), b_fwd = geo::dot(fb, -1.0 * u);  // cosines of the relative bearings
        const double a_stbd = geo::dot(sa, u), b_stbd = geo::dot(sb, -1.0 * u);
        const double recip = geo::dot(fa, fb);
        if (near_boundary(a_fwd, -sin_abaft) || near_boundary(b_fwd, -sin_abaft) || near_boundary(a_fwd, cos_tol) ||
            near_boundary(b_fwd, cos_tol) || near_boundary(recip, -cos_tol) || std::abs(a_stbd) < 1e-7 || std::abs(b_stbd) < 1e-7)
            continue;
        Expected e{};
        const bool b_abaft = a_fwd < -sin_abaft, a_abaft = b_fwd < -sin_abaft;
        if (b_abaft || a_abaft) {
            const bool b_over = b_abaft && a_abaft ? geo::norm2(b.velocity) > geo::norm2(a.velocity) : b_abaft;
            e = {Situation::overtaking, b_over ? Party::b : Party::a, b_over ? Party::a : Party::b};
        } else if (recip < -cos_tol && a_fwd > cos_tol && b_fwd > cos_tol) {
            e = {Situation::head_on, Party::both, Party::neither};
        } else {
            const bool ag = a_stbd > 0, bg = b_stbd > 0;
            e = {Situation::crossing, ag && bg ? Party::both : ag ? Party::a : bg ? Party::b : Party::neither,
                 ag && bg ? Party::neither : ag ? Party::b : bg ? Party::a : Party::neither};
        }
        const Classification c = classify(a, b, tol);
        ASSERT_EQ(c.situation, e.situation) << n;
        ASSERT_EQ(c.give_way, e.give_way) << n;
        ASSERT_EQ(c.stand_on, e.stand_on) << n;
        ++kinds[static_cast<int>(c.situation)];
        ++checked;
    }
    EXPECT_GT(checked, 19000);
    for (const int k : kinds) EXPECT_GT(k, 500);  // every kind is well represented
}

/// A straight track: from `start` (local metres) on `heading_deg` at `speed_ms`, a fix every
/// `every_s` seconds from t0 + from_s to t0 + to_s; `turn` degrees added to the heading (and the
/// course) from t0 + turn_at_s on.
track::Track straight(const std::string& id, XY start, double heading_deg, double speed_ms, double from_s, double to_s,
                      double every_s = 10, double turn_at_s = INFINITY, double turn = 0) {
    track::Track t;
    t.id = id;
    t.file = "hand-made";
    XY p = start;
    for (double s = from_s; s <= to_s + 1e-9; s += every_s) {
        const double h = s >= turn_at_s ? heading_deg + turn : heading_deg;
        track::Fix f;
        f.time_s = t0 + s;
        f.position = frame().inverse(p);
        f.heading_used_deg = std::fmod(h + 360, 360);
        f.heading_source = track::HeadingSource::heading;
        f.line = t.fixes.size() + 2;
        t.fixes.push_back(f);
        p = p + (speed_ms * every_s) * unit(h);
    }
    return t;
}

TEST(Colreg, HeadOnTracksStartAtTheRangeWithTheirCpaAndClosestApproach) {
    // 10 km apart, 200 m offset, closing at 10 m/s: within 3704 m when the distance along is
    // sqrt(3704^2 - 200^2), CPA 200 m then, closest 200 m at t = 1000 s.
    const track::Track a = straight("a", {0, 0}, 0, 5, 0, 2000);
    const track::Track b = straight("b", {200, 10000}, 180, 5, 0, 2000);
    const auto found = find_situations({&a, &b}, frame(), ColregOptions{}, 600);
    ASSERT_EQ(found.size(), 1u);
    const ColregEncounter& e = found[0];
    const double along = std::sqrt(3704.0 * 3704.0 - 200.0 * 200.0);
    EXPECT_NEAR(e.start_s - t0, (10000 - along) / 10, 1e-3);
    EXPECT_EQ(e.at_start.situation, Situation::head_on);
    EXPECT_NEAR(e.cpa_start.distance_m, 200, 1e-3);
    EXPECT_NEAR(e.cpa_start.time_s, along / 10, 1e-3);
    EXPECT_NEAR(e.closest_m, 200, 1e-3);
    EXPECT_NEAR(e.closest_s - t0, 1000, 1e-3);
    EXPECT_NEAR(e.end_s - t0, 1000 + along / 10, 1e-3);  // out of range again
    EXPECT_TRUE(std::isnan(e.action_a.time_s));
    EXPECT_TRUE(std::isnan(e.action_b.time_s));
}

TEST(Colreg, TheGiveWayShipsAlterationIsFoundAndTimed) {
    // Crossing: b from a's starboard; a turns 30 degrees to starboard at 500 s (kept), b stands on.
    const track::Track a = straight("a", {0, 0}, 0, 5, 0, 1500, 10, 500, 30);
    const track::Track b = straight("b", {5000, 5000}, 270, 5, 0, 1500);
    const auto found = find_situations({&a, &b}, frame(), ColregOptions{}, 600);
    ASSERT_EQ(found.size(), 1u);
    const ColregEncounter& e = found[0];
    EXPECT_EQ(e.at_start.situation, Situation::crossing);
    EXPECT_EQ(e.at_start.give_way, Party::a);
    EXPECT_EQ(e.at_start.stand_on, Party::b);
    EXPECT_LT(e.start_s - t0, 500);
    EXPECT_NEAR(e.action_a.time_s - t0, 500, 1e-9);
    EXPECT_TRUE(e.action_a.course);
    EXPECT_FALSE(e.action_a.speed);
    EXPECT_TRUE(std::isnan(e.action_b.time_s));
    // A turn of 30 degrees kept for only 20 s (less than sustain_s) is no action.
    track::Track wobble = straight("a", {0, 0}, 0, 5, 0, 1500);
    for (auto& f : wobble.fixes)
        if (f.time_s - t0 >= 500 && f.time_s - t0 < 520) f.heading_used_deg = 30;
    const auto w = find_situations({&wobble, &b}, frame(), ColregOptions{}, 600);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_TRUE(std::isnan(w[0].action_a.time_s));
}

TEST(Colreg, AShipNotUnderWayHasNoDutyAndGivesNoneToTheOther) {
    // b lies stopped (0.2 knots) on a's starboard bow: the geometry is a crossing, but the
    // rules give no give-way or stand-on ship.
    const track::Track a = straight("a", {0, 0}, 0, 5, 0, 1000);
    const track::Track b = straight("b", {1000, 3000}, 270, 0.1, 0, 1000);
    const auto found = find_situations({&a, &b}, frame(), ColregOptions{}, 600);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].at_start.situation, Situation::crossing);
    EXPECT_TRUE(found[0].b_stopped);
    EXPECT_FALSE(found[0].a_stopped);
    EXPECT_EQ(found[0].at_start.give_way, Party::neither);
    EXPECT_EQ(found[0].at_start.stand_on, Party::neither);
}

TEST(Colreg, PairsNeverWithinRangeOrNotWantedOrApartInTimeAreNotReported) {
    const track::Track a = straight("a", {0, 0}, 0, 5, 0, 1000);
    const track::Track far = straight("far", {5000, 0}, 0, 5, 0, 1000);        // 5 km abeam throughout
    const track::Track later = straight("later", {0, 6000}, 180, 5, 2000, 3000);  // after a has gone
    EXPECT_TRUE(find_situations({&a, &far, &later}, frame(), ColregOptions{}, 600).empty());
    const track::Track b = straight("b", {0, 8000}, 180, 5, 0, 1000);
    EXPECT_EQ(find_situations({&a, &b}, frame(), ColregOptions{}, 600).size(), 1u);
    EXPECT_TRUE(find_situations({&a, &b}, frame(), ColregOptions{}, 600, [](std::size_t, std::size_t) { return false; }).empty());
    // With fixes 400 s apart and a max gap of 300 s both ships are absent throughout.
    const track::Track a2 = straight("a", {0, 0}, 0, 5, 0, 1200, 400);
    const track::Track b2 = straight("b", {0, 8000}, 180, 5, 0, 1200, 400);
    EXPECT_TRUE(find_situations({&a2, &b2}, frame(), ColregOptions{}, 300).empty());
    ColregOptions bad;
    bad.range_m = 0;
    EXPECT_THROW(find_situations({&a, &b}, frame(), bad, 600), UsageError);
}

// ---------------------------------------------------------------- conduct (colreg_conduct.hpp)
// DNV's standard encounters (head-on, crossing give-way and stand-on, overtaking, overtaken),
// the own ship at 6 m/s (4 m/s overtaken, 8 m/s overtaking), a fix every 10 s, with and
// without proper manoeuvres. Each case's truth derived by hand (default ConductOptions: risk
// and well clear 926 m, early 1852 m, readily apparent 30 degrees or half the speed):

/// The rules the own ship breached in its one situation with `other`, in order.
std::vector<std::string> breached(const track::Track& own, const track::Track& other, std::string* role = nullptr) {
    const auto found = judge_conduct(own, {&other}, frame(), ConductOptions{}, 600);
    EXPECT_EQ(found.size(), 1u);
    std::vector<std::string> rules;
    if (found.empty()) return rules;
    if (role) *role = found[0].role;
    for (const ConductBreach& b : found[0].breaches) {
        rules.push_back(b.rule);
        EXPECT_FALSE(b.asked.empty());
        EXPECT_NE(b.did.find(own.id), std::string::npos) << b.did;
    }
    return rules;
}
using Rules = std::vector<std::string>;

TEST(Conduct, HeadOn) {
    // 12 km apart on reciprocal courses, closing at 12 m/s: within 2 nm at t = (12000 - 3704) / 12
    // = 691 s, CPA 0 at 1000 s. Both give way (rule 14).
    const track::Track other = straight("C1", {0, 12000}, 180, 6, 0, 1600);
    std::string role;
    // Held on: rule 14, at the closest approach.
    const track::Track held = straight("T1", {0, 0}, 0, 6, 0, 1600);
    EXPECT_EQ(breached(held, other, &role), Rules{"14"});
    EXPECT_EQ(role, "give-way");
    const auto h = judge_conduct(held, {&other}, frame(), ConductOptions{}, 600);
    ASSERT_EQ(h[0].breaches.size(), 1u);
    EXPECT_NEAR(h[0].breaches[0].time_s - t0, 1000, 1);
    EXPECT_EQ(h[0].rules, (Rules{"14", "8"}));
    // 35 degrees to starboard at 700 s (3600 m off): relative velocity (-3.44, -10.91) m/s from
    // (0, 3600): closest 1083 m. Early, large, clear: no breach.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 700, 35), other), Rules{});
    // The same to port: the mirror image, 1083 m clear, but rule 14 asks starboard.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 700, -35), other), Rules{"14"});
    // 15 degrees to starboard at 900 s (1200 m off): late, small, and closest (0, 1200) +
    // 100 s x (-1.55, -11.80) = 156 m: one rule-8 breach.
    const auto late = judge_conduct(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 900, 15), {&other}, frame(), ConductOptions{}, 600);
    ASSERT_EQ(late.size(), 1u);
    ASSERT_EQ(late[0].breaches.size(), 1u);
    EXPECT_EQ(late[0].breaches[0].rule, "8");
    EXPECT_NEAR(late[0].breaches[0].time_s - t0, 900, 1e-6);
    EXPECT_NEAR(late[0].action_range_m, 1200, 1);
    EXPECT_NEAR(late[0].course_change_deg, 15, 1e-6);
    EXPECT_NE(late[0].breaches[0].did.find("late"), std::string::npos);
    EXPECT_NE(late[0].breaches[0].did.find("too small"), std::string::npos);
    EXPECT_NE(late[0].breaches[0].did.find("passed 0.08 nm"), std::string::npos) << late[0].breaches[0].did;
}

TEST(Conduct, CrossingGiveWay) {
    // C1 from the own ship's starboard bow (45 degrees), both at 6 m/s, meeting at (0, 6000) at
    // 1000 s: within 2 nm at 1000 - 3704 / 8.485 = 563 s. The own ship gives way (rule 15).
    const track::Track other = straight("C1", {6000, 6000}, 270, 6, 0, 1600);
    std::string role;
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600), other, &role), Rules{"15"});
    EXPECT_EQ(role, "give-way");
    // 40 degrees to starboard at 600 s (3394 m off): closest 1161 m, passing astern of C1.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 600, 40), other), Rules{});
    // 40 degrees to port at 600 s: closest 1161 m too, but it crosses C1's line 1282 m ahead of her.
    const auto port = judge_conduct(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 600, -40), {&other}, frame(), ConductOptions{}, 600);
    ASSERT_EQ(port[0].breaches.size(), 1u);
    EXPECT_EQ(port[0].breaches[0].rule, "15");
    EXPECT_NE(port[0].breaches[0].did.find("crossed 128"), std::string::npos) << port[0].breaches[0].did;
    // 15 degrees to starboard at 850 s (1273 m off): late, small, closest 166 m: rule 16.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 850, 15), other), Rules{"16"});
    // Slowing from 6 to 2 m/s at 600 s (two thirds: readily apparent): C1 then crosses
    // (2400, 2400) + s (-6, -4) ahead, closest 2400 |(1, 1) - (6, 4) 30/52| = 1331 m: no breach.
    track::Track slow = straight("T1", {0, 0}, 0, 6, 0, 600);
    const track::Track rest = straight("T1", {0, 3600}, 0, 2, 610, 1600);
    slow.fixes.insert(slow.fixes.end(), rest.fixes.begin(), rest.fixes.end());
    EXPECT_EQ(breached(slow, other), Rules{});
}

TEST(Conduct, CrossingStandOn) {
    // C1 from the port bow: the own ship stands on (rule 17); C1 never acts.
    const track::Track other = straight("C1", {-6000, 6000}, 90, 6, 0, 1600);
    std::string role;
    // Course and speed kept: no breach, though C1 held on too.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600), other, &role), Rules{});
    EXPECT_EQ(role, "stand-on");
    const auto kept = judge_conduct(straight("T1", {0, 0}, 0, 6, 0, 1600), {&other}, frame(), ConductOptions{}, 600);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept[0].rules, (Rules{"15", "17"}));
    EXPECT_EQ(kept[0].did.rfind("T1 kept her course (000) and speed (11.7 kn) from ", 0), 0u) << kept[0].did;
    // Turning 40 degrees to starboard early (600 s, 3394 m off, C1 could still act): rule 17.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 600, 40), other), Rules{"17"});
    // The same at 900 s (849 m off, C1 has not acted): allowed (17(a)(ii), (b)).
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 900, 40), other), Rules{});
    // Then but to port, towards C1 on her port side: rule 17(c).
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600, 10, 900, -40), other), Rules{"17"});
}

TEST(Conduct, OvertakingAndOvertaken) {
    // The own ship at 8 m/s comes up from 5000 m astern of C1 (4 m/s, 50 m to starboard):
    // within 2 nm at 324 s, CPA 50 m. The own ship overtakes: rule 13, give-way.
    const track::Track slow = straight("C1", {50, 5000}, 0, 4, 0, 2000);
    std::string role;
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 8, 0, 2000), slow, &role), Rules{"13"});
    EXPECT_EQ(role, "give-way");
    // 30 degrees to starboard at 400 s (3400 m off): closest 2714 m, no breach.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 8, 0, 2000, 10, 400, 30), slow), Rules{});
    // Overtaken: the own ship at 4 m/s, C1 at 8 m/s from 5000 m astern: stand-on.
    const track::Track fast = straight("C1", {-50, -5000}, 0, 8, 0, 2000);
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 4, 0, 2000), fast, &role), Rules{});
    EXPECT_EQ(role, "stand-on");
    // Turning away early (400 s, 3400 m off): rule 17.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 4, 0, 2000, 10, 400, 30), fast), Rules{"17"});
}

TEST(Conduct, NoRiskNoDutyAndStoppedShips) {
    // Reciprocal courses 2 km apart: head-on geometry is not met (C1 33 degrees off the bow at
    // 2 nm), the CPA 2000 m is over 926 m: no duty.
    std::string role = "x";
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600), straight("C1", {2000, 12000}, 180, 6, 0, 1600), &role), Rules{});
    EXPECT_EQ(role, "");
    // Why there was no duty, in words: the CPA projected at the start, 2000 m = 1.08 nm.
    const track::Track far = straight("C1", {2000, 12000}, 180, 6, 0, 1600);
    const auto none = judge_conduct(straight("T1", {0, 0}, 0, 6, 0, 1600), {&far}, frame(), ConductOptions{}, 600);
    ASSERT_EQ(none.size(), 1u);
    EXPECT_TRUE(none[0].rules.empty());
    EXPECT_EQ(none[0].did.rfind("no risk of collision: CPA projected at the start 1.08 nm, closest approach 1.08 nm", 0), 0u) << none[0].did;
    // A ship at anchor ahead: no duty for either.
    EXPECT_EQ(breached(straight("T1", {0, 0}, 0, 6, 0, 1600), straight("C1", {0, 6000}, 0, 0, 0, 1600), &role), Rules{});
    EXPECT_EQ(role, "");
    const track::Track anchored = straight("C1", {0, 6000}, 0, 0, 0, 1600);
    const auto stopped = judge_conduct(straight("T1", {0, 0}, 0, 6, 0, 1600), {&anchored}, frame(), ConductOptions{}, 600);
    ASSERT_EQ(stopped.size(), 1u);
    EXPECT_EQ(stopped[0].did, "no duty: C1 was not under way when the situation began");
    ConductOptions bad;
    bad.cpa_m = 0;
    const track::Track a = straight("T1", {0, 0}, 0, 6, 0, 100);
    EXPECT_THROW(judge_conduct(a, {&a}, frame(), bad, 600), UsageError);
}

}  // namespace
}  // namespace shoal::audit
