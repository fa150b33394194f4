// Contact regions against GEOS on the same shapes: for every region, the hull point lies in a
// component of GEOS's intersection of the hull with the land (the union of the rings, overlaps
// and all), at the given distance from the land's boundary (GEOSDistance), the coast point on
// that boundary, the normal from one to the other; nothing of the component is deeper (GEOS's
// largest empty circle of the boundary within the component, and a grid of samples); one region
// per component. On random jagged coasts with piers over the land, islets, hulls convex and
// not, and hand-made shapes with hand-derived answers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <thread>

#include <shoal/check/contacts.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>
// The search's private geometry, for its cell cut (CellCutToItsBoxIsGeosIntersection); its
// other functions, not called here, are not warned about.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "check/contact_geometry.hpp"
#pragma GCC diagnostic pop
#include "check/contact_search.hpp"
#include "geo/geos_context.hpp"
#include "pathological_shapes.hpp"

namespace shoal::check {
namespace {

using geo::XY;

geo::LocalFrame any_frame() { return geo::LocalFrame::transverse_mercator({0, 0}); }

coast::LocalPolyline ring_of(std::vector<XY> r) {
    if (!(r.front() == r.back())) r.push_back(r.front());
    return {std::move(r), true};
}

std::vector<XY> rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}; }

/// Four islets of 7 jagged vertices and 2-10 m across, 460-500 m from the centre, at random bearings.
void add_islets(std::vector<coast::LocalPolyline>& rings, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0, 1);
    for (int k = 0; k < 4; ++k) {
        const double a = unit(rng) * 2 * std::numbers::pi, r0 = 460 + 40 * unit(rng), rad = 2 + 8 * unit(rng);
        std::vector<XY> islet;
        for (int v = 0; v < 7; ++v) {
            const double t = 2 * std::numbers::pi * v / 7;
            islet.push_back({r0 * std::cos(a) + rad * (1 + 0.3 * unit(rng)) * std::cos(t), r0 * std::sin(a) + rad * (1 + 0.3 * unit(rng)) * std::sin(t)});
        }
        rings.push_back(ring_of(islet));
    }
}

/// The land (union of the rings) in GEOS, and the answers to check a region against.
class Oracle {
public:
    explicit Oracle(const std::vector<coast::LocalPolyline>& rings) {
        std::vector<GEOSGeometry*> parts;
        for (const auto& r : rings) parts.push_back(geo::make_polygon(m_ctx, {r.points}).release());
        geo::GeomPtr coll = geo::own(m_ctx, GEOSGeom_createCollection_r(m_ctx, GEOS_GEOMETRYCOLLECTION, parts.data(), static_cast<unsigned>(parts.size())), "collection");
        m_land = geo::own(m_ctx, GEOSUnaryUnion_r(m_ctx, coll.get()), "union");
        m_boundary = geo::own(m_ctx, GEOSBoundary_r(m_ctx, m_land.get()), "boundary");
        for (const auto& r : rings) m_vertices.insert(m_vertices.end(), r.points.begin(), r.points.end());
        // And where two rings' boundaries cross.
        geo::GeomPtr noded = geo::own(m_ctx, GEOSNode_r(m_ctx, m_boundary.get()), "node");
        geo::GeomPtr pts = geo::own(m_ctx, GEOSGeom_extractUniquePoints_r(m_ctx, noded.get()), "points");
        for (int i = 0; i < GEOSGetNumGeometries_r(m_ctx, pts.get()); ++i) {
            double x, y;
            GEOSGeomGetX_r(m_ctx, GEOSGetGeometryN_r(m_ctx, pts.get(), i), &x), GEOSGeomGetY_r(m_ctx, GEOSGetGeometryN_r(m_ctx, pts.get(), i), &y);
            m_vertices.push_back({x, y});
        }
    }
    const geo::GeosContext& ctx() const { return m_ctx; }

    /// Whether p is a vertex of the land's boundary (to a micrometre).
    bool at_vertex(XY p) const {
        for (const XY& v : m_vertices)
            if (geo::distance(v, p) < 1e-6) return true;
        return false;
    }

