// The report's coast layer against GEOS: for random charts (islands with lakes, islands in
// those lakes, shallow areas of several depths), each tile's features must cover exactly what
// GEOS's intersection of the chart's polygons with the tile covers.
#include <Eigen/Core>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "geo/geos_context.hpp"
#include "report/qgis/chart_layer.hpp"
#include <shoal/audit/audit.hpp>

namespace shoal::report {
namespace {

using Ring = std::vector<geo::LonLat>;

/// A star-shaped ring around c (radius between lo and hi degrees), counter-clockwise or not.
Ring star(std::mt19937& rng, geo::LonLat c, double lo, double hi, bool ccw) {
    std::uniform_real_distribution<double> rad(lo, hi);
    const int n = std::uniform_int_distribution<int>(5, 24)(rng);
    Ring r;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n;
        const double d = rad(rng);
        r.push_back({c.lon + d * std::cos(a), c.lat + d * std::sin(a)});
    }
    if (!ccw) std::reverse(r.begin(), r.end());
    r.push_back(r.front());
    return r;
}

geo::GeomPtr polygon(const geo::GeosContext& ctx, const std::vector<Ring>& rings) {
    std::vector<std::vector<geo::XY>> xy;
    for (const auto& r : rings) {
        auto& v = xy.emplace_back();
        for (const auto& p : r) v.push_back({p.lon, p.lat});
    }
    return geo::make_polygon(ctx, xy);
}

double area(const geo::GeosContext& ctx, const GEOSGeometry* g) {
    double a = 0;
    GEOSArea_r(ctx, g, &a);
    return a;
}

TEST(ChartLayer, TilesEqualGeosIntersectionOfTheChartWithEachTile) {
    std::mt19937 rng(17);
    const geo::GeosContext ctx;
    for (int trial = 0; trial < 25; ++trial) {
        coast::Coastline coast;
        // Per group (kind, depth): the polygons as GEOS sees them, unioned.
        struct Truth {
            coast::HazardKind kind;
            double depth;
            std::vector<geo::GeomPtr> parts;
        };
        std::vector<Truth> truth;
        truth.push_back({coast::HazardKind::land, NAN, {}});
        truth.push_back({coast::HazardKind::shallow, 2.0, {}});
        truth.push_back({coast::HazardKind::shallow, 5.0, {}});
        auto add = [&](std::size_t group, const std::vector<Ring>& rings) {
            for (const auto& r : rings) {
                coast::Polyline pl;
                pl.points = r;
                pl.land_left = true;
                pl.hazard.kind = truth[group].kind;
                pl.hazard.depth_m = truth[group].depth;
                coast.polylines.push_back(pl);
            }
        };
        // Islands in separate cells of 0.04 degrees (tiles are 0.05: they cross tile edges).
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 3; ++j) {
                std::uniform_real_distribution<double> jitter(-0.004, 0.004);
                const geo::LonLat c{10.0 + 0.04 * i + 0.02 + jitter(rng), 56.0 + 0.04 * j + 0.02 + jitter(rng)};
                const std::size_t group = std::uniform_int_distribution<std::size_t>(0, 2)(rng);
                const Ring shell = star(rng, c, 0.010, 0.016, true);
                if (std::bernoulli_distribution(0.5)(rng)) {
                    // A lake, and perhaps an island in it.
                    const Ring lake = star(rng, c, 0.003, 0.005, false);
                    add(group, {shell, lake});
                    truth[group].parts.push_back(polygon(ctx, {shell, lake}));
                    if (std::bernoulli_distribution(0.5)(rng)) {
                        const Ring islet = star(rng, c, 0.0006, 0.0012, true);
                        add(group, {islet});
                        truth[group].parts.push_back(polygon(ctx, {islet}));
                    }
                } else {
                    add(group, {shell});
                    truth[group].parts.push_back(polygon(ctx, {shell}));
                }
            }
        std::set<ChartTile> tiles;
        for (int k = 0; k < 6; ++k) {
            std::uniform_real_distribution<double> lon(10.0, 10.16), lat(56.0, 56.12);
            tiles.insert(tile_of({lon(rng), lat(rng)}));
        }
        const std::vector<ChartFeature> features = chart_features(coast, tiles);
        // On threads: the same features, point for point, in the same order.
        for (const unsigned jobs : {2u, 3u, 8u}) {
            const std::vector<ChartFeature> threaded = chart_features(coast, tiles, jobs);
            ASSERT_EQ(threaded.size(), features.size()) << "trial " << trial << ", " << jobs << " threads";
            for (std::size_t k = 0; k < features.size(); ++k) {
                EXPECT_TRUE(threaded[k].tile == features[k].tile && threaded[k].kind == features[k].kind) << "trial " << trial << " feature " << k;
                EXPECT_EQ(threaded[k].polygons, features[k].polygons) << "trial " << trial << " feature " << k << ", " << jobs << " threads";
            }
        }
        // Sorted by tile, then kind and depth; one feature per (tile, group).
        for (std::size_t k = 1; k < features.size(); ++k) {
            const auto& a = features[k - 1];
            const auto& b = features[k];
            ASSERT_TRUE(a.tile < b.tile || (a.tile == b.tile && (a.kind < b.kind || (a.kind == b.kind && a.depth_m < b.depth_m))))
                << "trial " << trial << " feature " << k;
        }
        for (const ChartTile& t : tiles) {
            const double x0 = (t.col - 3600) * chart_tile_deg, y0 = (t.row - 1800) * chart_tile_deg;
            geo::GeomPtr box = polygon(ctx, {{{x0, y0}, {x0 + chart_tile_deg, y0}, {x0 + chart_tile_deg, y0 + chart_tile_deg},
                                              {x0, y0 + chart_tile_deg}, {x0, y0}}});
            for (auto& g : truth) {
                geo::GeomPtr expected = geo::own(ctx, GEOSGeom_createEmptyPolygon_r(ctx), "empty");
                for (const auto& p : g.parts) expected = geo::own(ctx, GEOSUnion_r(ctx, expected.get(), p.get()), "union");
                expected = geo::own(ctx, GEOSIntersection_r(ctx, expected.get(), box.get()), "intersection");
                geo::GeomPtr got = geo::own(ctx, GEOSGeom_createEmptyPolygon_r(ctx), "empty");
                int n = 0;
                for (const auto& f : features) {
                    if (!(f.tile == t) || f.kind != g.kind || !(f.depth_m == g.depth || (std::isnan(f.depth_m) && std::isnan(g.depth)))) continue;
                    ++n;
                    for (const auto& rings : f.polygons) {
                        geo::GeomPtr p = polygon(ctx, rings);
                        EXPECT_TRUE(GEOSisValid_r(ctx, p.get())) << "trial " << trial << " tile " << tile_key(t);
                        got = geo::own(ctx, GEOSUnion_r(ctx, got.get(), p.get()), "union");
                    }
                }
                EXPECT_LE(n, 1) << "one feature per tile and group";
                geo::GeomPtr diff = geo::own(ctx, GEOSSymDifference_r(ctx, expected.get(), got.get()), "difference");
                EXPECT_LT(area(ctx, diff.get()), 1e-12 + 1e-9 * area(ctx, expected.get()))
                    << "trial " << trial << " tile " << tile_key(t) << ": expected area " << area(ctx, expected.get()) << ", got "
                    << area(ctx, got.get());
            }
        }
    }
}

