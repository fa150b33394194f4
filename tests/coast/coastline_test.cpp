// Tests of coast::import_coastline on real and hand-made files in tests/data/coast.
//
// Expected counts were obtained independently of shoal, with GDAL's own tools on the same
// files (GDAL 3.6.2):
//   ogrinfo -so -al FILE                       -> feature counts, extents
//   /usr/bin/python3 + osgeo.ogr, walking every geometry: polygon parts, rings, line parts,
//   vertices (OGRGeometry.GetPointCount of every ring and line, closing point included),
//   point geometries and null/empty geometries of each layer.
// Orientation and land side are checked with GEOS against the polygons as OGR reads them.

#include <shoal/coast/coastline.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "geo/geos_context.hpp"
#include <shoal/geo/local_frame.hpp>
#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::UsageError;
using shoal::coast::Coastline;
using shoal::coast::import_coastline;
using shoal::coast::ImportOptions;
using shoal::coast::LayerStats;
using shoal::coast::Polyline;
using shoal::geo::LonLat;
using shoal::geo::XY;
using testing::AllOf;
using testing::Contains;
using testing::HasSubstr;
using testing::Not;
using testing::ThrowsMessage;
namespace t = shoal::test;

// uk_solent_land.geojson (GSHHG, copied whole): 13 features, 13 polygons of one ring each,
// 1977 vertices, no holes, no points, no empty geometries.
constexpr std::uint64_t solent_land_features = 13;
constexpr std::uint64_t solent_land_vertices = 1977;
// uk_solent_shoreline.geojson: 12 features, 12 LineStrings, 1973 vertices.
constexpr std::uint64_t solent_shore_features = 12;
constexpr std::uint64_t solent_shore_vertices = 1973;
// gr_saronic_piraeus_land.shp: 66 features, 66 single-ring polygons, 4277 vertices.
constexpr std::uint64_t piraeus_features = 66;
constexpr std::uint64_t piraeus_vertices = 4277;
// US4MD81M_cut.000 (S-57, updates applied), as read by GDAL's S57 driver:
//   LNDARE: 17 features = 15 single-ring polygons (18054 vertices) + 2 points
//   COALNE: 137 features, 137 LineStrings, 6283 vertices
//   SLCONS: 151 features = 150 LineStrings (557 vertices) + 1 point
constexpr std::uint64_t s57_lndare_features = 17, s57_lndare_polygons = 15, s57_lndare_points = 2, s57_lndare_vertices = 18054;
constexpr std::uint64_t s57_coalne_features = 137, s57_coalne_vertices = 6283;
constexpr std::uint64_t s57_slcons_features = 151, s57_slcons_lines = 150, s57_slcons_points = 1, s57_slcons_vertices = 557;

std::string coast_file(const std::string& name) { return t::data_path("coast/" + name); }

/// Twice the signed area (shoelace) of a closed ring in lon/lat degrees^2; > 0 counter-clockwise.
double signed_area2(const std::vector<LonLat>& ring) {
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
        a += (ring[i].lon - ring[0].lon) * (ring[i + 1].lat - ring[0].lat) -
             (ring[i + 1].lon - ring[0].lon) * (ring[i].lat - ring[0].lat);
    return a;
}

std::vector<XY> as_xy(const std::vector<LonLat>& pts) {
    std::vector<XY> out;
    for (const auto& p : pts) out.push_back({p.lon, p.lat});
    return out;
}

const LayerStats& layer_named(const Coastline& c, const std::string& name) {
    for (const auto& l : c.layers)
        if (l.layer == name) return l;
    throw std::runtime_error("no layer " + name + " in the import");
}

std::size_t polylines_of_layer(const Coastline& c, const std::string& name) {
    std::size_t n = 0;
    for (const auto& p : c.polylines)
        if (c.layers.at(p.layer).layer == name) ++n;
    return n;
}

