// Hull-to-hull contact against GEOS (GEOSIntersects / GEOSDistance on the same polygons) on
// random poses of several hull shapes, convex and not, some wholly inside others, and the
// pruned search against the all-edges answer.

#include <gtest/gtest.h>

#include <random>

#include <shoal/check/hull_contact.hpp>
#include "test_support.hpp"

namespace shoal::check {
namespace {

using geo::XY;

/// A frame centred at (0, 0) lon/lat.
const geo::LocalFrame& frame() {
    static const geo::LocalFrame f = geo::LocalFrame::transverse_mercator({0.0, 0.0});
    return f;
}

/// A box-shaped hull: 80 m forward and 20 m aft of the reference point, 8 m to either side.
hull::Hull box_hull() { return hull::Hull::from_contour({{80, -8}, {80, 8}, {-20, 8}, {-20, -8}}, "box"); }

/// A U-shaped (non-convex) hull: two hulls of a catamaran joined at the stern.
hull::Hull catamaran() {
    // The notch is x in [5, 55], y in [-6, 6]; the reference point is on the crossbeam.
    return hull::Hull::from_contour({{55, -12}, {55, -6}, {5, -6}, {5, 6}, {55, 6}, {55, 12}, {-5, 12}, {-5, -12}}, "cat");
}

TEST(HullContact, AgreesWithGeosOnRandomPoses) {
    const geo::GeosContext ctx;
    const std::vector<hull::Hull> hulls = {hull::Hull::from_dimensions({80, 20, 8, 8}), hull::Hull::from_dimensions_n({30, 10, 5, 4}, 8),
                                           box_hull(), catamaran(), hull::Hull::from_dimensions({200, 50, 20, 20})};
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t disagreements = 0, collisions = 0, nested = 0;
    for (int k = 0; k < 4000; ++k) {
        const hull::Hull& ha = hulls[rng() % hulls.size()];
        const hull::Hull& hb = hulls[rng() % hulls.size()];
        const double spread = k % 4 == 0 ? 20 : 200;
        const check::LocalPose pa = place(frame(), {frame().inverse({0, 0}), 360 * u(rng)});
        const check::LocalPose pb = place(frame(), {frame().inverse({(u(rng) - 0.5) * spread, (u(rng) - 0.5) * spread}), 360 * u(rng)});
        const auto a = hull_outline(ha, pa), b = hull_outline(hb, pb);
        const HullContact ref = hull_contact(a, b);
        const HullContact fast = hull_contact(ha, pa, hb, pb);
        auto ring = [](std::vector<XY> r) { r.push_back(r.front()); return r; };
        const auto ga = test::polygon(ctx, {ring(a)}), gb = test::polygon(ctx, {ring(b)});
        const bool geos_hit = GEOSIntersects_r(ctx, ga.get(), gb.get()) == 1;
        double geos_d = 0;
        ASSERT_EQ(GEOSDistance_r(ctx, ga.get(), gb.get(), &geos_d), 1);
        const bool ok = ref.collision == geos_hit && std::fabs(ref.clearance_m - geos_d) < 1e-6 &&
                        fast.collision == ref.collision && fast.clearance_m == ref.clearance_m && fast.on_a == ref.on_a &&
                        fast.on_b == ref.on_b && std::fabs(geo::distance(ref.on_a, ref.on_b) - ref.clearance_m) < 1e-6;
        if (!ok && ++disagreements <= 5)
            ADD_FAILURE() << "pose " << k << ": GEOS " << geos_hit << " " << geos_d << ", all edges " << ref.collision << " "
                          << ref.clearance_m << ", pruned " << fast.collision << " " << fast.clearance_m << "\n  a "
                          << test::wkt(ctx, ga.get()) << "\n  b " << test::wkt(ctx, gb.get());
        collisions += geos_hit;
        // One inside the other with no edges crossing: GEOS contains.
        nested += GEOSContains_r(ctx, ga.get(), gb.get()) == 1 || GEOSContains_r(ctx, gb.get(), ga.get()) == 1;
    }
    EXPECT_EQ(disagreements, 0u);
    EXPECT_GT(collisions, 500u);
    EXPECT_GT(nested, 10u) << "the poses should include hulls wholly inside others";
}

TEST(HullContact, SmallHullInsideABigOneIsAContact) {
    const auto big = hull::Hull::from_dimensions({200, 50, 20, 20}).placed({0, 0}, 0);
    const auto small = hull::Hull::from_contour({{10, -2}, {10, 2}, {-5, 2}, {-5, -2}}).placed({0, 20}, 0);
    EXPECT_TRUE(hull_contact(big, small).collision);
    EXPECT_TRUE(hull_contact(small, big).collision);
    // Inside the catamaran's notch but touching nothing: clear.
    const auto cat = catamaran().placed({0, 0}, 0);
    const auto boat = hull::Hull::from_contour({{10, -2}, {10, 2}, {-5, 2}, {-5, -2}}).placed({0, 20}, 0);
    const HullContact c = hull_contact(cat, boat);
    EXPECT_FALSE(c.collision);
    EXPECT_NEAR(c.clearance_m, 4, 1e-9);  // 2 m beam either side in the 12 m notch
}

}  // namespace
}  // namespace shoal::check
