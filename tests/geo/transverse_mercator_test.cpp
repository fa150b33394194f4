// shoal's own transverse Mercator against PROJ itself: the pipeline it copies, made by PROJ
// from the same text, gives the same bits forward and inverse, and refuses the same points.
#include "geo/transverse_mercator.hpp"

#include <gtest/gtest.h>
#include <proj.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using shoal::geo::TransverseMercator;

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

/// PROJ's pipeline for the centre, as shoal's frame definition writes it (9 decimals).
struct ProjPipeline {
    PJ_CONTEXT* ctx = proj_context_create();
    PJ* op = nullptr;
    ProjPipeline(const std::string& lat, const std::string& lon) {
        proj_log_level(ctx, PJ_LOG_NONE);
        const std::string text = "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad +step +proj=tmerc +lat_0=" + lat +
                                 " +lon_0=" + lon + " +k=1 +x_0=0 +y_0=0 +ellps=WGS84";
        op = proj_create(ctx, text.c_str());
    }
    ~ProjPipeline() {
        if (op) proj_destroy(op);
        proj_context_destroy(ctx);
    }
    ProjPipeline(const ProjPipeline&) = delete;
    ProjPipeline& operator=(const ProjPipeline&) = delete;
};

std::string nine_decimals(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9f", v);
    return buf;
}

/// Both give no point (refused, or not a number), or the same bits.
void expect_same(bool ok, double x, double y, PJ_COORD c, const std::string& what) {
    ok = ok && std::isfinite(x) && std::isfinite(y);
    const bool proj_ok = std::isfinite(c.v[0]) && std::isfinite(c.v[1]) && c.v[0] != HUGE_VAL;
    ASSERT_EQ(ok, proj_ok) << what << ": PROJ gives " << c.v[0] << ", " << c.v[1] << "; own " << x << ", " << y;
    if (!ok) return;
    ASSERT_EQ(bits(x), bits(c.v[0])) << what;
    ASSERT_EQ(bits(y), bits(c.v[1])) << what;
}

}  // namespace

TEST(TransverseMercator, GivesPROJsPipelineBitForBitEverywhereItProjects) {
    std::mt19937_64 rng(20261206);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::pair<double, double>> centres{{0, 0}, {59.85, 24.5}, {-33.9, 151.2}, {89.5, 180}, {-89.9, -180}, {36.1, -5.35}, {-0.0, -0.0}};
    for (int k = 0; k < 60; ++k) centres.push_back({-89.9 + 179.8 * u(rng), -180 + 360 * u(rng)});
    long projected = 0, refused = 0;
    for (const auto& [lat0, lon0] : centres) {
        const std::string lat_text = nine_decimals(lat0), lon_text = nine_decimals(lon0);
        const TransverseMercator own(std::strtod(lat_text.c_str(), nullptr), std::strtod(lon_text.c_str(), nullptr));
        const ProjPipeline proj(lat_text, lon_text);
        ASSERT_NE(proj.op, nullptr) << lat_text << " " << lon_text;
        const std::string centre = "centre " + lat_text + ", " + lon_text;
        for (int i = 0; i < 2500; ++i) {
            // Near the centre (where shoal works), far from it (up to and past where the
            // projection ends), over the poles and past them, and far outside any range.
            double lon, lat;
            switch (i % 5) {
            case 0: lon = lon0 + 4 * (u(rng) - 0.5); lat = lat0 + 4 * (u(rng) - 0.5); break;
            case 1: lon = lon0 + 360 * (u(rng) - 0.5); lat = -90 + 180 * u(rng); break;
            case 2: lon = -720 + 1440 * u(rng); lat = -90.0000001 + 180.0000002 * u(rng); break;
            case 3: lon = lon0 + 180 * (u(rng) - 0.5); lat = (u(rng) < 0.5 ? -1 : 1) * (90 - 1e-6 * u(rng)); break;
            default: lon = lon0 + (u(rng) < 0.5 ? -90 : 90) + 1e-3 * (u(rng) - 0.5); lat = lat0 + 10 * (u(rng) - 0.5); break;
            }
            double x = 0, y = 0;
            const bool ok = own.forward(lon, lat, x, y);
            const PJ_COORD f = proj_trans(proj.op, PJ_FWD, proj_coord(lon, lat, 0, 0));
            expect_same(ok, x, y, f, centre + " forward " + nine_decimals(lon) + ", " + nine_decimals(lat));
            ok ? ++projected : ++refused;
            // Back from a point near the projected one, and from one anywhere in the plane.
            for (const double scale : {50.0, 3.0e7}) {
                const double px = (ok ? x : 0) + scale * (u(rng) - 0.5), py = (ok ? y : 0) + scale * (u(rng) - 0.5);
                double ilon = 0, ilat = 0;
                const bool iok = own.inverse(px, py, ilon, ilat);
                const PJ_COORD b = proj_trans(proj.op, PJ_INV, proj_coord(px, py, 0, 0));
                expect_same(iok, ilon, ilat, b, centre + " inverse " + std::to_string(px) + ", " + std::to_string(py));
            }
        }
    }
    // The cases reach both sides: points projected, and points PROJ refuses.
    EXPECT_GT(projected, 100000);
    EXPECT_GT(refused, 1000);
}

