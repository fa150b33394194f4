#include "commands.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <filesystem>
#include <string>
#include <chrono>
#include <unistd.h>

#include <shoal/check/detector.hpp>
#include <shoal/coast/expected_areas.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/audit/audit.hpp>
#include <shoal/io/pose_csv.hpp>
#include <shoal/report/plot.hpp>
#include <shoal/report/report.hpp>
#include <shoal/track/reader.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::cli {

bool Command::parsed() const { return m_sub && m_sub->parsed(); }

namespace {

/// The smallest --step: a centimetre (a hull point moves at most this between checks).
constexpr double min_step_m = 0.01;

/// Numbers that must be finite: CLI11's PositiveNumber and NonNegativeNumber let NaN through
/// (every comparison with it is false), and a NaN option would silently switch a rule off.
const CLI::Validator finite = CLI::Validator(
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v)) return "must be a finite number (got '" + text + "')";
        return {};
    },
    "FINITE");

/// Before any work: the output can be written where it is asked for (its folder exists, it is
/// not a folder), and it is none of the inputs (the same file by any path: writing the output
/// would destroy the input it is made from).
void check_output(const std::string& output, const std::vector<std::string>& inputs) {
    namespace fs = std::filesystem;
    if (output.empty() || output == "-") return;
    std::error_code ec;
    const fs::path dir = fs::path(output).has_parent_path() ? fs::path(output).parent_path() : ".";
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + output + "': folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(output, ec)) throw InputError("cannot write '" + output + "': it is a directory");
    if (!fs::exists(output, ec)) return;
    for (const std::string& in : inputs)
        if (!in.empty() && fs::equivalent(output, in, ec) && !ec)
            throw UsageError("the output '" + output + "' is the input '" + in +
                             "': writing it would destroy the input; choose another -o");
}

/// Coastline sources and grids that exist but cannot be opened: said as such, not as "not a
/// vector dataset" (which is what OGR makes of a file it may not read).
void check_readable(const std::vector<std::string>& paths) {
    for (const std::string& p : paths) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(p, ec)) continue;
        if (std::FILE* f = std::fopen(p.c_str(), "rb")) std::fclose(f);
        else throw InputError("'" + p + "': cannot read (" + std::strerror(errno) + ")");
    }
}

void print_warnings(const std::vector<std::string>& warnings) {
    for (const auto& w : warnings) std::fprintf(stderr, "shoal: warning: %s\n", printable(w).c_str());
}

void print_grid(const grid::CoastGrid& g) {
    const auto& s = g.source();
    const geo::Box e = g.extent();
    std::printf("sources:        ");
    for (std::size_t i = 0; i < s.inputs.size(); ++i) std::printf("%s%s", i ? ", " : "", s.inputs[i].c_str());
    std::printf("\nlayers:         ");
    for (std::size_t i = 0; i < s.layers.size(); ++i) std::printf("%s%s", i ? ", " : "", s.layers[i].c_str());
    std::printf("\nfingerprint:    %016llx\n", static_cast<unsigned long long>(s.fingerprint));
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
    if (std::isnan(s.limiting_depth_m)) {
        std::printf("hazards:        land only (no limiting depth)\n");
    } else {
        std::printf("hazards:        limiting depth %.2f m: %llu depth areas and dangers kept (%llu with unknown depth), "
                    "%llu at or deeper skipped;\n                %llu shallow-water and %llu danger polylines; point dangers as %.1f m circles%s%s\n",
                    s.limiting_depth_m, static_cast<unsigned long long>(s.hazard_features),
                    static_cast<unsigned long long>(s.unknown_depth), static_cast<unsigned long long>(s.deep_skipped),
                    static_cast<unsigned long long>(s.shallow_polylines), static_cast<unsigned long long>(s.danger_polylines),
                    s.danger_radius_m, s.depth_field.empty() ? "" : "; depth field ", s.depth_field.c_str());
    }
    if (!g.has_land_side())
        std::printf("note:           only lines, no land polygons: a ship inside land, away from the coastline, is not seen\n");
}

