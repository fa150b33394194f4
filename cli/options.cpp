#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>

#include <shoal/util/error.hpp>
#include <shoal/util/option_names.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::cli {

namespace {
/// A validator for a number: accepted when `ok` holds for it, else "must be SAID (WHY; got 'TEXT')"
/// ("(got 'TEXT')" with no `why`).
CLI::Validator compared(const char* name, std::function<bool(double)> ok, std::string said, std::string why = "") {
    if (!why.empty()) why += "; ";
    return CLI::Validator(
        [ok = std::move(ok), said = std::move(said), why = std::move(why)](std::string& text) -> std::string {
            double v = 0;
            if (CLI::detail::lexical_cast(text, v) && ok(v)) return {};
            return "must be " + said + " (" + why + "got '" + text + "')";
        },
        name);
}
}  // namespace

const CLI::Validator finite = compared("FINITE", [](double v) { return std::isfinite(v); }, "a finite number");
const CLI::Validator positive = compared("POSITIVE", [](double v) { return v > 0; }, "> 0");
const CLI::Validator non_negative = compared("NONNEGATIVE", [](double v) { return v >= 0; }, ">= 0");

CLI::Validator at_most(double max, const std::string& what) {
    char bound[32];
    std::snprintf(bound, sizeof bound, "%g", max);
    return compared("MAX", [max](double v) { return v <= max; }, std::string("at most ") + bound, what);
}

void check_readable(const std::vector<std::string>& paths) {
    for (const std::string& p : paths) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(p, ec)) continue;
        if (std::FILE* f = std::fopen(p.c_str(), "rb")) std::fclose(f);
        else throw InputError("'" + p + "': cannot read (" + std::strerror(errno) + ")");
    }
}

std::string in_cli_terms(std::string message) { return in_terms_of(std::move(message), FrontEnd::cli); }

namespace {
bool g_quiet = false;
}

void set_quiet(bool q) { g_quiet = q; }
bool quiet() { return g_quiet; }
void note(const std::string& text) {
    if (!g_quiet) std::fprintf(stderr, "shoal: %s\n", text.c_str());
}

void print_warnings(const std::vector<std::string>& warnings) {
    if (g_quiet) return;
    for (const auto& w : warnings) std::fprintf(stderr, "shoal: warning: %s\n", printable(in_cli_terms(w)).c_str());
}

void print_errors(const std::vector<std::string>& errors) {
    for (const auto& e : errors) std::fprintf(stderr, "shoal: error: %s\n", printable(in_cli_terms(e)).c_str());
}

void print_grid(const grid::CoastGrid& g) {
    const auto& s = g.source();
    const geo::Box e = g.extent();
    std::printf("sources:        ");
    for (std::size_t i = 0; i < s.inputs.size(); ++i) std::printf("%s%s", i ? ", " : "", s.inputs[i].c_str());
    std::printf("\nlayers:         ");
    for (std::size_t i = 0; i < s.layers.size(); ++i) std::printf("%s%s", i ? ", " : "", s.layers[i].c_str());
    std::printf("\nfingerprint:    %s\n", grid::fingerprint_hex(s.fingerprint).c_str());
    std::printf("frame:          %s\n", g.frame().description().c_str());
    std::printf("cell size:      %.1f m\n", g.cell_size());
    std::printf("grid:           %d x %d cells, %.1f x %.1f km, origin (%.1f, %.1f) m\n", g.nx(), g.ny(),
                (e.maxx - e.minx) / 1000, (e.maxy - e.miny) / 1000, e.minx, e.miny);
    std::printf("cells:          %zu coast, %zu land, %zu water\n", g.coast_cell_count(), g.land_cell_count(),
                g.cell_count() - g.coast_cell_count() - g.land_cell_count());
    std::printf("coastline:      %llu vertices read, %llu polylines (%llu with land side known), %zu clipped segments\n",
                static_cast<unsigned long long>(s.input_vertices), static_cast<unsigned long long>(s.polylines),
                static_cast<unsigned long long>(s.land_polylines), g.segment_count());
    std::printf("memory:         %.2f MB (%.1f bytes per vertex)\n", g.memory_bytes() / 1e6,
                s.input_vertices ? static_cast<double>(g.memory_bytes()) / static_cast<double>(s.input_vertices) : 0.0);
    const auto depths = g.charted_depths();
    if (depths.empty()) {
        std::printf("hazards:        land only (no depth areas or dangers)\n");
    } else {
        const bool unknown = std::isnan(depths.front());
        const std::size_t known = depths.size() - (unknown ? 1 : 0);
        std::printf("hazards:        %llu depth areas and dangers kept with their depth (%llu with unknown depth), "
                    "%zu distinct charted depths (%.1f to %.1f m);\n                %llu shallow-water and %llu danger polylines; "
                    "point dangers as %.1f m circles%s%s\n",
                    static_cast<unsigned long long>(s.hazard_features), static_cast<unsigned long long>(s.unknown_depth), known,
                    known ? depths[unknown ? 1 : 0] : NAN, known ? depths.back() : NAN,
                    static_cast<unsigned long long>(s.shallow_polylines), static_cast<unsigned long long>(s.danger_polylines),
                    s.danger_radius_m, s.depth_field.empty() ? "" : "; depth field ", s.depth_field.c_str());
        char dflt[64] = "none (land only)";
        if (!std::isnan(s.limiting_depth_m)) std::snprintf(dflt, sizeof dflt, "%.2f m (--hazard-depth)", s.limiting_depth_m);
        std::printf("limiting depth: chosen per vessel at check time (draught + --ukc, or --hazard-depth); default %s\n", dflt);
    }
    if (s.structure_features > 0)
        std::printf("structures:     %llu piers, wharves, pontoons, dolphins, hulks ... (%llu polylines), hazards for every vessel; "
                    "lines as %.1f m wide bands, points as %.1f m circles\n",
                    static_cast<unsigned long long>(s.structure_features), static_cast<unsigned long long>(s.structure_polylines),
                    2 * coast::structure_line_half_width_m, coast::structure_point_radius_m);
    if (!g.has_land_side())
        std::printf("note:           only lines, no land polygons: a ship inside land, away from the coastline, is not seen\n");
}

