// Sweeping hulls along tracks: hand-made tracks with known answers (a spit crossed between
// fixes, an island crossed, a pier touched, open water, a gap), and random tracks near a
// real coastline swept with the grid detector and with the brute-force traversal.

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include <shoal/sweep/evidence.hpp>
#include <shoal/sweep/sweep.hpp>
#include <shoal/track/kinematics.hpp>
#include <shoal/check/brute_force.hpp>

namespace shoal::audit {
namespace {

using geo::XY;

/// The brute-force traversal behind the PoseChecker interface, with the detector's search
/// limit applied so both sweeps sample the same moments.
class BruteChecker final : public PoseChecker {
public:
    BruteChecker(std::vector<coast::LocalPolyline> lines, const hull::Hull& hull) : m_brute(std::move(lines), hull), m_hull(hull) {}
    check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const override {
        check::Contact c = m_brute.check(pose);
        if (c.clearance_m > options.max_clearance_m) c.clearance_m = INFINITY;
        return c;
    }
    const hull::Hull& hull() const override { return m_hull; }

private:
    check::BruteForce m_brute;
    hull::Hull m_hull;
};

/// A frame centred at (0, 0) lon/lat; hand-made shapes are written in its metres.
const geo::LocalFrame& frame() {
    static const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({0.0, 0.0});
    return f;
}

coast::LocalPolyline land(std::vector<XY> ring) {
    ring.push_back(ring.front());
    return {std::move(ring), true};
}

/// A track through local points (metres) at `speed_ms`, headings along the legs.
track::Track track_through(const std::vector<XY>& pts, double speed_ms, double t0 = 1.7e9) {
    track::Track t;
    t.id = "test";
    t.file = "hand-made";
    double time = t0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (i > 0) time += geo::distance(pts[i - 1], pts[i]) / speed_ms;
        const XY next = i + 1 < pts.size() ? pts[i + 1] : pts[i];
        const XY prev = i > 0 ? pts[i - 1] : pts[i];
        const XY dir = i + 1 < pts.size() ? next - pts[i] : pts[i] - prev;
        track::Fix f;
        f.time_s = time;
        f.position = frame().inverse(pts[i]);
        f.line = i + 2;
        // Grid heading ~ true heading at the frame's centre (convergence ~0 near lon 0).
        f.heading_used_deg = std::fmod(std::atan2(dir.x, dir.y) * 180 / std::numbers::pi + 360, 360);
        f.heading_source = track::HeadingSource::cog;
        t.fixes.push_back(f);
    }
    return t;
}

struct World {
    std::vector<coast::LocalPolyline> lines;
    grid::CoastGrid grid;
    hull::Hull hull = hull::Hull::from_dimensions({80, 20, 8, 8});
    explicit World(std::vector<coast::LocalPolyline> l, double cell = 200)
        : lines(std::move(l)), grid(grid::CoastGrid::build(lines, frame(), cell)) {}
    TrackResult sweep(const track::Track& t, SweepOptions o = {}) const {
        return sweep_track(t, frame(), DetectorChecker(grid, hull), o);
    }
    TrackResult brute_sweep(const track::Track& t, SweepOptions o = {}) const {
        return sweep_track(t, frame(), BruteChecker(lines, hull), o);
    }
};

std::size_t count(const TrackResult& r, EventKind k) {
    return static_cast<std::size_t>(std::count_if(r.events.begin(), r.events.end(), [&](const Event& e) { return e.kind == k; }));
}

TEST(Sweep, ThinSpitCrossedBetweenFixesIsAGrounding) {
    // A spit 1 m wide across the track; fixes 2 km apart on either side never touch it.
    World w({land({{-3000, 999.5}, {3000, 999.5}, {3000, 1000.5}, {-3000, 1000.5}}),
             land({{-5000, -5000}, {-4900, -5000}, {-4900, -4900}})});
    const track::Track t = track_through({{0, 0}, {0, 2000}}, 5.0);
    const TrackResult r = w.sweep(t);
    ASSERT_EQ(count(r, EventKind::grounding), 1u);
    const Event& g = r.events[0].kind == EventKind::grounding ? r.events[0] : r.events[1];
    // First contact: the bow (80 m ahead) reaches y = 999.5 when the position is at 919.5.
    EXPECT_NEAR(g.start_s - t.fixes[0].time_s, 919.5 / 5.0, 0.05);
    EXPECT_NEAR(frame().forward(g.point).y, 999.5, 0.5);
    EXPECT_EQ(g.fix_index, 0u);
    // The stern (20 m aft) leaves y = 1000.5 when the position is at 1020.5.
    EXPECT_NEAR(g.end_s - t.fixes[0].time_s, 1020.5 / 5.0, 0.05);
    // Approach and departure are close passes? No: they are part of one interval under the
    // margin that reaches contact, so only the grounding is reported.
    EXPECT_EQ(count(r, EventKind::close_pass), 0u);
}

TEST(Sweep, TrackOverTheMiddleOfAnIslandIsAGrounding) {
    World w({land({{-10000, 5000}, {10000, 5000}, {10000, 25000}, {-10000, 25000}})}, 500);
    // Fixes 10 km apart: one before the island, one in its middle (far from any segment), one beyond.
    // 1,000 s between fixes: a max gap of an hour sweeps across them.
    SweepOptions o;
    o.max_gap_s = 3600;
    const TrackResult r = w.sweep(track_through({{0, 0}, {0, 15000}, {0, 30000}}, 10.0), o);
    ASSERT_EQ(count(r, EventKind::grounding), 1u);
    EXPECT_GT(r.events[0].penetration_m, 9000);  // at the middle fix the hull is ~10 km inside
}

TEST(Sweep, TrackTouchingAPierEndIsAGrounding) {
    // A pier 4 m wide reaching east to x = -3; the ship heads north, its port side (c = 8)
    // 8 m west of its track.
    World w({land({{-100, 490}, {-100, 494}, {-3, 494}, {-3, 490}})});
    const TrackResult touching = w.sweep(track_through({{4, 0}, {4, 1000}}, 5.0));  // port side at x = -4: 1 m over the pier end
    EXPECT_EQ(count(touching, EventKind::grounding), 1u);
    const TrackResult clear = w.sweep(track_through({{25, 0}, {25, 1000}}, 5.0));  // port side at x = 17: 20 m off
    EXPECT_EQ(count(clear, EventKind::grounding), 0u);
    ASSERT_EQ(count(clear, EventKind::close_pass), 1u);
    EXPECT_NEAR(clear.events[0].min_clearance_m, 20.0, 0.01);
}

TEST(Sweep, CleanTrackInOpenWaterHasNoEvents) {
    World w({land({{0, 0}, {100, 0}, {100, 100}, {0, 100}}), land({{20000, 20000}, {20100, 20000}, {20100, 20100}})}, 500);
    SweepOptions o;
    o.max_gap_s = 3600;
    const TrackResult r = w.sweep(track_through({{5000, 2000}, {15000, 9000}, {9000, 15000}}, 8.0), o);
    EXPECT_TRUE(r.events.empty());
    EXPECT_EQ(r.summary.fixes, 3u);
    EXPECT_EQ(r.summary.uncovered_fixes, 0u);
    EXPECT_GT(r.summary.min_clearance_m, 50.0);
    // Open water: the lookahead lets the sweep skip most checks.
    EXPECT_LT(r.summary.poses, r.summary.distance_m / 5.0 / 4.0);
}

TEST(Sweep, GapSplitsTheTrackAndNothingIsSweptAcrossIt) {
    World w({land({{-3000, 999.5}, {3000, 999.5}, {3000, 1000.5}, {-3000, 1000.5}})});
    // The same crossing, but the fixes are 700 s apart: a gap over --max-gap 600.
    const track::Track t = track_through({{0, 0}, {0, 2000}}, 2000.0 / 700.0);
    const TrackResult r = w.sweep(t);
    EXPECT_EQ(r.summary.gaps, 1u);
    EXPECT_EQ(r.summary.segments, 2u);
    EXPECT_EQ(count(r, EventKind::grounding), 0u);
    SweepOptions longer;
    longer.max_gap_s = 800;
    EXPECT_EQ(count(w.sweep(t, longer), EventKind::grounding), 1u);
}

TEST(Sweep, FixesOutsideTheCoastlineAreaAreUncovered) {
    World w({land({{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}})});
    const TrackResult r = w.sweep(track_through({{500, 1500}, {500, 1800}, {500, 5000}}, 5.0));
    EXPECT_EQ(r.summary.uncovered_fixes, 3u);  // the grid covers the island's box only
}

/// The grid detector, counting the checks that reach it.
class CountingChecker final : public PoseChecker {
public:
    CountingChecker(const grid::CoastGrid& grid, const hull::Hull& hull) : m_inner(grid, hull) {}
    check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const override {
        ++calls;
        return m_inner.check(pose, options);
    }
    const hull::Hull& hull() const override { return m_inner.hull(); }
    const grid::CoastGrid* grid() const override { return m_inner.grid(); }
    bool covered(const check::LocalPose& pose) const override { return m_inner.covered(pose); }
    mutable std::size_t calls = 0;

private:
    DetectorChecker m_inner;
};

/// A day at anchor off an island: 8,640 fixes 10 s apart.
track::Track day_at_anchor(XY where, double heading_deg, double jitter_m, double swing_deg, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(-1, 1);
    track::Track t;
    t.id = "anchored";
    double hdg = heading_deg;
    for (std::size_t i = 0; i < 8640; ++i) {
        track::Fix f;
        f.time_s = 1.7e9 + 10.0 * static_cast<double>(i);
        f.position = frame().inverse(where + XY{jitter_m * unit(rng), jitter_m * unit(rng)});
        f.heading_used_deg = hdg;
        f.heading_source = track::HeadingSource::heading;
        f.line = i + 2;
        t.fixes.push_back(f);
        hdg = std::fmod(hdg + swing_deg * unit(rng) + 360, 360);
    }
    return t;
}

TEST(Sweep, StandingStillForADayCostsOneCheckPerFix) {
    World w({land({{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}})});
    // Still and clear, 200 m off: every fix checked, nothing between them, no event.
    const TrackResult clear = w.sweep(day_at_anchor({500, -200}, 90, 0, 0, 1));
    EXPECT_TRUE(clear.events.empty());
    EXPECT_EQ(clear.summary.poses, 8640u);
    EXPECT_EQ(clear.summary.distance_m, 0.0);
    // Still and aground from the first fix: one contact lasting the whole day (not a
    // grounding: it was never seen begin), and two real checks, not one per fix (a pose deep in
    // land costs a penetration search; an unchanged pose reuses the last answer): the fix's,
    // and the event's first sample again for the polyline that holds the hull (what it hit),
    // which the sweep's checks leave out.
    const CountingChecker counted(w.grid, w.hull);
    const TrackResult aground = sweep_track(day_at_anchor({500, 20}, 90, 0, 0, 2), frame(), counted, {});
    EXPECT_EQ(counted.calls, 2u);
    ASSERT_EQ(aground.events.size(), 1u);
    EXPECT_EQ(aground.events[0].kind, EventKind::contact_at_start);
    EXPECT_EQ(aground.events[0].unseen_after, "track start");
    EXPECT_DOUBLE_EQ(aground.events[0].start_s, 1.7e9);
    EXPECT_DOUBLE_EQ(aground.events[0].end_s, 1.7e9 + 10.0 * 8639);
    EXPECT_LE(aground.summary.poses, 8640u + 10u);
}

TEST(Sweep, SwingingAtAnchorForADayAgreesWithBruteForce) {
    // 60 m off the island with an 80 m bow, GPS jitter of 3 m and the heading swinging up to
    // 30 degrees between fixes: the bow touches the shore now and then.
    World w({land({{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}})});
    const track::Track t = day_at_anchor({500, -60}, 0, 3, 30, 3);
    const TrackResult a = w.sweep(t);
    const TrackResult b = w.brute_sweep(t);
    EXPECT_GT(count(a, EventKind::alongside), 10u) << "at anchor, the jitter no speed: every touch is alongside";
    EXPECT_EQ(count(a, EventKind::grounding), 0u);
    ASSERT_EQ(a.events.size(), b.events.size());
    for (std::size_t e = 0; e < a.events.size(); ++e) {
        EXPECT_EQ(a.events[e].kind, b.events[e].kind) << e;
        EXPECT_NEAR(a.events[e].start_s, b.events[e].start_s, 1e-6) << e;
        EXPECT_NEAR(a.events[e].end_s, b.events[e].end_s, 1e-6) << e;
    }
    EXPECT_EQ(a.summary.poses, b.summary.poses);
    EXPECT_LT(a.summary.poses, 8640u * 20u);  // bounded by the swing, not by the day
}

/// The Solent's land (tests/data) in a transverse Mercator frame at its centre, as a grid of
/// 500 m cells.
struct Solent {
    coast::Coastline coast = coast::import_coastline({SHOAL_TEST_DATA "coast/uk_solent_land.geojson"});
    geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
    std::vector<coast::LocalPolyline> lines = coast::project(coast, frame);
    grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
};

/// Random tracks near the Solent coast: the grid sweep and the brute-force sweep report the
/// same events (same sampling, so exactly the same).
TEST(Sweep, RandomTracksAgreeWithBruteForceSweep) {
    const Solent solent;
    const geo::LocalFrame& f = solent.frame;
    const auto& lines = solent.lines;
    const grid::CoastGrid& grid = solent.grid;
    const hull::Hull hull = hull::Hull::from_dimensions({60, 15, 6, 6});
    const DetectorChecker fast(grid, hull);
    const BruteChecker slow(lines, hull);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    std::size_t groundings = 0, passes = 0;
    for (int k = 0; k < 12; ++k) {
        // Start near a random coast vertex, wander 6 legs of ~400 m.
        const auto& l = lines[rng() % lines.size()];
        XY p = l.points[rng() % l.points.size()] + XY{(unit(rng) - 0.5) * 600, (unit(rng) - 0.5) * 600};
        track::Track t;
        t.id = "random" + std::to_string(k);
        double time = 1.6e9, hdg = 360 * unit(rng);
        for (int i = 0; i < 7; ++i) {
            track::Fix fix;
            fix.time_s = time;
            fix.position = f.inverse(p);
            fix.heading_used_deg = hdg;
            fix.line = static_cast<std::size_t>(i + 1);
            t.fixes.push_back(fix);
            hdg = std::fmod(hdg + (unit(rng) - 0.5) * 90 + 360, 360);
            const double h = hdg * std::numbers::pi / 180;
            p = p + 400.0 * XY{std::sin(h), std::cos(h)};
            time += 80;
        }
        const TrackResult a = sweep_track(t, f, fast, {});
        const TrackResult b = sweep_track(t, f, slow, {});
        ASSERT_EQ(a.events.size(), b.events.size()) << t.id;
        for (std::size_t e = 0; e < a.events.size(); ++e) {
            EXPECT_EQ(a.events[e].kind, b.events[e].kind) << t.id;
            EXPECT_NEAR(a.events[e].start_s, b.events[e].start_s, 1e-6) << t.id;
            EXPECT_NEAR(a.events[e].end_s, b.events[e].end_s, 1e-6) << t.id;
            EXPECT_NEAR(a.events[e].min_clearance_m, b.events[e].min_clearance_m, 1e-6) << t.id;
        }
        EXPECT_EQ(a.summary.poses, b.summary.poses) << t.id;
        groundings += count(a, EventKind::grounding);
        passes += count(a, EventKind::close_pass);
    }
    EXPECT_GT(groundings, 0u) << "the random tracks should meet land sometimes";
    EXPECT_GT(passes, 0u) << "the random tracks should pass close sometimes";
}

/// Everything a sweep reports about its events, poses and figures, compared exactly.
void expect_same_results(const TrackResult& a, const TrackResult& b, const std::string& what) {
    ASSERT_EQ(a.events.size(), b.events.size()) << what;
    for (std::size_t e = 0; e < a.events.size(); ++e) {
        const Event &x = a.events[e], &y = b.events[e];
        SCOPED_TRACE(what + " event " + std::to_string(e));
        EXPECT_EQ(x.kind, y.kind);
        EXPECT_EQ(x.start_s, y.start_s);
        EXPECT_EQ(x.end_s, y.end_s);
        EXPECT_EQ(x.min_clearance_m, y.min_clearance_m);
        EXPECT_EQ(x.penetration_m, y.penetration_m);
        EXPECT_EQ(x.point, y.point);
        EXPECT_EQ(x.ship, y.ship);
        EXPECT_EQ(x.hull, y.hull);
        EXPECT_EQ(x.fix_index, y.fix_index);
        EXPECT_EQ(x.hit, y.hit);
        EXPECT_TRUE(x.reference_inside_m == y.reference_inside_m || (std::isnan(x.reference_inside_m) && std::isnan(y.reference_inside_m)));
        EXPECT_EQ(x.reported_aground, y.reported_aground);
    }
    ASSERT_EQ(a.poses.size(), b.poses.size()) << what;
    for (std::size_t k = 0; k < a.poses.size(); ++k) {
        EXPECT_EQ(a.poses[k].contact, b.poses[k].contact) << what << " pose " << k;
        EXPECT_EQ(a.poses[k].clearance_m, b.poses[k].clearance_m) << what << " pose " << k;
        EXPECT_EQ(a.poses[k].covered, b.poses[k].covered) << what << " pose " << k;
        EXPECT_EQ(a.poses[k].time_s, b.poses[k].time_s) << what << " pose " << k;
    }
    EXPECT_EQ(a.summary.poses, b.summary.poses) << what;
    EXPECT_EQ(a.summary.min_clearance_m, b.summary.min_clearance_m) << what;
    EXPECT_EQ(a.summary.uncovered_fixes, b.summary.uncovered_fixes) << what;
    EXPECT_EQ(a.summary.groundings, b.summary.groundings) << what;
    EXPECT_EQ(a.summary.alongside, b.summary.alongside) << what;
    EXPECT_EQ(a.summary.close_passes, b.summary.close_passes) << what;
}

/// The events of `a` at the moments of the brute-force sweep's (to 1 us and 1 um: it knows no
/// chart's edge and no penetration, so only kinds, times and least clearances are compared).
void expect_same_moments(const TrackResult& a, const TrackResult& brute, const std::string& what) {
    ASSERT_EQ(a.events.size(), brute.events.size()) << what;
    for (std::size_t e = 0; e < brute.events.size(); ++e) {
        EXPECT_EQ(a.events[e].kind, brute.events[e].kind) << what << " event " << e;
        EXPECT_NEAR(a.events[e].start_s, brute.events[e].start_s, 1e-6) << what << " event " << e;
        EXPECT_NEAR(a.events[e].end_s, brute.events[e].end_s, 1e-6) << what << " event " << e;
        EXPECT_NEAR(a.events[e].min_clearance_m, brute.events[e].min_clearance_m, 1e-6) << what << " event " << e;
    }
}

/// SweepOptions::carry_over at fixes far from the coast: a fix's check searches further than
/// the lookahead, and the next fixes that cannot have come within it are not checked (a day of
/// AIS in open water). Sparse fixes (30-600 m apart, a gap now and then) in and out of the
/// search around the Solent's shores, some with the heading unknown (the hull's circle), swept
/// with answers carried and with every pose checked: the same events, poses and figures; on
/// some, the moments of the brute-force sweep; and fewer fix checks.
TEST(Sweep, FixesProvedBeyondTheSearchAreTheFullChecks) {
    const Solent solent;
    const geo::LocalFrame& f = solent.frame;
    const grid::CoastGrid& grid = solent.grid;
    const hull::Hull hull = hull::Hull::from_dimensions({120, 25, 10, 12});
    const CountingChecker fast(grid, hull);
    const CountingChecker round(grid, circle_hull(hull));
    const BruteChecker slow(solent.lines, hull);
    const SweepContext ctx{.unknown_heading = &round};
    SweepOptions carry, every;
    every.carry_over = false;
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> unit(0, 1);
    const geo::Box ext = grid.extent();
    std::size_t saved = 0, fixes = 0, beyond = 0, near = 0, watched = 0;
    for (int k = 0; k < 40; ++k) {
        track::Track t;
        t.id = "sparse" + std::to_string(k);
        XY p{ext.minx + (ext.maxx - ext.minx) * unit(rng), ext.miny + (ext.maxy - ext.miny) * unit(rng)};
        double time = 1.7e9, hdg = 360 * unit(rng);
        const double spacing = 30 + 570 * unit(rng) * unit(rng);
        for (int i = 0; i < 80; ++i) {
            track::Fix fix;
            fix.time_s = time;
            fix.position = f.inverse(p);
            fix.heading_used_deg = hdg;
            fix.heading_source = k % 5 == 3 && i % 7 < 2 ? track::HeadingSource::none : track::HeadingSource::heading;
            fix.line = static_cast<std::size_t>(i + 2);
            t.fixes.push_back(fix);
            hdg = std::fmod(hdg + (unit(rng) - 0.5) * 20 + 360, 360);
            const double h = hdg * std::numbers::pi / 180;
            p = p + spacing * (0.5 + unit(rng)) * XY{std::sin(h), std::cos(h)};
            time += unit(rng) < 0.03 ? 900 : 30;  // a gap now and then: a new piece
        }
        fast.calls = round.calls = 0;
        const TrackResult all = sweep_track(t, f, fast, every, ctx);
        const std::size_t full_calls = fast.calls + round.calls;
        fast.calls = round.calls = 0;
        const TrackResult carried = sweep_track(t, f, fast, carry, ctx);
        const std::size_t calls = fast.calls + round.calls;
        ASSERT_LE(calls, full_calls) << t.id;
        saved += full_calls - calls;
        fixes += t.fixes.size();
        expect_same_results(carried, all, t.id);
        for (const Pose& q : carried.poses) ++(std::isinf(q.clearance_m) ? beyond : near);
        if (k % 2 == 0) {  // the clearance watched (an assessment's): the same samples kept
            SweepOptions carry_watch = carry, every_watch = every;
            carry_watch.watch_clearance_m = every_watch.watch_clearance_m = 150;
            const TrackResult a = sweep_track(t, f, fast, carry_watch, ctx), b = sweep_track(t, f, fast, every_watch, ctx);
            expect_same_results(a, b, t.id + " watched");
            ASSERT_EQ(a.clearance.size(), b.clearance.size()) << t.id;
            for (std::size_t j = 0; j < a.clearance.size(); ++j) {
                const ClearanceSample &x = a.clearance[j], &y = b.clearance[j];
                EXPECT_TRUE(x.time_s == y.time_s && x.clearance_m == y.clearance_m && x.ship == y.ship && x.covered == y.covered &&
                            x.after_break == y.after_break)
                    << t.id << " watched sample " << j;
            }
            watched += a.clearance.size();
        }
        if (k % 5 != 0) continue;
        // The brute force (no chart's edge, no penetration): the same moments.
        const TrackResult brute = sweep_track(t, f, slow, carry);
        const TrackResult mine = sweep_track(t, f, fast, carry);
        expect_same_moments(mine, brute, t.id);
    }
    std::printf("%zu fixes, %zu poses kept beyond the search and %zu within it, %zu checks saved\n", fixes, beyond, near, saved);
    EXPECT_GT(beyond, 200u) << "too few poses beyond the search to mean anything";
    EXPECT_GT(near, 50u) << "too few poses near the coast to mean anything";
    EXPECT_GT(watched, 100u) << "too few clearance samples watched to mean anything";
    EXPECT_GT(saved, fixes / 4) << "the carried answers saved no checks";
}

/// A vessel on a straight course 3 km off the coast, a fix every 50 m: nothing within the
/// search anywhere, and a fix's check proves the next several clear of it; each fix's answer
/// is still nothing within the search.
TEST(Sweep, OpenWaterCostsACheckEveryFewFixes) {
    World w({land({{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}})});
    track::Track t;
    t.id = "open";
    for (int i = 0; i < 400; ++i) {
        track::Fix fix;
        fix.time_s = 1.7e9 + 10.0 * i;
        fix.position = frame().inverse({-10000 + 50.0 * i, -3000});
        fix.heading_used_deg = 90;
        fix.heading_source = track::HeadingSource::heading;
        fix.line = static_cast<std::size_t>(i + 2);
        t.fixes.push_back(fix);
    }
    const CountingChecker counted(w.grid, w.hull);
    SweepOptions every;
    every.carry_over = false;
    const TrackResult all = sweep_track(t, frame(), counted, every);
    EXPECT_EQ(counted.calls, 400u);  // every fix, nothing between (the lookahead covers 50 m)
    counted.calls = 0;
    const TrackResult carried = sweep_track(t, frame(), counted, {});
    expect_same_results(carried, all, "open water");
    EXPECT_LE(counted.calls, 400u / 4) << "a fix's check proves the next fixes clear";
    EXPECT_GE(counted.calls, 400u / 11) << "a check reaches no further than the lookahead (500 m, ten fixes) ahead";
    for (const Pose& q : carried.poses) EXPECT_TRUE(std::isinf(q.clearance_m));
}

/// SweepOptions::carry_over: the poses after a fix deep in contact are not checked while the
/// hull cannot have left it; every answer is still that of the full check. Tracks that cross
/// land (straight legs over the Solent's islands and shores, and off the chart's edge),
/// vessels alongside with GPS jitter and a swinging heading, swept with the contact carried
/// and with every pose checked: the same events, poses and figures; and the same moments as the
/// brute-force traversal (which reports no penetration, so it carries nothing).
TEST(Sweep, CarriedContactsAreTheFullChecks) {
    const Solent solent;
    const geo::LocalFrame& f = solent.frame;
    const auto& lines = solent.lines;
    const grid::CoastGrid& grid = solent.grid;
    const hull::Hull hull = hull::Hull::from_dimensions({60, 15, 6, 6});
    const CountingChecker fast(grid, hull);
    const BruteChecker slow(lines, hull);
    SweepOptions carry, every;
    every.carry_over = false;
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> unit(0, 1);
    std::size_t contacts = 0, saved = 0, passes = 0;
    const geo::Box ext = grid.extent();
    for (int k = 0; k < 36; ++k) {
        track::Track t;
        t.id = "crossing" + std::to_string(k);
        const auto& l = lines[rng() % lines.size()];
        const std::size_t v = rng() % (l.points.size() - 1);
        XY p = l.points[v];
        if (k % 6 == 5) p = {ext.minx + 300 * unit(rng), ext.miny + (ext.maxy - ext.miny) * unit(rng)};  // near the chart's edge
        const bool alongside = k % 3 == 0;
        double time = 1.6e9, hdg = 360 * unit(rng);
        const bool passing = k % 6 == 2 || k % 6 == 4;
        if (passing) {  // along the shore, 30-48 m off it (either side)
            const XY d = l.points[v + 1] - l.points[v];
            const double len = std::max(1e-6, std::hypot(d.x, d.y)), side = unit(rng) < 0.5 ? -1.0 : 1.0;
            p = p + side * (30 + 18 * unit(rng)) * XY{d.y / len, -d.x / len};
            hdg = std::fmod(std::atan2(d.x, d.y) * 180 / std::numbers::pi + 360, 360);
        }
        const double step = alongside ? 0 : passing ? 5 + 5 * unit(rng) : 20 + 60 * unit(rng);  // metres per fix
        for (int i = 0; i < (alongside ? 400 : passing ? 30 : 60); ++i) {
            track::Fix fix;
            fix.time_s = time;
            const XY jitter = alongside ? XY{3 * (unit(rng) - 0.5), 3 * (unit(rng) - 0.5)} : XY{0, 0};
            fix.position = f.inverse(p + jitter);
            fix.heading_used_deg = alongside ? std::fmod(hdg + 20 * (unit(rng) - 0.5) + 360, 360) : hdg;
            fix.heading_source = track::HeadingSource::heading;
            fix.line = static_cast<std::size_t>(i + 2);
            t.fixes.push_back(fix);
            if (!alongside) {
                hdg = std::fmod(hdg + (unit(rng) - 0.5) * (passing ? 1 : 6) + 360, 360);
                const double h = hdg * std::numbers::pi / 180;
                p = p + step * XY{std::sin(h), std::cos(h)};
            }
            time += 10;
        }
        fast.calls = 0;
        const TrackResult every_pose = sweep_track(t, f, fast, every);
        const std::size_t full_calls = fast.calls;
        fast.calls = 0;
        const TrackResult carried = sweep_track(t, f, fast, carry);
        saved += full_calls - fast.calls;
        expect_same_results(carried, every_pose, t.id);
        // No poses kept (check --no-project): none, and all else the same.
        SweepOptions no_poses = carry;
        no_poses.keep_poses = false;
        TrackResult lean = sweep_track(t, f, fast, no_poses);
        EXPECT_TRUE(lean.poses.empty()) << t.id;
        EXPECT_FALSE(carried.poses.empty()) << t.id;
        EXPECT_EQ(lean.summary.lines, carried.summary.lines) << t.id;
        lean.poses = carried.poses;
        expect_same_results(lean, carried, t.id + " without poses");
        contacts += carried.summary.groundings + carried.summary.alongside + carried.summary.contacts_at_start;
        passes += carried.summary.close_passes;
        if (k % 4 != 1) continue;
        // The brute force knows no chart's edge and no penetration: the moments and the checks.
        const TrackResult brute = sweep_track(t, f, slow, carry);
        expect_same_moments(carried, brute, t.id);
        EXPECT_EQ(carried.summary.poses, brute.summary.poses) << t.id;
    }
    std::printf("carried over: %zu contacts, %zu close passes, %zu checks saved\n", contacts, passes, saved);
    EXPECT_GT(contacts, 10u) << "too few contacts to mean anything";
    EXPECT_GT(passes, 5u) << "too few close passes to mean anything";
    EXPECT_GT(saved, 1000u) << "the carried contacts saved no checks";
}

}  // namespace
}  // namespace shoal::audit

