// Tests of the 2-D primitives in geo/point.hpp. Every answer is compared with GEOS on the same
// segments (GEOSIntersects_r, GEOSDistance_r, GEOSOrientationIndex_r), over thousands of random
// cases: small integer coordinates (exact in doubles, so collinear, touching and overlapping
// cases are frequent and GEOS's robust predicates give the exact answer) and general doubles.

#include <shoal/geo/point.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "test_support.hpp"

namespace {

using shoal::geo::Box;
using shoal::geo::XY;
namespace t = shoal::test;

std::string show(XY p) {
    std::ostringstream s;
    s.precision(17);
    s << "(" << p.x << " " << p.y << ")";
    return s.str();
}

std::string show(XY a, XY b, XY c, XY d) { return show(a) + "-" + show(b) + " vs " + show(c) + "-" + show(d); }

class PointTest : public testing::Test {
protected:
    /// Small integer coordinates: many exactly collinear, touching, overlapping and
    /// zero-length cases.
    XY int_point() { return {static_cast<double>(m_small(m_rng)), static_cast<double>(m_small(m_rng))}; }
    /// General coordinates of the size the grid sees (local metres, tens of km).
    XY real_point() { return {m_real(m_rng), m_real(m_rng)}; }

    bool geos_intersects(XY a, XY b, XY c, XY d) const {
        auto g1 = t::segment(m_geos, a, b), g2 = t::segment(m_geos, c, d);
        const char r = GEOSIntersects_r(m_geos, g1.get(), g2.get());
        if (r == 2) throw std::runtime_error("GEOSIntersects failed");
        return r == 1;
    }
    double geos_distance(const GEOSGeometry* g1, const GEOSGeometry* g2) const {
        double d = -1;
        if (!GEOSDistance_r(m_geos, g1, g2, &d)) throw std::runtime_error("GEOSDistance failed");
        return d;
    }
    double geos_seg_seg(XY a, XY b, XY c, XY d) const {
        auto g1 = t::segment(m_geos, a, b), g2 = t::segment(m_geos, c, d);
        return geos_distance(g1.get(), g2.get());
    }
    double geos_point_seg(XY p, XY a, XY b) const {
        auto g1 = t::point(m_geos, p), g2 = t::segment(m_geos, a, b);
        return geos_distance(g1.get(), g2.get());
    }

