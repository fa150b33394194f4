#pragma once
/// The `.shoalgrid` file format: a built CoastGrid saved so later runs skip the import.
///
/// Layout (little-endian): magic "SHOALGRD", u32 format version, u32 byte-order mark
/// 0x01020304, u64 payload size, u64 XXH3-64 checksum of the payload, then the payload
/// (parameters, frame, source fingerprint and hazard parameters, then the grid's flat arrays
/// and the per-polyline table of what each bounds: kind, danger, structure, depth, and name
/// by index into a table of the distinct names; then the levels of charted depth: per coast
/// cell the reference winding where it changes, per cell the first level a land cell is land
/// at). Written to a temporary file in the same folder and renamed, so a reader never sees
/// half a file.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <shoal/grid/coast_grid.hpp>

namespace shoal::grid {

inline constexpr char grid_magic[8] = {'S', 'H', 'O', 'A', 'L', 'G', 'R', 'D'};
/// 2: hazard fields and per-polyline kinds (depth hazards); 3: every depth area and danger
/// kept with its depth, and the levels of charted depth (CoastGrid::for_depth); 4: structures
/// (kind structure, each polyline's structure kind and name, their counts in the source).
inline constexpr std::uint32_t grid_format_version = 4;

class GridFile {
public:
    /// Writes atomically (temporary file + rename). Throws InputError naming the path.
    static void save(const CoastGrid& grid, const std::string& path);
    /// Reads and verifies a grid file. Throws InputError with one clear line for a file that
    /// is missing, not a grid, from another format version, cut short or damaged.
    static CoastGrid load(const std::string& path);
    /// Parses a grid from bytes already in memory (`name` is used in messages).
    static CoastGrid parse(const std::vector<char>& bytes, const std::string& name);
    static CoastGrid parse(std::span<const char> bytes, const std::string& name);
    static std::vector<char> serialize(const CoastGrid& grid);
    /// The definition of the frame a grid file is in (`geo::LocalFrame::definition()`), read from
    /// its first bytes alone, or "" when they are not those of a grid of this format version
    /// (`load` says what is wrong). Nothing else is checked: for a program that decides before
    /// loading whether it can compute the frame.
    static std::string frame_definition(const std::string& path);
};

/// True when the file starts with the grid magic (it is a grid, perhaps a damaged one).
bool looks_like_grid(const std::string& path);

}  // namespace shoal::grid
