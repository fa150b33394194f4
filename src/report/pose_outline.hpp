#pragma once
/// The hull outline of a pose as the report's `poses` layer draws it: simplified with GEOS
/// (GEOSSimplify, Douglas-Peucker of the closed outline; GEOSTopologyPreserveSimplify of the
/// polygon where that leaves a ring that is not simple, or has fewer than
/// pose_outline_min_corners corners) to within
/// pose_outline_tolerance of the hull's length (its longest vertex-to-vertex distance), in
/// local metres around the pose; never fewer than pose_outline_min_corners corners (else the
/// outline is kept whole). The kept vertices are the outline's own, unrounded, in order, and
/// the first (the generated hull's bow tip) is always kept. A 36-point hull comes out with
/// about 10 (docs/user-guide.md, "poses"). It depends only on the outline: shards merge
/// byte for byte.
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::report {

/// Fraction of the hull's length the drawn outline may depart from the true one.
inline constexpr double pose_outline_tolerance = 0.01;
/// Fewest distinct corners a simplified outline keeps.
inline constexpr std::size_t pose_outline_min_corners = 4;

/// `ring` (closed: first == last, lon/lat) simplified as above; returned as it is when it has
/// fewer than 4 points or simplification would leave fewer than pose_outline_min_corners corners.
std::vector<geo::LonLat> pose_outline(const std::vector<geo::LonLat>& ring);

}  // namespace shoal::report
