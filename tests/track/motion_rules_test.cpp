// The rules that read motion from fixes, each against an independent answer: wild fixes
// against the outliers injected into random tracks, stops against a brute-force reading of
// the definition over every window, speeds against the speeds the tracks were made with.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include <shoal/track/kinematics.hpp>
#include <shoal/track/track.hpp>
#include <shoal/track/wild_fixes.hpp>

namespace shoal::track {
namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr double knot = 1852.0 / 3600.0;  // m/s

/// lon/lat of a point `east`, `north` metres from (lon0, lat0) (small offsets).
geo::LonLat offset(geo::LonLat o, double east, double north) {
    const double r = 6371008.8;
    return {o.lon + east / (r * std::cos(o.lat * deg)) / deg, o.lat + north / r / deg};
}

Fix fix_at(double t, geo::LonLat p, std::size_t line) {
    Fix f;
    f.time_s = t;
    f.position = p;
    f.line = line;
    return f;
}

/// A random voyage: legs at 2-25 kn in random directions, stops, fixes every 2-30 s, GPS
/// jitter of 3 m.
Track random_voyage(std::mt19937_64& rng, std::size_t n) {
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> jitter(0, 3);
    Track t;
    t.id = "v";
    t.file = "random";
    double east = 0, north = 0, time = 1.7e9, course = 360 * u(rng), speed = 10 * knot;
    const geo::LonLat o{11.0, 55.5};
    for (std::size_t i = 0; i < n; ++i) {
        if (u(rng) < 0.05) {
            course = 360 * u(rng);
            speed = u(rng) < 0.3 ? 0.0 : (2 + 23 * u(rng)) * knot;
        }
        const double dt = 2 + 28 * u(rng);
        time += dt;
        east += speed * dt * std::sin(course * deg);
        north += speed * dt * std::cos(course * deg);
        t.fixes.push_back(fix_at(time, offset(o, east + jitter(rng), north + jitter(rng)), i + 2));
    }
    return t;
}

TEST(WildFixes, InjectedJumpsAndNullIslandAreDroppedAndNothingElse) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(0, 1);
    for (int trial = 0; trial < 200; ++trial) {
        Track t = random_voyage(rng, 200);
        // Inject 1-4 outliers at distinct places at least 12 fixes apart: a jump of 5-500 km
        // (far beyond 60 kn for 30 s) and back, or a fix at 0,0.
        std::set<std::size_t> lines;
        for (std::size_t k = 20; k + 20 < t.fixes.size(); k += 12 + static_cast<std::size_t>(40 * u(rng))) {
            Fix& f = t.fixes[k];
            if (u(rng) < 0.3) f.position = {0, 0};
            else f.position = offset(f.position, (u(rng) < 0.5 ? -1 : 1) * (5e3 + 5e5 * u(rng)), 2e4 * (u(rng) - 0.5));
            lines.insert(f.line);
        }
        const std::size_t before = t.fixes.size();
        const std::vector<WildFix> wild = drop_wild_fixes(t);
        std::set<std::size_t> found;
        for (const WildFix& w : wild) found.insert(w.line);
        ASSERT_EQ(found, lines) << "trial " << trial;
        EXPECT_EQ(t.fixes.size(), before - lines.size());
        for (const Fix& f : t.fixes) EXPECT_FALSE(f.jump_before) << "a jump and back is no break";
        // What is left is plausible from fix to fix.
        for (std::size_t i = 1; i < t.fixes.size(); ++i) ASSERT_TRUE(plausible(t.fixes[i - 1], t.fixes[i], {}));
    }
}

TEST(WildFixes, AJumpThatPersistsStartsANewPieceAndDropsNothing) {
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 100; ++trial) {
        Track t = random_voyage(rng, 120);
        // From fix 60 on, the whole track is 300 km away (a second vessel on the same MMSI).
        for (std::size_t i = 60; i < t.fixes.size(); ++i) t.fixes[i].position = offset(t.fixes[i].position, 3e5, 0);
        const std::vector<WildFix> wild = drop_wild_fixes(t);
        EXPECT_TRUE(wild.empty());
        ASSERT_EQ(t.fixes.size(), 120u);
        for (std::size_t i = 0; i < t.fixes.size(); ++i) EXPECT_EQ(t.fixes[i].jump_before, i == 60) << i;
        EXPECT_EQ(piece_start(t, 80, 600), 60u);
        EXPECT_EQ(piece_start(t, 59, 600), 0u);
    }
}

