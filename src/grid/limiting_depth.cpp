#include <shoal/grid/limiting_depth.hpp>

#include <cmath>

#include <shoal/coast/coastline.hpp>

namespace shoal::grid {

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

DepthFit depth_fit(const CoastGrid& grid, const DepthPlan& plan) noexcept {
    if (!plan.depth_m) return DepthFit::fits;
    const double built = grid.source().limiting_depth_m;
    if (std::isnan(built)) return DepthFit::land_only;
    if (built < *plan.depth_m) return DepthFit::shallower;
    if (built > *plan.depth_m) return DepthFit::deeper;
    return DepthFit::fits;
}

}  // namespace shoal::grid
