#pragma once
// A GeoJSON report's text staged at its path, with its QGIS style beside it (as stage_geojson).
#include <string>
#include <string_view>
#include <vector>

#include <shoal/util/output_file.hpp>

namespace shoal::report {

/// `text` staged at `path` and the QGIS style REPORT.qml beside it (report_outputs says
/// where), unless a file of that name exists that shoal did not write (a warning then).
std::vector<StagedOutput> stage_geojson_text(const std::string& path, std::string_view text, std::vector<std::string>* warnings);

}  // namespace shoal::report
