// Placement: where a pose (WGS84 position, true heading) puts the hull in a grid's frame, one
// pose or a batch with one projection, and many poses in blocks on threads.
#include <shoal/check/placement.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/parallel.hpp"

namespace shoal::check {

using geo::XY;

namespace {
/// Columns: the ship's forward and starboard unit vectors in (east, north) metres. (The
/// audit's audit::ship_to_en rounds the heading's radians otherwise; each keeps its own.)
Eigen::Matrix2d ship_to_en(double heading_deg) {
    // Any finite heading, normalised to [0, 360) as `shoal probe` reads it (io/pose_csv.cpp):
    // the same pose whoever asks (C API, Python, probe). Unnormalised, a heading of 5.72e307 or
    // more overflowed to infinity in the product below and every sine was NaN: "no contact".
    if (!(heading_deg >= 0.0 && heading_deg < 360.0)) {
        heading_deg = std::fmod(heading_deg, 360.0);
        if (heading_deg < 0) heading_deg += 360.0;
    }
    const double h = heading_deg * std::numbers::pi / 180.0;
    Eigen::Matrix2d m;
    m << std::sin(h), std::cos(h), std::cos(h), -std::sin(h);
    return m;
}
}  // namespace

LocalPose place(const geo::LocalFrame& frame, const Pose& pose) {
    return {frame.forward(pose.position), frame.jacobian(pose.position) * ship_to_en(pose.heading_deg)};
}

namespace {
LocalPose place_at(const geo::LocalFrame& frame, const geo::JacobianField& field, XY p, const Pose& pose) {
    const Eigen::Matrix2d j = field.covers(p) ? field.at(p) : frame.jacobian(pose.position);
    return {p, j * ship_to_en(pose.heading_deg)};
}
}  // namespace

LocalPose place(const geo::LocalFrame& frame, const geo::JacobianField& field, const Pose& pose) {
    return place_at(frame, field, frame.forward(pose.position), pose);
}

std::vector<LocalPose> place(const geo::LocalFrame& frame, const geo::JacobianField& field, std::span<const Pose> poses) {
    std::vector<double> xs(poses.size()), ys(poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) {
        xs[k] = poses[k].position.lon;
        ys[k] = poses[k].position.lat;
    }
    std::size_t bad = 0;
    std::vector<LocalPose> out(poses.size());
    if (!frame.forward(xs, ys, &bad)) {
        // Pose by pose, as one by one: the first that fails throws its own message.
        for (std::size_t k = 0; k < poses.size(); ++k) out[k] = place(frame, field, poses[k]);
        return out;
    }
    for (std::size_t k = 0; k < poses.size(); ++k) out[k] = place_at(frame, field, {xs[k], ys[k]}, poses[k]);
    return out;
}

void place_in_blocks(const geo::LocalFrame& frame, const geo::JacobianField& field, std::size_t n,
                     const std::function<Pose(std::size_t)>& pose_of, unsigned jobs,
                     const std::function<void(std::size_t from, std::span<const LocalPose> placed, unsigned worker)>& use) {
    constexpr std::size_t block = placement_block;
    const std::size_t blocks = (n + block - 1) / block;
    // A block that fails stops the blocks after it (the first failure in input order is thrown).
    detail::parallel_blocks(blocks, detail::thread_count(jobs), [&](std::size_t b, unsigned worker) {
        const std::size_t from = b * block, to = std::min(n, from + block);
        std::vector<Pose> todo;
        todo.reserve(to - from);
        for (std::size_t k = from; k < to; ++k) todo.push_back(pose_of(k));
        const std::vector<LocalPose> placed = place(frame, field, todo);
        use(from, placed, worker);
    });
}

std::vector<XY> hull_outline(const hull::Hull& hull, const LocalPose& pose) {
    std::vector<XY> out;
    out.reserve(hull.contour().size());
    const Eigen::Matrix2d& m = pose.ship_to_local;
    for (const XY& c : hull.contour())
        out.push_back({pose.position.x + m(0, 0) * c.x + m(0, 1) * c.y, pose.position.y + m(1, 0) * c.x + m(1, 1) * c.y});
    return out;
}

}  // namespace shoal::check
