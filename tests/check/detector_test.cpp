// The pose check against independent answers: GEOS (GEOSPreparedIntersects / Distance on the
// same land polygons, projected with the same frame) on many random poses near real
// coastlines, the brute-force traversal, and hand-made shapes with known answers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <ogrsf_frmts.h>
#include <mutex>
#include <random>
#include <span>
#include <thread>

#include <shoal/check/brute_force.hpp>
#include <shoal/check/detector.hpp>
#include "geo/geos_context.hpp"
#include <shoal/grid/coast_grid.hpp>
#include <shoal/util/error.hpp>

namespace shoal::check {
namespace {

using geo::XY;

std::string test_data(const std::string& rel) { return std::string(SHOAL_TEST_DATA) + rel; }

/// Land polygons of an OGR file as one prepared GEOS geometry in the frame's metres.
class LandOracle {
public:
    LandOracle(const std::string& path, const geo::LocalFrame& frame) : m_frame(frame) {
        GDALAllRegister();
        GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
        if (!ds) throw std::runtime_error("cannot open " + path);
        std::vector<GEOSGeometry*> parts;
        for (OGRLayer* layer : ds->GetLayers())
            for (auto& f : *layer) {
                const OGRGeometry* g = f->GetGeometryRef();
                if (!g || g->IsEmpty() || wkbFlatten(g->getGeometryType()) == wkbPoint) continue;
                std::vector<unsigned char> wkb(static_cast<std::size_t>(g->WkbSize()));
                g->exportToWkb(wkbNDR, wkb.data());
                const geo::GeomPtr lonlat = geo::own(m_ctx, GEOSGeomFromWKB_buf_r(m_ctx, wkb.data(), wkb.size()), "reading WKB");
                geo::GeomPtr local = geo::own(m_ctx, GEOSGeom_transformXY_r(m_ctx, lonlat.get(), &LandOracle::project, this), "projecting");
                if (GEOSGeomTypeId_r(m_ctx, local.get()) == GEOS_POLYGON) {
                    parts.push_back(local.release());
                    continue;
                }
                for (int i = 0; i < GEOSGetNumGeometries_r(m_ctx, local.get()); ++i)
                    parts.push_back(GEOSGeom_clone_r(m_ctx, GEOSGetGeometryN_r(m_ctx, local.get(), i)));
            }
        // A MultiPolygon (prepared, indexed); made valid by a union where parts overlap.
        m_land = geo::own(m_ctx, GEOSGeom_createCollection_r(m_ctx, GEOS_MULTIPOLYGON, parts.data(),
                                                             static_cast<unsigned>(parts.size())), "multipolygon");
        if (GEOSisValid_r(m_ctx, m_land.get()) != 1)
            m_land = geo::own(m_ctx, GEOSUnaryUnion_r(m_ctx, m_land.get()), "union");
        m_prepared = geo::PreparedPtr(GEOSPrepare_r(m_ctx, m_land.get()), {m_ctx.get()});
    }
    LandOracle(const LandOracle&) = delete;
    LandOracle& operator=(const LandOracle&) = delete;

    bool intersects(const std::vector<XY>& hull) const { return GEOSPreparedIntersects_r(m_ctx, m_prepared.get(), polygon(hull).get()) == 1; }
    /// How deep p lies in land: its distance to the land's boundary; -1 when not in land.
    double depth(XY p) const {
        const geo::GeomPtr pt = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, p.x, p.y), "point");
        if (GEOSPreparedContains_r(m_ctx, m_prepared.get(), pt.get()) != 1) return -1;
        if (!m_boundary) {
            m_boundary = geo::own(m_ctx, GEOSBoundary_r(m_ctx, m_land.get()), "boundary");
            m_prepared_boundary = geo::PreparedPtr(GEOSPrepare_r(m_ctx, m_boundary.get()), {m_ctx.get()});
        }
        double d = -1;
        GEOSPreparedDistance_r(m_ctx, m_prepared_boundary.get(), pt.get(), &d);
        return d;
    }
    /// How deep q lies inside the closed ring `hull`: its distance to the outline; -1 outside.
    double depth_in(const std::vector<XY>& hull, XY q) const {
        const geo::GeomPtr poly = polygon(hull), pt = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, q.x, q.y), "point");
        if (GEOSContains_r(m_ctx, poly.get(), pt.get()) != 1) return -1;
        const geo::GeomPtr outline = geo::own(m_ctx, GEOSBoundary_r(m_ctx, poly.get()), "outline");
        double d = -1;
        GEOSDistance_r(m_ctx, outline.get(), pt.get(), &d);
        return d;
    }
    double distance(const std::vector<XY>& hull) const {
        double d = -1;
        GEOSPreparedDistance_r(m_ctx, m_prepared.get(), polygon(hull).get(), &d);
        return d;
    }

private:
    static int project(double* x, double* y, void* self) {
        const XY p = static_cast<LandOracle*>(self)->m_frame.forward({*x, *y});
        *x = p.x;
        *y = p.y;
        return 1;
    }
    geo::GeomPtr polygon(std::vector<XY> ring) const {
        ring.push_back(ring.front());
        return geo::make_polygon(m_ctx, {ring});
    }
    geo::GeosContext m_ctx;
    const geo::LocalFrame& m_frame;
    geo::GeomPtr m_land{nullptr, {m_ctx.get()}};
    geo::PreparedPtr m_prepared{nullptr, {m_ctx.get()}};
    mutable geo::GeomPtr m_boundary{nullptr, {m_ctx.get()}};
    mutable geo::PreparedPtr m_prepared_boundary{nullptr, {m_ctx.get()}};
};

