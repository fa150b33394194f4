#pragma once
// shoal probe, shared by the full command module (probe_command.cpp) and the executable's own
// probe of a grid file (grid_probe.cpp): the same options and the same run, only the way the
// ship file, the poses and the grid are read differs (through GDAL's virtual files and the
// grid cache in the module; plain files and a grid file in the executable).

#include <functional>
#include <string>

#include "options.hpp"
#include <shoal/hull/hull.hpp>
#include <shoal/io/pose_csv.hpp>

namespace shoal::cli {

struct ProbeArgs {
    CoastAndShip opts;
    std::string poses;
    std::string output;
    unsigned jobs = 0;

    /// Adds the `probe` subcommand and its options to `app`; returns it.
    CLI::App* add(CLI::App& app);
};

/// How the inputs are read.
struct ProbeInputs {
    std::function<hull::Hull()> hull;                          ///< the ship (--ship or --dims)
    std::function<io::PoseFile()> poses;                       ///< the poses file, parsed
    std::function<grid::CoastGrid(const hull::Hull&)> grid;    ///< the grid (--coast)
};

/// Runs the probe; returns the exit status.
int run_probe(const ProbeArgs& args, const ProbeInputs& inputs);

}  // namespace shoal::cli
