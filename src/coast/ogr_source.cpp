#include "coast/ogr_source.hpp"

#include <cpl_vsi.h>
#include <ogr_spatialref.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <shoal/util/error.hpp>

#include "util/input_file.hpp"

namespace shoal::coast::ogr {

namespace fs = std::filesystem;

namespace {

/// For a zip or gzip OGR could not open as it is: how to name what it holds (GDAL's paths).
std::string packed_hint(const std::string& path) {
    if (detail::is_virtual_path(path)) return "";
    auto ends = [&](std::string_view suffix) { return detail::lower_ends_with(path, suffix); };
    if (ends(".zip")) return "; a file inside a zip is read as /vsizip/" + path + "/NAME (e.g. the .shp of a Shapefile)";
    if (ends(".tar.gz") || ends(".tgz") || ends(".tar")) return "; a file inside a tar is read as /vsitar/" + path + "/NAME";
    if (ends(".000.gz")) return "; an S-57 cell is read unpacked (GDAL applies updates to a .000 only) or from a zip, /vsizip/ZIP/NAME.000";
    if (ends(".gz")) return "; a gzipped file is read as /vsigzip/" + path;
    return "";
}

}  // namespace

GDALDatasetUniquePtr open_vector(const std::string& path, std::string* said) {
    detail::register_drivers();
    if (!detail::input_exists(path)) throw InputError("'" + path + "': no such file or directory");
    detail::require_dataset_file(path, "a coastline, chart or areas file");
    detail::GdalFailures failures;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) {
        const std::string why = detail::QuietErrors::last();
        throw InputError("'" + path + "': not a vector dataset OGR can read" + (why.empty() ? "" : " (" + why + ")") + packed_hint(path));
    }
    if (said) *said = failures.said();
    return ds;
}

bool crs_unreadable(const std::string& said) {
    return said.find("PROJ") != std::string::npos || said.find("crs") != std::string::npos || said.find("CRS") != std::string::npos;
}

bool is_s57(GDALDataset& ds) { return std::string(ds.GetDriver()->GetDescription()) == "S57"; }

bool s57_leader_possible(std::string_view head) {
    // GDAL's S-57 driver reads the first 1,024 bytes (GDALOpenInfo, a C string ending at the
    // first NUL) and claims them only when there are at least 10, the ISO 8211 leader's byte 6
    // is 'L', and "DSID" stands in that string. Anything that fails these cannot be claimed.
    head = head.substr(0, 1024);
    if (head.size() < 10 || head[6] != 'L') return false;
    return head.substr(0, head.find('\0')).find("DSID") != std::string_view::npos;
}

bool may_be_s57(const std::string& path) {
    // A local regular file whose first bytes cannot be an S-57 chart's is told without GDAL
    // (which the run may then never load: util/lazy_libraries.hpp); the rest, GDAL tells.
    if (!detail::is_virtual_path(path)) {
        std::error_code ec;
        if (fs::is_regular_file(path, ec) && !s57_leader_possible(detail::read_head(path, 1024))) return false;
    }
    detail::register_drivers();
    detail::QuietErrors quiet;
    const char* const s57_only[] = {"S57", nullptr};
    return GDALIdentifyDriverEx(path.c_str(), GDAL_OF_VECTOR, s57_only, nullptr) != nullptr;
}

std::string layer_names(GDALDataset& ds) {
    std::string s;
    for (OGRLayer* l : ds.GetLayers()) s += (s.empty() ? "" : ", ") + std::string(l->GetName());
    return s.empty() ? "none" : s;
}

std::vector<OGRLayer*> layers_named(GDALDataset& ds, const std::vector<const char*>& names) {
    std::vector<OGRLayer*> out;
    for (const char* name : names)
        if (OGRLayer* l = ds.GetLayerByName(name)) out.push_back(l);
    return out;
}

