#pragma once
/// The `.shoalgrid` cache file: a built CoastGrid saved so later runs skip the import.
///
/// Layout (little-endian): magic "SHOALGRD", u32 format version, u32 byte-order mark
/// 0x01020304, u64 payload size, u64 XXH3-64 checksum of the payload, then the payload
/// (parameters, frame, source fingerprint and hazard parameters, then the grid's flat arrays
/// and the per-polyline table of what each bounds). Written to a
/// temporary file in the same folder and renamed, so a reader never sees half a file.

#include <cstdint>
#include <string>
#include <vector>

#include <shoal/coast/coastline.hpp>
#include <shoal/grid/coast_grid.hpp>

namespace shoal::grid {

inline constexpr char grid_magic[8] = {'S', 'H', 'O', 'A', 'L', 'G', 'R', 'D'};
inline constexpr std::uint32_t grid_format_version = 2;  // 2: hazard fields and per-polyline kinds (depth hazards)

class GridFile {
public:
    /// Writes atomically (temporary file + rename). Throws InputError naming the path.
    static void save(const CoastGrid& grid, const std::string& path);
    /// Reads and verifies a grid file. Throws InputError with one clear line for a file that
    /// is missing, not a grid, from another format version, cut short or damaged.
    static CoastGrid load(const std::string& path);
    /// Parses a grid from bytes already in memory (`name` is used in messages).
    static CoastGrid parse(const std::vector<char>& bytes, const std::string& name);
    static std::vector<char> serialize(const CoastGrid& grid);
};

/// True when the file starts with the grid magic (it is a grid, perhaps a damaged one).
bool looks_like_grid(const std::string& path);

/// The coastline sources behind a run's grid `g`: `coast` as given, or, when it is one grid
/// file, the sources that grid was built from that still exist (their S-57 berths, harbours
/// and shore constructions are read from them).
std::vector<std::string> coast_sources(const std::vector<std::string>& coast, const CoastGrid& g);

/// Fingerprint of coastline sources and the options that shape a grid: XXH3 over the bytes of
/// every file the sources consist of (as GDAL lists them) and the option values. Throws
/// InputError for a missing or unreadable source.
std::uint64_t fingerprint_sources(const std::vector<std::string>& paths, const coast::ImportOptions& options,
                                  const std::string& crs, double cell_m);

/// Options for `load_or_build`: how to build when a coastline (not a grid) is given.
struct BuildRequest {
    coast::ImportOptions import;
    std::string crs;        ///< --crs ("" = transverse Mercator centred on the data)
    double cell_m = 0;      ///< --cell (0 = use ship_length_m or the default)
    double ship_length_m = 0;
    std::string cache_dir;  ///< "" = $SHOAL_CACHE_DIR, else $XDG_CACHE_HOME/shoal, else ~/.cache/shoal
};

/// What `load_or_build` did, for messages.
struct LoadReport {
    std::string how;  ///< "loaded grid", "reused cache", "built and cached", "built (cache not writable: ...)"
    std::string cache_path;
    std::vector<std::string> warnings;
    BuildStats build;
    double seconds = 0;
};

/// Builds a grid from coastline files: import, frame, cell size, clipping. Warnings (data
/// repairs, assumed CRS, frame scale error) go to `warnings`.
CoastGrid build_grid(const std::vector<std::string>& paths, const BuildRequest& request, std::vector<std::string>* warnings,
                     BuildStats* stats = nullptr, std::string* cell_note = nullptr);

/// `--coast COAST_OR_GRID`: a grid file is loaded; coastline sources are built into a grid
/// that is cached and reused while the sources and parameters are unchanged.
CoastGrid load_or_build(const std::vector<std::string>& paths, const BuildRequest& request, LoadReport* report = nullptr);

}  // namespace shoal::grid
