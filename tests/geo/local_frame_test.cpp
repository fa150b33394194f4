// Tests of geo::LocalFrame. Independent answers come from PROJ's geodesic routines on WGS84
// (geod_direct / geod_inverse, Karney's algorithms) and from known properties of UTM.

#include <shoal/geo/local_frame.hpp>

#include <cpl_error.h>
#include <geodesic.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "util/gdal_support.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <shoal/util/error.hpp>

namespace {

using shoal::UsageError;
using shoal::geo::LocalFrame;
using shoal::geo::LonLat;
using shoal::geo::XY;
using testing::AllOf;
using testing::HasSubstr;
using testing::ThrowsMessage;

constexpr double deg = std::numbers::pi / 180.0;

class Geodesic {
public:
    Geodesic() { geod_init(&m_g, 6378137.0, 1 / 298.257223563); }
    /// The point `s_m` metres from `p` along azimuth `az_deg` (clockwise from north).
    LonLat direct(LonLat p, double az_deg, double s_m) const {
        double lat = 0, lon = 0, azi2 = 0;
        geod_direct(&m_g, p.lat, p.lon, az_deg, s_m, &lat, &lon, &azi2);
        return {lon, lat};
    }
    /// Geodesic distance in metres.
    double distance(LonLat p, LonLat q) const {
        double s = 0, a1 = 0, a2 = 0;
        geod_inverse(&m_g, p.lat, p.lon, q.lat, q.lon, &s, &a1, &a2);
        return s;
    }

private:
    geod_geodesic m_g{};
};

/// Random points within `radius_m` of `centre`, uniform over the disc.
std::vector<LonLat> points_around(LonLat centre, double radius_m, int n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Geodesic geod;
    std::vector<LonLat> out;
    for (int k = 0; k < n; ++k) out.push_back(geod.direct(centre, 360 * u(rng), radius_m * std::sqrt(u(rng))));
    return out;
}

TEST(LocalFrame, ForwardInverseRoundTripWithinAMillimetre) {
    Geodesic geod;
    struct Frame {
        LocalFrame frame;
        LonLat centre;
    };
    std::vector<Frame> frames;
    for (LonLat c : {LonLat{-1.35, 50.75}, LonLat{23.35, 37.8}, LonLat{151.2, -33.9}, LonLat{24.9, 60.1}})
        frames.push_back({LocalFrame::transverse_mercator(c), c});
    frames.push_back({LocalFrame::from_user_crs("EPSG:32633"), {13.4, 52.5}});
    for (const auto& f : frames) {
        double worst = 0;
        for (const LonLat& p : points_around(f.centre, 100e3, 2000, 7)) {
            const LonLat back = f.frame.inverse(f.frame.forward(p));
            worst = std::max(worst, geod.distance(p, back));
        }
        EXPECT_LT(worst, 1e-3) << f.frame.description();
    }
}

TEST(LocalFrame, BatchForwardEqualsSingleForward) {
    const LocalFrame f = LocalFrame::transverse_mercator({-1.35, 50.75});
    const auto pts = points_around({-1.35, 50.75}, 50e3, 500, 11);
    std::vector<double> xs, ys;
    for (const auto& p : pts) {
        xs.push_back(p.lon);
        ys.push_back(p.lat);
    }
    std::size_t bad = 99;
    ASSERT_TRUE(f.forward(xs, ys, &bad));
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const XY one = f.forward(pts[i]);
        EXPECT_EQ(one.x, xs[i]);
        EXPECT_EQ(one.y, ys[i]);
    }
}

