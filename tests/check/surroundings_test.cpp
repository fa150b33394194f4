// Travel distances and the least charted depth under a hull (check/surroundings.hpp) against
// independent answers: GEOS on the same shapes (the hull moved by the distance less a
// millimetre is clear of land, moved a millimetre more it touches), hand-made quays with
// known gaps, and depth areas at known depths against GEOS intersects of the hull with each.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/check/surroundings.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/util/error.hpp>
#include "test_support.hpp"

namespace shoal::check {
namespace {

using geo::XY;

geo::LocalFrame any_frame() { return geo::LocalFrame::transverse_mercator({0, 0}); }

/// A closed ring (counter-clockwise: land on its left) bounding `what`.
coast::LocalPolyline ring(std::vector<XY> pts, coast::Hazard what = {}) {
    pts.push_back(pts.front());
    return {std::move(pts), true, std::move(what)};
}

coast::LocalPolyline rect(double x0, double y0, double x1, double y1, coast::Hazard what = {}) {
    return ring({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, std::move(what));
}

coast::Hazard shallow(double depth_m) {
    coast::Hazard h;
    h.kind = coast::HazardKind::shallow;
    h.depth_m = depth_m;
    return h;
}

/// A jagged island: a star-shaped ring around `c` of `n` points at random radii in
/// [0.3 r, r] (angles increasing: counter-clockwise, simple).
coast::LocalPolyline jagged_island(std::mt19937_64& rng, XY c, double r, int n) {
    std::uniform_real_distribution<double> rad(0.3 * r, r), jitter(-0.3, 0.3);
    std::vector<XY> pts;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * (k + 0.5 + jitter(rng)) / n;
        const double rr = rad(rng);
        pts.push_back({c.x + rr * std::cos(a), c.y + rr * std::sin(a)});
    }
    return ring(std::move(pts));
}

/// The hull at `pose` moved by `by` (local metres), as a GEOS polygon.
geo::GeomPtr moved_hull(const geo::GeosContext& ctx, const hull::Hull& hull, const LocalPose& pose, XY by) {
    std::vector<XY> pts = hull_outline(hull, pose);
    for (XY& p : pts) p = p + by;
    pts.push_back(pts.front());
    return test::polygon(ctx, {pts});
}

/// The union of the rings' areas, as GEOS sees them.
geo::GeomPtr areas(const geo::GeosContext& ctx, const std::vector<coast::LocalPolyline>& lines) {
    std::vector<geo::GeomPtr> parts;
    for (const auto& l : lines) parts.push_back(test::polygon(ctx, {l.points}));
    geo::GeomPtr all = test::collection(ctx, GEOS_GEOMETRYCOLLECTION, std::move(parts));
    return test::check(ctx, GEOSUnaryUnion_r(ctx, all.get()), "union");
}

/// Equal but for the rounding of a direction normalised another way.
bool same_distance(double a, double b) { return a == b || std::fabs(a - b) <= 1e-9 * (1 + std::fabs(b)); }

struct Scene {
    std::vector<coast::LocalPolyline> lines;
    grid::CoastGrid grid;
    hull::Hull hull;
    Detector detector;
    Scene(std::vector<coast::LocalPolyline> l, double cell, hull::Hull h)
        : lines(std::move(l)), grid(grid::CoastGrid::build(lines, any_frame(), cell)), hull(std::move(h)), detector(grid, hull) {}
    Surroundings at(const LocalPose& p, double max_m = INFINITY) const { return surroundings(detector, grid, p, max_m); }
};

// ---------------------------------------------------------------- hand-derived

TEST(Surroundings, QuayParallelToThePortSideGivesTheGap) {
    // Heading east (grid heading 90): port is north. The quay's face at y = 20; the hull's
    // port side at y = 5: a 15 m gap. Nothing to starboard, ahead or astern.
    Scene s({rect(-1000, 20, 1000, 300)}, 100, hull::Hull::from_dimensions({50, 10, 5, 5}));
    const Surroundings r = s.at(LocalPose::at({0, 0}, 90), 500);
    EXPECT_NEAR(r.port_m, 15, 1e-9);
    EXPECT_EQ(r.starboard_m, 500);
    EXPECT_EQ(r.ahead_m, 500);
    EXPECT_EQ(r.astern_m, 500);
    EXPECT_TRUE(std::isnan(r.least_depth_m));  // no depth charted (land only, not touched)
    // Heading west, the quay is to starboard.
    const Surroundings w = s.at(LocalPose::at({0, 0}, 270), 500);
    EXPECT_NEAR(w.starboard_m, 15, 1e-9);
    EXPECT_EQ(w.port_m, 500);
}

TEST(Surroundings, QuayAheadGivesTheGapToTheBowTip) {
    // Heading east, bow tip at x = 50, quay face at x = 200; a wall astern at x = -100 (the
    // transom at x = -10).
    Scene s({rect(200, -1000, 400, 1000), rect(-300, -1000, -100, 1000)}, 100, hull::Hull::from_dimensions({50, 10, 5, 5}));
    const Surroundings r = s.at(LocalPose::at({0, 0}, 90));
    EXPECT_NEAR(r.ahead_m, 150, 1e-9);
    EXPECT_NEAR(r.astern_m, 90, 1e-9);
    EXPECT_TRUE(std::isinf(r.port_m));  // nothing that way to the grid's end
    EXPECT_FALSE(r.covered);            // ... so the hull leaves the chart
    EXPECT_NEAR(travel_distance(s.detector, LocalPose::at({0, 0}, 90), {1, 0}, INFINITY), 150, 1e-9);
    EXPECT_NEAR(travel_distance(s.detector, LocalPose::at({0, 0}, 90), {1, 0}, 100), 100, 0);  // capped
}

TEST(Surroundings, InContactEverythingIsZero) {
    Scene s({rect(0, 3, 100, 50)}, 50, hull::Hull::from_dimensions({50, 10, 5, 5}));
    const Surroundings r = s.at(LocalPose::at({0, 0}, 90), 200);
    EXPECT_EQ(r.port_m, 0);
    EXPECT_EQ(r.starboard_m, 0);
    EXPECT_EQ(r.ahead_m, 0);
    EXPECT_EQ(r.astern_m, 0);
    EXPECT_EQ(r.least_depth_m, 0);  // on land
}

TEST(Surroundings, DistancesAreMetresOnTheGround) {
    // A placement at local scale 2 (two local metres per metre on the ground): the hull's
    // port side lies 10 local metres from the centreline, the quay at 20: a 10 local metre gap
    // is 5 m on the ground; a search to 4 m on the ground stops there.
    Scene s({rect(-1000, 20, 1000, 300)}, 100, hull::Hull::from_dimensions({50, 10, 5, 5}));
    LocalPose p = LocalPose::at({0, 0}, 90);
    p.ship_to_local *= 2;
    EXPECT_NEAR(s.at(p).port_m, 5, 1e-9);
    EXPECT_EQ(s.at(p, 4).port_m, 4);
    EXPECT_NEAR(travel_distance(s.detector, p, {0, 1}, INFINITY), 10, 1e-9);  // local metres
}

TEST(Surroundings, CoveredWhenTheReachStaysOnTheChart) {
    // The grid's extent is the land's box, grown to whole cells.
    Scene s({rect(0, 0, 1000, 1000), rect(2000, 0, 3000, 1000)}, 100, hull::Hull::from_dimensions({50, 10, 5, 5}));
    const geo::Box ext = s.grid.extent();
    const LocalPose between = LocalPose::at({1500, 500}, 90);  // east, between the two blocks
    const Surroundings near = s.at(between, 10);
    EXPECT_TRUE(near.covered) << "extent " << ext.minx << " " << ext.maxx << " " << ext.miny << " " << ext.maxy;
    EXPECT_NEAR(s.at(between).ahead_m, 2000 - 1550, 1e-9);
    // Port and starboard run along the gap to the grid's edge and beyond: not covered.
    EXPECT_FALSE(s.at(between, 2000).covered);
    EXPECT_TRUE(std::isinf(s.at(between).port_m));
}

TEST(Surroundings, BadArgumentsAreRefused) {
    Scene s({rect(0, 0, 100, 100)}, 50, hull::Hull::from_dimensions({50, 10, 5, 5}));
    const LocalPose p = LocalPose::at({500, 500}, 0);
    EXPECT_THROW(s.at(p, 0), UsageError);
    EXPECT_THROW(s.at(p, -1), UsageError);
    EXPECT_THROW(s.at(p, NAN), UsageError);
    EXPECT_THROW(travel_distance(s.detector, p, {1, 1}, 10), UsageError);
    EXPECT_THROW(travel_distance(s.detector, p, {1, 0}, NAN), UsageError);
    const grid::CoastGrid other = grid::CoastGrid::build(s.lines, any_frame(), 25);
    EXPECT_THROW(surroundings(s.detector, other, p, 10), UsageError);
}

// ---------------------------------------------------------------- against GEOS

/// Random poses near jagged random islands, random directions: the distance t found by
/// travel_distance against GEOS (moved by t - 1 mm clear, by t + 1 mm touching when t <
/// max_m), and surroundings' four axes equal to travel_distance along them.
void travel_against_geos(std::uint64_t seed, double cell_m, double max_m, int poses, std::optional<hull::Hull> notched = {}) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<coast::LocalPolyline> lines;
    for (int k = 0; k < 25; ++k)
        lines.push_back(jagged_island(rng, {2000 * unit(rng), 2000 * unit(rng)}, 50 + 250 * unit(rng), 5 + static_cast<int>(40 * unit(rng))));
    const Scene s(lines, cell_m,
                  notched ? *notched : hull::Hull::from_dimensions({40 + 60 * unit(rng), 5 + 20 * unit(rng), 4 + 6 * unit(rng), 4 + 6 * unit(rng)}));
    const bool convex = !notched;
    geo::GeosContext ctx;
    const geo::GeomPtr land = areas(ctx, lines);
    const test::PreparedPtr prepared = test::prepare(ctx, land.get());
    auto touches = [&](const LocalPose& p, XY by) {
        return GEOSPreparedIntersects_r(ctx, prepared.get(), moved_hull(ctx, s.hull, p, by).get()) == 1;
    };
    // The area the (convex) hull sweeps moving by `by`: the convex hull of it at both ends.
    auto sweep_touches = [&](const LocalPose& p, XY by) {
        std::vector<XY> pts = hull_outline(s.hull, p);
        const std::size_t n = pts.size();
        for (std::size_t i = 0; i < n; ++i) pts.push_back(pts[i] + by);
        std::vector<geo::GeomPtr> points;
        for (const XY& q : pts) points.push_back(test::point(ctx, q));
        const geo::GeomPtr all = test::collection(ctx, GEOS_MULTIPOINT, std::move(points));
        const geo::GeomPtr swept = test::check(ctx, GEOSConvexHull_r(ctx, all.get()), "convex hull");
        return GEOSPreparedIntersects_r(ctx, prepared.get(), swept.get()) == 1;
    };
    int contacts = 0, hits = 0, capped = 0;
    for (int k = 0; k < poses; ++k) {
        const LocalPose p = LocalPose::at({-300 + 2600 * unit(rng), -300 + 2600 * unit(rng)}, 360 * unit(rng));
        const double a = 2 * std::numbers::pi * unit(rng);
        const XY u{std::cos(a), std::sin(a)};
        const double t = travel_distance(s.detector, p, u, max_m);
        const std::string where = "seed " + std::to_string(seed) + " pose " + std::to_string(k) + " at " + std::to_string(p.position.x) +
                                  "," + std::to_string(p.position.y) + " direction " + std::to_string(a) + ": t = " + std::to_string(t);
        if (touches(p, {0, 0})) {
            ++contacts;
            EXPECT_EQ(t, 0) << where;
            continue;
        }
        ASSERT_GT(t, 0) << where;
        if (std::isinf(t)) {
            if (convex) {
                EXPECT_FALSE(sweep_touches(p, 1e5 * u)) << where;
            }
        } else if (t > 1e-3) {
            EXPECT_FALSE(touches(p, (t - 1e-3) * u)) << where;
            if (convex) {
                EXPECT_FALSE(sweep_touches(p, (t - 1e-3) * u)) << where;
            }
        }
        if (t < max_m) {
            ++hits;
            ASSERT_TRUE(std::isfinite(t)) << where;
            EXPECT_TRUE(touches(p, (t + 1e-3) * u)) << where;
        } else {
            ++capped;
            EXPECT_EQ(t, max_m) << where;
        }
        if (k % 8 == 0) {  // the four axes
            const Surroundings r = surroundings(s.detector, s.grid, p, max_m);
            const Eigen::Matrix2d& m = p.ship_to_local;
            EXPECT_PRED2(same_distance, r.ahead_m, travel_distance(s.detector, p, {m(0, 0), m(1, 0)}, max_m)) << where;
            EXPECT_PRED2(same_distance, r.astern_m, travel_distance(s.detector, p, {-m(0, 0), -m(1, 0)}, max_m)) << where;
            EXPECT_PRED2(same_distance, r.starboard_m, travel_distance(s.detector, p, {m(0, 1), m(1, 1)}, max_m)) << where;
            EXPECT_PRED2(same_distance, r.port_m, travel_distance(s.detector, p, {-m(0, 1), -m(1, 1)}, max_m)) << where;
        }
    }
    std::printf("seed %llu, cell %g m, max %g m: %d poses, %d in contact, %d hits, %d capped\n", static_cast<unsigned long long>(seed),
                cell_m, max_m, poses, contacts, hits, capped);
    EXPECT_GT(hits, poses / 8);
    EXPECT_GT(contacts, 0);
}

TEST(SurroundingsAgainstGeos, TravelNearJaggedIslandsWithinALimit) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) travel_against_geos(seed, 100, 400, 1500);
}

