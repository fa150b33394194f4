// Tests of geo::JacobianField. The independent answer is the Jacobian measured along
// geodesics (PROJ's geod_direct, Karney's algorithm): the local displacement of a point 50 m
// east and 50 m north of p, each way, over twice the distance.

#include <shoal/geo/jacobian_field.hpp>

#include <geodesic.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <shoal/geo/local_frame.hpp>

namespace {

using shoal::geo::Box;
using shoal::geo::JacobianField;
using shoal::geo::LocalFrame;
using shoal::geo::LonLat;
using shoal::geo::XY;

/// The frame's Jacobian at p measured along geodesics: (east, north) metres to local metres.
Eigen::Matrix2d geodesic_jacobian(const LocalFrame& frame, LonLat p) {
    geod_geodesic g{};
    geod_init(&g, 6378137.0, 1 / 298.257223563);
    constexpr double s = 50.0;
    auto at = [&](double azimuth) {
        double lat = 0, lon = 0, azi2 = 0;
        geod_direct(&g, p.lat, p.lon, azimuth, s, &lat, &lon, &azi2);
        return frame.forward({lon, lat});
    };
    const XY e = (1 / (2 * s)) * (at(90) - at(270)), n = (1 / (2 * s)) * (at(0) - at(180));
    Eigen::Matrix2d j;
    j << e.x, n.x, e.y, n.y;
    return j;
}

/// The local box of `half_m` metres about the centre's local position.
Box box_about(const LocalFrame& frame, LonLat centre, double half_x_m, double half_y_m) {
    const XY c = frame.forward(centre);
    return {c.x - half_x_m, c.y - half_y_m, c.x + half_x_m, c.y + half_y_m};
}

struct Case {
    std::string name;
    LocalFrame frame;
    Box box;
};

TEST(JacobianField, ReproducesTheFramesScaleAndConvergence) {
    std::vector<Case> cases;
    const LonLat helsinki{24.9, 60.1}, baltic{19.5, 59.5}, svalbard{15.0, 78.2}, equator{-40.0, 0.3}, denmark{10.5, 56.0};
    cases.push_back({"TM Helsinki 150 x 100 km", LocalFrame::transverse_mercator(helsinki), {}});
    cases.back().box = box_about(cases.back().frame, helsinki, 75e3, 50e3);
    cases.push_back({"TM Baltic 460 x 220 km", LocalFrame::transverse_mercator(baltic), {}});
    cases.back().box = box_about(cases.back().frame, baltic, 230e3, 110e3);
    cases.push_back({"TM Svalbard 300 x 300 km", LocalFrame::transverse_mercator(svalbard), {}});
    cases.back().box = box_about(cases.back().frame, svalbard, 150e3, 150e3);
    cases.push_back({"TM equator 600 x 400 km", LocalFrame::transverse_mercator(equator), {}});
    cases.back().box = box_about(cases.back().frame, equator, 300e3, 200e3);
    // A user's CRS, the data far off its central meridian; and one that is not conformal.
    cases.push_back({"UTM 33N east of its zone", LocalFrame::from_user_crs("EPSG:32633"), {}});
    cases.back().box = box_about(cases.back().frame, baltic, 150e3, 150e3);
    cases.push_back({"LAEA Europe", LocalFrame::from_user_crs("EPSG:3035"), {}});
    cases.back().box = box_about(cases.back().frame, denmark, 200e3, 200e3);
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(0, 1);
    for (const Case& c : cases) {
        const JacobianField field(c.frame, c.box);
        ASSERT_GT(field.degree(), 0) << c.name << ": no fit kept (worst " << field.worst_difference() << ")";
        EXPECT_LE(field.worst_difference(), JacobianField::tolerance) << c.name;
        double worst = 0, worst_old = 0;
        for (int k = 0; k < 2000; ++k) {
            const XY p{c.box.minx + u(rng) * (c.box.maxx - c.box.minx), c.box.miny + u(rng) * (c.box.maxy - c.box.miny)};
            ASSERT_TRUE(field.covers(p)) << c.name;
            const LonLat ll = c.frame.inverse(p);
            const Eigen::Matrix2d want = geodesic_jacobian(c.frame, ll);
            worst = std::max(worst, (field.at(p) - want).cwiseAbs().maxCoeff());
            worst_old = std::max(worst_old, (c.frame.jacobian(ll) - want).cwiseAbs().maxCoeff());
        }
        // The series is nearer the geodesic answer than the frame's own 1 m difference is.
        EXPECT_LT(worst, JacobianField::tolerance) << c.name << " (degree " << field.degree() << ")";
        std::printf("%s: degree %d, worst at the check points %.2g, against geodesics %.2g (the frame's 1 m difference %.2g)\n", c.name.c_str(), field.degree(), field.worst_difference(), worst, worst_old);
        EXPECT_LT(worst, worst_old) << c.name;
        // Outside the box: not covered.
        EXPECT_FALSE(field.covers({c.box.maxx + 1, c.box.miny})) << c.name;
        EXPECT_FALSE(field.covers({c.box.minx, c.box.miny - 1})) << c.name;
    }
}

TEST(JacobianField, CoversNothingWhereNoSeriesReproducesTheFrame) {
    const LocalFrame frame = LocalFrame::transverse_mercator({24.9, 60.1});
    // A box reaching round half the globe: the Jacobian there is no low-degree polynomial
    // (and PROJ fails at some nodes); an empty box and a NaN box have nothing to fit.
    for (const Box& box : {Box{-2e7, -9e6, 2e7, 9e6}, Box{0, 0, 0, 0}, Box{0, 0, NAN, 1}}) {
        const JacobianField field(frame, box);
        EXPECT_EQ(field.degree(), 0);
        EXPECT_GT(field.worst_difference(), JacobianField::tolerance);
        EXPECT_FALSE(field.covers({0, 0}));
        EXPECT_FALSE(field.covers({1e5, 1e5}));
    }
}

}  // namespace
