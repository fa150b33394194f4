// The parts of CoastAndShip that read through GDAL (options.hpp): in the full command module only.
#include "options.hpp"

#include <shoal/grid/grid_cache.hpp>
#include <shoal/util/error.hpp>

namespace shoal::cli {

hull::Hull CoastAndShip::load_hull() const {
    if (!ship_file.empty()) return hull::Hull::load(ship_file);
    if (!dims.empty()) return hull::Hull::from_dims_string(dims);
    throw UsageError("give the ship with --ship SHIP.json or --dims A,B,C,D");
}

grid::CoastGrid CoastAndShip::load_grid(const hull::Hull& hull) const { return load_grid_with(hull, grid::load_or_build); }

}  // namespace shoal::cli
