#pragma once
/// The audit tests' chart: the Solent's land (tests/data/coast/uk_solent_land.geojson) in a
/// 500 m grid, built once per test program and kept to its end.

#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_builder.hpp>

#include "test_support.hpp"

namespace shoal::test {

inline const grid::CoastGrid& solent_grid() {
    static const grid::CoastGrid* const g = [] {
        grid::BuildRequest req;
        req.cell_m = 500;
        return new grid::CoastGrid(grid::build_grid({data_path("coast/uk_solent_land.geojson")}, req, nullptr));
    }();
    return *g;
}

}  // namespace shoal::test
