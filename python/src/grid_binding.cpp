// shoal.Grid: a coastline grid loaded from a .shoalgrid file or built from coastline sources
// (the library's grid_builder and grid_cache, as `shoal import` and `--coast` use them).
#include "bindings.hpp"


#include <algorithm>
#include <cmath>
#include <cstdio>

#include <shoal/grid/grid_cache.hpp>
#include <shoal/grid/grid_file.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::python {

namespace {

template <class T>
std::optional<T> opt(const py::object& o) {
    return o.is_none() ? std::nullopt : std::optional<T>(o.cast<T>());
}

GridHandle load(const py::object& path) {
    GridHandle h;
    h.coast = paths_of(path);
    if (h.coast.size() != 1) throw py::value_error("Grid.load: one .shoalgrid file (Grid.build builds from coastline sources)");
    py::gil_scoped_release nogil;
    h.grid = std::make_shared<const grid::CoastGrid>(grid::GridFile::load(h.coast[0]));
    return h;
}

GridHandle build(const py::object& coast_paths, const py::object& crs, const py::object& cell_m, const py::object& ship_length_m,
                 const py::object& hazard_depth_m, const py::object& layers, const py::object& source_crs, const py::object& depth_field,
                 const py::object& danger_radius_m, bool cache, const py::object& cache_dir) {
    GridHandle h;
    h.coast = paths_of(coast_paths);
    if (h.coast.empty()) throw py::value_error("Grid.build: no coastline sources given");
    grid::BuildRequest req;
    if (auto v = opt<std::string>(crs)) req.crs = *v;
    const auto cell = opt<double>(cell_m), length = opt<double>(ship_length_m), danger = opt<double>(danger_radius_m);
    for (const auto& [name, v] : {std::pair{"cell_m", cell}, {"ship_length_m", length}, {"danger_radius_m", danger}})
        if (v) positive(name, *v);
    if (cell && length) throw py::value_error("give cell_m or ship_length_m, not both");
    req.cell_m = cell.value_or(0);
    req.ship_length_m = length.value_or(0);
    req.import.limiting_depth_m = depth_or_none(hazard_depth_m, "hazard_depth_m", false);
    if (!layers.is_none()) req.import.layers = py::isinstance<py::str>(layers) ? std::vector<std::string>{layers.cast<std::string>()}
                                                                              : layers.cast<std::vector<std::string>>();
    if (auto v = opt<std::string>(source_crs)) req.import.source_crs = *v;
    if (auto v = opt<std::string>(depth_field)) req.import.depth_field = *v;
    if (danger) req.import.danger_radius_m = *danger;
    std::vector<std::string> warnings;
    {
        py::gil_scoped_release nogil;
        if (cache || !cache_dir.is_none()) {
            if (!cache_dir.is_none()) {
                py::gil_scoped_acquire gil;
                req.cache_dir = paths_of(cache_dir).at(0);
            }
            grid::LoadReport report;
            h.grid = std::make_shared<const grid::CoastGrid>(grid::load_or_build(h.coast, req, &report));
            warnings = std::move(report.warnings);
        } else {
            h.grid = std::make_shared<const grid::CoastGrid>(grid::build_grid(h.coast, req, &warnings));
        }
    }
    warn_all(warnings);
    return h;
}

void save(const GridHandle& h, const py::object& path) {
    const std::vector<std::string> p = paths_of(path);
    if (p.size() != 1) throw py::value_error("Grid.save: one path");
    check_outputs({{p[0], "path", "the grid", grid::looks_like_grid}}, h.coast);
    py::gil_scoped_release nogil;
    grid::GridFile::save(*h.grid, p[0]);
}

/// The grid's extent in WGS84: (min lon, min lat, max lon, max lat) of its edges, sampled.
py::tuple bounds(const GridHandle& h) {
    const geo::Box e = h.grid->extent();
    double lo_lon = INFINITY, lo_lat = INFINITY, hi_lon = -INFINITY, hi_lat = -INFINITY;
    const int n = 16;
    for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        const geo::XY edge[] = {{e.minx + t * (e.maxx - e.minx), e.miny}, {e.minx + t * (e.maxx - e.minx), e.maxy},
                                {e.minx, e.miny + t * (e.maxy - e.miny)}, {e.maxx, e.miny + t * (e.maxy - e.miny)}};
        for (const geo::XY& p : edge) {
            const geo::LonLat q = h.grid->frame().inverse(p);
            lo_lon = std::min(lo_lon, q.lon), hi_lon = std::max(hi_lon, q.lon);
            lo_lat = std::min(lo_lat, q.lat), hi_lat = std::max(hi_lat, q.lat);
        }
    }
    return py::make_tuple(lo_lon, lo_lat, hi_lon, hi_lat);
}

}  // namespace

