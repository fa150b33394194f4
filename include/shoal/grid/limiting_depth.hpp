#pragma once
/// The limiting depth of a run: which charted depth makes water a hazard for the ship, and
/// whether a grid file already built serves it. The rule every front end follows:
/// an explicit hazard depth wins; else the ship's draught plus the under-keel clearance when
/// the ship has a draught; else land only.

#include <optional>

#include <shoal/grid/coast_grid.hpp>

namespace shoal::grid {

struct DepthPlan {
    enum class Source { hazard_depth, draught, land_only };
    std::optional<double> depth_m;  ///< the limiting depth; none: land only
    Source source = Source::land_only;
    double draught_m = 0;           ///< the ship's, when source is draught
    double ukc_m = 0;               ///< the under-keel clearance added to it
    /// An under-keel clearance was given but nothing uses it: no hazard depth and a ship
    /// without a draught, so the run checks against land only.
    bool ukc_unused = false;
};

/// The plan for a ship of draught `draught_m` (0: unknown) given an explicit `hazard_depth_m`
/// and an under-keel clearance `ukc_m` (both optional).
DepthPlan plan_limiting_depth(std::optional<double> hazard_depth_m, double draught_m, std::optional<double> ukc_m) noexcept;

/// How a grid's own limiting depth (fixed when it was built) serves a plan.
enum class DepthFit {
    fits,       ///< built for the plan's depth, or the plan is land only
    land_only,  ///< the plan has a depth; the grid holds land only: shallow water is not checked
    shallower,  ///< built for a smaller depth: water between the two is not seen as a hazard
    deeper,     ///< built for a larger depth: more water counts as a hazard than needed
};

DepthFit depth_fit(const CoastGrid& grid, const DepthPlan& plan) noexcept;

}  // namespace shoal::grid