TEST(WildFixes, LoneFixesBetweenJumpsAndAtTheEndsAreWild) {
    const geo::LonLat o{12.5, 55.6};
    Track t;
    // A lone fix 800 km away first, then a run, a lone fix 1,000 km away, the run again, and a
    // last fix far away: the three lone ones are wild; the run is kept whole.
    t.fixes.push_back(fix_at(0, offset(o, 8e5, 0), 2));
    for (int i = 0; i < 5; ++i) t.fixes.push_back(fix_at(10 + 10.0 * i, offset(o, 50.0 * i, 0), 3 + i));
    t.fixes.push_back(fix_at(57, offset(o, 0, 1e6), 8));
    for (int i = 5; i < 10; ++i) t.fixes.push_back(fix_at(10 + 10.0 * i, offset(o, 50.0 * i, 0), 4 + i));
    t.fixes.push_back(fix_at(200, offset(o, -9e5, 0), 14));
    const std::vector<WildFix> wild = drop_wild_fixes(t);
    std::vector<std::size_t> lines;
    for (const auto& w : wild) lines.push_back(w.line);
    EXPECT_EQ(lines, (std::vector<std::size_t>{2, 8, 14}));
    ASSERT_EQ(t.fixes.size(), 10u);
    for (const Fix& f : t.fixes) EXPECT_FALSE(f.jump_before);
    // Two lone fixes far apart (the shared MMSI 111111111 of the DMA log): neither can be told
    // wild; both stay, as pieces of their own.
    Track two;
    two.fixes = {fix_at(0, {13.6379, 54.1637}, 2), fix_at(7, {5.8445, 62.3235}, 3)};
    EXPECT_TRUE(drop_wild_fixes(two).empty());
    ASSERT_EQ(two.fixes.size(), 2u);
    EXPECT_TRUE(two.fixes[1].jump_before);
}

TEST(WildFixes, ReasonsNameTheJump) {
    const geo::LonLat o{24.9, 60.1};
    Track t;
    for (int i = 0; i < 6; ++i) t.fixes.push_back(fix_at(10.0 * i, offset(o, 40.0 * i, 0), 2 + i));
    t.fixes[3].position = offset(o, 120, 5200);
    const std::vector<WildFix> wild = drop_wild_fixes(t);
    ASSERT_EQ(wild.size(), 1u);
    EXPECT_EQ(wild[0].line, 5u);
    EXPECT_NE(wild[0].why.find("jump of 5.2 km in 10 s"), std::string::npos) << wild[0].why;
    EXPECT_NE(wild[0].why.find("line 4"), std::string::npos) << wild[0].why;
    EXPECT_NEAR(wild[0].implied_kn, 5200 / 10.0 / knot, 20);
}

/// The stop rule read literally: fix i is stopped when some window [s, i] lasts at least the
/// stop time and all its fixes fit in a box (metres, equirectangular about the piece's first
/// fix) of diagonal at most the stop diameter. Every window is tried.
std::vector<bool> brute_stopped(const Track& t, const MotionOptions& o) {
    const std::size_t n = t.fixes.size();
    std::vector<bool> out(n, false);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t b = piece_start(t, i, o.max_gap_s);
        const geo::LonLat p0 = t.fixes[b].position;
        const double kx = 6371008.8 * deg * std::cos(p0.lat * deg), ky = 6371008.8 * deg;
        for (std::size_t s = b; s <= i && !out[i]; ++s) {
            if (t.fixes[i].time_s - t.fixes[s].time_s < o.stop_duration_s) break;
            double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
            for (std::size_t k = s; k <= i; ++k) {
                const double x = (t.fixes[k].position.lon - p0.lon) * kx, y = (t.fixes[k].position.lat - p0.lat) * ky;
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
            out[i] = std::hypot(x1 - x0, y1 - y0) <= o.stop_diameter_m;
        }
    }
    return out;
}