TEST(LocalFrame, TransverseMercatorOriginIsTheCentre) {
    const LocalFrame f = LocalFrame::transverse_mercator({-1.35, 50.75});
    const XY o = f.forward({-1.35, 50.75});
    EXPECT_NEAR(o.x, 0.0, 1e-6);
    EXPECT_NEAR(o.y, 0.0, 1e-6);
    EXPECT_THAT(f.description(), HasSubstr("transverse Mercator"));
    // 1 km due north of the centre lies on the y axis, 1 km away (scale 1 on the central meridian).
    const XY n = f.forward(Geodesic().direct({-1.35, 50.75}, 0.0, 1000.0));
    EXPECT_NEAR(n.x, 0.0, 1e-6);
    EXPECT_NEAR(n.y, 1000.0, 1e-6);
}

/// A 400 m step from P along a random azimuth, mapped with the jacobian and inverted, lands
/// where the geodesic from P lands (PROJ geod_direct on WGS84).
void expect_jacobian_predicts_geodesic_steps(const LocalFrame& frame, LonLat centre, std::uint64_t seed) {
    Geodesic geod;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> az_dist(0.0, 360.0);
    constexpr double step_m = 400.0;
    double worst = 0;
    for (const LonLat& p : points_around(centre, 50e3, 500, seed)) {
        const double az = az_dist(rng);
        const Eigen::Matrix2d j = frame.jacobian(p);
        const Eigen::Vector2d en(step_m * std::sin(az * deg), step_m * std::cos(az * deg));  // (east, north)
        const Eigen::Vector2d d = j * en;
        const XY q = frame.forward(p) + XY{d.x(), d.y()};
        const double miss = geod.distance(frame.inverse(q), geod.direct(p, az, step_m));
        worst = std::max(worst, miss);
        ASSERT_LT(miss, 0.01) << frame.description() << ": from (" << p.lon << ", " << p.lat << ") azimuth " << az;
    }
    testing::Test::RecordProperty("worst_miss_m_" + std::to_string(seed), std::to_string(worst));
}

TEST(LocalFrame, JacobianOfTransverseMercatorPredictsGeodesicSteps) {
    std::uint64_t seed = 1;
    for (LonLat c : {LonLat{-1.35, 50.75}, LonLat{23.35, 37.8}, LonLat{-76.3, 38.7}, LonLat{151.2, -33.9}, LonLat{24.9, 60.1}})
        expect_jacobian_predicts_geodesic_steps(LocalFrame::transverse_mercator(c), c, seed++);
}

TEST(LocalFrame, JacobianOfUtmIncludesScaleAndConvergence) {
    // 2.4 degrees off the zone's central meridian (15E): convergence about 1.9 degrees and
    // scale about 0.9997, both far larger than the 1 cm tolerance over a 400 m step.
    expect_jacobian_predicts_geodesic_steps(LocalFrame::from_user_crs("EPSG:32633"), {12.6, 52.5}, 42);
}

TEST(LocalFrame, UserUtmZoneGivesKnownCoordinates) {
    const LocalFrame f = LocalFrame::from_user_crs("EPSG:32633");  // UTM 33N: lon_0 15E, k0 0.9996, x_0 500 km
    EXPECT_THAT(f.description(), HasSubstr("EPSG:32633"));
    const XY eq = f.forward({15.0, 0.0});
    EXPECT_NEAR(eq.x, 500000.0, 1e-3);
    EXPECT_NEAR(eq.y, 0.0, 1e-3);
    // On the central meridian, northing = k0 x the meridian arc from the equator.
    const double arc = Geodesic().distance({15.0, 0.0}, {15.0, 50.0});
    const XY p = f.forward({15.0, 50.0});
    EXPECT_NEAR(p.x, 500000.0, 1e-3);
    EXPECT_NEAR(p.y, 0.9996 * arc, 1e-3);
    // Its scale error on the central meridian is 1 - k0.
    EXPECT_NEAR(f.max_scale_error({14.9999, 49.9}, {15.0001, 50.1}), 4e-4, 2e-7);
    // Rebuilt from its definition, it is the same frame.
    const LocalFrame g = LocalFrame::from_definition(f.definition());
    EXPECT_EQ(g.forward({16.0, 51.0}), f.forward({16.0, 51.0}));
}

