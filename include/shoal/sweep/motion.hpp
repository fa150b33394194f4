#pragma once
/// A track in the local frame and how a ship moves between its fixes: position interpolated
/// linearly in local metres, heading by the shorter turn, the frame's local scale and
/// convergence (the Jacobian) interpolated too. Shared by the coastline sweep and the
/// ship-to-ship encounters so both place a hull at a moment the same way.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/track/track.hpp>

namespace shoal::audit {

/// A fix in the local frame: position and the map (east, north) metres -> local metres.
struct LocalFix {
    geo::XY position;
    Eigen::Matrix2d jacobian;
};

/// The map from ship coordinates (x forward, y starboard) to (east, north) metres for a true heading.
Eigen::Matrix2d ship_to_en(double heading_deg);

/// Signed shorter turn from a to b in degrees, in (-180, 180].
double turn(double a_deg, double b_deg);

/// Every fix of `t` in `frame` (one batch through PROJ). Throws InputError naming the track,
/// the file and the line of the first fix that cannot be projected.
std::vector<LocalFix> project_fixes(const track::Track& t, const geo::LocalFrame& frame);

/// Everything needed to place the ship at any moment between two fixes. Holds references:
/// `t` and `local` must outlive it.
class Motion {
public:
    Motion(const track::Track& t, const std::vector<LocalFix>& local) : m_track(t), m_local(local) {}

    /// Pose at fraction f in [0, 1] of the way from fix i to fix i+1 (f = 0: fix i itself).
    check::LocalPose pose(std::size_t i, double f) const;
    /// The reference point of pose(i, f), the same number, without the rotation.
    geo::XY position(std::size_t i, double f) const {
        if (f == 0 || i + 1 >= m_track.fixes.size()) return m_local[i].position;
        return m_local[i].position + f * (m_local[i + 1].position - m_local[i].position);
    }
    /// Epoch seconds at fraction f of the way from fix i to fix i+1.
    double time(std::size_t i, double f) const;
    /// True heading in [0, 360) at fraction f of the way from fix i to fix i+1.
    double heading(std::size_t i, double f) const;

    const track::Track& track() const noexcept { return m_track; }
    const std::vector<LocalFix>& local() const noexcept { return m_local; }

private:
    const track::Track& m_track;
    const std::vector<LocalFix>& m_local;
};

}  // namespace shoal::audit