/// Where each fix's stay began: the first fix of the longest window [s, i] (within its piece)
/// whose fixes fit in the stop diameter's box, each window from [i, i] back tried in turn.
std::vector<std::size_t> brute_stay_start(const Track& t, const MotionOptions& o) {
    const std::size_t n = t.fixes.size();
    std::vector<std::size_t> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t b = piece_start(t, i, o.max_gap_s);
        const geo::LonLat p0 = t.fixes[b].position;
        const double kx = 6371008.8 * deg * std::cos(p0.lat * deg), ky = 6371008.8 * deg;
        // Going back from i, the box grows: the last window that fits is the longest (every
        // window inside a fitting one fits).
        std::size_t first = i;
        double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
        for (std::size_t s = i + 1; s-- > b;) {
            const double x = (t.fixes[s].position.lon - p0.lon) * kx, y = (t.fixes[s].position.lat - p0.lat) * ky;
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            if (!(std::hypot(x1 - x0, y1 - y0) <= o.stop_diameter_m)) break;
            first = s;
        }
        out[i] = first;
    }
    return out;
}

TEST(Stops, AgreeWithEveryWindowReadByBruteForce) {
    std::mt19937_64 rng(99);
    std::size_t stopped = 0, moving = 0, longest = 0;
    for (int trial = 0; trial < 60; ++trial) {
        Track t = random_voyage(rng, 300);
        if (trial % 3 == 0)  // some gaps too
            for (std::size_t i = 100; i < t.fixes.size(); ++i) t.fixes[i].time_s += 900;
        MotionOptions o;
        o.stop_diameter_m = trial % 2 ? 50.0 : 20.0;
        resolve_motion(t, o);
        const std::vector<bool> want = brute_stopped(t, o);
        const std::vector<std::size_t> start = brute_stay_start(t, o);
        for (std::size_t i = 0; i < t.fixes.size(); ++i) {
            ASSERT_EQ(t.fixes[i].stopped, want[i]) << "trial " << trial << " fix " << i;
            ASSERT_EQ(t.fixes[i].stay_since_s, t.fixes[start[i]].time_s) << "trial " << trial << " fix " << i;
            longest = std::max(longest, i - start[i]);
            (want[i] ? stopped : moving) += 1;
        }
    }
    EXPECT_GT(stopped, 1000u) << "the random voyages stop often enough to test the rule";
    EXPECT_GT(longest, 100u) << "stays longer than the sliding window's queues keep (16) before they let go of their front";
    EXPECT_GT(moving, 1000u);
}

TEST(Stops, StoppingAfterAContactIsNotStoppedBeforeIt) {
    // Under way at 10 kn, fixes every 10 s, then dead still from fix 30 on (aground).
    const geo::LonLat o{24.9, 60.1};
    Track t;
    for (int i = 0; i < 90; ++i) t.fixes.push_back(fix_at(10.0 * i, offset(o, 0, 10 * knot * 10 * std::min(i, 30)), 2 + i));
    resolve_motion(t);
    for (int i = 0; i <= 30; ++i) EXPECT_FALSE(t.fixes[i].stopped) << i;
    // Stopped once it has lain within 50 m for 120 s: from fix 42 (t = 420 s) on.
    EXPECT_FALSE(t.fixes[41].stopped);
    EXPECT_TRUE(t.fixes[42].stopped);
    // Seen from a contact at t = 295 s: it came to a stop at fix 30 (t = 300 s), 5 s later.
    const auto stop = stopped_after(t, 30, 295.0, {});
    ASSERT_TRUE(stop.has_value());
    EXPECT_DOUBLE_EQ(*stop, 300.0);
    // A vessel that never stops: none.
    Track under_way;
    for (int i = 0; i < 60; ++i) under_way.fixes.push_back(fix_at(10.0 * i, offset(o, 0, 51.0 * i), 2 + i));
    resolve_motion(under_way);
    EXPECT_FALSE(stopped_after(under_way, 0, 0.0, {}).has_value());
}

