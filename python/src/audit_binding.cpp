// shoal._audit, behind shoal.audit: fixes given as columns (numpy arrays and lists, from a
// DataFrame in shoal/__init__.py) become track::Track objects in memory, read by the rules of
// the CSV reader (same validity of positions, headings, COG, SOG, same static data per
// vessel); audit::audit_tracks sweeps them (the CLI's code path) and every layer of the report
// comes back as columns built from report_fields (the report's names, types and rounding).
#include "bindings.hpp"

#include <pybind11/numpy.h>

#include <cmath>
#include <exception>
#include <map>

#include <shoal/audit/audit.hpp>
#include <shoal/coast/expected_areas.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/track/row_rules.hpp>
#include <shoal/track/time.hpp>
#include <shoal/track/track_table.hpp>
#include <shoal/track/vessels_table.hpp>
#include <shoal/util/error.hpp>

#include <shoal/report/report_fields.hpp>

namespace shoal::python {

namespace {

namespace fields = report::fields;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A column of numbers (NaN: no value), or none when the column is absent.
struct Numbers {
    Array array;
    const double* data = nullptr;
    double at(std::size_t k) const noexcept { return data ? data[k] : NAN; }
    explicit operator bool() const noexcept { return data != nullptr; }
};

Numbers numbers(const py::dict& cols, const char* key, std::size_t n) {
    Numbers c;
    if (!cols.contains(key) || cols[key].is_none()) return c;
    c.array = Array::ensure(cols[key]);
    if (!c.array) throw py::type_error(std::string("column '") + key + "' is not numeric");
    if (static_cast<std::size_t>(c.array.size()) != n)
        throw py::value_error(std::string("column '") + key + "' has " + std::to_string(c.array.size()) + " values, not " + std::to_string(n));
    c.data = c.array.data();
    return c;
}

std::vector<std::string> texts(const py::dict& cols, const char* key, std::size_t n) {
    if (!cols.contains(key) || cols[key].is_none()) return {};
    std::vector<std::string> v = cols[key].cast<std::vector<std::string>>();
    if (v.size() != n) throw py::value_error(std::string("column '") + key + "' has " + std::to_string(v.size()) + " values, not " + std::to_string(n));
    return v;
}

/// The fixes as tracks, one per id in the order ids first appear, by the CSV reader's rules.
std::vector<track::Track> make_tracks(const py::dict& cols, const std::string& file, track::ReadReport& report) {
    if (!cols.contains("lat") || !cols.contains("lon") || !(cols.contains("time") || cols.contains("time_text")))
        throw py::value_error("the fixes need time, lat and lon columns");
    const std::size_t n = static_cast<std::size_t>(Array::ensure(cols["lat"]).size());
    const Numbers lat = numbers(cols, "lat", n), lon = numbers(cols, "lon", n), time = numbers(cols, "time", n);
    // Times as text are read as the CSV reader reads them (ISO 8601, epoch, dd/mm/yyyy hh:mm:ss).
    const std::vector<std::string> time_text = texts(cols, "time_text", n);
    const Numbers heading = numbers(cols, "heading", n), cog = numbers(cols, "cog", n), sog = numbers(cols, "sog", n);
    const Numbers dims[4] = {numbers(cols, "a", n), numbers(cols, "b", n), numbers(cols, "c", n), numbers(cols, "d", n)};
    const Numbers draught = numbers(cols, "draught", n), line = numbers(cols, "line", n), ship_type = numbers(cols, "ship_type", n);
    const std::vector<std::string> ids = texts(cols, "id", n), names = texts(cols, "name", n), status = texts(cols, "nav_status", n);
    const std::vector<std::string> mobile = texts(cols, "mobile_type", n);
    const bool has_id = !ids.empty(), has_dims = dims[0] && dims[1] && dims[2] && dims[3];
    py::gil_scoped_release nogil;
    // Tracks by the CSV reader's table (one per vessel id, in the order ids first appear; static
    // data by the row rules), packed as the reader packs them, then unpacked.
    std::vector<track::PackedTrack> packed;
    track::TrackTable table(packed, file, has_id, false);
    for (std::size_t k = 0; k < n; ++k) {
        ++report.rows;
        const std::size_t row_line = line ? static_cast<std::size_t>(line.at(k)) : k + 1;
        const auto skip = [&](const std::string& what) { report.skip(file + " line " + std::to_string(row_line) + ": " + what + "; row skipped"); };
        if (!mobile.empty() && !track::is_vessel_row(mobile[k])) {
            skip(track::not_a_vessel_message(mobile[k]));
            continue;
        }
        if (has_id && ids[k].empty()) {
            skip("no vessel id");
            continue;
        }
        double t = time.at(k);
        if (!time_text.empty()) {
            if (time_text[k].empty()) {
                skip("no time");
                continue;
            }
            const auto parsed = track::parse_time(time_text[k]);
            if (!parsed) {
                skip(track::invalid_time_message(time_text[k]));
                continue;
            }
            if (parsed->date_missing) {
                skip(track::undated_time_message(time_text[k]));
                continue;
            }
            if (!track::plausible_fix_time(parsed->seconds)) {
                skip(track::implausible_time_message(time_text[k]));
                continue;
            }
            t = parsed->seconds;
        }
        if (std::isnan(t)) {
            skip("no time");
            continue;
        }
        if (!track::plausible_fix_time(t)) {
            skip(track::implausible_time_message(t));
            continue;
        }
        track::Fix fix;
        fix.time_s = t;
        fix.position = {lon.at(k), lat.at(k)};
        if (std::string what; track::position_problem(fix.position.lat, fix.position.lon, what)) {
            skip(what);
            continue;
        }
        fix.heading_deg = track::valid_heading(heading.at(k));
        fix.cog_deg = track::valid_cog(cog.at(k));
        fix.sog_kn = track::valid_sog(sog.at(k));
        if (!status.empty()) fix.nav_status = track::parse_nav_status(status[k]);
        fix.line = row_line;
        track::PackedTrack& tr = packed[table.track_for(has_id ? std::string_view(ids[k]) : std::string_view())];
        if (!names.empty()) track::offer_name(tr, names[k]);
        if (has_dims) track::offer_dims(tr, track::dims_from_abcd(dims[0].at(k), dims[1].at(k), dims[2].at(k), dims[3].at(k)), track::dims_from_abcd_source);
        if (draught) track::offer_draught(tr, draught.at(k));
        if (ship_type) track::offer_ship_type(tr, ship_type.at(k));
        tr.push_back(fix);
    }
    std::vector<track::Track> tracks;
    tracks.reserve(packed.size());
    for (track::PackedTrack& p : packed) {
        tracks.push_back(p.unpack());
        p.release_fixes();
    }
    for (track::Track& tr : tracks) track::normalise(tr, report);
    return tracks;
}

py::object to_python(const fields::Value& v) {
    return std::visit(
        [](const auto& x) -> py::object {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::monostate>) return py::none();
            else return py::cast(x);
        },
        v);
}

const char* type_name(fields::Type t) {
    switch (t) {
    case fields::Type::text: return "text";
    case fields::Type::integer: return "integer";
    case fields::Type::real: return "real";
    case fields::Type::boolean: return "boolean";
    case fields::Type::datetime: return "datetime";
    }
    return "text";
}

/// One layer: its fields (name, type, unit) in the report's order and a list of values per field.
template <class Row>
py::dict layer(const std::vector<fields::Field<Row>>& table, const std::vector<Row>& rows, const audit::AuditResult& r) {
    py::list names, types, units;
    py::dict columns;
    for (const auto& f : table) {
        if (f.present && !f.present(r)) continue;
        names.append(f.name), types.append(type_name(f.type)), units.append(f.unit);
        py::list values;
        for (const Row& row : rows) values.append(to_python(fields::value_of(f, row)));
        columns[f.name] = values;
    }
    py::dict out;
    out["names"] = names, out["types"] = types, out["units"] = units, out["columns"] = columns;
    return out;
}

py::tuple point(geo::LonLat p) {
    return py::make_tuple(fields::round_to(p.lon, fields::coordinate_decimals), fields::round_to(p.lat, fields::coordinate_decimals));
}

py::dict run_audit(const GridHandle& g, const py::dict& cols, const std::string& file, const py::object& ship, const py::object& dims,
                   double margin_m, double step_m, double max_gap_s, double max_speed_kn, double berthing_speed_kn, double stop_diameter_m,
                   double stop_time_s, unsigned jobs, bool encounters, double ship_margin_m, std::size_t max_encounters_per_ship,
                   const py::object& berths,
                   double berth_tolerance_m, const py::object& vessels, const py::object& ukc, const py::object& hazard_depth_m,
                   const py::object& progress, const py::object& world) {
    std::string label;
    const hull::Hull hull = hull_of(ship, dims, &label);
    plan_depth(g, hull, hazard_depth_m, ukc);  // validates and warns as the CLI does
    audit::AuditOptions options;
    options.hazard_depth_m = depth_or_none(hazard_depth_m, "hazard_depth_m", false);
    options.ukc_m = depth_or_none(ukc, "ukc", true);
    options.sweep.margin_m = positive("margin_m", margin_m, true);
    options.sweep.step_m = positive("step_m", step_m);
    audit::check_step(step_m);
    options.sweep.max_gap_s = positive("max_gap_s", max_gap_s);
    options.wild.max_speed_kn = positive("max_speed_kn", max_speed_kn);
    options.sweep.berthing_speed_kn =
        positive("berthing_speed_kn", berthing_speed_kn, true, audit::SweepOptions::max_berthing_speed_kn, "faster is no berthing");
    options.sweep.stop_diameter_m = positive("stop_diameter_m", stop_diameter_m);
    options.sweep.stop_duration_s = positive("stop_time_s", stop_time_s);
    options.jobs = jobs;
    options.encounters = encounters;
    // As the CLI: real traffic's world unless an exercise (encounters).
    options.world = encounters ? audit::World::simulated : audit::World::real;
    if (!world.is_none()) {
        const auto w = audit::parse_world(py::cast<std::string>(world));
        if (!w) throw py::value_error("world must be 'simulated' or 'real', not '" + py::cast<std::string>(py::str(world)) + "'");
        options.world = *w;
    }
    options.encounter.ship_margin_m = positive("ship_margin_m", ship_margin_m, true);
    options.max_encounters_per_ship = max_encounters_per_ship;
    positive("berth_tolerance_m", berth_tolerance_m, false, coast::ExpectedAreas::max_tolerance_m, "a berth grown by more is no berth");
    const std::vector<std::string> berth_files = berths.is_none() ? std::vector<std::string>{} : paths_of(berths);
    const std::vector<std::string> vessel_files = vessels.is_none() ? std::vector<std::string>{} : paths_of(vessels);

    track::ReadReport read;
    std::vector<track::Track> tracks = make_tracks(cols, file, read);
    std::vector<std::string> warnings;
    std::exception_ptr progress_error;
    std::map<std::string, track::VesselInfo> vessel_info;
    audit::AuditResult r;
    report::RunInfo info;
    {
        py::gil_scoped_release nogil;
        // Expected-contact areas: `berths`, and the S-57 charts the grid came from (as the CLI).
        const coast::ExpectedAreas areas = coast::ExpectedAreas::load(berth_files, grid::coast_sources(g.coast, *g.grid), g.grid->frame(),
                                                                      berth_tolerance_m, &warnings);
        options.areas = &areas;
        // As the CLI: the first table that names a vessel gives its data (track::merge_vessels).
        vessel_info = track::read_vessels_files(vessel_files, &warnings);
        if (!vessel_files.empty()) options.vessels = &vessel_info;
        if (!progress.is_none())
            options.progress = [&](std::size_t done, std::size_t total) {
                if (progress_error) return;
                py::gil_scoped_acquire gil;
                try {
                    progress(done, total);
                } catch (...) {
                    progress_error = std::current_exception();  // raised once the audit is over (its workers never see it)
                }
            };
        const std::size_t n_tracks = tracks.size();
        r = audit::audit_tracks(std::move(tracks), *g.grid, hull, label, options);
        options.progress = nullptr;
        // The fixes were one "file": its read report gives the problems and skipped rows, as the CLI's files do.
        audit::FileResult fr;
        fr.file = file;
        fr.format = "DataFrame";
        fr.read = read;
        fr.tracks = n_tracks;
        r.files.push_back(std::move(fr));
        r.skipped_rows += read.skipped;
        info = report::run_info(g.coast, *g.grid, ship.is_none() ? label : hull.name(), options, berth_files, hull.draught());
        options.areas = nullptr;
    }
    if (progress_error) std::rethrow_exception(progress_error);
    if (read.skipped) warnings.push_back(file + ": " + std::to_string(read.skipped) + " bad rows skipped (listed in problems)");
    if (read.reordered) warnings.push_back(file + ": " + std::to_string(read.reordered) + " fixes out of time order (sorted by time)");
    if (read.duplicates)
        warnings.push_back(file + ": " + std::to_string(read.duplicates) + " fixes repeat an earlier time of their vessel (dropped)");
    for (const auto& e : r.errors) warnings.push_back("track '" + e.track + "' in '" + e.file + "': " + e.message + " (track skipped)");
    warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
    warn_all(warnings);

    py::dict out;
    std::vector<fields::EventRow> events;
    py::list event_points;
    for (const auto& t : r.tracks)
        for (const auto& e : t.events) {
            events.push_back({t.summary, e});
            event_points.append(point(e.point));
        }
    out["events"] = layer(fields::event_fields(), events, r);
    out["event_points"] = event_points;
    const std::vector<fields::TrackRow> track_rows = fields::track_rows(r);
    out["tracks"] = layer(fields::track_fields(), track_rows, r);
    py::list lines;
    for (const auto& t : r.tracks) {
        py::list pieces;
        for (const auto& piece : t.summary.lines) {
            py::list pts;
            for (const auto& p : piece) pts.append(point(p));
            pieces.append(pts);
        }
        lines.append(pieces);
    }
    out["track_lines"] = lines;
    out["problems"] = layer(fields::problem_fields(), fields::problem_rows(r), r);
    if (r.has_encounters) {
        std::vector<fields::EncounterRow> enc;
        py::list enc_points;
        for (const auto& e : r.encounters.events) {
            enc.push_back({r, e});
            enc_points.append(point(e.point));
        }
        out["encounters"] = layer(fields::encounter_fields(), enc, r);
        out["encounter_points"] = enc_points;
        std::vector<fields::ApproachRow> approaches;
        for (const auto& a : r.encounters.approaches) approaches.push_back({r, a});
        out["closest_approaches"] = layer(fields::approach_fields(), approaches, r);
    }
    const std::vector<fields::RunRow> run{{r, info}};
    out["run"] = layer(fields::run_fields(), run, r);
    out["summary"] = layer(fields::summary_fields(), run, r);
    return out;
}

}  // namespace

