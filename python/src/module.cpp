// The extension module shoal._shoal: exceptions, and what the concept files share.
#include "bindings.hpp"


#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <shoal/grid/limiting_depth.hpp>
#include <shoal/track/columns.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/option_names.hpp>
#include <shoal/version.hpp>


namespace shoal::python {

std::vector<std::string> paths_of(const py::handle& paths) {
    const py::module_ os = py::module_::import("os");
    std::vector<std::string> out;
    if (py::isinstance<py::str>(paths) || py::hasattr(paths, "__fspath__")) {
        out.push_back(py::str(os.attr("fspath")(paths)));
        return out;
    }
    if (py::isinstance<py::bytes>(paths)) throw py::type_error("paths must be str or os.PathLike (or a list of them), not bytes");
    for (const py::handle p : paths) out.push_back(py::str(os.attr("fspath")(p)));
    return out;
}

std::string in_python_terms(std::string message) { return in_terms_of(std::move(message), FrontEnd::python); }

void warn_all(const std::vector<std::string>& messages) {
    for (const auto& w : messages)
        if (PyErr_WarnEx(PyExc_UserWarning, in_python_terms(w).c_str(), 1) != 0) throw py::error_already_set();
}

namespace {

std::string shortest(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return {buf, r.ptr};
}

}  // namespace

hull::Hull hull_of(const py::object& ship, const py::object& dims, std::string* label) {
    if (!ship.is_none() && !dims.is_none()) throw py::value_error("give the ship as ship=PATH or dims=(a, b, c, d), not both");
    if (!ship.is_none()) {
        const std::vector<std::string> p = paths_of(ship);
        if (p.size() != 1) throw py::value_error("ship: one ship file (schemas/ship.schema.json)");
        hull::Hull h = hull::Hull::load(p[0]);
        if (label) *label = "ship file";
        return h;
    }
    if (dims.is_none()) throw py::value_error("give the ship as ship=PATH (a ship file) or dims=(a, b, c, d) (AIS dimensions, metres)");
    const auto values = dims.cast<std::vector<double>>();
    if (values.size() != 4)
        throw py::value_error("dims: four numbers a, b, c, d (metres from the position reference point to bow, stern, port, starboard); got " +
                              std::to_string(values.size()));
    static const char* letters[] = {"a", "b", "c", "d"};
    std::string text;
    for (std::size_t i = 0; i < 4; ++i) {
        if (!std::isfinite(values[i]) || values[i] <= 0)
            throw InputError("dims: " + std::string(letters[i]) + " must be a finite number > 0 (got " + shortest(values[i]) + ")");
        text += (i ? "," : "") + shortest(values[i]);
    }
    hull::Hull h = hull::Hull::from_dims_string(text);
    // The report's name for the hull's origin, as the CLI writes it: DataFrames and reports compare.
    if (label) *label = "--dims " + text;
    return h;
}

std::optional<double> depth_or_none(const py::object& o, const char* name, bool non_negative) {
    if (o.is_none()) return std::nullopt;
    const double v = o.cast<double>();
    if (!std::isfinite(v) || (non_negative && v < 0))
        throw py::value_error(std::string(name) + (non_negative ? " must be a finite number >= 0 (metres)" : " must be a finite number (metres)"));
    return v;
}

/// A number for a message, as Python would write it ("50", "0.5", "nan").
std::string number_text(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return {buf, r.ptr};
}

double positive(const char* name, double v, bool zero_ok, double max, const char* why) {
    if (!std::isfinite(v) || v < 0 || (!zero_ok && v == 0))
        throw py::value_error(std::string(name) + " must be a finite number " + (zero_ok ? ">= 0" : "> 0") + " (got " + number_text(v) + ")");
    if (!(v <= max))
        throw py::value_error(std::string(name) + " must be at most " + number_text(max) + " (" + (*why ? std::string(why) + "; " : std::string()) +
                              "got " + number_text(v) + ")");
    return v;
}

grid::DepthPlan plan_depth(const GridHandle& g, const hull::Hull& hull, const py::object& hazard_depth_m, const py::object& ukc) {
    const std::optional<double> hazard = depth_or_none(hazard_depth_m, "hazard_depth_m", false);
    const std::optional<double> u = depth_or_none(ukc, "ukc", true);
    // As `shoal probe`: hazard_depth_m, else the ship's draught + ukc, else the grid's default.
    const grid::DepthPlan plan = grid::plan_vessel_depth(hazard, NAN, hull.draught(), u, *g.grid);
    const std::vector<std::string> w = grid::depth_warnings(plan, *g.grid);
    warn_all(w);
    return plan;
}

}  // namespace shoal::python

PYBIND11_MODULE(_shoal, m) {
    namespace sp = shoal::python;
    namespace py = pybind11;
    m.doc() = "shoal: ship tracks audited against chart coastlines (the C++ library, bound with pybind11)";
    m.attr("__version__") = SHOAL_VERSION_STRING;
    // Bad input is a ValueError (a file, row or value that cannot be used); so are contradictory options.
    static py::exception<shoal::InputError> input_error(m, "InputError", PyExc_ValueError);
    static py::exception<shoal::UsageError> usage_error(m, "UsageError", PyExc_ValueError);
    input_error.attr("__module__") = "shoal";
    usage_error.attr("__module__") = "shoal";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const shoal::InputError& e) {
            PyErr_SetString(input_error.ptr(), sp::in_python_terms(e.what()).c_str());
        } catch (const shoal::UsageError& e) {
            PyErr_SetString(usage_error.ptr(), sp::in_python_terms(e.what()).c_str());
        }
    });
    // The column names of the track readers (one table: shoal/track/columns.hpp), for
    // shoal.DEFAULT_COLUMNS and the columns of a DataFrame found as the CSV reader finds them.
    m.def("_column_table", [] {
        py::list out;
        for (const shoal::track::ColumnNames& c : shoal::track::column_table()) {
            py::list names;
            for (const std::string_view n : c.names) names.append(py::str(n.data(), n.size()));
            out.append(py::make_tuple(py::str(c.field.data(), c.field.size()), names));
        }
        return out;
    });
    m.def("_normalise_column_name", [](const std::string& name) { return shoal::track::normalise_column_name(name); });
    m.def("_is_time_column_name", [](const std::string& name) { return shoal::track::is_time_column_name(name); });
    sp::bind_grid(m);
    sp::bind_detector(m);
    sp::bind_audit(m);
}
