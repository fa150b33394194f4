// Shallow water and dangers as hazards, on a real S-57 cut (tests/data/coast/
// US4MD81M_hazard_cut.000: LNDARE, COALNE, DEPARE, DRGARE, UWTROC, WRECKS, OBSTRN off
// Annapolis). What is checked, each against an answer found independently:
// - import counts per layer and per kind equal OGR's own attribute filters (DRVAL1 < D ...);
// - a ship of deeper draught grounds where a shallower one does not;
// - a wreck with an unknown sounding is a hazard, whatever the limiting depth;
// - collision and clearance for random poses equal GEOS on the same hazard polygons, built
//   straight from the OGR layers (land + shallow depth areas + danger polygons and circles),
//   and what each contact hit is the feature GEOS finds nearest or touching (also on the
//   whole US4MD81M cell when ../shared/data is there, with its structures: SLCONS and MORFAC
//   as the documented bands and discs);
// - the hazard table and the limiting depth survive the cache, whose key includes them;
// - events say what was hit (land, shallow with its depth, danger with its kind) on
//   hand-made tracks, through the library and through the `shoal` executable.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numbers>
#include <random>
#include <sys/wait.h>

#include <nlohmann/json.hpp>
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <shoal/audit/audit.hpp>
#include <shoal/sweep/sweep.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/grid/limiting_depth.hpp>
#include <shoal/hull/hull.hpp>
#include "run_shoal.hpp"
#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace shoal {
namespace {

using coast::DangerKind;
using coast::HazardKind;
using geo::LonLat;
using geo::XY;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

const std::string& cut() {
    static const std::string p = test::data_path("coast/US4MD81M_hazard_cut.000");
    return p;
}

/// The exact position of the point feature of `layer` nearest to `near`, read with OGR.
LonLat point_feature(const char* layer, LonLat near) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(cut().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    LonLat best{NAN, NAN};
    double best_d = INFINITY;
    for (auto& f : *ds->GetLayerByName(layer)) {
        const OGRGeometry* g = f->GetGeometryRef();
        if (!g || wkbFlatten(g->getGeometryType()) != wkbPoint) continue;
        const double d = std::hypot(g->toPoint()->getX() - near.lon, g->toPoint()->getY() - near.lat);
        if (d < best_d) {
            best_d = d;
            best = {g->toPoint()->getX(), g->toPoint()->getY()};
        }
    }
    if (!(best_d < 1e-4)) throw std::runtime_error(std::string("no ") + layer + " point there");
    return best;
}

// Places in the cut (found with OGR; see tests/data/README.md):
const LonLat in_depth_3_6{-76.45138, 38.92249};  // inside the DEPARE 3.6-5.4 m, 268 m from its edge
const LonLat in_depth_5_4{-76.44027, 38.92116};  // inside the DEPARE 5.4-9.1 m, 513 m from its edge
const LonLat wreck_unknown = point_feature("WRECKS", {-76.43120, 38.94417});      // no VALSOU, in the 5.4 m area
const LonLat obstruction_5_9 = point_feature("OBSTRN", {-76.42332, 38.93916});    // VALSOU 5.9, in the 9.1 m area

coast::ImportOptions with_limit(std::optional<double> depth_m) {
    coast::ImportOptions o;
    o.limiting_depth_m = depth_m;
    return o;
}

hull::Hull ship_with_draught(double draught_m) {
    char json[200];
    std::snprintf(json, sizeof json, R"({"name": "test ship", "a": 45, "b": 15, "c": 5, "d": 5, "draught": %g})", draught_m);
    return hull::Hull::parse(json, "test ship");
}

grid::CoastGrid grid_for(std::optional<double> limit, double cell_m = 300, const std::string& chart = cut()) {
    grid::BuildRequest r;
    r.import.limiting_depth_m = limit;
    r.cell_m = cell_m;
    std::vector<std::string> warnings;
    return grid::build_grid({chart}, r, &warnings);
}

bool same_depth(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// ---------------------------------------------------------------- import counts

/// Features of `layer` in the cut that pass the OGR SQL `where`, counted by OGR itself.
std::uint64_t ogr_count(const std::string& layer, const std::string& where) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(cut().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    OGRLayer* l = ds->GetLayerByName(layer.c_str());
    if (!l || l->SetAttributeFilter(where.c_str()) != OGRERR_NONE) throw std::runtime_error("bad filter " + where);
    std::uint64_t n = 0;
    for (auto& f : *l) {
        (void)f;
        ++n;
    }
    return n;
}

/// Rings (polygons) and points of the features of `layer` that pass `where`.
std::uint64_t ogr_rings_and_points(const std::string& layer, const std::string& where) {
    GDALDatasetUniquePtr ds(GDALDataset::Open(cut().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    OGRLayer* l = ds->GetLayerByName(layer.c_str());
    l->SetAttributeFilter(where.c_str());
    std::uint64_t n = 0;
    for (auto& f : *l) {
        const OGRGeometry* g = f->GetGeometryRef();
        switch (wkbFlatten(g->getGeometryType())) {
        case wkbPolygon: n += 1 + static_cast<std::uint64_t>(g->toPolygon()->getNumInteriorRings()); break;
        case wkbPoint: n += 1; break;
        default: throw std::runtime_error("unexpected geometry in " + layer);
        }
    }
    return n;
}

TEST(HazardImport, CountsPerLayerAndKindEqualOgr) {
    // Every depth area and danger is kept with its depth, whatever the grid's default limit
    // (which no longer changes what is read: a one-depth import was the old limitation).
    for (std::optional<double> d : {std::optional<double>(), std::optional<double>(3.0), std::optional<double>(11.0)}) {
        SCOPED_TRACE("default limit " + (d ? std::to_string(*d) : std::string("none")));
        const coast::Coastline c = coast::import_coastline({cut()}, with_limit(d));
        ASSERT_EQ(c.layers.size(), 7u) << "the default S-57 set has seven layers";
        std::uint64_t shallow_rings = 0, danger_rings = 0;
        for (const auto& l : c.layers) {
            SCOPED_TRACE(l.layer);
            const bool area = l.layer == "DEPARE" || l.layer == "DRGARE";
            const bool danger = l.layer == "UWTROC" || l.layer == "WRECKS" || l.layer == "OBSTRN";
            if (!area && !danger) {
                EXPECT_EQ(l.kind, HazardKind::land);
                EXPECT_EQ(l.hazards, 0u);
                continue;
            }
            const std::string f = area ? "DRVAL1" : "VALSOU";
            const std::string unknown = f + " IS NULL";
            EXPECT_EQ(l.kind, area ? HazardKind::shallow : HazardKind::danger);
            EXPECT_EQ(l.features, ogr_count(l.layer, ""));
            EXPECT_EQ(l.hazards, ogr_count(l.layer, ""));
            EXPECT_EQ(l.unknown_depth, ogr_count(l.layer, unknown));
            (area ? shallow_rings : danger_rings) += ogr_rings_and_points(l.layer, "");
        }
        EXPECT_EQ(c.count(HazardKind::shallow), shallow_rings);
        EXPECT_EQ(c.count(HazardKind::danger), danger_rings);
        EXPECT_EQ(c.count(HazardKind::land), ogr_rings_and_points("LNDARE", "") + ogr_count("COALNE", ""));
        for (const auto& p : c.polylines) {
            if (p.hazard.kind != HazardKind::land) {
                EXPECT_TRUE(p.land_left);
            }
        }
    }
    // The cut's own figures, as a sanity check of the filters (tests/data/README.md).
    EXPECT_EQ(ogr_count("DEPARE", "DRVAL1 < 3"), 4u);
    EXPECT_EQ(ogr_count("WRECKS", "VALSOU IS NULL"), 2u);
}

TEST(HazardImport, DepthLayersAndFieldsNeedNoLimitAndBadOptionsAreRefused) {
    coast::ImportOptions o;
    o.layers = {"LNDARE", "DEPARE"};
    const coast::Coastline c = coast::import_coastline({cut()}, o);
    ASSERT_EQ(c.layers.size(), 2u);
    EXPECT_EQ(c.layers[1].kind, HazardKind::shallow);
    EXPECT_EQ(c.layers[1].hazards, ogr_count("DEPARE", ""));
    o = {};
    o.danger_radius_m = 0;
    EXPECT_THAT([&] { coast::import_coastline({cut()}, o); }, ThrowsMessage<UsageError>(HasSubstr("ImportOptions::danger_radius_m")));
    o = {};
    o.depth_field = "NO_SUCH_FIELD";
    EXPECT_THAT([&] { coast::import_coastline({cut()}, o); }, ThrowsMessage<InputError>(HasSubstr("NO_SUCH_FIELD")));
}

TEST(HazardImport, LimitingDepthIsTheHazardDepthElseDraughtPlusUkcElseNone) {
    EXPECT_EQ(coast::limiting_depth(4.0, 7.0, 1.0), 4.0);
    EXPECT_EQ(coast::limiting_depth(std::nullopt, 7.0, 1.0), 8.0);
    EXPECT_EQ(coast::limiting_depth(std::nullopt, 0.0, 1.0), std::nullopt);
}

TEST(HazardImport, DepthFieldMakesDepthAreasOfOtherSources) {
    test::TempDir dir;
    const std::string land = dir.file("land.geojson"), depths = dir.file("depths.geojson");
    std::ofstream(land) << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},
        "geometry":{"type":"Polygon","coordinates":[[[0,0],[0.01,0],[0.01,0.01],[0,0.01],[0,0]]]}}]})";
    std::ofstream(depths) << R"({"type":"FeatureCollection","features":[
        {"type":"Feature","properties":{"mindepth":2.0},"geometry":{"type":"Polygon","coordinates":[[[0.02,0],[0.03,0],[0.03,0.01],[0.02,0]]]}},
        {"type":"Feature","properties":{"mindepth":8.0},"geometry":{"type":"Polygon","coordinates":[[[0.04,0],[0.05,0],[0.05,0.01],[0.04,0]]]}},
        {"type":"Feature","properties":{"mindepth":null},"geometry":{"type":"Polygon","coordinates":[[[0.06,0],[0.07,0],[0.07,0.01],[0.06,0]]]}}]})";
    coast::ImportOptions o = with_limit(5);
    o.depth_field = "mindepth";
    const coast::Coastline c = coast::import_coastline({land, depths}, o);
    ASSERT_EQ(c.layers.size(), 2u);
    EXPECT_EQ(c.layers[0].kind, HazardKind::land);
    EXPECT_EQ(c.layers[1].kind, HazardKind::shallow);
    EXPECT_EQ(c.layers[1].hazards, 3u) << "all kept, the 8 m one too: the limit is chosen at check time";
    EXPECT_EQ(c.layers[1].unknown_depth, 1u);
    ASSERT_EQ(c.polylines.size(), 4u);
    EXPECT_EQ(c.polylines[0].hazard.kind, HazardKind::land);
    EXPECT_EQ(c.polylines[1].hazard.kind, HazardKind::shallow);
    EXPECT_EQ(c.polylines[1].hazard.depth_m, 2.0);
    EXPECT_EQ(c.polylines[2].hazard.depth_m, 8.0);
    EXPECT_TRUE(std::isnan(c.polylines[3].hazard.depth_m));
}

