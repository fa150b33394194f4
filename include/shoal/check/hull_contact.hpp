#pragma once
/// Hull-to-hull contact: whether two hull outlines (simple polygons, local metres) touch or
/// overlap, and if not their clearance and closest points. Used by the ship-to-ship
/// encounters (audit/encounters.hpp); exact, the same answer as GEOS' intersects and distance.

#include <cmath>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::check {

/// Contact between two hull outlines (simple polygons) in local metres.
struct HullContact {
    bool collision = false;         ///< the outlines touch or overlap, or one holds the other
    double clearance_m = INFINITY;  ///< 0 on collision
    geo::XY on_a, on_b;             ///< closest points (the same contact point on collision)
};

/// Exact contact of outlines `a` and `b` (open or closed rings): every edge pair, then
/// containment of a vertex of one in the other. Of equally near edge pairs the first (in
/// edge order of a, then b) gives the points.
HullContact hull_contact(const std::vector<geo::XY>& a, const std::vector<geo::XY>& b);

/// The same answer for two hulls at poses, as find_encounters computes it: only the edge
/// pairs that capsule bounds (around chunks of edges, then single edges) cannot rule out are
/// tested.
HullContact hull_contact(const hull::Hull& a, const LocalPose& pose_a, const hull::Hull& b, const LocalPose& pose_b);

}  // namespace shoal::check