    double to_boundary(XY p) const {
        if (!m_prepared_boundary) m_prepared_boundary = geo::PreparedPtr(GEOSPrepare_r(m_ctx, m_boundary.get()), {m_ctx.get()});
        geo::GeomPtr pt = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, p.x, p.y), "point");
        double d = -1;
        GEOSPreparedDistance_r(m_ctx, m_prepared_boundary.get(), pt.get(), &d);
        return d;
    }
    bool in_land(XY p) const {
        geo::GeomPtr pt = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, p.x, p.y), "point");
        return GEOSIntersects_r(m_ctx, m_land.get(), pt.get()) == 1;
    }

    /// Checks `regions` of `hull` (open ring) against GEOS; returns the number of failures.
    int verify(const std::vector<XY>& hull_open, const std::vector<ContactRegion>& regions, const std::string& what,
               bool sample = true, double oracle_tol = 1e-2) const {
        std::vector<XY> hull = hull_open;
        hull.push_back(hull.front());
        geo::GeomPtr hp = geo::make_polygon(m_ctx, {hull});
        geo::GeomPtr inter = geo::own(m_ctx, GEOSIntersection_r(m_ctx, hp.get(), m_land.get()), "intersection");
        std::vector<const GEOSGeometry*> comps;
        for (int i = 0; i < GEOSGetNumGeometries_r(m_ctx, inter.get()); ++i) {
            const GEOSGeometry* g = GEOSGetGeometryN_r(m_ctx, inter.get(), i);
            double area = 0;
            GEOSArea_r(m_ctx, g, &area);
            if (GEOSGeomTypeId_r(m_ctx, g) == GEOS_POLYGON && area > 1e-6) comps.push_back(g);
        }
        int failures = 0;
        auto fail = [&](const std::string& msg) {
            if (++failures <= 5) ADD_FAILURE() << what << ": " << msg;
        };
        std::size_t deep_regions = 0;
        for (const ContactRegion& r : regions) deep_regions += r.depth_m > 1e-6 ? 1 : 0;
        if (deep_regions != comps.size() && regions.size() != comps.size())
            fail("regions " + std::to_string(regions.size()) + ", GEOS components " + std::to_string(comps.size()));
        std::vector<bool> matched(comps.size(), false);
        for (const ContactRegion& r : regions) {
            const double d = to_boundary(r.hull_point);
            if (std::fabs(d - r.depth_m) > 1e-6) fail("depth " + std::to_string(r.depth_m) + " but GEOS says " + std::to_string(d));
            if (r.depth_m > 1e-6 && !in_land(r.hull_point)) fail("the hull point is not in land");
            if (to_boundary(r.coast_point) > 1e-6) fail("the coast point is not on the boundary");
            const double nl = std::hypot(r.normal.x, r.normal.y);
            if (std::fabs(nl - 1) > 1e-9) fail("normal not unit");
            const XY moved = r.hull_point + r.depth_m * r.normal;
            if (geo::distance(moved, r.coast_point) > 1e-6) fail("point + depth * normal is not the coast point");
            if (r.depth_m > 1e-3) {
                // Moved less is still in land; moved a little more is free.
                if (!in_land(r.hull_point + (r.depth_m - 1e-3) * r.normal)) fail("moved less than depth is already free");
                // ... unless the nearest point is the tip of a water inlet sharper than a right
                // angle: past the tip lies land again, whatever the way out.
                if (in_land(r.hull_point + (r.depth_m + 1e-3) * r.normal) && !at_vertex(r.coast_point)) {
                    char buf[300];
                    std::snprintf(buf, sizeof buf, "moved depth + 1 mm is not free: point (%.4f %.4f) coast (%.4f %.4f) depth %.4f normal (%.4f %.4f)",
                                  r.hull_point.x, r.hull_point.y, r.coast_point.x, r.coast_point.y, r.depth_m, r.normal.x, r.normal.y);
                    fail(buf);
                }
            }
            // Its component, and nothing of it deeper.
            geo::GeomPtr pt = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, r.hull_point.x, r.hull_point.y), "pt");
            int k = -1;
            double best = INFINITY;
            for (std::size_t c = 0; c < comps.size(); ++c) {
                double dc = 0;
                GEOSDistance_r(m_ctx, comps[c], pt.get(), &dc);
                if (dc < best) best = dc, k = static_cast<int>(c);
            }
            if (k < 0 || best > 1e-6) {
                if (r.depth_m > 1e-6) fail("the hull point is in no component of the intersection");
                continue;
            }
            if (matched[k] && r.depth_m > 1e-6) fail("two regions in one component");
            matched[k] = true;
            // GEOS's largest empty circle of the boundary, centre within the component.
            double env_w = 0;
            {
                double xmin, ymin, xmax, ymax;
                GEOSGeom_getXMin_r(m_ctx, comps[k], &xmin), GEOSGeom_getXMax_r(m_ctx, comps[k], &xmax);
                GEOSGeom_getYMin_r(m_ctx, comps[k], &ymin), GEOSGeom_getYMax_r(m_ctx, comps[k], &ymax);
                env_w = std::max(xmax - xmin, ymax - ymin);
                if (sample) {
                    const int n = 24;
                    for (int i = 0; i <= n; ++i)
                        for (int j = 0; j <= n; ++j) {
                            const XY q{xmin + (xmax - xmin) * i / n, ymin + (ymax - ymin) * j / n};
                            geo::GeomPtr qp = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, q.x, q.y), "q");
                            if (GEOSIntersects_r(m_ctx, comps[k], qp.get()) != 1) continue;
                            const double dq = to_boundary(q);
                            if (dq > r.depth_m + 1e-6) {
                                fail("a sample of the region is deeper: " + std::to_string(dq) + " > " + std::to_string(r.depth_m));
                                i = n + 1;
                                break;
                            }
                        }
                }
            }
            // Independently: a branch and bound of GEOS's distance to the boundary over the
            // component (d is 1-Lipschitz: a cell holds nothing deeper than d at its centre plus
            // its half-diagonal), to oracle_tol: a point it finds deeper is a real counterexample.
            const double deepest = max_depth(comps[k], oracle_tol);
            if (deepest > r.depth_m + 1e-6) fail("GEOS finds a deeper point: " + std::to_string(deepest) + " > " + std::to_string(r.depth_m));
            (void)env_w;
        }
        for (std::size_t c = 0; c < comps.size(); ++c)
            if (!matched[c]) fail("a component of the intersection has no region");
        return failures;
    }

    /// The greatest distance to the land's boundary of a point of polygon `comp`, to `tol`
    /// (a lower bound, at most tol under the truth).
    double max_depth(const GEOSGeometry* comp, double tol) const {
        if (!m_prepared_boundary) m_prepared_boundary = geo::PreparedPtr(GEOSPrepare_r(m_ctx, m_boundary.get()), {m_ctx.get()});
        const geo::PreparedPtr pc(GEOSPrepare_r(m_ctx, comp), {m_ctx.get()});
        double xmin, ymin, xmax, ymax;
        GEOSGeom_getXMin_r(m_ctx, comp, &xmin), GEOSGeom_getXMax_r(m_ctx, comp, &xmax);
        GEOSGeom_getYMin_r(m_ctx, comp, &ymin), GEOSGeom_getYMax_r(m_ctx, comp, &ymax);
        const double side = std::max(xmax - xmin, ymax - ymin);
        struct Cell { double x, y, h; };  // centre, half side
        std::vector<Cell> stack{{(xmin + xmax) / 2, (ymin + ymax) / 2, side / 2}};
        double best = 0;
        while (!stack.empty()) {
            const Cell c = stack.back();
            stack.pop_back();
            geo::GeomPtr pt = geo::own(m_ctx, GEOSGeom_createPointFromXY_r(m_ctx, c.x, c.y), "pt");
            double d = 0;
            GEOSPreparedDistance_r(m_ctx, m_prepared_boundary.get(), pt.get(), &d);
            double to_comp = 0;
            GEOSPreparedDistance_r(m_ctx, pc.get(), pt.get(), &to_comp);
            const double r = c.h * std::sqrt(2.0);
            if (to_comp > r) continue;                      // the cell misses the component
            if (to_comp == 0) best = std::max(best, d);     // the centre is in it
            if (d + r <= best + tol) continue;
            const double q = c.h / 2;
            for (int i = -1; i <= 1; i += 2)
                for (int j = -1; j <= 1; j += 2) stack.push_back({c.x + i * q, c.y + j * q, q});
        }
        return best;
    }

