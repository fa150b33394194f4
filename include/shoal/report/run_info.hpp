#pragma once
/// What a run was, for its report: the run header (RunInfo: the coast, the grid, the ship, the
/// rules and options, the inputs' fingerprints) and the chart its `coast` layer draws.

#include <cmath>
#include <future>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::report {

/// What the run was: goes into the report's "shoal" member.
struct RunInfo {
    std::string coast;        ///< the --coast inputs
    std::string frame;        ///< description of the local frame
    double cell_m = 0;
    /// The limiting depth of the vessels with no draught of their own (`--hazard-depth` for
    /// every vessel, else the default ship's draught + ukc, else the grid's default); NaN:
    /// land only for them. Each track says its own (TrackSummary::limiting_depth_m).
    double limiting_depth_m = NAN;
    std::string limiting_depth_source = "land_only";  ///< where that came from (grid::to_string(DepthPlan::Source))
    double ukc_m = 0;                   ///< under-keel clearance added to every draught
    std::string grid_fingerprint;
    /// --coast a grid file: a fingerprint (fingerprint_sources) of the chart sources it names, read
    /// again at check time (S-57 berths and shore constructions, the compilation scale, the coast
    /// layer); "" when --coast gives the sources (grid_fingerprint covers their bytes then)
    std::string chart_fingerprint;
    std::string ship;         ///< the default hull: ship name or "--dims a,b,c,d"
    audit::SweepOptions sweep;
    audit::World world = audit::World::real;  ///< the world the contacts' kinds were decided in
    audit::EvidenceOptions evidence;          ///< the real world's rules
    track::WildFixOptions wild;
    std::string berths;        ///< the --berths sources (expected-contact areas), comma-separated
    std::string berths_fingerprint;  ///< files_fingerprint of the --berths sources ("" when none)
    double berth_tolerance_m = 10;   ///< lines and points of berths count within this (--berth-tolerance)
    std::string ship_fingerprint;    ///< files_fingerprint of the ship file, or of the --dims text
    std::string vessels;             ///< the vessels tables (--vessels, then those found in track folders), comma-separated
    std::string vessels_fingerprint; ///< files_fingerprint of those tables ("" when none)
    bool hull_from_length_width = false;  ///< --hull-from-length-width
    std::string date;                ///< --date (YYYY-MM-DD) for logs whose times carry none, "" when none
    std::string roles_fingerprint;   ///< exercise mode: files_fingerprint of the roles file ("" when none)
    double ship_margin_m = 0;  ///< exercise mode: close quarters under this
    std::string exercise_by = "run";  ///< exercise mode: how tracks are grouped (audit::ExerciseBy)
    std::string roles;                ///< exercise mode: the exercise (roles) file, "" when none
    std::string assessment;           ///< --assess: the assessment file, "" when none
    std::string role_column;          ///< exercise mode: the role column (--role-column), "" when none
    double encounter_range_m = audit::ColregOptions{}.range_m;  ///< exercise mode: COLREG situations within this
    std::size_t max_encounters_per_ship = audit::AuditOptions{}.max_encounters_per_ship;  ///< exercise mode: 0, no limit
    /// The chart's box in lon/lat (x lon, y lat): the grid's extent, its border taken back from
    /// the grid's frame; empty (minx > maxx) when not known. The QGIS project opens on it, in the
    /// UTM zone of its centre (qgis_project.hpp), whatever the tracks' extent.
    geo::Box chart_lonlat;
    /// The chart for the report's `coast` layer (read_chart); null: no coast layer.
    const coast::Coastline* chart = nullptr;
    /// When valid (and `chart` null), the chart for the `coast` layer of a GeoJSON report is
    /// still being read while the report's other files are written (check does so on more than
    /// one thread): the coast layer waits for it; null from it, no coast layer. chart_of().
    std::shared_future<const coast::Coastline*> chart_later;
    /// The report's map for QGIS: its `poses` and `coast` layers and its QGIS project (a
    /// GeoPackage's stored project; beside a GeoJSON report REPORT.qgz and the layer files it
    /// opens). false (--no-project): the events, tracks and hulls only.
    bool project = true;
    /// Threads that write a GeoJSON report's QGIS project layer files, in blocks of features,
    /// the report itself on one more meanwhile (1: one thread at work at a time, one file after
    /// another; 0: all cores; the CLI passes --jobs).
    unsigned jobs = 0;
};

