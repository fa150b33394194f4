#pragma once
/// Reading vector sources with OGR, shared by the coastline import and the expected-contact
/// areas: opening a dataset, choosing its layers (S-57 object classes by name), making a
/// feature's geometry linear, and bringing a layer's coordinates to WGS84 lon/lat (its CRS,
/// one the user names, or lon/lat assumed only when every coordinate is one). Internal.

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "util/gdal_support.hpp"

namespace shoal::coast::ogr {

/// Opens `path` as a vector dataset, read-only, GDAL kept quiet. Throws InputError for a
/// missing path or one OGR cannot read (with GDAL's reason). `said`, when given, receives
/// the failures GDAL reported while opening a dataset it did open (GdalFailures::said(); ""
/// for none): a GeoJSON file is parsed when opened, and a geometry it cannot read is then a
/// feature without one.
GDALDatasetUniquePtr open_vector(const std::string& path, std::string* said = nullptr);

/// Whether what GDAL said while opening a file (open_vector's `said`) is that its CRS could
/// not be read: a GeoJSON "crs" PROJ does not know, after which GDAL takes the layer as WGS84.
bool crs_unreadable(const std::string& said);

/// Whether `ds` is an S-57 chart (ENC).
bool is_s57(GDALDataset& ds);
/// Whether GDAL's S-57 driver claims `path` (it reads the file's first bytes only): a file it
/// does not claim is no chart, and need not be opened (opening a GeoJSON coast parses it whole).
bool may_be_s57(const std::string& path);
/// False when `head`, a file's first bytes, cannot be claimed by GDAL's S-57 driver (too short,
/// no ISO 8211 leader mark, no "DSID" field name): may_be_s57 then answers without GDAL.
bool s57_leader_possible(std::string_view head);
/// "A, B, C" (or "none"): the layer names of `ds`, for messages.
std::string layer_names(GDALDataset& ds);
/// The layers of `ds` named in `names`, in that order, those it has.
std::vector<OGRLayer*> layers_named(GDALDataset& ds, const std::vector<const char*>& names);

std::string upper(std::string s);

/// "In 'FILE' layer 'LAYER' feature FID": where a message's feature is.
std::string feature_where(const std::string& file, const std::string& layer, std::int64_t fid);

/// The feature's geometry with curves made linear (`owned` holds the linear copy), or null.
struct LinearGeometry {
    const OGRGeometry* geometry = nullptr;
    std::unique_ptr<OGRGeometry> owned;
};
LinearGeometry linear_geometry(const OGRFeature& feature);

/// The points of a curve as P{x, y}.
template <class P>
std::vector<P> points_of(const OGRSimpleCurve& c) {
    std::vector<P> pts(static_cast<std::size_t>(c.getNumPoints()));
    for (int i = 0; i < c.getNumPoints(); ++i) pts[static_cast<std::size_t>(i)] = {c.getX(i), c.getY(i)};
    return pts;
}

/// " (e.g. X, Y in feature FID)" when (x, y) is not a longitude within +-max_lon and a
/// latitude, else "".
std::string not_lonlat_note(double x, double y, std::int64_t fid, double max_lon);

/// How a layer's coordinates reach WGS84 lon/lat.
struct LayerCrs {
    std::string description;        ///< the CRS, for messages and the layer's stats
    detail::TransformPtr to_wgs84;  ///< null: they are WGS84 lon/lat already
};

/// What to do for a layer without a CRS.
struct NoCrsRule {
    std::string source_crs;   ///< the CRS to assume (--source-crs), "" = none
    std::string remedy;       ///< ends the error when the coordinates are not lon/lat: "; name its CRS ..."
    std::string assumed;      ///< the description when lon/lat is assumed
};

/// The CRS of `layer` of `file` and the transformation to WGS84. `first_not_lonlat(max_lon)`
/// names the first coordinate of the layer that is not lon/lat ("" when all are): a layer
/// without a CRS, or one GDAL calls WGS84 (every GeoJSON), must hold lon/lat. Throws
/// UsageError for a bad --source-crs, InputError for coordinates that are not what the CRS
/// says and for a CRS with no way to WGS84; a warning says when lon/lat was assumed.
LayerCrs layer_crs(OGRLayer& layer, const std::string& file, const NoCrsRule& no_crs,
                   const std::function<std::string(double max_lon)>& first_not_lonlat, std::vector<std::string>& warnings);

/// Transforms xs, ys in place; the index of the first vertex that failed (or is not finite),
/// or xs.size() when all went through.
std::size_t transform(OGRCoordinateTransformation& ct, std::vector<double>& xs, std::vector<double>& ys);

/// Drops consecutive repeated points.
template <class P>
void drop_repeats(std::vector<P>& pts) {
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
}

}  // namespace shoal::coast::ogr