private:
    mutable geo::PreparedPtr m_prepared_boundary;
    std::vector<XY> m_vertices;
    geo::GeosContext m_ctx;
    geo::GeomPtr m_land, m_boundary;
};

struct Scene {
    std::vector<coast::LocalPolyline> rings;
    grid::CoastGrid grid;
    Oracle oracle;
    Scene(std::vector<coast::LocalPolyline> r, double cell)
        : rings(std::move(r)), grid(grid::CoastGrid::build(rings, any_frame(), cell)), oracle(rings) {}
};

TEST(ContactRegions, CellCutToItsBoxIsGeosIntersection) {
    // clip_to_box (an interior cell: its parent's polygon cut to its box) against GEOS's
    // intersection of the same polygon and box, by area, on random convex polygons and boxes
    // over, across and beside them; and a hexagon convex only to rounding (a dent of 5e-11 the
    // convexity test lets through) whose cut gains two vertices at one side.
    geo::GeosContext ctx;
    auto geos_area = [&](const std::vector<XY>& poly, const geo::Box& b) {
        std::vector<XY> ring = poly;
        ring.push_back(poly.front());
        geo::GeomPtr pg = geo::make_polygon(ctx, {ring});
        geo::GeomPtr bx = geo::make_polygon(ctx, {rect(b.minx, b.miny, b.maxx, b.maxy)});
        geo::GeomPtr inter = geo::own(ctx, GEOSIntersection_r(ctx, pg.get(), bx.get()), "intersection");
        double a = 0;
        GEOSArea_r(ctx, inter.get(), &a);
        return a;
    };
    auto area = [](const std::vector<XY>& v) {
        double a2 = 0;
        for (std::size_t i = 0; i < v.size(); ++i) a2 += geo::cross(v[i], v[(i + 1) % v.size()]);
        return a2 / 2;
    };
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<XY> out, tmp;
    int cut = 0;
    for (int k = 0; k < 3000; ++k) {
        // Points on an ellipse at sorted angles: a convex polygon, counter-clockwise.
        const int n = 3 + static_cast<int>(unit(rng) * 30);
        std::vector<double> t(static_cast<std::size_t>(n));
        for (double& a : t) a = unit(rng) * 2 * std::numbers::pi;
        std::sort(t.begin(), t.end());
        t.erase(std::unique(t.begin(), t.end()), t.end());
        const double rx = 1 + 50 * unit(rng), ry = 1 + 50 * unit(rng), cx = 100 * unit(rng), cy = 100 * unit(rng);
        std::vector<XY> poly;
        for (double a : t) poly.push_back({cx + rx * std::cos(a), cy + ry * std::sin(a)});
        if (poly.size() < 3 || !(area(poly) > 1e-9)) continue;
        const double x0 = cx - 1.5 * rx + 3 * rx * unit(rng), y0 = cy - 1.5 * ry + 3 * ry * unit(rng);
        const geo::Box b{x0, y0, x0 + 2 * rx * unit(rng) + 1e-3, y0 + 2 * ry * unit(rng) + 1e-3};
        clip_to_box(poly, b, out, tmp);
        const double want = geos_area(poly, b);
        ASSERT_NEAR(out.empty() ? 0.0 : area(out), want, 1e-9 * (1 + rx * ry)) << "polygon " << k;
        for (XY p : out) ASSERT_TRUE(p.x >= b.minx && p.x <= b.maxx && p.y >= b.miny && p.y <= b.maxy) << "polygon " << k;
        cut += out.empty() ? 0 : 1;
    }
    EXPECT_GT(cut, 1000);
    const double d = 5e-11;
    const std::vector<XY> dented{{0.5, 0}, {1, 0.4}, {1 - d, 0.5}, {1, 0.6}, {0.5, 1}, {0, 0.5}};
    const geo::Box b{0.01, 0.01, 1 - d / 2, 0.99};
    clip_to_box(dented, b, out, tmp);
    EXPECT_NEAR(area(out), geos_area(dented, b), 1e-9);
}

