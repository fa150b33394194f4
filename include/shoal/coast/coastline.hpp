#pragma once
/// Reading coastlines with OGR. Land polygons become their boundary rings as closed
/// polylines oriented so that land lies on the left; lines stay lines (land side unknown).
/// Supported: any OGR vector source (Shapefile, GeoJSON, GeoPackage, FlatGeobuf, S-57 ENC
/// cells: layers LNDARE and COALNE by default).
///
/// Depth areas (S-57 DEPARE, DRGARE, or polygons with a `depth_field`) and dangers (UWTROC,
/// WRECKS, OBSTRN) are read too, every one of them, and kept exactly like land with their
/// charted depth (least depth DRVAL1 or the depth field; sounding VALSOU, or unknown); a point
/// danger becomes a small polygon around it. Which of them is a hazard is decided at check
/// time for each vessel's limiting depth (grid::CoastGrid::for_depth).

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::coast {

/// What a polyline bounds: land, a depth area (shallow water for a vessel whose limiting depth
/// exceeds its charted depth), or a danger.
enum class HazardKind : std::uint8_t { land, shallow, danger };
/// The kind of a danger: S-57 UWTROC (rock), WRECKS (wreck), OBSTRN (obstruction).
enum class DangerKind : std::uint8_t { none, rock, wreck, obstruction };

const char* to_string(HazardKind k) noexcept;    ///< "land", "shallow", "danger"
const char* to_string(DangerKind k) noexcept;    ///< "", "rock", "wreck", "obstruction"

/// What a polyline is, kept per polyline from import to the grid and the events.
struct Hazard {
    HazardKind kind = HazardKind::land;
    DangerKind danger = DangerKind::none;
    /// Charted depth in metres: a depth area's least depth (DRVAL1 or the depth field), a
    /// danger's sounding (VALSOU); NaN when unknown or for land. Negative: dries.
    double depth_m = NAN;
};

/// One boundary polyline in WGS84 lon/lat. Rings from polygons are closed (last == first).
/// The "land" side of a hazard polygon (shallow area, danger) is its inside: it lies on the
/// left like land, and `land_left` is true for it too.
struct Polyline {
    std::vector<geo::LonLat> points;
    bool land_left = false;   ///< true when land (or the hazard) lies to the left of the direction of travel
    std::uint32_t layer = 0;  ///< index into Coastline::layers
    std::int64_t fid = -1;    ///< OGR feature id in that layer
    Hazard hazard{};          ///< what it bounds
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
    /// What the layer holds: land (also lines such as COALNE), depth areas or dangers.
    HazardKind kind = HazardKind::land;
    std::string depth_field;          ///< the attribute holding the depth ("" for land layers)
    std::uint64_t hazards = 0;        ///< depth areas / dangers kept (features)
    std::uint64_t unknown_depth = 0;  ///< of which with no depth in the data (a hazard for every vessel with a limit)
};

struct ImportOptions {
    /// Layer names to read (matched exactly, then case-insensitively); empty: the default set.
    std::vector<std::string> layers;
    /// CRS to assume for sources that carry none (otherwise lon/lat is assumed only when
    /// every coordinate is a valid longitude/latitude).
    std::string source_crs;
    /// The grid's default limiting depth in metres (`shoal import --hazard-depth`), kept in
    /// the grid (GridSource::limiting_depth_m) for checks that give no depth of their own
    /// (a Detector made without one, the C API's shoal_detector_new). It does not change what
    /// is read: every depth area and danger is kept with its depth.
    std::optional<double> limiting_depth_m;
    /// Radius in metres of the polygon a point danger becomes (a 16-gon around the circle),
    /// in (0, max_danger_radius_m].
    double danger_radius_m = 10.0;
    /// The largest danger radius (10 km): a point danger is a rock or a wreck, and a circle of
    /// 1e300 m cannot be projected (a usage error, not the chart's fault).
    static constexpr double max_danger_radius_m = 10'000.0;
    /// For sources other than S-57 layers: the attribute holding a polygon's least depth. A
    /// layer with this field holds depth areas; layers without it hold land.
    std::string depth_field;
};

/// The limiting depth for a ship: `hazard_depth_m` when given, else its draught plus the
/// under-keel clearance `ukc_m` when it has a draught (> 0), else none (land only).
std::optional<double> limiting_depth(std::optional<double> hazard_depth_m, double draught_m, double ukc_m) noexcept;

/// Sides of the polygon a point danger becomes. It is circumscribed about the circle of the
/// danger radius r, so the circle lies wholly inside it: vertex k (k = 0..15, counter-
/// clockwise) lies r / cos(pi / 16) metres from the point, at angle 2 pi k / 16 from east,
/// turned into degrees with the metres per degree at the point's latitude
/// (geo::metres_per_degree).
inline constexpr int danger_polygon_sides = 16;

struct Coastline {
    std::vector<Polyline> polylines;
    std::vector<LayerStats> layers;
    std::vector<std::string> warnings;  ///< messages for the user (repairs, assumptions)
    std::vector<std::string> files;     ///< every file the sources consist of (for fingerprints)
    geo::LonLat min{INFINITY, INFINITY};
    geo::LonLat max{-INFINITY, -INFINITY};

    std::uint64_t vertex_count() const noexcept;
    bool has_land_side() const noexcept;
    /// Polylines of that kind.
    std::uint64_t count(HazardKind kind) const noexcept;
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
    Hazard hazard{};
};

/// Projects every polyline into `frame`. Throws InputError naming the feature of a point
/// the frame cannot represent.
std::vector<LocalPolyline> project(const Coastline& coast, const geo::LocalFrame& frame);

}  // namespace shoal::coast
