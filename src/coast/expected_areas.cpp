#include <shoal/coast/expected_areas.hpp>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>

#include "coast/ogr_source.hpp"
#include "coast/s57_structure.hpp"
#include "geo/geos_context.hpp"
#include "util/input_file.hpp"
#include "util/parse_util.hpp"
#include <shoal/geo/local_frame.hpp>
#include <shoal/util/error.hpp>

namespace shoal::coast {

namespace fs = std::filesystem;
using geo::GeomPtr;
using geo::GeosContext;
using geo::XY;

const char* to_string(AreaRole r) noexcept {
    switch (r) {
    case AreaRole::expected: return "expected";
    case AreaRole::structure: return "structure";
    }
    return "?";
}

namespace {

using detail::QuietErrors;
using detail::register_drivers;
using geo::PreparedDeleter;
using geo::PreparedPtr;
using geo::TreeDeleter;
using geo::TreePtr;
using ogr::upper;

/// The S-57 object classes read, in the order a chart's layers are read.
constexpr const char* s57_area_layers[] = {"BERTHS", "HRBARE", "ACHARE", "SLCONS", "PONTON", "MORFAC", "HULKES"};
constexpr const char* s57_area_layer_list = "BERTHS, HRBARE, ACHARE, SLCONS, PONTON, MORFAC, HULKES";

/// What a layer holds, from its name: an S-57 object class, or (user files only) any area.
struct LayerRole {
    AreaRole role = AreaRole::expected;
    std::string kind = "area";  // for structures: taken per feature (s57::structure_kind)
};

std::optional<LayerRole> s57_role(const std::string& layer_name) {
    const std::string name = upper(layer_name);
    if (name == "BERTHS") return LayerRole{AreaRole::expected, "berth"};
    if (name == "HRBARE") return LayerRole{AreaRole::expected, "harbour"};
    if (name == "ACHARE") return LayerRole{AreaRole::expected, "anchorage"};
    if (s57::is_structure_class(name)) return LayerRole{AreaRole::structure, "structure"};
    return std::nullopt;
}

/// One feature's geometry as read: in source coordinates, then (after to_local) in local
/// metres. Polygons are lists of rings (first the shell); lines and points get buffered.
struct RawFeature {
    ExpectedArea area;
    std::vector<std::vector<std::vector<XY>>> polygons;
    std::vector<std::vector<XY>> lines;
    std::vector<XY> points;

    bool empty() const noexcept { return polygons.empty() && lines.empty() && points.empty(); }
    template <class F> void for_each_sequence(F&& f) {
        for (auto& poly : polygons)
            for (auto& ring : poly) f(ring);
        for (auto& line : lines) f(line);
        f(points);
    }
};

/// A finished area: the feature it came from and its polygonal geometry in local metres.
struct Built {
    ExpectedArea area;
    GeomPtr geom;
};

/// Reads one layer into areas. `user` layers must hold something usable.
class LayerReader {
public:
    /// `open_said`: what GDAL reported as failures while opening the file (ogr::open_vector).
    LayerReader(std::string file, OGRLayer& layer, LayerRole role, bool user, const geo::LocalFrame& frame,
                double tolerance_m, const GeosContext& geos, std::vector<std::string>& warnings, std::string open_said = {})
        : m_file(std::move(file)), m_layer(layer), m_role(std::move(role)), m_user(user), m_frame(frame),
          m_tolerance_m(tolerance_m), m_geos(geos), m_warnings(warnings), m_open_said(std::move(open_said)) {}