struct Disagreements {
    int poses = 0, collisions = 0, flag = 0, clearance = 0, brute = 0;
    double worst_clearance_error = 0;
};

/// Random poses near the coast of `path`: touching, overlapping, a few metres off, on land
/// and in open water, all headings; compared with GEOS (and brute force on a subset).
Disagreements compare_with_geos(const std::string& path, int n_poses, double cell_m, int brute_every) {
    const coast::Coastline coast = coast::import_coastline({path});
    const geo::LocalFrame frame =
        geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
    const auto lines = coast::project(coast, frame);
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, cell_m);
    const LandOracle oracle(path, frame);
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18}, "test ship");
    const Detector det(grid, hull);
    const BruteForce brute(lines, hull);

    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<XY> vertices;
    for (const auto& l : lines) vertices.insert(vertices.end(), l.points.begin(), l.points.end());
    const geo::Box ext = grid.extent();
    Disagreements d;
    for (int k = 0; k < n_poses; ++k) {
        XY pos;
        if (k % 10 == 0) {  // anywhere: deep inland, open water
            pos = {ext.minx + unit(rng) * (ext.maxx - ext.minx), ext.miny + unit(rng) * (ext.maxy - ext.miny)};
        } else {  // near a coastline vertex or on a segment, within a hull's reach
            const auto& l = lines[rng() % lines.size()];
            const std::size_t i = rng() % (l.points.size() - 1);
            const XY on = l.points[i] + unit(rng) * (l.points[i + 1] - l.points[i]);
            const double r = (k % 3 == 0 ? 5.0 : 2.5 * hull.radius()) * unit(rng), a = 2 * std::numbers::pi * unit(rng);
            pos = on + XY{r * std::cos(a), r * std::sin(a)};
        }
        const double heading = 360 * unit(rng);
        LocalPose pose = place(frame, Pose{frame.inverse(pos), heading});
        const std::vector<XY> outline = hull_outline(hull, pose);
        const Contact c = det.check(pose, {INFINITY, false});
        const bool geos_hit = oracle.intersects(outline);
        ++d.poses;
        d.collisions += geos_hit;
        if (c.collision != geos_hit) {
            ++d.flag;
            ADD_FAILURE() << path << ": pose " << k << " at (" << pos.x << ", " << pos.y << ") heading " << heading
                          << ": detector says collision=" << c.collision << ", GEOS says " << geos_hit;
            continue;
        }
        if (!geos_hit) {
            const double g = oracle.distance(outline);
            const double err = std::fabs(g - c.clearance_m);
            d.worst_clearance_error = std::max(d.worst_clearance_error, err);
            if (!(err <= 1e-3)) {
                ++d.clearance;
                ADD_FAILURE() << path << ": pose " << k << " clearance " << c.clearance_m << " vs GEOS " << g;
            }
        }
        if (brute_every > 0 && k % brute_every == 0) {
            const Contact b = brute.check(pose);
            if (b.collision != c.collision || std::fabs(b.clearance_m - c.clearance_m) > 1e-6) {
                ++d.brute;
                ADD_FAILURE() << path << ": pose " << k << " brute force " << b.collision << "/" << b.clearance_m
                              << " vs detector " << c.collision << "/" << c.clearance_m;
            }
        }
    }
    return d;
}

TEST(DetectorVsGeos, SolentTwentyThousandPosesAgree) {
    const Disagreements d = compare_with_geos(test_data("coast/uk_solent_land.geojson"), 20000, 500, 20);
    EXPECT_EQ(d.flag, 0);
    EXPECT_EQ(d.clearance, 0);
    EXPECT_EQ(d.brute, 0);
    EXPECT_GT(d.collisions, 2000) << "too few colliding poses to mean anything";
    EXPECT_LT(d.collisions, 18000) << "too few clear poses to mean anything";
    std::printf("solent: %d poses, %d collisions, worst clearance error %.3g m\n", d.poses, d.collisions, d.worst_clearance_error);
}

TEST(DetectorVsGeos, SaronicShapefileSmallCellsAgree) {
    const Disagreements d = compare_with_geos(test_data("coast/gr_saronic_piraeus_land.shp"), 20000, 150, 0);
    EXPECT_EQ(d.flag, 0);
    EXPECT_EQ(d.clearance, 0);
    std::printf("saronic: %d poses, %d collisions, worst clearance error %.3g m\n", d.poses, d.collisions, d.worst_clearance_error);
}

/// Every land file in $SHOAL_SHARED_DATA/coast/gshhg (the project's shared data), when set.
TEST(DetectorVsGeos, SharedCoastlinesAgree) {
    const char* shared = std::getenv("SHOAL_SHARED_DATA");
    if (!shared) GTEST_SKIP() << "SHOAL_SHARED_DATA not set";
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(shared) / "coast" / "gshhg")) {
        const std::string name = e.path().filename().string();
        if (name.find("_land.geojson") == std::string::npos) continue;
        const Disagreements d = compare_with_geos(e.path().string(), 20000, 500, 0);
        EXPECT_EQ(d.flag + d.clearance, 0) << name;
        std::printf("%s: %d poses, %d collisions, %d disagreements, worst clearance error %.3g m\n", name.c_str(), d.poses,
                    d.collisions, d.flag + d.clearance, d.worst_clearance_error);
    }
}

