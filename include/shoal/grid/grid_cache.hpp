#pragma once
/// The grid cache: where built grids are kept (a folder private to the user), under which key
/// (the sources' fingerprint), and when one is reused; `load_or_build` behind `--coast`.
/// Includes the format and the builder, whose names callers of the cache use too.

#include <string>
#include <vector>

#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/grid/grid_file.hpp>

namespace shoal::grid {

/// What `load_or_build` did, for messages.
struct LoadReport {
    std::string how;  ///< "loaded grid", "reused cache", "built and cached", "built (cache not writable: ...)"
    std::string cache_path;
    std::vector<std::string> warnings;
    BuildStats build;
    double seconds = 0;
};

/// `--coast COAST_OR_GRID`: a grid file is loaded; coastline sources are built into a grid
/// that is cached and reused while the sources and parameters are unchanged.
CoastGrid load_or_build(const std::vector<std::string>& paths, const BuildRequest& request, LoadReport* report = nullptr);

}  // namespace shoal::grid
