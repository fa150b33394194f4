#include <shoal/coast/coastline.hpp>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <iterator>
#include <memory>
#include <numbers>

#include "coast/ogr_source.hpp"
#include "coast/s57_structure.hpp"
#include "geo/geos_context.hpp"
#include "util/parse_util.hpp"
#include <shoal/geo/local_frame.hpp>
#include <shoal/util/error.hpp>

namespace shoal::coast {

using geo::LonLat;

namespace {

using detail::QuietErrors;
using detail::register_drivers;

/// A polygon, line or (danger, structure) point part as read, in source coordinates until
/// transformed.
struct RawPart {
    bool polygon = false;
    std::vector<std::vector<LonLat>> rings;  // one entry for a line, one of one point for a point
    std::int64_t fid = -1;
    bool point = false;
    double depth_m = NAN;  // the feature's charted depth (hazard layers)
    StructureKind structure = StructureKind::none;  // the feature's kind (structure layers)
    std::string name;      // the feature's name
};

/// What a layer holds, from its name (S-57 object classes, in any OGR source) or from the
/// depth field: land, depth areas, dangers or structures, and the attribute holding a depth.
struct LayerRole {
    HazardKind kind = HazardKind::land;
    DangerKind danger = DangerKind::none;
    std::string field;
};

LayerRole role_of(OGRLayer& layer, const ImportOptions& options) {
    const std::string name = ogr::upper(layer.GetName());
    if (s57::is_structure_class(name)) return {HazardKind::structure, DangerKind::none, ""};
    if (name == "DEPARE" || name == "DRGARE") return {HazardKind::shallow, DangerKind::none, "DRVAL1"};
    if (name == "UWTROC") return {HazardKind::danger, DangerKind::rock, "VALSOU"};
    if (name == "WRECKS") return {HazardKind::danger, DangerKind::wreck, "VALSOU"};
    if (name == "OBSTRN") return {HazardKind::danger, DangerKind::obstruction, "VALSOU"};
    if (!options.depth_field.empty() && layer.GetLayerDefn()->GetFieldIndex(options.depth_field.c_str()) >= 0)
        return {HazardKind::shallow, DangerKind::none, options.depth_field};
    return {};
}

class LayerReader {
public:
    /// `open_said`: what GDAL reported as failures while opening the file (ogr::open_vector).
    LayerReader(std::string file, OGRLayer& layer, const ImportOptions& options, Coastline& out, geo::GeosContext& geos,
                std::string open_said = {})
        : m_file(std::move(file)), m_layer(layer), m_options(options), m_out(out), m_geos(geos), m_open_said(std::move(open_said)) {}