void bind_audit(py::module_& m) {
    const audit::SweepOptions sweep;
    const track::WildFixOptions wild;
    const audit::EncounterOptions encounter;
    m.def("_audit", &run_audit, py::arg("grid"), py::arg("columns"), py::arg("file"), py::kw_only(), py::arg("ship") = py::none(),
          py::arg("dims") = py::none(), py::arg("margin_m") = sweep.margin_m, py::arg("step_m") = sweep.step_m,
          py::arg("max_gap_s") = sweep.max_gap_s, py::arg("max_speed_kn") = wild.max_speed_kn,
          py::arg("berthing_speed_kn") = sweep.berthing_speed_kn, py::arg("stop_diameter_m") = sweep.stop_diameter_m,
          py::arg("stop_time_s") = sweep.stop_duration_s, py::arg("jobs") = 0u, py::arg("encounters") = false,
          py::arg("ship_margin_m") = encounter.ship_margin_m,
          py::arg("max_encounters_per_ship") = audit::AuditOptions{}.max_encounters_per_ship, py::arg("berths") = py::none(), py::arg("berth_tolerance_m") = 10.0,
          py::arg("vessels") = py::none(), py::arg("ukc") = py::none(), py::arg("hazard_depth_m") = py::none(),
          py::arg("progress") = py::none(), py::arg("world") = py::none(),
          "The audit behind shoal.audit: `columns` maps id, time (epoch seconds), lat, lon, heading, cog, sog, a, b, c, d, "
          "draught, ship_type, name, nav_status, line to arrays or lists; returns every layer of the report as columns.");
}

}  // namespace shoal::python
