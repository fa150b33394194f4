#pragma once
/// Writing an audit's results: the GeoJSON report (RFC 7946, WGS84 lon/lat; one Point feature
/// per event, the run summary in the top-level member "shoal"), the GeoPackage (layers
/// events, tracks, hulls) and the summary table for stdout. Reports are deterministic (no
/// wall-clock figures in them) and written atomically.

#include <cmath>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>

namespace shoal::report {

/// What the run was: goes into the report's "shoal" member.
struct RunInfo {
    std::string coast;        ///< the --coast inputs
    std::string frame;        ///< description of the local frame
    double cell_m = 0;
    double limiting_depth_m = NAN;  ///< the grid's limiting depth; NaN: land only
    std::string grid_fingerprint;
    std::string ship;         ///< the default hull: ship name or "--dims a,b,c,d"
    audit::SweepOptions sweep;
    track::WildFixOptions wild;
    std::string berths;        ///< the --berths sources (expected-contact areas), comma-separated
    double ship_margin_m = 0;  ///< exercise mode: close quarters under this
};

/// The GeoJSON report as text (schemas/report.schema.json).
std::string geojson(const audit::AuditResult& result, const RunInfo& info);
/// Also writes the QGIS style REPORT.qml beside it, unless a file of that name exists that
/// shoal did not write (then a warning goes into `warnings`, when given, and it is left alone).
void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info,
                   std::vector<std::string>* warnings = nullptr);

/// The GeoPackage report: layers `events` (points), `tracks` (lines with per-track figures),
/// `hulls` (hull footprints at each event), in EPSG:4326. Written to a temporary file, renamed.
void write_gpkg(const std::string& path, const audit::AuditResult& result, const RunInfo& info);

/// The human summary: one line per track with events, totals, and problems met.
std::string summary_table(const audit::AuditResult& result);

/// "FILE line N: fix at LAT, LON (TIME) of track 'ID' dropped as an outlier: WHY".
std::string wild_fix_message(const audit::TrackSummary& track, const track::WildFix& fix);

/// ISO 8601 UTC, e.g. 2014-08-15T19:00:00.042Z (milliseconds only when not whole seconds).
std::string iso_time(double epoch_s);

/// Short text for maps: "aground 10:03:12Z" (land), "aground shallow 3.6 m 10:03:12Z",
/// "aground wreck 10:03:12Z" (a danger; its sounding when charted), "close 10:03:12Z".
std::string event_label(const audit::Event& e);

}  // namespace shoal::report