#include "sweep/local_track.hpp"

namespace shoal::audit {
namespace {

/// project_fixes takes the Jacobian from linear models around anchors every ~2 km; it must
/// match the frame's own Jacobian at each fix to far better than 2.5e-5 (1 cm over 400 m),
/// also 60 km from the central meridian at 60 N, on a track that wanders off its anchor line.
TEST(LocalTrack, JacobianFromAnchorsMatchesTheFrameAtEveryFix) {
    const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({24.0, 60.0});
    track::Track t;
    t.id = "wander";
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(-1, 1);
    geo::LonLat p{25.0, 60.2};
    for (int i = 0; i < 3000; ++i) {
        track::Fix fix;
        fix.time_s = 1.7e9 + i;
        fix.position = p;
        t.fixes.push_back(fix);
        p = {p.lon + 0.004 * unit(rng), p.lat + 0.002 * unit(rng)};  // a few hundred metres a step, any way
    }
    const std::vector<LocalFix> local = project_fixes(t, f);
    double worst = 0;
    for (std::size_t i = 0; i < t.fixes.size(); i += 7)
        worst = std::max(worst, (local[i].jacobian - f.jacobian(t.fixes[i].position)).cwiseAbs().maxCoeff());
    EXPECT_LT(worst, 1e-6);
    std::printf("worst Jacobian element difference: %.3g\n", worst);
}

}  // namespace
}  // namespace shoal::audit

