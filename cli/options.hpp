#pragma once
// What the commands share: option validators, the coast-and-ship options of probe and check,
// and how warnings and grids are printed.

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/limiting_depth.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::cli {

/// Numbers that must be finite: "must be a finite number (got 'inf')" (an infinite or NaN
/// option would silently switch a rule off; `positive` and `non_negative` refuse NaN too).
extern const CLI::Validator finite;
/// > 0 and >= 0, said plainly: "must be > 0 (got '-1')" (CLI11's own print the range with its
/// upper bound, the largest double, in 309 digits).
extern const CLI::Validator positive;
extern const CLI::Validator non_negative;
/// At most `max`; `what` says why ("the largest cell"): "must be at most 100000 (the largest cell; got '1e300')".
CLI::Validator at_most(double max, const std::string& what);

/// Coastline sources and grids that exist but cannot be opened: said as such, not as "not a
/// vector dataset" (which is what OGR makes of a file it may not read).
void check_readable(const std::vector<std::string>& paths);

/// A library message in the CLI's terms: the option fields it names (`SweepOptions::step_m`,
/// `BuildRequest::crs`, ...) become the flags that set them (`--step`, `--crs`).
std::string in_cli_terms(std::string message);

/// "shoal: warning: ..." on stderr, one line each, in the CLI's terms, terminal escapes shown as hex.
void print_warnings(const std::vector<std::string>& warnings);
/// "shoal: error: ..." the same way, also with --quiet: what made the run fail (exit 2) though
/// the report was written (a debrief page refused).
void print_errors(const std::vector<std::string>& errors);
/// --quiet: warnings and notes on stderr are left out (errors never are); `quiet()` says so.
void set_quiet(bool quiet);
bool quiet();
/// A note or warning line on stderr ("shoal: " + text), unless --quiet.
void note(const std::string& text);

/// What a grid holds (import and info).
void print_grid(const grid::CoastGrid& g);

/// --hazard-depth, --depth-field, --danger-radius: which depth areas and dangers are hazards.
void add_hazard_options(CLI::App& sub, coast::ImportOptions& import);

/// Options shared by the commands that take `--coast COAST_OR_GRID` and a ship.
struct CoastAndShip {
    std::vector<std::string> coast;
    std::string ship_file;
    std::string dims;
    grid::BuildRequest request;
    std::optional<double> ukc;  ///< --ukc: under-keel clearance required, metres
    bool verbose = false;

    void add(CLI::App& sub);
    /// Every input file named: `more`, the coastline sources and the ship file.
    std::vector<std::string> inputs(std::vector<std::string> more) const;
    /// The ship: --ship read through GDAL's virtual files (Hull::load), else --dims.
    hull::Hull load_hull() const;
    /// The same with `ship_file_hull` reading the ship file (the executable's own probe parses
    /// one it has read itself); UsageError when neither --ship nor --dims is given.
    hull::Hull hull_with(const std::function<hull::Hull(const std::string& path)>& ship_file_hull) const;
    /// Where the default hull came from, for the report: "ship file" or "--dims A,B,C,D".
    std::string hull_label() const;
    /// The grid: a grid file as it is, or coastline sources built (or taken from the cache)
    /// with every depth area and danger; says on stderr the limiting depth `hull` gives
    /// (--hazard-depth, else its draught + --ukc) when it has one.
    grid::CoastGrid load_grid(const hull::Hull& hull) const;
    /// load_grid with `load` in the place of grid::load_or_build (the executable's own probe
    /// reads a grid file only: it links no GDAL). load_hull and load_grid are in
    /// options_full.cpp (the full command module), the rest here (both).
    using GridLoader = grid::CoastGrid (*)(const std::vector<std::string>& paths, const grid::BuildRequest& request, grid::LoadReport* report);
    grid::CoastGrid load_grid_with(const hull::Hull& hull, GridLoader load) const;
    /// Warns about the limiting depth `plan` on grid `g` (grid::depth_warnings), naming the coast.
    void warn_depth(const grid::DepthPlan& plan, const grid::CoastGrid& g) const;
};

}  // namespace shoal::cli