void bind_grid(py::module_& m) {
    py::class_<GridHandle>(m, "Grid",
                           "A coastline grid: cells of water, land and coast in a local frame. Make one with Grid.load "
                           "(a .shoalgrid file written by `shoal import` or Grid.save) or Grid.build (coastline sources).")
        .def_static("load", &load, py::arg("path"), "Reads a .shoalgrid file (checked: magic, version, checksum).")
        .def_static("build", &build, py::arg("coast_paths"), py::kw_only(), py::arg("crs") = py::none(), py::arg("cell_m") = py::none(),
                    py::arg("ship_length_m") = py::none(), py::arg("hazard_depth_m") = py::none(), py::arg("layers") = py::none(),
                    py::arg("source_crs") = py::none(), py::arg("depth_field") = py::none(), py::arg("danger_radius_m") = py::none(),
                    py::arg("cache") = false, py::arg("cache_dir") = py::none(),
                    "Builds a grid from coastline sources (any OGR vector source, S-57 charts), as `shoal import` does: "
                    "crs (default a transverse Mercator centred on the data), cell_m (default 500, or 2.5 x ship_length_m), "
                    "hazard_depth_m (depth areas shallower and dangers are hazards; default land only), layers, source_crs, "
                    "depth_field, danger_radius_m. cache=True (or a cache_dir) keeps and reuses the grid as --coast does.")
        .def("save", &save, py::arg("path"), "Writes the grid as a .shoalgrid file (atomically).")
        .def_property_readonly("fingerprint", [](const GridHandle& h) { return grid::fingerprint_hex(h.grid->source().fingerprint); }, "XXH3 of the sources' bytes and the build options, in hex (the report's grid_fingerprint)")
        .def_property_readonly("frame", [](const GridHandle& h) { return h.grid->frame().description(); }, "the local frame")
        .def_property_readonly("cell_m", [](const GridHandle& h) { return h.grid->cell_size(); }, "cell edge, metres")
        .def_property_readonly("shape", [](const GridHandle& h) { return py::make_tuple(h.grid->nx(), h.grid->ny()); }, "(columns, rows)")
        .def_property_readonly("limiting_depth_m", [](const GridHandle& h) -> py::object {
            const double d = h.grid->source().limiting_depth_m;
            return std::isnan(d) ? py::none() : py::cast(d);
        }, "the depth its hazards were chosen for, metres; None: land only")
        .def_property_readonly("bounds", &bounds, "(min lon, min lat, max lon, max lat) of the grid's extent, WGS84 degrees")
        .def_property_readonly("extent_m", [](const GridHandle& h) {
            const geo::Box e = h.grid->extent();
            return py::make_tuple(e.minx, e.miny, e.maxx, e.maxy);
        }, "(min x, min y, max x, max y) of the grid's extent in the local frame, metres")
        .def_property_readonly("sources", [](const GridHandle& h) { return h.grid->source().inputs; }, "the coastline sources it was built from")
        .def_property_readonly("layers", [](const GridHandle& h) { return h.grid->source().layers; }, "file:layer of every layer read")
        .def_property_readonly("memory_bytes", [](const GridHandle& h) { return h.grid->memory_bytes(); })
        .def("__repr__", [](const GridHandle& h) {
            char buf[256];
            std::snprintf(buf, sizeof buf, "<shoal.Grid %d x %d cells of %.1f m, fingerprint %s>", h.grid->nx(), h.grid->ny(),
                          h.grid->cell_size(), grid::fingerprint_hex(h.grid->source().fingerprint).c_str());
            return std::string(buf);
        });
}

}  // namespace shoal::python
