// Tests of coast::ExpectedAreas on hand-made files in tests/data/coast/areas (see its
// README.md) and on the real S-57 cut tests/data/coast/US4MD81M_cut.000.
//
// Every point answer is compared with an answer found without shoal's loader: the same file
// read with OGR alone, each vertex transformed to WGS84 with OGR and projected with the same
// LocalFrame, then OGRGeometry::Intersects for polygons and OGRGeometry::Distance <= the
// tolerance for lines and points. A buffer is a polygon with 8 segments per quarter circle
// circumscribed about the tolerance, so points between tolerance and tolerance / cos(pi/32)
// from a line may fall either way: those are not compared.
//
// Counts in the S-57 cut (GDAL 3.6.2, /usr/bin/python3 + osgeo.ogr over layer SLCONS):
// 151 features: 150 LineStrings + 1 Point (FID 287, CATSLC 12 ramp), CATSLC an Integer field:
// 136 x 4 (pier), 10 x 10 (sea wall), 2 x 6 (wharf), 2 x 1 (breakwater), 1 x 12 (ramp); no
// OBJNAM set; no BERTHS, HRBARE or ACHARE layer. FID 282 is a pier, a LineString of 7
// points whose vertex 1 (-76.4946579, 38.9104682) lies 0.014 degrees (over 1 km) from every
// other SLCONS feature.

#include <shoal/coast/expected_areas.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <shoal/geo/local_frame.hpp>
#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::UsageError;
using shoal::coast::AreaRole;
using shoal::coast::ExpectedArea;
using shoal::coast::ExpectedAreas;
using shoal::geo::LocalFrame;
using shoal::geo::LonLat;
using shoal::geo::XY;
using testing::AllOf;
using testing::Contains;
using testing::HasSubstr;
using testing::IsEmpty;
using testing::ThrowsMessage;
namespace t = shoal::test;

std::string areas_file(const std::string& name) { return t::data_path("coast/areas/" + name); }
std::string coast_file(const std::string& name) { return t::data_path("coast/" + name); }

constexpr double tolerance_m = 15.0;
/// Beyond this distance from a line or point nothing is inside its buffer.
const double buffer_outer_m = tolerance_m / std::cos(std::numbers::pi / 32);

const LocalFrame& helsinki_frame() {
    static const LocalFrame f = LocalFrame::transverse_mercator({24.96, 60.163});
    return f;
}

const LocalFrame& annapolis_frame() {
    static const LocalFrame f = LocalFrame::transverse_mercator({-76.40, 38.95});
    return f;
}

/// Local coordinates of a lon/lat point, with the frame's batch call as the loader uses it.
XY local(const LocalFrame& frame, LonLat p) {
    std::vector<double> xs{p.lon}, ys{p.lat};
    std::size_t bad = 0;
    if (!frame.forward(xs, ys, &bad)) throw std::runtime_error("test point cannot be projected");
    return {xs[0], ys[0]};
}

// ---------------------------------------------------------------------------------------------
// The independent answer: OGR alone

/// One feature as OGR reads it, projected into the frame vertex by vertex.
struct Reference {
    std::string layer;
    std::int64_t fid = -1;
    std::string catslc;  // the raw CATSLC value as text ("" when unset)
    bool polygonal = false;
    std::unique_ptr<OGRGeometry> geom;  // local metres
};

void project_in_place(OGRGeometry& g, OGRCoordinateTransformation* ct, const LocalFrame& frame) {
    auto move = [&](double& x, double& y) {
        if (ct && !ct->Transform(1, &x, &y)) throw std::runtime_error("test cannot transform a vertex");
        const XY p = local(frame, {x, y});
        x = p.x;
        y = p.y;
    };
    switch (wkbFlatten(g.getGeometryType())) {
    case wkbPoint: {
        OGRPoint& pt = *g.toPoint();
        double x = pt.getX(), y = pt.getY();
        move(x, y);
        pt.setX(x);
        pt.setY(y);
        return;
    }
    case wkbLineString:
    case wkbLinearRing: {
        OGRSimpleCurve& c = *g.toSimpleCurve();
        for (int i = 0; i < c.getNumPoints(); ++i) {
            double x = c.getX(i), y = c.getY(i);
            move(x, y);
            c.setPoint(i, x, y);
        }
        return;
    }
    case wkbPolygon:
        for (OGRLinearRing* ring : *g.toPolygon()) project_in_place(*ring, ct, frame);
        return;
    default:
        for (OGRGeometry* sub : *g.toGeometryCollection()) project_in_place(*sub, ct, frame);
    }
}

