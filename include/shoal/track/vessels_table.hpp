#pragma once
/// Tables of AIS static data ("vessels tables": `*_vessels.csv`, DMA's and MarineCadastre's
/// static exports): each vessel's name, dimensions, draught and ship type by MMSI, read, joined
/// across tables, and recognised by their header among track files.

#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/hull/hull.hpp>

namespace shoal::track {

/// Whether the CSV file at `path` (a file or a GDAL virtual path) is a table of AIS static data
/// by its header: an MMSI column, a column a vessels table gives (name, ship type, draught,
/// dimensions) and no position column. Its name does not matter; a file that cannot be read is not one.
bool is_vessels_table(const std::string& path);

/// AIS static data of one vessel.
struct VesselInfo {
    std::string name;                      ///< empty when not known
    std::optional<hull::Dimensions> dims;  ///< A,B,C,D when all four are > 0
    double draught_m = NAN;
    int ship_type = -1;                    ///< AIS ship and cargo type, -1 when not known
    std::string source;                    ///< where it came from, for the report ("vessels file F")
    /// Where the dimensions, the draught and the ship type came from when not from `source` (merge_vessels
    /// took them from a later table that gave what the first lacked); empty: `source`.
    std::string dims_source, draught_source, ship_type_source;
    std::vector<std::string> sources;      ///< every table that names it, in order (merge_vessels): which tables matched a track
};

/// An MMSI as a spreadsheet may write it, as digits: "230035780.0" and "2.30035780E+08" are
/// "230035780" (an integral number whose every digit is written; "2.3003578E+08" is not one: its
/// ninth digit is not written); anything else is returned as it is.
std::string integral_id(std::string_view id);

/// The warnings for the vessels tables of `vessels` (VesselInfo::sources) none of whose vessels
/// is a track of `track_ids` (matched as join_static_data does: the id, or its integral_id):
/// "vessels file F: none of its N vessels is a track read (...): its data are not used".
std::vector<std::string> unmatched_vessels_tables(const std::map<std::string, VesselInfo>& vessels, const std::vector<std::string>& track_ids);

/// The deepest draught a vessels table may give (metres): the deepest ships draw about 25 m
/// (AIS gives at most 25.5); more is a wrong unit (decimetres) or a corrupt field.
inline constexpr double max_draught_m = 30.0;

/// The largest vessels file read (64 MiB: some 600,000 vessels' rows); a larger one, or an
/// endless source such as /dev/zero, is refused at that limit.
inline constexpr std::size_t max_vessels_bytes = std::size_t{64} << 20;

/// Reads a vessels file (`*_vessels.csv`: mmsi,name,to_bow_m,to_stern_m,to_port_m,to_stbd_m,
/// draught_m; also shiptype; A,B,C,D accepted for the dimensions), keyed by MMSI. A vessel named
/// in several rows takes the first non-empty name, the first complete dimensions and the first
/// draught. One row a line. A bad row costs that row, with a warning in `warnings` naming the
/// file, the line and what is wrong (the first ten, then a count): a quote not closed on its
/// line, a number of fields other than the header's (a decimal comma in a comma-separated file),
/// no mmsi, a value that is not a number or is negative, dimensions larger than any ship
/// (hull::Hull::plausible), a draught over max_draught_m. Empty values and AIS 0 are "not
/// known". With ';' or tab as separator, decimal commas are read. Throws InputError when the
/// file cannot be read or has no mmsi column.
std::map<std::string, VesselInfo> read_vessels(const std::string& path, std::vector<std::string>* warnings = nullptr);

/// Joins the vessels of one table (`from`, read from `source`: "vessels file F") into `into`.
/// The rule for one vessel in several tables: the first given keeps its values; a later table
/// only fills what it lacks (name, dimensions, draught, ship type). When two tables give
/// different dimensions or draughts for one vessel, one warning for that vessel names both
/// sources and which one is used.
void merge_vessels(std::map<std::string, VesselInfo>& into, std::map<std::string, VesselInfo>&& from, const std::string& source,
                   std::vector<std::string>* warnings = nullptr);

/// Every table of `paths` read (read_vessels) and joined in that order (merge_vessels, each
/// the source "vessels file F"), their warnings into `warnings`.
std::map<std::string, VesselInfo> read_vessels_files(const std::vector<std::string>& paths, std::vector<std::string>* warnings = nullptr);

}  // namespace shoal::track
