// Ship-to-ship encounters: hand-made exercises with known answers (crossing, head-on,
// overtaking, near miss, a turn in place, gaps, spans that do not overlap), and random
// exercises against the brute force (hull-to-hull contact: tests/check/hull_contact_test.cpp).

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include <shoal/exercise/encounters.hpp>
#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace shoal::audit {
namespace {

using geo::XY;

constexpr double t0 = 1.7e9;

/// A frame centred at (0, 0) lon/lat; hand-made exercises are written in its metres, where
/// grid north is true north and the scale is 1 to 1e-8.
const geo::LocalFrame& frame() {
    static const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({0.0, 0.0});
    return f;
}

/// A box-shaped hull: 80 m forward and 20 m aft of the reference point, 8 m to either side.
hull::Hull box_hull() { return hull::Hull::from_contour({{80, -8}, {80, 8}, {-20, 8}, {-20, -8}}, "box"); }

XY heading_vector(double heading_deg) {
    const double h = heading_deg * std::numbers::pi / 180;
    return {std::sin(h), std::cos(h)};
}

/// A ship steaming straight from `start` (local metres) on `heading_deg` at `speed_ms`, a fix
/// every `every_s` seconds from t0 + `from_s` to t0 + `to_s`.
track::Track straight(const std::string& id, XY start, double heading_deg, double speed_ms, double from_s, double to_s,
                      double every_s = 10) {
    track::Track t;
    t.id = id;
    t.file = "hand-made";
    for (double s = from_s; s <= to_s + 1e-9; s += every_s) {
        track::Fix f;
        f.time_s = t0 + s;
        f.position = frame().inverse(start + (speed_ms * (s - from_s)) * heading_vector(heading_deg));
        f.heading_used_deg = heading_deg;
        f.heading_source = track::HeadingSource::heading;
        f.line = t.fixes.size() + 2;
        t.fixes.push_back(f);
    }
    return t;
}

struct Exercise {
    std::vector<track::Track> tracks;
    std::vector<hull::Hull> hulls;
    void add(track::Track t, hull::Hull h = box_hull()) {
        tracks.push_back(std::move(t));
        hulls.push_back(std::move(h));
    }
    std::vector<const track::Track*> pointers() const {
        std::vector<const track::Track*> out;
        for (const auto& t : tracks) out.push_back(&t);
        return out;
    }
    EncounterResult run(const EncounterOptions& o = {}) const { return find_encounters(pointers(), hulls, frame(), o); }
    EncounterResult brute(const EncounterOptions& o = {}) const { return find_encounters_brute(pointers(), hulls, frame(), o); }
};

std::size_t count(const EncounterResult& r, EncounterKind k) {
    return static_cast<std::size_t>(std::count_if(r.events.begin(), r.events.end(), [&](const Encounter& e) { return e.kind == k; }));
}

XY local(geo::LonLat p) { return frame().forward(p); }

TEST(Encounters, CrossingShipsCollideBowIntoSide) {
    // A heads north from (0, 0); B heads east along y = 1010 and is there first: A's bow
    // (y = 5t + 80) meets B's starboard side (y = 1002) at t = 184.4 s, while B's hull spans
    // x in [-98, 2]; they part when B's stern passes x = 8 at t = 205.6 s.
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 400));
    x.add(straight("B", {-1000, 1010}, 90, 5, 0, 400));
    const EncounterResult r = x.run();
    ASSERT_EQ(r.events.size(), 1u);
    const Encounter& e = r.events[0];
    EXPECT_EQ(e.kind, EncounterKind::collision);
    EXPECT_EQ(std::string(to_string(e.kind)), "collision");
    EXPECT_NEAR(e.start_s - t0, 184.4, 0.02);
    EXPECT_NEAR(e.end_s - t0, 205.6, 0.02);
    EXPECT_EQ(e.min_clearance_m, 0);
    const XY p = local(e.point);
    EXPECT_NEAR(p.y, 1002, 0.1);
    EXPECT_GE(p.x, -8.1);
    EXPECT_LE(p.x, 2.1);
    EXPECT_EQ(e.a.track, 0u);
    EXPECT_EQ(e.b.track, 1u);
    EXPECT_NEAR(e.a.heading_deg, 0, 1e-9);
    EXPECT_NEAR(e.b.heading_deg, 90, 1e-9);
    EXPECT_NEAR(local(e.a.position).y, 922, 0.1);
    EXPECT_NEAR(local(e.b.position).x, -78, 0.1);
    EXPECT_EQ(e.a.fix_index, 18u);
    ASSERT_EQ(e.a.hull.size(), 5u);  // closed ring of the 4-point box
    EXPECT_EQ(e.a.hull.front(), e.a.hull.back());
    ASSERT_EQ(r.approaches.size(), 1u);
    EXPECT_EQ(r.approaches[0].clearance_m, 0);
    EXPECT_EQ(r.approaches[0].time_s, e.start_s);
    EXPECT_NEAR(r.approaches[0].distance_m, std::hypot(78, 88), 0.2);
    // 41 fix times; relative motion bound 10 m/s: 19 instants between fixes 10 s apart (20
    // when the frame's scale makes 50 m a hair longer).
    EXPECT_GE(r.instants, 41u + 40u * 19u);
    EXPECT_LE(r.instants, 41u + 40u * 20u);
}