    shoal::geo::GeosContext m_geos;
    std::mt19937_64 m_rng{20240611};
    std::uniform_int_distribution<int> m_small{-4, 4};
    std::uniform_real_distribution<double> m_real{-30000.0, 30000.0};
};

TEST_F(PointTest, OrientAgreesWithGeosOrientationIndex) {
    int mismatches = 0, collinear = 0;
    for (int n = 0; n < 20000; ++n) {
        const bool small = n % 2 == 0;
        const XY a = small ? int_point() : real_point(), b = small ? int_point() : real_point();
        const XY p = small ? int_point() : real_point();
        const double o = shoal::geo::orient(a, b, p);
        const int ours = o > 0 ? 1 : o < 0 ? -1 : 0;
        // GEOS: 1 when p is counter-clockwise (left) of a->b, -1 clockwise, 0 collinear.
        const int geos = GEOSOrientationIndex_r(m_geos, a.x, a.y, b.x, b.y, p.x, p.y);
        collinear += geos == 0;
        if (ours != geos) {
            ++mismatches;
            ADD_FAILURE() << "orient " << show(a) << " " << show(b) << " " << show(p) << ": ours " << ours << ", GEOS " << geos;
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(collinear, 500) << "the sample should contain many collinear triples";
}

TEST_F(PointTest, SegmentsIntersectAgreesWithGeosOnRandomSegments) {
    int mismatches = 0, touching = 0, hits = 0;
    for (int n = 0; n < 40000; ++n) {
        const bool small = n % 4 != 3;  // 3/4 exact small-integer cases, 1/4 general doubles
        const XY a = small ? int_point() : real_point(), b = small ? int_point() : real_point();
        const XY c = small ? int_point() : real_point(), d = small ? int_point() : real_point();
        const bool ours = shoal::geo::segments_intersect(a, b, c, d);
        const bool geos = geos_intersects(a, b, c, d);
        hits += geos;
        if (geos) {
            auto g1 = t::segment(m_geos, a, b), g2 = t::segment(m_geos, c, d);
            touching += GEOSTouches_r(m_geos, g1.get(), g2.get()) == 1;
        }
        if (ours != geos) {
            ++mismatches;
            ADD_FAILURE() << show(a, b, c, d) << ": ours " << ours << ", GEOS " << geos;
        }
        // The predicate is symmetric in its two segments and in their directions.
        EXPECT_EQ(ours, shoal::geo::segments_intersect(d, c, b, a)) << show(a, b, c, d);
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(hits, 5000);
    EXPECT_GT(touching, 1000) << "the sample should contain many touching cases";
}

TEST_F(PointTest, SegmentsIntersectOnHandPickedCollinearAndTouchingCases) {
    struct Case {
        XY a, b, c, d;
    };
    const Case cases[] = {
        {{0, 0}, {4, 0}, {4, 0}, {6, 0}},    // collinear, sharing an end point
        {{0, 0}, {4, 0}, {5, 0}, {6, 0}},    // collinear, disjoint
        {{0, 0}, {4, 0}, {1, 0}, {3, 0}},    // collinear, one inside the other
        {{0, 0}, {4, 0}, {-1, 0}, {5, 0}},   // collinear, other way round
        {{0, 0}, {4, 4}, {2, 2}, {2, 2}},    // zero-length segment on the other
        {{0, 0}, {4, 4}, {2, 2.5}, {2, 2.5}},  // zero-length segment off it
        {{0, 0}, {4, 0}, {2, 0}, {2, 5}},    // T junction
        {{0, 0}, {4, 0}, {2, 1e-300}, {2, 5}},  // almost a T junction
        {{0, 0}, {1, 1}, {1, 0}, {0, 1}},    // proper crossing
        {{0, 0}, {1, 1}, {1, 1}, {1, 1}},    // point at an end point
        {{0.1, 0.1}, {0.3, 0.3}, {0.2, 0.2}, {0.7, -5}},  // end point on a segment, inexact
    };
    for (const Case& c : cases)
        EXPECT_EQ(shoal::geo::segments_intersect(c.a, c.b, c.c, c.d), geos_intersects(c.a, c.b, c.c, c.d))
            << show(c.a, c.b, c.c, c.d);
}

TEST_F(PointTest, PointSegmentDistanceAgreesWithGeos) {
    double worst = 0;
    for (int n = 0; n < 20000; ++n) {
        const bool small = n % 2 == 0;
        const XY p = small ? int_point() : real_point();
        const XY a = small ? int_point() : real_point(), b = small ? int_point() : real_point();
        double tpar = -1;
        const double d2 = shoal::geo::point_segment_dist2(p, a, b, &tpar);
        const double g = geos_point_seg(p, a, b);
        const double scale = std::max({1.0, std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y), std::abs(p.x), std::abs(p.y)});
        const double err = std::abs(std::sqrt(d2) - g);
        worst = std::max(worst, err / scale);
        ASSERT_LE(err, 1e-12 * scale) << show(p) << " to " << show(a) << "-" << show(b) << ": ours " << std::sqrt(d2)
                                      << ", GEOS " << g;
        // The parameter names the closest point: it is on the segment and at that distance.
        ASSERT_GE(tpar, 0.0);
        ASSERT_LE(tpar, 1.0);
        const XY foot = a + tpar * (b - a);
        EXPECT_NEAR(shoal::geo::distance(p, foot), g, 1e-12 * scale);
        EXPECT_LE(geos_point_seg(foot, a, b), 1e-9 * scale);
    }
    RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST_F(PointTest, SegmentSegmentDistanceAgreesWithGeosAndReturnsTheClosestPoints) {
    int zero = 0;
    for (int n = 0; n < 20000; ++n) {
        const bool small = n % 2 == 0;
        const XY a = small ? int_point() : real_point(), b = small ? int_point() : real_point();
        const XY c = small ? int_point() : real_point(), d = small ? int_point() : real_point();
        XY pa{NAN, NAN}, pc{NAN, NAN};
        const double d2 = shoal::geo::segment_segment_dist2(a, b, c, d, &pa, &pc);
        const double g = geos_seg_seg(a, b, c, d);
        const double scale = std::max({1.0, std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y), std::abs(c.x),
                                       std::abs(c.y), std::abs(d.x), std::abs(d.y)});
        zero += g == 0.0;
        ASSERT_NEAR(std::sqrt(d2), g, 1e-12 * scale) << show(a, b, c, d);
        ASSERT_EQ(d2 == 0.0, g == 0.0) << show(a, b, c, d);
        // The points returned lie on their segments and are that far apart.
        EXPECT_LE(geos_point_seg(pa, a, b), 1e-9 * scale) << show(a, b, c, d) << " point on ab " << show(pa);
        EXPECT_LE(geos_point_seg(pc, c, d), 1e-9 * scale) << show(a, b, c, d) << " point on cd " << show(pc);
        EXPECT_NEAR(shoal::geo::distance(pa, pc), g, 1e-9 * scale) << show(a, b, c, d);
    }
    EXPECT_GT(zero, 3000) << "the sample should contain many intersecting pairs";
}

TEST_F(PointTest, BoxDistanceAgreesWithGeosOnBoxPolygons) {
    for (int n = 0; n < 3000; ++n) {
        Box b1, b2;
        b1.extend(int_point());
        b1.extend(int_point());
        b2.extend(int_point());
        b2.extend(int_point());
        if (b1.minx == b1.maxx || b1.miny == b1.maxy || b2.minx == b2.maxx || b2.miny == b2.maxy) continue;
        auto g1 = t::box_polygon(m_geos, b1), g2 = t::box_polygon(m_geos, b2);
        EXPECT_NEAR(b1.distance_to(b2), geos_distance(g1.get(), g2.get()), 1e-12);
    }
    EXPECT_TRUE(Box{}.empty());
    Box b;
    b.extend(XY{1, 2});
    EXPECT_FALSE(b.empty());
    const Box g = b.grown(0.5);
    EXPECT_EQ(g.minx, 0.5);
    EXPECT_EQ(g.maxy, 2.5);
}

}  // namespace
