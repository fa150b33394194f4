#pragma once
// What the binding's files share: the grid as Python holds it, path arguments, warnings, and
// library messages in Python terms. One file per Python concept: grid.cpp (shoal.Grid),
// detector.cpp (shoal.Detector), audit.cpp (shoal._audit behind shoal.audit), module.cpp.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // in every file of the module: the casters must agree

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <shoal/grid/limiting_depth.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::python {

namespace py = pybind11;

/// A grid as Python holds it: shared by the detectors made from it (each keeps it alive), with
/// the coast paths it came from (a grid file, or the sources built), as `--coast` names them.
struct GridHandle {
    std::shared_ptr<const grid::CoastGrid> grid;
    std::vector<std::string> coast;
};

/// One path (str or os.PathLike) or an iterable of them, as strings.
std::vector<std::string> paths_of(const py::handle& paths);

/// A library message in Python terms: the option fields it names (`SweepOptions::step_m`,
/// `BuildRequest::crs`, ...) become the keyword arguments that set them (`step_m`, `crs`).
std::string in_python_terms(std::string message);

/// Each message as a Python `UserWarning` (call with the GIL held).
void warn_all(const std::vector<std::string>& messages);

/// The hull of `ship` (a ship file path) or `dims` (a, b, c, d in metres), exactly one of them;
/// `label` gets the report's name for its origin ("ship file", "--dims a,b,c,d", as the CLI).
hull::Hull hull_of(const py::object& ship, const py::object& dims, std::string* label);

/// The limiting depth a Detector or an audit's default uses (grid::plan_vessel_depth, as the
/// CLI): `hazard_depth_m`, else the ship's draught + `ukc`, else the grid's default; warns
/// when `ukc` cannot be used. Throws ValueError for a value that is not a depth.
grid::DepthPlan plan_depth(const GridHandle& g, const hull::Hull& hull, const py::object& hazard_depth_m, const py::object& ukc);
/// A depth keyword's value: none for None; ValueError "NAME must be a finite number (metres)"
/// for one that is not (or, `non_negative`, is under 0).
std::optional<double> depth_or_none(const py::object& o, const char* name, bool non_negative);
/// `v` if it is a finite number > 0 (>= 0 when `zero_ok`) and at most `max` (the library's
/// bound, `why` said with it, as the CLI's); ValueError naming `name` otherwise.
double positive(const char* name, double v, bool zero_ok = false, double max = INFINITY, const char* why = "");

void bind_grid(py::module_& m);
void bind_detector(py::module_& m);
void bind_audit(py::module_& m);

}  // namespace shoal::python