TEST(LocalFrame, TransverseMercatorRebuiltFromItsDefinitionIsTheSame) {
    const LocalFrame f = LocalFrame::transverse_mercator({23.35, 37.8});
    const LocalFrame g = LocalFrame::from_definition(f.definition());
    EXPECT_EQ(g.definition(), f.definition());
    EXPECT_EQ(g.description(), f.description());
    LocalFrame copy(f);
    LocalFrame assigned = LocalFrame::transverse_mercator({0, 0});
    assigned = f;
    for (const LonLat& p : points_around({23.35, 37.8}, 30e3, 50, 3)) {
        EXPECT_EQ(g.forward(p), f.forward(p));
        EXPECT_EQ(copy.forward(p), f.forward(p));
        EXPECT_EQ(assigned.forward(p), f.forward(p));
    }
}

// shoal's own transverse Mercator is made from its PROJ pipeline, with no GDAL parse and no
// search of PROJ's database; the same text given as a user's CRS goes through both. The two
// must give the same numbers, bit for bit: forward, inverse, in a batch, on the thread that
// made the frame and on others (each makes its own copy of the operation).
TEST(LocalFrame, OwnTransverseMercatorEqualsPROJsSearchedOperationBitForBit) {
    std::mt19937_64 rng(20261205);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // PROJ rounds a CRS's angle within about 1e-8 of a whole degree to it: such centres
    // (up to 1.5e-8 off) are made the searched way, those just beyond by the pipeline.
    std::vector<LonLat> centres{{0, 0},           {-180, 0},          {180, 89.5},           {24.5, 59.85},
                                {-1.35, 50.75},   {151.2, -33.9},     {12.000000001, 45},    {24.5, 59.999999995},
                                {45, 89.999999999}, {-45.999999991, 0.000000009}, {12.00000002, -7.99999998}, {-0.0, -0.0}};
    for (int k = 0; k < 24; ++k) centres.push_back({-180 + 360 * u(rng), -85 + 170 * u(rng)});
    auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    auto near_whole = [](double v) { return v != std::round(v) && std::fabs(v - std::round(v)) <= 1.5e-8; };
    int computed_by_shoal_count = 0;
    unsigned seed = 1;
    for (const LonLat c : centres) {
        const LocalFrame own = LocalFrame::transverse_mercator(c);
        const LocalFrame searched = LocalFrame::from_user_crs(own.definition());
        const LocalFrame rebuilt = LocalFrame::from_definition(own.definition());
        ASSERT_FALSE(searched.computed_by_shoal());
        // The centre as written (9 decimals) decides the path.
        double lat = 0, lon = 0;
        ASSERT_EQ(std::sscanf(own.definition().c_str(), "+proj=tmerc +lat_0=%lf +lon_0=%lf", &lat, &lon), 2);
        EXPECT_EQ(own.computed_by_shoal(), !near_whole(lat) && !near_whole(lon)) << own.definition();
        EXPECT_EQ(rebuilt.computed_by_shoal(), own.computed_by_shoal());
        EXPECT_EQ(LocalFrame(own).computed_by_shoal(), own.computed_by_shoal());
        computed_by_shoal_count += own.computed_by_shoal() ? 1 : 0;
        const auto pts = points_around(c, 200e3, 300, seed++);
        std::vector<double> xs, ys, xs2, ys2;
        for (const LonLat& p : pts) {
            const XY a = own.forward(p), b = searched.forward(p), r = rebuilt.forward(p);
            ASSERT_EQ(bits(a.x), bits(b.x)) << own.definition() << " at " << p.lon << ", " << p.lat;
            ASSERT_EQ(bits(a.y), bits(b.y)) << own.definition() << " at " << p.lon << ", " << p.lat;
            ASSERT_EQ(bits(r.x), bits(a.x));
            ASSERT_EQ(bits(r.y), bits(a.y));
            // A local point off the projected ones (a hull's corner), back to lon/lat.
            const XY q{a.x + 50 * (u(rng) - 0.5), a.y + 50 * (u(rng) - 0.5)};
            const LonLat ia = own.inverse(q), ib = searched.inverse(q);
            ASSERT_EQ(bits(ia.lon), bits(ib.lon)) << own.definition();
            ASSERT_EQ(bits(ia.lat), bits(ib.lat)) << own.definition();
            xs.push_back(p.lon);
            ys.push_back(p.lat);
        }
        xs2 = xs;
        ys2 = ys;
        std::size_t bad = 0;
        ASSERT_TRUE(own.forward(xs, ys, &bad));
        ASSERT_TRUE(searched.forward(xs2, ys2, &bad));
        EXPECT_EQ(xs, xs2);
        EXPECT_EQ(ys, ys2);
        // On another thread each frame makes its own operation (from the pipeline, or by the search).
        std::vector<XY> there_own, there_searched;
        std::thread([&] {
            for (const LonLat& p : pts) {
                there_own.push_back(own.forward(p));
                there_searched.push_back(searched.forward(p));
            }
        }).join();
        for (std::size_t i = 0; i < pts.size(); ++i) ASSERT_EQ(there_own[i], there_searched[i]);
    }
    EXPECT_EQ(computed_by_shoal_count, static_cast<int>(centres.size()) - 4);  // the four a hair off whole degrees
}

