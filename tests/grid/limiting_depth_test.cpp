// Tests of limiting_depth.hpp: the rule (explicit hazard depth, else draught + UKC, else land
// only), by hand. How a grid file serves a plan is tested end to end in tests/cli
// (ALandOnlyGridWithAShipThatHasADraughtIsSaid).

#include <gtest/gtest.h>

#include <shoal/grid/limiting_depth.hpp>

namespace {

using shoal::grid::DepthPlan;
using shoal::grid::plan_limiting_depth;

TEST(PlanLimitingDepth, AnExplicitDepthWinsOverTheDraught) {
    const DepthPlan p = plan_limiting_depth(7.5, 9.0, 1.0);
    EXPECT_EQ(p.depth_m, 7.5);
    EXPECT_EQ(p.source, DepthPlan::Source::hazard_depth);
    EXPECT_FALSE(p.ukc_unused);
}

TEST(PlanLimitingDepth, ElseTheDraughtPlusTheUnderKeelClearance) {
    const DepthPlan p = plan_limiting_depth(std::nullopt, 9.0, 1.5);
    EXPECT_EQ(p.depth_m, 10.5);
    EXPECT_EQ(p.source, DepthPlan::Source::draught);
    EXPECT_EQ(p.draught_m, 9.0);
    EXPECT_EQ(p.ukc_m, 1.5);
    EXPECT_EQ(plan_limiting_depth(std::nullopt, 9.0, std::nullopt).depth_m, 9.0);
}

TEST(PlanLimitingDepth, ElseLandOnlyAndAnUnderKeelClearanceGoesUnused) {
    const DepthPlan p = plan_limiting_depth(std::nullopt, 0.0, 2.0);
    EXPECT_EQ(p.depth_m, std::nullopt);
    EXPECT_EQ(p.source, DepthPlan::Source::land_only);
    EXPECT_TRUE(p.ukc_unused);
    EXPECT_FALSE(plan_limiting_depth(std::nullopt, 0.0, std::nullopt).ukc_unused);
}

}  // namespace
