#pragma once
// A GeoJSON report's text staged at its path, with its QGIS style beside it (as stage_geojson);
// how the layer files beside a report write a coordinate.
#include <string>
#include <string_view>
#include <vector>

#include <shoal/geo/point.hpp>
#include <shoal/report/report_fields.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

/// `text` staged at `path` and the QGIS style REPORT.qml beside it (report_outputs says
/// where), unless a file of that name exists that shoal did not write (a warning then).
std::vector<StagedOutput> stage_geojson_text(const std::string& path, std::string_view text, std::vector<std::string>* warnings);

/// Appends `v` as printf's "%.7f" (fields::coordinate_decimals) prints it, as GDAL writes
/// GeoJSON coordinates, its trailing zeros dropped ("24.5", "60.2761559"); `null` when not
/// finite. The coordinates of the layer files beside a report.
void append_coordinate(std::string& out, double v);

/// GeoJSON positions [lon,lat] (append_coordinate's numbers) and the text around them, appended
/// to `out` a few kilobytes at a time: a std::string append for every number and bracket was
/// a fifth of the work of writing a day's layer files. What is put reaches `out` at flush().
class PositionWriter {
public:
    explicit PositionWriter(std::string& out) : m_out(out) {}
    PositionWriter(const PositionWriter&) = delete;
    PositionWriter& operator=(const PositionWriter&) = delete;
    /// The character `before` (none when '\0'), then the position `p`.
    void put(char before, geo::LonLat p);
    void put(char c);
    void flush();

private:
    std::string& m_out;
    std::size_t m_n = 0;
    char m_buf[4096];
};

/// Appends a row of `table` as a JSON object: nlohmann's dump() of the object of its fields
/// (present in `r`, in the table's order), one object a thread reused from row to row. How the
/// layer files write their properties. Instantiated for the rows of the layer files
/// (fields::TrackRow, HullRow, PoseRow, CoastRow).
template <class Row>
void append_object(std::string& out, const std::vector<fields::Field<Row>>& table, const Row& row, const audit::AuditResult& r);

}  // namespace shoal::report