TEST(ContactRegions, BowIntoAStraightQuay) {
    // Land south of y = 0; the ship heads south with its bow 2 m past the quay's edge.
    Scene s({ring_of(rect(-1000, -1000, 1000, 0))}, 100);
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 8, 8});
    const Detector det(s.grid, hull);
    const LocalPose p = LocalPose::at({0, 98}, 180);
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_NEAR(regions[0].depth_m, 2, 1e-9);
    EXPECT_NEAR(regions[0].normal.x, 0, 1e-12);
    EXPECT_NEAR(regions[0].normal.y, 1, 1e-12);
    EXPECT_NEAR(regions[0].hull_point.y, -2, 1e-9);
    EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "bow"), 0);
}

TEST(ContactRegions, WindingsKeptBetweenCallsAreThoseOfTheGridAsked) {
    // A thread keeps the windings it knows from call to call on one grid (CoastGrid::instance):
    // a grid made where another was, with the same cells but other land, is not answered with
    // the first one's. A: land up to y = 0; B: up to y = -10; the same extent (an islet each).
    // The bow 2 m past y = 0 is in A's land and in B's water.
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 8, 8});
    const LocalPose p = LocalPose::at({0, 98}, 180);
    const coast::LocalPolyline islet = ring_of(rect(900, 900, 910, 910));
    std::optional<grid::CoastGrid> g;
    g.emplace(grid::CoastGrid::build({ring_of(rect(-1000, -1000, 1000, 0)), islet}, any_frame(), 100));
    const grid::CoastGrid* where = &*g;
    const std::uint64_t a = g->instance();
    {
        const Detector det(*g, hull);
        for (int k = 0; k < 3; ++k) {
            const auto regions = contact_regions(det, p);
            ASSERT_EQ(regions.size(), 1u);
            EXPECT_NEAR(regions[0].depth_m, 2, 1e-9);
        }
    }
    g.emplace(grid::CoastGrid::build({ring_of(rect(-1000, -1000, 1000, -10)), islet}, any_frame(), 100));
    ASSERT_EQ(&*g, where);
    EXPECT_NE(g->instance(), a);
    const Detector det(*g, hull);
    EXPECT_TRUE(contact_regions(det, p).empty());
    EXPECT_EQ(contact_regions(det, LocalPose::at({0, 88}, 180)).size(), 1u);  // 2 m past y = -10
    // A copy is another grid object: another number.
    const grid::CoastGrid copy = *g;
    EXPECT_NE(copy.instance(), g->instance());
}