// ---------------------------------------------------------------- single poses

check::Contact check_at(const grid::CoastGrid& g, const hull::Hull& hull, LonLat where, double heading_deg,
                        std::optional<double> limit_m) {
    return check::Detector(g, hull, limit_m).check(check::Pose{where, heading_deg});
}

/// One grid of the cut with every depth area and danger (no default limit), built once.
const grid::CoastGrid& one_grid() {
    static const grid::CoastGrid g = grid_for(std::nullopt);
    return g;
}

TEST(HazardPoses, DeeperDraughtGroundsWhereAShallowerOneDoesNotOnOneGrid) {
    // Inside the 3.6 m depth area: a ship of draught 3.0 m floats, one of 3.5 m with 0.5 m
    // under-keel clearance (limiting depth 4.0 m) is aground; both on the same grid.
    const hull::Hull shallow = ship_with_draught(3.0), deep = ship_with_draught(3.5);
    const grid::CoastGrid& g = one_grid();
    const auto l3 = coast::limiting_depth(std::nullopt, shallow.draught(), 0.0);
    const auto l4 = coast::limiting_depth(std::nullopt, deep.draught(), 0.5);
    ASSERT_EQ(l3, 3.0);
    ASSERT_EQ(l4, 4.0);
    for (double heading : {0.0, 30.0, 145.0, 270.0}) {
        const check::Contact afloat = check_at(g, shallow, in_depth_3_6, heading, l3);
        EXPECT_FALSE(afloat.collision);
        EXPECT_GT(afloat.clearance_m, 150);
        const check::Contact aground = check_at(g, deep, in_depth_3_6, heading, l4);
        ASSERT_TRUE(aground.collision);
        // Wholly inside the area: the contact names the area holding the hull.
        ASSERT_LT(aground.polyline, g.polyline_count());
        EXPECT_EQ(g.hazard(aground.polyline).kind, HazardKind::shallow);
        EXPECT_EQ(g.hazard(aground.polyline).depth_m, 3.6);
    }
    // A charted obstruction of 5.9 m: clear at 5.0 m, a hazard at 6.0 m.
    EXPECT_FALSE(check_at(g, shallow, obstruction_5_9, 0, 5.0).collision);
    const check::Contact hit = check_at(g, deep, obstruction_5_9, 0, 6.0);
    ASSERT_TRUE(hit.collision);
    EXPECT_EQ(g.hazard(hit.polyline).kind, HazardKind::danger);
    EXPECT_EQ(g.hazard(hit.polyline).danger, DangerKind::obstruction);
    EXPECT_EQ(g.hazard(hit.polyline).depth_m, 5.9);
    // A limit equal to a charted depth: that depth is not under it (DRVAL1 3.6 is no hazard at 3.6).
    EXPECT_FALSE(check_at(g, deep, in_depth_3_6, 0, 3.6).collision);
    EXPECT_TRUE(check_at(g, deep, in_depth_3_6, 0, std::nextafter(3.6, 10.0)).collision);
    // A grid built with a default limit (import --hazard-depth) checks at it when no limit is given.
    const grid::CoastGrid g4 = grid_for(4.0);
    EXPECT_TRUE(check::Detector(g4, deep).check(check::Pose{in_depth_3_6, 0}).collision);
    EXPECT_FALSE(check::Detector(g, deep).check(check::Pose{in_depth_3_6, 0}).collision) << "no default: land only";
}

TEST(HazardPoses, WreckWithAnUnknownSoundingIsAHazardAtAnyLimit) {
    const hull::Hull ship = ship_with_draught(1.0);
    const grid::CoastGrid& g = one_grid();
    for (double limit : {0.5, 5.0, 30.0}) {
        const check::Contact c = check_at(g, ship, wreck_unknown, 90, limit);
        ASSERT_TRUE(c.collision) << "limit " << limit;
        EXPECT_EQ(g.hazard(c.polyline).kind, HazardKind::danger);
        EXPECT_EQ(g.hazard(c.polyline).danger, DangerKind::wreck);
        EXPECT_TRUE(std::isnan(g.hazard(c.polyline).depth_m));
    }
    EXPECT_FALSE(check_at(g, ship, wreck_unknown, 90, std::nullopt).collision) << "land only: the wreck is not there";
    // 25 m east of the wreck, heading north: the port side (c = 5 m) is 20 m from it, and
    // the wreck's 16-gon reaches 10 m / cos(pi / 16) = 10.196 m east (a vertex).
    const Eigen::Vector2d mpd = geo::metres_per_degree(wreck_unknown.lat);
    const check::Contact beside = check_at(g, ship, {wreck_unknown.lon + 25 / mpd.x(), wreck_unknown.lat}, 0, 5.0);
    EXPECT_FALSE(beside.collision);
    EXPECT_NEAR(beside.clearance_m, 20 - 10 / std::cos(std::numbers::pi / 16), 0.02);
    EXPECT_EQ(g.hazard(beside.polyline).danger, DangerKind::wreck);
}