TEST(SurroundingsAgainstGeos, TravelNearJaggedIslandsWithoutALimit) {
    // Small cells: the sweep walks many of them outward, to the grid's end when nothing is met.
    for (std::uint64_t seed = 11; seed <= 13; ++seed) travel_against_geos(seed, 37, INFINITY, 1500);
}

TEST(SurroundingsAgainstGeos, TravelWithLargeCellsAndALongReach) {
    for (std::uint64_t seed = 21; seed <= 22; ++seed) travel_against_geos(seed, 1000, 3000, 1000);
}

TEST(SurroundingsAgainstGeos, TravelOfAHullWithANotch) {
    // Not convex: a coast point can enter the notch before it meets the hull's outer edges
    // (the sweep's area is then not the convex hull at both ends: only the ends are checked).
    const hull::Hull notched = hull::Hull::from_contour({{40, 0}, {20, 8}, {-20, 8}, {-20, -8}, {0, -8}, {0, -3}, {10, -3}, {10, -8}, {20, -8}});
    for (std::uint64_t seed = 31; seed <= 33; ++seed) travel_against_geos(seed, 60, 300, 1500, notched);
}

// ---------------------------------------------------------------- least charted depth

/// Random depth areas (some overlapping, some of unknown depth) and a little land: the least
/// charted depth under random hulls against GEOS intersects of the hull with each area.
TEST(SurroundingsAgainstGeos, LeastDepthEqualsTheShallowestAreaTouched) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    const std::vector<double> depth_choices{-1.0, 2.0, 3.5, 5.0, 8.0, 12.0, NAN};
    std::vector<coast::LocalPolyline> lines;
    std::vector<double> depth_of;  // per line: NaN unknown; land marked by is_land
    std::vector<bool> is_land;
    for (int k = 0; k < 30; ++k) {
        const double x = 2000 * unit(rng), y = 2000 * unit(rng), w = 40 + 300 * unit(rng), h = 40 + 300 * unit(rng);
        const double d = depth_choices[static_cast<std::size_t>(unit(rng) * depth_choices.size()) % depth_choices.size()];
        lines.push_back(rect(x, y, x + w, y + h, shallow(d)));
        depth_of.push_back(d);
        is_land.push_back(false);
    }
    for (int k = 0; k < 3; ++k) {
        lines.push_back(jagged_island(rng, {2000 * unit(rng), 2000 * unit(rng)}, 80, 12));
        depth_of.push_back(NAN);
        is_land.push_back(true);
    }
    const grid::CoastGrid base = grid::CoastGrid::build(lines, any_frame(), 150);
    EXPECT_LE(base.charted_depths().size(), depth_choices.size());
    EXPECT_TRUE(std::isnan(base.charted_depths()[0]));
    const hull::Hull hull = hull::Hull::from_dimensions({60, 15, 6, 6});
    const Detector land_only(base, hull, std::nullopt);
    geo::GeosContext ctx;
    std::vector<geo::GeomPtr> polys;
    for (const auto& l : lines) polys.push_back(test::polygon(ctx, {l.points}));
    int on_land = 0, unknown = 0, known = 0, none = 0;
    for (int k = 0; k < 1500; ++k) {
        const LocalPose p = LocalPose::at({-100 + 2400 * unit(rng), -100 + 2400 * unit(rng)}, 360 * unit(rng));
        const geo::GeomPtr h = moved_hull(ctx, hull, p, {0, 0});
        bool land = false, any_unknown = false;
        double least = INFINITY;
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (GEOSIntersects_r(ctx, polys[i].get(), h.get()) != 1) continue;
            if (is_land[i])
                land = true;
            else if (std::isnan(depth_of[i]))
                any_unknown = true;
            else
                least = std::min(least, depth_of[i]);
        }
        const double want = land ? 0.0 : any_unknown || std::isinf(least) ? NAN : least;
        const double got = least_charted_depth(base, hull, p);
        const std::string where = "pose " + std::to_string(k) + " at " + std::to_string(p.position.x) + "," + std::to_string(p.position.y);
        if (std::isnan(want))
            EXPECT_TRUE(std::isnan(got)) << where << ": got " << got;
        else
            EXPECT_EQ(got, want) << where;
        // The same through surroundings, whatever the detector's own limiting depth.
        if (k % 10 == 0) {
            const double s = surroundings(land_only, base, p, 100).least_depth_m;
            EXPECT_TRUE(s == got || (std::isnan(s) && std::isnan(got))) << where;
        }
        on_land += land;
        unknown += !land && any_unknown;
        known += !std::isnan(want) && !land;
        none += !land && !any_unknown && std::isinf(least);
    }
    std::printf("%d poses on land, %d over unknown depths, %d over known depths, %d over no area\n", on_land, unknown, known, none);
    EXPECT_GT(on_land, 10);
    EXPECT_GT(unknown, 10);
    EXPECT_GT(known, 300);
    EXPECT_GT(none, 50);
}

