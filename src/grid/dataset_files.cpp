// grid::dataset_files: the files of a vector dataset, as GDAL lists them (grid_builder.hpp). A
// file of its own: the one part of fingerprinting a grid's sources that needs GDAL, which a
// program without GDAL could define otherwise (docs/performance.md, "What a check without GDAL needs").
#include <shoal/grid/grid_builder.hpp>

#include <gdal_priv.h>

#include "util/gdal_support.hpp"

namespace shoal::grid {

std::vector<std::string> dataset_files(const std::string& path) {
    detail::register_drivers();
    std::vector<std::string> files;
    detail::QuietErrors quiet;
    // A JSON dataset is its one file (GDAL's GetFileList says so too), and opening it parses
    // all of it (275 M instructions for a 1 MB GeoJSON coast): told by its driver alone.
    if (GDALDriverH driver = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr)) {
        const std::string name = GDALGetDriverShortName(driver);
        if (name == "GeoJSON" || name == "GeoJSONSeq" || name == "ESRIJSON" || name == "TopoJSON") {
            VSIStatBufL st;
            if (VSIStatExL(path.c_str(), &st, VSI_STAT_EXISTS_FLAG) == 0) files.push_back(path);
            return files;
        }
    }
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (ds) {
        if (char** list = ds->GetFileList()) {
            for (char** f = list; *f; ++f) files.emplace_back(*f);
            CSLDestroy(list);
        }
    }
    return files;
}

}  // namespace shoal::grid
