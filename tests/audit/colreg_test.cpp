// COLREG situations (colreg.hpp): constructed encounters of each kind classified as rules
// 13-15 say, the borderline bearings either side of 22.5 degrees abaft the beam, random cases
// against a classification written with vector algebra (no angles), and find_situations on
// straight tracks against hand-derived start, CPA/TCPA, closest approach and action times.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <shoal/audit/colreg.hpp>
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

}  // namespace
}  // namespace shoal::audit