// ---- hand-made shapes in local metres ----

geo::LocalFrame any_frame() { return geo::LocalFrame::transverse_mercator({0, 0}); }

coast::LocalPolyline land_ring(std::vector<XY> ring) {
    ring.push_back(ring.front());
    return {std::move(ring), true};
}

struct Scene {
    std::vector<coast::LocalPolyline> lines;
    grid::CoastGrid grid;
    hull::Hull hull;
    Scene(std::vector<coast::LocalPolyline> l, double cell, hull::Hull h)
        : lines(std::move(l)), grid(grid::CoastGrid::build(lines, any_frame(), cell)), hull(std::move(h)) {}
    Contact grid_check(const LocalPose& p) const { return Detector(grid, hull).check(p); }
    Contact brute_check(const LocalPose& p) const { return BruteForce(lines, hull).check(p); }
};

TEST(DetectorShapes, ThinSpitBetweenHullPointsIsContact) {
    // A spit 0.5 m wide and 2 km long, crossing the ship amidships: no hull point is on it.
    Scene s({land_ring({{-1000, -0.25}, {1000, -0.25}, {1000, 0.25}, {-1000, 0.25}})}, 500,
            hull::Hull::from_dimensions({100, 20, 8, 8}));
    const LocalPose across = LocalPose::at({0, 30}, 180);  // heading south, the spit under the hull
    EXPECT_TRUE(s.grid_check(across).collision);
    EXPECT_TRUE(s.brute_check(across).collision);
    const LocalPose clear = LocalPose::at({0, 30}, 0);  // heading north: stern 20 m short of... (b=20 from y=30)
    const Contact c = s.grid_check(clear);
    EXPECT_FALSE(c.collision);
    EXPECT_NEAR(c.clearance_m, 30 - 20 - 0.25, 1e-6);
}

TEST(DetectorShapes, PierBetweenContourPointsIsContact) {
    // A pier 2 m wide pokes 3 m into the hull's starboard side halfway between two contour points.
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 10, 10});
    // The ship lies along +x (grid heading 90), starboard is -y. Side at y = -10.
    const auto& c = hull.contour();
    double x_gap = 0;  // the middle of the longest starboard side edge
    double longest = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        const XY a = c[i], b = c[(i + 1) % c.size()];
        if (std::fabs(a.y - 10) < 1e-9 && std::fabs(b.y - 10) < 1e-9 && std::fabs(b.x - a.x) > longest) {
            longest = std::fabs(b.x - a.x);
            x_gap = (a.x + b.x) / 2;
        }
    }
    ASSERT_GT(longest, 4) << "the generated hull has no straight starboard side to put a pier against";
    Scene s({land_ring({{x_gap - 1, -40}, {x_gap + 1, -40}, {x_gap + 1, -7}, {x_gap - 1, -7}})}, 200, hull);
    const LocalPose p = LocalPose::at({0, 0}, 90);
    EXPECT_TRUE(s.grid_check(p).collision);
    EXPECT_TRUE(s.brute_check(p).collision);
    // Moved 3.5 m to port, the pier end is 0.5 m off the side.
    const Contact off = s.grid_check(LocalPose::at({0, 3.5}, 90));
    EXPECT_FALSE(off.collision);
    EXPECT_NEAR(off.clearance_m, 0.5, 1e-9);
}

TEST(DetectorShapes, ShipDeepInsideAnIslandIsContact) {
    Scene s({land_ring({{0, 0}, {20000, 0}, {20000, 20000}, {0, 20000}})}, 500, hull::Hull::from_dimensions({100, 20, 8, 8}));
    ASSERT_EQ(s.grid.state(s.grid.col_of(10000), s.grid.row_of(10000)), grid::CellState::land);
    const Contact c = s.grid_check(LocalPose::at({10000, 10000}, 33));
    EXPECT_TRUE(c.collision);
    EXPECT_NEAR(c.penetration_m, 10000 - 8, 100);  // the deepest hull point is ~10 km from the shore
}

TEST(DetectorShapes, IsletInsideTheHullIsContact) {
    Scene s({land_ring({{1, -1}, {3, -1}, {3, 1}, {1, 1}}), land_ring({{5000, 5000}, {5100, 5000}, {5100, 5100}})}, 300,
            hull::Hull::from_dimensions({100, 20, 8, 8}));
    const Contact c = s.grid_check(LocalPose::at({0, 0}, 90));
    EXPECT_TRUE(c.collision);
    EXPECT_NEAR(c.penetration_m, 7, 1e-9);  // the islet's corner (3, -1) or (3,1) is 7 m from the side
}