/// --hazard-depth, --depth-field, --danger-radius: which depth areas and dangers are hazards.
void add_hazard_options(CLI::App& sub, coast::ImportOptions& import) {
    sub.add_option("--hazard-depth", import.limiting_depth_m,
                   "Limiting depth in metres: depth areas shallower and dangers with a sounding under it (or unknown) are "
                   "hazards like land (default: none, land only; for probe and check the ship's draught + --ukc when it has one)")
        ->check(finite);
    sub.add_option("--depth-field", import.depth_field,
                   "Attribute holding a polygon's least depth in sources other than S-57 (DEPARE/DRGARE use DRVAL1)");
    sub.add_option("--danger-radius", import.danger_radius_m, "Radius in metres of the circle a point danger becomes (default 10)")
        ->check(finite)->check(CLI::PositiveNumber);
}

class ImportCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("import", "Build a coastline grid and save it as a .shoalgrid cache file");
        m_sub->footer("Usage: shoal import COAST... -o GRID [--cell M | --ship-length M] [--crs CRS] [--layer NAME] [--hazard-depth M]\n"
                      "With --hazard-depth, depth areas shallower and dangers with a sounding under it (or none) are hazards like land.");
        m_sub->add_option("coast", m_inputs, "Coastline sources: any OGR vector file (Shapefile, GeoJSON, GeoPackage, S-57 .000, ...)")
            ->required();
        m_sub->add_option("-o,--output", m_output, "Grid file to write (.shoalgrid)")->required();
        auto* cell = m_sub->add_option("--cell", m_request.cell_m, "Cell edge in metres (default 500, or 2.5 x --ship-length)")
                         ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--ship-length", m_request.ship_length_m, "Largest ship length in metres: cell = 2.5 x this")
            ->check(finite)->check(CLI::PositiveNumber)->excludes(cell);
        m_sub->add_option("--crs", m_request.crs, "Projected CRS for the local frame (default: transverse Mercator centred on the data)");
        m_sub->add_option("--layer", m_request.import.layers,
                          "Layer(s) to read (default: all; S-57: LNDARE and COALNE, with --hazard-depth also DEPARE, DRGARE, UWTROC, WRECKS, OBSTRN)")
            ->delimiter(',');
        m_sub->add_option("--source-crs", m_request.import.source_crs, "CRS of sources that carry none (default: WGS84 if all coordinates are lon/lat)");
        add_hazard_options(*m_sub, m_request.import);
    }
    int run() override {
        check_output(m_output, m_inputs);
        check_readable(m_inputs);
        std::vector<std::string> warnings;
        grid::BuildStats stats;
        std::string cell_note;
        grid::CoastGrid g = grid::build_grid(m_inputs, m_request, &warnings, &stats, &cell_note);
        print_warnings(warnings);
        grid::GridFile::save(g, m_output);
        std::printf("%s\n", cell_note.c_str());
        print_grid(g);
        std::printf("build time:     %.3f s (project %.3f s, clip %.3f s with %llu GEOSClipByRect calls, cell states %.3f s)\n",
                    stats.total_s, stats.project_s, stats.clip_s, static_cast<unsigned long long>(stats.clip_calls), stats.state_s);
        std::printf("wrote:          %s (%llu bytes)\n", m_output.c_str(),
                    static_cast<unsigned long long>(std::filesystem::file_size(m_output)));
        return exit_ok;
    }

private:
    std::vector<std::string> m_inputs;
    std::string m_output;
    grid::BuildRequest m_request;
};

class InfoCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("info", "Print what a grid file holds");
        m_sub->footer("Usage: shoal info GRID");
        m_sub->add_option("grid", m_path, "Grid file written by shoal import")->required();
    }
    int run() override {
        const grid::CoastGrid g = grid::GridFile::load(m_path);
        std::printf("grid file:      %s (format version %u)\n", m_path.c_str(), grid::grid_format_version);
        print_grid(g);
        return exit_ok;
    }

private:
    std::string m_path;
};

/// Options shared by the commands that take `--coast COAST_OR_GRID` and a ship.
struct CoastAndShip {
    std::vector<std::string> coast;
    std::string ship_file;
    std::string dims;
    grid::BuildRequest request;
    std::optional<double> ukc;  ///< --ukc: under-keel clearance required, metres
    bool verbose = false;

