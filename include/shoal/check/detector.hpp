#pragma once
/// `Detector`: the pose check. Given where a ship's reference point is and its true heading,
/// does the hull touch land, and how far is it from land? Uses the grid: only the cells
/// under the hull's bounding box grown by the margin are read, then rings of cells outward
/// until no nearer coastline can exist.

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

#include <shoal/check/placement.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::check {

/// The result of one pose check.
struct Contact {
    bool collision = false;         ///< hull touches or overlaps land (or a coastline line)
    bool covered = true;            ///< the hull's box lies inside the grid's extent
    double clearance_m = INFINITY;  ///< distance hull to coastline; 0 on collision; INFINITY when beyond the search limit
    double penetration_m = 0;       ///< on collision: how deep the hull reaches past the coastline (see docs)
    geo::XY hull_point;             ///< hull point realising the clearance (a contact point on collision)
    geo::XY coast_point;            ///< coastline point realising the clearance (same point on collision)
    /// The grid polyline realising the contact or the clearance (grid::CoastGrid::hazard says
    /// what it bounds): the one a hull edge crosses, or the nearest; for a hull wholly inside
    /// land or a hazard, the nearest ring that holds it (CoastGrid::enclosing_polyline); for a
    /// hazard wholly under the hull, that hazard. no_polyline when none is known.
    std::uint32_t polyline = grid::CoastGrid::no_polyline;
};

struct CheckOptions {
    /// Search for clearance no further than this (metres); beyond it clearance is INFINITY.
    /// Collision does not depend on it: 0 asks whether the hull touches and little else.
    double max_clearance_m = INFINITY;
    /// Compute penetration depth on collision (extra nearest-segment searches).
    bool want_penetration = true;
    /// Find `Contact::polyline` for a hull wholly inside land or over an islet (a search of
    /// the grid's rings); when false it is left no_polyline in those two cases. The polyline
    /// of a crossing edge or of the clearance costs nothing and is always given (but see
    /// want_contact_point).
    bool want_polyline = true;
    /// Say where a collision is: `Contact::hull_point` and `coast_point` the point the full
    /// search finds (a crossing of a hull edge, else the hull point or coast vertex found
    /// inside), and the polyline it crossed. When false (and want_polyline false), a collision
    /// may be answered by the hull point this thread last found on land, tried before any
    /// search (one winding test): both points are then that point and the polyline
    /// no_polyline. Collision, covered, clearance and penetration are the same either way.
    bool want_contact_point = true;
    /// A clearance the hull is known to have at most (metres): say, the last pose's clearance
    /// plus how far any hull point moved since. The clearance search starts with it as its
    /// bound, so the far coast is passed over from the first segment on; when nothing lies
    /// that near (a hint too small), it searches again without. The answer is the same
    /// whatever the hint; only the time changes (but for an exact tie: when two pairs of
    /// hull and coast points are exactly equally near, either may be given). INFINITY (or
    /// NaN, or <= 0): no hint.
    double clearance_hint_m = INFINITY;
};

class Detector {
public:
    /// Checks against the hazards of `grid` for its default limiting depth
    /// (GridSource::limiting_depth_m, `shoal import --hazard-depth`; none: land only). Keeps a
    /// reference to `grid`, which must outlive the detector (a temporary grid is refused).
    Detector(const grid::CoastGrid& grid, const hull::Hull& hull);
    /// Checks against the hazards for the vessel's own limiting depth `limiting_depth_m`
    /// (draught + under-keel clearance; CoastGrid::for_depth): land, and the depth areas and
    /// dangers charted shallower or of unknown depth. None: land only.
    Detector(const grid::CoastGrid& grid, const hull::Hull& hull, std::optional<double> limiting_depth_m);
    Detector(grid::CoastGrid&& grid, const hull::Hull& hull) = delete;
    Detector(grid::CoastGrid&& grid, const hull::Hull& hull, std::optional<double> limiting_depth_m) = delete;

    Contact check(const Pose& pose, const CheckOptions& options = {}) const;
    Contact check(const LocalPose& pose, const CheckOptions& options = {}) const;

    /// Whether the hull at `pose` lies inside the grid's extent: Contact::covered, as check()
    /// gives it, without the check.
    bool covers(const LocalPose& pose) const noexcept;

    /// Nearest coastline segment to p within `max_m` (INFINITY if none): distance, and the point.
    double nearest_coast(geo::XY p, double max_m, geo::XY* on_coast) const;

    /// The grid checked against: the hazards for the detector's limiting depth.
    const grid::CoastGrid& grid() const noexcept { return m_grid; }
    const hull::Hull& hull() const noexcept { return m_hull; }

private:
    const grid::CoastGrid& m_grid;
    hull::Hull m_hull;
};

}  // namespace shoal::check