TEST(Surroundings, LeastDepthOnAGridOfLandOnly) {
    Scene s({rect(0, 3, 100, 50)}, 50, hull::Hull::from_dimensions({50, 10, 5, 5}));
    EXPECT_EQ(least_charted_depth(s.grid, s.hull, LocalPose::at({0, 0}, 90)), 0);  // touches land
    EXPECT_TRUE(std::isnan(least_charted_depth(s.grid, s.hull, LocalPose::at({0, -100}, 90))));
}

TEST(Surroundings, TravelStopsAtTheDetectorsHazardsOnly) {
    // A 3 m area 30 m to port, a 10 m area 20 m to port: a vessel limited at 5 m stops at the
    // 3 m area, one at 15 m at the 10 m area; land only: nothing.
    const std::vector<coast::LocalPolyline> lines{rect(-500, 25, 500, 100, shallow(10)), rect(-500, 35, 500, 100, shallow(3))};
    const grid::CoastGrid base = grid::CoastGrid::build(lines, any_frame(), 100);
    const hull::Hull hull = hull::Hull::from_dimensions({50, 10, 5, 5});
    const LocalPose p = LocalPose::at({0, 0}, 90);
    EXPECT_NEAR(surroundings(Detector(base, hull, 5.0), base, p, 200).port_m, 30, 1e-9);
    EXPECT_NEAR(surroundings(Detector(base, hull, 15.0), base, p, 200).port_m, 20, 1e-9);
    EXPECT_EQ(surroundings(Detector(base, hull, std::nullopt), base, p, 200).port_m, 200);
    // Moved 22 m to port, the hull overlaps the 10 m area.
    EXPECT_EQ(least_charted_depth(base, hull, LocalPose::at({0, 22}, 90)), 10);
    EXPECT_EQ(least_charted_depth(base, hull, LocalPose::at({0, 40}, 90)), 3);
}