/// Every feature of the named layers (all layers when empty) of `path`, in OGR's order.
std::vector<Reference> read_reference(const std::string& path, const LocalFrame& frame,
                                      const std::vector<std::string>& layers = {}) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) throw std::runtime_error("OGR cannot open " + path);
    std::vector<OGRLayer*> chosen;
    if (layers.empty())
        for (OGRLayer* l : ds->GetLayers()) chosen.push_back(l);
    for (const auto& name : layers) chosen.push_back(ds->GetLayerByName(name.c_str()));
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::vector<Reference> out;
    for (OGRLayer* l : chosen) {
        if (!l) throw std::runtime_error("missing layer in " + path);
        std::unique_ptr<OGRCoordinateTransformation> ct;
        if (const OGRSpatialReference* srs = l->GetSpatialRef(); srs && !(srs->IsGeographic() && srs->IsSame(&wgs84))) {
            OGRSpatialReference src(*srs);
            src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            ct.reset(OGRCreateCoordinateTransformation(&src, &wgs84));
        }
        const int catslc = l->GetLayerDefn()->GetFieldIndex("CATSLC");
        for (auto& f : *l) {
            const OGRGeometry* g = f->GetGeometryRef();
            if (!g || g->IsEmpty()) continue;
            Reference r;
            r.layer = l->GetName();
            r.fid = f->GetFID();
            if (catslc >= 0 && f->IsFieldSetAndNotNull(catslc)) r.catslc = f->GetFieldAsString(catslc);
            const auto type = wkbFlatten(g->getGeometryType());
            r.polygonal = type == wkbPolygon || type == wkbMultiPolygon;
            r.geom.reset(g->clone());
            project_in_place(*r.geom, ct.get(), frame);
            out.push_back(std::move(r));
        }
    }
    return out;
}

/// The reference answer at p: the index of the first feature that holds p, -1 for none, or
/// nullopt when p is too near an edge (or within the buffer's slack) to be sure.
std::optional<int> reference_answer(const std::vector<Reference>& refs, XY p) {
    OGRPoint pt(p.x, p.y);
    for (std::size_t i = 0; i < refs.size(); ++i) {
        const Reference& r = refs[i];
        if (r.polygonal) {
            std::unique_ptr<OGRGeometry> boundary(r.geom->Boundary());
            if (boundary->Distance(&pt) < 1e-6) return std::nullopt;
            if (r.geom->Intersects(&pt)) return static_cast<int>(i);
        } else {
            const double d = r.geom->Distance(&pt);
            if (d <= tolerance_m) return static_cast<int>(i);
            if (d < buffer_outer_m) return std::nullopt;
        }
    }
    return -1;
}