namespace shoal::audit {
namespace {

TEST(Sweep, TheHullsCircleIsContactAtSomeHeadingAgainstBruteForceOverHeadings) {
    // An island and a pier; random positions around them. The circle's clearance must be the
    // least clearance of the hull over all headings (brute force over 720 headings), to within
    // the 36-gon's overshoot (0.4 % of the radius) and the heading sampling.
    World w({land({{0, 0}, {600, 0}, {600, 400}, {300, 700}, {0, 400}}), land({{900, 200}, {1300, 200}, {1300, 204}, {900, 204}})});
    const hull::Hull circle = circle_hull(w.hull);
    const double r = w.hull.radius();
    EXPECT_NEAR(circle.radius(), r / std::cos(std::numbers::pi / 36), 1e-9);
    const DetectorChecker by_circle(w.grid, circle);
    const BruteChecker brute(w.lines, w.hull);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> ux(-300, 1600), uy(-300, 1000);
    std::size_t contacts = 0, clear = 0;
    for (int k = 0; k < 300; ++k) {
        const XY p{ux(rng), uy(rng)};
        double least = INFINITY;
        for (int h = 0; h < 720; ++h) {
            const check::Contact c = brute.check(check::LocalPose::at(p, h * 0.5), {1e9, false});
            least = std::min(least, c.collision ? 0.0 : c.clearance_m);
        }
        const check::Contact c = by_circle.check(check::LocalPose::at(p, 0), {1e9, false});
        const double got = c.collision ? 0.0 : c.clearance_m;
        if (least == 0) {
            ++contacts;
            EXPECT_TRUE(c.collision) << "contact at some heading is contact of the circle, at " << p.x << "," << p.y;
        } else {
            ++clear;
            EXPECT_LE(got, least + 1e-6) << p.x << "," << p.y;
            EXPECT_GE(got, least - 0.01 * r) << p.x << "," << p.y;
        }
    }
    EXPECT_GT(contacts, 30u);
    EXPECT_GT(clear, 30u);
}

TEST(Sweep, ContactKindsFollowWhatWasObserved) {
    // A straight shore at y = 1000 (land to the north). Hand-derived answers for each rule.
    World w({land({{-5000, 1000}, {5000, 1000}, {5000, 3000}, {-5000, 3000}})}, 500);
    SweepOptions o;
    auto resolved = [&](track::Track t) {
        track::resolve_motion(t, o.motion());
        return t;
    };
    // Under way at 10 kn (5.144 m/s) heading north from y = 0: the bow (80 m ahead) touches
    // at y = 920, 920 / 5.144 s after the start; then it lies there: one grounding.
    {
        track::Track t = track_through({{0, 0}, {0, 940}}, 10 * 1852.0 / 3600);
        for (int i = 1; i <= 30; ++i) {
            track::Fix f = t.fixes.back();
            f.time_s += 10;
            f.line += 1;
            t.fixes.push_back(f);
        }
        const TrackResult r = w.sweep(resolved(t), o);
        ASSERT_EQ(r.events.size(), 1u);
        const Event& e = r.events[0];
        EXPECT_EQ(e.kind, EventKind::grounding);
        EXPECT_NEAR(e.start_s - t.fixes[0].time_s, 920 / (10 * 1852.0 / 3600), 0.05);
        EXPECT_NEAR(e.speed_kn, 10.0, 0.1) << "great-circle metres against the frame's";
        EXPECT_EQ(e.speed_source, track::SpeedSource::positions);
        EXPECT_FALSE(e.stopped_before);
        // Contact at 178.8 s, at the fix (182.7 s) it lies still: stopped from there.
        ASSERT_TRUE(std::isfinite(e.stopped_after_s));
        EXPECT_NEAR(e.stopped_after_s, (940 - 920) / (10 * 1852.0 / 3600), 0.05);
        EXPECT_NEAR(e.reference_inside_m, -80.0, 0.5) << "the reference point is 80 m behind the bow, in water";
        EXPECT_EQ(r.summary.groundings, 1u);
    }
    // The same approach at 0.5 kn: under the berthing speed, alongside.
    {
        const TrackResult r = w.sweep(resolved(track_through({{0, 880}, {0, 930}}, 0.5 * 1852.0 / 3600)), o);
        ASSERT_EQ(r.events.size(), 1u);
        EXPECT_EQ(r.events[0].kind, EventKind::alongside);
        EXPECT_NEAR(r.events[0].speed_kn, 0.5, 0.01);
        o.berthing_speed_kn = 0.4;  // with a lower berthing speed it is a grounding
        EXPECT_EQ(w.sweep(resolved(track_through({{0, 880}, {0, 930}}, 0.5 * 1852.0 / 3600)), o).events[0].kind, EventKind::grounding);
        o.berthing_speed_kn = 1.0;
    }
    // Already in contact at the first fix: not seen begin.
    {
        // Heading south, the stern (20 m aft) is 10 m inside the shore.
        const TrackResult r = w.sweep(resolved(track_through({{0, 990}, {0, -500}}, 5.0)), o);
        ASSERT_FALSE(r.events.empty());
        EXPECT_EQ(r.events[0].kind, EventKind::contact_at_start);
        EXPECT_EQ(r.events[0].unseen_after, "track start");
        EXPECT_EQ(r.summary.groundings, 0u);
    }
    // Lying still 60 m off for 5 min, then pushed 70 m north within one fix
    // interval (a jitter burst, a tug): stopped before the contact, so alongside.
    {
        track::Track t = track_through({{0, 860}}, 1.0);
        for (int i = 1; i <= 30; ++i) {
            track::Fix f = t.fixes.back();
            f.time_s += 10;
            f.line += 1;
            t.fixes.push_back(f);
        }
        track::Fix f = t.fixes.back();
        f.time_s += 6;
        f.position = frame().inverse({0, 930});
        f.line += 1;
        t.fixes.push_back(f);
        const TrackResult r = w.sweep(resolved(t), o);
        ASSERT_EQ(r.events.size(), 1u);
        EXPECT_EQ(r.events[0].kind, EventKind::alongside);
        EXPECT_TRUE(r.events[0].stopped_before);
    }
    // Lying at anchor 600 m off for 5 min, then the next fix 180 s on is on the shore (it ran
    // 640 m at 6.9 kn between them): the stopped fix no longer vouches for the contact, which
    // is a grounding (before: alongside, "stopped before the contact").
    {
        track::Track t = track_through({{0, 300}}, 0.0);
        for (int i = 1; i <= 30; ++i) {
            track::Fix f = t.fixes.back();
            f.time_s += 10;
            f.line += 1;
            t.fixes.push_back(f);
        }
        for (int i = 0; i < 30; ++i) {
            track::Fix f = t.fixes.back();
            f.time_s += i == 0 ? 180 : 10;
            f.position = frame().inverse({0, 940});
            f.line += 1;
            t.fixes.push_back(f);
        }
        const TrackResult r = w.sweep(resolved(t), o);
        ASSERT_EQ(r.events.size(), 1u);
        EXPECT_FALSE(r.events[0].stopped_before);
        EXPECT_EQ(r.events[0].kind, EventKind::grounding);
        EXPECT_NEAR(r.events[0].speed_kn, 640 / 180.0 * 3600 / 1852, 0.1);
    }
}

}  // namespace
}  // namespace shoal::audit

