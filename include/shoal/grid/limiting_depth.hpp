#pragma once
/// The limiting depth of a vessel: which charted depth makes water a hazard for it. The rule
/// every front end follows: an explicit hazard depth (for every vessel) wins; else the
/// vessel's own draught (AIS type 5, a track column, a vessels table) plus the under-keel
/// clearance; else the default ship's draught (the ship file's `draught`) plus it; else the
/// grid's default limiting depth (`shoal import --hazard-depth`); else land only. One grid
/// holds every depth area and danger, so each vessel is checked at its own limit
/// (CoastGrid::for_depth).

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <shoal/grid/coast_grid.hpp>

namespace shoal::grid {

struct DepthPlan {
    enum class Source {
        hazard_depth,    ///< an explicit hazard depth for every vessel
        draught,         ///< the default ship's draught (ship file) + under-keel clearance
        land_only,       ///< nothing known: land only
        vessel_draught,  ///< the vessel's own draught + under-keel clearance
        grid_default,    ///< the grid's default limiting depth (import --hazard-depth)
    };
    std::optional<double> depth_m;  ///< the limiting depth; none: land only
    Source source = Source::land_only;
    double draught_m = 0;           ///< the draught used, when source is draught or vessel_draught
    double ukc_m = 0;               ///< the under-keel clearance added to it
    /// An under-keel clearance was given but nothing uses it: no hazard depth and a ship
    /// without a draught, so the check is against land only (or the grid's default).
    bool ukc_unused = false;
};

/// "hazard_depth", "ship_draught", "land_only", "vessel_draught", "grid_default" (the report's
/// `limiting_depth_source`).
const char* to_string(DepthPlan::Source s) noexcept;

/// The plan for a ship of draught `draught_m` (0: unknown) given an explicit `hazard_depth_m`
/// and an under-keel clearance `ukc_m` (both optional).
DepthPlan plan_limiting_depth(std::optional<double> hazard_depth_m, double draught_m, std::optional<double> ukc_m) noexcept;

/// The plan for one vessel of a run: `hazard_depth_m` when given; else its own draught
/// `vessel_draught_m` (NaN or <= 0: not known) + `ukc_m`; else the default ship's draught
/// `default_draught_m` (0: none) + `ukc_m`; else `grid`'s default limiting depth; else land only.
DepthPlan plan_vessel_depth(std::optional<double> hazard_depth_m, double vessel_draught_m, double default_draught_m,
                            std::optional<double> ukc_m, const CoastGrid& grid) noexcept;

/// What the user should hear about `plan` for checks against `grid` (named `grid_name` in the
/// message; "": "the grid"): an under-keel clearance that nothing uses, and a limiting depth
/// on a grid that holds land only (a shallow grounding would be missed without a word). Option
/// fields are named as the library names them (AuditOptions::ukc_m): see in_terms_of().
std::vector<std::string> depth_warnings(const DepthPlan& plan, const CoastGrid& grid, const std::string& grid_name = "");

}  // namespace shoal::grid