/// Every polygon-derived polyline is closed, has land on its left, and its orientation is
/// counter-clockwise for a shell and clockwise for a hole; checked against the polygons of
/// `layer` of `file` as OGR reads them:
///  - GEOS says the ring is counter-clockwise exactly when its shoelace area is positive;
///  - just left of the middle of its longest edge lies inside the OGR land, just right outside;
///  - the signed areas of all rings add up to GEOS's area of the OGR land.
void expect_land_on_the_left(const Coastline& c, const std::string& file, const std::string& layer) {
    shoal::geo::GeosContext geos;
    const auto polys = t::read_polygons_with_ogr(file, layer);
    std::vector<shoal::geo::GeomPtr> parts;
    for (const auto& p : polys) {
        std::vector<std::vector<XY>> rings;
        for (const auto& r : p.rings) rings.push_back(as_xy(r));
        parts.push_back(t::polygon(geos, rings));
    }
    const auto land = t::check(geos, GEOSUnaryUnion_r(geos, t::collection(geos, GEOS_GEOMETRYCOLLECTION, std::move(parts)).get()), "union");
    const auto prepared = t::prepare(geos, land.get());
    const GEOSPreparedGeometry* prep = prepared.get();
    double land_area = 0;
    GEOSArea_r(geos, land.get(), &land_area);

    double sum_area = 0;
    int checked = 0;
    for (const Polyline& pl : c.polylines) {
        if (c.layers.at(pl.layer).layer != layer || !pl.land_left) continue;
        ++checked;
        ASSERT_GE(pl.points.size(), 4u);
        EXPECT_EQ(pl.points.front(), pl.points.back()) << "ring of feature " << pl.fid << " is not closed";
        const double a2 = signed_area2(pl.points);
        sum_area += a2 / 2;
        // GEOS's orientation of the same ring agrees with the sign of the area.
        auto seq = t::sequence(geos, as_xy(pl.points));
        char ccw = 0;
        ASSERT_TRUE(GEOSCoordSeq_isCCW_r(geos, seq, &ccw));
        GEOSCoordSeq_destroy_r(geos, seq);
        EXPECT_EQ(ccw == 1, a2 > 0) << "feature " << pl.fid;
        // Land to the left of the longest edge, water to its right.
        std::size_t k_best = 0;
        double len_best = -1;
        for (std::size_t k = 0; k + 1 < pl.points.size(); ++k) {
            const double len = std::hypot(pl.points[k + 1].lon - pl.points[k].lon, pl.points[k + 1].lat - pl.points[k].lat);
            if (len > len_best) {
                len_best = len;
                k_best = k;
            }
        }
        const LonLat a = pl.points[k_best], b = pl.points[k_best + 1];
        const double eps = 1e-6 / len_best;  // about 0.1 m to either side, in degrees
        const XY mid{(a.lon + b.lon) / 2, (a.lat + b.lat) / 2};
        const XY left{mid.x - eps * (b.lat - a.lat), mid.y + eps * (b.lon - a.lon)};
        const XY right{mid.x + eps * (b.lat - a.lat), mid.y - eps * (b.lon - a.lon)};
        auto pl_left = t::point(geos, left), pl_right = t::point(geos, right);
        EXPECT_EQ(GEOSPreparedContains_r(geos, prep, pl_left.get()), 1) << "feature " << pl.fid << ": left of edge " << k_best << " is not land";
        EXPECT_EQ(GEOSPreparedContains_r(geos, prep, pl_right.get()), 0) << "feature " << pl.fid << ": right of edge " << k_best << " is land";
    }
    EXPECT_GT(checked, 0);
    EXPECT_NEAR(sum_area, land_area, 1e-9 * land_area) << "signed ring areas should add up to the land area";
}

// ---------------------------------------------------------------------------------------------
// Each format