TEST(ChartLayer, TilesNearATrackFollowItsSegmentsAndTheMargin) {
    auto tiles_near = [](const std::vector<geo::LonLat>& line, double margin_m) {
        std::set<ChartTile> out;
        add_tiles_near(out, line, margin_m);
        return out;
    };
    // A segment 0.5 degrees long along a parallel: every tile it crosses, and the rows within 2 km.
    const std::set<ChartTile> t = tiles_near({{10.01, 56.025}, {10.51, 56.025}}, 2000.0);
    for (double lon = 10.01; lon < 10.51; lon += 0.01) EXPECT_TRUE(t.count(tile_of({lon, 56.025}))) << lon;
    // 2 km is 0.018 degrees of latitude: 56.025 +- 0.018 stays within row 56.00-56.05.
    for (const ChartTile& x : t) EXPECT_EQ(x.row, tile_of({10.0, 56.025}).row);
    EXPECT_EQ(tile_key(tile_of({10.01, 56.025})), "R2920C3800");
    // Near a tile edge, the margin reaches the next row.
    const std::set<ChartTile> u = tiles_near({{10.02, 56.049}}, 2000.0);
    EXPECT_TRUE(u.count(tile_of({10.02, 56.06})));
    EXPECT_TRUE(u.count(tile_of({10.02, 56.04})));
}