TEST(Encounters, CollisionBetweenFixesFarApartIsFound) {
    // The same crossing with two fixes per ship, 400 s apart: only the instants between them see it.
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 400, 400));
    x.add(straight("B", {-1000, 1010}, 90, 5, 0, 400, 400));
    const EncounterResult r = x.run();
    ASSERT_EQ(r.events.size(), 1u);
    EXPECT_NEAR(r.events[0].start_s - t0, 184.4, 0.02);
    EXPECT_NEAR(r.events[0].end_s - t0, 205.6, 0.02);
}

TEST(Encounters, HeadOnPassAtFortyMetresIsCloseQuarters) {
    // A north along x = 0, B south along x = 40: sides 24 m apart while abreast. With a 30 m
    // margin, clearance sqrt(24^2 + gap^2) < 30 while the bow gap 1840 - 10t < 18 (t > 182.2 s)
    // until the stern gap 10t - 2040 < 18 (t < 205.8 s). Instants are 0.5 s apart.
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 400));
    x.add(straight("B", {40, 2000}, 180, 5, 0, 400));
    EncounterOptions o;
    o.ship_margin_m = 30;
    const EncounterResult r = x.run(o);
    ASSERT_EQ(r.events.size(), 1u);
    const Encounter& e = r.events[0];
    EXPECT_EQ(e.kind, EncounterKind::close_quarters);
    EXPECT_GT(e.start_s - t0, 182.2);
    EXPECT_LE(e.start_s - t0, 182.7);
    EXPECT_LT(e.end_s - t0, 205.8);
    EXPECT_GE(e.end_s - t0, 205.3);
    EXPECT_NEAR(e.min_clearance_m, 24, 1e-6);
    EXPECT_NEAR(local(e.point).x, 20, 1e-6);  // midway between the two sides
    EXPECT_NEAR(e.b.heading_deg, 180, 1e-9);
    ASSERT_EQ(r.approaches.size(), 1u);
    EXPECT_NEAR(r.approaches[0].clearance_m, 24, 1e-6);
    EXPECT_GE(r.approaches[0].time_s - t0, 184.0 - 1e-6);  // the first moment abreast
    EXPECT_LE(r.approaches[0].time_s - t0, 204.0);
    // The default 20 m margin: no event, but the closest approach is still there.
    const EncounterResult quiet = x.run();
    EXPECT_TRUE(quiet.events.empty());
    ASSERT_EQ(quiet.approaches.size(), 1u);
    EXPECT_NEAR(quiet.approaches[0].clearance_m, 24, 1e-6);
}