    std::vector<Built> read() {
        const s57::StructureFields fields = s57::structure_fields(layer_name(), *m_layer.GetLayerDefn());
        std::vector<RawFeature> raws;
        std::uint64_t features = 0, unusable = 0, not_structures = 0;
        m_layer.ResetReading();
        detail::GdalFailures failures;
        for (auto& feature : m_layer) {
            ++features;
            RawFeature raw;
            raw.area.role = m_role.role;
            raw.area.kind = m_role.kind;
            if (m_role.role == AreaRole::structure) {
                const StructureKind kind = s57::structure_kind(fields, *feature);
                // A mooring buoy or a chain is no structure (coast::is_hazard); SLCONS of an
                // unknown category stays "structure".
                if (!is_hazard(kind)) {
                    ++not_structures;
                    continue;
                }
                raw.area.kind = to_string(kind);
            }
            raw.area.name = s57::feature_name(fields, *feature);
            raw.area.file = m_file;
            raw.area.layer = m_layer.GetName();
            raw.area.fid = feature->GetFID();
            const ogr::LinearGeometry linear = ogr::linear_geometry(*feature);
            const OGRGeometry* g = linear.geometry;
            if (g && !g->IsEmpty()) collect(*g, raw);
            if (raw.empty()) {
                ++unusable;
                continue;
            }
            raws.push_back(std::move(raw));
        }
        // A user's areas file OGR could not read whole is refused, as a coastline is: a berth
        // left out would make a contact there a grounding (a Shapefile cut short; a GeoJSON crs
        // GDAL cannot find, taken as WGS84; a geometry with text for coordinates).
        if (m_user) {
            const std::string what = "layer '" + layer_name() + "' in '" + m_file + "'";
            if (ogr::crs_unreadable(m_open_said))
                throw InputError(what + ": its CRS is not one GDAL can read (" + m_open_said + "); give the file a CRS GDAL knows");
            if (failures.count() > 0 || (!m_open_said.empty() && unusable > 0))
                throw InputError(what + ": OGR could not read all of it (" + (failures.count() > 0 ? failures.said() : m_open_said) +
                                 "): the file is damaged or cut short, and an area left out would make a contact there a grounding");
        }
        const auto nothing_usable = [&](const std::string& why) {
            return InputError("layer '" + layer_name() + "' in '" + m_file + "' has no polygon, line or point to use as an area" + why);
        };
        if (raws.empty()) {
            if (m_user && (features == 0 || unusable > 0))
                throw nothing_usable(features == 0 ? " (it has no features)" : " (" + std::to_string(features) + " features without one)");
            return {};
        }
        if (unusable > 0)
            m_warnings.push_back("layer '" + layer_name() + "' in '" + m_file + "': " + std::to_string(unusable) +
                                 " feature(s) without a polygon, line or point skipped");
        to_local(raws);
        std::vector<Built> out;
        for (auto& raw : raws)
            if (GeomPtr g = build(raw)) out.push_back(Built{std::move(raw.area), std::move(g)});
        if (out.empty() && m_user) throw nothing_usable(" (only degenerate ones)");
        return out;
    }

private:
    std::string layer_name() const { return m_layer.GetName(); }

    std::string where(std::int64_t fid) const { return ogr::feature_where(m_file, layer_name(), fid); }

    static std::vector<XY> points_of(const OGRSimpleCurve& c) { return ogr::points_of<XY>(c); }

    void collect(const OGRGeometry& g, RawFeature& raw) {
        if (g.IsEmpty()) return;
        switch (wkbFlatten(g.getGeometryType())) {
        case wkbPolygon: {
            auto& rings = raw.polygons.emplace_back();
            for (const OGRLinearRing* ring : *g.toPolygon()) rings.push_back(points_of(*ring));
            return;
        }
        case wkbLineString:
        case wkbLinearRing:
            raw.lines.push_back(points_of(*g.toSimpleCurve()));
            return;
        case wkbPoint:
            raw.points.push_back({g.toPoint()->getX(), g.toPoint()->getY()});
            return;
        case wkbMultiPoint:
        case wkbMultiPolygon:
        case wkbMultiLineString:
        case wkbGeometryCollection:
            for (const OGRGeometry* sub : *g.toGeometryCollection()) collect(*sub, raw);
            return;
        default:
            m_warnings.push_back(where(raw.area.fid) + ": geometry type " + OGRGeometryTypeToName(g.getGeometryType()) +
                                 " cannot be an area; skipped");
        }
    }

    /// "" when every coordinate is a longitude within +-max_lon and a latitude, else
    /// " (e.g. X, Y in feature N)" naming the first that is not.
    static std::string first_not_lonlat(std::vector<RawFeature>& raws, double max_lon) {
        std::string bad;
        for (auto& raw : raws) {
            raw.for_each_sequence([&](const std::vector<XY>& seq) {
                for (const XY& p : seq)
                    if (bad.empty()) bad = ogr::not_lonlat_note(p.x, p.y, raw.area.fid, max_lon);
            });
            if (!bad.empty()) break;
        }
        return bad;
    }