TEST(Speed, FromPositionsMatchesTheSpeedSailedAndIgnoresJitter) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> jitter(0, 5);
    const geo::LonLat o{10.0, 56.0};
    for (double kn : {0.0, 0.3, 1.0, 4.0, 12.0, 30.0}) {
        Track t;
        for (int i = 0; i < 200; ++i) {
            const double d = kn * knot * 2.0 * i;
            t.fixes.push_back(fix_at(2.0 * i, offset(o, d * std::sin(1.0) + jitter(rng), d * std::cos(1.0) + jitter(rng)), 2 + i));
        }
        resolve_motion(t);
        for (const Fix& f : t.fixes) {
            ASSERT_EQ(f.speed_source, SpeedSource::positions);
            // 5 m of jitter (sigma) at both ends over >= 120 s: within 0.5 kn.
            EXPECT_NEAR(f.speed_used_kn, kn, 0.5) << kn << " at fix " << (&f - t.fixes.data());
        }
        // Fix to fix (2 s apart) the jitter alone reads as several knots: that is what the window is for.
    }
    Track with_sog;
    with_sog.fixes = {fix_at(0, o, 2), fix_at(10, offset(o, 0, 1000), 3)};
    with_sog.fixes[0].sog_kn = 7.5;
    resolve_motion(with_sog);
    EXPECT_EQ(with_sog.fixes[0].speed_source, SpeedSource::sog);
    EXPECT_DOUBLE_EQ(with_sog.fixes[0].speed_used_kn, 7.5);
    EXPECT_EQ(with_sog.fixes[1].speed_source, SpeedSource::positions);
    Track one;
    one.fixes = {fix_at(0, o, 2)};
    resolve_motion(one);
    EXPECT_EQ(one.fixes[0].speed_source, SpeedSource::none);
}

TEST(NavStatus, NumbersAndDmaTextAreRead) {
    EXPECT_EQ(parse_nav_status("0"), 0);
    EXPECT_EQ(parse_nav_status("6"), nav_status_aground);
    EXPECT_EQ(parse_nav_status("15"), 15);
    EXPECT_EQ(parse_nav_status("16"), nav_status_unknown);
    EXPECT_EQ(parse_nav_status(""), nav_status_unknown);
    EXPECT_EQ(parse_nav_status("Under way using engine"), 0);
    EXPECT_EQ(parse_nav_status("Moored"), nav_status_moored);
    EXPECT_EQ(parse_nav_status("Aground"), nav_status_aground);
    EXPECT_EQ(parse_nav_status("At anchor"), nav_status_at_anchor);
    EXPECT_EQ(parse_nav_status("Restricted maneuverability"), 3);
    EXPECT_EQ(parse_nav_status("Unknown value"), 15);
    EXPECT_EQ(parse_nav_status("banana"), nav_status_unknown);
    EXPECT_STREQ(nav_status_text(5), "moored");
    EXPECT_STREQ(nav_status_text(nav_status_unknown), "");
}

TEST(Headings, NeverNorthWhenNothingIsKnown) {
    const geo::LonLat o{24.9, 60.1};
    Track t;
    for (int i = 0; i < 5; ++i) t.fixes.push_back(fix_at(60.0 * i, o, 2 + i));  // still, no heading, no COG
    resolve_motion(t);
    resolve_headings(t);
    for (const Fix& f : t.fixes) EXPECT_EQ(f.heading_source, HeadingSource::none);
    // Once the vessel moves, the heading comes from its positions, and it is held after.
    t.fixes.push_back(fix_at(400, offset(o, 1000, 0), 7));
    t.fixes.push_back(fix_at(460, offset(o, 1300, 0), 8));
    resolve_motion(t);
    resolve_headings(t);
    EXPECT_EQ(t.fixes[5].heading_source, HeadingSource::positions);
    EXPECT_NEAR(t.fixes[5].heading_used_deg, 90, 0.5);
}

}  // namespace
}  // namespace shoal::track