    void read() {
        LayerStats stats;
        stats.file = m_file;
        stats.layer = m_layer.GetName();
        m_role = role_of(m_layer, m_options);
        stats.kind = m_role.kind;
        stats.depth_field = m_role.field;
        int depth_index = -1;
        if (m_role.kind == HazardKind::shallow || m_role.kind == HazardKind::danger) {
            const char* what = m_role.kind == HazardKind::danger ? "dangers" : "depth areas";
            depth_index = m_layer.GetLayerDefn()->GetFieldIndex(m_role.field.c_str());
            if (depth_index < 0)
                throw InputError("layer '" + stats.layer + "' in '" + m_file + "' holds " + what + " but has no field " +
                                 m_role.field + " for their depth");
        }
        m_layer_index = static_cast<std::uint32_t>(m_out.layers.size());
        const s57::StructureFields names = s57::structure_fields(m_layer.GetName(), *m_layer.GetLayerDefn());
        m_layer.ResetReading();
        std::vector<RawPart> parts;
        std::vector<std::int64_t> no_geometry;  // features OGR gave without a geometry
        detail::GdalFailures failures;
        for (auto& feature : m_layer) {
            ++stats.features;
            StructureKind structure = StructureKind::none;
            if (m_role.kind == HazardKind::structure) {
                structure = s57::structure_kind(names, *feature);
                if (!is_hazard(structure)) {  // a mooring buoy, a chain: not a hard structure
                    ++stats.not_hazards;
                    continue;
                }
            }
            double depth = NAN;
            // Every depth area and danger is kept with its charted depth: which of them is a
            // hazard is decided at check time, for each vessel's own limiting depth.
            if (depth_index >= 0 && feature->IsFieldSetAndNotNull(depth_index)) {
                depth = feature->GetFieldAsDouble(depth_index);
                if (!std::isfinite(depth)) depth = NAN;
            }
            const ogr::LinearGeometry linear = ogr::linear_geometry(*feature);
            const OGRGeometry* g = linear.geometry;
            if (!g) no_geometry.push_back(feature->GetFID());
            if (!g || g->IsEmpty()) {
                ++stats.empty_skipped;
                continue;
            }
            const std::size_t before = parts.size();
            const std::uint64_t points_before = stats.points_skipped;
            collect(*g, feature->GetFID(), parts, stats);
            if (parts.size() == before && stats.points_skipped == points_before) ++stats.empty_skipped;
            if (parts.size() > before && m_role.kind == HazardKind::structure) {
                ++stats.structures;
            } else if (parts.size() > before && m_role.kind != HazardKind::land) {
                ++stats.hazards;
                if (std::isnan(depth)) ++stats.unknown_depth;
            }
            if (parts.size() > before) {
                std::string name = s57::feature_name(names, *feature);
                for (std::size_t i = before; i < parts.size(); ++i) {
                    parts[i].depth_m = depth;
                    parts[i].structure = structure;
                    parts[i].name = name;
                }
            }
        }
        said_while_reading(failures, no_geometry, stats.features);
        if (stats.features == 0)
            throw InputError("layer '" + stats.layer + "' in '" + m_file + "' has no features");
        stats.crs = to_wgs84(parts);
        const std::size_t first_new = m_out.polylines.size();
        for (auto& part : parts) {
            if (part.polygon)
                add_polygon(part, stats);
            else if (m_role.kind == HazardKind::structure)
                add_structure_outline(part, stats);
            else if (part.point)
                add_danger_point(part);
            else
                add_line(part, stats);
        }
        // The extent of what was kept (add_line moves the points out of `parts`).
        for (std::size_t i = first_new; i < m_out.polylines.size(); ++i)
            for (const auto& p : m_out.polylines[i].points) {
                m_out.min = {std::min(m_out.min.lon, p.lon), std::min(m_out.min.lat, p.lat)};
                m_out.max = {std::max(m_out.max.lon, p.lon), std::max(m_out.max.lat, p.lat)};
            }
        m_out.layers.push_back(std::move(stats));
    }

private:
    std::string where(std::int64_t fid) const { return ogr::feature_where(m_file, m_layer.GetName(), fid); }