    /// Transforms every coordinate from the layer's CRS to WGS84 lon/lat, then into the frame.
    void to_local(std::vector<RawFeature>& raws) {
        const ogr::LayerCrs crs =
            ogr::layer_crs(m_layer, m_file, {"", "; give the file its CRS (e.g. with ogr2ogr -a_srs EPSG:...)", "WGS84 (assumed)"},
                           [&](double max_lon) { return first_not_lonlat(raws, max_lon); }, m_warnings);
        const std::string& description = crs.description;
        OGRCoordinateTransformation* ct = crs.to_wgs84.get();
        std::vector<double> xs, ys;
        for (auto& raw : raws) {
            raw.for_each_sequence([&](std::vector<XY>& seq) {
                if (seq.empty()) return;
                xs.resize(seq.size());
                ys.resize(seq.size());
                for (std::size_t i = 0; i < seq.size(); ++i) { xs[i] = seq[i].x; ys[i] = seq[i].y; }
                if (ct && ogr::transform(*ct, xs, ys) < seq.size())
                    throw InputError(where(raw.area.fid) + ": a vertex cannot be transformed to WGS84 from " + description);
                const std::vector<double> lon = xs, lat = ys;
                std::size_t bad = 0;
                if (!m_frame.forward(xs, ys, &bad)) {
                    char buf[96];
                    std::snprintf(buf, sizeof buf, " (lon %.6f, lat %.6f)", lon[bad], lat[bad]);
                    throw InputError(where(raw.area.fid) + ": a vertex" + buf + " cannot be projected into the local frame (" +
                                     m_frame.description() + ")");
                }
                for (std::size_t i = 0; i < seq.size(); ++i) seq[i] = {xs[i], ys[i]};
            });
        }
    }

    static void drop_repeats(std::vector<XY>& pts) { ogr::drop_repeats(pts); }

    GeomPtr collection(int type, std::vector<GeomPtr> parts) const {
        std::vector<GEOSGeometry*> raw;
        for (auto& p : parts) raw.push_back(p.get());
        GEOSGeometry* c = GEOSGeom_createCollection_r(m_geos, type, raw.data(), static_cast<unsigned>(raw.size()));
        if (c)
            for (auto& p : parts) static_cast<void>(p.release());  // now owned by the collection
        return geo::own(m_geos, c, "creating a collection");
    }

    /// The polygons of a feature, valid (repaired when not), or null when none is usable.
    GeomPtr build_polygons(RawFeature& raw) {
        std::vector<GeomPtr> polys;
        for (auto& rings : raw.polygons) {
            std::vector<std::vector<XY>> kept;
            for (auto& ring : rings) {
                drop_repeats(ring);
                if (!ring.empty() && !(ring.front() == ring.back())) ring.push_back(ring.front());
                if (ring.size() < 4) {
                    if (kept.empty()) break;  // degenerate shell: nothing of this polygon is usable
                    continue;                 // a degenerate hole adds nothing
                }
                kept.push_back(std::move(ring));
            }
            if (kept.empty()) {
                m_warnings.push_back(where(raw.area.fid) + ": polygon with fewer than 3 distinct points; skipped");
                continue;
            }
            polys.push_back(geo::make_polygon(m_geos, kept));
        }
        if (polys.empty()) return nullptr;
        GeomPtr g = polys.size() == 1 ? std::move(polys[0]) : collection(GEOS_MULTIPOLYGON, std::move(polys));
        if (GEOSisValid_r(m_geos, g.get()) == 1) return g;
        char* reason = GEOSisValidReason_r(m_geos, g.get());
        const std::string why = reason ? reason : "invalid";
        GEOSFree_r(m_geos, reason);
        GeomPtr fixed = geo::own(m_geos, GEOSMakeValid_r(m_geos, g.get()), "repairing a polygon");
        // GEOSMakeValid may return a collection with the collapsed parts as lines or points.
        std::vector<std::vector<std::vector<XY>>> valid;
        geo::collect_polygons(m_geos, fixed.get(), valid);
        polys.clear();
        for (const auto& rings : valid) polys.push_back(geo::make_polygon(m_geos, rings));
        if (polys.empty()) {
            m_warnings.push_back(where(raw.area.fid) + ": invalid polygon (" + why +
                                 ") has no area left after GEOSMakeValid; skipped");
            return nullptr;
        }
        m_warnings.push_back(where(raw.area.fid) + ": invalid polygon (" + why + ") repaired with GEOSMakeValid");
        return polys.size() == 1 ? std::move(polys[0]) : collection(GEOS_MULTIPOLYGON, std::move(polys));
    }