/// Random points over the references' extent grown by 100 m, and as many within 3 tolerances
/// of their vertices (where the edges of polygons and buffers are).
std::vector<XY> sample_points(const std::vector<Reference>& refs, std::size_t n, unsigned seed) {
    OGREnvelope env;
    std::vector<XY> vertices;
    for (const auto& r : refs) {
        OGREnvelope e;
        r.geom->getEnvelope(&e);
        env.Merge(e);
        const OGRGeometry& g = *r.geom;
        if (wkbFlatten(g.getGeometryType()) == wkbLineString)
            for (const OGRPoint& v : *g.toLineString()) vertices.push_back({v.getX(), v.getY()});
        if (wkbFlatten(g.getGeometryType()) == wkbPoint) vertices.push_back({g.toPoint()->getX(), g.toPoint()->getY()});
        if (wkbFlatten(g.getGeometryType()) == wkbPolygon)
            for (const OGRLinearRing* ring : *g.toPolygon())
                for (const OGRPoint& v : *ring) vertices.push_back({v.getX(), v.getY()});
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ux(env.MinX - 100, env.MaxX + 100), uy(env.MinY - 100, env.MaxY + 100);
    std::uniform_real_distribution<double> near(-3 * tolerance_m, 3 * tolerance_m);
    std::vector<XY> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back({ux(rng), uy(rng)});
    if (!vertices.empty()) {
        std::uniform_int_distribution<std::size_t> pick(0, vertices.size() - 1);
        for (std::size_t i = 0; i < n; ++i) {
            const XY v = vertices[pick(rng)];
            out.push_back({v.x + near(rng), v.y + near(rng)});
        }
    }
    return out;
}

/// How many points were compared, by the reference's answer (-1: no area).
using Tally = std::map<int, std::size_t>;

std::size_t total(const Tally& tally) {
    std::size_t n = 0;
    for (const auto& [answer, count] : tally) n += count;
    return n;
}

/// Compares areas.find(p, role) with the reference at every point.
Tally expect_same_answers(const ExpectedAreas& areas, AreaRole role, const std::vector<Reference>& refs,
                          const std::vector<XY>& points) {
    Tally tally;
    std::size_t failures = 0;
    for (const XY& p : points) {
        const std::optional<int> want = reference_answer(refs, p);
        if (!want) continue;
        ++tally[*want];
        const ExpectedArea* got = areas.find(p, role);
        const bool same = *want < 0 ? got == nullptr
                                    : got != nullptr && got->fid == refs[static_cast<std::size_t>(*want)].fid &&
                                          got->layer == refs[static_cast<std::size_t>(*want)].layer;
        if (!same && ++failures <= 10)
            ADD_FAILURE() << "at local (" << p.x << ", " << p.y << "): expected "
                          << (*want < 0 ? std::string("no area") : "feature " + std::to_string(refs[static_cast<std::size_t>(*want)].fid))
                          << ", got " << (got ? "feature " + std::to_string(got->fid) + " of " + got->layer : std::string("none"));
    }
    return tally;
}

const ExpectedArea* area_with_fid(const ExpectedAreas& areas, std::int64_t fid) {
    for (const auto& a : areas.areas())
        if (a.fid == fid) return &a;
    return nullptr;
}

// ---------------------------------------------------------------------------------------------
// (a) a hand-made GeoJSON: two harbour polygons (one with a hole) and a berth line

TEST(ExpectedAreas, EmptyFindsNothing) {
    const ExpectedAreas none;
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(none.size(), 0u);
    EXPECT_EQ(none.count(AreaRole::expected), 0u);
    EXPECT_EQ(none.find({0, 0}, AreaRole::expected), nullptr);
    EXPECT_EQ(none.find({0, 0}, AreaRole::structure), nullptr);
}

TEST(ExpectedAreas, UserGeoJsonIsReadFeatureByFeature) {
    std::vector<std::string> warnings;
    const std::string path = areas_file("helsinki_harbours.geojson");
    const ExpectedAreas areas = ExpectedAreas::load({path}, {}, helsinki_frame(), tolerance_m, &warnings);
    EXPECT_THAT(warnings, IsEmpty());
    ASSERT_EQ(areas.size(), 3u);
    EXPECT_EQ(areas.count(AreaRole::expected), 3u);
    EXPECT_EQ(areas.count(AreaRole::structure), 0u);
    const std::vector<std::string> names = {"Eteläsatama", "Katajanokka", "Olympialaituri"};
    for (std::size_t i = 0; i < 3; ++i) {
        const ExpectedArea& a = areas.areas()[i];
        EXPECT_EQ(a.role, AreaRole::expected);
        EXPECT_EQ(a.kind, "area");
        EXPECT_EQ(a.name, names[i]);  // from the attribute "Name": any case
        EXPECT_EQ(a.file, path);
        EXPECT_EQ(a.layer, "helsinki_harbours");
        EXPECT_EQ(a.fid, static_cast<std::int64_t>(i + 1));
    }
}

TEST(ExpectedAreas, AUsersFileOgrCannotReadWholeIsRefused) {
    // A berths file cut short: before, the 25 polygons before the cut were the berths, a warning
    // said "41 feature(s) ... skipped", and contacts at the berths left out were groundings.
    t::TempDir dir;
    for (const char* ext : {".shp", ".shx", ".dbf", ".prj"})
        std::filesystem::copy_file(coast_file(std::string("gr_saronic_piraeus_land") + ext), dir.file(std::string("berths") + ext));
    const std::string path = dir.file("berths.shp");
    const LocalFrame frame = LocalFrame::transverse_mercator({23.6, 37.9});
    EXPECT_EQ(ExpectedAreas::load({path}, {}, frame, tolerance_m, nullptr).size(), 66u);
    std::filesystem::resize_file(path, 40000);
    EXPECT_THAT([&] { ExpectedAreas::load({path}, {}, frame, tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("could not read all of it"), HasSubstr("Error in fread()"))));
    // A GeoJSON crs GDAL cannot find (taken as WGS84 before, without a word).
    const std::string odd = dir.file("odd.geojson");
    const std::string text = R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::999999"}}, "features": [)"
                             R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[[23.6, 37.9], [23.61, 37.9], [23.61, 37.91], [23.6, 37.9]]]}}]})";
    t::write_bytes(odd, std::vector<char>(text.begin(), text.end()));
    EXPECT_THAT([&] { ExpectedAreas::load({odd}, {}, frame, tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(odd), HasSubstr("its CRS is not one GDAL can read"))));
}

