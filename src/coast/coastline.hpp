#pragma once
/// Reading coastlines with OGR. Land polygons become their boundary rings as closed
/// polylines oriented so that land lies on the left; lines stay lines (land side unknown).
/// Supported: any OGR vector source (Shapefile, GeoJSON, GeoPackage, FlatGeobuf, S-57 ENC
/// cells: layers LNDARE and COALNE by default).

#include <cstdint>
#include <string>
#include <vector>

#include "geo/point.hpp"

namespace shoal::coast {

/// One boundary polyline in WGS84 lon/lat. Rings from polygons are closed (last == first).
struct Polyline {
    std::vector<geo::LonLat> points;
    bool land_left = false;   ///< true when land lies to the left of the direction of travel
    std::uint32_t layer = 0;  ///< index into Coastline::layers
    std::int64_t fid = -1;    ///< OGR feature id in that layer
};

/// What one layer contributed, for `shoal import` and for tests.
struct LayerStats {
    std::string file;
    std::string layer;
    std::string crs;                  ///< the layer's CRS name, or how it was assumed
    std::uint64_t features = 0;       ///< features read
    std::uint64_t polygons = 0;       ///< polygon parts read (a MultiPolygon counts each part)
    std::uint64_t lines = 0;          ///< line parts read
    std::uint64_t vertices = 0;       ///< vertices of the polygons and lines as read
    std::uint64_t points_skipped = 0; ///< point geometries (not coastline) skipped
    std::uint64_t empty_skipped = 0;  ///< features with no or an empty/degenerate geometry
    std::uint64_t repaired = 0;       ///< invalid polygons repaired with GEOSMakeValid
};

struct ImportOptions {
    /// Layer names to read (matched exactly, then case-insensitively); empty: the default set.
    std::vector<std::string> layers;
    /// CRS to assume for sources that carry none (otherwise lon/lat is assumed only when
    /// every coordinate is a valid longitude/latitude).
    std::string source_crs;
};

struct Coastline {
    std::vector<Polyline> polylines;
    std::vector<LayerStats> layers;
    std::vector<std::string> warnings;  ///< messages for the user (repairs, assumptions)
    std::vector<std::string> files;     ///< every file the sources consist of (for fingerprints)
    geo::LonLat min{INFINITY, INFINITY};
    geo::LonLat max{-INFINITY, -INFINITY};

    std::uint64_t vertex_count() const noexcept;
    bool has_land_side() const noexcept;
};

/// Reads and merges coastlines from `paths`. Throws InputError with one clear line naming
/// the file and layer for: a missing file, one OGR cannot read, a layer that is not there,
/// an empty layer, no CRS with coordinates that are not lon/lat, no usable geometry.
Coastline import_coastline(const std::vector<std::string>& paths, const ImportOptions& options = {});

}  // namespace shoal::coast

namespace shoal::geo { class LocalFrame; }

namespace shoal::coast {

/// A polyline of the coastline in local metres.
struct LocalPolyline {
    std::vector<geo::XY> points;
    bool land_left = false;
};

/// Projects every polyline into `frame`. Throws InputError naming the feature of a point
/// the frame cannot represent.
std::vector<LocalPolyline> project(const Coastline& coast, const geo::LocalFrame& frame);

}  // namespace shoal::coast