/// The S-57 cut off Annapolis (land, depth areas, dangers; tests/grid/hazard_test.cpp) as one
/// grid holding every depth, 300 m cells.
const grid::CoastGrid& annapolis_cut() {
    static const grid::CoastGrid g = [] {
        grid::BuildRequest r;
        r.cell_m = 300;
        std::vector<std::string> warnings;
        return grid::build_grid({test::data_path("coast/US4MD81M_hazard_cut.000")}, r, &warnings);
    }();
    return g;
}

/// Random poses over a grid's extent (local metres, scale 1).
std::vector<LocalPose> poses_over(const grid::CoastGrid& g, int n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    const geo::Box e = g.extent();
    std::vector<LocalPose> out;
    for (int k = 0; k < n; ++k)
        out.push_back(LocalPose::at({e.minx + (e.maxx - e.minx) * unit(rng), e.miny + (e.maxy - e.miny) * unit(rng)}, 360 * unit(rng)));
    return out;
}

TEST(Surroundings, LeastDepthOnAChartEqualsALinearScanOfItsLevels) {
    // The binary search assumes that touching grows with the level; a scan of every level
    // from 0 up, with a check at each, does not.
    const grid::CoastGrid& base = annapolis_cut();
    const std::span<const double> depths = base.charted_depths();
    ASSERT_GT(depths.size(), 5u);
    const hull::Hull hull = hull::Hull::from_dimensions({45, 15, 5, 5});
    int land = 0, known = 0, unknown = 0;
    for (const LocalPose& p : poses_over(base, 3000, 17)) {
        double want = NAN;
        for (std::size_t level = 0; level <= depths.size(); ++level) {
            const std::optional<double> limit = level == 0 ? std::nullopt
                                                : std::isnan(depths[level - 1]) ? std::optional<double>(-INFINITY)
                                                                                : std::optional<double>(std::nextafter(depths[level - 1], INFINITY));
            ASSERT_EQ(base.level_of(limit), level);
            if (Detector(base, hull, limit).check(p).collision) {
                want = level == 0 ? 0.0 : depths[level - 1];
                break;
            }
        }
        const double got = least_charted_depth(base, hull, p);
        EXPECT_TRUE(got == want || (std::isnan(got) && std::isnan(want))) << "at " << p.position.x << "," << p.position.y;
        land += want == 0;
        known += want > 0 || want < 0;
        unknown += std::isnan(want);
    }
    std::printf("on the Annapolis cut: %d poses on land, %d over a known depth, %d none or unknown\n", land, known, unknown);
    EXPECT_GT(land, 100);
    EXPECT_GT(known, 100);
}

