#pragma once
/// The QGIS project stored in a GeoPackage report (QGIS's `qgis_projects` table, opened with
/// `qgis --project 'geopackage:REPORT.gpkg?projectName=shoal'`): the report's layers in order
/// (coast at the bottom, then tracks, poses, hulls, encounters, events on top) with their
/// styles, the project CRS the UTM zone of the run's centre, the map extent the run's tracks,
/// and the temporal controller's range the run (first to last fix).
///
/// Stored as QGIS 3.22 stores it: a row (name, metadata, content) whose content is the .qgz
/// (a zip holding one .qgs) written out in hexadecimal text; the layers' sources are
/// "./REPORT.gpkg|layername=LAYER", relative to the folder of the GeoPackage (renaming the
/// file breaks them, as it does for any QGIS project).
#include <cmath>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>

class GDALDataset;

namespace shoal::report {

inline constexpr const char* qgis_project_name = "shoal";

/// What the project shows of a run: the box of its tracks (lon x, lat y; empty when x0 > x1)
/// and its first and last fix (NaN: none). `merge` adds up the parts' views.
struct ProjectView {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    double first_fix_s = NAN, last_fix_s = NAN;
    /// This view and `other` together.
    void add(const ProjectView& other);
};
ProjectView project_view(const audit::AuditResult& result);

/// The project's .qgs XML for the layers of `gpkg` (a GeoPackage named `file_name`).
std::string qgis_project_xml(GDALDataset& gpkg, const std::string& file_name, const ProjectView& view);

/// `content` as a .qgz: a zip (deflated, with a fixed date so the same run writes the same bytes) holding NAME.
std::string zip_one(const std::string& name, const std::string& content);

/// Writes the project into the `qgis_projects` table of `gpkg`.
void add_qgis_project(GDALDataset& gpkg, const std::string& file_name, const ProjectView& view);

}  // namespace shoal::report
