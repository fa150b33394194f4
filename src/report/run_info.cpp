// The run header of a report (report::run_info): what was checked, against what, by which rules.
#include <shoal/report/report.hpp>

#include <cstdio>

namespace shoal::report {

namespace {

std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out;
}

}  // namespace

RunInfo run_info(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const std::string& ship,
                 const audit::AuditOptions& options, const std::vector<std::string>& berths) {
    RunInfo info;
    info.coast = joined(coast);
    info.frame = grid.frame().description();
    info.cell_m = grid.cell_size();
    info.limiting_depth_m = grid.source().limiting_depth_m;
    char fp[20];
    std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(grid.source().fingerprint));
    info.grid_fingerprint = fp;
    info.ship = ship;
    info.sweep = options.sweep;
    info.wild = options.wild;
    info.berths = joined(berths);
    info.ship_margin_m = options.encounter.ship_margin_m;
    info.exercise_by = audit::to_string(options.exercise_by);
    info.encounter_range_m = options.colreg.range_m;
    return info;
}

}  // namespace shoal::report