// ---------------------------------------------------------------- cost

/// A diagnosis figure, not a limit: the time per surroundings call near jagged islands.
TEST(SurroundingsCost, PerCall) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<coast::LocalPolyline> lines;
    for (int k = 0; k < 40; ++k) lines.push_back(jagged_island(rng, {10000 * unit(rng), 10000 * unit(rng)}, 100 + 400 * unit(rng), 200));
    const Scene s(lines, 500, hull::Hull::from_dimensions({150, 35, 14, 15}));
    std::vector<LocalPose> poses;
    for (int k = 0; k < 2000; ++k) poses.push_back(LocalPose::at({10000 * unit(rng), 10000 * unit(rng)}, 360 * unit(rng)));
    for (double max_m : {500.0, 2000.0, double{INFINITY}}) {
        double sum = 0;
        const auto t0 = std::chrono::steady_clock::now();
        for (const LocalPose& p : poses) sum += s.at(p, max_m).ahead_m;
        const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / poses.size();
        const auto t1 = std::chrono::steady_clock::now();
        for (const LocalPose& p : poses) sum += s.detector.check(p, {.max_clearance_m = max_m}).clearance_m > 0;
        const double check_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t1).count() / poses.size();
        std::printf("max_m %g: surroundings %.1f us per call; Detector::check to the same reach %.1f us (%g)\n", max_m, us, check_us, sum);
    }
}