TEST(LocalFrame, ScaleErrorOfTransverseMercatorGrowsAwayFromTheCentralMeridian) {
    // Point scale of a transverse Mercator with k0 = 1 is about 1 + x^2 / (2 R^2): at 0.5 degrees
    // of longitude off the meridian at 50N (about 35.8 km) that is 1.6e-5.
    const LocalFrame f = LocalFrame::transverse_mercator({0.0, 50.0});
    const Geodesic geod;
    const double x = geod.distance({0.0, 50.0}, {0.5, 50.0});
    const double r = 6371e3;
    EXPECT_NEAR(f.max_scale_error({-0.5, 49.9}, {0.5, 50.1}), x * x / (2 * r * r), 5e-7);
}

TEST(LocalFrame, MetresPerDegreeMatchesGeodesicDistances) {
    const Geodesic geod;
    for (double lat : {-60.0, -33.9, 0.0, 12.5, 37.8, 50.75, 60.1, 80.0}) {
        const Eigen::Vector2d mpd = shoal::geo::metres_per_degree(lat);
        const double h = 1e-4;
        EXPECT_NEAR(mpd.x(), geod.distance({0.0, lat}, {h, lat}) / h, 1e-2) << lat;
        EXPECT_NEAR(mpd.y(), geod.distance({0.0, lat - h / 2}, {0.0, lat + h / 2}) / h, 1e-2) << lat;
    }
}

TEST(LocalFrame, GeographicOrUnknownCrsIsAUsageError) {
    shoal::detail::QuietErrors quiet;  // GDAL would also print its own message to stderr
    EXPECT_THAT([] { LocalFrame::from_user_crs("EPSG:4326"); },
                ThrowsMessage<UsageError>(AllOf(HasSubstr("EPSG:4326"), HasSubstr("not a projected CRS"))));
    EXPECT_THAT([] { LocalFrame::from_user_crs("+proj=longlat +datum=WGS84"); },
                ThrowsMessage<UsageError>(HasSubstr("+proj=longlat")));
    EXPECT_THAT([] { LocalFrame::from_user_crs("no such crs, really"); },
                ThrowsMessage<UsageError>(AllOf(HasSubstr("no such crs, really"), HasSubstr("not one GDAL understands"))));
    EXPECT_THAT([] { LocalFrame::from_user_crs(""); }, ThrowsMessage<UsageError>(HasSubstr("CRS")));
    EXPECT_THAT([] { LocalFrame::from_definition("EPSG:999999"); }, ThrowsMessage<UsageError>(HasSubstr("EPSG:999999")));
}

}  // namespace
