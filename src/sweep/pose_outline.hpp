#pragma once
/// The hull outline of a pose as the report's `poses` layer draws it (Pose::hull): simplified
/// with GEOS (GEOSSimplify, Douglas-Peucker of the closed outline; GEOSTopologyPreserveSimplify
/// of the polygon where that leaves a ring that is not simple, or has fewer than
/// pose_outline_min_corners corners) to within pose_outline_tolerance of the hull's length (its
/// longest vertex-to-vertex distance), in metres; never fewer than pose_outline_min_corners
/// corners (else the outline is kept whole). The kept vertices are the outline's own, in
/// order, and the first (the generated hull's bow tip) is always kept. A 36-point hull comes
/// out with about 10 (docs/user-guide.md, "poses"). The sweep simplifies a hull once, in its
/// own metres (a pose places it by a rotation and the frame's conformal scale, which change
/// nothing of it), and places only the corners kept. It depends only on the outline: shards
/// merge byte for byte.
#include <cstddef>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::audit {

/// Fraction of the hull's length the drawn outline may depart from the true one.
inline constexpr double pose_outline_tolerance = 0.01;
/// Fewest distinct corners a simplified outline keeps.
inline constexpr std::size_t pose_outline_min_corners = 4;

/// The vertices of the closed outline `ring` (metres, first == last) the drawn outline keeps,
/// as ascending indices into it from 0, the closing vertex not counted: every vertex but the
/// last when it has fewer than 4 points or simplification would leave fewer than
/// pose_outline_min_corners corners.
std::vector<std::size_t> pose_outline_corners(const std::vector<geo::XY>& ring);

}  // namespace shoal::audit
