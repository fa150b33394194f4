#pragma once
/// The GeoPackage report: the GeoJSON report's fields (geojson_report.hpp) as layers events,
/// tracks, hulls, encounters and tables problems, closest_approaches, run, summary.

#include <string>

#include <shoal/audit/audit.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

/// A GeoPackage shoal wrote as a report or a shard's part: GDAL opens it as a GeoPackage
/// holding the layers events and tracks.
bool is_shoal_gpkg_report(const std::string& path);

/// The GeoPackage report, staged at `path`: layers events, encounters, tracks, hulls (with
/// `info.project` also poses, coast and the stored QGIS project), tables
/// problems, closest_approaches, run, summary (docs/user-guide.md), in
/// EPSG:4326, QGIS styles in its `layer_styles` table. Throws InputError when `path` is not a
/// regular file (a device: "a GeoPackage must be a regular file ...") or cannot be written.
StagedOutput stage_gpkg(const std::string& path, const audit::AuditResult& result, const RunInfo& info);
/// stage_gpkg, then commit.
void write_gpkg(const std::string& path, const audit::AuditResult& result, const RunInfo& info);

}  // namespace shoal::report