TEST(ExpectedAreas, PointAnswersMatchOgr) {
    const std::string path = areas_file("helsinki_harbours.geojson");
    const ExpectedAreas areas = ExpectedAreas::load({path}, {}, helsinki_frame(), tolerance_m, nullptr);
    const auto refs = read_reference(path, helsinki_frame());
    ASSERT_EQ(refs.size(), 3u);
    const auto points = sample_points(refs, 4000, 20240611);
    const Tally tally = expect_same_answers(areas, AreaRole::expected, refs, points);
    EXPECT_GT(total(tally), points.size() * 9 / 10);
    // The points fall in every area and outside them all, many times each.
    for (int answer : {-1, 0, 1, 2}) EXPECT_GT(tally.count(answer) ? tally.at(answer) : 0, 100u) << "answer " << answer;
    // No structures in a user file of areas.
    for (std::size_t i = 0; i < points.size(); i += 10) EXPECT_EQ(areas.find(points[i], AreaRole::structure), nullptr);
}

TEST(ExpectedAreas, HolesOverlapsBoundariesAndBuffers) {
    const LocalFrame& f = helsinki_frame();
    const ExpectedAreas areas =
        ExpectedAreas::load({areas_file("helsinki_harbours.geojson")}, {}, f, tolerance_m, nullptr);
    auto fid_at = [&](XY p) -> std::int64_t {
        const ExpectedArea* a = areas.find(p, AreaRole::expected);
        return a ? a->fid : -1;
    };
    EXPECT_EQ(fid_at(local(f, {24.9520, 60.1600})), 1);   // inside Eteläsatama
    EXPECT_EQ(fid_at(local(f, {24.9560, 60.1620})), -1);  // in its hole
    EXPECT_EQ(fid_at(local(f, {24.9700, 60.1660})), 2);   // inside Katajanokka only
    EXPECT_EQ(fid_at(local(f, {24.9610, 60.1640})), 1);   // in both: the first read
    EXPECT_EQ(fid_at(local(f, {24.9800, 60.1800})), -1);  // outside everything
    // Boundaries count: a shell vertex, and a vertex of the hole.
    EXPECT_EQ(fid_at(local(f, {24.9620, 60.1580})), 1);
    EXPECT_EQ(fid_at(local(f, {24.9540, 60.1610})), 1);
    // The berth line: its middle vertex, and points off it at right angles to its first leg.
    const XY a = local(f, {24.9480, 60.1570}), b = local(f, {24.9450, 60.1600});
    const XY mid = 0.5 * (a + b);
    const XY dir = (1.0 / shoal::geo::distance(a, b)) * (b - a);
    const XY normal{-dir.y, dir.x};
    EXPECT_EQ(fid_at(b), 3);
    EXPECT_EQ(fid_at(mid + (tolerance_m - 0.01) * normal), 3);
    EXPECT_EQ(fid_at(mid - (tolerance_m - 0.01) * normal), 3);
    EXPECT_EQ(fid_at(mid + (buffer_outer_m + 0.01) * normal), -1);
    EXPECT_EQ(fid_at(a - (tolerance_m - 0.01) * dir), 3);  // round cap at the end
    EXPECT_EQ(fid_at(a - (buffer_outer_m + 0.01) * dir), -1);
}