std::string upper(std::string s) {
    for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

std::string feature_where(const std::string& file, const std::string& layer, std::int64_t fid) {
    return "In '" + file + "' layer '" + layer + "' feature " + std::to_string(fid);
}

LinearGeometry linear_geometry(const OGRFeature& feature) {
    LinearGeometry out;
    out.geometry = feature.GetGeometryRef();
    if (out.geometry && out.geometry->hasCurveGeometry()) {
        out.owned.reset(out.geometry->getLinearGeometry());
        out.geometry = out.owned.get();
    }
    return out;
}

std::string not_lonlat_note(double x, double y, std::int64_t fid, double max_lon) {
    if (std::fabs(x) <= max_lon && std::fabs(y) <= 90.0) return "";
    // %.10g, not %.3f: a coordinate of 1e120 in %.3f is 124 digits, and the note was cut short
    // before the feature it names.
    char buf[128];
    std::snprintf(buf, sizeof buf, " (e.g. %.10g, %.10g in feature %lld)", x, y, static_cast<long long>(fid));
    return buf;
}

LayerCrs layer_crs(OGRLayer& layer, const std::string& file, const NoCrsRule& no_crs,
                   const std::function<std::string(double max_lon)>& first_not_lonlat, std::vector<std::string>& warnings) {
    const std::string what = "layer '" + std::string(layer.GetName()) + "' in '" + file + "'";
    const OGRSpatialReference* layer_srs = layer.GetSpatialRef();
    OGRSpatialReference src;
    LayerCrs out;
    if (layer_srs) {
        src = *layer_srs;
        const char* name = src.GetName();
        out.description = name ? name : "unnamed CRS";
    } else if (!no_crs.source_crs.empty()) {
        if (src.SetFromUserInput(no_crs.source_crs.c_str()) != OGRERR_NONE)
            throw UsageError("ImportOptions::source_crs '" + no_crs.source_crs + "' is not a CRS GDAL understands");
        out.description = "none in file; ImportOptions::source_crs " + no_crs.source_crs;
    } else {
        // A Shapefile's .prj that GDAL could not read leaves it without a CRS, without a word
        // (the .shp named, or a layer of a folder of Shapefiles; on disk or in GDAL's paths).
        std::string shp;
        if (detail::lower_ends_with(file, ".shp")) shp = file;
        else if (std::string(layer.GetName()).find('/') == std::string::npos && detail::is_folder_input(file))
            shp = file + "/" + layer.GetName() + ".shp";
        for (const char* ext : {".prj", ".PRJ"}) {
            if (shp.empty()) break;
            const std::string prj = shp.substr(0, shp.size() - 4) + ext;
            VSIStatBufL st;
            if (VSIStatL(prj.c_str(), &st) == 0 && VSI_ISREG(st.st_mode) && st.st_size > 0)
                throw InputError(what + ": its " + fs::path(prj).filename().string() + " is not a CRS GDAL can read" + no_crs.remedy + ", or mend the .prj");
        }
        if (const std::string bad = first_not_lonlat(180.0); !bad.empty())
            throw InputError(what + " has no CRS and its coordinates are not longitude/latitude" + bad + no_crs.remedy);
        warnings.push_back(what + " has no CRS; assuming WGS84 longitude/latitude (every coordinate is a valid one)");
        out.description = no_crs.assumed;
        return out;
    }
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (src.IsGeographic() && src.IsSame(&wgs84)) {
        // GDAL reports WGS84 for every GeoJSON without a "crs" member (RFC 7946), even when
        // its coordinates are metres: those must not pass as longitude/latitude (0..360
        // longitudes are accepted).
        if (const std::string bad = first_not_lonlat(360.0); !bad.empty())
            throw InputError(what + " has the CRS " + out.description + " but its coordinates are not longitude/latitude" + bad +
                             "; give the file its real CRS (e.g. convert it with ogr2ogr -s_srs ... -t_srs EPSG:4326)");
        return out;
    }
    out.to_wgs84.reset(OGRCreateCoordinateTransformation(&src, &wgs84));
    if (!out.to_wgs84) throw InputError(what + ": no transformation from " + out.description + " to WGS84");
    return out;
}

std::size_t transform(OGRCoordinateTransformation& ct, std::vector<double>& xs, std::vector<double>& ys) {
    std::vector<int> ok(xs.size(), 0);
    ct.Transform(xs.size(), xs.data(), ys.data(), nullptr, ok.data());
    for (std::size_t i = 0; i < xs.size(); ++i)
        if (!ok[i] || !std::isfinite(xs[i]) || !std::isfinite(ys[i])) return i;
    return xs.size();
}

}  // namespace shoal::coast::ogr