/// The tiles near a line are those of each point's own margin in degrees (metres_per_degree at
/// its latitude), whatever the bounds over the line that spare most points that computation:
/// random lines from the equator to the poles, across the antimeridian and over tiles' edges,
/// margins from 1 m to 20 km.
TEST(ChartLayer, TilesNearALineAreThoseOfEachPointsOwnMargin) {
    auto reference = [](const std::vector<geo::LonLat>& line, double margin_m) {
        std::set<ChartTile> out;
        auto mark = [&](geo::LonLat p) {
            if (!std::isfinite(p.lon) || !std::isfinite(p.lat)) return;
            const Eigen::Vector2d m = geo::metres_per_degree(std::clamp(p.lat, -89.0, 89.0));
            const double dlat = margin_m / m.y(), dlon = margin_m / std::max(1.0, m.x());
            const ChartTile a = tile_of({p.lon - dlon, std::max(-90.0, p.lat - dlat)});
            const ChartTile b = tile_of({p.lon + dlon, std::min(89.999999, p.lat + dlat)});
            for (int r = a.row; r <= b.row; ++r)
                for (int c = a.col; c <= b.col; ++c) out.insert({c, r});
        };
        for (std::size_t i = 0; i < line.size(); ++i) {
            mark(line[i]);
            if (i == 0) continue;
            const geo::LonLat a = line[i - 1], b = line[i];
            const double span = std::max(std::fabs(b.lon - a.lon), std::fabs(b.lat - a.lat));
            const int n = static_cast<int>(std::min(1e5, std::ceil(span / (chart_tile_deg / 4))));
            for (int k = 1; k < n; ++k) {
                const double f = static_cast<double>(k) / n;
                mark({a.lon + f * (b.lon - a.lon), a.lat + f * (b.lat - a.lat)});
            }
        }
        return out;
    };
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int trial = 0; trial < 3000; ++trial) {
        const double margin = std::pow(10.0, 4.3 * unit(rng));
        geo::LonLat p{-180 + 360 * unit(rng), trial % 10 == 0 ? 89.99 * (2 * unit(rng) - 1) : 80 * (2 * unit(rng) - 1)};
        if (trial % 7 == 0) p.lat = std::round(p.lat / chart_tile_deg) * chart_tile_deg + 1e-9 * (unit(rng) - 0.5);  // on a tile's edge
        std::vector<geo::LonLat> line;
        const double step = trial % 3 == 0 ? 0.0005 : 0.01;
        for (int k = 0; k < 60; ++k) {
            line.push_back(p);
            p = {p.lon + step * (2 * unit(rng) - 1), std::clamp(p.lat + step * (2 * unit(rng) - 1), -89.999, 89.999)};
        }
        if (trial % 11 == 0) line.push_back({NAN, 10});
        if (trial % 13 == 0) line = {{p.lon, 2.6 + 3 * unit(rng)}, {p.lon + 0.4, -2.6 - 3 * unit(rng)}, {p.lon + 0.5, 3.0}};  // over the equator
        std::set<ChartTile> got;
        add_tiles_near(got, line, margin);
        ASSERT_EQ(got, reference(line, margin)) << "trial " << trial << ", margin " << margin << " m, from " << line[0].lon << ", " << line[0].lat;
    }
}

/// The run's tiles on any number of threads are the union of each line's (add_tiles_near):
/// runs of tracks of very different lengths, tracks without a line, one track, none.
TEST(ChartLayer, TheRunsTilesAreEachLinesOnAnyNumberOfThreads) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int trial = 0; trial < 40; ++trial) {
        audit::AuditResult r;
        const int tracks = trial == 0 ? 0 : trial == 1 ? 1 : 1 + static_cast<int>(30 * unit(rng));
        for (int k = 0; k < tracks; ++k) {
            audit::TrackResult& t = r.tracks.emplace_back();
            const int lines = static_cast<int>(3 * unit(rng));  // 0: a track refused, or of no line
            for (int l = 0; l < lines; ++l) {
                auto& line = t.summary.lines.emplace_back();
                geo::LonLat p{-10 + 40 * unit(rng), 30 + 30 * unit(rng)};
                const int n = unit(rng) < 0.2 ? 2000 : static_cast<int>(50 * unit(rng));
                for (int i = 0; i < n; ++i) {
                    line.push_back(p);
                    p = {p.lon + 0.02 * (2 * unit(rng) - 1), p.lat + 0.02 * (2 * unit(rng) - 1)};
                }
            }
        }
        std::set<ChartTile> expected;
        for (const auto& t : r.tracks)
            for (const auto& line : t.summary.lines) add_tiles_near(expected, line);
        for (const unsigned jobs : {1u, 2u, 3u, 8u}) ASSERT_EQ(tiles_near(r, jobs), expected) << "trial " << trial << ", " << jobs << " threads";
    }
}

}  // namespace
}  // namespace shoal::report