    void add(CLI::App& sub) {
        sub.add_option("--coast", coast, "A grid file, or coastline sources (built into a cached grid)")->required();
        auto* ship = sub.add_option("--ship", ship_file, "Ship file (schemas/ship.schema.json)");
        sub.add_option("--dims", dims, "AIS dimensions A,B,C,D in metres instead of --ship")->excludes(ship);
        auto* cell = sub.add_option("--cell", request.cell_m, "Cell edge in metres when building from a coastline")
                         ->check(finite)->check(CLI::PositiveNumber);
        sub.add_option("--ship-length", request.ship_length_m, "Cell = 2.5 x this when building from a coastline")
            ->check(finite)->check(CLI::PositiveNumber)->excludes(cell);
        sub.add_option("--crs", request.crs, "Projected CRS of the local frame when building from a coastline");
        sub.add_option("--layer", request.import.layers, "Layer(s) to read from coastline sources")->delimiter(',');
        sub.add_option("--source-crs", request.import.source_crs, "CRS of coastline sources that carry none");
        sub.add_option("--cache-dir", request.cache_dir, "Folder for built grids (default $SHOAL_CACHE_DIR or ~/.cache/shoal)");
        sub.add_option("--ukc", ukc, "Under-keel clearance required, metres: limiting depth = the ship's draught + this (default 0)")
            ->check(finite)->check(CLI::NonNegativeNumber);
        add_hazard_options(sub, request.import);
        sub.add_flag("-v,--verbose", verbose, "Say how the grid was obtained and how long it took");
    }
    /// Every input file named: `more`, the coastline sources and the ship file.
    std::vector<std::string> inputs(std::vector<std::string> more) const {
        more.insert(more.end(), coast.begin(), coast.end());
        if (!ship_file.empty()) more.push_back(ship_file);
        return more;
    }
    hull::Hull load_hull() const {
        if (!ship_file.empty()) return hull::Hull::load(ship_file);
        if (!dims.empty()) return hull::Hull::from_dims_string(dims);
        throw UsageError("give the ship with --ship SHIP.json or --dims A,B,C,D");
    }
    /// The grid for `hull`: a grid file as it is, or coastline sources built for the limiting
    /// depth (--hazard-depth, else the ship's draught + --ukc, else land only).
    grid::CoastGrid load_grid(const hull::Hull& hull) const {
        grid::BuildRequest req = request;
        const bool explicit_limit = req.import.limiting_depth_m.has_value();
        char why[160] = "--hazard-depth";
        if (!explicit_limit && hull.draught() > 0) {
            req.import.limiting_depth_m = coast::limiting_depth(std::nullopt, hull.draught(), ukc.value_or(0.0));
            std::snprintf(why, sizeof why, "draught %.2f m + under-keel clearance %.2f m", hull.draught(), ukc.value_or(0.0));
        } else if (!explicit_limit && ukc) {
            print_warnings({"--ukc needs a ship with a draught (or give --hazard-depth): checking against land only"});
        }
        const bool is_grid = coast.size() == 1 && grid::looks_like_grid(coast[0]);
        if (!is_grid && req.import.limiting_depth_m)
            std::fprintf(stderr, "shoal: limiting depth %.2f m (%s): shallower depth areas and dangers are hazards\n",
                         *req.import.limiting_depth_m, why);
        check_readable(coast);
        grid::LoadReport report;
        grid::CoastGrid g = grid::load_or_build(coast, req, &report);
        print_warnings(report.warnings);
        if (is_grid && req.import.limiting_depth_m) {
            const double built = g.source().limiting_depth_m;
            const double want = *req.import.limiting_depth_m;
            char buf[400];
            if (std::isnan(built))  // with a draught too: a shallow grounding would be missed without a word
                std::snprintf(buf, sizeof buf, "the grid '%s' holds land only (built without a limiting depth): shallow water and dangers "
                              "are not checked for the limiting depth %.2f m (%s); rebuild it with shoal import --hazard-depth",
                              coast[0].c_str(), want, why);
            else if (!std::isnan(built) && built != want)
                std::snprintf(buf, sizeof buf, "the grid '%s' was built for the limiting depth %.2f m, not %.2f m (%s): %s; rebuild it with "
                              "shoal import --hazard-depth %.2f", coast[0].c_str(), built, want, why,
                              built < want ? "water between those depths is not seen as a hazard" : "more water counts as a hazard than needed",
                              want);
            else
                buf[0] = 0;
            if (buf[0]) print_warnings({buf});
        }
        if (verbose)
            std::fprintf(stderr, "shoal: %s%s%s in %.3f s\n", printable(report.how).c_str(), report.cache_path.empty() ? "" : " ",
                         printable(report.cache_path).c_str(), report.seconds);
        return g;
    }
};

class ProbeCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("probe", "Check single poses (lat,lon,heading per CSV row): collision and clearance");
        m_sub->footer("Usage: shoal probe --coast COAST_OR_GRID --ship SHIP.json POSES.csv [-o OUT.csv]\n"
                      "Writes lat,lon,heading,collision,clearance_m,covered per pose (collision 0/1; clearance 0 when touching;\n"
                      "covered 0 for a pose outside the chart, whose collision and clearance are then empty).\n"
                      "A bad row is reported on stderr with its line number and skipped.\n"
                      "Shallow water and dangers count as hazards for a limiting depth: --hazard-depth, else the ship's draught + --ukc.");
        m_opts.add(*m_sub);
        m_sub->add_option("poses", m_poses, "CSV of poses: lat,lon,heading (a header line is optional)")->required();
        m_sub->add_option("-o,--output", m_output, "Write the CSV here instead of stdout (written atomically)");
    }
    int run() override {
        check_output(m_output, m_opts.inputs({m_poses}));
        const hull::Hull hull = m_opts.load_hull();
        const io::PoseFile poses = io::read_pose_csv(m_poses);
        for (const auto& e : poses.errors) std::fprintf(stderr, "shoal: warning: %s\n", printable(e).c_str());
        if (poses.skipped > poses.errors.size())
            std::fprintf(stderr, "shoal: warning: %zu more bad rows skipped\n", poses.skipped - poses.errors.size());
        const grid::CoastGrid g = m_opts.load_grid(hull);
        const check::Detector detector(g, hull);
        std::string out = "lat,lon,heading,collision,clearance_m,covered\n";
        char line[160];
        std::size_t uncovered = 0;
        for (const auto& p : poses.poses) {
            const check::Contact c = detector.check(check::Pose{{p.lon, p.lat}, p.heading_deg});
            // Outside the chart nothing is claimed: no collision found there means nothing.
            if (c.covered || c.collision)
                std::snprintf(line, sizeof line, "%.7f,%.7f,%.1f,%d,%.3f,%d\n", p.lat, p.lon, p.heading_deg, c.collision ? 1 : 0,
                              c.collision ? 0.0 : c.clearance_m, c.covered ? 1 : 0);
            else
                std::snprintf(line, sizeof line, "%.7f,%.7f,%.1f,,,0\n", p.lat, p.lon, p.heading_deg);
            uncovered += c.covered ? 0 : 1;
            out += line;
        }
        if (uncovered)
            std::fprintf(stderr, "shoal: warning: %zu of %zu poses lie (partly) outside the chart's area: covered 0, collision and clearance unknown\n",
                         uncovered, poses.poses.size());
        write_file_atomically(m_output, out);
        return exit_ok;
    }

private:
    CoastAndShip m_opts;
    std::string m_poses;
    std::string m_output;
};

/// A progress line on stderr: fixes done, rate and time left. Only when stderr is a terminal.
class Progress {
public:
    explicit Progress(bool on) : m_on(on), m_t0(std::chrono::steady_clock::now()) {}
    void operator()(std::size_t done, std::size_t total) {
        if (!m_on || total == 0) return;
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_t0).count();
        const double rate = s > 0 ? static_cast<double>(done) / s : 0;
        const double left = rate > 0 ? static_cast<double>(total - done) / rate : 0;
        const int width = 30;
        const int fill = static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total));
        std::fprintf(stderr, "\r[%.*s%*s] %3.0f%%  %.2fM fixes/s  %3.0f s left ", fill, "==============================",
                     width - fill, "", 100.0 * static_cast<double>(done) / static_cast<double>(total), rate / 1e6, left);
        if (done == total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }

private:
    bool m_on;
    std::chrono::steady_clock::time_point m_t0;
};

class CheckCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("check", "Audit voyage tracks: sweep the hull along them, report groundings and close passes");
        m_sub->footer("Usage: shoal check --coast COAST_OR_GRID --ship SHIP.json TRACK... -o REPORT.geojson [--margin M] [--step M] [--jobs N]\n"
                      "Tracks: CSV with a header (AIS exports too), GPX, GeoJSON, NMEA 0183 logs; folders are searched.\n"
                      "Shallow water and dangers count as hazards for a limiting depth: --hazard-depth, else the ship's draught + --ukc.\n"
                      "Contacts are groundings only when they begin under way after the vessel was seen clear; contacts of a\n"
                      "vessel stopped or under --berthing-speed are alongside, those at a track's first fix in_contact_at_start,\n"
                      "those inside --berths areas expected_contact. Wild fixes (over --max-speed) are dropped and listed.\n"
                      "Exit status: 0 no grounding, 1 at least one grounding (or ship collision), 2 bad usage or unreadable input.");
        m_opts.add(*m_sub);
        m_sub->add_option("tracks", m_tracks, "Track files or folders")->required();
        m_sub->add_option("-o,--output", m_output, "Report to write: .geojson, or .gpkg (GeoPackage)")->required();
        m_sub->add_option("--format", m_format, "geojson or gpkg (default: from the extension of -o)")
            ->check(CLI::IsMember({"geojson", "gpkg"}));
        m_sub->add_option("--margin", m_audit.sweep.margin_m, "Close pass: clearance under this many metres (default 50)")
            ->check(finite)->check(CLI::NonNegativeNumber);
        m_sub->add_option("--step", m_audit.sweep.step_m, "No hull point moves more than this many metres between checks (default 5, at least 0.01)")
            ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--max-gap", m_audit.sweep.max_gap_s, "A gap between fixes longer than this (seconds) splits the track (default 600)")
            ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--jobs,-j", m_audit.jobs, "Tracks checked in parallel (default: all cores)");
        m_sub->add_flag("--encounters", m_audit.encounters,
                        "Exercise mode: the tracks are one exercise; also report ship-to-ship collisions and close quarters");
        m_sub->add_option("--ship-margin", m_audit.encounter.ship_margin_m,
                          "Exercise mode: close quarters when hulls come within this many metres (default 20)")
            ->check(finite)->check(CLI::NonNegativeNumber);
        m_sub->add_option("--berths", m_berths,
                          "Areas where contact is expected (berths, harbours, anchorages): any OGR vector source, every layer; "
                          "contacts there are expected_contact, not groundings. S-57 charts given as --coast add their "
                          "BERTHS, HRBARE and ACHARE, and SLCONS as shore constructions");
        m_sub->add_option("--berth-tolerance", m_berth_tolerance_m,
                          "Lines and points of --berths and S-57 berths / shore constructions count within this many metres (default 10)")
            ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--berthing-speed", m_audit.sweep.berthing_speed_kn,
                          "A contact that begins under this speed (knots) is alongside (berthing, moored), not a grounding (default 1)")
            ->check(finite)->check(CLI::NonNegativeNumber);
        m_sub->add_option("--stop-diameter", m_audit.sweep.stop_diameter_m,
                          "Stopped: every fix of --stop-time seconds within a box of this diagonal, metres (default 50)")
            ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--stop-time", m_audit.sweep.stop_duration_s, "Stopped: a stay of at least this many seconds (default 120)")
            ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--max-speed", m_audit.wild.max_speed_kn,
                          "Fastest plausible speed, knots: a fix that implies more against its neighbours is dropped as an "
                          "outlier, a jump that persists starts a new piece of track (default 60)")
            ->check(finite)->check(CLI::PositiveNumber);
        m_sub->add_option("--plot", m_plot, "Also draw the run as an SVG picture: overview and zoomed panels, groundings first");
        m_sub->add_option("--date", m_date, "Date (YYYY-MM-DD, UTC) for logs whose times carry none (NMEA without RMC/ZDA)");
        m_sub->add_flag("--progress,!--no-progress", m_progress, "Progress bar on stderr (default: when stderr is a terminal)");
    }
    int run() override {
        std::vector<std::string> all_inputs = m_opts.inputs(track::expand_inputs(m_tracks));
        all_inputs.insert(all_inputs.end(), m_berths.begin(), m_berths.end());
        check_output(m_output, all_inputs);
        if (!m_plot.empty()) {
            // The picture is an output too: never one of the inputs, nor the report itself.
            check_output(m_plot, all_inputs);
            std::error_code ec;
            if (m_plot == m_output || (std::filesystem::exists(m_plot, ec) && std::filesystem::exists(m_output, ec) &&
                                       std::filesystem::equivalent(m_plot, m_output, ec)))
                throw UsageError("--plot '" + m_plot + "' is the report -o '" + m_output + "': choose another file for the picture");
        }
        if (m_audit.sweep.step_m < min_step_m)
            throw UsageError("--step " + std::to_string(m_audit.sweep.step_m) + " is under the smallest step, " + std::to_string(min_step_m) +
                             " m: a sweep that fine never ends");
        const hull::Hull hull = m_opts.load_hull();
        if (!m_date.empty()) {
            int y = 0, mo = 0, d = 0;
            char tail = 0;
            const auto day = std::sscanf(m_date.c_str(), "%d-%d-%d%c", &y, &mo, &d, &tail) == 3
                                 ? track::utc_seconds(y, mo, d, 0, 0, 0) : std::nullopt;
            if (!day) throw UsageError("--date '" + m_date + "' is not a date YYYY-MM-DD");
            m_audit.read.date_s = *day;
        }
        const std::string format = !m_format.empty() ? m_format
                                   : std::filesystem::path(m_output).extension() == ".gpkg" ? "gpkg" : "geojson";
        for (const std::string& out : {m_output, m_plot}) {
            if (out.empty()) continue;
            const std::filesystem::path dir = std::filesystem::path(out).has_parent_path() ? std::filesystem::path(out).parent_path() : ".";
            if (!std::filesystem::is_directory(dir))
                throw InputError("cannot write '" + out + "': folder '" + dir.string() + "' does not exist");
        }
        const grid::CoastGrid g = m_opts.load_grid(hull);
        check_readable(m_berths);
        // Expected-contact areas: --berths, and the S-57 charts the coast came from.
        std::vector<std::string> area_warnings;
        const coast::ExpectedAreas areas =
            coast::ExpectedAreas::load(m_berths, grid::coast_sources(m_opts.coast, g), g.frame(), m_berth_tolerance_m, &area_warnings);
        print_warnings(area_warnings);
        if (!areas.empty())
            std::fprintf(stderr, "shoal: %zu expected-contact areas (berths, harbours, anchorages) and %zu shore constructions\n",
                         areas.count(coast::AreaRole::expected), areas.count(coast::AreaRole::structure));
        m_audit.areas = &areas;
        Progress bar(m_progress.value_or(::isatty(2) != 0));
        m_audit.progress = [&](std::size_t done, std::size_t total) { bar(done, total); };
        const audit::AuditResult r = audit::run_audit(m_tracks, g, hull, m_opts.ship_file.empty() ? "--dims " + m_opts.dims : "ship file", m_audit);
        for (const auto& f : r.files) {
            for (const auto& m : f.read.messages) std::fprintf(stderr, "shoal: warning: %s\n", printable(m).c_str());
            if (f.read.skipped > f.read.messages.size())
                std::fprintf(stderr, "shoal: warning: %s: %zu more bad rows skipped\n", printable(f.file).c_str(), f.read.skipped - f.read.messages.size());
            if (f.read.reordered)
                std::fprintf(stderr, "shoal: warning: %s: %zu fixes out of time order (sorted by time)\n", printable(f.file).c_str(), f.read.reordered);
            if (f.read.duplicates)
                std::fprintf(stderr, "shoal: warning: %s: %zu fixes repeat an earlier time of their vessel (dropped)\n", printable(f.file).c_str(),
                             f.read.duplicates);
            if (!f.error.empty()) std::fprintf(stderr, "shoal: error: %s (file skipped)\n", printable(f.error).c_str());
        }
        std::size_t wild_said = 0;
        for (const auto& t : r.tracks)
            for (const auto& w : t.summary.wild_fixes)
                if (wild_said++ < 20) print_warnings({report::wild_fix_message(t.summary, w)});
        print_warnings(r.warnings);
        if (wild_said > 20) std::fprintf(stderr, "shoal: warning: %zu more wild fixes dropped (listed in the report's problems)\n", wild_said - 20);
        for (const auto& e : r.errors)
            std::fprintf(stderr, "shoal: error: track '%s' in '%s': %s (track skipped)\n", printable(e.track).c_str(), printable(e.file).c_str(), printable(e.message).c_str());
        report::RunInfo info;
        for (const auto& c : m_opts.coast) info.coast += (info.coast.empty() ? "" : ", ") + c;
        info.frame = g.frame().description();
        info.cell_m = g.cell_size();
        info.limiting_depth_m = g.source().limiting_depth_m;
        char fp[20];
        std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(g.source().fingerprint));
        info.grid_fingerprint = fp;
        info.ship = m_opts.ship_file.empty() ? "--dims " + m_opts.dims : hull.name();
        info.sweep = m_audit.sweep;
        info.wild = m_audit.wild;
        for (const auto& b : m_berths) info.berths += (info.berths.empty() ? "" : ", ") + b;
        info.ship_margin_m = m_audit.encounter.ship_margin_m;
        const auto t0 = std::chrono::steady_clock::now();
        if (format == "gpkg") report::write_gpkg(m_output, r, info);
        else {
            std::vector<std::string> style_warnings;
            report::write_geojson(m_output, r, info, &style_warnings);
            print_warnings(style_warnings);
        }
        // The report is written: a picture that cannot be written is an error said as such,
        // but it must not hide the groundings the report holds (exit 1 stays 1).
        bool plot_failed = false;
        if (!m_plot.empty()) {
            try {
                report::write_plot_svg(m_plot, r, g);
            } catch (const InputError& e) {
                std::fprintf(stderr, "shoal: error: the picture was not written: %s (the report %s was)\n", printable(e.what()).c_str(),
                             printable(m_output).c_str());
                plot_failed = true;
            }
        }
        const double write_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // With -o - the report is stdout: the table goes to stderr, so the JSON stays clean.
        std::FILE* table = m_output == "-" ? stderr : stdout;
        std::fputs(report::summary_table(r).c_str(), table);
        const double fps = r.sweep_s > 0 ? static_cast<double>(r.fixes) / r.sweep_s : 0;
        std::fprintf(table, "time: read %.3f s, sweep %.3f s (%.0f fixes/s), write %.3f s\nreport: %s\n", r.read_s, r.sweep_s, fps, write_s,
                     printable(m_output).c_str());
        bool unreadable = r.tracks.empty() && (!r.errors.empty() || std::any_of(r.files.begin(), r.files.end(), [](const auto& f) { return !f.error.empty(); }));
        if (unreadable) return exit_usage;
        if (r.groundings > 0 || r.collisions > 0) return exit_found;
        return plot_failed ? exit_usage : exit_ok;
    }

private:
    CoastAndShip m_opts;
    std::vector<std::string> m_tracks;
    std::string m_output;
    std::string m_format;
    std::optional<bool> m_progress;
    std::string m_date;
    std::string m_plot;
    std::vector<std::string> m_berths;
    double m_berth_tolerance_m = 10.0;
    audit::AuditOptions m_audit;
};

}  // namespace

std::vector<std::unique_ptr<Command>> make_commands() {
    std::vector<std::unique_ptr<Command>> v;
    v.push_back(std::make_unique<ImportCommand>());
    v.push_back(std::make_unique<InfoCommand>());
    v.push_back(std::make_unique<ProbeCommand>());
    v.push_back(std::make_unique<CheckCommand>());
    return v;
}

}  // namespace shoal::cli
