#pragma once
/// QGIS styles for the report layers, so a report opens styled: groundings red, close passes
/// amber, labelled with the time of first contact; tracks coloured by least clearance; hull
/// footprints outlined. QGIS loads `NAME.qml` beside `NAME.geojson` as the layer's default
/// style, and a GeoPackage's `layer_styles` table for its layers.

#include <string>
#include <string_view>

class GDALDataset;

namespace shoal::report {

/// The QML of layer `layer` ("events", "tracks" or "hulls"); empty for another name.
std::string_view layer_style(std::string_view layer);

/// Writes `NAME.qml` (the events style) beside a GeoJSON report `NAME.geojson`, atomically.
/// Writes the style beside a GeoJSON report (REPORT.qml), marked as shoal's. An existing file
/// of that name that shoal did not write (no mark) is left as it is: returns a warning then,
/// "" when the style was written.
std::string write_sidecar_style(const std::string& geojson_path, std::string_view layer = "events");
/// The mark shoal puts in the styles it writes beside reports.
inline constexpr std::string_view sidecar_mark = "<!-- written by shoal beside its report; shoal replaces it at the next run -->";

/// Adds the `layer_styles` table with a default style for each of the report's layers.
void add_layer_styles(GDALDataset& gpkg);

}  // namespace shoal::report