TEST(DetectorShapes, ShipOnCellBordersAndCornersMatchesGeos) {
    // A coast of right angles whose vertices and edges sit exactly on cell borders and corners.
    std::vector<coast::LocalPolyline> lines{land_ring({{0, 0}, {400, 0}, {400, 200}, {200, 200}, {200, 400}, {0, 400}})};
    const hull::Hull hull = hull::Hull::from_dimensions({40, 10, 5, 5});
    Scene s(lines, 100, hull);
    geo::GeosContext ctx;
    std::vector<XY> ring = lines[0].points;
    geo::GeomPtr land = geo::make_polygon(ctx, {ring});
    int checked = 0;
    for (double x = -100; x <= 500; x += 50)
        for (double y = -100; y <= 500; y += 50)
            for (double hdg : {0.0, 45.0, 90.0, 180.0, 271.0}) {
                const LocalPose p = LocalPose::at({x, y}, hdg);
                std::vector<XY> outline = hull_outline(hull, p);
                outline.push_back(outline.front());
                geo::GeomPtr hp = geo::make_polygon(ctx, {outline});
                const bool hit = GEOSIntersects_r(ctx, land.get(), hp.get()) == 1;
                double dist = 0;
                GEOSDistance_r(ctx, land.get(), hp.get(), &dist);
                const Contact c = s.grid_check(p);
                EXPECT_EQ(c.collision, hit) << "at " << x << "," << y << " heading " << hdg;
                if (!hit) {
                    EXPECT_NEAR(c.clearance_m, dist, 1e-9) << "at " << x << "," << y << " heading " << hdg;
                }
                ++checked;
            }
    EXPECT_GT(checked, 500);
}

TEST(DetectorShapes, ClearanceSearchStopsAtTheLimit) {
    Scene s({land_ring({{0, 0}, {100, 0}, {100, 100}, {0, 100}})}, 100, hull::Hull::from_dimensions({40, 10, 5, 5}));
    // Far outside the grid, to the east: covered is false, clearance still exact.
    const Contact far = s.grid_check(LocalPose::at({1000, 50}, 0));
    EXPECT_FALSE(far.covered);
    EXPECT_NEAR(far.clearance_m, 1000 - 5 - 100, 1e-9);
    const Contact limited = Detector(s.grid, s.hull).check(LocalPose::at({1000, 50}, 0), {100.0, false});
    EXPECT_TRUE(std::isinf(limited.clearance_m));
}

/// The Solent's land (tests/data), projected to a transverse Mercator frame at its centre,
/// as a grid of 500 m cells.
struct Solent {
    std::string path = test_data("coast/uk_solent_land.geojson");
    coast::Coastline coast = coast::import_coastline({path});
    geo::LocalFrame frame =
        geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
    std::vector<coast::LocalPolyline> lines = coast::project(coast, frame);
    grid::CoastGrid grid = grid::CoastGrid::build(lines, frame, 500);
};

/// Poses over the Solent, seeded by `seed`: `tracks` straight runs of 81 poses `step_m` apart
/// through a random coastline vertex (into land and out), turning `turn_deg` a pose; then
/// `random` poses anywhere within a square of side `spread_m` around a random coastline vertex,
/// at random headings.
std::vector<LocalPose> runs_into_land_and_random(const Solent& solent, std::uint64_t seed, int tracks, double step_m, double turn_deg,
                                                 int random, double spread_m) {
    const geo::LocalFrame& frame = solent.frame;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<LocalPose> poses;
    for (int track = 0; track < tracks; ++track) {
        const auto& l = solent.lines[rng() % solent.lines.size()];
        const XY on = l.points[rng() % l.points.size()];
        const double a = 2 * std::numbers::pi * unit(rng), heading = a * 180 / std::numbers::pi;
        const XY dir{std::sin(a), std::cos(a)};
        for (int k = -40; k <= 40; ++k) poses.push_back(place(frame, Pose{frame.inverse(on + (step_m * k) * dir), heading + turn_deg * k}));
    }
    for (int k = 0; k < random; ++k) {
        const auto& l = solent.lines[rng() % solent.lines.size()];
        const XY on = l.points[rng() % l.points.size()];
        poses.push_back(place(frame, Pose{frame.inverse(on + XY{spread_m * unit(rng) - spread_m / 2, spread_m * unit(rng) - spread_m / 2}),
                                          360 * unit(rng)}));
    }
    return poses;
}

/// Detector::covers (what the sweep asks of a pose it does not check) is whether every point of
/// the hull's outline lies inside the grid's extent, and what check() says: on poses inside,
/// outside and across the Solent grid's edges and corners, at random headings, as placed.
TEST(DetectorCovers, WhetherTheOutlineLiesInsideTheExtent) {
    const Solent solent;
    const hull::Hull hull = hull::Hull::from_dimensions({150, 35, 14, 14});
    const Detector det(solent.grid, hull);
    const geo::Box ext = solent.grid.extent();
    std::mt19937_64 rng(15);
    std::uniform_real_distribution<double> unit(0, 1);
    int inside = 0, outside = 0;
    for (int k = 0; k < 20000; ++k) {
        // Near an edge or a corner (within the hull's radius and a little more) half the time.
        XY p{ext.minx + (ext.maxx - ext.minx) * unit(rng), ext.miny + (ext.maxy - ext.miny) * unit(rng)};
        const double off = (unit(rng) - 0.5) * 2.4 * hull.radius();
        switch (k % 4) {
            case 0: p.x = (k % 8 ? ext.minx : ext.maxx) + off; break;
            case 1: p.y = (k % 8 != 1 ? ext.miny : ext.maxy) + off; break;
            case 2: p = {(k % 16 < 8 ? ext.minx : ext.maxx) + off, (k % 16 < 8 ? ext.miny : ext.maxy) + (unit(rng) - 0.5) * 2.4 * hull.radius()}; break;
            default: break;
        }
        const LocalPose pose = place(solent.frame, Pose{solent.frame.inverse(p), 360 * unit(rng)});
        bool expected = true;
        for (const XY& q : hull_outline(hull, pose))
            expected = expected && q.x >= ext.minx && q.x <= ext.maxx && q.y >= ext.miny && q.y <= ext.maxy;
        ASSERT_EQ(det.covers(pose), expected) << "pose " << k;
        ASSERT_EQ(det.check(pose, {.max_clearance_m = 50, .want_penetration = false}).covered, expected) << "pose " << k;
        ++(expected ? inside : outside);
    }
    EXPECT_GT(inside, 5000);
    EXPECT_GT(outside, 2000);
}