// ---------------------------------------------------------------- against GEOS

/// The hazard features of an S-57 chart for a limiting depth, read with OGR alone and
/// projected vertex by vertex with the grid's frame; point dangers become the documented
/// 16-gons; an invalid polygon is repaired with GEOSMakeValid, as the import does.
class HazardOracle {
public:
    struct Feature {
        HazardKind kind;
        DangerKind danger;
        double depth_m;
        geo::GeomPtr geom;
        test::PreparedPtr prepared;
        geo::Box box;
    };

    HazardOracle(const std::string& chart, double limit_m, double radius_m, const geo::LocalFrame& frame) : m_frame(frame) {
        GDALAllRegister();
        GDALDatasetUniquePtr ds(GDALDataset::Open(chart.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
        std::vector<GEOSGeometry*> parts;
        struct LayerDef {
            const char* name;
            HazardKind kind;
            DangerKind danger;
            const char* field;
        } defs[] = {{"LNDARE", HazardKind::land, DangerKind::none, nullptr},
                    {"COALNE", HazardKind::land, DangerKind::none, nullptr},
                    {"DEPARE", HazardKind::shallow, DangerKind::none, "DRVAL1"},
                    {"DRGARE", HazardKind::shallow, DangerKind::none, "DRVAL1"},
                    {"UWTROC", HazardKind::danger, DangerKind::rock, "VALSOU"},
                    {"WRECKS", HazardKind::danger, DangerKind::wreck, "VALSOU"},
                    {"OBSTRN", HazardKind::danger, DangerKind::obstruction, "VALSOU"},
                    // Structures, hazards at any limit (docs/method.md): their kind is checked
                    // by the structure tests; here only the class's.
                    {"SLCONS", HazardKind::structure, DangerKind::none, nullptr},
                    {"PONTON", HazardKind::structure, DangerKind::none, nullptr},
                    {"HULKES", HazardKind::structure, DangerKind::none, nullptr},
                    {"MORFAC", HazardKind::structure, DangerKind::none, nullptr}};
        for (const auto& def : defs) {
            OGRLayer* l = ds->GetLayerByName(def.name);
            if (!l) continue;
            for (auto& f : *l) {
                double depth = NAN;
                if (def.field) {
                    const int i = f->GetFieldIndex(def.field);
                    if (f->IsFieldSetAndNotNull(i)) depth = f->GetFieldAsDouble(i);
                    if (depth >= limit_m) continue;
                }
                const OGRGeometry* g = f->GetGeometryRef();
                if (!g) continue;
                const bool structure = def.kind == HazardKind::structure;
                if (structure && std::string(def.name) == "MORFAC") {
                    const int cat = f->GetFieldIndex("CATMOR");
                    if (f->IsFieldSetAndNotNull(cat) && (f->GetFieldAsInteger(cat) == 6 || f->GetFieldAsInteger(cat) == 7)) continue;
                }
                const auto type = wkbFlatten(g->getGeometryType());
                geo::GeomPtr geom{nullptr, {m_ctx.get()}};
                m_box = {};
                if (structure && (type == wkbLineString || type == wkbPoint)) {
                    geom = structure_polygon(*g);
                } else if (type == wkbPolygon) {
                    std::vector<std::vector<XY>> rings;
                    for (const OGRLinearRing* r : *g->toPolygon()) rings.push_back(project(*r));
                    geom = test::polygon(m_ctx, rings);
                } else if (type == wkbLineString) {
                    geom = test::line(m_ctx, project(*g->toLineString()));
                } else if (type == wkbPoint && def.kind == HazardKind::danger) {
                    geom = test::polygon(m_ctx, {danger_polygon(*g->toPoint(), radius_m)});
                } else {
                    continue;  // point islets of LNDARE are not coastline
                }
                if (GEOSisValid_r(m_ctx, geom.get()) != 1) {
                    geom = test::check(m_ctx, GEOSMakeValid_r(m_ctx, geom.get()), "make valid");
                    ++m_repaired;
                }
                parts.push_back(GEOSGeom_clone_r(m_ctx, geom.get()));
                test::PreparedPtr prepared = test::prepare(m_ctx, geom.get());
                m_features.push_back({def.kind, def.danger, depth, std::move(geom), std::move(prepared), m_box});
            }
        }
        // Poses are sampled near the outline of all hazards together (shared edges inside
        // it, such as between two shallow areas, are not where contacts begin).
        geo::GeomPtr all = test::check(m_ctx, GEOSGeom_createCollection_r(m_ctx, GEOS_GEOMETRYCOLLECTION, parts.data(),
                                                                          static_cast<unsigned>(parts.size())), "collection");
        geo::GeomPtr outline = test::check(m_ctx, GEOSBoundary_r(m_ctx, test::check(m_ctx, GEOSUnaryUnion_r(m_ctx, all.get()), "union").get()), "boundary");
        std::vector<std::vector<XY>> lines;
        geo::collect_lines(m_ctx, outline.get(), lines);
        for (const auto& l : lines) m_vertices.insert(m_vertices.end(), l.begin(), l.end());
    }

    const std::vector<Feature>& features() const noexcept { return m_features; }
    int repaired() const noexcept { return m_repaired; }
    const std::vector<XY>& vertices() const noexcept { return m_vertices; }
    geo::GeomPtr hull_polygon(std::vector<XY> ring) const {
        ring.push_back(ring.front());
        return test::polygon(m_ctx, {ring});
    }
    bool intersects(const Feature& f, const GEOSGeometry* hull) const { return GEOSPreparedIntersects_r(m_ctx, f.prepared.get(), hull) == 1; }
    double distance(const Feature& f, const GEOSGeometry* hull) const {
        double d = -1;
        if (!GEOSPreparedDistance_r(m_ctx, f.prepared.get(), hull, &d)) throw std::runtime_error("GEOSPreparedDistance failed");
        return d;
    }

private:
    std::vector<XY> project(const OGRSimpleCurve& c) {
        std::vector<XY> out;
        for (int i = 0; i < c.getNumPoints(); ++i) out.push_back(m_frame.forward(LonLat{c.getX(i), c.getY(i)}));
        out.erase(std::unique(out.begin(), out.end()), out.end());
        for (const XY& q : out) m_box.extend(q);
        return out;
    }
    /// docs/method.md: a structure's line or point becomes the GEOS buffer (8 segments a quarter
    /// circle) of the width / cos(pi / 32), made in metres of the equirectangular scale at its
    /// first vertex and turned back into degrees; its vertices are then projected one by one.
    geo::GeomPtr structure_polygon(const OGRGeometry& g) {
        std::vector<LonLat> ll;
        if (wkbFlatten(g.getGeometryType()) == wkbPoint) {
            ll.push_back({g.toPoint()->getX(), g.toPoint()->getY()});
        } else {
            const OGRLineString& l = *g.toLineString();
            for (int i = 0; i < l.getNumPoints(); ++i)
                if (ll.empty() || !(ll.back() == LonLat{l.getX(i), l.getY(i)})) ll.push_back({l.getX(i), l.getY(i)});
        }
        const LonLat o = ll.front();
        const Eigen::Vector2d mpd = geo::metres_per_degree(o.lat);
        std::vector<XY> xy;
        for (const LonLat& p : ll) xy.push_back({(p.lon - o.lon) * mpd.x(), (p.lat - o.lat) * mpd.y()});
        const bool point = xy.size() == 1;
        geo::GeomPtr shape = point ? test::point(m_ctx, xy[0]) : test::line(m_ctx, xy);
        const double width = point ? coast::structure_point_radius_m : coast::structure_line_half_width_m;
        geo::GeomPtr buffer = test::check(m_ctx, GEOSBuffer_r(m_ctx, shape.get(), width / std::cos(std::numbers::pi / 32), 8), "buffer");
        std::vector<std::vector<std::vector<XY>>> polys;
        geo::collect_polygons(m_ctx, buffer.get(), polys);
        if (polys.size() != 1) throw std::runtime_error("a structure's buffer is not one polygon");
        for (auto& ring : polys[0])
            for (XY& p : ring) {
                p = m_frame.forward(LonLat{o.lon + p.x / mpd.x(), o.lat + p.y / mpd.y()});
                m_box.extend(p);
            }
        return test::polygon(m_ctx, polys[0]);
    }

    /// docs/method.md: 16 vertices at radius / cos(pi / 16), counter-clockwise from east,
    /// turned into degrees with the metres per degree at the danger's latitude.
    std::vector<XY> danger_polygon(const OGRPoint& p, double radius_m) {
        const Eigen::Vector2d mpd = geo::metres_per_degree(p.getY());
        const double r = radius_m / std::cos(std::numbers::pi / 16);
        std::vector<XY> ring;
        for (int k = 0; k < 16; ++k) {
            const double a = 2 * std::numbers::pi * k / 16;
            ring.push_back(m_frame.forward(LonLat{p.getX() + r * std::cos(a) / mpd.x(), p.getY() + r * std::sin(a) / mpd.y()}));
            m_box.extend(ring.back());
        }
        ring.push_back(ring.front());
        return ring;
    }

    geo::GeosContext m_ctx;
    const geo::LocalFrame& m_frame;
    std::vector<Feature> m_features;
    std::vector<XY> m_vertices;
    geo::Box m_box;  // of the feature being read
    int m_repaired = 0;
};

struct Disagreements {
    int poses = 0, collisions = 0, flag = 0, clearance = 0, hit = 0, ties = 0;
    double worst_clearance_error = 0;
};

/// Distance between two boxes (0 when they meet).
double box_distance(const geo::Box& a, const geo::Box& b) {
    const double dx = std::max({0.0, a.minx - b.maxx, b.minx - a.maxx}), dy = std::max({0.0, a.miny - b.maxy, b.miny - a.maxy});
    return std::hypot(dx, dy);
}

/// Random poses near the hazards and anywhere in the grid, checked by the detector and by
/// GEOS on every feature (prepared) that may be nearest: collision, clearance and what was hit.
/// Random poses checked at `limit_m` on grid `g` (one grid for every limit), against GEOS on
/// the chart's features shallower than the limit.
Disagreements compare_with_geos(const grid::CoastGrid& g, double limit_m, int n_poses, const std::string& chart = cut(),
                                std::uint64_t seed = 4242) {
    const HazardOracle oracle(chart, limit_m, 10.0, g.frame());
    const auto& features = oracle.features();
    const hull::Hull hull = hull::Hull::from_dimensions({90, 30, 14, 16}, "test ship");
    const check::Detector det(g, hull, limit_m);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    const auto& vs = oracle.vertices();
    const geo::Box ext = g.extent();
    Disagreements d;
    for (int k = 0; k < n_poses; ++k) {
        XY pos;
        if (k % 10 == 0) {
            pos = {ext.minx + unit(rng) * (ext.maxx - ext.minx), ext.miny + unit(rng) * (ext.maxy - ext.miny)};
        } else {
            const XY v = vs[rng() % vs.size()];
            const double r = (k % 3 == 0 ? 5.0 : 4.0 * hull.radius()) * unit(rng), a = 2 * std::numbers::pi * unit(rng);
            pos = v + XY{r * std::cos(a), r * std::sin(a)};
        }
        const double heading = 360 * unit(rng);
        const check::LocalPose pose = check::place(g.frame(), check::Pose{g.frame().inverse(pos), heading});
        const std::vector<XY> outline = check::hull_outline(hull, pose);
        const geo::GeomPtr hp = oracle.hull_polygon(outline);
        const check::Contact c = det.check(pose, {INFINITY, false});
        ++d.poses;
        // Features by the distance of their boxes from the hull's; those whose box lies
        // farther than the least distance found cannot be nearest (nor touch).
        geo::Box hb;
        for (const XY& q : outline) hb.extend(q);
        std::vector<std::pair<double, std::size_t>> order;
        for (std::size_t i = 0; i < features.size(); ++i) order.push_back({box_distance(hb, features[i].box), i});
        std::sort(order.begin(), order.end());
        std::vector<double> dist(features.size(), INFINITY);
        bool geos_hit = false;
        double least = INFINITY;
        for (const auto& [box_d, i] : order) {
            if (box_d > least + 1e-3) break;
            const bool touches = box_d == 0 && oracle.intersects(features[i], hp.get());
            geos_hit = geos_hit || touches;
            dist[i] = touches ? 0.0 : oracle.distance(features[i], hp.get());
            least = std::min(least, dist[i]);
        }
        d.collisions += geos_hit;
        if (c.collision != geos_hit) {
            ++d.flag;
            ADD_FAILURE() << "limit " << limit_m << " pose " << k << " at (" << pos.x << ", " << pos.y << ") heading " << heading
                          << ": detector collision=" << c.collision << ", GEOS " << geos_hit;
            continue;
        }
        const double best = *std::min_element(dist.begin(), dist.end());
        if (!geos_hit) {
            const double err = std::fabs(best - c.clearance_m);
            d.worst_clearance_error = std::max(d.worst_clearance_error, err);
            if (!(err <= 1e-3)) {
                ++d.clearance;
                ADD_FAILURE() << "limit " << limit_m << " pose " << k << " clearance " << c.clearance_m << " vs GEOS " << best;
                continue;
            }
        }
        // What was hit: a feature with the reported kind, danger and depth must touch the hull
        // (collision) or lie at the least distance (clearance), within 1 mm.
        if (c.polyline >= g.polyline_count()) {
            ++d.hit;
            ADD_FAILURE() << "pose " << k << ": no polyline reported";
            continue;
        }
        const coast::Hazard& h = g.hazard(c.polyline);
        bool found = false;
        int nearest = 0;
        for (std::size_t i = 0; i < dist.size(); ++i) {
            if (dist[i] > best + 1e-3) continue;
            ++nearest;
            const auto& f = features[i];
            found = found || (f.kind == h.kind && f.danger == h.danger && same_depth(f.depth_m, h.depth_m));
        }
        d.ties += nearest > 1;
        if (!found) {
            ++d.hit;
            ADD_FAILURE() << "limit " << limit_m << " pose " << k << " at (" << pos.x << ", " << pos.y << ") heading " << heading
                          << ": detector says it hit " << coast::to_string(h.kind) << " " << coast::to_string(h.danger) << " "
                          << h.depth_m << ", no such feature is nearest by GEOS";
        }
    }
    return d;
}

Disagreements compare_with_geos(double limit_m, double cell_m, int n_poses, const std::string& chart = cut()) {
    return compare_with_geos(grid_for(std::nullopt, cell_m, chart), limit_m, n_poses, chart);
}

TEST(HazardVsGeos, RandomPosesAgreeForALimitOf2Point5Metres) {
    const Disagreements d = compare_with_geos(2.5, 150, 10000);
    EXPECT_EQ(d.flag, 0);
    EXPECT_EQ(d.clearance, 0);
    EXPECT_EQ(d.hit, 0);
    EXPECT_GT(d.collisions, 3000);
    EXPECT_LT(d.collisions, 8500);
    std::printf("limit 2.5 m: %d poses, %d collisions, %d disagreements (flag %d, clearance %d, hit %d), %d ties, worst clearance error %.3g m\n",
                d.poses, d.collisions, d.flag + d.clearance + d.hit, d.flag, d.clearance, d.hit, d.ties, d.worst_clearance_error);
}

TEST(HazardVsGeos, RandomPosesAgreeForALimitOf6Metres) {
    const Disagreements d = compare_with_geos(6.0, 400, 10000);
    EXPECT_EQ(d.flag, 0);
    EXPECT_EQ(d.clearance, 0);
    EXPECT_EQ(d.hit, 0);
    EXPECT_GT(d.collisions, 3000);
    EXPECT_LT(d.collisions, 8500);
    std::printf("limit 6 m: %d poses, %d collisions, %d disagreements (flag %d, clearance %d, hit %d), %d ties, worst clearance error %.3g m\n",
                d.poses, d.collisions, d.flag + d.clearance + d.hit, d.flag, d.clearance, d.hit, d.ties, d.worst_clearance_error);
}

/// The whole US4MD81M cell (updates applied) from the project's shared data, when it is there:
/// $SHOAL_SHARED_DATA, or ../shared/data beside the repository.
TEST(HazardVsGeos, WholeSharedS57CellAgrees) {
    std::filesystem::path shared = std::getenv("SHOAL_SHARED_DATA")
                                       ? std::filesystem::path(std::getenv("SHOAL_SHARED_DATA"))
                                       : std::filesystem::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().parent_path() / "shared" / "data";
    const std::filesystem::path cell = shared / "coast" / "s57" / "US4MD81M" / "US4MD81M.000";
    if (!std::filesystem::exists(cell)) GTEST_SKIP() << cell << " not found (set SHOAL_SHARED_DATA)";
    const Disagreements d = compare_with_geos(4.0, 500, 10000, cell.string());
    EXPECT_EQ(d.flag, 0);
    EXPECT_EQ(d.clearance, 0);
    EXPECT_EQ(d.hit, 0);
    std::printf("US4MD81M, limit 4 m: %d poses, %d collisions, %d disagreements (flag %d, clearance %d, hit %d), %d ties, worst clearance error %.3g m\n",
                d.poses, d.collisions, d.flag + d.clearance + d.hit, d.flag, d.clearance, d.hit, d.ties, d.worst_clearance_error);
}

track::Track track_through(const geo::LocalFrame& frame, const std::vector<XY>& pts);

/// One grid, many vessels: random limiting depths (and one exactly at a charted depth),
/// each checked on the same grid against GEOS on the features shallower than it.
TEST(HazardVsGeos, RandomLimitsOnOneGridAgree) {
    const grid::CoastGrid g = grid_for(std::nullopt, 300);
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> depth(-1.0, 12.0);
    int poses = 0, collisions = 0;
    std::set<std::size_t> levels;
    for (int k = 0; k < 8; ++k) {
        const double limit = k == 0 ? 3.6 : k == 1 ? 5.4 : depth(rng);
        SCOPED_TRACE("limit " + std::to_string(limit));
        levels.insert(g.level_of(limit));
        const Disagreements d = compare_with_geos(g, limit, 1000, cut(), 100 + static_cast<std::uint64_t>(k));
        EXPECT_EQ(d.flag, 0);
        EXPECT_EQ(d.clearance, 0);
        EXPECT_EQ(d.hit, 0);
        poses += d.poses;
        collisions += d.collisions;
    }
    EXPECT_GE(levels.size(), 5u) << "the limits span several levels of charted depth";
    EXPECT_GT(collisions, poses / 5);
    std::printf("one grid, 8 limits: %d poses, %d collisions, %zu levels of %zu\n", poses, collisions, levels.size(),
                g.charted_depths().size() + 1);
}

TEST(HazardLevels, ALevelGridEqualsAGridBuiltFromItsHazardsAlone) {
    // The grid for a limit, derived from the grid of everything, is the grid built from only
    // the polylines that are hazards at that limit (cells, segments, windings), as a build
    // with a one-depth import gave before.
    const coast::Coastline all = coast::import_coastline({cut()});
    const geo::LocalFrame frame =
        geo::LocalFrame::transverse_mercator({(all.min.lon + all.max.lon) / 2, (all.min.lat + all.max.lat) / 2});
    const std::vector<coast::LocalPolyline> lines = coast::project(all, frame);
    const grid::CoastGrid g = grid::CoastGrid::build(lines, frame, 250);
    for (std::optional<double> limit : {std::optional<double>(), std::optional<double>(1.0), std::optional<double>(3.7),
                                        std::optional<double>(9.0)}) {
        SCOPED_TRACE(limit ? std::to_string(*limit) : "land only");
        const grid::CoastGrid& view = g.for_depth(limit);
        EXPECT_EQ(&view, &g.for_depth(limit)) << "built once, then kept";
        // The polylines that are hazards at that limit, alone in a grid of their own.
        std::vector<coast::LocalPolyline> kept;
        for (const auto& l : lines) {
            const bool hazard = l.hazard.kind == HazardKind::land ||
                                (limit && (std::isnan(l.hazard.depth_m) || l.hazard.depth_m < *limit));
            if (hazard) kept.push_back(l);
        }
        const grid::CoastGrid alone = grid::CoastGrid::build(kept, frame, 250);  // its own extent and cells
        EXPECT_LE(view.segment_count(), g.segment_count());
        int differ = 0;
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> ux(g.extent().minx, g.extent().maxx), uy(g.extent().miny, g.extent().maxy);
        std::uniform_real_distribution<double> uh(0, 360);
        const hull::Hull ship = hull::Hull::from_dimensions({60, 20, 8, 8}, "ship");
        const check::Detector on_view(view, ship), on_alone(alone, ship, limit);  // alone: everything it holds
        double worst = 0;
        for (int k = 0; k < 5000; ++k) {
            const XY p{ux(rng), uy(rng)};
            differ += view.is_land(p) != alone.is_land(p);
            const check::LocalPose pose = check::LocalPose::at(p, uh(rng));
            const check::Contact c1 = on_view.check(pose, {400, false}), c2 = on_alone.check(pose, {400, false});
            if (!c2.covered) continue;
            differ += c1.collision != c2.collision;
            if (!c1.collision && std::isfinite(c2.clearance_m)) worst = std::max(worst, std::fabs(c1.clearance_m - c2.clearance_m));
            else differ += std::isfinite(c1.clearance_m) != std::isfinite(c2.clearance_m);
        }
        EXPECT_LT(worst, 1e-6);
        EXPECT_EQ(differ, 0);
    }
    EXPECT_EQ(&g.for_depth(1000.0), &g) << "a limit under which every hazard lies is the grid itself";
}

TEST(HazardLevels, AGridFileOfVersion2IsRefused) {
    std::vector<char> bytes = grid::GridFile::serialize(one_grid());
    std::vector<char> old = bytes;
    const std::uint32_t v2 = 2;
    std::memcpy(old.data() + 8, &v2, sizeof v2);
    EXPECT_THAT([&] { grid::GridFile::parse(old, "old.shoalgrid"); },
                ThrowsMessage<InputError>(HasSubstr("has format version 2; this shoal reads version " + std::to_string(grid::grid_format_version) +
                                                     ": rebuild it with shoal import")));
    // A level out of range (the last land level), the checksum made right: damaged, said so.
    const std::uint16_t bad = 0xFFFF;
    std::memcpy(bytes.data() + bytes.size() - sizeof bad, &bad, sizeof bad);
    const std::uint64_t sum = XXH3_64bits(bytes.data() + 32, bytes.size() - 32);
    std::memcpy(bytes.data() + 24, &sum, sizeof sum);
    EXPECT_THAT([&] { grid::GridFile::parse(bytes, "bad.shoalgrid"); }, ThrowsMessage<InputError>(HasSubstr("land level out of range")));
}

/// Two vessels of different draughts in one audit, on one grid: the deep one grounds in the
/// 3.6 m area where the shallow one floats; GEOS on the depth areas shallower than each
/// vessel's limit says the same of the hull at the event and along the shallow one's path.
TEST(HazardFleet, TwoDraughtsInOneRunFromOneGrid) {
    const grid::CoastGrid& g = one_grid();
    auto make = [&](const std::string& id, double draught) {
        std::vector<XY> local{g.frame().forward(in_depth_5_4), g.frame().forward(in_depth_3_6)};
        track::Track t = track_through(g.frame(), local);
        t.id = id;
        t.draught_m = draught;
        t.draught_source = "test";
        return t;
    };
    audit::AuditOptions o;
    o.ukc_m = 0.5;
    o.jobs = 2;
    const hull::Hull dflt = hull::Hull::from_dimensions({45, 15, 5, 5}, "default");  // no draught
    const audit::AuditResult r = audit::audit_tracks({make("shallow", 3.0), make("deep", 4.0), make("unknown", NAN)}, g, dflt, "--dims", o);
    ASSERT_EQ(r.tracks.size(), 3u);
    const audit::TrackResult& shallow = r.tracks[0];
    const audit::TrackResult& deep = r.tracks[1];
    EXPECT_EQ(shallow.summary.limiting_depth_m, 3.5);
    EXPECT_EQ(shallow.summary.limiting_depth_source, "vessel_draught");
    EXPECT_EQ(deep.summary.limiting_depth_m, 4.5);
    EXPECT_TRUE(std::isnan(r.tracks[2].summary.limiting_depth_m));
    EXPECT_EQ(r.tracks[2].summary.limiting_depth_source, "land_only");
    EXPECT_THAT(r.warnings, ::testing::Contains(HasSubstr("1 of 3 tracks have no draught of their own and were checked against land only")));
    EXPECT_EQ(shallow.summary.groundings, 0u);
    ASSERT_EQ(deep.summary.groundings, 1u);
    const audit::Event& e = deep.events.front();
    EXPECT_EQ(e.kind, audit::EventKind::grounding);
    EXPECT_EQ(e.hit, HazardKind::shallow);
    EXPECT_EQ(e.charted_depth_m, 3.6);

    // GEOS: the deep vessel's hull at first contact touches a feature shallower than 4.5 m
    // (within a millimetre: the contact is refined by bisection), that feature is the 3.6 m area.
    const HazardOracle deep_oracle(cut(), 4.5, 10.0, g.frame());
    std::vector<XY> ring;
    for (const LonLat& q : e.hull) ring.push_back(g.frame().forward(q));
    ring.pop_back();
    const geo::GeomPtr hp = deep_oracle.hull_polygon(ring);
    double least = INFINITY;
    double least_depth = NAN;
    for (const auto& f : deep_oracle.features()) {
        const double d = deep_oracle.distance(f, hp.get());
        if (d < least) least = d, least_depth = f.depth_m;
    }
    EXPECT_LT(least, 1e-3);
    EXPECT_EQ(least_depth, 3.6);
    // GEOS: the shallow vessel's hull, every 5 m along the same path, touches nothing shallower than 3.5 m.
    const HazardOracle shallow_oracle(cut(), 3.5, 10.0, g.frame());
    const hull::Hull& hull = dflt;
    const XY a = g.frame().forward(in_depth_5_4), b = g.frame().forward(in_depth_3_6);
    const double heading = std::fmod(std::atan2(b.x - a.x, b.y - a.y) * 180 / std::numbers::pi + 360, 360);
    const int n = static_cast<int>(geo::distance(a, b) / 5);
    int touching = 0;
    for (int k = 0; k <= n; ++k) {
        const XY p = a + (static_cast<double>(k) / n) * (b - a);
        const check::LocalPose pose = check::place(g.frame(), check::Pose{g.frame().inverse(p), heading});
        const geo::GeomPtr h = shallow_oracle.hull_polygon(check::hull_outline(hull, pose));
        for (const auto& f : shallow_oracle.features()) touching += shallow_oracle.intersects(f, h.get());
    }
    EXPECT_EQ(touching, 0);
}

// ---------------------------------------------------------------- cache

TEST(HazardCache, RoundTripKeepsTheHazardTableAndLevelsAndTheKeyIgnoresTheLimit) {
    test::TempDir dir;
    const grid::CoastGrid g = grid_for(4.0);
    EXPECT_EQ(g.source().limiting_depth_m, 4.0);
    EXPECT_EQ(g.source().danger_radius_m, 10.0);
    EXPECT_GT(g.source().shallow_polylines, 0u);
    EXPECT_GT(g.source().danger_polylines, 0u);
    EXPECT_GT(g.charted_depths().size(), 3u);
    grid::GridFile::save(g, dir.file("h.shoalgrid"));
    const grid::CoastGrid back = grid::GridFile::load(dir.file("h.shoalgrid"));
    EXPECT_TRUE(back == g);
    ASSERT_EQ(back.polyline_count(), g.polyline_count());
    for (std::uint32_t k = 0; k < g.polyline_count(); ++k) {
        EXPECT_EQ(back.hazard(k).kind, g.hazard(k).kind);
        EXPECT_EQ(back.hazard(k).danger, g.hazard(k).danger);
        EXPECT_TRUE(same_depth(back.hazard(k).depth_m, g.hazard(k).depth_m));
    }
    // Every level of the loaded grid is the same grid as the built one's.
    for (double limit : {0.5, 3.7, 6.0})
        EXPECT_TRUE(back.for_depth(limit) == g.for_depth(limit)) << limit;
    EXPECT_EQ(back.source().shallow_polylines, g.source().shallow_polylines);
    EXPECT_EQ(back.source().unknown_depth, g.source().unknown_depth);
    EXPECT_TRUE(std::isnan(grid_for(std::nullopt).source().limiting_depth_m));

    // The cache key: the danger radius and the depth field change it; the limit does not
    // (one grid serves every draught).
    std::set<std::uint64_t> keys;
    auto key = [&](coast::ImportOptions o) { keys.insert(grid::fingerprint_sources({cut()}, o, "", 300)); };
    key(with_limit(std::nullopt));
    key(with_limit(4.0));
    key(with_limit(4.5));
    EXPECT_EQ(keys.size(), 1u);
    coast::ImportOptions o = with_limit(4.0);
    o.danger_radius_m = 20;
    key(o);
    o = with_limit(4.0);
    o.depth_field = "DEPTH";
    key(o);
    EXPECT_EQ(keys.size(), 3u);

    // load_or_build: one build, reused for every limit; the default limit is the request's.
    grid::BuildRequest r;
    r.cell_m = 300;
    r.cache_dir = dir.file("cache");
    grid::LoadReport rep;
    r.import.limiting_depth_m = 4.0;
    grid::load_or_build({cut()}, r, &rep);
    EXPECT_EQ(rep.how, "built and cached");
    r.import.limiting_depth_m = 5.0;
    const grid::CoastGrid g5 = grid::load_or_build({cut()}, r, &rep);
    EXPECT_EQ(rep.how, "reused cached grid");
    EXPECT_EQ(g5.source().limiting_depth_m, 5.0);
    r.import.limiting_depth_m = std::nullopt;
    const grid::CoastGrid g0 = grid::load_or_build({cut()}, r, &rep);
    EXPECT_EQ(rep.how, "reused cached grid");
    EXPECT_TRUE(std::isnan(g0.source().limiting_depth_m));
}

// ---------------------------------------------------------------- events

/// A track through points given in the grid's local metres, 5 m/s, headings along the legs.
track::Track track_through(const geo::LocalFrame& frame, const std::vector<XY>& pts) {
    track::Track t;
    t.id = "hand-made";
    t.file = "hand-made";
    double time = 1.7e9;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (i > 0) time += geo::distance(pts[i - 1], pts[i]) / 5.0;
        const XY dir = i + 1 < pts.size() ? pts[i + 1] - pts[i] : pts[i] - pts[i - 1];
        track::Fix f;
        f.time_s = time;
        f.position = frame.inverse(pts[i]);
        f.line = i + 2;
        f.heading_used_deg = std::fmod(std::atan2(dir.x, dir.y) * 180 / std::numbers::pi + 360, 360);
        f.heading_source = track::HeadingSource::cog;
        t.fixes.push_back(f);
    }
    return t;
}

std::vector<audit::Event> events_of(const grid::CoastGrid& g, const std::vector<LonLat>& pts, double margin_m = 50) {
    std::vector<XY> local;
    for (const LonLat& p : pts) local.push_back(g.frame().forward(p));
    audit::SweepOptions o;
    o.margin_m = margin_m;
    return audit::sweep_track(track_through(g.frame(), local), g.frame(), audit::DetectorChecker(g, ship_with_draught(4.5)), o).events;
}

LonLat offset(LonLat p, double east_m, double north_m) {
    const Eigen::Vector2d mpd = geo::metres_per_degree(p.lat);
    return {p.lon + east_m / mpd.x(), p.lat + north_m / mpd.y()};
}

TEST(HazardEvents, EventsSayWhatWasHit) {
    // Draught 4.5 m + 0.5 m under-keel clearance: limiting depth 5 m.
    const grid::CoastGrid g = grid_for(coast::limiting_depth(std::nullopt, 4.5, 0.5));
    ASSERT_EQ(g.source().limiting_depth_m, 5.0);

    // Over the wreck (no sounding), in 5.4 m water that is no hazard for this ship.
    auto ev = events_of(g, {offset(wreck_unknown, 0, -300), offset(wreck_unknown, 0, 300)});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].kind, audit::EventKind::grounding);
    EXPECT_EQ(ev[0].hit, HazardKind::danger);
    EXPECT_EQ(ev[0].danger, DangerKind::wreck);
    EXPECT_TRUE(std::isnan(ev[0].charted_depth_m));

    // Past it 25 m to the east: a close pass, and it says what it passed.
    ev = events_of(g, {offset(wreck_unknown, 25, -300), offset(wreck_unknown, 25, 300)});
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].kind, audit::EventKind::close_pass);
    EXPECT_EQ(ev[0].hit, HazardKind::danger);
    EXPECT_EQ(ev[0].danger, DangerKind::wreck);
    EXPECT_NEAR(ev[0].min_clearance_m, 20 - 10 / std::cos(std::numbers::pi / 16), 0.05);

    // From the 5.4 m area into the 3.6 m area: aground in shallow water of charted depth 3.6 m.
    ev = events_of(g, {in_depth_5_4, in_depth_3_6});
    ASSERT_FALSE(ev.empty());
    EXPECT_EQ(ev[0].kind, audit::EventKind::grounding);
    EXPECT_EQ(ev[0].hit, HazardKind::shallow);
    EXPECT_EQ(ev[0].charted_depth_m, 3.6);
    EXPECT_EQ(ev[0].danger, DangerKind::none);

    // Westward onto the shore south of Annapolis: against land only, the hull hits land; with
    // the hazards it is aground from the start, in the drying-to-1.8 m area off the shore.
    const std::vector<LonLat> ashore = {{-76.4560, 38.90855}, {-76.4651, 38.90855}};
    const grid::CoastGrid land_only = grid_for(std::nullopt);
    ev = events_of(land_only, ashore);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].kind, audit::EventKind::grounding);
    EXPECT_EQ(ev[0].hit, HazardKind::land);
    EXPECT_TRUE(std::isnan(ev[0].charted_depth_m));
    ev = events_of(g, ashore);
    ASSERT_EQ(ev.size(), 1u);
    EXPECT_EQ(ev[0].kind, audit::EventKind::contact_at_start) << "in contact at the first fix: not seen begin";
    EXPECT_EQ(ev[0].hit, HazardKind::shallow);
    EXPECT_EQ(ev[0].charted_depth_m, 0.0);
    EXPECT_EQ(ev[0].start_s, 1.7e9) << "aground at the first fix";
}