TEST(CoastImport, GeoJsonLandPolygons) {
    const Coastline c = import_coastline({coast_file("uk_solent_land.geojson")});
    ASSERT_EQ(c.layers.size(), 1u);
    const LayerStats& l = c.layers[0];
    EXPECT_EQ(l.layer, "uk_solent_land");
    EXPECT_THAT(l.file, HasSubstr("uk_solent_land.geojson"));
    EXPECT_THAT(l.crs, HasSubstr("WGS 84"));
    EXPECT_EQ(l.features, solent_land_features);
    EXPECT_EQ(l.polygons, solent_land_features);
    EXPECT_EQ(l.lines, 0u);
    EXPECT_EQ(l.vertices, solent_land_vertices);
    EXPECT_EQ(l.points_skipped, 0u);
    EXPECT_EQ(l.empty_skipped, 0u);
    EXPECT_EQ(l.repaired, 0u);
    EXPECT_EQ(c.polylines.size(), static_cast<std::size_t>(solent_land_features));  // one ring each
    EXPECT_EQ(c.vertex_count(), static_cast<std::uint64_t>(solent_land_vertices));   // no repeated points to drop
    EXPECT_TRUE(c.has_land_side());
    EXPECT_TRUE(c.warnings.empty());
    // Extent as ogrinfo reports it: (-1.800000, 50.572885) - (-0.900000, 50.950000).
    EXPECT_NEAR(c.min.lon, -1.8, 1e-6);
    EXPECT_NEAR(c.min.lat, 50.572885, 1e-6);
    EXPECT_NEAR(c.max.lon, -0.9, 1e-6);
    EXPECT_NEAR(c.max.lat, 50.95, 1e-6);
    std::set<std::int64_t> fids;
    for (const auto& p : c.polylines) fids.insert(p.fid);
    EXPECT_EQ(fids.size(), static_cast<std::size_t>(solent_land_features));
    expect_land_on_the_left(c, coast_file("uk_solent_land.geojson"), "uk_solent_land");
}

TEST(CoastImport, GeoJsonShorelineLinesHaveNoLandSide) {
    const Coastline c = import_coastline({coast_file("uk_solent_shoreline.geojson")});
    ASSERT_EQ(c.layers.size(), 1u);
    EXPECT_EQ(c.layers[0].features, solent_shore_features);
    EXPECT_EQ(c.layers[0].lines, solent_shore_features);
    EXPECT_EQ(c.layers[0].polygons, 0u);
    EXPECT_EQ(c.layers[0].vertices, solent_shore_vertices);
    EXPECT_EQ(c.polylines.size(), static_cast<std::size_t>(solent_shore_features));
    EXPECT_EQ(c.vertex_count(), static_cast<std::uint64_t>(solent_shore_vertices));
    EXPECT_FALSE(c.has_land_side());
    // Extent as ogrinfo reports it: (-1.800000, 50.572885) - (-0.900000, 50.916243).
    EXPECT_NEAR(c.min.lon, -1.8, 1e-6);
    EXPECT_NEAR(c.min.lat, 50.572885, 1e-6);
    EXPECT_NEAR(c.max.lon, -0.9, 1e-6);
    EXPECT_NEAR(c.max.lat, 50.916243, 1e-6);
}

TEST(CoastImport, Shapefile) {
    const Coastline c = import_coastline({coast_file("gr_saronic_piraeus_land.shp")});
    ASSERT_EQ(c.layers.size(), 1u);
    const LayerStats& l = c.layers[0];
    EXPECT_EQ(l.layer, "gr_saronic_piraeus_land");
    EXPECT_EQ(l.features, piraeus_features);
    EXPECT_EQ(l.polygons, piraeus_features);
    EXPECT_EQ(l.vertices, piraeus_vertices);
    EXPECT_EQ(c.polylines.size(), static_cast<std::size_t>(piraeus_features));
    EXPECT_EQ(c.vertex_count(), static_cast<std::uint64_t>(piraeus_vertices));
    // The sources of a Shapefile are its four files (for the cache fingerprint).
    std::set<std::string> ext;
    for (const auto& f : c.files) ext.insert(std::filesystem::path(f).extension().string());
    EXPECT_EQ(ext, (std::set<std::string>{".dbf", ".prj", ".shp", ".shx"}));
    expect_land_on_the_left(c, coast_file("gr_saronic_piraeus_land.shp"), "gr_saronic_piraeus_land");
}

TEST(CoastImport, GeoPackageReadsEveryLayerByDefault) {
    // uk_solent.gpkg: ogr2ogr -f GPKG of the two Solent GeoJSON files, layers "land", "shoreline".
    const Coastline c = import_coastline({coast_file("uk_solent.gpkg")});
    ASSERT_EQ(c.layers.size(), 2u);
    EXPECT_EQ(layer_named(c, "land").features, solent_land_features);
    EXPECT_EQ(layer_named(c, "land").vertices, solent_land_vertices);
    EXPECT_EQ(layer_named(c, "shoreline").features, solent_shore_features);
    EXPECT_EQ(layer_named(c, "shoreline").lines, solent_shore_features);
    EXPECT_EQ(layer_named(c, "shoreline").vertices, solent_shore_vertices);
    EXPECT_EQ(c.polylines.size(), static_cast<std::size_t>(solent_land_features + solent_shore_features));
    EXPECT_EQ(c.vertex_count(), static_cast<std::uint64_t>(solent_land_vertices + solent_shore_vertices));
    expect_land_on_the_left(c, coast_file("uk_solent.gpkg"), "land");
}