TEST(ExpectedAreas, MovedAreasKeepTheirPointers) {
    ExpectedAreas a = ExpectedAreas::load({areas_file("helsinki_harbours.geojson")}, {}, helsinki_frame(), tolerance_m, nullptr);
    const XY p = local(helsinki_frame(), {24.9520, 60.1600});
    const ExpectedArea* before = a.find(p, AreaRole::expected);
    ASSERT_NE(before, nullptr);
    ExpectedAreas b(std::move(a));
    EXPECT_EQ(b.find(p, AreaRole::expected), before);
    ExpectedAreas c;
    c = std::move(b);
    EXPECT_EQ(c.find(p, AreaRole::expected), before);
    EXPECT_EQ(c.size(), 3u);
}

TEST(ExpectedAreas, FindIsSafeFromSeveralThreads) {
    const std::string path = areas_file("helsinki_harbours.geojson");
    const ExpectedAreas areas = ExpectedAreas::load({path}, {}, helsinki_frame(), tolerance_m, nullptr);
    const auto points = sample_points(read_reference(path, helsinki_frame()), 1500, 7);
    std::vector<const ExpectedArea*> serial;
    for (const XY& p : points) serial.push_back(areas.find(p, AreaRole::expected));
    std::vector<std::vector<const ExpectedArea*>> answers(4);
    std::vector<std::thread> threads;
    for (auto& out : answers)
        threads.emplace_back([&areas, &points, &out] {
            for (const XY& p : points) out.push_back(areas.find(p, AreaRole::expected));
        });
    for (auto& th : threads) th.join();
    for (const auto& out : answers) EXPECT_EQ(out, serial);
}

// ---------------------------------------------------------------------------------------------
// (b) the S-57 cut: shoreline constructions

TEST(ExpectedAreasS57, ChartGivesItsShorelineConstructions) {
    const std::string path = coast_file("US4MD81M_cut.000");
    std::vector<std::string> warnings;
    const ExpectedAreas areas = ExpectedAreas::load({}, {path}, annapolis_frame(), tolerance_m, &warnings);
    EXPECT_THAT(warnings, IsEmpty());  // BERTHS, HRBARE, ACHARE absent: not worth a warning
    EXPECT_EQ(areas.size(), 151u);
    EXPECT_EQ(areas.count(AreaRole::structure), 151u);
    EXPECT_EQ(areas.count(AreaRole::expected), 0u);
    std::map<std::string, int> kinds;
    for (const auto& a : areas.areas()) {
        ++kinds[a.kind];
        EXPECT_EQ(a.role, AreaRole::structure);
        EXPECT_EQ(a.layer, "SLCONS");
        EXPECT_EQ(a.file, path);
        EXPECT_EQ(a.name, "");
    }
    EXPECT_EQ(kinds, (std::map<std::string, int>{{"pier", 136}, {"sea wall", 10}, {"wharf", 2}, {"breakwater", 2}, {"ramp", 1}}));
}