TEST(TransverseMercator, RefusesWhatPROJRefuses) {
    const TransverseMercator own(59.85, 24.5);
    const ProjPipeline proj("59.850000000", "24.500000000");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double points[][2] = {{nan, 60}, {24, nan}, {HUGE_VAL, 60}, {24, HUGE_VAL}, {24, 90.0000001}, {24, -90.0000001},
                                {24, 90}, {600, 60}, {-600, 60}, {573, 60}, {24.5 + 150, 0}, {24.5 - 89.9, 0}, {-1e300, 1e300}};
    for (const auto& p : points) {
        double x = 0, y = 0;
        const bool ok = own.forward(p[0], p[1], x, y);
        expect_same(ok, x, y, proj_trans(proj.op, PJ_FWD, proj_coord(p[0], p[1], 0, 0)), "forward " + std::to_string(p[0]) + ", " + std::to_string(p[1]));
        double lon = 0, lat = 0;
        const bool iok = own.inverse(p[0] * 1e5, p[1] * 1e5, lon, lat);
        expect_same(iok, lon, lat, proj_trans(proj.op, PJ_INV, proj_coord(p[0] * 1e5, p[1] * 1e5, 0, 0)), "inverse");
    }
}

// Every UTM zone of WGS 84, north and south, against the operation PROJ finds in its database
// from EPSG:4326 to EPSG:326zz / 327zz (what OGR's coordinate transformation runs): the same bits
// forward and back, the same points refused.
TEST(TransverseMercator, UtmZonesAreTheOperationsPROJFindsForTheirEpsgCodes) {
    PJ_CONTEXT* ctx = proj_context_create();
    proj_log_level(ctx, PJ_LOG_NONE);
    std::mt19937_64 rng(20261207);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    long compared = 0;
    for (int zone = 1; zone <= 60; ++zone)
        for (const bool south : {false, true}) {
            const std::string target = "EPSG:" + std::to_string((south ? 32700 : 32600) + zone);
            PJ* raw = proj_create_crs_to_crs(ctx, "EPSG:4326", target.c_str(), nullptr);
            ASSERT_NE(raw, nullptr) << target;
            PJ* op = proj_normalize_for_visualization(ctx, raw);  // lon, lat order, as OGR's traditional GIS order
            proj_destroy(raw);
            ASSERT_NE(op, nullptr) << target;
            const TransverseMercator own = TransverseMercator::utm(zone, south);
            const double lon0 = zone * 6.0 - 183.0;
            for (int i = 0; i < 400; ++i) {
                // Within the zone and its neighbours (a chart's box), and anywhere.
                const bool near = i % 4 != 0;
                const double lon = near ? lon0 + 20 * (u(rng) - 0.5) : -180 + 360 * u(rng);
                const double lat = near ? (south ? -84 * u(rng) : 84 * u(rng)) : -90 + 180 * u(rng);
                double x = 0, y = 0;
                const bool ok = own.forward(lon, lat, x, y);
                expect_same(ok, x, y, proj_trans(op, PJ_FWD, proj_coord(lon, lat, 0, 0)), target + " forward " + nine_decimals(lon) + ", " + nine_decimals(lat));
                double ilon = 0, ilat = 0;
                const double px = 500000 + 1.2e6 * (u(rng) - 0.5), py = (south ? 1e7 : 0) + (south ? -1 : 1) * 9.3e6 * u(rng);
                const bool iok = own.inverse(px, py, ilon, ilat);
                expect_same(iok, ilon, ilat, proj_trans(op, PJ_INV, proj_coord(px, py, 0, 0)), target + " inverse");
                ++compared;
            }
            proj_destroy(op);
        }
    proj_context_destroy(ctx);
    EXPECT_EQ(compared, 48000);
    EXPECT_THROW(TransverseMercator::utm(0, false), std::invalid_argument);
    EXPECT_THROW(TransverseMercator::utm(61, true), std::invalid_argument);
}