TEST(CoastImport, GeoPackageLayerChoice) {
    ImportOptions opt;
    opt.layers = {"shoreline"};
    const Coastline c = import_coastline({coast_file("uk_solent.gpkg")}, opt);
    ASSERT_EQ(c.layers.size(), 1u);
    EXPECT_EQ(c.layers[0].layer, "shoreline");
    EXPECT_EQ(c.polylines.size(), static_cast<std::size_t>(solent_shore_features));
    EXPECT_FALSE(c.has_land_side());
    // Names also match case-insensitively.
    opt.layers = {"LAND"};
    const Coastline d = import_coastline({coast_file("uk_solent.gpkg")}, opt);
    ASSERT_EQ(d.layers.size(), 1u);
    EXPECT_EQ(d.layers[0].layer, "land");
    EXPECT_EQ(d.polylines.size(), static_cast<std::size_t>(solent_land_features));
}

TEST(CoastImport, S57ReadsLndareCoalneAndStructuresByDefault) {
    // The cut holds no depth area or danger: its default layers are land and SLCONS.
    const Coastline c = import_coastline({coast_file("US4MD81M_cut.000")});
    ASSERT_EQ(c.layers.size(), 3u);
    const LayerStats& land = layer_named(c, "LNDARE");
    EXPECT_EQ(land.features, s57_lndare_features);
    EXPECT_EQ(land.polygons, s57_lndare_polygons);
    EXPECT_EQ(land.points_skipped, s57_lndare_points);
    EXPECT_EQ(land.vertices, s57_lndare_vertices);
    EXPECT_EQ(land.lines, 0u);
    const LayerStats& coal = layer_named(c, "COALNE");
    EXPECT_EQ(coal.features, s57_coalne_features);
    EXPECT_EQ(coal.lines, s57_coalne_features);
    EXPECT_EQ(coal.vertices, s57_coalne_vertices);
    const LayerStats& slcons = layer_named(c, "SLCONS");
    EXPECT_EQ(slcons.kind, shoal::coast::HazardKind::structure);
    EXPECT_EQ(slcons.features, s57_slcons_features);
    EXPECT_EQ(slcons.structures, s57_slcons_features) << "every line and the point become structures";
    EXPECT_EQ(slcons.points, s57_slcons_points);
    EXPECT_EQ(polylines_of_layer(c, "LNDARE"), static_cast<std::size_t>(s57_lndare_polygons));
    EXPECT_EQ(polylines_of_layer(c, "COALNE"), static_cast<std::size_t>(s57_coalne_features));
    EXPECT_GE(polylines_of_layer(c, "SLCONS"), static_cast<std::size_t>(s57_slcons_features));
    for (const auto& p : c.polylines) EXPECT_EQ(p.land_left, c.layers.at(p.layer).layer != "COALNE");
    expect_land_on_the_left(c, coast_file("US4MD81M_cut.000"), "LNDARE");
}

TEST(CoastImport, S57LayerChoice) {
    ImportOptions opt;
    opt.layers = {"SLCONS"};
    const Coastline c = import_coastline({coast_file("US4MD81M_cut.000")}, opt);
    ASSERT_EQ(c.layers.size(), 1u);
    const LayerStats& l = c.layers[0];
    EXPECT_EQ(l.layer, "SLCONS");
    EXPECT_EQ(l.features, s57_slcons_features);
    EXPECT_EQ(l.lines, s57_slcons_lines);
    EXPECT_EQ(l.points, s57_slcons_points) << "a point structure is read (a disc around it)";
    EXPECT_EQ(l.points_skipped, 0u);
    EXPECT_EQ(l.vertices, s57_slcons_vertices + s57_slcons_points);

    opt.layers = {"LNDARE"};
    const Coastline d = import_coastline({coast_file("US4MD81M_cut.000")}, opt);
    ASSERT_EQ(d.layers.size(), 1u);
    EXPECT_EQ(d.layers[0].layer, "LNDARE");
    EXPECT_EQ(d.polylines.size(), static_cast<std::size_t>(s57_lndare_polygons));

    // Lines only. Extent of the COALNE geometries (osgeo.ogr, union of GetEnvelope()):
    // (-76.575703, 38.885413) - (-76.293462, 39.000000).
    opt.layers = {"COALNE"};
    const Coastline e = import_coastline({coast_file("US4MD81M_cut.000")}, opt);
    EXPECT_EQ(e.polylines.size(), static_cast<std::size_t>(s57_coalne_features));
    EXPECT_NEAR(e.min.lon, -76.575703, 1e-6);
    EXPECT_NEAR(e.min.lat, 38.885413, 1e-6);
    EXPECT_NEAR(e.max.lon, -76.293462, 1e-6);
    EXPECT_NEAR(e.max.lat, 39.0, 1e-6);
}

