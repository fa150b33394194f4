#pragma once
/// What a bridge simulator asks every frame beside the contacts: how far the hull can move
/// along each of its four axes before it touches a hazard (the *travel distance*), and the
/// least charted depth under it.
///
/// The travel distance is exact: the hull outline translated by t along a direction first
/// touches a segment of the grid at the least t where a hull vertex, moving along the
/// direction, meets a segment, or a segment's end, moving the other way, meets a hull edge.
/// Only the cells the swept hull covers are read (its box swept along the direction), and
/// only as far out as needed: the sweep grows by doubling until a contact is found within it.

#include <cmath>

#include <shoal/check/detector.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::check {

/// How far (local metres) the hull of `detector` at `pose` can be translated along
/// `direction_local_unit` (a unit vector in local metres) before it touches a segment of the
/// detector's grid (land or a hazard): 0 when the pose is already in contact
/// (Detector::check says collision); capped at `max_m` (> 0; INFINITY: until the grid ends,
/// and INFINITY when nothing lies that way). Throws UsageError for a direction that is not a
/// unit vector or a max_m that is not > 0.
double travel_distance(const Detector& detector, const LocalPose& pose, geo::XY direction_local_unit, double max_m);

/// The least charted depth (metres) of the depth areas and dangers that the hull of `hull`
/// at `pose` touches or overlaps, read from `base`, the grid holding every depth area and
/// danger (the grid a Detector was made from, not Detector::grid()): 0 when it touches land or
/// a structure (whatever the depths around); NaN when it touches none of them (no depth
/// charted there) or when the least is an area or danger of unknown depth. A depth may be
/// negative (the area dries). Found by a binary search over the grid's levels
/// (CoastGrid::charted_depths) with one pose check per level tried: whether the hull touches
/// the hazards of a level only grows with the level.
double least_charted_depth(const grid::CoastGrid& base, const hull::Hull& hull, const LocalPose& pose);

/// The answers of `surroundings`: distances in true metres on the ground.
struct Surroundings {
    /// The hull's box, and the hull's box moved by each distance found (by max_m where none
    /// was found), lie inside the grid's extent. When false, a distance says only what the
    /// chart holds (INFINITY with max_m INFINITY is always uncovered: the hull leaves the chart).
    bool covered = false;
    double port_m = 0;       ///< travel to port (ship frame -y); 0 in contact, capped at max_m
    double starboard_m = 0;  ///< travel to starboard (+y)
    double ahead_m = 0;      ///< travel ahead (+x)
    double astern_m = 0;     ///< travel astern (-x)
    double least_depth_m = NAN;  ///< least_charted_depth
};

/// The hull's travel distances along its four axes and the least charted depth under it.
/// Each axis of the ship frame is mapped through LocalPose::ship_to_local; the local scale
/// along it (the mapped vector's length) turns local metres into metres on the ground, and
/// max_m (> 0, INFINITY allowed) is on the ground too. `base` is the grid `detector` was made
/// from (see least_charted_depth); UsageError when its cells differ from the detector's grid's.
Surroundings surroundings(const Detector& detector, const grid::CoastGrid& base, const LocalPose& pose, double max_m);

}  // namespace shoal::check