TEST(ContactRegions, SidePressedIntoAQuayAlongItsLength) {
    // The starboard side parallel to the quay, 0.5 m into it: the depth is the same along the
    // side; any point of it, one step of the search.
    Scene s({ring_of(rect(-1000, -1000, 1000, 0))}, 100);
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 8, 8});
    const Detector det(s.grid, hull);
    const LocalPose p = LocalPose::at({0, 7.5}, 90);  // heading east: starboard is south, at y = -0.5
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_NEAR(regions[0].depth_m, 0.5, 1e-9);
    EXPECT_NEAR(regions[0].normal.y, 1, 1e-12);
    EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "side"), 0);
}

TEST(ContactRegions, PierAcrossTheHullAndTheShoreAtOnce) {
    // A pier 4 m wide crossing the hull amidships (no hull vertex on it), and the shore under the
    // bow: two regions; the pier's depth is half its width, its normal across the pier.
    Scene s({ring_of(rect(-2, -200, 2, 60)), ring_of(rect(-1000, 80, 1000, 1000))}, 50);
    const hull::Hull hull = hull::Hull::from_dimensions({60, 40, 10, 10});
    const Detector det(s.grid, hull);
    const LocalPose p = LocalPose::at({0, 25}, 0);  // heading north: bow at y = 85, 5 m into the shore
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 2u);
    EXPECT_NEAR(regions[0].depth_m, 5, 1e-6);
    EXPECT_NEAR(regions[1].depth_m, 2, 1e-6);
    EXPECT_NEAR(std::fabs(regions[1].normal.x), 1, 1e-9);
    EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "pier and shore"), 0);
}

TEST(ContactRegions, THeadPierUnderTheHullIsDeepestInside) {
    // A stem 2 m wide with a head 30 x 12 m wholly under a wide hull: the outline only crosses
    // the stem (1 m deep), the head's middle is 6 m deep.
    std::vector<XY> t{{-1, -300}, {1, -300}, {1, 0}, {15, 0}, {15, 12}, {-15, 12}, {-15, 0}, {-1, 0}, {-1, -300}};
    Scene s({ring_of(t)}, 50);
    const hull::Hull hull = hull::Hull::from_dimensions({60, 40, 30, 30});
    const Detector det(s.grid, hull);
    const LocalPose p = LocalPose::at({0, 10}, 0);
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 1u);
    // Deepest where the top edge and the stem's corners (+-1, 0) are equally far: y = 143/24.
    EXPECT_NEAR(regions[0].depth_m, 145.0 / 24, 1e-6);
    EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "T head"), 0);
}

TEST(ContactRegions, DolphinWhollyUnderTheHull) {
    std::vector<XY> octagon;
    for (int k = 0; k < 8; ++k) octagon.push_back({50 + 1.5 * std::cos(k * std::numbers::pi / 4), 3 + 1.5 * std::sin(k * std::numbers::pi / 4)});
    Scene s({ring_of(octagon)}, 50);
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 10, 10});
    const Detector det(s.grid, hull);
    const LocalPose p = LocalPose::at({0, 0}, 90);
    ASSERT_TRUE(det.check(p).collision);
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_NEAR(regions[0].depth_m, 1.5 * std::cos(std::numbers::pi / 8), 1e-6);
    EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "dolphin"), 0);
}

TEST(ContactRegions, HullWhollyInsideAnIsland) {
    Scene s({ring_of(rect(0, 0, 4000, 3000))}, 500);
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 8, 8});
    const Detector det(s.grid, hull);
    const LocalPose p = LocalPose::at({2000, 2900}, 0);  // bow 20 m from the north shore; stern 120 m
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 1u);
    // The deepest hull point: the stern corners are 80 m + ... from the north shore and far from
    // the others; the deepest is the stern's middle at y = 2880: 120 m.
    EXPECT_NEAR(regions[0].depth_m, 120, 1e-6);
    EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "inside"), 0);
}

TEST(ContactRegions, PierRootOverTheLandIsNotItsBoundary) {
    // A pier drawn over the land at its root (overlapping rings): the pier's sides inside the land
    // and the shore inside the pier bound nothing; the bow in the root is as deep as the union says.
    Scene s({ring_of(rect(-1000, -1000, 1000, 0)), ring_of(rect(-5, -50, 5, 100))}, 50);
    const hull::Hull hull = hull::Hull::from_dimensions({100, 20, 8, 8});
    const Detector det(s.grid, hull);
    for (double y : {95.0, 80.0, 10.0, 3.0}) {
        const LocalPose p = LocalPose::at({0.5, y + 100}, 180);  // heading south, bow at (0.5, y)
        const auto regions = contact_regions(det, p);
        EXPECT_EQ(s.oracle.verify(hull_outline(hull, p), regions, "pier root at " + std::to_string(y)), 0);
    }
}