    /// The area within the tolerance of the feature's lines and points, or null when none.
    GeomPtr build_buffer(RawFeature& raw) {
        std::vector<GeomPtr> parts;
        auto add_point = [&](XY p) {
            parts.push_back(geo::own(m_geos, GEOSGeom_createPointFromXY_r(m_geos, p.x, p.y), "creating a point"));
        };
        for (auto& line : raw.lines) {
            drop_repeats(line);
            if (line.size() >= 2) parts.push_back(geo::make_linestring(m_geos, line.data(), line.size()));
            else if (line.size() == 1) add_point(line[0]);
        }
        for (const XY& p : raw.points) add_point(p);
        if (parts.empty()) return nullptr;
        GeomPtr linework = parts.size() == 1 ? std::move(parts[0]) : collection(GEOS_GEOMETRYCOLLECTION, std::move(parts));
        constexpr int q = expected_area_quadrant_segments;
        const double radius = m_tolerance_m / std::cos(std::numbers::pi / (4 * q));
        return geo::own(m_geos, GEOSBuffer_r(m_geos, linework.get(), radius, q), "buffering a line or point");
    }

    GeomPtr build(RawFeature& raw) {
        GeomPtr polys = build_polygons(raw);
        GeomPtr buffer = build_buffer(raw);
        GeomPtr g;
        if (polys && buffer) g = geo::own(m_geos, GEOSUnion_r(m_geos, polys.get(), buffer.get()), "joining an area's parts");
        else g = polys ? std::move(polys) : std::move(buffer);
        if (g && GEOSisEmpty_r(m_geos, g.get()) == 1) g.reset();
        return g;
    }

    std::string m_file;
    OGRLayer& m_layer;
    LayerRole m_role;
    bool m_user;
    const geo::LocalFrame& m_frame;
    double m_tolerance_m;
    const GeosContext& m_geos;
    std::vector<std::string>& m_warnings;
    std::string m_open_said;
};

/// The same file, as far as the file system can tell (for skipping a chart also given as a user file).
std::string file_key(const std::string& path) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec);
    return ec ? path : p.string();
}

}  // namespace

struct ExpectedAreas::Impl {
    GeosContext geos;                      // destroyed last: everything below belongs to it
    mutable std::mutex mutex;              // serialises the GEOS work of find()
    std::vector<ExpectedArea> areas;
    std::vector<GeomPtr> geoms;            // areas[i]'s polygonal geometry in local metres
    std::vector<PreparedPtr> prepared;     // prepared views of geoms[i]
    TreePtr trees[2];                      // per role: items are &areas[i]
    std::size_t counts[2] = {0, 0};

    /// Prepares every geometry and indexes it; areas and geoms are final from here on.
    void index() {
        for (auto& t : trees) t = TreePtr(GEOSSTRtree_create_r(geos, 10), TreeDeleter{geos.get()});
        for (std::size_t i = 0; i < areas.size(); ++i) {
            const GEOSPreparedGeometry* p = GEOSPrepare_r(geos, geoms[i].get());
            if (!p) throw LibraryError("preparing an area failed in GEOS: " + geos.last_message());
            prepared.emplace_back(p, PreparedDeleter{geos.get()});
            const auto role = static_cast<std::size_t>(areas[i].role);
            GEOSSTRtree_insert_r(geos, trees[role].get(), geoms[i].get(), &areas[i]);
            ++counts[role];
        }
    }
};

ExpectedAreas::ExpectedAreas() = default;
ExpectedAreas::ExpectedAreas(ExpectedAreas&&) noexcept = default;
ExpectedAreas& ExpectedAreas::operator=(ExpectedAreas&&) noexcept = default;
ExpectedAreas::~ExpectedAreas() = default;

