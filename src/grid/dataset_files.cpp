// grid::dataset_files: the files of a vector dataset, as GDAL lists them (grid_builder.hpp). A
// file of its own: the one part of fingerprinting a grid's sources that needs GDAL, but for a
// plain GeoJSON file, told without it (docs/performance.md, "GDAL, GEOS and PROJ loaded when a
// run needs them").
#include <shoal/grid/grid_builder.hpp>

#include <gdal_priv.h>

#include <filesystem>

#include "util/gdal_support.hpp"
#include "util/input_file.hpp"

namespace shoal::grid {

namespace {

/// A local regular file named *.geojson whose first character that is not blank is '{'. Of
/// GDAL 3.6's vector drivers, only the JSON ones (GeoJSON, GeoJSONSeq, ESRIJSON, TopoJSON) claim
/// or open such a file (the others want another name, a prefix, binary magic, XML or a folder),
/// and each lists it alone: GDAL's answer is the path, or none when it cannot read it, which
/// dataset_files gives as the path too. Told without GDAL, which a check may then never load
/// (util/lazy_libraries.hpp); grid_cache_test compares it with GDAL's list on every committed
/// GeoJSON and on files made to sit at its edges.
bool geojson_alone(const std::string& path) {
    if (detail::is_virtual_path(path) || !detail::lower_ends_with(path, ".geojson")) return false;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    const std::string head = detail::read_head(path, 4096);
    const std::size_t first = head.find_first_not_of(" \t\r\n");
    return first != std::string::npos && head[first] == '{';
}

}  // namespace

std::vector<std::string> dataset_files(const std::string& path) {
    if (geojson_alone(path)) return {path};
    detail::register_drivers();
    std::vector<std::string> files;
    detail::QuietErrors quiet;
    // A JSON dataset is its one file (GDAL's GetFileList says so too), and opening it parses
    // all of it (275 M instructions for a 1 MB GeoJSON coast): told by its driver alone.
    if (GDALDriverH driver = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr)) {
        const std::string name = GDALGetDriverShortName(driver);
        if (name == "GeoJSON" || name == "GeoJSONSeq" || name == "ESRIJSON" || name == "TopoJSON") {
            return {path};
        }
    }
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (ds) {
        if (char** list = ds->GetFileList()) {
            for (char** f = list; *f; ++f) files.emplace_back(*f);
            CSLDestroy(list);
        }
    }
    if (files.empty()) files.push_back(path);
    return files;
}

}  // namespace shoal::grid
