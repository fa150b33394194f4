#pragma once
/// Building a CoastGrid from coastline sources: import, local frame, cell size, clipping, and
/// the record of what it was built from (GridSource, with the fingerprint that keys the cache).

#include <cstdint>
#include <string>
#include <vector>

#include <shoal/coast/coastline.hpp>
#include <shoal/grid/coast_grid.hpp>

namespace shoal::grid {

/// The coastline sources behind a run's grid `g`: `coast` as given, or, when it is one grid
/// file, the sources that grid was built from that still exist (their S-57 berths, harbours
/// and shore constructions are read from them).
std::vector<std::string> coast_sources(const std::vector<std::string>& coast, const CoastGrid& g);

/// The files a vector dataset consists of (a Shapefile's .shp, .shx, .dbf, .prj ...), as GDAL's
/// GetFileList lists them; a JSON dataset (GeoJSON, GeoJSONSeq, ESRIJSON, TopoJSON) is its one
/// file, told without opening it (a plain *.geojson file without GDAL). The path itself when GDAL
/// lists none (it cannot open it, or it is not there).
std::vector<std::string> dataset_files(const std::string& path);

/// Fingerprint of coastline sources and the options that shape a grid: XXH3 over the bytes of
/// every file the sources consist of (as GDAL lists them) and the option values. Throws
/// InputError for a missing or unreadable source.
std::uint64_t fingerprint_sources(const std::vector<std::string>& paths, const coast::ImportOptions& options,
                                  const std::string& crs, double cell_m);

/// How to build a grid from coastline sources (and, for `load_or_build`, where to cache it).
struct BuildRequest {
    coast::ImportOptions import;
    std::string crs;        ///< --crs ("" = transverse Mercator centred on the data)
    double cell_m = 0;      ///< --cell (0 = use ship_length_m or the default)
    double ship_length_m = 0;
    std::string cache_dir;  ///< "" = $SHOAL_CACHE_DIR, else $XDG_CACHE_HOME/shoal, else ~/.cache/shoal
};

/// Builds a grid from coastline files: import, frame, cell size, clipping. Warnings (data
/// repairs, assumed CRS, frame scale error) go to `warnings`.
CoastGrid build_grid(const std::vector<std::string>& paths, const BuildRequest& request, std::vector<std::string>* warnings,
                     BuildStats* stats = nullptr, std::string* cell_note = nullptr);

}  // namespace shoal::grid
