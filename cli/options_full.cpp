// The parts of CoastAndShip that read through GDAL (options.hpp): in the full command module only.
#include "options.hpp"

#include <shoal/grid/grid_cache.hpp>
#include <shoal/util/error.hpp>

namespace shoal::cli {

hull::Hull CoastAndShip::load_hull() const {
    return hull_with([](const std::string& path) { return hull::Hull::load(path); });
}

grid::CoastGrid CoastAndShip::load_grid(const hull::Hull& hull) const { return load_grid_with(hull, grid::load_or_build); }

}  // namespace shoal::cli