    /// A coastline OGR could not read whole is refused: a grid without part of its land would
    /// call that land water. GDAL says so only through its error handler (a Shapefile cut short:
    /// "Error in fread()", the features after the cut without a geometry; a GeoJSON geometry
    /// with text for coordinates: the feature without one). A feature with no geometry and no
    /// failure (a Shapefile's null shape, GeoJSON's "geometry": null, a type GDAL does not
    /// know) holds no coastline: it is skipped, and said.
    void said_while_reading(const detail::GdalFailures& failures, const std::vector<std::int64_t>& no_geometry, std::uint64_t features) {
        // A GeoJSON "crs" GDAL cannot find: GDAL says so when it opens the file and takes the
        // layer as WGS84 (RFC 7946), whatever its coordinates are. Said first: the features
        // are then not the problem.
        if (ogr::crs_unreadable(m_open_said))
            throw InputError("layer '" + std::string(m_layer.GetName()) + "' in '" + m_file + "': its CRS is not one GDAL can read (" + m_open_said +
                             "); give the file a CRS GDAL knows (e.g. convert it with ogr2ogr -t_srs EPSG:4326)");
        std::string fids;
        for (std::size_t i = 0; i < no_geometry.size() && i < 5; ++i) fids += (i ? ", " : "") + std::to_string(no_geometry[i]);
        if (no_geometry.size() > 5) fids += ", ...";
        const std::string which = std::to_string(no_geometry.size()) + " of its " + std::to_string(features) + " features (" + fids + ")";
        const std::string said = failures.count() ? failures.said() : m_open_said;
        const std::string what = "layer '" + std::string(m_layer.GetName()) + "' in '" + m_file + "'";
        if (failures.count() || (!said.empty() && !no_geometry.empty()))
            throw InputError(what + ": OGR could not read all of it (" + said + ")" +
                             (no_geometry.empty() ? "" : "; " + which + " came without a geometry") +
                             ": the file is damaged or cut short, and a grid without part of its land would call that land water");
        if (!no_geometry.empty())
            m_out.warnings.push_back(what + ": " + which + (no_geometry.size() == 1 ? " has" : " have") +
                                     " no geometry OGR could read (none given, or one OGR does not know, as a GeoJSON type misspelt); "
                                     "skipped: no land is drawn for " + (no_geometry.size() == 1 ? "it" : "them"));
    }

    static std::vector<LonLat> points_of(const OGRSimpleCurve& c) { return ogr::points_of<LonLat>(c); }

    void collect(const OGRGeometry& g, std::int64_t fid, std::vector<RawPart>& parts, LayerStats& stats) {
        switch (wkbFlatten(g.getGeometryType())) {
        case wkbPolygon: {
            const auto& poly = *g.toPolygon();
            if (poly.IsEmpty()) return;
            RawPart part;
            part.polygon = true;
            part.fid = fid;
            for (const OGRLinearRing* ring : poly) {
                part.rings.push_back(points_of(*ring));
                stats.vertices += part.rings.back().size();
            }
            ++stats.polygons;
            parts.push_back(std::move(part));
            return;
        }
        case wkbLineString:
        case wkbLinearRing: {
            const auto& line = *g.toSimpleCurve();
            if (line.IsEmpty()) return;
            RawPart part;
            part.rings.push_back(points_of(line));
            part.fid = fid;
            parts.push_back(std::move(part));
            stats.vertices += parts.back().rings[0].size();
            ++stats.lines;
            return;
        }
        case wkbPoint:
            if (has_point_hazards()) {  // a point danger or structure: a small polygon around it
                const auto& pt = *g.toPoint();
                RawPart part;
                part.point = true;
                part.fid = fid;
                part.rings.push_back({LonLat{pt.getX(), pt.getY()}});
                parts.push_back(std::move(part));
                ++stats.vertices;
                ++stats.points;
                return;
            }
            ++stats.points_skipped;
            return;
        case wkbMultiPoint:
            if (has_point_hazards()) {
                for (const OGRGeometry* sub : *g.toGeometryCollection()) collect(*sub, fid, parts, stats);
                return;
            }
            ++stats.points_skipped;
            return;
        case wkbMultiPolygon:
        case wkbMultiLineString:
        case wkbGeometryCollection: {
            for (const OGRGeometry* sub : *g.toGeometryCollection()) collect(*sub, fid, parts, stats);
            return;
        }
        default:
            m_out.warnings.push_back(where(fid) + ": geometry type " + OGRGeometryTypeToName(g.getGeometryType()) +
                                     " is not coastline; skipped");
        }
    }

    /// "" when every coordinate is a longitude within +-max_lon and a latitude, else
    /// " (e.g. X, Y in feature N)" naming the first that is not.
    static std::string first_not_lonlat(const std::vector<RawPart>& parts, double max_lon) {
        for (const auto& part : parts)
            for (const auto& ring : part.rings)
                for (const auto& p : ring)
                    if (std::string bad = ogr::not_lonlat_note(p.lon, p.lat, part.fid, max_lon); !bad.empty()) return bad;
        return "";
    }