#include "sweep/pose_outline.hpp"
#include "geo/geos_context.hpp"

namespace shoal::audit {
namespace {

/// The poses' outlines (Pose::hull, as the poses layer draws them): the corners kept of the
/// hull's outline placed at the fix (the full outline placed independently here, from the
/// track's motion), in order from the bow tip, within 1 % of the hull's length of the full
/// outline by GEOS's Hausdorff distance, a valid polygon, fewer points; the hull's circle too.
TEST(Sweep, KeptPosesDrawTheHullsOutlineWithinOnePercentOfItsLength) {
    const Solent solent;
    const geo::LocalFrame& f = solent.frame;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    const geo::GeosContext ctx;
    std::size_t poses = 0;
    for (const char* dims : {"60,15,6,6", "150,35,14,14", "12,3,2,2", "300,50,25,25"}) {
        const hull::Hull hull = hull::Hull::from_dims_string(dims);
        const hull::Hull circle = circle_hull(hull);
        const DetectorChecker fast(solent.grid, hull), round(solent.grid, circle);
        for (int k = 0; k < 6; ++k) {
            track::Track t;
            t.id = std::string(dims) + " " + std::to_string(k);
            const geo::Box ext = solent.grid.extent();
            XY p{ext.minx + (ext.maxx - ext.minx) * unit(rng), ext.miny + (ext.maxy - ext.miny) * unit(rng)};
            double hdg = 360 * unit(rng);
            for (int i = 0; i < 40; ++i) {
                track::Fix fix;
                fix.time_s = 1.6e9 + 60.0 * i;
                fix.position = f.inverse(p);
                fix.heading_used_deg = hdg;
                fix.heading_source = k == 5 ? track::HeadingSource::none : track::HeadingSource::heading;
                fix.line = static_cast<std::size_t>(i + 2);
                t.fixes.push_back(fix);
                hdg = std::fmod(hdg + 40 * (unit(rng) - 0.5) + 360, 360);
                const double h = hdg * std::numbers::pi / 180;
                p = p + 300 * XY{std::sin(h), std::cos(h)};
            }
            SweepOptions o;
            o.pose_interval_s = 0;  // every fix
            const SweepContext ctx_circle{.unknown_heading = &round};
            const TrackResult r = sweep_track(t, f, fast, o, k == 5 ? ctx_circle : SweepContext{});
            const LocalTrack motion(t, f);
            ASSERT_EQ(r.poses.size(), t.fixes.size()) << t.id;
            for (const Pose& pose : r.poses) {
                SCOPED_TRACE(t.id + " fix " + std::to_string(pose.fix_index));
                const hull::Hull& used = k == 5 ? circle : hull;
                std::vector<geo::LonLat> full;
                for (const XY& q : check::hull_outline(used, motion.pose({pose.fix_index, 0.0}))) full.push_back(f.inverse(q));
                full.push_back(full.front());
                ASSERT_GE(pose.hull.size(), pose_outline_min_corners + 1);
                EXPECT_LT(pose.hull.size(), full.size()) << "fewer points";
                EXPECT_EQ(pose.hull.front(), full.front()) << "the bow tip (or the circle's first point) is kept";
                EXPECT_EQ(pose.hull.back(), pose.hull.front()) << "closed";
                std::size_t at = 0;
                for (std::size_t i = 0; i + 1 < pose.hull.size(); ++i) {
                    while (at + 1 < full.size() && !(full[at] == pose.hull[i])) ++at;
                    ASSERT_LT(at + 1, full.size()) << "corner " << i << " is one of the outline's own, in order";
                }
                auto local = [&](const std::vector<geo::LonLat>& ring) {
                    std::vector<XY> xy;
                    for (const auto& q : ring) xy.push_back(f.forward(q));
                    return xy;
                };
                const std::vector<XY> a = local(full);
                double length = 0;
                for (const XY& u : a)
                    for (const XY& v : a) length = std::max(length, geo::distance(u, v));
                const geo::GeomPtr ga = geo::make_polygon(ctx, {a}), gb = geo::make_polygon(ctx, {local(pose.hull)});
                double hausdorff = 0;
                ASSERT_EQ(GEOSHausdorffDistance_r(ctx, ga.get(), gb.get(), &hausdorff), 1);
                EXPECT_LE(hausdorff, 0.0101 * length);
                EXPECT_EQ(GEOSisValid_r(ctx, gb.get()), 1);
                ++poses;
            }
        }
    }
    EXPECT_EQ(poses, 4u * 6u * 40u);
}

}  // namespace
}  // namespace shoal::audit

