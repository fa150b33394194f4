#pragma once
/// The GeoJSON report (RFC 7946, WGS84 lon/lat; one Point feature per event, the run in the
/// top-level member "shoal") and the outputs a report consists of; the texts events are
/// labelled with. Reports are deterministic (no wall-clock figures in them) and written
/// atomically.
///
/// A caller that writes several outputs (the report, its style, a picture) checks them all
/// first with `check_outputs(report_outputs(path, format) + the others, inputs)`, stages each
/// (stage_geojson / stage_gpkg / StagedOutput), and puts them in place together with
/// `commit_all`: an interrupt before then leaves every earlier file as it was.

#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

/// The GeoJSON report as text (schemas/report.schema.json).
std::string geojson(const audit::AuditResult& result, const RunInfo& info);

/// Throws UsageError when a QGIS project cannot name the report at `path`: its file name holds
/// '|', which QGIS's OGR provider reads as the start of a layer's options.
void check_project_name(const std::string& path);

/// The files a report at `path` consists of, for check_outputs: the report ("-o", "the
/// report") and, for a GeoJSON report in a regular file, its QGIS style REPORT.qml beside it
/// and, with `project`, its QGIS project REPORT.qgz and the layer files that opens,
/// REPORT.LAYER.geojson and REPORT.LAYER.qml for LAYER tracks, hulls, poses and coast.
/// `format`: "geojson" or "gpkg".
/// The report itself is replaced only when shoal wrote it (OutputSpec::ours).
std::vector<OutputSpec> report_outputs(const std::string& path, const std::string& format, bool project = true);

/// A GeoJSON report or shard's part shoal wrote: a top-level member "shoal" (the run, an
/// object) that begins within its first 4 KiB. A "shoal" anywhere else (a feature's property
/// `"shoal": true` in someone's hazard file, a string) is not shoal's mark.
bool is_shoal_geojson_report(const std::string& path);
/// The GeoJSON report, staged at `path` (not yet in place: commit_all puts it there), and the
/// QGIS style REPORT.qml beside it, unless a file of that name exists that shoal did not write
/// (then a warning goes into `warnings`, when given, and that file is left alone). With
/// `info.project`, also the QGIS project REPORT.qgz beside it and the layer files it opens
/// (REPORT.tracks.geojson, .hulls, .poses and, with a chart (`chart_of(info)`), .coast, each with its .qml),
/// unless one of those exists that shoal did not write (a warning then, and none of them is
/// written). Nothing beside stdout, a device or a pipe. Throws InputError naming the file it
/// could not write.
std::vector<StagedOutput> stage_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info,
                                        std::vector<std::string>* warnings = nullptr);
/// stage_geojson, then commit_all.
void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info,
                   std::vector<std::string>* warnings = nullptr);

/// "FILE line N: fix at LAT, LON (TIME) of track 'ID' dropped as an outlier: WHY".
std::string wild_fix_message(const audit::TrackSummary& track, const track::WildFix& fix);

/// ISO 8601 UTC, e.g. 2014-08-15T19:00:00.042Z (milliseconds only when not whole seconds).
std::string iso_time(double epoch_s);

/// Short text for maps: "aground 10:03:12Z" (land), "aground shallow 3.6 m 10:03:12Z",
/// "aground wreck 10:03:12Z" (a danger; its sounding when charted), "aground pier 'Pier 25'
/// 10:03:12Z" (a structure: its kind, and its name when it has one), "close 10:03:12Z".
std::string event_label(const audit::Event& e);

}  // namespace shoal::report