/// RunInfo::chart, else what RunInfo::chart_later gives (waiting for it), else null.
inline const coast::Coastline* chart_of(const RunInfo& info) {
    if (info.chart || !info.chart_later.valid()) return info.chart;
    return info.chart_later.get();
}

/// The chart the run was checked against, for the report's `coast` layer: the grid's sources
/// (`coast` as given, or the files a .shoalgrid records) read again through the coast reader
/// with the options the grid was built with (layers, source CRS, limiting depth, danger
/// radius, depth field). Nothing, with the reason in `warning`, when they cannot be read (a
/// grid whose sources have moved or are bad now): the report then has no coast layer. The
/// layer draws the chart near the tracks' lines of `run`: with none (an empty input, every
/// track refused) it is empty whatever the chart, which is then not read (an empty chart).
/// (Made by the QGIS packaging, report/qgis/chart_layer.cpp.)
std::optional<coast::Coastline> read_chart(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const audit::AuditResult& run,
                                           std::string& warning);

/// The chart for the report's `coast` layer (read_chart), read when made, or, `meanwhile`, on
/// a thread of its own while the report is written (given to the report as RunInfo::chart_later:
/// its coast layer waits for it). The thread is joined when this goes, whatever was thrown.
class ChartRead {
public:
    ChartRead(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const audit::AuditResult& run, bool meanwhile);
    ChartRead(const ChartRead&) = delete;
    ChartRead& operator=(const ChartRead&) = delete;
    /// Whether the chart is being read on its thread (false: read already, or no thread to be had).
    bool meanwhile() const noexcept { return m_later.valid(); }
    /// The chart to `info`: RunInfo::chart when read already, else RunInfo::chart_later.
    void give(RunInfo& info) const;
    /// Why there is no chart, once the read is over (waits for it): "" when there is one, or
    /// when the read threw (what it threw comes out of RunInfo::chart_later).
    const std::string& warning() const;

private:
    std::optional<coast::Coastline> m_chart;
    std::string m_warning;
    std::promise<const coast::Coastline*> m_read;
    std::shared_future<const coast::Coastline*> m_later;
    std::jthread m_thread;  // last: joined before the chart and the warning it writes go
};

/// The chart's box in lon/lat (RunInfo::chart_lonlat): the grid's extent taken back from its frame.
geo::Box chart_box_lonlat(const grid::CoastGrid& grid);

/// The run header of a check: the coast sources `coast` as given, the grid's frame, cell and
/// fingerprint, the default hull `ship` (its name, or "--dims a,b,c,d") and its draught
/// `default_draught_m` (0: none), the rules of `options` (limiting depth too), the
/// expected-contact sources `berths`.
RunInfo run_info(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const std::string& ship,
                 const audit::AuditOptions& options, const std::vector<std::string>& berths, double default_draught_m = 0);

/// A fingerprint (XXH3, 16 hex digits) of the bytes and sizes of the files at `paths`, in
/// order ("" for none): what the run header says of the inputs other than the coast (the grid
/// has its own) so that merge tells parts of edited inputs apart. A path that is not a regular
/// file (a pipe, a device, standard input) is never opened: its name is fingerprinted. GDAL
/// paths (/vsizip/...) are read through GDAL.
std::string files_fingerprint(const std::vector<std::string>& paths);
/// The size in bytes and files_fingerprint of one file (size -1 when it is not a regular file).
std::pair<long long, std::string> file_size_and_fingerprint(const std::string& path);
/// The size and fingerprint of a file as a run read it: standard input or a pipe (which cannot
/// be read again) by the bytes the readers were handed (ReadReport::stream_digest), any other
/// file by file_size_and_fingerprint.
std::pair<long long, std::string> read_file_fingerprint(const audit::FileResult& file);

}  // namespace shoal::report