TEST(Encounters, OvertakingCloseAbeamIsCloseQuarters) {
    // B (6 m/s) overtakes A (3 m/s) 30 m to starboard: sides 14 m apart. Close quarters while
    // sqrt(14^2 + gap^2) < 20: from B's bow 14.28 m short of A's stern (t = 61.905 s) until
    // B's stern 14.28 m past A's bow (t = 138.095 s). Instants are 5/9 s apart.
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 3, 0, 200));
    x.add(straight("B", {30, -300}, 0, 6, 0, 200));
    const EncounterResult r = x.run();
    ASSERT_EQ(r.events.size(), 1u);
    const Encounter& e = r.events[0];
    EXPECT_EQ(e.kind, EncounterKind::close_quarters);
    const double g = std::sqrt(20.0 * 20.0 - 14.0 * 14.0);
    EXPECT_GT(e.start_s - t0, (200 - g) / 3);
    EXPECT_LE(e.start_s - t0, (200 - g) / 3 + 5.0 / 9 + 1e-6);
    EXPECT_LT(e.end_s - t0, (400 + g) / 3);
    EXPECT_GE(e.end_s - t0, (400 + g) / 3 - 5.0 / 9 - 1e-6);
    EXPECT_NEAR(e.min_clearance_m, 14, 1e-6);
}

TEST(Encounters, OvertakingOverlappingIsACollisionFromBowToStern) {
    // B 12 m to starboard of A: its port side (x = 4) overlaps A's starboard side (x = 8).
    // B's bow (6t - 220) reaches A's stern (3t - 20) at t = 66.667 s; B's stern (6t - 320)
    // passes A's bow (3t + 80) at t = 133.333 s. First contact: x in [4, 8], y = 180.
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 3, 0, 200));
    x.add(straight("B", {12, -300}, 0, 6, 0, 200));
    const EncounterResult r = x.run();
    ASSERT_EQ(r.events.size(), 1u);
    const Encounter& e = r.events[0];
    EXPECT_EQ(e.kind, EncounterKind::collision);
    EXPECT_NEAR(e.start_s - t0, 200.0 / 3, 0.02);
    EXPECT_NEAR(e.end_s - t0, 400.0 / 3, 0.02);
    const XY p = local(e.point);
    EXPECT_NEAR(p.y, 180, 0.1);
    EXPECT_GE(p.x, 4 - 0.1);
    EXPECT_LE(p.x, 8 + 0.1);
}

TEST(Encounters, NearMissAheadOfTheBowIsCloseQuartersWithoutContact) {
    // B (10 m/s east) clears A's bow: its stern corner passes x = 8 when A's bow is 3 m short
    // of B's side (t = 183.8 s). The least clearance, corner to corner, is sqrt(7.2) = 2.683 m
    // at t = 183.92 s; sampled every 5 m of relative motion it is seen within a metre.
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 400));
    x.add(straight("B", {-1810, 1010}, 90, 10, 0, 400));
    const EncounterResult r = x.run();
    ASSERT_EQ(r.events.size(), 1u);
    const Encounter& e = r.events[0];
    EXPECT_EQ(e.kind, EncounterKind::close_quarters);
    EXPECT_GE(e.min_clearance_m, std::sqrt(7.2) - 1e-9);
    EXPECT_LE(e.min_clearance_m, 3.0 + 1e-9);
    // B's side passes over A's bow first: clearance 922 - 5t drops under 20 m at t = 180.4 s.
    EXPECT_GT(e.start_s - t0, 180.4);
    EXPECT_LE(e.start_s - t0, 180.4 + 1.0 / 3 + 1e-6);  // instants 1/3 s apart (15 m/s bound)
    ASSERT_EQ(r.approaches.size(), 1u);
    EXPECT_EQ(r.approaches[0].clearance_m, e.min_clearance_m);
    EXPECT_NEAR(r.approaches[0].time_s - t0, 183.92, 0.4);
}

