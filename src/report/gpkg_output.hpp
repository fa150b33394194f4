#pragma once
// The GeoPackage report's frame, one for `check` (stage_gpkg) and `merge`: how the file is
// created, its layers (in the order they are created and filled), its QGIS styles and project.
#include <cpl_port.h>

#include <functional>
#include <string>

#include "report/qgis/qgis_project.hpp"
#include <shoal/audit/audit.hpp>
#include <shoal/report/gpkg_report.hpp>
#include <shoal/util/output_file.hpp>

class GDALDataset;
class OGRLayer;

namespace shoal::report {

/// The layers and tables of a GeoPackage report; null: not in this report. Rows are written
/// in this order too: events, encounters, breaches, tracks, hulls, poses, coast, learned, problems,
/// approaches, scores, run, summary, part.
struct GpkgLayers {
    OGRLayer *events = nullptr, *tracks = nullptr, *hulls = nullptr, *poses = nullptr, *coast = nullptr, *encounters = nullptr,
             *problems = nullptr, *approaches = nullptr, *run = nullptr, *summary = nullptr;
    OGRLayer *breaches = nullptr, *scores = nullptr;  ///< --assess
    OGRLayer* learned = nullptr;  ///< --world real: what the run's traffic taught
    /// A shard's report only: one row, field `order`, the JSON of report/part_order.hpp.
    OGRLayer* part = nullptr;
};

/// Creates the empty layers of a report of the shape of `shape` (exercise mode:
/// has_encounters; --assess: has_assessment; a shard: shard; --world real: world), each with the fields report_fields.hpp lists for it; the
/// `coast` layer when `chart`, the `poses` layer when `poses`.
GpkgLayers make_gpkg_layers(GDALDataset& ds, const audit::AuditResult& shape, bool chart, bool poses);

/// The map layers a GeoJSON report lacks (it holds the events), each written into a file of
/// its own beside it (geojson_report.cpp, write_layer): the same fields, rows and geometries
/// as the GeoPackage's layers of those names.
enum class MapLayer { tracks, hulls, poses, coast, learned };
/// "tracks", "hulls", "poses", "coast", "learned": the layer's name and its style's.
const char* name_of(MapLayer which) noexcept;

/// A GeoPackage report staged at `path`: created as every report is (a fixed "current date":
/// the same rows, the same bytes), filled by `fill` (make_gpkg_layers, then the rows in one
/// transaction), then given its QGIS styles and project (`view`; null: no project, --no-project).
/// Throws InputError when `path` is not a regular file or cannot be written.
StagedOutput stage_gpkg_with(const std::string& path, const std::function<void(GDALDataset&)>& fill, const ProjectView* view);

}  // namespace shoal::report
