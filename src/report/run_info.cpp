// The run header of a report (report::run_info): what was checked, against what, by which rules.
#include <shoal/report/report.hpp>

#include <cmath>
#include <cstdio>

#include <shoal/grid/limiting_depth.hpp>

namespace shoal::report {

namespace {

std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out;
}

}  // namespace

RunInfo run_info(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const std::string& ship,
                 const audit::AuditOptions& options, const std::vector<std::string>& berths, double default_draught_m) {
    RunInfo info;
    info.coast = joined(coast);
    info.frame = grid.frame().description();
    info.cell_m = grid.cell_size();
    const grid::DepthPlan depth = grid::plan_vessel_depth(options.hazard_depth_m, NAN, default_draught_m, options.ukc_m, grid);
    info.limiting_depth_m = depth.depth_m.value_or(NAN);
    info.limiting_depth_source = grid::to_string(depth.source);
    info.ukc_m = options.ukc_m.value_or(0.0);
    info.grid_fingerprint = grid::fingerprint_hex(grid.source().fingerprint);
    info.ship = ship;
    info.sweep = options.sweep;
    info.world = options.world;
    info.evidence = options.evidence;
    info.wild = options.wild;
    info.berths = joined(berths);
    info.ship_margin_m = options.encounter.ship_margin_m;
    info.exercise_by = audit::exercise_by_text(options.exercise_by, options.read.exercise_column);
    info.role_column = options.read.role_column;
    info.encounter_range_m = options.colreg.range_m;
    info.max_encounters_per_ship = options.max_encounters_per_ship;
    return info;
}

}  // namespace shoal::report