ExpectedAreas ExpectedAreas::load(const std::vector<std::string>& user_files, const std::vector<std::string>& charts,
                                  const geo::LocalFrame& frame, double tolerance_m, std::vector<std::string>* warnings) {
    if (!(tolerance_m > 0) || !(tolerance_m <= max_tolerance_m))
        throw UsageError("the tolerance around lines and points of expected areas must be > 0 and at most " + track::detail::fmt(max_tolerance_m) + " metres (got " +
                         std::to_string(tolerance_m) + ")");
    // GDAL's drivers are registered by the first file opened (ogr::open_vector): a run with no
    // --berths and no S-57 chart among its sources needs no GDAL here (util/lazy_libraries.hpp).
    std::unique_ptr<Impl> impl;  // made (with its GEOS context) by the first file read
    std::vector<std::string> local_warnings;
    std::vector<std::string>& warn = warnings ? *warnings : local_warnings;
    auto read_layers = [&](const std::string& path, const std::vector<std::pair<OGRLayer*, LayerRole>>& layers, bool user,
                           const std::string& open_said) {
        QuietErrors quiet;
        if (!impl) impl = std::make_unique<Impl>();
        for (const auto& [layer, role] : layers)
            for (Built& b : LayerReader(path, *layer, role, user, frame, tolerance_m, impl->geos, warn, open_said).read()) {
                impl->areas.push_back(std::move(b.area));
                impl->geoms.push_back(std::move(b.geom));
            }
    };
    auto s57_layers = [](GDALDataset& ds) {
        std::vector<std::pair<OGRLayer*, LayerRole>> chosen;
        for (OGRLayer* l : ogr::layers_named(ds, {std::begin(s57_area_layers), std::end(s57_area_layers)}))
            chosen.emplace_back(l, *s57_role(l->GetName()));
        return chosen;
    };

    std::set<std::string> user_keys;
    for (const std::string& path : user_files) {
        std::string open_said;
        GDALDatasetUniquePtr ds = ogr::open_vector(path, &open_said);
        user_keys.insert(file_key(path));
        std::vector<std::pair<OGRLayer*, LayerRole>> chosen;
        if (ogr::is_s57(*ds)) {
            chosen = s57_layers(*ds);
            if (chosen.empty())
                throw InputError("S-57 chart '" + path + "' has none of the layers " + s57_area_layer_list +
                                 " (its layers: " + ogr::layer_names(*ds) + ")");
        } else {
            for (OGRLayer* l : ds->GetLayers()) chosen.emplace_back(l, s57_role(l->GetName()).value_or(LayerRole{}));
            if (chosen.empty()) throw InputError("'" + path + "' has no vector layers");
        }
        read_layers(path, chosen, true, open_said);
    }
    for (const std::string& path : charts) {
        if (user_keys.count(file_key(path))) continue;  // already read as a user file
        // A file the S-57 driver does not claim (a GeoJSON, a shapefile) is no chart and is not
        // opened: opening a GeoJSON coast would parse it whole. A missing one fails as any input.
        if (detail::input_exists(path) && !ogr::may_be_s57(path)) continue;
        GDALDatasetUniquePtr ds = ogr::open_vector(path);
        if (ogr::is_s57(*ds)) read_layers(path, s57_layers(*ds), false, {});
    }

    ExpectedAreas out;
    if (!impl || impl->areas.empty()) return out;
    impl->index();
    out.m_impl = std::move(impl);
    return out;
}

namespace {

void collect_item(void* item, void* userdata) {
    static_cast<std::vector<const ExpectedArea*>*>(userdata)->push_back(static_cast<const ExpectedArea*>(item));
}

}  // namespace

const ExpectedArea* ExpectedAreas::find(geo::XY p, AreaRole role) const {
    if (!m_impl) return nullptr;
    Impl& impl = *m_impl;
    const auto r = static_cast<std::size_t>(role);
    if (impl.counts[r] == 0) return nullptr;
    std::lock_guard lock(impl.mutex);
    GeomPtr point = geo::own(impl.geos, GEOSGeom_createPointFromXY_r(impl.geos, p.x, p.y), "creating a query point");
    std::vector<const ExpectedArea*> candidates;
    GEOSSTRtree_query_r(impl.geos, impl.trees[r].get(), point.get(), &collect_item, &candidates);
    std::sort(candidates.begin(), candidates.end());  // areas are in one vector: pointer order is read order
    for (const ExpectedArea* a : candidates) {
        const auto i = static_cast<std::size_t>(a - impl.areas.data());
        const char hit = GEOSPreparedIntersects_r(impl.geos, impl.prepared[i].get(), point.get());
        if (hit == 2) throw LibraryError("testing a point against an expected area failed in GEOS: " + impl.geos.last_message());
        if (hit == 1) return a;
    }
    return nullptr;
}

const std::vector<ExpectedArea>& ExpectedAreas::areas() const noexcept {
    static const std::vector<ExpectedArea> none;
    return m_impl ? m_impl->areas : none;
}

std::size_t ExpectedAreas::size() const noexcept { return m_impl ? m_impl->areas.size() : 0; }

std::size_t ExpectedAreas::count(AreaRole role) const noexcept {
    return m_impl ? m_impl->counts[static_cast<std::size_t>(role)] : 0;
}

}  // namespace shoal::coast
