#pragma once
/// Areas where contact is expected: harbours, berths, anchorages and the user's own areas,
/// and shoreline constructions (quays, piers, breakwaters). A hull touching land inside such
/// an area is a ship alongside, not a grounding; the audit asks `find` before it calls a
/// contact a grounding.
///
/// Sources: any OGR vector files the user names (every layer; role *expected*, kind "area",
/// or taken from the layer name when it is an S-57 object class), and the S-57 charts among
/// the coastline sources (layers BERTHS, HRBARE, ACHARE as *expected*, SLCONS, PONTON,
/// MORFAC and HULKES as *structure*, each when present; mooring buoys and chains, which are
/// no structure (coast::is_hazard), left out). Polygons are kept as they are (an invalid one is
/// repaired with GEOSMakeValid); lines and points, as S-57 berths and shoreline
/// constructions often are, become the area within the tolerance of them.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::geo { class LocalFrame; }

namespace shoal::coast {

/// *expected*: a berth, harbour, anchorage or user area, where touching land is normal.
/// *structure*: an S-57 shoreline construction (SLCONS: quay, pier, breakwater, ...), pontoon
/// (PONTON), mooring facility (MORFAC: dolphin, bollard, pile, ...) or hulk (HULKES).
enum class AreaRole : std::uint8_t { expected, structure };

const char* to_string(AreaRole r) noexcept;  ///< "expected", "structure"

/// One area, as read from one feature.
struct ExpectedArea {
    AreaRole role = AreaRole::expected;
    /// "berth" (S-57 BERTHS), "harbour" (HRBARE), "anchorage" (ACHARE), "area" (any other
    /// layer of a user file); for structures coast::to_string(StructureKind): the name of the
    /// S-57 CATSLC value ("breakwater", "groyne", "mole", "pier", "promenade pier", "wharf",
    /// "training wall", "rip rap", "revetment", "sea wall", "landing steps", "ramp",
    /// "slipway", "fender", "solid face wharf", "open face wharf", "log ramp", or "structure"
    /// when it has none), "pontoon", "hulk", or of the CATMOR value ("dolphin", "deviation
    /// dolphin", "bollard", "tie-up wall", "post or pile", or "mooring facility" when it has
    /// none).
    std::string kind;
    /// The feature's OBJNAM, else its attribute called "name" (any case); "" when neither is set.
    std::string name;
    std::string file;
    std::string layer;
    std::int64_t fid = -1;  ///< OGR feature id in that layer
};

/// Number of segments a buffer uses per quarter circle. A line or point becomes the polygon
/// circumscribed about its tolerance: every point within tolerance_m of it is inside, and
/// nothing farther than tolerance_m / cos(pi / (4 * expected_area_quadrant_segments)) is.
inline constexpr int expected_area_quadrant_segments = 8;

/// The areas of a run, in local metres, with a spatial index for point queries. Movable (a
/// moved-from object is empty), not copyable; the pointers `find` and `areas` give stay valid
/// while the areas live, also when they are moved to another object.
class ExpectedAreas {
public:
    /// No areas: `find` always answers nullptr.
    ExpectedAreas();
    ExpectedAreas(ExpectedAreas&&) noexcept;
    ExpectedAreas& operator=(ExpectedAreas&&) noexcept;
    ExpectedAreas(const ExpectedAreas&) = delete;
    ExpectedAreas& operator=(const ExpectedAreas&) = delete;
    ~ExpectedAreas();

    /// Reads the areas and projects them into `frame`.
    ///
    /// `user_files`: OGR vector sources; every layer is read (an S-57 chart given here: its
    /// layers BERTHS, HRBARE, ACHARE, SLCONS, PONTON, MORFAC and HULKES). A layer named
    /// BERTHS, HRBARE or ACHARE gives that kind, SLCONS, PONTON, MORFAC and HULKES
    /// structures, any other layer kind "area".
    /// `charts`: the coastline sources; those that are S-57 (GDAL driver "S57") give their
    /// BERTHS, HRBARE and ACHARE (expected) and SLCONS, PONTON, MORFAC, HULKES (structure)
    /// when present; the others, and absent layers, give nothing.
    ///
    /// Lines and points become buffers of `tolerance_m` metres (> 0), see
    /// expected_area_quadrant_segments. Coordinates in any CRS are transformed to WGS84 and
    /// then into `frame`; a layer without a CRS whose coordinates are all longitudes and
    /// latitudes is taken as WGS84 (with a warning). Repairs, assumptions and features
    /// without usable geometry are reported in `warnings` (when not null).
    ///
    /// Throws InputError naming the file (and layer, feature) for: a missing file, one OGR
    /// cannot read, an S-57 user file with none of the seven layers, a user layer with no
    /// polygon, line or point at all, no CRS with coordinates that are not lon/lat, a vertex
    /// that cannot be transformed or projected. UsageError when tolerance_m is not > 0 and at
    /// most max_tolerance_m.
    /// The largest tolerance (1 km): a berth's line grown by more is no berth (and by 1e300 m
    /// GEOS cannot buffer it).
    static constexpr double max_tolerance_m = 1000.0;

    static ExpectedAreas load(const std::vector<std::string>& user_files, const std::vector<std::string>& charts,
                              const geo::LocalFrame& frame, double tolerance_m, std::vector<std::string>* warnings);

    /// The first area (in the order read: user files, then charts; layers and features in
    /// file order) of `role` that contains the local point `p`, its boundary included; nullptr
    /// when none does. Safe to call from several threads at once (the GEOS work is serialised).
    const ExpectedArea* find(geo::XY p, AreaRole role) const;

    /// Every area read, in the order `find` tries them.
    const std::vector<ExpectedArea>& areas() const noexcept;
    std::size_t size() const noexcept;
    bool empty() const noexcept { return size() == 0; }
    std::size_t count(AreaRole role) const noexcept;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;  // null when empty
};

}  // namespace shoal::coast
