#pragma once
/// The QGIS project of a report, one writer for both formats: the report's layers in order
/// (coast at the bottom, then tracks, poses, hulls, encounters, events on top), each with its
/// source (relative to the project's folder), style and temporal settings (the style's), the
/// project CRS the UTM zone of the chart's centre and the map extent the chart (the grid's
/// extent: where the audit can say anything), and the temporal controller's range the run (first
/// to last fix). Without a chart box (none known), the run's tracks give both. A chart wider
/// than 24 degrees of longitude (a world coast) is shown in EPSG:4326, not in one UTM zone.
///
/// - A GeoPackage report stores it in QGIS's `qgis_projects` table (opened with
///   `qgis --project 'geopackage:REPORT.gpkg?projectName=shoal'`), as QGIS 3.22 stores it: a
///   row (name, metadata, content) whose content is the .qgz written out in hexadecimal text;
///   the layers' sources are "./REPORT.gpkg|layername=LAYER".
/// - A GeoJSON report gets REPORT.qgz beside it (report/geojson_output.hpp), whose layers are
///   the report itself (events) and the per-layer files beside it (REPORT.poses.geojson, ...).
///
/// Renaming or moving the files breaks the relative sources, as it does for any QGIS project.
#include <cmath>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/geo/point.hpp>

class GDALDataset;

namespace shoal::report {

inline constexpr const char* qgis_project_name = "shoal";

/// What the project shows of a run: the box of its tracks (lon x, lat y; empty when x0 > x1),
/// the box of its chart (the same; empty: not known) and its first and last fix (NaN: none).
/// `merge` adds up the parts' views.
struct ProjectView {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    geo::Box chart;
    double first_fix_s = NAN, last_fix_s = NAN;
    /// Exercise mode: the run's exercises, sorted, each once (empty outside exercise mode). The
    /// project then has a group per exercise (see qgis_project_xml).
    std::vector<std::string> exercises{};
    /// This view and `other` together.
    void add(const ProjectView& other);
};
/// The view of `result` checked against the chart whose lon/lat box is `chart` (RunInfo::chart_lonlat).
ProjectView project_view(const audit::AuditResult& result, const geo::Box& chart);

/// One layer of the project: `name` (also the name of its style, layer_style), its geometry
/// ("Point", "Line" or "Polygon") and its OGR source relative to the project's folder
/// ("./REPORT.gpkg|layername=poses", "./REPORT.poses.geojson").
struct ProjectLayer {
    std::string name, geometry, source;
    /// It has an `exercise` field to filter on (an empty GeoJSON file has no fields: filtering
    /// it would leave the layer invalid in QGIS, and there is nothing to filter).
    bool filterable = true;
};

/// The project's .qgs XML: `layers` top of the map first, titled after `report_name`. With
/// exercises (ProjectView::exercises), the layers with an `exercise` field (exercise_layers)
/// are in a group per exercise ("exercise NAME"), each a copy filtered to that exercise (the
/// OGR source's `subset`), the groups under a mutually exclusive group "exercises" (the first
/// shown): a frame of the replay never holds ships of two exercises. The other layers (learned,
/// coast) stay below, shared.
std::string qgis_project_xml(const std::vector<ProjectLayer>& layers, const std::string& report_name, const ProjectView& view);

/// `qgs` as a .qgz: a zip holding it as `member` (deflated by zlib), the bytes GDAL's zip writer
/// wrote for it (no date: the same XML gives the same bytes), made without GDAL.
std::string qgz_of(const std::string& member, const std::string& qgs);

/// Whether the .qgz at `path` (a regular file) holds `member` and that says shoal wrote it
/// (sidecar_mark, report/qgis/qgis_styles.hpp): false for anything else (not a zip, another
/// project, or shoal's project saved over by QGIS, which drops the mark).
bool is_shoal_qgz(const std::string& path, const std::string& member);

/// Writes the project into the `qgis_projects` table of `gpkg` (named `file_name`): its
/// layers, those of report_layers_top_first that it has (defined with the GeoPackage report,
/// gpkg_report.cpp: the one part of the project that needs GDAL).
void add_qgis_project(GDALDataset& gpkg, const std::string& file_name, const ProjectView& view);

/// The layers that have an `exercise` field in exercise mode.
inline constexpr const char* exercise_layers[] = {"breaches", "events", "encounters", "hulls", "poses", "tracks"};

/// The report's map layers, top of the map first (QGIS's layer tree order).
inline constexpr const char* report_layers_top_first[] = {"breaches", "events", "encounters", "hulls", "poses", "tracks", "learned", "coast"};

}  // namespace shoal::report