TEST(CoastImport, SeveralInputsAreMerged) {
    const std::vector<std::string> paths = {coast_file("uk_solent_land.geojson"), coast_file("gr_saronic_piraeus_land.shp"),
                                            coast_file("uk_solent_shoreline.geojson")};
    const Coastline c = import_coastline(paths);
    ASSERT_EQ(c.layers.size(), 3u);
    EXPECT_EQ(c.polylines.size(), static_cast<std::size_t>(solent_land_features + piraeus_features + solent_shore_features));
    EXPECT_EQ(c.vertex_count(), static_cast<std::uint64_t>(solent_land_vertices + piraeus_vertices + solent_shore_vertices));
    // Each polyline points back at the layer, and so the file, it came from.
    EXPECT_EQ(polylines_of_layer(c, "uk_solent_land"), static_cast<std::size_t>(solent_land_features));
    EXPECT_EQ(polylines_of_layer(c, "gr_saronic_piraeus_land"), static_cast<std::size_t>(piraeus_features));
    EXPECT_EQ(polylines_of_layer(c, "uk_solent_shoreline"), static_cast<std::size_t>(solent_shore_features));
    for (const auto& p : c.polylines) {
        const auto& l = c.layers.at(p.layer);
        EXPECT_EQ(p.land_left, l.layer != "uk_solent_shoreline");
        if (l.layer == "gr_saronic_piraeus_land") EXPECT_THAT(l.file, HasSubstr(".shp"));
        else EXPECT_THAT(l.file, HasSubstr(".geojson"));
        // Piraeus lies east of 22.9E, the Solent west of 0.9W.
        EXPECT_EQ(p.points.front().lon > 20, l.layer == "gr_saronic_piraeus_land");
    }
    // The extent spans both regions (ogrinfo: Solent -1.8..-0.9 E, 50.572885..50.95 N;
    // Piraeus 22.9..23.8 E, 37.5..38.1 N).
    EXPECT_NEAR(c.min.lon, -1.8, 1e-6);
    EXPECT_NEAR(c.min.lat, 37.5, 1e-6);
    EXPECT_NEAR(c.max.lon, 23.8, 1e-6);
    EXPECT_NEAR(c.max.lat, 50.95, 1e-6);
    EXPECT_THAT(c.files, Contains(HasSubstr("uk_solent_land.geojson")));
    EXPECT_THAT(c.files, Contains(HasSubstr("gr_saronic_piraeus_land.dbf")));
    EXPECT_THAT(c.files, Contains(HasSubstr("uk_solent_shoreline.geojson")));
}

// ---------------------------------------------------------------------------------------------
// Orientation, repairs, skipped geometries

TEST(CoastImport, WronglyOrientedShellAndHoleAreTurnedSoLandIsOnTheLeft) {
    // Feature 1: a shell written clockwise with a counter-clockwise hole (both the wrong way).
    // Feature 2: a MultiPolygon of two islets. Hand-made; 4 rings, 19 vertices (ogrinfo).
    const Coastline c = import_coastline({coast_file("island_with_lake.geojson")});
    ASSERT_EQ(c.layers.size(), 1u);
    EXPECT_EQ(c.layers[0].features, 2u);
    EXPECT_EQ(c.layers[0].polygons, 3u);
    EXPECT_EQ(c.layers[0].vertices, 19u);
    ASSERT_EQ(c.polylines.size(), 4u);
    int shells = 0, holes = 0;
    for (const auto& p : c.polylines) {
        const double a2 = signed_area2(p.points);
        // The lake is the only ring inside 50.605..50.635 N, 1.385..1.355 W.
        const bool is_hole = std::all_of(p.points.begin(), p.points.end(), [](LonLat q) {
            return q.lat > 50.605 && q.lat < 50.635 && q.lon > -1.385 && q.lon < -1.355;
        });
        (is_hole ? holes : shells) += 1;
        EXPECT_EQ(a2 < 0, is_hole) << "feature " << p.fid << ": shells counter-clockwise, holes clockwise";
    }
    EXPECT_EQ(shells, 3);
    EXPECT_EQ(holes, 1);
    expect_land_on_the_left(c, coast_file("island_with_lake.geojson"), "island_with_lake");
}