    /// Transforms every part to WGS84 lon/lat; returns the CRS description for the stats.
    std::string to_wgs84(std::vector<RawPart>& parts) {
        const ogr::LayerCrs crs =
            ogr::layer_crs(m_layer, m_file, {m_options.source_crs, "; name its CRS with ImportOptions::source_crs", "none in file; assumed WGS84 lon/lat"},
                           [&](double max_lon) { return first_not_lonlat(parts, max_lon); }, m_out.warnings);
        if (!crs.to_wgs84) return crs.description;
        for (auto& part : parts) {
            for (auto& ring : part.rings) {
                std::vector<double> xs(ring.size()), ys(ring.size());
                for (std::size_t i = 0; i < ring.size(); ++i) { xs[i] = ring[i].lon; ys[i] = ring[i].lat; }
                if (const std::size_t i = ogr::transform(*crs.to_wgs84, xs, ys); i < ring.size())
                    throw InputError(where(part.fid) + ": vertex " + std::to_string(i) + " cannot be transformed to WGS84 from " +
                                     crs.description);
                for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = {xs[i], ys[i]};
            }
        }
        return crs.description;
    }

    static void drop_repeats(std::vector<LonLat>& pts) { ogr::drop_repeats(pts); }

    static double signed_area(const std::vector<LonLat>& ring) {
        double a = 0;
        for (std::size_t i = 0; i + 1 < ring.size(); ++i)
            a += (ring[i].lon - ring[0].lon) * (ring[i + 1].lat - ring[0].lat) -
                 (ring[i + 1].lon - ring[0].lon) * (ring[i].lat - ring[0].lat);
        return a / 2;
    }

    void add_line(RawPart& part, LayerStats& stats) {
        auto& pts = part.rings[0];
        drop_repeats(pts);
        if (pts.size() < 2) {
            ++stats.empty_skipped;
            return;
        }
        m_out.polylines.push_back(Polyline{std::move(pts), false, m_layer_index, part.fid, hazard_of(part)});
    }

    bool has_point_hazards() const noexcept { return m_role.kind == HazardKind::danger || m_role.kind == HazardKind::structure; }

    Hazard hazard_of(const RawPart& part) const {
        Hazard h;
        h.name = part.name;
        if (m_role.kind == HazardKind::land) return h;
        h.kind = m_role.kind;
        h.danger = m_role.danger;
        h.structure = part.structure;
        h.depth_m = part.depth_m;
        return h;
    }

    /// A structure drawn as a line or a point: the polygon around it within
    /// structure_line_half_width_m or structure_point_radius_m (circumscribed, see
    /// structure_quadrant_segments), buffered with GEOS in metres of a local equirectangular
    /// scale at the feature's first vertex (geo::metres_per_degree there; over a pier's length
    /// the scale changes by a few parts in 10,000 of the width), then turned back into degrees.
    void add_structure_outline(RawPart& part, LayerStats& stats) {
        auto& pts = part.rings[0];
        drop_repeats(pts);
        if (pts.empty()) {
            ++stats.empty_skipped;
            return;
        }
        const LonLat origin = pts.front();
        const Eigen::Vector2d mpd = geo::metres_per_degree(origin.lat);
        std::vector<geo::XY> xy(pts.size());
        for (std::size_t i = 0; i < pts.size(); ++i) xy[i] = {(pts[i].lon - origin.lon) * mpd.x(), (pts[i].lat - origin.lat) * mpd.y()};
        const bool point = xy.size() == 1;
        geo::GeomPtr shape = point ? geo::own(m_geos, GEOSGeom_createPointFromXY_r(m_geos, 0.0, 0.0), "creating a point")
                                   : geo::make_linestring(m_geos, xy.data(), xy.size());
        constexpr int q = structure_quadrant_segments;
        const double width = point ? structure_point_radius_m : structure_line_half_width_m;
        const double radius = width / std::cos(std::numbers::pi / (4 * q));
        geo::GeomPtr buffer = geo::own(m_geos, GEOSBuffer_r(m_geos, shape.get(), radius, q), "buffering a structure");
        std::vector<std::vector<std::vector<geo::XY>>> polygons;
        geo::collect_polygons(m_geos, buffer.get(), polygons);
        for (auto& rings : polygons)
            for (auto& ring : rings)
                for (geo::XY& p : ring) p = {origin.lon + p.x / mpd.x(), origin.lat + p.y / mpd.y()};
        add_rings(polygons, part);
    }