// ---------------------------------------------------------------- the executable

using test::Outcome;

Outcome shoal_run(const test::TempDir& dir, const std::string& args) { return test::run_shoal(args, dir.file("cache"), dir.file("stderr.txt")); }

TEST(HazardCli, CheckReportsWhatWasHitAndTheReportValidates) {
    test::TempDir dir;
    const std::string ship = dir.file("ship.json"), tracks = dir.file("tracks.csv");
    std::ofstream(ship) << R"({"name": "Test Ship", "a": 45, "b": 15, "c": 5, "d": 5, "draught": 4.5})";
    {
        std::ofstream out(tracks);
        out << "mmsi,timestamp,lat,lon,heading\n";
        const LonLat w0 = offset(wreck_unknown, 0, -300), w1 = offset(wreck_unknown, 0, 300);
        char row[200];
        std::snprintf(row, sizeof row, "1,2024-05-01T10:00:00Z,%.7f,%.7f,0\n1,2024-05-01T10:02:00Z,%.7f,%.7f,0\n", w0.lat, w0.lon, w1.lat, w1.lon);
        out << row;
        std::snprintf(row, sizeof row, "2,2024-05-01T10:00:00Z,%.7f,%.7f,263\n2,2024-05-01T10:04:00Z,%.7f,%.7f,263\n", in_depth_5_4.lat,
                      in_depth_5_4.lon, in_depth_3_6.lat, in_depth_3_6.lon);
        out << row;
    }
    const std::string report = dir.file("r.geojson");
    const Outcome r = shoal_run(dir, "check --world simulated --coast '" + cut() + "' --ship '" + ship + "' --ukc 0.5 --cell 300 '" + tracks +
                                         "' -o '" + report + "'");
    ASSERT_EQ(r.status, 1) << r.err << r.out;
    EXPECT_THAT(r.err, HasSubstr("limiting depth 5.00 m (ship file draught 4.50 m + under-keel clearance 0.50 m)"));
    const auto doc = nlohmann::json::parse(std::string(test::read_bytes(report).data(), test::read_bytes(report).size()));
    EXPECT_EQ(doc["shoal"]["limiting_depth_m"], 5.0);
    EXPECT_EQ(doc["shoal"]["limiting_depth_source"], "ship_draught");
    EXPECT_EQ(doc["shoal"]["ukc_m"], 0.5);
    for (const auto& t : doc["shoal"]["tracks"]) {
        EXPECT_EQ(t["limiting_depth_m"], 5.0);
        EXPECT_EQ(t["limiting_depth_source"], "ship_draught");
    }
    std::map<std::string, nlohmann::json> first;  // track -> properties of its first event
    for (const auto& f : doc["features"])
        if (!first.count(f["properties"]["track"])) first[f["properties"]["track"]] = f["properties"];
    ASSERT_EQ(first.size(), 2u);
    EXPECT_EQ(first["1"]["hit"], "danger");
    EXPECT_EQ(first["1"]["danger"], "wreck");
    EXPECT_TRUE(first["1"]["charted_depth_m"].is_null());
    EXPECT_EQ(first["2"]["hit"], "shallow");
    EXPECT_EQ(first["2"]["danger"], "");
    EXPECT_EQ(first["2"]["charted_depth_m"], 3.6);
    EXPECT_THAT(first["2"]["label"].get<std::string>(), HasSubstr("aground shallow 3.6 m "));
    EXPECT_THAT(first["1"]["label"].get<std::string>(), HasSubstr("aground wreck "));

    // The report matches its schema (Debian's python3-jsonschema).
    const std::string schema = std::filesystem::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().string() +
                               "/schemas/report.schema.json";
    const std::string validate = "/usr/bin/python3 -c \"import json,sys,jsonschema; jsonschema.validate(json.load(open(sys.argv[1])), "
                                 "json.load(open(sys.argv[2])))\" '" + report + "' '" + schema + "'";
    EXPECT_EQ(std::system(validate.c_str()), 0);

    // The GeoPackage has the same fields.
    const std::string gpkg = dir.file("r.gpkg");
    ASSERT_EQ(shoal_run(dir, "check --world simulated --coast '" + cut() + "' --ship '" + ship + "' --ukc 0.5 --cell 300 '" + tracks + "' -o '" + gpkg + "'").status, 1);
    GDALDatasetUniquePtr ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(ds);
    OGRLayer* events = ds->GetLayerByName("events");
    ASSERT_TRUE(events);
    std::set<std::string> hits;
    for (auto& f : *events) {
        hits.insert(f->GetFieldAsString("hit"));
        if (std::string(f->GetFieldAsString("hit")) == "shallow") {
            EXPECT_DOUBLE_EQ(f->GetFieldAsDouble("charted_depth_m"), 3.6);
        }
        if (std::string(f->GetFieldAsString("hit")) == "danger") {
            EXPECT_STREQ(f->GetFieldAsString("danger"), "wreck");
            EXPECT_FALSE(f->IsFieldSetAndNotNull(f->GetFieldIndex("charted_depth_m")));
        }
    }
    EXPECT_EQ(hits, (std::set<std::string>{"danger", "shallow"}));
}