TEST(Encounters, TurnInPlaceSweepsTheBowIntoANeighbour) {
    // A turns from north to east in 10 s without moving; B lies north-east of it. At both
    // fixes they are apart (44 m, then 32 m), but halfway A's bow tip (56.6, 56.6) is inside
    // B's hull: the instants between the fixes account for rotation.
    Exercise x;
    track::Track a = straight("A", {0, 0}, 0, 0, 0, 10);
    a.fixes[1].heading_used_deg = 90;
    x.add(a);
    x.add(straight("B", {60, 60}, 0, 0, 0, 10));
    const EncounterResult r = x.run();
    ASSERT_EQ(count(r, EncounterKind::collision), 1u);
    EXPECT_GT(r.events[0].start_s - t0, 0.0);
    EXPECT_LT(r.events[0].end_s - t0, 10.0);
}

TEST(Encounters, ShipsAtTheSamePlaceAtDifferentTimesAreNeverPaired) {
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 400));
    x.add(straight("B", {0, 0}, 0, 5, 1000, 1400));
    const EncounterResult r = x.run();
    EXPECT_TRUE(r.events.empty());
    EXPECT_TRUE(r.approaches.empty());
    EXPECT_EQ(r.pairs_checked, 0u);
}

TEST(Encounters, AShipIsAbsentDuringAGapInItsTrack) {
    // A passes through B (at anchor at y = 1000) between fixes 700 s apart: a gap over the
    // 600 s default, so A is absent there. With --max-gap 800 they collide.
    Exercise x;
    track::Track a = straight("A", {0, 0}, 0, 5, 0, 700, 700);
    x.add(a);
    x.add(straight("B", {-50, 1000}, 90, 0, 0, 700, 60));
    const EncounterResult r = x.run();
    EXPECT_TRUE(r.events.empty());
    EXPECT_TRUE(r.approaches.empty());
    EncounterOptions o;
    o.max_gap_s = 800;
    EXPECT_EQ(count(x.run(o), EncounterKind::collision), 1u);
}

TEST(Encounters, ThresholdDecidesWhichPairsGetAClosestApproach) {
    // Head-on 300 m apart: beyond the automatic threshold (20 + 5 + 2 x 80.4 m).
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 400));
    x.add(straight("B", {300, 2000}, 180, 5, 0, 400));
    const EncounterResult r = x.run();
    EXPECT_TRUE(r.approaches.empty());
    EXPECT_NEAR(r.threshold_m, 25 + 2 * std::hypot(80, 8), 1e-9);
    EncounterOptions o;
    o.threshold_m = 400;
    const EncounterResult wide = x.run(o);
    ASSERT_EQ(wide.approaches.size(), 1u);
    EXPECT_NEAR(wide.approaches[0].clearance_m, 284, 1e-6);
    EXPECT_TRUE(wide.events.empty());
}

TEST(Encounters, BadOptionsAndInputsAreRejected) {
    Exercise x;
    x.add(straight("A", {0, 0}, 0, 5, 0, 40));
    EncounterOptions o;
    o.step_m = 0;
    EXPECT_THROW(x.run(o), UsageError);
    o = {};
    o.ship_margin_m = -1;
    EXPECT_THROW(x.run(o), UsageError);
    EXPECT_THROW(find_encounters(x.pointers(), {}, frame(), {}), UsageError);
    x.tracks[0].fixes[2].heading_used_deg = NAN;
    EXPECT_THROW(x.run(), InputError);
}

/// A U-shaped (non-convex) hull: two hulls of a catamaran joined at the stern.
hull::Hull catamaran() {
    return hull::Hull::from_contour({{55, -12}, {55, -6}, {5, -6}, {5, 6}, {55, 6}, {55, 12}, {-5, 12}, {-5, -12}}, "cat");
}

// ---------------------------------------------------------------------------------------
// Random exercises against the brute force