TEST(CoastImport, InvalidPolygonIsRepairedAndTheWarningNamesIt) {
    const Coastline c = import_coastline({coast_file("invalid_bowtie.geojson")});
    ASSERT_EQ(c.layers.size(), 1u);
    EXPECT_EQ(c.layers[0].features, 2u);
    EXPECT_EQ(c.layers[0].repaired, 1u);
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_THAT(c.warnings[0], AllOf(HasSubstr("invalid_bowtie.geojson"), HasSubstr("feature 42"), HasSubstr("invalid")));
    EXPECT_THAT(c.warnings[0], Not(HasSubstr("feature 7")));
    // The valid square (feature 7) is one ring; the bow-tie (feature 42) becomes its two
    // triangles, meeting at the crossing point (-1.19, 50.71). By hand: the bow-tie's box is
    // 0.02 x 0.02 degrees and each triangle covers a quarter of it, 1e-4 degrees^2.
    std::vector<const Polyline*> bow;
    for (const auto& p : c.polylines) {
        EXPECT_TRUE(p.land_left);
        EXPECT_EQ(p.points.front(), p.points.back());
        if (p.fid == 42) bow.push_back(&p);
        else EXPECT_EQ(p.fid, 7);
    }
    ASSERT_EQ(bow.size(), 2u);
    for (const Polyline* p : bow) {
        EXPECT_NEAR(signed_area2(p->points) / 2, 1e-4, 1e-12) << "each triangle counter-clockwise, 1e-4 deg^2";
        EXPECT_TRUE(std::any_of(p->points.begin(), p->points.end(), [](LonLat q) {
            return std::abs(q.lon - -1.19) < 1e-12 && std::abs(q.lat - 50.71) < 1e-12;
        }));
    }
}

TEST(CoastImport, PointsAndEmptyGeometriesAreCountedAndSkipped) {
    // mixed_points_empty.geojson, 7 features (ogrinfo -al): 1 polygon (5 vertices), 1 point,
    // 1 multipoint, 1 null geometry, 1 LINESTRING EMPTY, 1 line of one point repeated
    // (2 vertices), 1 usable line (3 vertices).
    const Coastline c = import_coastline({coast_file("mixed_points_empty.geojson")});
    ASSERT_EQ(c.layers.size(), 1u);
    const LayerStats& l = c.layers[0];
    EXPECT_EQ(l.features, 7u);
    EXPECT_EQ(l.polygons, 1u);
    EXPECT_EQ(l.lines, 2u);
    EXPECT_EQ(l.points_skipped, 2u);
    EXPECT_EQ(l.empty_skipped, 3u);  // null, empty, and the line with one distinct point
    EXPECT_EQ(l.vertices, 10u);
    ASSERT_EQ(c.polylines.size(), 2u);
    std::set<std::int64_t> fids{c.polylines[0].fid, c.polylines[1].fid};
    EXPECT_EQ(fids, (std::set<std::int64_t>{1, 7}));
}

TEST(CoastImport, AFeatureWithoutAGeometryIsSkippedAndNamed) {
    // mixed_points_empty.geojson's feature 4 has "geometry": null: no coastline in it, and
    // nothing that GDAL failed to read; the warning names it.
    const std::string path = coast_file("mixed_points_empty.geojson");
    const Coastline c = import_coastline({path});
    EXPECT_THAT(c.warnings, Contains(AllOf(HasSubstr(path), HasSubstr("'mixed_points_empty'"), HasSubstr("1 of its 7 features (4) has no geometry"))));
}

