#include <shoal/grid/limiting_depth.hpp>

#include <cmath>

#include <shoal/coast/coastline.hpp>

namespace shoal::grid {

const char* to_string(DepthPlan::Source s) noexcept {
    switch (s) {
    case DepthPlan::Source::hazard_depth: return "hazard_depth";
    case DepthPlan::Source::draught: return "ship_draught";
    case DepthPlan::Source::land_only: return "land_only";
    case DepthPlan::Source::vessel_draught: return "vessel_draught";
    case DepthPlan::Source::grid_default: return "grid_default";
    }
    return "?";
}

DepthPlan plan_limiting_depth(std::optional<double> hazard_depth_m, double draught_m, std::optional<double> ukc_m) noexcept {
    DepthPlan plan;
    plan.ukc_m = ukc_m.value_or(0.0);
    plan.depth_m = coast::limiting_depth(hazard_depth_m, draught_m, plan.ukc_m);
    if (hazard_depth_m) {
        plan.source = DepthPlan::Source::hazard_depth;
    } else if (plan.depth_m) {
        plan.source = DepthPlan::Source::draught;
        plan.draught_m = draught_m;
    } else {
        plan.ukc_unused = ukc_m.has_value();
    }
    return plan;
}

DepthPlan plan_vessel_depth(std::optional<double> hazard_depth_m, double vessel_draught_m, double default_draught_m,
                            std::optional<double> ukc_m, const CoastGrid& grid) noexcept {
    if (!hazard_depth_m && vessel_draught_m > 0) {  // false for NaN
        DepthPlan plan = plan_limiting_depth(std::nullopt, vessel_draught_m, ukc_m);
        plan.source = DepthPlan::Source::vessel_draught;
        return plan;
    }
    DepthPlan plan = plan_limiting_depth(hazard_depth_m, default_draught_m, ukc_m);
    if (!plan.depth_m && !std::isnan(grid.source().limiting_depth_m)) {
        plan.depth_m = grid.source().limiting_depth_m;
        plan.source = DepthPlan::Source::grid_default;
    }
    return plan;
}

}  // namespace shoal::grid