/// Diagnosis figures on charts: the Solent (land only, 500 m cells) and the Annapolis cut
/// (9 charted depths: the least depth's binary search makes 4-5 checks).
TEST(SurroundingsCost, PerCallOnCharts) {
    grid::BuildRequest r;
    r.cell_m = 500;
    std::vector<std::string> warnings;
    const grid::CoastGrid solent = grid::build_grid({test::data_path("coast/uk_solent_land.geojson")}, r, &warnings);
    const hull::Hull hull = hull::Hull::from_dimensions({150, 35, 14, 15});
    auto per_call_us = [](const std::vector<LocalPose>& poses, auto&& f) {
        const auto t0 = std::chrono::steady_clock::now();
        double sum = 0;
        for (const LocalPose& p : poses) sum += f(p);
        const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / static_cast<double>(poses.size());
        return sum == -1 ? 0 : us;  // sum used
    };
    for (const auto& [name, g] : {std::pair<const char*, const grid::CoastGrid*>{"Solent", &solent}, {"Annapolis cut", &annapolis_cut()}}) {
        const Detector d(*g, hull, 8.0);
        // Afloat: the poses clear of land and hazards, as a simulator's ship mostly is.
        std::vector<LocalPose> poses;
        for (const LocalPose& p : poses_over(*g, 6000, 23))
            if (!d.check(p).collision) poses.push_back(p);
        for (double max_m : {500.0, 2000.0, double{INFINITY}}) {
            const double all = per_call_us(poses, [&](const LocalPose& p) { return surroundings(d, *g, p, max_m).ahead_m; });
            const double ahead = per_call_us(poses, [&](const LocalPose& p) {
                return travel_distance(d, p, {p.ship_to_local(0, 0), p.ship_to_local(1, 0)}, max_m);
            });
            const double check = per_call_us(poses, [&](const LocalPose& p) { return d.check(p, {.max_clearance_m = max_m}).clearance_m; });
            std::printf("%s, max_m %g: surroundings %.1f us per call; one travel_distance %.1f us; Detector::check to max_m %.1f us\n",
                        name, max_m, all, ahead, check);
        }
        const double depth = per_call_us(poses, [&](const LocalPose& p) { return least_charted_depth(*g, hull, p); });
        std::printf("%s: least_charted_depth %.1f us per call (%zu charted depths); %zu poses afloat\n", name, depth,
                    g->charted_depths().size(), poses.size());
    }
}

}  // namespace
}  // namespace shoal::check
