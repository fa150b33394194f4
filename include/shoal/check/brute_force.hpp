#pragma once
/// The paper's "traversal": every pose is checked against every coastline segment. Used by
/// tests and benchmarks as the reference, never by the CLI.

#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>

namespace shoal::check {

class BruteForce {
public:
    BruteForce(std::vector<coast::LocalPolyline> lines, const hull::Hull& hull);
    /// Collision and clearance exactly as Detector defines them, without any index.
    Contact check(const LocalPose& pose) const;
    /// Winding number of land around p over all land boundary segments (> 0: land).
    int winding(geo::XY p) const;

private:
    std::vector<coast::LocalPolyline> m_lines;
    hull::Hull m_hull;
};

}  // namespace shoal::check