/// A random pose for the CheckOptions tests: every fourth (by `k`) anywhere over the Solent
/// grid (deep inland, open water), the others within `reach` metres of a random coast vertex.
LocalPose options_pose(const Solent& solent, double reach, int k, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0, 1);
    const geo::Box ext = solent.grid.extent();
    XY pos;
    if (k % 4 == 0) {
        pos = {ext.minx + unit(rng) * (ext.maxx - ext.minx), ext.miny + unit(rng) * (ext.maxy - ext.miny)};
    } else {
        const auto& l = solent.lines[rng() % solent.lines.size()];
        const XY on = l.points[rng() % l.points.size()];
        const double r = reach * unit(rng), a = 2 * std::numbers::pi * unit(rng);
        pos = on + XY{r * std::cos(a), r * std::sin(a)};
    }
    return place(solent.frame, Pose{solent.frame.inverse(pos), 360 * unit(rng)});
}

/// Asking for less (no penetration, no enclosing polyline: what probe and the sweep ask)
/// changes nothing else: the same flags, clearance and points as the full check on random
/// poses near the coast and deep inland, and the same polyline wherever one is given.
TEST(DetectorOptions, AskingLessChangesNothingElse) {
    const Solent solent;
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18}, "test ship");
    const Detector det(solent.grid, hull);
    std::mt19937_64 rng(15);
    int left_out = 0, deep = 0;
    for (int k = 0; k < 4000; ++k) {
        const LocalPose pose = options_pose(solent, 2.5 * hull.radius(), k, rng);
        for (const double limit : {100.0, static_cast<double>(INFINITY)}) {
            const Contact full = det.check(pose, {limit, true, true});
            const Contact lean = det.check(pose, {limit, false, false});
            ASSERT_EQ(lean.collision, full.collision) << k;
            // Whether it touches, nothing else (the sweep's bisection): no clearance searched.
            ASSERT_EQ(det.check(pose, {0.0, false, false}).collision, full.collision) << k;
            ASSERT_EQ(lean.covered, full.covered) << k;
            ASSERT_EQ(lean.clearance_m, full.clearance_m) << k;
            ASSERT_EQ(lean.hull_point, full.hull_point) << k;
            ASSERT_EQ(lean.coast_point, full.coast_point) << k;
            EXPECT_EQ(lean.penetration_m, 0.0) << k;
            deep += full.penetration_m > 0;
            if (lean.polyline != full.polyline) {
                // Only the enclosing polyline of a contact without a crossing edge is left out.
                ASSERT_TRUE(full.collision) << k;
                ASSERT_EQ(lean.polyline, grid::CoastGrid::no_polyline) << k;
                ++left_out;
            }
        }
    }
    EXPECT_GT(left_out, 50) << "too few hulls wholly on land to mean anything";
    EXPECT_GT(deep, 500);
}

/// CheckOptions::clearance_hint_m changes no answer, bit for bit, whatever the hint: at the
/// clearance (a hair over, a hair under), well over it, far under it (the search runs again
/// without it), and hints that mean none (0, negative, NaN, infinite). Random poses near the
/// coast, inland and in open water, with the sweep's search limit, a short one and none. (On a
/// projected chart no two pairs of points are exactly equally near: the points are pinned too.)
TEST(DetectorOptions, AClearanceHintChangesNoAnswer) {
    const Solent solent;
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18}, "test ship");
    const Detector det(solent.grid, hull);
    std::mt19937_64 rng(1515);
    int clear = 0, beyond = 0;
    for (int k = 0; k < 3000; ++k) {
        const LocalPose pose = options_pose(solent, 4 * hull.radius(), k, rng);
        for (const double limit : {40.0, 550.0, static_cast<double>(INFINITY)}) {
            for (const bool penetration : {true, false}) {
                const CheckOptions plain{.max_clearance_m = limit, .want_penetration = penetration, .want_polyline = false};
                const Contact want = det.check(pose, plain);
                const double c = want.clearance_m;
                clear += !want.collision && std::isfinite(c);
                beyond += !want.collision && !std::isfinite(c);
                const double base = std::isfinite(c) && c > 0 ? c : 30.0;
                for (const double hint : {base, base * (1 + 1e-12), base * (1 - 1e-12), base + 5, base * 0.5, base * 0.01, 1e7, 0.0, -1.0,
                                          static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
                    CheckOptions o = plain;
                    o.clearance_hint_m = hint;
                    const Contact got = det.check(pose, o);
                    ASSERT_EQ(got.collision, want.collision) << k << " hint " << hint;
                    ASSERT_EQ(got.covered, want.covered) << k << " hint " << hint;
                    ASSERT_EQ(got.clearance_m, want.clearance_m) << k << " hint " << hint;
                    ASSERT_EQ(got.hull_point, want.hull_point) << k << " hint " << hint;
                    ASSERT_EQ(got.coast_point, want.coast_point) << k << " hint " << hint;
                    ASSERT_EQ(got.polyline, want.polyline) << k << " hint " << hint;
                    ASSERT_EQ(got.penetration_m, want.penetration_m) << k << " hint " << hint;
                }
            }
        }
    }
    EXPECT_GT(clear, 3000);
    EXPECT_GT(beyond, 1000);
}