/// --hazard-depth, --depth-field, --danger-radius: which depth areas and dangers are hazards.
void add_hazard_options(CLI::App& sub, coast::ImportOptions& import) {
    sub.add_option("--hazard-depth", import.limiting_depth_m,
                   "Limiting depth in metres: depth areas shallower and dangers with a sounding under it (or unknown) are "
                   "hazards like land. check and probe: for every vessel (default: each vessel's own draught + --ukc, else the "
                   "ship file's, else the grid's default, else land only); import: the grid's default")
        ->check(finite);
    sub.add_option("--depth-field", import.depth_field,
                   "Attribute holding a polygon's least depth in sources other than S-57 (DEPARE/DRGARE use DRVAL1)");
    sub.add_option("--danger-radius", import.danger_radius_m, "Radius in metres of the circle a point danger becomes (default 10)")
        ->check(finite)->check(positive)->check(at_most(coast::ImportOptions::max_danger_radius_m, "a point danger is a rock or a wreck"));
}


void CoastAndShip::add(CLI::App& sub) {
    sub.add_option("--coast", coast, "A grid file, or coastline sources (built into a cached grid)")->required();
    auto* ship = sub.add_option("--ship", ship_file, "Ship file (schemas/ship.schema.json)");
    sub.add_option("--dims", dims, "AIS dimensions A,B,C,D in metres instead of --ship")->excludes(ship);
    auto* cell = sub.add_option("--cell", request.cell_m, "Cell edge in metres when building from a coastline")
                     ->check(finite)->check(positive)->check(at_most(grid::CoastGrid::max_cell_m, "the largest cell"));
    sub.add_option("--ship-length", request.ship_length_m, "Cell = 2.5 x this when building from a coastline")
        ->check(finite)->check(positive)->check(at_most(hull::Hull::max_length_m, "longer than any ship"))->excludes(cell);
    sub.add_option("--crs", request.crs, "Projected CRS of the local frame when building from a coastline");
    sub.add_option("--layer", request.import.layers, "Layer(s) to read from coastline sources")->delimiter(',');
    sub.add_option("--source-crs", request.import.source_crs, "CRS of coastline sources that carry none");
    sub.add_option("--cache-dir", request.cache_dir, "Folder for built grids (default $SHOAL_CACHE_DIR or ~/.cache/shoal)");
    sub.add_option("--ukc", ukc, "Under-keel clearance required, metres: limiting depth = the ship's draught + this (default 0)")
        ->check(finite)->check(non_negative);
    add_hazard_options(sub, request.import);
    sub.add_flag("-v,--verbose", verbose,
                 "Say how the grid was obtained and how long it took; check: also list every track in the summary's table (by "
                 "default the counts of each kind of event come first, then only the tracks with events)");
}

std::vector<std::string> CoastAndShip::inputs(std::vector<std::string> more) const {
    more.insert(more.end(), coast.begin(), coast.end());
    if (!ship_file.empty()) more.push_back(ship_file);
    return more;
}

hull::Hull CoastAndShip::hull_with(const std::function<hull::Hull(const std::string&)>& ship_file_hull) const {
    if (!ship_file.empty()) return ship_file_hull(ship_file);
    if (!dims.empty()) return hull::Hull::from_dims_string(dims);
    throw UsageError("give the ship with --ship SHIP.json or --dims A,B,C,D");
}

std::string CoastAndShip::hull_label() const { return ship_file.empty() ? "--dims " + dims : "ship file"; }

void CoastAndShip::warn_depth(const grid::DepthPlan& plan, const grid::CoastGrid& g) const {
    print_warnings(grid::depth_warnings(plan, g, coast.size() == 1 ? coast[0] : ""));
}

grid::CoastGrid CoastAndShip::load_grid_with(const hull::Hull& hull, GridLoader load) const {
    // One grid serves every limiting depth: it is built (or cached) the same whatever the
    // draught; the limit is chosen per vessel at check time.
    const grid::DepthPlan plan = grid::plan_limiting_depth(request.import.limiting_depth_m, hull.draught(), ukc);
    if (plan.depth_m) {
        char why[160] = "--hazard-depth, for every vessel";
        if (plan.source == grid::DepthPlan::Source::draught)
            std::snprintf(why, sizeof why, "ship file draught %.2f m + under-keel clearance %.2f m", plan.draught_m, plan.ukc_m);
        if (!quiet()) std::fprintf(stderr, "shoal: limiting depth %.2f m (%s): shallower depth areas and dangers are hazards\n", *plan.depth_m, why);
    }
    check_readable(coast);
    grid::LoadReport report;
    grid::CoastGrid g = load(coast, request, &report);
    print_warnings(report.warnings);
    if (verbose)
        std::fprintf(stderr, "shoal: %s%s%s in %.3f s\n", printable(report.how).c_str(), report.cache_path.empty() ? "" : " ",
                     printable(report.cache_path).c_str(), report.seconds);
    return g;
}

}  // namespace shoal::cli