TEST(ContactRegions, CoastlineDrawnAlongTheLandsEdgeIsNoRegionOfItsOwn) {
    // A chart draws the coastline as an open line (no land side) on the land area's edge. Where
    // it crosses the hull it lies on the hazards' boundary: the hull's contact there is the
    // land's region, not a second one of depth 0 (which, the crossing being on the boundary to
    // a rounding, came and went from pose to pose and with the search's first reach).
    const XY u{std::cos(0.37), std::sin(0.37)}, n{-u.y, u.x};  // the shore's direction; land on its right
    std::vector<XY> land{-1000 * u, -1000 * u - 1000 * n, 1000 * u - 1000 * n, 1000 * u};  // counter-clockwise
    coast::LocalPolyline coastline{{-1000 * u, -333.3 * u, 271.9 * u, 1000 * u}, false, {}};
    // And a line across the water (a cable, a pipeline drawn as a line without land side).
    coast::LocalPolyline across{{598 * u + 200 * n, 598 * u + 5 * n}, false, {}};
    const std::vector<coast::LocalPolyline> lines{ring_of(land), coastline, across};
    const grid::CoastGrid grid = grid::CoastGrid::build(lines, any_frame(), 37);
    const Oracle oracle({ring_of(land)});
    const hull::Hull hull = hull::Hull::from_dimensions({60, 12, 6, 6});
    const Detector det(grid, hull);
    const double heading = 180 - 0.37 * 180 / std::numbers::pi;  // towards the land, across the shore
    for (int i = 0; i < 60; ++i) {
        const double along = -400 + 13.7 * i, depth = 0.05 + 0.04 * i;
        // The bow (60 m ahead of the reference point) `depth` into the land.
        const LocalPose p = LocalPose::at(along * u + (60 - depth) * n, heading);
        const auto regions = contact_regions(det, p);
        ASSERT_EQ(regions.size(), 1u) << "pose " << i;
        EXPECT_NEAR(regions[0].depth_m, depth, 1e-6) << "pose " << i;
        EXPECT_EQ(oracle.verify(hull_outline(hull, p), regions, "shore line " + std::to_string(i)), 0);
    }
    // The line across the water under the hull, 2 m beside its centreline: a region of depth 0,
    // beside the land's when the bow is in.
    const LocalPose p = LocalPose::at(600 * u + 70 * n, heading);
    const auto regions = contact_regions(det, p);
    ASSERT_EQ(regions.size(), 1u);
    EXPECT_EQ(regions[0].depth_m, 0);
    const LocalPose q = LocalPose::at(600 * u + 59.5 * n, heading);  // the bow 0.5 m in
    const auto both = contact_regions(det, q);
    ASSERT_EQ(both.size(), 2u);
    EXPECT_NEAR(both[0].depth_m, 0.5, 1e-6);
    EXPECT_EQ(both[1].depth_m, 0);
}

TEST(ContactRegions, RandomJaggedCoastsAgreeWithGeos) {
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> unit(0, 1);
    int poses = 0, contacts = 0, failures = 0;
    for (int scene = 0; scene < 6; ++scene) {
        std::vector<coast::LocalPolyline> rings;
        // An island of jagged coast, piers over its edge, islets off it.
        std::vector<XY> island = test::star_ring(60 + 40 * scene, 400, 25, 100 + scene);
        rings.push_back(ring_of(island));
        for (int k = 0; k < 6; ++k) {
            const double a = unit(rng) * 2 * std::numbers::pi, w = 1 + 6 * unit(rng), len = 30 + 60 * unit(rng);
            const XY c{std::cos(a), std::sin(a)}, nrm{-std::sin(a), std::cos(a)};
            const XY base = 360 * c;
            rings.push_back(ring_of({base - w * nrm, base + len * c - w * nrm, base + len * c + w * nrm, base + w * nrm}));
        }
        add_islets(rings, rng);
        Scene s(rings, 40 + 30 * scene);
        const hull::Hull convex = hull::Hull::from_dimensions({60 + 80 * unit(rng), 10 + 20 * unit(rng), 5 + 10 * unit(rng), 5 + 10 * unit(rng)});
        std::vector<XY> wavy = test::wavy_hull(48);
        for (XY& q : wavy) q = 0.5 * q;
        const hull::Hull nonconvex = hull::Hull::from_contour(wavy);
        for (const hull::Hull* hull : {&convex, &nonconvex}) {
            const Detector det(s.grid, *hull);
            for (int i = 0; i < 36; ++i) {
                const double a = unit(rng) * 2 * std::numbers::pi, r = 330 + 190 * unit(rng);
                const LocalPose p = LocalPose::at({r * std::cos(a), r * std::sin(a)}, 360 * unit(rng));
                const Contact c = det.check(p, {.max_clearance_m = 0});
                const auto regions = contact_regions(det, p);
                ++poses;
                if (c.collision) {
                    ++contacts;
                    EXPECT_FALSE(regions.empty()) << "scene " << scene << " pose " << i << ": a collision with no region";
                } else {
                    EXPECT_TRUE(regions.empty()) << "scene " << scene << " pose " << i << ": regions without a collision";
                }
                failures += s.oracle.verify(hull_outline(*hull, p), regions, "scene " + std::to_string(scene) + " pose " + std::to_string(i), i % 4 == 0,
                                          i % 9 == 0 ? 1e-2 : 0.25);
            }
        }
    }
    std::printf("%d poses, %d in contact, %d failures\n", poses, contacts, failures);
    EXPECT_GT(contacts, poses / 5);
}