TEST(DetectorOptions, NotAskingWhereChangesNothingElse) {
    // CheckOptions::want_contact_point false (probe, the C API, the sweep once a contact is
    // open): a collision may be answered by the hull point the thread last found on land,
    // before any search. Tracks running into land and out (where that point is on land again),
    // and random poses (where it is anywhere), in order: collision, covered, clearance and
    // penetration the full check's, bit for bit; a contact point that differs from the full
    // check's is a vertex of the hull's outline that GEOS finds in the land polygons.
    const Solent solent;
    const geo::LocalFrame& frame = solent.frame;
    const LandOracle oracle(solent.path, frame);
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18}, "test ship");
    const Detector det(solent.grid, hull);
    const std::vector<LocalPose> poses = runs_into_land_and_random(solent, 21, 40, 20.0, 0.3, 1000, 600.0);
    int elsewhere = 0, contacts = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
        for (const bool penetration : {false, true}) {
            const double limit = k % 2 ? 550.0 : INFINITY;
            const Contact lean = det.check(poses[k], {.max_clearance_m = limit, .want_penetration = penetration, .want_polyline = false,
                                                      .want_contact_point = false});
            const Contact full = det.check(poses[k], {.max_clearance_m = limit, .want_penetration = penetration, .want_polyline = false});
            ASSERT_EQ(lean.collision, full.collision) << "pose " << k;
            ASSERT_EQ(lean.covered, full.covered) << "pose " << k;
            ASSERT_EQ(lean.clearance_m, full.clearance_m) << "pose " << k;
            ASSERT_EQ(lean.penetration_m, full.penetration_m) << "pose " << k;
            if (!lean.collision) {
                ASSERT_EQ(lean.hull_point, full.hull_point) << "pose " << k;
                ASSERT_EQ(lean.coast_point, full.coast_point) << "pose " << k;
                continue;
            }
            contacts += !penetration;
            if (lean.hull_point == full.hull_point && lean.coast_point == full.coast_point) continue;
            elsewhere += !penetration;
            const std::vector<XY> outline = hull_outline(hull, poses[k]);
            double nearest = INFINITY;  // a vertex up to the rounding of placing it
            for (const XY& v : outline) nearest = std::min(nearest, std::sqrt(geo::norm2(v - lean.hull_point)));
            ASSERT_LT(nearest, 1e-6) << "pose " << k << ": not a hull vertex";
            ASSERT_EQ(lean.coast_point, lean.hull_point) << "pose " << k;
            ASSERT_GE(oracle.depth(lean.hull_point), 0) << "pose " << k << ": GEOS finds the point in water";
        }
    }
    EXPECT_GT(contacts, 1500);
    EXPECT_GT(elsewhere, 500) << "too few contacts answered by a point on land to mean anything";
}

TEST(DetectorPenetration, AgreesWithGeos) {
    // Penetration, as documented: the deepest of the hull points in land (their distance to
    // the coast) and of the coast vertices inside the hull (their distance to its outline),
    // the vertices being those of the grid's segments (the coastline's, and where it crosses
    // a cell's side). Answered by GEOS on the land polygons and the hull's polygon, on poses
    // touching the shore, half on land, deep in land (a search of several rings of cells).
    const Solent solent;
    const std::string& path = solent.path;
    const geo::LocalFrame& frame = solent.frame;
    const auto& lines = solent.lines;
    const grid::CoastGrid& grid = solent.grid;
    const LandOracle oracle(path, frame);
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18}, "test ship");
    const Detector det(grid, hull);
    std::vector<XY> vertices;  // every segment's first point, by x
    for (int j = 0; j < grid.ny(); ++j)
        for (int i = 0; i < grid.nx(); ++i)
            for (const grid::Segment& sg : grid.segments(i, j)) vertices.push_back(sg.a);
    std::sort(vertices.begin(), vertices.end(), [](XY a, XY b) { return a.x < b.x; });
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> unit(0, 1);
    int contacts = 0, deep = 0;
    for (int k = 0; k < 1500; ++k) {
        const auto& l = lines[rng() % lines.size()];
        const XY on = l.points[rng() % l.points.size()];
        const double r = (k % 2 == 0 ? 3000.0 : hull.radius()) * unit(rng), a = 2 * std::numbers::pi * unit(rng);
        const LocalPose pose = place(frame, Pose{frame.inverse(on + XY{r * std::cos(a), r * std::sin(a)}), 360 * unit(rng)});
        const Contact c = det.check(pose, {INFINITY, true, false});
        if (!c.collision || !c.covered) continue;
        ++contacts;
        const std::vector<XY> outline = hull_outline(hull, pose);
        double want = 0;
        for (const XY& p : outline) want = std::max(want, oracle.depth(p));
        geo::Box box;
        for (const XY& p : outline) box.extend(p);
        auto from = std::lower_bound(vertices.begin(), vertices.end(), box.minx, [](XY v, double x) { return v.x < x; });
        for (; from != vertices.end() && from->x <= box.maxx; ++from)
            if (from->y >= box.miny && from->y <= box.maxy) want = std::max(want, oracle.depth_in(outline, *from));
        ASSERT_NEAR(c.penetration_m, want, 1e-6) << "pose " << k;
        deep += want > 300;
    }
    EXPECT_GT(contacts, 600);
    EXPECT_GT(deep, 50) << "too few hulls deep in land to mean anything";
}

