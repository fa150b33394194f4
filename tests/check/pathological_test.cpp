// Pathological geometry must not blow up and must stay exact: a coastline of a million
// vertices in one ring (through the real import, from a GeoPackage), a grid cell crossed by
// thousands of segments, a hull of 1,000 points. Every answer is compared with GEOS on the
// same shapes (and with the brute-force traversal where it is cheap) on random poses. Times
// are measured by bench/bench_pathological, not here.

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <shoal/check/brute_force.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/grid/coast_grid.hpp>
#include "pathological_shapes.hpp"
#include "test_support.hpp"

namespace shoal::check {
namespace {

using geo::XY;

/// GEOS's answer for a hull outline against a prepared land geometry.
struct GeosAnswer {
    bool hit = false;
    double distance = 0;
};

GeosAnswer geos_answer(const geo::GeosContext& ctx, const GEOSPreparedGeometry* land, std::vector<XY> outline) {
    outline.push_back(outline.front());
    const geo::GeomPtr hull = test::polygon(ctx, {outline});
    GeosAnswer a;
    a.hit = GEOSPreparedIntersects_r(ctx, land, hull.get()) == 1;
    if (!a.hit) GEOSPreparedDistance_r(ctx, land, hull.get(), &a.distance);
    return a;
}

/// Checks `n` random poses from `draw` with the detector and GEOS (and brute force on every
/// `brute_every`-th, 0 for none); returns how many poses touched land.
template <class Draw>
int expect_agreement(const grid::CoastGrid& grid, const hull::Hull& hull, const geo::GeosContext& ctx,
                     const GEOSPreparedGeometry* land, const BruteForce* brute, int n, int brute_every, Draw draw) {
    const Detector det(grid, hull);
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> unit(0, 1);
    int hits = 0;
    for (int k = 0; k < n; ++k) {
        const XY pos = draw(rng);
        const LocalPose pose = LocalPose::at(pos, 360 * unit(rng));
        const Contact c = det.check(pose, {INFINITY, false});
        const GeosAnswer g = geos_answer(ctx, land, hull_outline(hull, pose));
        hits += g.hit;
        EXPECT_EQ(c.collision, g.hit) << "pose " << k << " at (" << pos.x << ", " << pos.y << ")";
        if (!g.hit && !c.collision) {
            EXPECT_NEAR(c.clearance_m, g.distance, 1e-3) << "pose " << k << " at (" << pos.x << ", " << pos.y << ")";
        }
        if (brute && brute_every > 0 && k % brute_every == 0) {
            const Contact b = brute->check(pose);
            EXPECT_EQ(b.collision, c.collision) << "brute force, pose " << k;
            if (!b.collision) {
                EXPECT_NEAR(b.clearance_m, c.clearance_m, 1e-6) << "brute force, pose " << k;
            }
        }
    }
    return hits;
}

/// Writes `ring` (local metres in `frame`) as one lon/lat polygon to a GeoPackage.
void write_gpkg_polygon(const std::string& path, const std::vector<XY>& ring, const geo::LocalFrame& frame) {
    GDALAllRegister();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
    ASSERT_NE(drv, nullptr);
    GDALDatasetUniquePtr ds(drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    ASSERT_TRUE(ds);
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    OGRLayer* layer = ds->CreateLayer("land", &wgs84, wkbPolygon, nullptr);
    ASSERT_NE(layer, nullptr);
    auto lr = std::make_unique<OGRLinearRing>();
    lr->setNumPoints(static_cast<int>(ring.size()), false);
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const geo::LonLat ll = frame.inverse(ring[i]);
        lr->setPoint(static_cast<int>(i), ll.lon, ll.lat);
    }
    OGRPolygon poly;
    poly.addRingDirectly(lr.release());
    OGRFeature f(layer->GetLayerDefn());
    f.SetGeometry(&poly);
    ASSERT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
}

TEST(Pathological, CoastlineOfAMillionVerticesInOneRing) {
    const geo::LocalFrame made_in = geo::LocalFrame::transverse_mercator({10.0, 55.0});
    const std::vector<XY> ring = test::star_ring(1'000'000, 20'000, 0.05);
    test::TempDir dir;
    const std::string path = dir.file("million.gpkg");
    write_gpkg_polygon(path, ring, made_in);

    const coast::Coastline coast = coast::import_coastline({path});
    const auto frame = geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
    const auto lines = coast::project(coast, frame);
    std::size_t vertices = 0;
    for (const auto& l : lines) vertices += l.points.size();
    EXPECT_EQ(vertices, ring.size());
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
    std::size_t most = 0;
    for (int j = 0; j < grid.ny(); ++j)
        for (int i = 0; i < grid.nx(); ++i) most = std::max(most, grid.segments(i, j).size());
    EXPECT_GT(most, 3000u) << "a 500 m coast cell holds thousands of the 0.13 m segments";

    // The oracle: the polygon as OGR reads it from the file, projected vertex by vertex.
    geo::GeosContext ctx;
    const geo::GeomPtr land = test::projected_land(ctx, test::read_polygons_with_ogr(path), frame);
    const test::PreparedPtr prepared = test::prepare(ctx, land.get());
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18});
    const int hits = expect_agreement(grid, hull, ctx, prepared.get(), nullptr, 400, 0, [&](std::mt19937_64& rng) {
        std::uniform_real_distribution<double> unit(0, 1);
        const XY on = frame.forward(made_in.inverse(ring[rng() % (ring.size() - 1)]));
        const double r = 2.5 * hull.radius() * unit(rng), a = 2 * std::numbers::pi * unit(rng);
        return on + XY{r * std::cos(a), r * std::sin(a)};
    });
    EXPECT_GT(hits, 40);
    EXPECT_LT(hits, 360);
}

TEST(Pathological, CellCrossedByThousandsOfSegments) {
    const std::vector<XY> ring = test::comb_ring(5000, 500, 4000);
    const std::vector<coast::LocalPolyline> lines{{ring, true}};
    const geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({0, 0});
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
    std::size_t most = 0;
    for (int j = 0; j < grid.ny(); ++j)
        for (int i = 0; i < grid.nx(); ++i) most = std::max(most, grid.segments(i, j).size());
    EXPECT_GE(most, 2500u) << "the comb's cells are crossed by thousands of segments";

    geo::GeosContext ctx;
    const geo::GeomPtr land = test::polygon(ctx, {ring});
    ASSERT_EQ(GEOSisValid_r(ctx, land.get()), 1);
    const test::PreparedPtr prepared = test::prepare(ctx, land.get());
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18});
    const BruteForce brute(lines, hull);
    const int hits = expect_agreement(grid, hull, ctx, prepared.get(), &brute, 600, 5, [](std::mt19937_64& rng) {
        std::uniform_real_distribution<double> unit(0, 1);
        // Most poses just above the teeth, where the clearance is decided among thousands of
        // segments; the rest anywhere around the comb.
        if (rng() % 4 != 0) return XY{-300 + 1100 * unit(rng), 1800 + 500 * unit(rng)};
        return XY{-800 + 2100 * unit(rng), -3000 + 5800 * unit(rng)};
    });
    EXPECT_GT(hits, 60);
    EXPECT_LT(hits, 540);
}

