#pragma once
/// Reading coastlines with OGR. Land polygons become their boundary rings as closed
/// polylines oriented so that land lies on the left; lines stay lines (land side unknown).
/// Supported: any OGR vector source (Shapefile, GeoJSON, GeoPackage, FlatGeobuf, S-57 ENC
/// cells: the layers of s57_default_layers by default).
///
/// Depth areas (S-57 DEPARE, DRGARE, or polygons with a `depth_field`) and dangers (UWTROC,
/// WRECKS, OBSTRN) are read too, every one of them, and kept exactly like land with their
/// charted depth (least depth DRVAL1 or the depth field; sounding VALSOU, or unknown); a point
/// danger becomes a small polygon around it. Which of them is a hazard is decided at check
/// time for each vessel's limiting depth (grid::CoastGrid::for_depth).
///
/// Structures (S-57 SLCONS shoreline constructions, PONTON pontoons, HULKES hulks, MORFAC
/// dolphins, bollards and piles) are hazards for every vessel, like land: a hull cannot pass
/// through a pier at any draught. Their areas are kept as rings; a structure drawn as a line
/// (a pier, a wharf face) or a point (a dolphin) has no area, and becomes the polygon around
/// it of structure_line_half_width_m or structure_point_radius_m. Each keeps its kind (from
/// the object class and CATSLC / CATMOR) and its name (OBJNAM).

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::coast {

/// What a polyline bounds: land, a depth area (shallow water for a vessel whose limiting depth
/// exceeds its charted depth), a danger, or a structure (a pier, wharf, pontoon, dolphin,
/// hulk: a hazard for every vessel, like land).
enum class HazardKind : std::uint8_t { land, shallow, danger, structure };
/// The kind of a danger: S-57 UWTROC (rock), WRECKS (wreck), OBSTRN (obstruction).
enum class DangerKind : std::uint8_t { none, rock, wreck, obstruction };
/// The kind of a structure, from its S-57 object class and category attribute: SLCONS by
/// CATSLC (1 breakwater ... 17 log ramp), PONTON, HULKES, MORFAC by CATMOR (1 dolphin ...
/// 7 mooring buoy). A class without (a known value of) its attribute: shoreline_construction
/// ("structure") for SLCONS, mooring_facility for MORFAC.
enum class StructureKind : std::uint8_t {
    none,
    breakwater, groyne, mole, pier, promenade_pier, wharf, training_wall, rip_rap, revetment, sea_wall,
    landing_steps, ramp, slipway, fender, solid_face_wharf, open_face_wharf, log_ramp,  // CATSLC 1-17
    shoreline_construction,
    pontoon,
    hulk,
    dolphin, deviation_dolphin, bollard, tie_up_wall, post_or_pile, chain_wire_cable, mooring_buoy,  // CATMOR 1-7
    mooring_facility,
};

const char* to_string(HazardKind k) noexcept;    ///< "land", "shallow", "danger", "structure"
const char* to_string(DangerKind k) noexcept;    ///< "", "rock", "wreck", "obstruction"
/// "" (none), the S-57 names in lower case ("pier", "open face wharf", "pontoon", "hulk",
/// "dolphin", "post or pile", "chain/wire/cable", "mooring buoy"), "structure" for
/// shoreline_construction, "mooring facility".
const char* to_string(StructureKind k) noexcept;

/// Whether a structure of that kind is a hazard: a hard body fixed where it is charted. Not a
/// mooring buoy (CATMOR 7: it floats and swings on its mooring, and vessels are made fast to
/// it on purpose) nor a chain, wire or cable (CATMOR 6: ground tackle, slack or on the bottom).
/// A MORFAC of unknown category is one (an unknown is taken as a hazard, like an unknown depth).
constexpr bool is_hazard(StructureKind k) noexcept {
    return k != StructureKind::none && k != StructureKind::mooring_buoy && k != StructureKind::chain_wire_cable;
}
/// Whether polylines of that kind are hazards for every vessel whatever its limiting depth:
/// land and structures (depth areas and dangers depend on the vessel's limiting depth).
constexpr bool for_every_vessel(HazardKind k) noexcept { return k == HazardKind::land || k == HazardKind::structure; }

/// What a polyline is, kept per polyline from import to the grid and the events.
struct Hazard {
    HazardKind kind = HazardKind::land;
    DangerKind danger = DangerKind::none;
    StructureKind structure = StructureKind::none;  ///< the structure's kind (kind structure), else none
    /// Charted depth in metres: a depth area's least depth (DRVAL1 or the depth field), a
    /// danger's sounding (VALSOU); NaN when unknown or for land and structures. Negative: dries.
    double depth_m = NAN;
    /// The feature's name: its OBJNAM (S-57), else its attribute called "name" (any case);
    /// "" when it has none ("Pier 25", "Blair Waterway").
    std::string name;
};

/// Half the width of the polygon a structure drawn as a line becomes (metres): a line pier is
/// narrower than the chart can draw (at 1:15,000 a 0.3 mm line is 4.5 m), and the narrowest
/// such piers and floats are about 2 m wide; a wider band would put a ship lying alongside a
/// wharf face, fenders and all, in contact with it before it touches.
inline constexpr double structure_line_half_width_m = 1.0;
/// Radius of the polygon a structure drawn as a point becomes (metres): a dolphin, a cluster
/// of 3-19 piles or a small concrete block, is 2-5 m across; a pile or bollard is smaller.
inline constexpr double structure_point_radius_m = 2.5;
/// Segments per quarter circle of those polygons (GEOSBuffer): their vertices lie at the
/// width / cos(pi / (4 * 8)) (0.5 % more), so the polygon holds every point within the width
/// of the line or point, and nothing 0.5 % farther.
inline constexpr int structure_quadrant_segments = 8;

/// The S-57 object classes read from a chart by default, in this order: land (LNDARE,
/// COALNE), depth areas (DEPARE, DRGARE), dangers (UWTROC, WRECKS, OBSTRN), structures
/// (SLCONS, PONTON, HULKES, MORFAC).
inline constexpr const char* s57_default_layers[] = {"LNDARE", "COALNE", "DEPARE", "DRGARE", "UWTROC", "WRECKS",
                                                     "OBSTRN", "SLCONS", "PONTON", "HULKES", "MORFAC"};

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
    std::uint64_t points = 0;         ///< point parts read (dangers, structures)
    std::uint64_t points_skipped = 0; ///< point geometries (not coastline) skipped
    std::uint64_t empty_skipped = 0;  ///< features with no or an empty/degenerate geometry
    std::uint64_t repaired = 0;       ///< invalid polygons repaired with GEOSMakeValid
    /// What the layer holds: land (also lines such as COALNE), depth areas, dangers or structures.
    HazardKind kind = HazardKind::land;
    std::string depth_field;          ///< the attribute holding the depth ("" for land and structure layers)
    std::uint64_t hazards = 0;        ///< depth areas / dangers kept (features)
    std::uint64_t unknown_depth = 0;  ///< of which with no depth in the data (a hazard for every vessel with a limit)
    std::uint64_t structures = 0;     ///< structures kept (features)
    std::uint64_t not_hazards = 0;    ///< structures that are no hazard (mooring buoys, chains: is_hazard) left out
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