    /// A point danger: the polygon circumscribed about the circle of the danger radius.
    void add_danger_point(const RawPart& part) {
        const LonLat c = part.rings[0][0];
        const Eigen::Vector2d mpd = geo::metres_per_degree(c.lat);
        const int n = danger_polygon_sides;
        const double r = m_options.danger_radius_m / std::cos(std::numbers::pi / n);
        std::vector<LonLat> ring;
        for (int k = 0; k < n; ++k) {
            const double a = 2 * std::numbers::pi * k / n;
            ring.push_back({c.lon + r * std::cos(a) / mpd.x(), c.lat + r * std::sin(a) / mpd.y()});
        }
        ring.push_back(ring.front());
        m_out.polylines.push_back(Polyline{std::move(ring), true, m_layer_index, part.fid, hazard_of(part)});
    }

    void add_polygon(RawPart& part, LayerStats& stats) {
        std::vector<std::vector<geo::XY>> rings;
        for (auto& ring : part.rings) {
            drop_repeats(ring);
            if (!ring.empty() && !(ring.front() == ring.back())) ring.push_back(ring.front());
            if (ring.size() < 4) {
                if (rings.empty()) {  // degenerate shell: nothing of this polygon is usable
                    m_out.warnings.push_back(where(part.fid) + ": polygon with fewer than 3 distinct points; skipped");
                    ++stats.empty_skipped;
                    return;
                }
                continue;  // a degenerate hole adds nothing
            }
            std::vector<geo::XY> xy(ring.size());
            for (std::size_t i = 0; i < ring.size(); ++i) xy[i] = {ring[i].lon, ring[i].lat};
            rings.push_back(std::move(xy));
        }
        geo::GeomPtr poly = geo::make_polygon(m_geos, rings);
        std::vector<std::vector<std::vector<geo::XY>>> valid;
        if (GEOSisValid_r(m_geos, poly.get()) == 1) {
            valid.push_back(std::move(rings));
        } else {
            char* reason = GEOSisValidReason_r(m_geos, poly.get());
            const std::string why = reason ? reason : "invalid";
            GEOSFree_r(m_geos, reason);
            geo::GeomPtr fixed = geo::own(m_geos, GEOSMakeValid_r(m_geos, poly.get()), "repairing a polygon");
            geo::collect_polygons(m_geos, fixed.get(), valid);
            ++stats.repaired;
            m_out.warnings.push_back(where(part.fid) + ": invalid polygon (" + why + ") repaired with GEOSMakeValid");
        }
        add_rings(valid, part);
    }

    /// Appends the rings of `polygons` (x, y: lon, lat) as polylines, land on the left.
    void add_rings(std::vector<std::vector<std::vector<geo::XY>>>& polygons, const RawPart& part) {
        for (auto& poly_rings : polygons) {
            for (std::size_t r = 0; r < poly_rings.size(); ++r) {
                std::vector<LonLat> ll(poly_rings[r].size());
                for (std::size_t i = 0; i < ll.size(); ++i) ll[i] = {poly_rings[r][i].x, poly_rings[r][i].y};
                const double area = signed_area(ll);
                if (area == 0.0) continue;
                // Shells counter-clockwise, holes clockwise: land is then always on the left.
                if ((r == 0) != (area > 0)) std::reverse(ll.begin(), ll.end());
                m_out.polylines.push_back(Polyline{std::move(ll), true, m_layer_index, part.fid, hazard_of(part)});
            }
        }
    }