namespace shoal::audit {
namespace {

/// The point a grounding reports is where hull and coast meet at the moment it reports (found
/// by bisection between a clear sample and one in contact): on the coast, and on or inside the
/// hull's outline placed at the event's start, both within a millimetre, by brute force over
/// the coast's segments and the outline's edges. Tracks run into the Solent's shores and
/// islands at 3-12 m per second, a fix every 10 s.
TEST(Sweep, AGroundingsPointIsWhereHullAndCoastMeetAtItsStart) {
    const Solent solent;
    const geo::LocalFrame& f = solent.frame;
    const hull::Hull hull = hull::Hull::from_dimensions({60, 15, 6, 6});
    const DetectorChecker checker(solent.grid, hull);
    std::mt19937_64 rng(115);
    std::uniform_real_distribution<double> unit(0, 1);
    auto coast_dist = [&](XY q) {
        double d2 = INFINITY;
        for (const auto& l : solent.lines)
            for (std::size_t k = 0; k + 1 < l.points.size(); ++k) d2 = std::min(d2, geo::point_segment_dist2(q, l.points[k], l.points[k + 1]));
        return std::sqrt(d2);
    };
    std::size_t groundings = 0;
    for (int k = 0; k < 40; ++k) {
        track::Track t;
        t.id = "into land " + std::to_string(k);
        const auto& l = solent.lines[rng() % solent.lines.size()];
        const double hdg = 360 * unit(rng), h = hdg * std::numbers::pi / 180, speed = 3 + 9 * unit(rng);
        const XY dir{std::sin(h), std::cos(h)};
        XY p = l.points[rng() % l.points.size()] - 300.0 * dir;  // 300 m short of a coast vertex, heading at it
        for (int i = 0; i < 12; ++i, p = p + 10 * speed * dir) {
            track::Fix fix;
            fix.time_s = 1.6e9 + 10.0 * i;
            fix.position = f.inverse(p);
            fix.heading_used_deg = hdg;
            fix.heading_source = track::HeadingSource::heading;
            fix.line = static_cast<std::size_t>(i + 2);
            t.fixes.push_back(fix);
        }
        const TrackResult r = sweep_track(t, f, checker, {});
        const LocalTrack motion(t, f);
        for (const Event& e : r.events) {
            if (e.kind != EventKind::grounding) continue;
            ++groundings;
            std::size_t i = 0;
            while (i + 2 < t.fixes.size() && t.fixes[i + 1].time_s <= e.start_s) ++i;
            const double frac = (e.start_s - t.fixes[i].time_s) / (t.fixes[i + 1].time_s - t.fixes[i].time_s);
            std::vector<XY> ring = check::hull_outline(hull, motion.pose({i, frac}));
            ring.push_back(ring.front());
            const XY q = f.forward(e.point);
            double to_outline2 = INFINITY;
            bool inside = false;
            for (std::size_t v = 0; v + 1 < ring.size(); ++v) {
                const XY a = ring[v], b = ring[v + 1];
                to_outline2 = std::min(to_outline2, geo::point_segment_dist2(q, a, b));
                if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
            }
            EXPECT_LT(coast_dist(q), 1e-3) << t.id << " at " << e.start_s;
            EXPECT_TRUE(inside || std::sqrt(to_outline2) < 1e-3) << t.id << " at " << e.start_s << ": " << std::sqrt(to_outline2) << " m off the hull";
        }
    }
    EXPECT_GT(groundings, 15u) << "too few groundings to mean anything";
}

}  // namespace
}  // namespace shoal::audit

