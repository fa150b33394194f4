#pragma once
/// Contact regions: what a simulator's collision response needs once a hull overlaps land, a
/// hazard or another hull. For a pose, every connected region where the hull overlaps what it
/// must not, each at its deepest point: the point of the region farthest inside (from the
/// boundary of everything the hull must not overlap: land, structures and the hazards of the
/// detector's limiting depth, taken together), the nearest boundary point, the unit normal
/// that frees the point by the shortest way, and the depth along it.
///
/// Exact to a micrometre: the deepest point is found by branch and bound (the outline inside
/// the hazards first, then the region's interior) with bounds that are tight on straight
/// boundaries, so a quay along the hull's side or a pier across it costs a few steps.

#include <cstdint>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/grid/coast_grid.hpp>

namespace shoal::check {

/// One connected region where the hull overlaps what it must not, at its deepest point.
struct ContactRegion {
    geo::XY hull_point;   ///< local metres: the region's deepest point (in the hull and in the hazard)
    geo::XY coast_point;  ///< local metres: the nearest point of the hazards' boundary to hull_point
    geo::XY normal;       ///< local unit vector: moving hull_point along it by the depth frees it
    double depth_m = 0;   ///< |coast_point - hull_point| in metres on the ground (>= 0)
    /// The boundary polyline coast_point lies on (grid::CoastGrid::hazard says what it bounds);
    /// no_polyline for a hull (hull_contact_regions).
    std::uint32_t polyline = grid::CoastGrid::no_polyline;
};

/// Every contact region of the detector's hull at `pose` against the detector's grid (land and
/// the hazards of its limiting depth, together), deepest first. Empty when the hull neither
/// touches nor overlaps them; a pose Detector::check calls a collision has at least one (depth
/// 0 when the hull only touches). A polyline without a land side (an open coastline line)
/// crossing the hull in the water gives a region of depth 0 at a point where it does; met on
/// the hazards' boundary (a coastline drawn on the land's edge) it gives none: the hull's
/// contact there is the hazards' region.
std::vector<ContactRegion> contact_regions(const Detector& detector, const LocalPose& pose);

/// The regions where hull outline `a` overlaps hull outline `b` (simple polygons, local metres,
/// open or closed rings), deepest first, the normal freeing a's point out of b. `scale`: local
/// metres per metre on the ground (LocalPose::ship_to_local's), for depth_m.
std::vector<ContactRegion> hull_contact_regions(const std::vector<geo::XY>& a, const std::vector<geo::XY>& b,
                                                double scale = 1.0);

/// Local metres per metre on the ground of a pose (the square root of its map's determinant).
double local_scale(const LocalPose& pose) noexcept;

/// A region as a simulator reads it: in the ship frame of its pose (x forward, y starboard,
/// metres on the ground from the reference point), the points in WGS84, and what was hit.
struct ShipFrameContact {
    double x_m = 0, y_m = 0;  ///< the deepest hull point
    double nx = 1, ny = 0;    ///< unit normal freeing it
    double depth_m = 0;
    geo::LonLat point, coast_point;
    /// What the region overlaps (grid::CoastGrid::hazard of its polyline); null for a hull or
    /// when the polyline is not known.
    const coast::Hazard* hazard = nullptr;
};

/// `region` of the hull at `pose` in `frame`, with its hazard from `grid` (null: none).
ShipFrameContact in_ship_frame(const ContactRegion& region, const LocalPose& pose, const geo::LocalFrame& frame,
                               const grid::CoastGrid* grid);

}  // namespace shoal::check
