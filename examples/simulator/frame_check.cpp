// A simulator's per-frame check through shoal's C++ library, built against the installed
// package with CMake (find_package(Shoal CONFIG), target Shoal::shoal): load a grid once, then
// check the own ship's pose every frame (a 30 fps frame has 33 ms for everything).
//   frame_check_cpp GRID [FRAMES]   sails a circle of 2 km radius around the grid's centre
#include <shoal/check/detector.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/version.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

int main(int argc, char** argv) try {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s GRID [FRAMES]\n", argv[0]);
        return 2;
    }
    const shoal::grid::CoastGrid grid = shoal::grid::GridFile::load(argv[1]);
    const shoal::check::Detector detector(grid, shoal::hull::Hull::from_dimensions({150, 35, 14, 15}, "ferry"));
    const int frames = argc > 2 ? std::stoi(argv[2]) : 3000;
    const shoal::geo::Box e = grid.extent();
    const shoal::geo::XY centre{(e.minx + e.maxx) / 2, (e.miny + e.maxy) / 2};
    int contacts = 0;
    double seconds = 0;
    for (int k = 0; k < frames; ++k) {
        const double a = 2 * std::numbers::pi * k / frames;
        const shoal::geo::XY p{centre.x + 2000 * std::cos(a), centre.y + 2000 * std::sin(a)};
        const shoal::check::Pose pose{grid.frame().inverse(p), std::fmod(360 - a * 180 / std::numbers::pi, 360.0)};
        const auto t0 = std::chrono::steady_clock::now();
        const shoal::check::Contact c = detector.check(pose, {500.0, false});
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        contacts += c.collision ? 1 : 0;
    }
    std::printf("shoal %s: %d frames, %d in contact, %.2f us per check\n", SHOAL_VERSION_STRING, frames, contacts, 1e6 * seconds / frames);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "frame_check_cpp: %s\n", e.what());
    return 2;
}