    std::string m_file;
    OGRLayer& m_layer;
    const ImportOptions& m_options;
    Coastline& m_out;
    geo::GeosContext& m_geos;
    std::string m_open_said;
    std::uint32_t m_layer_index = 0;
    LayerRole m_role;
};

}  // namespace

Coastline import_coastline(const std::vector<std::string>& paths, const ImportOptions& options) {
    register_drivers();
    if (paths.empty()) throw UsageError("no coastline file given");
    if (options.limiting_depth_m && !std::isfinite(*options.limiting_depth_m))
        throw UsageError("the limiting depth must be a finite number of metres");
    if (!(options.danger_radius_m > 0) || !(options.danger_radius_m <= ImportOptions::max_danger_radius_m))
        throw UsageError("ImportOptions::danger_radius_m must be > 0 and at most " + track::detail::fmt(ImportOptions::max_danger_radius_m) + " metres");
    Coastline out;
    geo::GeosContext geos;
    std::vector<bool> found(options.layers.size(), false);
    for (const std::string& path : paths) {
        std::string open_said;
        GDALDatasetUniquePtr ds = ogr::open_vector(path, &open_said);
        if (char** files = ds->GetFileList()) {
            for (char** f = files; *f; ++f) out.files.emplace_back(*f);
            CSLDestroy(files);
        }
        std::vector<OGRLayer*> chosen;
        if (!options.layers.empty()) {
            for (std::size_t i = 0; i < options.layers.size(); ++i)
                if (OGRLayer* l = ds->GetLayerByName(options.layers[i].c_str())) {
                    chosen.push_back(l);
                    found[i] = true;
                }
            if (chosen.empty())
                throw InputError("'" + path + "' has no layer named " + options.layers.front() +
                                 (options.layers.size() > 1 ? " (nor the other ImportOptions::layers names)" : "") +
                                 "; its layers: " + ogr::layer_names(*ds));
        } else if (ogr::is_s57(*ds)) {
            // Land, depth areas, dredged areas and dangers (each kept with its charted depth),
            // and structures.
            const std::vector<const char*> names(std::begin(s57_default_layers), std::end(s57_default_layers));
            chosen = ogr::layers_named(*ds, names);
            if (chosen.empty()) {
                std::string list;
                for (const char* n : names) list += (list.empty() ? "" : ", ") + std::string(n);
                throw InputError("S-57 chart '" + path + "' has none of the layers " + list +
                                 "; pick layers with ImportOptions::layers (its layers: " + ogr::layer_names(*ds) + ")");
            }
        } else {
            for (OGRLayer* l : ds->GetLayers()) chosen.push_back(l);
            if (chosen.empty()) throw InputError("'" + path + "' has no vector layers");
        }
        QuietErrors quiet;
        for (OGRLayer* layer : chosen) LayerReader(path, *layer, options, out, geos, open_said).read();
    }
    for (std::size_t i = 0; i < options.layers.size(); ++i)
        if (!found[i]) throw InputError("no input has a layer named '" + options.layers[i] + "'");
    if (!options.depth_field.empty() &&
        std::none_of(out.layers.begin(), out.layers.end(), [&](const LayerStats& l) { return l.depth_field == options.depth_field; }))
        throw InputError("no layer read has the field '" + options.depth_field + "' named by ImportOptions::depth_field");
    if (out.polylines.empty()) {
        std::string names;
        for (const auto& l : out.layers) names += (names.empty() ? "'" : ", '") + l.layer + "'";
        throw InputError("no coastline (polygon or line) geometry in layer " + names + " of '" + paths.front() +
                         (paths.size() > 1 ? "' and the other inputs" : "'"));
    }
    return out;
}

}  // namespace shoal::coast