TEST(HazardCli, ImportInfoAndProbeWithAHazardDepth) {
    test::TempDir dir;
    const std::string g = dir.file("h.shoalgrid");
    const Outcome imp = shoal_run(dir, "import '" + cut() + "' --hazard-depth 4 --cell 300 -o '" + g + "'");
    ASSERT_EQ(imp.status, 0) << imp.err;
    const Outcome info = shoal_run(dir, "info '" + g + "'");
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_THAT(info.out, HasSubstr("default 4.00 m (--hazard-depth)"));
    const std::string poses = dir.file("poses.csv");
    char row[120];
    std::snprintf(row, sizeof row, "%.7f,%.7f,30\n", in_depth_3_6.lat, in_depth_3_6.lon);
    std::ofstream(poses) << row;
    // Built for 4 m: the 3.6 m area is a hazard. From the chart itself at 3 m: it is not.
    const Outcome deep = shoal_run(dir, "probe --coast '" + g + "' --dims 45,15,5,5 '" + poses + "'");
    ASSERT_EQ(deep.status, 0) << deep.err;
    EXPECT_THAT(deep.out, HasSubstr(",30.0,1,0.000"));
    const Outcome shallow = shoal_run(dir, "probe --coast '" + cut() + "' --hazard-depth 3 --cell 300 --dims 45,15,5,5 '" + poses + "'");
    ASSERT_EQ(shallow.status, 0) << shallow.err;
    EXPECT_THAT(shallow.out, HasSubstr(",30.0,0,"));
    // The same grid file at another limit (was: a warning that the grid served one depth only).
    const Outcome at3 = shoal_run(dir, "probe --coast '" + g + "' --hazard-depth 3 --dims 45,15,5,5 '" + poses + "'");
    ASSERT_EQ(at3.status, 0) << at3.err;
    EXPECT_THAT(at3.out, HasSubstr(",30.0,0,"));
    EXPECT_THAT(deep.err, HasSubstr("limiting depth 4.00 m (the grid's default"));
}