TEST(ExpectedAreasS57, KnownPierAndRampAreFoundAndOpenWaterIsNot) {
    const LocalFrame& f = annapolis_frame();
    const ExpectedAreas areas = ExpectedAreas::load({}, {coast_file("US4MD81M_cut.000")}, f, tolerance_m, nullptr);
    const XY pier = local(f, {-76.4946579, 38.9104682});  // vertex 1 of pier FID 282
    const ExpectedArea* a = areas.find(pier, AreaRole::structure);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->fid, 282);
    EXPECT_EQ(a->kind, "pier");
    EXPECT_EQ(areas.find(pier + XY{0, tolerance_m - 0.01}, AreaRole::structure), a);
    EXPECT_EQ(areas.find(pier, AreaRole::expected), nullptr);  // a structure is not an expected area
    // The one point feature (a ramp) is its circle of the tolerance.
    const XY ramp = local(f, {-76.3558875, 38.953357});
    const ExpectedArea* r = areas.find(ramp + XY{tolerance_m - 0.01, 0}, AreaRole::structure);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->fid, 287);
    EXPECT_EQ(r->kind, "ramp");
    EXPECT_EQ(areas.find(ramp + XY{buffer_outer_m + 0.01, 0}, AreaRole::structure), nullptr);
    // Mid-bay, over 1 km from every construction (checked with OGR).
    const XY water = local(f, {-76.42, 38.98});
    const auto refs = read_reference(coast_file("US4MD81M_cut.000"), f, {"SLCONS"});
    OGRPoint pt(water.x, water.y);
    for (const auto& ref : refs) ASSERT_GT(ref.geom->Distance(&pt), 1000.0) << "feature " << ref.fid;
    EXPECT_EQ(areas.find(water, AreaRole::structure), nullptr);
}

TEST(ExpectedAreasS57, PointAnswersMatchOgr) {
    const std::string path = coast_file("US4MD81M_cut.000");
    const ExpectedAreas areas = ExpectedAreas::load({}, {path}, annapolis_frame(), tolerance_m, nullptr);
    const auto refs = read_reference(path, annapolis_frame(), {"SLCONS"});
    ASSERT_EQ(refs.size(), 151u);
    // The kind named for each feature's CATSLC value.
    const std::map<std::string, std::string> names = {{"1", "breakwater"}, {"4", "pier"}, {"6", "wharf"}, {"10", "sea wall"}, {"12", "ramp"}};
    for (const auto& ref : refs) {
        const ExpectedArea* a = area_with_fid(areas, ref.fid);
        ASSERT_NE(a, nullptr) << "feature " << ref.fid;
        EXPECT_EQ(a->kind, names.at(ref.catslc)) << "feature " << ref.fid;
    }
    const auto points = sample_points(refs, 3000, 4242);
    const Tally tally = expect_same_answers(areas, AreaRole::structure, refs, points);
    EXPECT_GT(total(tally), points.size() * 8 / 10);
    EXPECT_GT(tally.size(), 100u);  // the points fall in over 100 different constructions
    EXPECT_GT(tally.count(-1) ? tally.at(-1) : 0, 1000u);
}

TEST(ExpectedAreasS57, ChartAsUserFileAndOtherSources) {
    const std::string s57 = coast_file("US4MD81M_cut.000");
    // Given as a user file too: read once; a coastline that is not S-57 gives nothing.
    const ExpectedAreas a = ExpectedAreas::load({s57}, {s57, coast_file("uk_solent_land.geojson")}, annapolis_frame(),
                                                tolerance_m, nullptr);
    EXPECT_EQ(a.count(AreaRole::structure), 151u);
    EXPECT_EQ(a.size(), 151u);
    const ExpectedAreas none = ExpectedAreas::load({}, {coast_file("uk_solent_land.geojson")}, annapolis_frame(),
                                                   tolerance_m, nullptr);
    EXPECT_TRUE(none.empty());
    // A source the S-57 driver does not claim is not opened at all: a file no driver reads
    // costs nothing (opened, it would throw "not a vector dataset"), and the chart beside it
    // still gives its areas.
    const ExpectedAreas beside = ExpectedAreas::load({}, {coast_file("not_a_dataset.txt"), s57}, annapolis_frame(), tolerance_m, nullptr);
    EXPECT_EQ(beside.count(AreaRole::structure), 151u);
}

// ---------------------------------------------------------------------------------------------
// (c) the same areas in a projected CRS (EPSG:3067), layers named after S-57 classes