TEST(ContactRegions, ShortcutsGiveTheDepthsOfTheFullSearch) {
    // The search's shortcuts (src/check/contact_search.hpp): the first reach of 2 m, the ridge
    // points of the two-site bounds tried as deepest points, the bounds of the pairs with a third
    // site, a convex hull's reach cut to its slabs, a cell's polygon cut from its parent's.
    // Each may give another deepest point of the same depth, never another depth: on random
    // jagged coasts with piers bent halfway along (a vertex in each side: near it the two
    // nearest sites are two pieces of one side, the case the third site is for), over and
    // beside the land, and islets, every region's depth with all of them, each alone, and a
    // first reach of 0.25 m or 64 m, is that of the search without any (a first reach of 1 m),
    // within 2 um (each exact to a micrometre), and the regions are as many.
    std::mt19937_64 rng(53);
    std::uniform_real_distribution<double> unit(0, 1);
    const detail::ContactSearch full{.first_reach_m = 1.0, .ridge_candidates = false, .third_site = false, .hull_slabs = false, .cut_from_parent = false};
    const std::vector<detail::ContactSearch> ways{
        {},
        {.first_reach_m = 1.0, .ridge_candidates = true, .third_site = false, .hull_slabs = false, .cut_from_parent = false},
        {.first_reach_m = 1.0, .ridge_candidates = false, .third_site = true, .hull_slabs = false, .cut_from_parent = false},
        {.first_reach_m = 2.0, .ridge_candidates = false, .third_site = false, .hull_slabs = false, .cut_from_parent = false},
        {.first_reach_m = 1.0, .ridge_candidates = false, .third_site = false, .hull_slabs = true, .cut_from_parent = false},
        {.first_reach_m = 1.0, .ridge_candidates = false, .third_site = false, .hull_slabs = false, .cut_from_parent = true},
        {.first_reach_m = 0.25},
        {.first_reach_m = 64.0},
    };
    int contacts = 0, regions_seen = 0, deep = 0, differ = 0;
    double worst = 0;
    for (int scene = 0; scene < 4; ++scene) {
        std::vector<coast::LocalPolyline> rings{ring_of(test::star_ring(60 + 40 * scene, 400, 25, 200 + scene))};
        for (int k = 0; k < 10; ++k) {
            const double a = unit(rng) * 2 * std::numbers::pi, w = 1 + 4 * unit(rng), len = 30 + 60 * unit(rng);
            const double bend = 0.5 * unit(rng) - 0.25, w2 = w * (0.8 + 0.4 * unit(rng));  // the sides bent at mid-length
            const XY c{std::cos(a), std::sin(a)}, nrm{-std::sin(a), std::cos(a)};
            const XY base = (360 + 40 * unit(rng)) * c, mid = base + 0.5 * len * c + bend * nrm, tip = base + len * c + 2 * bend * nrm;
            rings.push_back(ring_of({base - w * nrm, mid - w2 * nrm, tip - w * nrm, tip + w * nrm, mid + w2 * nrm, base + w * nrm}));
        }
        add_islets(rings, rng);
        const grid::CoastGrid g = grid::CoastGrid::build(rings, any_frame(), 40 + 30 * scene);
        const hull::Hull convex = hull::Hull::from_dimensions({60 + 80 * unit(rng), 10 + 20 * unit(rng), 5 + 10 * unit(rng), 5 + 10 * unit(rng)});
        std::vector<XY> wavy = test::wavy_hull(48);
        for (XY& q : wavy) q = 0.5 * q;
        const hull::Hull nonconvex = hull::Hull::from_contour(wavy);
        for (const hull::Hull* hull : {&convex, &nonconvex}) {
            const Detector det(g, *hull);
            for (int i = 0; i < 150; ++i) {
                const double a = unit(rng) * 2 * std::numbers::pi, r = 330 + 190 * unit(rng);
                const LocalPose p = LocalPose::at({r * std::cos(a), r * std::sin(a)}, 360 * unit(rng));
                const auto want = detail::contact_regions(det, p, full);
                if (want.empty()) continue;
                ++contacts;
                regions_seen += static_cast<int>(want.size());
                for (const ContactRegion& region : want) deep += region.depth_m > 1.0 ? 1 : 0;
                for (std::size_t w = 0; w < ways.size(); ++w) {
                    const auto got = detail::contact_regions(det, p, ways[w]);
                    if (got.size() != want.size()) {
                        if (++differ <= 5) ADD_FAILURE() << "scene " << scene << " pose " << i << " way " << w << ": " << got.size() << " regions, the full search " << want.size();
                        continue;
                    }
                    // Deepest first: the depths in order (regions of depths within 2 um may swap).
                    for (std::size_t k = 0; k < got.size(); ++k) {
                        const double dd = std::fabs(got[k].depth_m - want[k].depth_m);
                        worst = std::max(worst, dd);
                        if (dd > 2e-6 && ++differ <= 5)
                            ADD_FAILURE() << "scene " << scene << " pose " << i << " way " << w << " region " << k << ": depth " << got[k].depth_m
                                          << ", the full search " << want[k].depth_m;
                    }
                }
            }
        }
    }
    std::printf("%d poses in contact, %d regions (%d deeper than 1 m), worst depth difference %.3g m\n", contacts, regions_seen, deep, worst);
    EXPECT_EQ(differ, 0);
    EXPECT_GT(contacts, 300);
    EXPECT_GT(deep, 30);  // the first reach grown: the reach's shortcut is tried
}

