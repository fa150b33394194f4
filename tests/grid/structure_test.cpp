// Structures in the grid, on the real S-57 cut tests/data/coast/US5WA22M_tacoma_cut.000 (Port
// of Tacoma: Piers 23-25, a wharf, pontoons, dolphins; tests/data/README.md). What is checked,
// each against an answer found independently:
// - every SLCONS, PONTON and MORFAC feature is in the grid, as polylines of kind structure
//   with the kind of its class and category and its OBJNAM, for every limiting depth;
// - the bands and discs lines and points become agree with GEOS: the detector's clearance of
//   a tiny hull at random points near them lies between the GEOS distance to the charted line
//   or point less the documented width, and that less the 0.5 % the polygons are circumscribed
//   by (docs/method.md), on 20,000 points;
// - the table survives the grid file, whose version 3 (no structures) is refused and, as a
//   cache, rebuilt.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/util/error.hpp>
#include "test_support.hpp"

namespace shoal {
namespace {

namespace t = shoal::test;
using coast::HazardKind;
using coast::StructureKind;
using geo::LonLat;
using geo::XY;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

const std::string& cut() {
    static const std::string p = t::data_path("coast/US5WA22M_tacoma_cut.000");
    return p;
}

grid::CoastGrid build(double cell_m = 100) {
    grid::BuildRequest r;
    r.cell_m = cell_m;
    std::vector<std::string> warnings;
    return grid::build_grid({cut()}, r, &warnings);
}

const grid::CoastGrid& the_grid() {
    static const grid::CoastGrid g = build();
    return g;
}

/// A hull 2 cm long and wide: its clearance is the distance from its position to the hazards,
/// within 1.5 cm.
const hull::Hull& tiny() {
    static const hull::Hull h = hull::Hull::from_dimensions({0.01, 0.01, 0.01, 0.01}, "tiny");
    return h;
}
constexpr double tiny_reach_m = 0.015;

GDALDatasetUniquePtr open_cut() {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(cut().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) throw std::runtime_error("cannot open the cut");
    return ds;
}

/// A feature of the cut, read with OGR: its class, category, name and first vertex.
struct Charted {
    std::string layer;
    int category = 0;
    std::string name;
    LonLat first;
};

std::vector<Charted> charted(const char* layer) {
    GDALDatasetUniquePtr ds = open_cut();
    std::vector<Charted> out;
    for (auto& f : *ds->GetLayerByName(layer)) {
        Charted c{layer, 0, "", {}};
        for (const char* cat : {"CATSLC", "CATMOR"})
            if (const int i = f->GetFieldIndex(cat); i >= 0 && f->IsFieldSetAndNotNull(i)) c.category = f->GetFieldAsInteger(i);
        if (const int i = f->GetFieldIndex("OBJNAM"); i >= 0 && f->IsFieldSetAndNotNull(i)) c.name = f->GetFieldAsString(i);
        const OGRGeometry* g = f->GetGeometryRef();
        switch (wkbFlatten(g->getGeometryType())) {
        case wkbPoint: c.first = {g->toPoint()->getX(), g->toPoint()->getY()}; break;
        case wkbLineString: c.first = {g->toLineString()->getX(0), g->toLineString()->getY(0)}; break;
        case wkbPolygon: c.first = {g->toPolygon()->getExteriorRing()->getX(0), g->toPolygon()->getExteriorRing()->getY(0)}; break;
        default: throw std::runtime_error("unexpected geometry");
        }
        out.push_back(std::move(c));
    }
    return out;
}

StructureKind expected_kind(const Charted& c) {
    if (c.layer == "PONTON") return StructureKind::pontoon;
    if (c.layer == "HULKES") return StructureKind::hulk;
    if (c.layer == "MORFAC") return static_cast<StructureKind>(static_cast<int>(StructureKind::dolphin) + c.category - 1);
    return static_cast<StructureKind>(static_cast<int>(StructureKind::breakwater) + c.category - 1);
}

TEST(StructureGrid, EveryStructureIsInTheGridWithItsKindAndNameAtEveryDepth) {
    const grid::CoastGrid& g = the_grid();
    EXPECT_EQ(g.source().structure_features, 84u);
    // The grid's table is the import's, polyline by polyline (the grid is built from it in order).
    const coast::Coastline coast = coast::import_coastline({cut()});
    ASSERT_EQ(g.polyline_count(), coast.polylines.size());
    std::size_t polylines = 0;
    std::map<std::pair<std::string, std::int64_t>, std::vector<std::uint32_t>> of_feature;
    for (std::uint32_t k = 0; k < g.polyline_count(); ++k) {
        const coast::Hazard& h = g.hazard(k);
        const coast::Polyline& p = coast.polylines[k];
        EXPECT_EQ(h.kind, p.hazard.kind);
        EXPECT_EQ(h.structure, p.hazard.structure);
        EXPECT_EQ(h.name, p.hazard.name);
        polylines += h.kind == HazardKind::structure;
        of_feature[{coast.layers[p.layer].layer, p.fid}].push_back(k);
    }
    EXPECT_EQ(g.source().structure_polylines, polylines);
    // Every structure the chart has, with the kind of its class and category and its OBJNAM.
    GDALDatasetUniquePtr ds = open_cut();
    int features = 0;
    for (const char* layer : {"SLCONS", "PONTON", "MORFAC"}) {
        const std::vector<Charted> all = charted(layer);
        std::size_t i = 0;
        for (auto& f : *ds->GetLayerByName(layer)) {
            const Charted& c = all.at(i++);
            const auto& ks = of_feature[{layer, f->GetFID()}];
            ASSERT_FALSE(ks.empty()) << layer << " feature " << f->GetFID();
            for (std::uint32_t k : ks) {
                EXPECT_EQ(g.hazard(k).kind, HazardKind::structure);
                EXPECT_EQ(g.hazard(k).structure, expected_kind(c)) << layer << " feature " << f->GetFID();
                EXPECT_EQ(g.hazard(k).name, c.name) << layer << " feature " << f->GetFID();
                EXPECT_TRUE(std::isnan(g.hazard(k).depth_m));
            }
            ++features;
        }
    }
    EXPECT_EQ(features, 84);
    // A structure is a hazard for every vessel: at each dolphin, and in Pier 23's band 0.5 m
    // off its north-west tip (in the water), the tiny hull touches it whatever the limiting
    // depth (none: land only, and structures; with one, a depth area there may be named).
    std::vector<std::pair<LonLat, StructureKind>> probes = {{{-122.4144568 - 0.5 / geo::metres_per_degree(47.2848659).x(), 47.2848659},
                                                             StructureKind::pier}};
    for (const Charted& c : charted("MORFAC")) probes.push_back({c.first, StructureKind::dolphin});
    for (const auto& [where, kind] : probes)
        for (std::optional<double> limit : {std::optional<double>(), std::optional<double>(0.5), std::optional<double>(30.0)}) {
            const check::Contact hit = check::Detector(g, tiny(), limit).check(check::Pose{where, 0.0});
            ASSERT_TRUE(hit.collision) << where.lon << ", " << where.lat;
            const coast::Hazard& h = g.hazard(hit.polyline);
            if (!limit) {
                EXPECT_EQ(h.kind, HazardKind::structure);
                EXPECT_EQ(h.structure, kind) << coast::to_string(h.structure);
            } else {
                EXPECT_TRUE(h.kind == HazardKind::structure || h.kind == HazardKind::shallow) << coast::to_string(h.kind);
            }
            if (kind == StructureKind::pier && !limit) {
                EXPECT_EQ(h.name, "Pier 23");
            }
        }
    // Structures are level 0, with land: the land-only level holds them.
    EXPECT_EQ(g.level_of(std::nullopt), 0u);
    EXPECT_EQ(&g.for_depth(1000.0), &g);
}

TEST(StructureGrid, ADolphinIsADiscOfTwoAndAHalfMetres) {
    const grid::CoastGrid& g = the_grid();
    const Charted dolphin = charted("MORFAC").front();
    const XY c = g.frame().forward(dolphin.first);
    const double outer = coast::structure_point_radius_m / std::cos(std::numbers::pi / (4 * coast::structure_quadrant_segments));
    for (double bearing = 0; bearing < 360; bearing += 7.5) {
        const XY dir{std::sin(bearing * std::numbers::pi / 180), std::cos(bearing * std::numbers::pi / 180)};
        const auto at = [&](double r) { return check::Detector(g, tiny()).check(check::LocalPose::at(c + r * dir, 0.0), {50.0, false}); };
        EXPECT_TRUE(at(coast::structure_point_radius_m - tiny_reach_m).collision) << bearing;
        const check::Contact out = at(outer + 0.5);
        ASSERT_FALSE(out.collision) << bearing;
        EXPECT_NEAR(out.clearance_m, 0.5 + (outer - coast::structure_point_radius_m) / 2, (outer - coast::structure_point_radius_m) / 2 + tiny_reach_m)
            << bearing;
        EXPECT_EQ(g.hazard(out.polyline).structure, StructureKind::dolphin);
    }
}

/// The charted shapes read with OGR and projected vertex by vertex into the grid's frame: land
/// and structure areas as polygons, coastlines as lines, structure lines and points as they
/// are, with the width
/// they stand for (docs/method.md); what the detector's clearance must agree with.
class ChartedShapes {
public:
    explicit ChartedShapes(const geo::LocalFrame& frame) : m_frame(frame) {
        GDALDatasetUniquePtr ds = open_cut();
        for (const char* layer : {"LNDARE", "COALNE", "SLCONS", "PONTON", "MORFAC"}) {
            for (auto& f : *ds->GetLayerByName(layer)) {
                const OGRGeometry* g = f->GetGeometryRef();
                const auto type = wkbFlatten(g->getGeometryType());
                if (type == wkbPolygon) {
                    std::vector<std::vector<XY>> rings;
                    for (const OGRLinearRing* r : *g->toPolygon()) rings.push_back(project(*r));
                    m_shapes.push_back({t::polygon(m_ctx, rings), 0.0});
                } else if (std::string(layer) == "COALNE" && type == wkbLineString) {
                    m_shapes.push_back({t::line(m_ctx, project(*g->toLineString())), 0.0});
                } else if (std::string(layer) != "LNDARE" && type == wkbLineString) {
                    m_shapes.push_back({t::line(m_ctx, project(*g->toLineString())), coast::structure_line_half_width_m});
                    m_lines.push_back(m_shapes.size() - 1);
                } else if (std::string(layer) != "LNDARE" && type == wkbPoint) {
                    m_shapes.push_back({t::point(m_ctx, m_frame.forward(LonLat{g->toPoint()->getX(), g->toPoint()->getY()})),
                                        coast::structure_point_radius_m});
                    m_lines.push_back(m_shapes.size() - 1);
                }
            }
        }
    }
    struct Distance {
        double exact = INFINITY;   ///< to the nearest charted hazard (negative: inside a band or disc by that much; 0 inside an area)
        double least = INFINITY;   ///< the least the grid's polygons may give: bands and discs reach farther by `slack` of their width
        bool widened = false;      ///< the nearest is a band or disc
    };
    /// The distance from p to the charted hazards, with `slack` the fraction of a width by
    /// which the circumscribed bands and discs may reach farther.
    Distance distance(XY p, double slack) const {
        const geo::GeomPtr pt = t::point(m_ctx, p);
        Distance out;
        for (const Shape& s : m_shapes) {
            double d = 0;
            GEOSDistance_r(m_ctx, s.geom.get(), pt.get(), &d);
            d -= s.width;
            if (d < out.exact) {
                out.exact = d;
                out.widened = s.width > 0;
            }
            out.least = std::min(out.least, d - slack * s.width);
        }
        return out;
    }
    /// A random point within `r` metres of a random vertex of a line or point structure.
    XY near_structure(std::mt19937_64& rng, double r) const {
        const Shape& s = m_shapes[m_lines[rng() % m_lines.size()]];
        const GEOSGeometry* g = s.geom.get();
        const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(m_ctx, g);
        unsigned n = 0;
        GEOSCoordSeq_getSize_r(m_ctx, seq, &n);
        XY v;
        GEOSCoordSeq_getXY_r(m_ctx, seq, static_cast<unsigned>(rng() % n), &v.x, &v.y);
        std::uniform_real_distribution<double> u(0, 1);
        const double rr = r * std::sqrt(u(rng)), a = 2 * std::numbers::pi * u(rng);
        return v + XY{rr * std::cos(a), rr * std::sin(a)};
    }

private:
    struct Shape {
        geo::GeomPtr geom;
        double width;
    };
    std::vector<XY> project(const OGRSimpleCurve& c) const {
        std::vector<XY> out;
        for (int i = 0; i < c.getNumPoints(); ++i) out.push_back(m_frame.forward(LonLat{c.getX(i), c.getY(i)}));
        return out;
    }
    geo::GeosContext m_ctx;
    const geo::LocalFrame& m_frame;
    std::vector<Shape> m_shapes;
    std::vector<std::size_t> m_lines;  // shapes that are structure lines or points
};

TEST(StructureGrid, BandsAndDiscsAgreeWithGeosOnRandomPoints) {
    const grid::CoastGrid& g = the_grid();
    const ChartedShapes charted_shapes(g.frame());
    const check::Detector det(g, tiny());
    // The polygons reach at most this fraction of the width farther (circumscribed).
    const double slack = 1 / std::cos(std::numbers::pi / (4 * coast::structure_quadrant_segments)) - 1;
    std::mt19937_64 rng(20230714);
    int points = 0, near_widened = 0, inside = 0, clear = 0, bad = 0;
    double worst_over = 0, worst_under = 0;
    for (int k = 0; k < 20000; ++k) {
        const XY p = charted_shapes.near_structure(rng, 6.0);
        const ChartedShapes::Distance dist = charted_shapes.distance(p, slack);
        const double d = dist.exact;
        const bool widened = dist.widened;
        const check::Contact c = det.check(check::LocalPose::at(p, 0.0), {50.0, false});
        ++points;
        near_widened += widened;
        if (d < -tiny_reach_m) {
            ++inside;
            if (!c.collision && ++bad <= 10) ADD_FAILURE() << "(" << p.x << ", " << p.y << ") lies " << -d << " m inside, detector clear " << c.clearance_m;
            continue;
        }
        if (dist.least > tiny_reach_m) {
            ++clear;
            if (c.collision) {
                if (++bad <= 10) ADD_FAILURE() << "(" << p.x << ", " << p.y << ") lies " << d << " m off, detector in contact";
                continue;
            }
            // clearance within [least, exact], give or take the tiny hull's reach
            const double over = c.clearance_m - d, under = dist.least - c.clearance_m;
            worst_over = std::max(worst_over, over);
            if (under > worst_under && std::getenv("SHOAL_TEST_VERBOSE"))
                std::printf("under %.5f at (%.3f, %.3f): GEOS %.5f (%s), detector %.5f, hit %s %s\n", under, p.x, p.y, d,
                            widened ? "band or disc" : "area", c.clearance_m, coast::to_string(g.hazard(c.polyline).kind),
                            coast::to_string(g.hazard(c.polyline).structure));
            worst_under = std::max(worst_under, under);
            if ((over > 1e-4 || under > tiny_reach_m) && ++bad <= 10)
                ADD_FAILURE() << "(" << p.x << ", " << p.y << "): GEOS " << d << " m (" << (widened ? "band or disc" : "area")
                              << "), detector " << c.clearance_m;
        }
    }
    EXPECT_EQ(bad, 0);
    EXPECT_GT(inside, 2000);
    EXPECT_GT(clear, 5000);
    EXPECT_GT(near_widened, 10000) << "most points should be nearest a band or disc";
    std::printf("[ measured ] %d points: %d inside, %d clear (%d nearest a band or disc); the detector's clearance over GEOS's "
                "by at most %.2g m, under the least the circumscribed polygons allow by at most %.4f m (the tiny hull reaches %.3f m)\n",
                points, inside, clear, near_widened, worst_over, worst_under, tiny_reach_m);
}

TEST(StructureGrid, KindsAndNamesSurviveTheGridFile) {
    const grid::CoastGrid& g = the_grid();
    const grid::CoastGrid back = grid::GridFile::parse(grid::GridFile::serialize(g), "tacoma.shoalgrid");
    EXPECT_TRUE(back == g);
    ASSERT_EQ(back.polyline_count(), g.polyline_count());
    std::set<std::string> names;
    for (std::uint32_t k = 0; k < back.polyline_count(); ++k) {
        EXPECT_EQ(back.hazard(k).kind, g.hazard(k).kind);
        EXPECT_EQ(back.hazard(k).structure, g.hazard(k).structure);
        EXPECT_EQ(back.hazard(k).name, g.hazard(k).name);
        if (!back.hazard(k).name.empty()) names.insert(back.hazard(k).name);
    }
    EXPECT_TRUE(names.count("Pier 23") && names.count("Pier 24") && names.count("Pier 25"));
    EXPECT_EQ(back.source().structure_features, g.source().structure_features);
    EXPECT_EQ(back.source().structure_polylines, g.source().structure_polylines);
}

TEST(StructureGrid, AGridFileOfVersion3IsRefusedAndTheCacheRebuilt) {
    std::vector<char> bytes = grid::GridFile::serialize(the_grid());
    const std::uint32_t v3 = 3;
    std::memcpy(bytes.data() + 8, &v3, sizeof v3);  // the u32 format version after the 8-byte magic
    EXPECT_THAT([&] { grid::GridFile::parse(bytes, "old.shoalgrid"); },
                ThrowsMessage<InputError>(HasSubstr("has format version 3; this shoal reads version " +
                                                    std::to_string(grid::grid_format_version) + ": rebuild it with shoal import")));
    // A cached grid of version 3 where the cache keeps this chart's grid: rebuilt, structures and all.
    t::TempDir dir;
    grid::BuildRequest r;
    r.cell_m = 100;
    r.cache_dir = dir.file("cache");
    grid::LoadReport first;
    const grid::CoastGrid g1 = grid::load_or_build({cut()}, r, &first);
    ASSERT_EQ(first.how, "built and cached");
    std::vector<char> cached = t::read_bytes(first.cache_path);
    std::memcpy(cached.data() + 8, &v3, sizeof v3);
    t::write_bytes(first.cache_path, cached);
    grid::LoadReport second;
    const grid::CoastGrid g2 = grid::load_or_build({cut()}, r, &second);
    EXPECT_EQ(second.how, "built and cached");
    ASSERT_FALSE(second.warnings.empty());
    EXPECT_THAT(second.warnings.front(), AllOf(HasSubstr("format version 3"), HasSubstr("rebuild")));
    EXPECT_EQ(g2.source().structure_features, 84u);
    EXPECT_TRUE(g1 == g2);
}

}  // namespace
}  // namespace shoal