TEST(CoastImport, SourceCrsOptionPlacesAFileWithoutCrs) {
    // projected_no_crs.shp: the square 620000..622000 E, 5615000..5617000 N of UTM zone 30N,
    // with its .prj removed. Corners by gdaltransform -s_srs EPSG:32630 -t_srs EPSG:4326:
    //   (620000, 5615000) -> (-1.30166551214441, 50.67445483827)
    //   (622000, 5617000) -> (-1.27271347785026, 50.6920168617526)
    ImportOptions opt;
    opt.source_crs = "EPSG:32630";
    const Coastline c = import_coastline({coast_file("projected_no_crs.shp")}, opt);
    ASSERT_EQ(c.polylines.size(), 1u);
    EXPECT_THAT(c.layers[0].crs, HasSubstr("EPSG:32630"));
    const auto& pts = c.polylines[0].points;
    auto has = [&](double lon, double lat) {
        return std::any_of(pts.begin(), pts.end(), [&](LonLat q) { return std::abs(q.lon - lon) < 1e-9 && std::abs(q.lat - lat) < 1e-9; });
    };
    EXPECT_TRUE(has(-1.30166551214441, 50.67445483827));
    EXPECT_TRUE(has(-1.27271347785026, 50.6920168617526));
}

// ---------------------------------------------------------------------------------------------
// Bad input: one InputError naming the file (and layer)

TEST(CoastImportErrors, MissingFile) {
    const std::string path = coast_file("no_such_coast.geojson");
    EXPECT_THAT([&] { import_coastline({path}); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("no such file"))));
}

TEST(CoastImportErrors, FileOgrCannotRead) {
    const std::string path = coast_file("not_a_dataset.txt");
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("not a vector dataset"))));
}

TEST(CoastImportErrors, LayerThatIsNotThere) {
    ImportOptions opt;
    opt.layers = {"harbours"};
    const std::string path = coast_file("uk_solent.gpkg");
    EXPECT_THAT([&] { import_coastline({path}, opt); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("harbours"), HasSubstr("land, shoreline"))));
    // One of two names missing: still an error, naming the missing one.
    opt.layers = {"land", "harbours"};
    EXPECT_THAT([&] { import_coastline({path}, opt); }, ThrowsMessage<InputError>(HasSubstr("'harbours'")));
    // An S-57 layer that the cell lacks.
    opt.layers = {"DEPARE"};
    EXPECT_THAT([&] { import_coastline({coast_file("US4MD81M_cut.000")}, opt); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("US4MD81M_cut.000"), HasSubstr("DEPARE"))));
}

TEST(CoastImportErrors, AShapefileCutShortIsRefused) {
    // The Saronic land polygons (66 features, ogrinfo -al) with the .shp cut after 40,000 of
    // its bytes: GDAL reads the records before the cut, says "Error in fread()" for the rest
    // and hands those features back without a geometry. Before, the grid was built from the
    // 25 polygons left, without a word: land where the 41 others lay was water.
    t::TempDir dir;
    for (const char* ext : {".shp", ".shx", ".dbf", ".prj"})
        std::filesystem::copy_file(coast_file(std::string("gr_saronic_piraeus_land") + ext), dir.file(std::string("land") + ext));
    const std::string path = dir.file("land.shp");
    EXPECT_NO_THROW(import_coastline({path}));  // whole, it reads
    ASSERT_GT(std::filesystem::file_size(path), 60000u);
    std::filesystem::resize_file(path, 40000);
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("layer 'land'"), HasSubstr("could not read all of it"),
                                                HasSubstr("Error in fread()"), HasSubstr("of its 66 features"), HasSubstr("without a geometry"))));
}

TEST(CoastImportErrors, AGeoJsonGeometryGdalCannotReadIsRefused) {
    // Text for coordinates: GDAL says "Invalid 'x' coordinate" when it parses the file and
    // gives the feature no geometry. The good square beside it is not enough for a grid.
    t::TempDir dir;
    const std::string path = dir.file("bad.geojson");
    const std::string square = "[[[-1.25, 50.80], [-1.20, 50.80], [-1.20, 50.84], [-1.25, 50.84], [-1.25, 50.80]]]";
    const std::string text = R"({"type": "FeatureCollection", "features": [)"
                             R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[["a", "b"], [1, 2], [3, 4], ["a", "b"]]]}},)"
                             R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": )" + square + "}}]}";
    t::write_bytes(path, std::vector<char>(text.begin(), text.end()));
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("could not read all of it"), HasSubstr("Invalid 'x' coordinate"),
                                                HasSubstr("1 of its 2 features (0)"))));
    // Without the bad feature, the same file reads.
    const std::string good = R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": )" +
                             square + "}}]}";
    t::write_bytes(path, std::vector<char>(good.begin(), good.end()));
    EXPECT_EQ(import_coastline({path}).polylines.size(), 1u);
}