/// A random exercise: ships wandering in a square of `side` metres, each with its own span,
/// fix interval and phase, some with gaps, hulls of several shapes.
Exercise random_exercise(std::mt19937_64& rng, std::size_t ships, double side) {
    std::uniform_real_distribution<double> u(0, 1);
    const std::vector<hull::Hull> shapes = {hull::Hull::from_dimensions({80, 20, 8, 8}), hull::Hull::from_dimensions_n({30, 10, 5, 4}, 8),
                                            box_hull(), catamaran(), hull::Hull::from_dimensions({150, 40, 15, 15})};
    Exercise x;
    for (std::size_t k = 0; k < ships; ++k) {
        track::Track t;
        t.id = "ship" + std::to_string(k);
        t.file = "random";
        XY p{side * u(rng), side * u(rng)};
        double hdg = 360 * u(rng), time = t0 + 200 * u(rng);
        const double speed = 1 + 9 * u(rng), every = 5 + 25 * u(rng);
        const int n = 10 + static_cast<int>(rng() % 30);
        for (int i = 0; i < n; ++i) {
            track::Fix f;
            f.time_s = time;
            f.position = frame().inverse(p);
            f.heading_used_deg = hdg;
            f.line = static_cast<std::size_t>(i + 1);
            t.fixes.push_back(f);
            double dt = every * (0.5 + u(rng));
            if (u(rng) < 0.03) dt += 700;  // a gap
            hdg = std::fmod(hdg + (u(rng) - 0.5) * 60 + 360, 360);
            p = p + (speed * std::min(dt, 60.0)) * heading_vector(hdg);
            // Keep to the square: turn back towards its middle when outside.
            if (p.x < 0 || p.y < 0 || p.x > side || p.y > side) {
                const XY to = XY{side / 2, side / 2} - p;
                hdg = std::fmod(std::atan2(to.x, to.y) * 180 / std::numbers::pi + 360, 360);
            }
            time += dt;
        }
        x.add(std::move(t), shapes[rng() % shapes.size()]);
    }
    return x;
}

/// Every difference between two results, one line each.
std::vector<std::string> differences(const EncounterResult& fast, const EncounterResult& brute) {
    std::vector<std::string> out;
    auto say = [&](const std::string& what) { out.push_back(what); };
    if (fast.instants != brute.instants) say("instants " + std::to_string(fast.instants) + " vs " + std::to_string(brute.instants));
    if (fast.pairs_checked != brute.pairs_checked)
        say("pairs checked " + std::to_string(fast.pairs_checked) + " vs " + std::to_string(brute.pairs_checked));
    auto ship_eq = [](const ShipAt& x, const ShipAt& y) {
        return x.track == y.track && x.position == y.position && x.heading_deg == y.heading_deg && x.fix_index == y.fix_index &&
               x.hull == y.hull;
    };
    const std::size_t ne = std::max(fast.events.size(), brute.events.size());
    for (std::size_t k = 0; k < ne; ++k) {
        if (k >= fast.events.size() || k >= brute.events.size()) {
            say("event " + std::to_string(k) + " missing on one side");
            continue;
        }
        const Encounter& x = fast.events[k];
        const Encounter& y = brute.events[k];
        if (x.kind != y.kind || x.start_s != y.start_s || x.end_s != y.end_s || x.min_clearance_m != y.min_clearance_m ||
            x.distance_m != y.distance_m || !(x.point == y.point) || !ship_eq(x.a, y.a) || !ship_eq(x.b, y.b)) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "event %zu: %s %zu-%zu %.3f-%.3f %.6f vs %s %zu-%zu %.3f-%.3f %.6f", k, to_string(x.kind),
                          x.a.track, x.b.track, x.start_s - t0, x.end_s - t0, x.min_clearance_m, to_string(y.kind), y.a.track,
                          y.b.track, y.start_s - t0, y.end_s - t0, y.min_clearance_m);
            say(buf);
        }
    }
    const std::size_t na = std::max(fast.approaches.size(), brute.approaches.size());
    for (std::size_t k = 0; k < na; ++k) {
        if (k >= fast.approaches.size() || k >= brute.approaches.size()) {
            say("approach " + std::to_string(k) + " missing on one side");
            continue;
        }
        const ClosestApproach& x = fast.approaches[k];
        const ClosestApproach& y = brute.approaches[k];
        if (x.a != y.a || x.b != y.b || x.time_s != y.time_s || x.clearance_m != y.clearance_m || x.distance_m != y.distance_m ||
            !(x.a_position == y.a_position) || !(x.b_position == y.b_position)) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "approach %zu-%zu: %.3f s %.6f m vs %zu-%zu: %.3f s %.6f m", x.a, x.b, x.time_s - t0,
                          x.clearance_m, y.a, y.b, y.time_s - t0, y.clearance_m);
            say(buf);
        }
    }
    return out;
}

