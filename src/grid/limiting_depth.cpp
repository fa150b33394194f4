#include <shoal/grid/limiting_depth.hpp>

#include <cmath>
#include <cstdio>

#include <shoal/coast/coastline.hpp>

namespace shoal::coast {

// Here rather than in coastline.cpp (which reads charts with GDAL): the GDAL-free core
// (src/CMakeLists.txt: shoal_core) plans a vessel's limiting depth too.
std::optional<double> limiting_depth(std::optional<double> hazard_depth_m, double draught_m, double ukc_m) noexcept {
    if (hazard_depth_m) return hazard_depth_m;
    if (draught_m > 0) return draught_m + ukc_m;
    return std::nullopt;
}

}  // namespace shoal::coast

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

std::vector<std::string> depth_warnings(const DepthPlan& plan, const CoastGrid& grid, const std::string& grid_name) {
    std::vector<std::string> w;
    if (plan.ukc_unused && !plan.depth_m)
        w.push_back("AuditOptions::ukc_m needs a ship with a draught (or give AuditOptions::hazard_depth_m): checking against land only");
    if (plan.depth_m && grid.charted_depths().empty()) {
        const char* why = "the ship's draught + AuditOptions::ukc_m";
        switch (plan.source) {
            case DepthPlan::Source::hazard_depth: why = "AuditOptions::hazard_depth_m"; break;
            case DepthPlan::Source::grid_default: why = "the grid's default"; break;
            case DepthPlan::Source::vessel_draught: why = "the vessel's draught + AuditOptions::ukc_m"; break;
            case DepthPlan::Source::draught:
            case DepthPlan::Source::land_only: break;  // land only has no depth: not here
        }
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.2f m (%s)", *plan.depth_m, why);
        w.push_back((grid_name.empty() ? std::string("the grid") : "the grid '" + grid_name + "'") +
                    " holds land only (no depth areas or dangers): shallow water is not checked for the limiting depth " + buf +
                    "; build it from a chart with depth areas (S-57 DEPARE, or ImportOptions::depth_field)");
    }
    return w;
}

}  // namespace shoal::grid