TEST(DetectorPenetration, TheSameWhateverPoseCameBefore) {
    // The search starts from the hull point found deepest by the thread's last penetration:
    // that changes which points are searched, never the depth. Tracks running into land and
    // out (where the hint helps) and random poses (where it points anywhere), checked in
    // order, in reverse, and each on a fresh thread (which starts from the first point, as
    // before the hint): the same depth, bit for bit. (DetectorPenetration.AgreesWithGeos
    // holds the depth to GEOS's.)
    const Solent solent;
    const hull::Hull hull = hull::Hull::from_dimensions({150, 40, 14, 18}, "test ship");
    const Detector det(solent.grid, hull);
    const std::vector<LocalPose> poses = runs_into_land_and_random(solent, 5, 30, 25.0, 0.2, 300, 400.0);
    const CheckOptions asked{INFINITY, true, false};
    std::vector<double> forward, backward(poses.size());
    for (const LocalPose& p : poses) forward.push_back(det.check(p, asked).penetration_m);
    for (std::size_t k = poses.size(); k-- > 0;) backward[k] = det.check(poses[k], asked).penetration_m;
    int deep = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
        ASSERT_EQ(forward[k], backward[k]) << "pose " << k;
        deep += forward[k] > 100;
        double fresh = NAN;
        std::thread([&] { fresh = det.check(poses[k], asked).penetration_m; }).join();
        ASSERT_EQ(forward[k], fresh) << "pose " << k;
    }
    EXPECT_GT(deep, 300) << "too few hulls deep in land to mean anything";
}

TEST(DetectorPenetration, AHullPointOnACoastCornerMisleadsNoOtherPointsCount) {
    // A land square (200..1200 m both ways) and a notched hull with one point on its corner
    // (200, 200) and one 20 m inside it, (220, 230): 20 m deep (its nearest side is x = 200;
    // the other points lie in water). Counted from the hull point on the corner, the winding of
    // the next point came out 0 (a review's case): each point is counted from its cell's own
    // reference point. Every rotation of the outline (which point the search meets first).
    // (An islet far off: the grid's extent holds the hull.)
    const std::vector<coast::LocalPolyline> lines{land_ring({{200, 200}, {1200, 200}, {1200, 1200}, {200, 1200}}),
                                                  land_ring({{-3000, -3000}, {-2990, -3000}, {-2990, -2990}, {-3000, -2990}})};
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, any_frame(), 500);
    const XY pos{200, 180};
    const std::vector<XY> local{{190, 210}, {200, 200}, {220, 230}, {230, 160}, {170, 160}};
    for (std::size_t start = 0; start < local.size(); ++start) {
        std::vector<XY> ship;  // heading north: forward is +y, starboard +x
        for (std::size_t k = 0; k < local.size(); ++k) {
            const XY p = local[(start + k) % local.size()];
            ship.push_back({p.y - pos.y, p.x - pos.x});
        }
        const Detector det(grid, hull::Hull::from_contour(ship));
        const Contact c = det.check(LocalPose::at(pos, 0));
        ASSERT_TRUE(c.collision) << start;
        EXPECT_NEAR(c.penetration_m, 20, 1e-9) << start;
        EXPECT_NEAR(det.check(LocalPose::at(pos, 0)).penetration_m, 20, 1e-9) << start << " (the deepest point tried first)";
    }
}