TEST(Pathological, HullOfAThousandPointsOnARealCoast) {
    const std::string path = test::data_path("coast/uk_solent_land.geojson");
    const coast::Coastline coast = coast::import_coastline({path});
    const auto frame = geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
    const auto lines = coast::project(coast, frame);
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
    geo::GeosContext ctx;
    const geo::GeomPtr land = test::projected_land(ctx, test::read_polygons_with_ogr(path), frame);
    const test::PreparedPtr prepared = test::prepare(ctx, land.get());
    const hull::Hull hull = hull::Hull::from_contour(test::wavy_hull(1000), "thousand points");
    ASSERT_EQ(hull.contour().size(), 1000u);
    const BruteForce brute(lines, hull);
    const int hits = expect_agreement(grid, hull, ctx, prepared.get(), &brute, 1000, 50, [&](std::mt19937_64& rng) {
        std::uniform_real_distribution<double> unit(0, 1);
        const auto& l = lines[rng() % lines.size()];
        const XY on = l.points[rng() % l.points.size()];
        const double r = 2.5 * hull.radius() * unit(rng), a = 2 * std::numbers::pi * unit(rng);
        return on + XY{r * std::cos(a), r * std::sin(a)};
    });
    EXPECT_GT(hits, 100);
    EXPECT_LT(hits, 900);
}

}  // namespace
}  // namespace shoal::check
