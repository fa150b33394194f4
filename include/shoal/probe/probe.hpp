#pragma once
/// `Probe`: the one library face for checking poses, rendered by `shoal probe`, Python's
/// `Detector.check` and the C API's `shoal_check`. It owns the detector (the grid at the vessel's
/// limiting depth and the hull) and the placement (the frame's Jacobian fitted once over the
/// chart), validates each pose once, checks a span of poses in blocks on threads, and applies
/// the one rule of what an answer claims:
///
///   Outside the chart nothing is claimed. A hull whose box lies (partly) outside the grid's
///   extent is not covered: a collision found there is real and is said, but no collision
///   found says nothing, and no clearance is claimed (Answer::claimed() is false).

#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/geo/jacobian_field.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::probe {

/// What is asked of every pose.
struct Ask {
    /// Search for clearance no further than this (metres); beyond it the clearance is INFINITY.
    double max_clearance_m = INFINITY;
    /// Measure how deep the hull reaches past the coast on a collision.
    bool want_penetration = false;
};

/// What the probe says of one pose.
struct Answer {
    bool valid = false;      ///< the pose was checked (false: refused, see Batch::first_problem)
    bool covered = false;    ///< the hull's box lies inside the chart (the grid's extent)
    bool collision = false;  ///< the hull touches or overlaps land or a hazard (real, chart or not)
    /// 0 on collision; where claimed, the clearance (INFINITY beyond Ask::max_clearance_m);
    /// NaN where nothing is claimed (outside the chart, no collision found; or not valid).
    double clearance_m = NAN;
    double penetration_m = NAN;  ///< on collision when asked (Ask::want_penetration), else NaN

    /// The rule: inside the chart, or a collision found (which is real wherever it is).
    bool claimed() const noexcept { return valid && (covered || collision); }
};

/// Why a pose (WGS84 degrees, true heading in degrees) cannot be checked, in words ("latitude
/// 95 is outside [-90, 90]", "heading nan is not a number"); none when it can: latitude in
/// [-90, 90], longitude in [-180, 180], heading finite (any value, taken modulo 360).
std::optional<std::string> pose_problem(double lat, double lon, double heading_deg);

/// The answers for a span of poses.
struct Batch {
    std::vector<Answer> answers;  ///< one per pose, in input order
    std::size_t invalid = 0;      ///< poses refused (not valid, or not placeable)
    std::size_t uncovered = 0;    ///< valid poses whose hull is not covered by the chart
    /// The first pose refused (in input order), and why (pose_problem's words, or the
    /// placement's InputError); first_invalid is the number of poses when none was.
    std::size_t first_invalid = 0;
    std::string first_problem;
};

class Probe {
public:
    /// Poses against the hazards of `grid` for the limiting depth `limiting_depth_m` (none:
    /// land only); keeps a reference to `grid`, which must outlive the probe.
    Probe(const grid::CoastGrid& grid, const hull::Hull& hull, std::optional<double> limiting_depth_m);
    /// At the grid's own default limiting depth (GridSource::limiting_depth_m).
    Probe(const grid::CoastGrid& grid, const hull::Hull& hull);
    Probe(grid::CoastGrid&& grid, const hull::Hull& hull, std::optional<double>) = delete;
    Probe(grid::CoastGrid&& grid, const hull::Hull& hull) = delete;

    /// The pose placed in the grid's frame (one projection; the Jacobian from the field).
    /// Throws InputError when PROJ cannot place it; the pose must be valid (pose_problem).
    check::LocalPose place(const check::Pose& pose) const;

    /// One pose. Throws InputError naming the problem for a pose not valid or not placeable.
    Answer check(const check::Pose& pose, const Ask& ask = {}) const;

    /// Poses 0 .. n-1 (`pose_of(k)`, called from every thread) checked in blocks of
    /// check::placement_block on `jobs` threads (0: every core): each valid pose placed with
    /// its block (one projection), an invalid or unplaceable one answered not valid. `use(from,
    /// answers, worker)` is called once per block on the thread that checked it, in any order;
    /// `worker` numbers the thread (0 .. threads - 1). Returns the batch's counts (its answers
    /// empty: they were handed to `use`). Throws what `use` throws (the first block in input
    /// order that failed).
    Batch check_blocks(std::size_t n, const std::function<check::Pose(std::size_t)>& pose_of, const Ask& ask, unsigned jobs,
                       const std::function<void(std::size_t from, std::span<const Answer> answers, unsigned worker)>& use) const;
    /// The same, the answers kept in the batch.
    Batch check(std::span<const check::Pose> poses, const Ask& ask = {}, unsigned jobs = 0) const;

    const check::Detector& detector() const noexcept { return m_detector; }
    /// The grid as given (its frame and extent; the detector's grid is its hazards at the depth).
    const grid::CoastGrid& grid() const noexcept { return m_grid; }
    const geo::JacobianField& field() const noexcept { return m_field; }

private:
    Answer answer(const check::LocalPose& pose, const Ask& ask) const;

    const grid::CoastGrid& m_grid;
    check::Detector m_detector;
    geo::JacobianField m_field;
};

}  // namespace shoal::probe
