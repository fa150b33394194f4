#pragma once
/// Shapes that stress the grid, the pose check and the sweep, in local metres. Shared by
/// tests/check/pathological_test.cpp and tests/sweep/sweep_test.cpp (answers against GEOS
/// and brute force) and bench/bench_pathological.cpp (times and memory).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::test {

/// A closed ring of `n` vertices (n + 1 points, the last equal to the first), counter-clockwise
/// and star-shaped around (0, 0), so simple for any n: radius `r` x (1 + 3 % sin 37t + 0.05 % sin
/// 1013t) plus a uniform jitter of up to +-`jitter` metres. A million vertices on r = 20 km
/// puts them 0.13 m apart.
inline std::vector<geo::XY> star_ring(std::size_t n, double r, double jitter, std::uint64_t seed = 1) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> noise(-jitter, jitter);
    std::vector<geo::XY> ring(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
        const double rad = r * (1 + 0.03 * std::sin(37 * t) + 0.0005 * std::sin(1013 * t)) + noise(rng);
        ring[i] = {rad * std::cos(t), rad * std::sin(t)};
    }
    ring[n] = ring[0];
    return ring;
}

/// Land whose top is a comb: `segments` (even) near-vertical segments zigzag across x in
/// [0, width] between tooth tips at y ~ +height/2 and notches at y ~ -height/2 (each varied
/// at random by up to a tenth of the height), above a base at y = -height/2 - 500. With width
/// 500 and 5,000 segments every cell of a 500 m grid over the comb is crossed by thousands of
/// segments 0.1 m apart. Closed, counter-clockwise (land on the left).
inline std::vector<geo::XY> comb_ring(std::size_t segments, double width, double height, std::uint64_t seed = 2) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<geo::XY> cw;  // built clockwise: up the left side, along the teeth, down the right
    const double base = -height / 2 - 500;
    cw.push_back({0, base});
    for (std::size_t k = 0; k <= segments; ++k) {
        const double x = width * static_cast<double>(k) / static_cast<double>(segments);
        const double y = k % 2 == 0 ? height / 2 - unit(rng) * height / 10 : -height / 2 + unit(rng) * height / 10;
        cw.push_back({x, y});
    }
    cw.push_back({width, base});
    std::vector<geo::XY> ring(cw.rbegin(), cw.rend());
    ring.push_back(ring.front());
    return ring;
}

/// A hull outline of `n` points (x forward, y starboard) around the reference point: a
/// 190 x 32 m ellipse, 20 m of it aft of the reference point, with a wavy edge.
inline std::vector<geo::XY> wavy_hull(std::size_t n) {
    std::vector<geo::XY> pts(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
        const double wave = 1 + 0.02 * std::sin(97 * t);
        pts[i] = {95 * wave * std::cos(t) + 75, 16 * wave * std::sin(t)};
    }
    return pts;
}

}  // namespace shoal::test