TEST(ExpectedAreasProjected, GeoPackageInTm35finGivesTheSameAnswers) {
    const LocalFrame& f = helsinki_frame();
    const std::string gpkg = areas_file("helsinki_harbours_3067.gpkg");
    const std::string geojson = areas_file("helsinki_harbours.geojson");
    std::vector<std::string> warnings;
    const ExpectedAreas projected = ExpectedAreas::load({gpkg}, {}, f, tolerance_m, &warnings);
    EXPECT_THAT(warnings, IsEmpty());
    const ExpectedAreas lonlat = ExpectedAreas::load({geojson}, {}, f, tolerance_m, nullptr);
    ASSERT_EQ(projected.size(), 3u);
    EXPECT_EQ(projected.count(AreaRole::expected), 3u);
    const auto& p = projected.areas();
    EXPECT_EQ(p[0].kind, "harbour");
    EXPECT_EQ(p[1].kind, "harbour");
    EXPECT_EQ(p[2].kind, "berth");
    EXPECT_EQ(p[0].layer, "HRBARE");
    EXPECT_EQ(p[2].layer, "BERTHS");
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(p[i].fid, lonlat.areas()[i].fid);
        EXPECT_EQ(p[i].name, lonlat.areas()[i].name);
    }
    const auto refs = read_reference(gpkg, f);
    const auto refs_lonlat = read_reference(geojson, f);
    const auto points = sample_points(refs, 4000, 31337);
    EXPECT_GT(total(expect_same_answers(projected, AreaRole::expected, refs, points)), points.size() * 9 / 10);
    // Point by point the same areas as from the lon/lat file (apart from points within the
    // reference's doubt of either).
    std::size_t compared = 0;
    for (const XY& q : points) {
        if (!reference_answer(refs, q) || !reference_answer(refs_lonlat, q)) continue;
        ++compared;
        const ExpectedArea* x = projected.find(q, AreaRole::expected);
        const ExpectedArea* y = lonlat.find(q, AreaRole::expected);
        ASSERT_EQ(x == nullptr, y == nullptr) << "at " << q.x << ", " << q.y;
        if (x) {
            EXPECT_EQ(x->fid, y->fid);
        }
    }
    EXPECT_GT(compared, points.size() * 9 / 10);
}

// ---------------------------------------------------------------------------------------------
// Repairs, points, skipped features

TEST(ExpectedAreas, InvalidPolygonIsRepairedWithAWarning) {
    const LocalFrame f = LocalFrame::transverse_mercator({-1.25, 50.71});
    const std::string path = coast_file("invalid_bowtie.geojson");
    std::vector<std::string> warnings;
    const ExpectedAreas areas = ExpectedAreas::load({path}, {}, f, tolerance_m, &warnings);
    EXPECT_EQ(areas.size(), 2u);
    EXPECT_THAT(warnings, Contains(AllOf(HasSubstr(path), HasSubstr("'invalid_bowtie'"), HasSubstr("feature 42"),
                                         HasSubstr("GEOSMakeValid"))));
    // The bow-tie (-1.20 50.70, -1.18 50.72, -1.18 50.70, -1.20 50.72) is two triangles
    // meeting at (-1.19, 50.71): left and right of it are inside, above and below are not.
    const auto fid_at = [&](LonLat p) -> std::int64_t {
        const ExpectedArea* a = areas.find(local(f, p), AreaRole::expected);
        return a ? a->fid : -1;
    };
    EXPECT_EQ(fid_at({-1.197, 50.71}), 42);
    EXPECT_EQ(fid_at({-1.183, 50.71}), 42);
    EXPECT_EQ(fid_at({-1.19, 50.717}), -1);
    EXPECT_EQ(fid_at({-1.19, 50.703}), -1);
    EXPECT_EQ(fid_at({-1.29, 50.705}), 7);
}

