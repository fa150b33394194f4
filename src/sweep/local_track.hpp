#pragma once
/// The one answer to "where is this ship at time t": a track in the run's local frame. Per fix
/// its position (local metres) and the frame's Jacobian there; between two fixes the position
/// moves linearly in local metres, the heading by the shorter turn and the Jacobian linearly.
/// A moment on the track is a fix interval and a fraction of it (`Where`); `at(t)` finds the
/// one holding time t. The track is broken where `Breaks` says (a gap in time, and if asked a
/// jump). Used by the coastline sweep, the exercise's encounters and clock, COLREG situations
/// and conduct, and the assessment, so that all of them place a ship at a moment the same way.

#include <Eigen/Core>
#include <cmath>
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

/// An angle in degrees brought into [0, 360).
double wrap_360(double a_deg) noexcept;

/// Every fix of `t` in `frame` (one batch through PROJ). Throws InputError naming the track,
/// the file and the line of the first fix that cannot be projected.
std::vector<LocalFix> project_fixes(const track::Track& t, const geo::LocalFrame& frame);

/// Where a track is broken, so that nothing is placed between the two fixes: a fix interval
/// longer than `max_gap_s` (a gap), and with `at_jumps` one ending at a fix after a jump
/// (track::Fix::jump_before).
struct Breaks {
    double max_gap_s = INFINITY;
    bool at_jumps = false;
};

/// What a LocalTrack places: hulls (`poses`: the frame's Jacobian at each fix too, 15 more
/// projected points every 2 km of track) or reference points only (`positions`: one projected
/// point per fix; pose() refused).
enum class Placing { poses, positions };

/// A moment on a track: the fraction f of the way from fix i to fix i + 1 (f = 0: fix i itself;
/// always 0 at the last fix).
struct Where {
    std::size_t i = 0;
    double f = 0;
};

/// A track in the local frame. Holds a reference: the track must outlive it.
class LocalTrack {
public:
    /// Projects every fix of `t` (throws InputError for a fix the frame cannot hold), with the
    /// frame's Jacobians (project_fixes) when `placing` is poses.
    LocalTrack(const track::Track& t, const geo::LocalFrame& frame, Breaks breaks = {}, Placing placing = Placing::poses);

    const track::Track& track() const noexcept { return m_track; }
    std::size_t size() const noexcept { return m_position.size(); }
    double time(std::size_t i) const { return m_track.fixes[i].time_s; }
    geo::XY position(std::size_t i) const { return m_position[i]; }
    const std::vector<geo::XY>& positions() const noexcept { return m_position; }
    /// The map (east, north) metres -> local metres at fix i (Placing::poses only).
    const Eigen::Matrix2d& jacobian(std::size_t i) const { return m_jacobian[i]; }
    /// The box of the fixes' positions (lo > hi for no fix).
    geo::XY lo() const noexcept { return m_lo; }
    geo::XY hi() const noexcept { return m_hi; }

    /// Fix interval i (fix i to fix i + 1) is sailed: no break (Breaks) ends it.
    bool sailed(std::size_t i) const { return i < m_sailed.size() && m_sailed[i]; }
    /// Present at `t`: within the track's span and not inside a break.
    bool present(double t) const;

    /// The fix at or before t and the fraction of its interval; before the first fix the
    /// first fix, at or after the last the last.
    Where at(double t) const;
    /// The fix interval holding t, in [0, size() - 2] (needs two fixes): the last fix's time
    /// belongs to the last interval, which it ends (a fix time inside the track: the interval
    /// it starts).
    std::size_t interval(double t) const;
    /// The fraction of fix interval i at t, not clamped (t outside the interval: outside [0, 1]);
    /// 0 at the last fix.
    double fraction(std::size_t i, double t) const {
        if (i + 1 >= size()) return 0;
        return (t - time(i)) / (time(i + 1) - time(i));
    }

    /// Epoch seconds at w.
    double time(Where w) const {
        if (w.f == 0 || w.i + 1 >= size()) return time(w.i);
        return time(w.i) + w.f * (time(w.i + 1) - time(w.i));
    }
    /// The reference point, local metres.
    geo::XY position(Where w) const {
        if (w.f == 0 || w.i + 1 >= size()) return m_position[w.i];
        return m_position[w.i] + w.f * (m_position[w.i + 1] - m_position[w.i]);
    }
    /// True heading from the fixes' resolved headings (track::Fix::heading_used_deg) turned by
    /// the shorter way; not wrapped between fixes (wrap_360 for [0, 360)).
    double heading(Where w) const {
        const double a = m_track.fixes[w.i].heading_used_deg;
        if (w.f == 0 || w.i + 1 >= size()) return a;
        return a + w.f * turn(a, m_track.fixes[w.i + 1].heading_used_deg);
    }
    /// The pose: reference point and the map from ship coordinates to local metres (Placing::poses only).
    check::LocalPose pose(Where w) const;

    /// A per-fix quantity (speed, velocity, ...) interpolated linearly at w (a value that is
    /// not finite at either end of the interval makes it so).
    template <class V>
    V interpolate(const std::vector<V>& per_fix, Where w) const {
        if (w.i + 1 >= size()) return per_fix[w.i];
        return per_fix[w.i] + w.f * (per_fix[w.i + 1] - per_fix[w.i]);
    }
    /// Per-fix headings (degrees) turned by the shorter way at w; not wrapped.
    double interpolate_heading(const std::vector<double>& per_fix_deg, Where w) const {
        const double a = per_fix_deg[w.i];
        if (w.f == 0 || w.i + 1 >= size()) return a;
        return a + w.f * turn(a, per_fix_deg[w.i + 1]);
    }

private:
    const track::Track& m_track;
    std::vector<geo::XY> m_position;         ///< per fix
    std::vector<Eigen::Matrix2d> m_jacobian;  ///< per fix; none with Placing::positions
    std::vector<bool> m_sailed;  ///< per fix interval
    geo::XY m_lo{INFINITY, INFINITY}, m_hi{-INFINITY, -INFINITY};
};

}  // namespace shoal::audit
