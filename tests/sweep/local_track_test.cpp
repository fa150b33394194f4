// The one "where is this ship at time t" (src/sweep/local_track.hpp): its lookups of a moment
// against a plain scan of the fixes, its breaks, and its placement between fixes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include <shoal/util/error.hpp>

#include "sweep/local_track.hpp"

namespace shoal::audit {
namespace {

using geo::XY;

/// Fixes at irregular times (1-40 s apart) on a wandering course, headings crossing north.
track::Track wandering(const geo::LocalFrame& f, int n, std::uint64_t seed) {
    track::Track t;
    t.id = "wander";
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    XY p{0, 0};
    double time = 1.7e9, hdg = 350;
    for (int i = 0; i < n; ++i) {
        track::Fix fix;
        fix.time_s = time;
        fix.position = f.inverse(p);
        fix.heading_used_deg = hdg;
        fix.heading_source = track::HeadingSource::heading;
        fix.jump_before = i > 0 && unit(rng) < 0.1;
        fix.line = static_cast<std::size_t>(i + 2);
        t.fixes.push_back(fix);
        time += 1 + 39 * unit(rng);
        hdg = std::fmod(hdg + 30 * (unit(rng) - 0.5) + 360, 360);
        p = p + 100 * unit(rng) * XY{std::sin(hdg * std::numbers::pi / 180), std::cos(hdg * std::numbers::pi / 180)};
    }
    return t;
}

/// Random moments over the track's span and a little beyond, and every fix time.
std::vector<double> moments(const track::Track& t, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    const double t0 = t.fixes.front().time_s, t1 = t.fixes.back().time_s;
    std::uniform_real_distribution<double> when(t0 - 30, t1 + 30);
    std::vector<double> out;
    for (int k = 0; k < 2000; ++k) out.push_back(when(rng));
    for (const track::Fix& f : t.fixes) out.push_back(f.time_s);
    return out;
}

TEST(LocalTrack, AtIsTheFixAtOrBeforeAndItsFractionByAPlainScan) {
    const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({24.0, 60.0});
    const track::Track t = wandering(f, 60, 1);
    const LocalTrack lt(t, f);
    const std::size_t n = t.fixes.size();
    for (const double time : moments(t, 2)) {
        std::size_t i = 0;
        for (std::size_t k = 0; k < n; ++k)
            if (t.fixes[k].time_s <= time) i = k;
        double frac = 0;
        if (time >= t.fixes.front().time_s && i + 1 < n) frac = (time - t.fixes[i].time_s) / (t.fixes[i + 1].time_s - t.fixes[i].time_s);
        const Where w = lt.at(time);
        EXPECT_EQ(w.i, i) << time;
        EXPECT_EQ(w.f, frac) << time;
        EXPECT_GE(w.f, 0.0);
        EXPECT_LT(w.f, 1.0);
    }
    EXPECT_EQ(lt.at(t.fixes[7].time_s).f, 0.0) << "a fix time is the fix itself";
    EXPECT_EQ(lt.position(lt.at(t.fixes[7].time_s)), f.forward(t.fixes[7].position));
    EXPECT_EQ(lt.at(t.fixes.back().time_s + 100).i, n - 1) << "after the end: the last fix";
}

TEST(LocalTrack, IntervalHoldsTheMomentAndTheLastFixEndsTheLastInterval) {
    const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({24.0, 60.0});
    const track::Track t = wandering(f, 40, 3);
    const LocalTrack lt(t, f);
    const std::size_t n = t.fixes.size();
    for (const double time : moments(t, 4)) {
        std::size_t want = 0;
        for (std::size_t k = 0; k + 1 < n; ++k)
            if (t.fixes[k].time_s <= time) want = k;
        const std::size_t i = lt.interval(time);
        EXPECT_EQ(i, want) << time;
        if (time >= t.fixes.front().time_s && time <= t.fixes.back().time_s) {
            const double fr = lt.fraction(i, time);
            EXPECT_GE(fr, 0.0);
            EXPECT_LE(fr, 1.0);
        }
    }
    EXPECT_EQ(lt.interval(t.fixes.back().time_s), n - 2);
    EXPECT_EQ(lt.fraction(n - 2, t.fixes.back().time_s), 1.0);
    EXPECT_EQ(lt.fraction(n - 1, t.fixes.back().time_s + 5), 0.0) << "0 at the last fix";
}

TEST(LocalTrack, BreaksAtGapsAndOnlyIfAskedAtJumps) {
    const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({24.0, 60.0});
    const track::Track t = wandering(f, 80, 5);
    const double max_gap_s = 25;
    const LocalTrack gaps(t, f, Breaks{.max_gap_s = max_gap_s});
    const LocalTrack both(t, f, Breaks{.max_gap_s = max_gap_s, .at_jumps = true});
    const LocalTrack never(t, f);
    std::size_t gap_count = 0, jump_count = 0;
    for (std::size_t i = 0; i + 1 < t.fixes.size(); ++i) {
        const bool gap = t.fixes[i + 1].time_s - t.fixes[i].time_s > max_gap_s, jump = t.fixes[i + 1].jump_before;
        gap_count += gap;
        jump_count += jump && !gap;
        EXPECT_EQ(gaps.sailed(i), !gap) << i;
        EXPECT_EQ(both.sailed(i), !gap && !jump) << i;
        EXPECT_TRUE(never.sailed(i)) << i;
        const double mid = 0.5 * (t.fixes[i].time_s + t.fixes[i + 1].time_s);
        EXPECT_EQ(gaps.present(mid), !gap) << i;
        EXPECT_TRUE(gaps.present(t.fixes[i].time_s)) << "a fix is always present";
    }
    EXPECT_FALSE(gaps.sailed(t.fixes.size() - 1)) << "no interval after the last fix";
    EXPECT_FALSE(gaps.present(t.fixes.front().time_s - 1));
    EXPECT_FALSE(gaps.present(t.fixes.back().time_s + 1));
    EXPECT_GT(gap_count, 0u) << "the track must have gaps to test";
    EXPECT_GT(jump_count, 0u) << "and jumps";
}

TEST(LocalTrack, BetweenFixesPositionIsLinearAndHeadingTurnsTheShorterWay) {
    const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({24.0, 60.0});
    track::Track t;
    for (int i = 0; i < 2; ++i) {
        track::Fix fix;
        fix.time_s = 100.0 + 10 * i;
        fix.position = f.inverse({1000.0 * i, 500.0 * i});
        fix.heading_used_deg = i == 0 ? 350 : 20;
        t.fixes.push_back(fix);
    }
    const LocalTrack lt(t, f);
    const Where w = lt.at(103);
    EXPECT_EQ(w.i, 0u);
    EXPECT_DOUBLE_EQ(w.f, 0.3);
    EXPECT_DOUBLE_EQ(lt.time(w), 103);
    const XY a = lt.position(0), b = lt.position(1), p = lt.position(w);
    EXPECT_NEAR(p.x, a.x + 0.3 * (b.x - a.x), 1e-9);
    EXPECT_NEAR(p.y, a.y + 0.3 * (b.y - a.y), 1e-9);
    EXPECT_NEAR(lt.heading(w), 359.0, 1e-9) << "through north, 30 degrees in all, not 330 the long way";
    EXPECT_NEAR(wrap_360(lt.heading(lt.at(108))), 14.0, 1e-9);
    // The pose at a fix: the frame's Jacobian there times the heading's rotation, the one the frame gives.
    const check::LocalPose pose = lt.pose(lt.at(100));
    const Eigen::Matrix2d want = f.jacobian(t.fixes[0].position) * ship_to_en(350);
    EXPECT_LT((pose.ship_to_local - want).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_EQ(pose.position, a);
    // A per-fix quantity, linearly.
    EXPECT_DOUBLE_EQ(lt.interpolate(std::vector<double>{2.0, 12.0}, w), 5.0);
    EXPECT_DOUBLE_EQ(lt.interpolate(std::vector<double>{2.0, 12.0}, lt.at(200)), 12.0);
}

TEST(LocalTrack, PositionsOnlyPlacesTheSamePointsAndRefusesPoses) {
    const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({24.0, 60.0});
    const track::Track t = wandering(f, 50, 7);
    const LocalTrack poses(t, f), positions(t, f, {}, Placing::positions);
    for (std::size_t i = 0; i < t.fixes.size(); ++i) {
        EXPECT_EQ(positions.position(i), poses.position(i)) << i;
        EXPECT_EQ(positions.position(i), f.forward(t.fixes[i].position)) << "one point at a time, the same " << i;
    }
    for (const double time : moments(t, 8)) EXPECT_EQ(positions.position(positions.at(time)), poses.position(poses.at(time))) << time;
    EXPECT_THROW(positions.pose(positions.at(t.fixes[3].time_s)), UsageError);
}

TEST(LocalTrack, WrapAndTurn) {
    EXPECT_EQ(wrap_360(-10), 350);
    EXPECT_EQ(wrap_360(370), 10);
    EXPECT_EQ(wrap_360(-1e-17), 0.0) << "never 360";
    EXPECT_EQ(turn(350, 10), 20);
    EXPECT_EQ(turn(10, 350), -20);
    EXPECT_EQ(turn(0, 180), 180);
}

}  // namespace
}  // namespace shoal::audit
