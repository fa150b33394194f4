#pragma once
/// QGIS styles for the report layers, so a report opens styled: groundings red, close passes
/// amber, labelled with the time of first contact; tracks coloured by least clearance; hull
/// footprints outlined. QGIS loads `NAME.qml` beside `NAME.geojson` as the layer's default
/// style, and a GeoPackage's `layer_styles` table for its layers.

#include <optional>
#include <string>
#include <string_view>

#include <shoal/util/output_file.hpp>

class GDALDataset;

namespace shoal::report {

/// The QML of layer `layer` ("events", "tracks" or "hulls"); empty for another name.
std::string_view layer_style(std::string_view layer);

/// Stages the style of `layer` as `qml_path` (REPORT.qml beside a GeoJSON report), marked as
/// shoal's. An existing file of that name that shoal did not write (no mark) is left as it is:
/// returns nothing then, with the warning in `warning`.
std::optional<StagedOutput> stage_sidecar_style(const std::string& qml_path, std::string_view layer, std::string& warning);
/// The mark shoal puts in the styles it writes beside reports (and in the other files of a
/// GeoJSON report's QGIS project: its layer files, its .qgs).
inline constexpr std::string_view sidecar_mark = "<!-- written by shoal beside its report; shoal replaces it at the next run -->";
/// Whether `path` is a regular file whose first 4 KiB hold sidecar_mark (shoal wrote it). A
/// FIFO or a device is never opened.
bool is_shoal_sidecar(const std::string& path);

/// Adds the `layer_styles` table with a default style for each of the report's layers.
void add_layer_styles(GDALDataset& gpkg);

}  // namespace shoal::report
