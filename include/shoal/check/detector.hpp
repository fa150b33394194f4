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

#include <shoal/geo/jacobian_field.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/grid/coast_grid.hpp>
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
