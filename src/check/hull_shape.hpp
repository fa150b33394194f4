#pragma once
/// Hull outlines prepared for fast contact checks (internal to src/check and src/audit): the
/// outline cut into chunks of edges with a bounding capsule each, placed at a pose, and the
/// pruned contact search that only tests the edge pairs those capsules cannot rule out.
/// Public face: check::hull_contact (include/shoal/check/hull_contact.hpp).

#include <cmath>
#include <cstdint>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/check/hull_contact.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::check::detail {

using geo::XY;

/// Slack (metres) subtracted from every lower bound so that rounding in the placed points
/// cannot make a bound exceed a distance computed from them.
constexpr double bound_slack_m = 1e-4;

/// A segment grown by a radius: every point within `r` of the segment mid +- hv.
struct Capsule {
    XY mid;  ///< midpoint of the axis
    XY hv;   ///< half the axis: the axis runs from mid - hv to mid + hv
    double r = 0;
};

/// Lower bound of the distance between anything in two capsules, by the separating axis
/// through their midpoints: |D| - |hv_a . u| - |hv_b . u| - r_a - r_b with u = D / |D|.
/// True when that bound exceeds `d` (strictly; `or_equal`: or equals it). No square root:
/// q = |D|^2 - |hv_a . D| - |hv_b . D| is compared with (d + r_a + r_b) |D|, both squared.
inline bool apart(const Capsule& a, const Capsule& b, double d, bool or_equal = false) noexcept {
    const XY D = b.mid - a.mid;
    const double L2 = geo::norm2(D);
    const double q = L2 - std::fabs(geo::dot(a.hv, D)) - std::fabs(geo::dot(b.hv, D));
    if (!(q > 0)) return false;
    const double R = d + a.r + b.r;
    return or_equal ? q * q >= R * R * L2 : q * q > R * R * L2;
}

/// A run of consecutive edges [first, end) of an outline and the capsule holding it, in the
/// ship frame: the chord from its first to its last point, grown by the farthest point's
/// distance (small on a straight side, so facing sides of two ships are told apart early).
struct Chunk {
    std::uint32_t first = 0, end = 0;
    Capsule capsule;
};

/// A hull outline prepared for contact checks.
struct HullShape {
    std::vector<XY> contour;  ///< ship frame, open ring
    double radius = 0;        ///< max distance of a contour point from the reference point
    std::vector<Chunk> chunks;
};

HullShape prepare(const std::vector<XY>& contour);

/// A hull placed at a pose, in local metres.
struct Placed {
    XY position;
    double m00 = 1, m01 = 0, m10 = 0, m11 = 1;  ///< ship -> local map
    double sigma = 1;                           ///< its largest stretch (spectral norm)
    std::vector<XY> pts;                        ///< the outline, first point repeated at the end
    std::vector<Capsule> edges;                 ///< per edge: the edge itself, grown by the slack
    std::vector<Capsule> chunks;                ///< per chunk: its capsule mapped, radius times sigma plus the slack

    XY map(XY c) const noexcept { return {position.x + m00 * c.x + m01 * c.y, position.y + m10 * c.x + m11 * c.y}; }
    XY map_vector(XY v) const noexcept { return {m00 * v.x + m01 * v.y, m10 * v.x + m11 * v.y}; }
};

/// Largest singular value of a 2x2 matrix.
inline double spectral_norm(double a, double b, double c, double d) {
    const double s = a * a + b * b + c * c + d * d;
    const double det = a * d - b * c;
    return std::sqrt((s + std::sqrt(std::max(0.0, s * s - 4 * det * det))) / 2);
}

/// The pose and the chunk capsules: enough for chunks_apart.
void place_chunks(const HullShape& shape, const LocalPose& pose, Placed& out);
/// The outline and its edges, after place_chunks.
void place_outline(const HullShape& shape, Placed& out);
/// Both.
void place(const HullShape& shape, const LocalPose& pose, Placed& out);

/// Every edge pair of two closed rings: the reference.
HullContact contact_all(const std::vector<XY>& a, const std::vector<XY>& b);

/// An edge pair (edge of a, edge of b); UINT32_MAX: none.
struct EdgePair {
    std::uint32_t i = UINT32_MAX, j = UINT32_MAX;
};

/// Do the chunk capsules prove the clearance > margin_m and >= best_m? (Needs place_chunks only.)
bool chunks_apart(const Placed& a, const Placed& b, double margin_m, double best_m);

/// The same answer as contact_all, testing only the edge pairs that capsule bounds (of chunks
/// of edges, of an edge against a chunk, of two edges) cannot prove farther apart than the
/// nearest pair found so far. `hint` (the nearest pair last time, updated) gives a good bound
/// at once. Returns false without an answer ("far": clearance > `margin_m` and >= `best_m`)
/// when the chunk bounds prove that; margin_m = INFINITY never gives up. Every bound has
/// `bound_slack_m` to spare and ties are never pruned, so the nearest pair (and of equals the
/// first) is always tested.
bool contact_pruned(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b, double margin_m, double best_m,
                    HullContact& out, EdgePair* hint = nullptr);

/// contact_all(...).collision, sooner: stops at the first edge pair in contact and reads only
/// the pairs whose capsules touch.
bool touching_pruned(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b, EdgePair* hint);

}  // namespace shoal::check::detail
