#pragma once
/// Placement: where a ship's pose (the WGS84 position of its reference point and its true
/// heading) puts the hull in a grid's local frame, for the Detector to check.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <numbers>
#include <span>
#include <vector>

#include <shoal/geo/jacobian_field.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::check {

/// A ship's pose: WGS84 position of the reference point and true heading in degrees.
struct Pose {
    geo::LonLat position;
    double heading_deg = 0;
};

/// A pose in the grid's frame: reference point in local metres and the linear map from ship
/// coordinates (x forward, y starboard, metres) to local metres (rotation by the grid
/// heading, times the frame's local scale).
struct LocalPose {
    geo::XY position;
    Eigen::Matrix2d ship_to_local = Eigen::Matrix2d::Identity();

    /// The pose at `position` (local metres) heading `grid_heading_deg` clockwise from grid
    /// north (the frame's +y), at a local scale of 1: shapes made in metres, tests, benchmarks.
    static LocalPose at(geo::XY position, double grid_heading_deg) {
        const double h = grid_heading_deg * std::numbers::pi / 180;
        LocalPose p;
        p.position = position;
        p.ship_to_local << std::sin(h), std::cos(h), std::cos(h), -std::sin(h);
        return p;
    }
};

/// Where the hull of `hull` lies for `pose` in `frame`: heading corrected for meridian
/// convergence and the frame's scale applied, so points land where geodesics put them.
LocalPose place(const geo::LocalFrame& frame, const Pose& pose);
/// `place` with one projection: the Jacobian taken from `field` (fitted to a frame of the same
/// definition as `frame`) where it covers the position, else from the frame as `place` does.
LocalPose place(const geo::LocalFrame& frame, const geo::JacobianField& field, const Pose& pose);
/// The same for many poses, their positions projected in one batch. Throws InputError, as
/// one by one, for the first pose that cannot be placed.
std::vector<LocalPose> place(const geo::LocalFrame& frame, const geo::JacobianField& field, std::span<const Pose> poses);
/// How many poses place_in_blocks places at once.
inline constexpr std::size_t placement_block = 4096;
/// Poses 0 .. n-1 (`pose_of(k)` gives pose k) placed placement_block at a time, as the batch
/// `place` does (one projection a pose), on `jobs` threads (0: every core; at most 4 a core):
/// `use(from, placed, worker)` is called once per block, on the thread that placed it, with
/// the poses from, from + 1, ... in order; `worker` (0 .. threads - 1) is that thread's number,
/// for state of its own. Blocks come in any order, several at once; `pose_of` is called from
/// every thread. Throws, on the calling thread once the threads have stopped, what the first
/// block in input order that failed threw (InputError for a pose that cannot be placed, as one
/// by one; or what `use` threw); the blocks after it may not have been handed over.
void place_in_blocks(const geo::LocalFrame& frame, const geo::JacobianField& field, std::size_t n,
                     const std::function<Pose(std::size_t)>& pose_of, unsigned jobs,
                     const std::function<void(std::size_t from, std::span<const LocalPose> placed, unsigned worker)>& use);
/// The hull's outline in local metres for a pose.
std::vector<geo::XY> hull_outline(const hull::Hull& hull, const LocalPose& pose);

}  // namespace shoal::check