TEST(ExpectedAreas, PointsBecomeCirclesAndUnusableFeaturesAreSkipped) {
    const LocalFrame f = LocalFrame::transverse_mercator({-1.27, 50.75});
    const std::string path = coast_file("mixed_points_empty.geojson");
    std::vector<std::string> warnings;
    const ExpectedAreas areas = ExpectedAreas::load({path}, {}, f, tolerance_m, &warnings);
    // Features 4 (no geometry) and 5 (an empty line) have nothing; 6, a line of one repeated
    // point, is a point.
    EXPECT_EQ(areas.size(), 5u);
    EXPECT_THAT(warnings, Contains(AllOf(HasSubstr(path), HasSubstr("'mixed_points_empty'"), HasSubstr("2 feature"))));
    const auto fid_at = [&](XY p) -> std::int64_t {
        const ExpectedArea* a = areas.find(p, AreaRole::expected);
        return a ? a->fid : -1;
    };
    const XY point = local(f, {-1.25, 50.75});
    EXPECT_EQ(fid_at(point + XY{0, tolerance_m - 0.01}), 2);
    EXPECT_EQ(fid_at(point + XY{0, buffer_outer_m + 0.01}), -1);
    // Both points of the MultiPoint belong to feature 3.
    EXPECT_EQ(fid_at(local(f, {-1.27, 50.77})), 3);
    EXPECT_EQ(fid_at(local(f, {-1.28, 50.78})), 3);
    EXPECT_EQ(fid_at(local(f, {-1.26, 50.72}) + XY{-tolerance_m + 0.01, 0}), 6);
    EXPECT_EQ(fid_at(local(f, {-1.25, 50.74})), 7);
}

// ---------------------------------------------------------------------------------------------
// (d) errors: one InputError naming the file (and layer)

TEST(ExpectedAreasErrors, MissingOrUnreadableFile) {
    const std::string missing = areas_file("no_such_areas.geojson");
    EXPECT_THAT([&] { ExpectedAreas::load({missing}, {}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(missing), HasSubstr("no such file"))));
    EXPECT_THAT([&] { ExpectedAreas::load({}, {missing}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(missing), HasSubstr("no such file"))));
    const std::string text = coast_file("not_a_dataset.txt");
    EXPECT_THAT([&] { ExpectedAreas::load({text}, {}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(text), HasSubstr("not a vector dataset"))));
}

TEST(ExpectedAreasErrors, UserLayerWithoutGeometry) {
    const std::string path = areas_file("no_geometry.geojson");
    EXPECT_THAT([&] { ExpectedAreas::load({path}, {}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("'no_geometry'"), HasSubstr("no polygon, line or point"))));
    const std::string empty = coast_file("empty_collection.geojson");
    EXPECT_THAT([&] { ExpectedAreas::load({empty}, {}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(empty), HasSubstr("'empty_collection'"), HasSubstr("no features"))));
}

TEST(ExpectedAreasErrors, S57UserFileWithoutAreaLayers) {
    const std::string path = coast_file("US4MD81M_hazard_cut.000");
    EXPECT_THAT([&] { ExpectedAreas::load({path}, {}, annapolis_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("BERTHS, HRBARE, ACHARE, SLCONS"))));
    // As a chart it just has none.
    EXPECT_TRUE(ExpectedAreas::load({}, {path}, annapolis_frame(), tolerance_m, nullptr).empty());
}

TEST(ExpectedAreasErrors, NoCrsAndNotLonLat) {
    const std::string path = coast_file("projected_no_crs.shp");
    EXPECT_THAT([&] { ExpectedAreas::load({path}, {}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("'projected_no_crs'"), HasSubstr("no CRS"))));
    const std::string geojson = coast_file("projected_no_crs.geojson");
    EXPECT_THAT([&] { ExpectedAreas::load({geojson}, {}, helsinki_frame(), tolerance_m, nullptr); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(geojson), HasSubstr("not longitude/latitude"))));
}

TEST(ExpectedAreasErrors, ToleranceMustBePositive) {
    EXPECT_THROW(ExpectedAreas::load({}, {}, helsinki_frame(), 0.0, nullptr), UsageError);
    EXPECT_THROW(ExpectedAreas::load({}, {}, helsinki_frame(), NAN, nullptr), UsageError);
}

}  // namespace
