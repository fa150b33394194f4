#pragma once
/// The CSV of `shoal probe`: its poses read, rows `lat,lon,heading` (degrees, true heading),
/// split by track::CsvSplitter (quotes honoured, one separator a file). A header line naming
/// the columns (lat/latitude, lon/lng/longitude, heading/hdg) is optional; without one the
/// columns are in that order. And its answers written, one row a pose.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shoal::io {

/// Most bytes a pose file may hold (some eight million poses).
inline constexpr std::size_t max_pose_file_bytes = std::size_t{1} << 28;

struct PoseRow {
    double lat = 0, lon = 0, heading_deg = 0;
    std::size_t line = 0;  ///< 1-based line number in the file
};

struct PoseFile {
    std::vector<PoseRow> poses;
    std::size_t skipped = 0;          ///< bad rows skipped
    std::vector<std::string> errors;  ///< messages for the first few bad rows ("FILE line N: ...")
};

/// Throws InputError for a missing or unreadable file, or a header without lat/lon columns.
PoseFile read_pose_csv(const std::string& path);
/// The same from text already in memory (`name` is used in messages).
PoseFile parse_pose_csv(const std::string& text, const std::string& name);

/// The header line of the CSV `shoal probe` writes.
inline constexpr std::string_view probe_output_header = "lat,lon,heading,collision,clearance_m,covered\n";
/// One row of that CSV for `pose`, appended to `out`: lat and lon to 7 decimals, the heading to
/// 1, then, when the answer is `claimed`, collision 0/1 and the clearance in metres to 3 decimals,
/// else both empty (outside the chart nothing is claimed), and covered 0/1. Numbers as printf's
/// "%.Nf" writes them.
void append_probe_row(std::string& out, const PoseRow& pose, bool claimed, bool collision, double clearance_m, bool covered);
/// The file at `path` starts with that header: a probe's output, which a probe may replace.
bool is_probe_output(const std::string& path);

}  // namespace shoal::io