/// GEOS distance between the two hulls an event reports (read back from lon/lat).
double geos_distance(const geo::GeosContext& ctx, const Encounter& e) {
    auto poly = [&](const std::vector<geo::LonLat>& ring) {
        std::vector<XY> xy;
        for (const geo::LonLat& p : ring) xy.push_back(local(p));
        return test::polygon(ctx, {xy});
    };
    double d = NAN;
    GEOSDistance_r(ctx, poly(e.a.hull).get(), poly(e.b.hull).get(), &d);
    return d;
}

TEST(Encounters, RandomExercisesAgreeWithBruteForcePairing) {
    const geo::GeosContext ctx;
    std::mt19937_64 rng(2024);
    std::size_t disagreements = 0, geos_disagreements = 0, collisions = 0, close = 0, approaches = 0, pairs = 0;
    for (int k = 0; k < 20; ++k) {
        // Mostly small exercises; the last four crowded (40-60 ships), so the broad phase's
        // candidate list is rebuilt often and ships enter and leave between builds.
        const Exercise x = k < 16 ? random_exercise(rng, 8 + rng() % 20, 1500 + 1500 * (k % 3)) : random_exercise(rng, 40 + rng() % 21, 2500);
        EncounterOptions o;
        o.ship_margin_m = k % 2 == 0 ? 20 : 60;
        if (k % 5 == 4) o.threshold_m = 150;  // a fixed threshold smaller than some pairs need
        const EncounterResult fast = x.run(o);
        const EncounterResult brute = x.brute(o);
        const auto diff = differences(fast, brute);
        disagreements += diff.size();
        for (std::size_t d = 0; d < diff.size() && d < 5; ++d) ADD_FAILURE() << "exercise " << k << ": " << diff[d];
        collisions += count(fast, EncounterKind::collision);
        close += count(fast, EncounterKind::close_quarters);
        approaches += fast.approaches.size();
        pairs += fast.pairs_checked;
        for (const Encounter& e : fast.events) {
            EXPECT_LE(e.start_s, e.end_s);
            EXPECT_LT(e.a.track, e.b.track);
            if (e.kind == EncounterKind::close_quarters) {
                EXPECT_LT(e.min_clearance_m, o.ship_margin_m);
            }
            // The hulls the event reports, checked with GEOS: touching at a collision's first
            // contact, the least clearance apart at close quarters.
            const double d = geos_distance(ctx, e);
            if (!(std::fabs(d - e.min_clearance_m) < 1e-5) && ++geos_disagreements <= 5)
                ADD_FAILURE() << "exercise " << k << ": " << to_string(e.kind) << " " << e.a.track << "-" << e.b.track << " at "
                              << e.start_s - t0 << " s: clearance " << e.min_clearance_m << ", GEOS " << d;
        }
        // The fast path computes far fewer hull pairs than it checks.
        EXPECT_LE(fast.hull_checks, brute.hull_checks);
    }
    EXPECT_EQ(disagreements, 0u);
    EXPECT_EQ(geos_disagreements, 0u);
    EXPECT_GT(collisions, 10u);
    EXPECT_GT(close, 10u);
    EXPECT_GT(approaches, 100u);
    std::printf("random exercises: %zu collisions, %zu close quarters, %zu approaches, %zu pair checks; "
                "%zu disagreements with the brute force, %zu with GEOS\n",
                collisions, close, approaches, pairs, disagreements, geos_disagreements);
}

}  // namespace
}  // namespace shoal::audit