/// `shoal check` of a fleet with two draughts (a draught column) from one grid: the deep
/// vessel grounds in the 3.6 m area, the shallow one floats; each track says its limit.
TEST(HazardCli, FleetWithTwoDraughtsInOneCheck) {
    test::TempDir dir;
    const std::string tracks = dir.file("fleet.csv");
    {
        std::ofstream out(tracks);
        out << "mmsi,timestamp,lat,lon,heading,draught\n";
        char row[240];
        for (const auto& [id, draught] : {std::pair<int, double>{1, 3.0}, {2, 4.0}}) {
            std::snprintf(row, sizeof row, "%d,2024-05-01T10:00:00Z,%.7f,%.7f,263,%.1f\n%d,2024-05-01T10:04:00Z,%.7f,%.7f,263,%.1f\n", id,
                          in_depth_5_4.lat, in_depth_5_4.lon, draught, id, in_depth_3_6.lat, in_depth_3_6.lon, draught);
            out << row;
        }
    }
    const std::string report = dir.file("fleet.geojson");
    const Outcome r = shoal_run(dir, "check -v --world simulated --coast '" + cut() + "' --dims 45,15,5,5 --ukc 0.5 --cell 300 '" + tracks + "' -o '" + report + "'");
    ASSERT_EQ(r.status, 1) << r.err << r.out;
    EXPECT_THAT(r.err, HasSubstr("built and cached"));
    const auto bytes = test::read_bytes(report);
    const auto doc = nlohmann::json::parse(std::string(bytes.data(), bytes.size()));
    std::map<std::string, nlohmann::json> tr;
    for (const auto& t : doc["shoal"]["tracks"]) tr[t["track"]] = t;
    ASSERT_EQ(tr.size(), 2u);
    EXPECT_EQ(tr["1"]["limiting_depth_m"], 3.5);
    EXPECT_EQ(tr["2"]["limiting_depth_m"], 4.5);
    EXPECT_EQ(tr["1"]["limiting_depth_source"], "vessel_draught");
    EXPECT_EQ(tr["1"]["groundings"], 0);
    EXPECT_EQ(tr["2"]["groundings"], 1);
    EXPECT_TRUE(doc["shoal"]["limiting_depth_m"].is_null()) << "the default hull has no draught";
    EXPECT_EQ(doc["shoal"]["limiting_depth_source"], "land_only");
    int shallow_groundings = 0;
    for (const auto& f : doc["features"])
        if (f["properties"]["kind"] == "grounding") {
            EXPECT_EQ(f["properties"]["track"], "2");
            shallow_groundings += f["properties"]["hit"] == "shallow" && f["properties"]["charted_depth_m"] == 3.6;
        }
    EXPECT_EQ(shallow_groundings, 1);
    const std::string schema = std::filesystem::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().string() +
                               "/schemas/report.schema.json";
    const std::string validate = "/usr/bin/python3 -c \"import json,sys,jsonschema; jsonschema.validate(json.load(open(sys.argv[1])), "
                                 "json.load(open(sys.argv[2])))\" '" + report + "' '" + schema + "'";
    EXPECT_EQ(std::system(validate.c_str()), 0);
    // Run again: the cached grid serves it (no second build), the same report.
    const Outcome again = shoal_run(dir, "check -v --coast '" + cut() + "' --dims 45,15,5,5 --ukc 0.5 --cell 300 '" + tracks + "' -o '" +
                                             dir.file("again.geojson") + "'");
    EXPECT_THAT(again.err, HasSubstr("reused cached grid"));
}

}  // namespace
}  // namespace shoal