TEST(CoastImportErrors, ACrsGdalCannotReadIsSaidAsSuch) {
    // A GeoJSON "crs" that PROJ does not know: GDAL said so when it opened the file and took
    // the layer as WGS84; before, the file was imported as lon/lat without a word, or refused
    // as "has the CRS WGS 84 but its coordinates are not longitude/latitude".
    t::TempDir dir;
    const std::string path = dir.file("odd_crs.geojson");
    const std::string text = R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::999999"}}, "features": [)"
                             R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[[-1.25, 50.7], [-1.2, 50.7], [-1.2, 50.74], [-1.25, 50.7]]]}}]})";
    t::write_bytes(path, std::vector<char>(text.begin(), text.end()));
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("its CRS is not one GDAL can read"), HasSubstr("crs not found"))));
    // A Shapefile whose .prj GDAL cannot read (it then has no CRS, silently): said, unless the
    // CRS is named.
    for (const char* ext : {".shp", ".shx", ".dbf"})
        std::filesystem::copy_file(coast_file(std::string("gr_saronic_piraeus_land") + ext), dir.file(std::string("land") + ext));
    const std::string prj = "GARBAGE[";
    t::write_bytes(dir.file("land.prj"), std::vector<char>(prj.begin(), prj.end()));
    EXPECT_THAT([&] { import_coastline({dir.file("land.shp")}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("land.shp"), HasSubstr("its land.prj is not a CRS GDAL can read"))));
    ImportOptions named;
    named.source_crs = "EPSG:4326";
    EXPECT_EQ(import_coastline({dir.file("land.shp")}, named).polylines.size(), import_coastline({coast_file("gr_saronic_piraeus_land.shp")}).polylines.size());
}

TEST(CoastImportErrors, EmptyLayer) {
    const std::string path = coast_file("empty_collection.geojson");
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("'empty_collection'"), HasSubstr("no features"))));
}

TEST(CoastImportErrors, OnlyPoints) {
    const std::string path = coast_file("points_only.geojson");
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("'points_only'"), HasSubstr("no coastline"))));
}

TEST(CoastImportErrors, NoCrsAndProjectedCoordinatesInAShapefile) {
    const std::string path = coast_file("projected_no_crs.shp");
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("'projected_no_crs'"), HasSubstr("no CRS"),
                                                HasSubstr("not longitude/latitude"))));
}

TEST(CoastImportErrors, NoCrsAndProjectedCoordinatesInGeoJson) {
    // GeoJSON without a "crs" member is WGS84 by RFC 7946 (GDAL reports EPSG:4326), so
    // metres in it are coordinates that cannot be longitude/latitude.
    const std::string path = coast_file("projected_no_crs.geojson");
    EXPECT_THAT([&] { import_coastline({path}); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("'projected_no_crs'"), HasSubstr("not longitude/latitude"))));
}

TEST(CoastImportErrors, NoInputIsAUsageError) {
    EXPECT_THROW(import_coastline({}), UsageError);
}

// ---------------------------------------------------------------------------------------------
// Projection into the local frame

TEST(CoastProject, EveryVertexIsProjectedWithTheFrameInOrder) {
    const Coastline c = import_coastline({coast_file("uk_solent_land.geojson")});
    const auto frame = shoal::geo::LocalFrame::transverse_mercator({-1.35, 50.76});
    const auto lines = shoal::coast::project(c, frame);
    ASSERT_EQ(lines.size(), c.polylines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
        EXPECT_EQ(lines[i].land_left, c.polylines[i].land_left);
        ASSERT_EQ(lines[i].points.size(), c.polylines[i].points.size());
        for (std::size_t k = 0; k < lines[i].points.size(); ++k) {
            const XY p = frame.forward(c.polylines[i].points[k]);
            EXPECT_NEAR(lines[i].points[k].x, p.x, 1e-9);
            EXPECT_NEAR(lines[i].points[k].y, p.y, 1e-9);
        }
    }
}

}  // namespace