TEST(Placement, ManyPosesAtOnceAsOneByOne) {
    // check::place for a batch: the same positions as one by one (one batch projection), the
    // Jacobian from a field over the chart where it covers the pose, to well under 1e-8 of
    // the frame's own (which carries ~3e-9 of rounding); outside the field (about 60 % of
    // these poses), the same bits.
    const geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({24.9, 60.1});
    const XY c = frame.forward({24.9, 60.1});
    const geo::JacobianField field(frame, geo::Box{c.x - 60e3, c.y - 40e3, c.x + 60e3, c.y + 40e3});
    ASSERT_GT(field.degree(), 0);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<Pose> poses;
    for (int k = 0; k < 5000; ++k)
        poses.push_back({{24.9 + 3.6 * (unit(rng) - 0.5), 60.1 + 1.1 * (unit(rng) - 0.5)}, 360 * unit(rng)});
    const std::vector<LocalPose> batch = place(frame, field, poses);
    ASSERT_EQ(batch.size(), poses.size());
    int outside = 0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
        const LocalPose one = place(frame, poses[k]);
        ASSERT_EQ(batch[k].position, one.position) << "pose " << k;
        if (field.covers(one.position)) {
            ASSERT_LT((batch[k].ship_to_local - one.ship_to_local).cwiseAbs().maxCoeff(), 1e-8) << "pose " << k;
        } else {
            ++outside;
            ASSERT_EQ(batch[k].ship_to_local, one.ship_to_local) << "pose " << k;
        }
    }
    EXPECT_GT(outside, 1000);
    EXPECT_LT(outside, 4000);
    // A pose that cannot be projected: the error place() gives for it.
    poses[17].position.lon = NAN;
    std::string one_by_one;
    try {
        place(frame, poses[17]);
    } catch (const InputError& e) {
        one_by_one = e.what();
    }
    ASSERT_FALSE(one_by_one.empty());
    try {
        place(frame, field, poses);
        ADD_FAILURE() << "no error for a pose that cannot be projected";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), one_by_one);
    }
}

TEST(Placement, InBlocksOnThreadsAsTheBatch) {
    // place_in_blocks on 1, 2 and 5 threads: every pose handed over once, in its block's
    // order, placed as the batch place() places it (the same bits); a worker number below the
    // threads asked. A pose PROJ refuses in block 2 and one in block 5: the error is block 2's,
    // as one by one, whatever the threads.
    const geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({24.9, 60.1});
    const XY c = frame.forward({24.9, 60.1});
    const geo::JacobianField field(frame, geo::Box{c.x - 60e3, c.y - 40e3, c.x + 60e3, c.y + 40e3});
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<Pose> poses;
    for (std::size_t k = 0; k < 6 * placement_block + 123; ++k)
        poses.push_back({{24.9 + 3.6 * (unit(rng) - 0.5), 60.1 + 1.1 * (unit(rng) - 0.5)}, 360 * unit(rng)});
    const std::vector<LocalPose> batch = place(frame, field, poses);
    auto pose_of = [&](std::size_t k) { return poses[k]; };
    for (unsigned jobs : {1u, 2u, 5u}) {
        std::vector<LocalPose> got(poses.size());
        std::vector<int> times(poses.size(), 0);
        std::mutex m;
        place_in_blocks(frame, field, poses.size(), pose_of, jobs, [&](std::size_t from, std::span<const LocalPose> placed, unsigned worker) {
            const std::lock_guard lock(m);
            EXPECT_LT(worker, jobs);
            EXPECT_EQ(from % placement_block, 0u);
            for (std::size_t i = 0; i < placed.size(); ++i) {
                got[from + i] = placed[i];
                ++times[from + i];
            }
        });
        for (std::size_t k = 0; k < poses.size(); ++k) {
            ASSERT_EQ(times[k], 1) << "pose " << k << ", " << jobs << " threads";
            ASSERT_EQ(got[k].position, batch[k].position) << "pose " << k << ", " << jobs << " threads";
            ASSERT_EQ(got[k].ship_to_local, batch[k].ship_to_local) << "pose " << k << ", " << jobs << " threads";
        }
    }
    const std::size_t bad2 = 2 * placement_block + 77, bad5 = 5 * placement_block + 3;
    poses[bad2].position.lat = NAN;
    poses[bad5].position.lon = NAN;
    std::string one_by_one;
    try {
        place(frame, poses[bad2]);
    } catch (const InputError& e) {
        one_by_one = e.what();
    }
    ASSERT_FALSE(one_by_one.empty());
    for (unsigned jobs : {1u, 2u, 5u}) {
        try {
            place_in_blocks(frame, field, poses.size(), pose_of, jobs, [](std::size_t, std::span<const LocalPose>, unsigned) {});
            ADD_FAILURE() << "no error for a pose that cannot be projected, " << jobs << " threads";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), one_by_one) << jobs << " threads";
        }
    }
}

TEST(Placement, BowLandsWhereTheGeodesicPutsIt) {
    // Checked in depth in geo tests; here: place() gives the frame's scale and convergence.
    const geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({24.5, 60.0});
    const hull::Hull hull = hull::Hull::from_dimensions({300, 100, 20, 20});
    const LocalPose p = place(frame, Pose{{25.3, 60.3}, 37});
    const std::vector<XY> outline = hull_outline(hull, p);
    // The bow tip is the contour point at x = a.
    std::size_t tip = 0;
    for (std::size_t i = 0; i < hull.contour().size(); ++i)
        if (hull.contour()[i].x > hull.contour()[tip].x) tip = i;
    const geo::LonLat bow = frame.inverse(outline[tip]);
    // Independent: the bow is 300 m from the position along true azimuth 37 (flat-earth
    // approximation at this scale is good to ~1 mm per 300 m).
    const Eigen::Vector2d mpd = geo::metres_per_degree(60.3);
    const double de = (bow.lon - 25.3) * mpd.x(), dn = (bow.lat - 60.3) * mpd.y();
    EXPECT_NEAR(std::hypot(de, dn), 300, 0.01);
    EXPECT_NEAR(std::atan2(de, dn) * 180 / std::numbers::pi, 37, 0.01);
}

}  // namespace
}  // namespace shoal::check