namespace shoal::audit {
namespace {

TEST(Evidence, HowLongAVesselLayThereIsItsWholeVisitNotItsFirstStay) {
    // A ship runs north onto a shore (land from y = 1000) at 5 m/s, its bow 30 m in when it
    // comes to rest (reference at y = 950, slowing over its last 45 m), and lies there 4 h,
    // a fix a minute, GPS jitter of up to 20 m (class B AIS). The first stay's box holds the last of the
    // approach, and jitter breaks it within minutes; the stays after it are the same visit.
    // Before, the event said it lay there for the first stay alone.
    World w({land({{-3000, 1000}, {3000, 1000}, {3000, 3000}, {-3000, 3000}})});
    std::vector<XY> pts;
    for (double y = 0; y <= 900; y += 50) pts.push_back({0, y});
    // A fix `dt` after the last at local point `p`, the last one's data otherwise.
    auto add_to = [](track::Track& k, XY p, double dt) {
        track::Fix f = k.fixes.back();
        f.time_s += dt;
        f.position = frame().inverse(p);
        f.line = k.fixes.size() + 2;
        k.fixes.push_back(f);
    };
    track::Track t = track_through(pts, 5.0);
    auto add = [&](XY p, double dt) { add_to(t, p, dt); };
    for (const double y : {920.0, 935.0, 945.0, 950.0}) add({0, y}, 5);
    std::mt19937_64 rng(36);
    std::uniform_real_distribution<double> jitter(-20, 20);
    const double rest_s = t.fixes.back().time_s;
    for (int k = 0; k < 240; ++k) add({jitter(rng), 950 + jitter(rng)}, 60);
    const double time = t.fixes.back().time_s;
    track::resolve_motion(t);
    TrackResult r = w.sweep(t);
    gather_evidence(t, w.hull.length(), frame(), w.grid, SweepOptions{}, EvidenceOptions{}, r);
    ASSERT_GE(r.stays.size(), 2u) << "jitter must break the stay for this test to mean anything";
    EXPECT_LT(r.stays[0].end_s - r.stays[0].start_s, 3 * 3600.0);
    const auto g = std::find_if(r.events.begin(), r.events.end(), [](const Event& e) { return is_contact(e.kind); });
    ASSERT_NE(g, r.events.end());
    EXPECT_EQ(g->kind, EventKind::grounding);
    // 4 h: from its first stay to the end of its last (the fixes after the last stay, fewer
    // than a stay's five minutes, are none).
    EXPECT_NEAR(g->evidence.stay_s, time - rest_s, 300.0);
    EXPECT_LE(g->evidence.stay_s, time - t.fixes.front().time_s);

    // The same ship floats off after 40 min, backs 200 m off the shore (its bow 130 m clear) and
    // anchors there 5 h: the same visit (within the berth radius), but it lay where it touched
    // for 40 min only.
    track::Track u = track_through(pts, 5.0);
    auto add_u = [&](XY p, double dt) { add_to(u, p, dt); };
    for (const double y : {920.0, 935.0, 945.0, 950.0}) add_u({0, y}, 5);
    for (int k = 0; k < 40; ++k) add_u({jitter(rng) / 4, 950 + jitter(rng) / 4}, 60);
    for (const double y : {900.0, 850.0, 800.0, 750.0}) add_u({0, y}, 30);
    for (int k = 0; k < 300; ++k) add_u({jitter(rng), 750 + jitter(rng)}, 60);
    track::resolve_motion(u);
    TrackResult ru = w.sweep(u);
    gather_evidence(u, w.hull.length(), frame(), w.grid, SweepOptions{}, EvidenceOptions{}, ru);
    const auto gu = std::find_if(ru.events.begin(), ru.events.end(), [](const Event& e) { return is_contact(e.kind); });
    ASSERT_NE(gu, ru.events.end());
    EXPECT_LT(gu->evidence.stay_s, 60 * 60.0) << "the anchorage after it is not lying aground";
    EXPECT_GT(gu->evidence.stay_s, 30 * 60.0);
}

TEST(Evidence, AVesselThatLeftItsAnchorageBetweenSparseFixesIsUnderWayAtTheContact) {
    // At anchor 600 m off a shore (land from y = 1000) for 10 min at 0 kn, a fix every 10 s;
    // the next fix, 3 minutes on, has it on the shore (it ran 640 m at 6.9 kn), lying there
    // an hour. Before: "came to rest at the contact from 0 kn: berthing" (the speed of the
    // anchored fix); the positions say it was under way: a grounding inside a gap of the fixes.
    World w({land({{-3000, 1000}, {3000, 1000}, {3000, 3000}, {-3000, 3000}})});
    track::Track t = track_through({{0, 300}}, 0.0);
    auto add = [&](XY p, double dt) {
        track::Fix f = t.fixes.back();
        f.time_s += dt;
        f.position = frame().inverse(p);
        f.line = t.fixes.size() + 2;
        t.fixes.push_back(f);
    };
    for (int k = 0; k < 60; ++k) add({0, 300}, 10);
    add({0, 940}, 180);
    for (int k = 0; k < 60; ++k) add({0, 940}, 60);
    track::resolve_motion(t);
    TrackResult r = w.sweep(t);
    gather_evidence(t, w.hull.length(), frame(), w.grid, SweepOptions{}, EvidenceOptions{}, r);
    const auto c = std::find_if(r.events.begin(), r.events.end(), [](const Event& e) { return is_contact(e.kind); });
    ASSERT_NE(c, r.events.end());
    EXPECT_FALSE(c->stopped_before);
    EXPECT_GT(c->evidence.speed_before_kn, 6.0) << "from the anchored fix to the contact, not the anchored fix's own";
    const std::size_t at = static_cast<std::size_t>(c - r.events.begin());
    decide_kinds(r, {}, {}, EvidenceOptions{});
    EXPECT_EQ(r.events.at(at).kind, EventKind::grounding) << r.events.at(at).evidence.reason;
}

TEST(Evidence, AStopAfterTheVesselSailedClearOfTheLandIsNotSaidToBeInTheLand) {
    // A ship sails north at 5 m/s through a 200 m strip of charted land (y 1000-1200: a canal,
    // a channel the chart lacks) and stops 1.8 km on, in open water, for an hour. Before: its
    // contact said "went on 2080 m through charted land and came to rest there"; it came to
    // rest in the water, after it was seen clear of the land.
    World w({land({{-3000, 1000}, {3000, 1000}, {3000, 1200}, {-3000, 1200}})});
    std::vector<XY> pts;
    for (double y = 0; y <= 3000; y += 50) pts.push_back({0, y});
    track::Track t = track_through(pts, 5.0);
    for (int k = 0; k < 60; ++k) {
        track::Fix f = t.fixes.back();
        f.time_s += 60;
        f.line = t.fixes.size() + 2;
        t.fixes.push_back(f);
    }
    track::resolve_motion(t);
    TrackResult r = w.sweep(t);
    gather_evidence(t, w.hull.length(), frame(), w.grid, SweepOptions{}, EvidenceOptions{}, r);
    const auto c = std::find_if(r.events.begin(), r.events.end(), [](const Event& e) { return is_contact(e.kind); });
    ASSERT_NE(c, r.events.end());
    ASSERT_NE(c->evidence.stay, static_cast<std::size_t>(-1)) << "the stop in the water is found";
    EXPECT_FALSE(c->evidence.rests_in_contact);
    const std::size_t at = static_cast<std::size_t>(c - r.events.begin());
    decide_kinds(r, {}, {}, EvidenceOptions{});
    const Event& e = r.events.at(at);
    EXPECT_EQ(e.kind, EventKind::alongside) << e.evidence.reason;
    EXPECT_EQ(e.evidence.reason.find("through charted land and came to rest there"), std::string::npos) << e.evidence.reason;
    EXPECT_NE(e.evidence.reason.find("went through charted land and was seen clear of it again, then came to rest 20"), std::string::npos)
        << e.evidence.reason;
    EXPECT_NE(e.evidence.reason.find(" m on: the chart lacks water there"), std::string::npos) << e.evidence.reason;
}

}  // namespace
}  // namespace shoal::audit