TEST(ContactRegions, ThreadsAskingOneDetectorGetTheAnswersOfOne) {
    // contact_regions keeps its working lists per thread and its winding numbers per call: one
    // detector asked from several threads at once, each pose in a different order, must give
    // every thread the same regions, to the bit, as one thread alone.
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<coast::LocalPolyline> rings{ring_of(test::star_ring(200, 400, 25, 7))};
    for (int k = 0; k < 8; ++k) {
        const double a = unit(rng) * 2 * std::numbers::pi, w = 1 + 6 * unit(rng), len = 30 + 60 * unit(rng);
        const XY c{std::cos(a), std::sin(a)}, nrm{-std::sin(a), std::cos(a)};
        const XY base = 360 * c;
        rings.push_back(ring_of({base - w * nrm, base + len * c - w * nrm, base + len * c + w * nrm, base + w * nrm}));
    }
    Scene s(rings, 60);
    const hull::Hull hull = hull::Hull::from_dimensions({60, 12, 6, 6});
    const Detector det(s.grid, hull);
    std::vector<LocalPose> poses;
    std::vector<std::vector<ContactRegion>> alone;
    for (int tries = 0; tries < 5000 && poses.size() < 200; ++tries) {
        const double a = unit(rng) * 2 * std::numbers::pi, r = 330 + 190 * unit(rng);
        const LocalPose p = LocalPose::at({r * std::cos(a), r * std::sin(a)}, 360 * unit(rng));
        auto regions = contact_regions(det, p);
        if (regions.empty()) continue;
        poses.push_back(p);
        alone.push_back(std::move(regions));
    }
    ASSERT_EQ(poses.size(), 200u);
    auto same = [](const ContactRegion& x, const ContactRegion& y) {
        return x.hull_point == y.hull_point && x.coast_point == y.coast_point && x.normal == y.normal && x.depth_m == y.depth_m &&
               x.polyline == y.polyline;
    };
    constexpr int threads = 4;
    std::vector<int> differ(threads, 0);
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (int round = 0; round < 3; ++round)
                for (std::size_t k = 0; k < poses.size(); ++k) {
                    const std::size_t i = (k * (2 * t + 1) + 37 * t) % poses.size();  // each thread its own order
                    const auto got = contact_regions(det, poses[i]);
                    if (got.size() != alone[i].size() || !std::equal(got.begin(), got.end(), alone[i].begin(), same)) ++differ[t];
                }
        });
    for (std::thread& th : pool) th.join();
    for (int t = 0; t < threads; ++t) EXPECT_EQ(differ[t], 0) << "thread " << t;
}

TEST(HullContactRegions, RandomHullsAgreeWithGeos) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    int overlaps = 0;
    for (int i = 0; i < 200; ++i) {
        const hull::Hull a = hull::Hull::from_dimensions({40 + 100 * unit(rng), 10 + 30 * unit(rng), 5 + 10 * unit(rng), 5 + 10 * unit(rng)});
        const hull::Hull b = hull::Hull::from_dimensions({40 + 100 * unit(rng), 10 + 30 * unit(rng), 5 + 10 * unit(rng), 5 + 10 * unit(rng)});
        const auto pa = hull_outline(a, LocalPose::at({0, 0}, 360 * unit(rng)));
        const auto pb = hull_outline(b, LocalPose::at({-80 + 160 * unit(rng), -80 + 160 * unit(rng)}, 360 * unit(rng)));
        std::vector<XY> ring = pb;
        ring.push_back(ring.front());
        const Oracle oracle({ring_of(ring)});
        const auto regions = hull_contact_regions(pa, pb);
        overlaps += regions.empty() ? 0 : 1;
        EXPECT_EQ(oracle.verify(pa, regions, "pair " + std::to_string(i), i % 5 == 0), 0);
    }
    EXPECT_GT(overlaps, 40);
}

}  // namespace
}  // namespace shoal::check
