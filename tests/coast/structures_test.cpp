// Structures read from S-57 charts: SLCONS shoreline constructions, PONTON pontoons, HULKES
// hulks and MORFAC dolphins, as hazards of the coastline (coast::HazardKind::structure, with
// their kind and name) and as the *structure* expected-contact areas. On the real cut
// tests/data/coast/US5WA22M_tacoma_cut.000 (Port of Tacoma: Piers 23-25, a wharf, pontoons,
// dolphins; tests/data/README.md) and, when ../shared/data is there, the whole US5WA22M cell
// (717 piers, 582 pontoons, 103 dolphins and 11 mooring buoys, 5 hulks). Every count is
// OGR's own (attribute filters over the layers); lines and points become the documented
// bands and discs (coast::structure_line_half_width_m, structure_point_radius_m).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include <shoal/coast/coastline.hpp>
#include <shoal/coast/expected_areas.hpp>
#include <shoal/geo/local_frame.hpp>
#include "coast/ogr_source.hpp"
#include "test_support.hpp"

namespace shoal::coast {
namespace {

namespace t = shoal::test;
using geo::LonLat;
using geo::XY;

const std::string& cut() {
    static const std::string p = t::data_path("coast/US5WA22M_tacoma_cut.000");
    return p;
}

/// The whole US5WA22M cell from the project's shared data ($SHOAL_SHARED_DATA, or
/// ../shared/data beside the repository); "" when it is not there.
std::string whole_cell() {
    const std::filesystem::path shared = std::getenv("SHOAL_SHARED_DATA")
                                             ? std::filesystem::path(std::getenv("SHOAL_SHARED_DATA"))
                                             : std::filesystem::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().parent_path() /
                                                   "shared" / "data";
    const std::filesystem::path cell = shared / "coast" / "s57" / "US5WA22M" / "US5WA22M.000";
    return std::filesystem::exists(cell) ? cell.string() : "";
}

GDALDatasetUniquePtr open(const std::string& path) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) throw std::runtime_error("cannot open " + path);
    return ds;
}

/// Features of `layer` passing the OGR SQL filter `where`, by geometry type, as OGR counts them.
struct OgrCount {
    std::uint64_t features = 0, polygons = 0, lines = 0, points = 0;
};
OgrCount ogr_count(const std::string& path, const std::string& layer, const std::string& where = "") {
    GDALDatasetUniquePtr ds = open(path);
    OgrCount n;
    OGRLayer* l = ds->GetLayerByName(layer.c_str());
    if (!l) return n;
    if (!where.empty() && l->SetAttributeFilter(where.c_str()) != OGRERR_NONE) throw std::runtime_error("bad filter " + where);
    for (auto& f : *l) {
        ++n.features;
        const OGRGeometry* g = f->GetGeometryRef();
        switch (wkbFlatten(g->getGeometryType())) {
        case wkbPolygon: ++n.polygons; break;
        case wkbLineString: ++n.lines; break;
        case wkbPoint: ++n.points; break;
        default: throw std::runtime_error("unexpected geometry in " + layer);
        }
    }
    return n;
}

const LayerStats& layer_named(const Coastline& c, const std::string& name) {
    for (const auto& l : c.layers)
        if (l.layer == name) return l;
    throw std::runtime_error("no layer " + name);
}

TEST(StructureImport, CountsPerLayerEqualOgr) {
    const Coastline c = import_coastline({cut()});
    // The cut's layers, in the default order; it has no dangers and no hulk.
    std::vector<std::string> names;
    for (const auto& l : c.layers) names.push_back(l.layer);
    EXPECT_EQ(names, (std::vector<std::string>{"LNDARE", "COALNE", "DEPARE", "DRGARE", "SLCONS", "PONTON", "MORFAC"}));
    std::uint64_t features = 0;
    for (const char* layer : {"SLCONS", "PONTON", "MORFAC"}) {
        SCOPED_TRACE(layer);
        const LayerStats& l = layer_named(c, layer);
        const OgrCount n = ogr_count(cut(), layer);
        EXPECT_EQ(l.kind, HazardKind::structure);
        EXPECT_EQ(l.features, n.features);
        EXPECT_EQ(l.structures, n.features) << "no mooring buoy or chain in the cut";
        EXPECT_EQ(l.not_hazards, 0u);
        EXPECT_EQ(l.polygons, n.polygons);
        EXPECT_EQ(l.lines, n.lines);
        EXPECT_EQ(l.points, n.points);
        EXPECT_EQ(l.points_skipped, 0u);
        EXPECT_EQ(l.hazards, 0u) << "structures are not depth hazards";
        EXPECT_TRUE(l.depth_field.empty());
        features += n.features;
    }
    // The cut's own figures (tests/data/README.md), as a check of the filters.
    EXPECT_EQ(features, 84u);
    EXPECT_EQ(ogr_count(cut(), "SLCONS", "CATSLC = 4").features, 49u);
    EXPECT_EQ(ogr_count(cut(), "SLCONS", "CATSLC = 6").features, 2u);
    EXPECT_EQ(ogr_count(cut(), "MORFAC", "CATMOR = 1").features, 4u);
    // Every structure polyline is a ring with its inside on the left, of a known kind, with no depth.
    std::uint64_t rings = 0;
    for (const Polyline& p : c.polylines) {
        if (p.hazard.kind != HazardKind::structure) {
            EXPECT_EQ(p.hazard.structure, StructureKind::none);
            continue;
        }
        ++rings;
        EXPECT_TRUE(p.land_left);
        EXPECT_TRUE(p.points.front() == p.points.back());
        EXPECT_TRUE(is_hazard(p.hazard.structure)) << to_string(p.hazard.structure);
        EXPECT_TRUE(std::isnan(p.hazard.depth_m));
        const std::string& layer = c.layers.at(p.layer).layer;
        if (layer == "PONTON") {
            EXPECT_EQ(p.hazard.structure, StructureKind::pontoon);
        }
        if (layer == "MORFAC") {
            EXPECT_EQ(p.hazard.structure, StructureKind::dolphin);
        }
    }
    EXPECT_EQ(c.count(HazardKind::structure), rings);
    EXPECT_GE(rings, features) << "at least one ring per structure";
}

TEST(StructureImport, EachFeatureKeepsTheKindOfItsCatslcAndItsName) {
    const Coastline c = import_coastline({cut()});
    std::uint32_t slcons = 0;
    for (std::uint32_t i = 0; i < c.layers.size(); ++i)
        if (c.layers[i].layer == "SLCONS") slcons = i;
    std::map<std::int64_t, std::vector<const Polyline*>> by_fid;
    for (const Polyline& p : c.polylines)
        if (p.layer == slcons) by_fid[p.fid].push_back(&p);
    const std::map<int, StructureKind> catslc = {{4, StructureKind::pier}, {6, StructureKind::wharf}, {8, StructureKind::rip_rap},
                                                 {10, StructureKind::sea_wall}, {13, StructureKind::slipway}};
    GDALDatasetUniquePtr ds = open(cut());
    std::set<std::string> named;
    for (auto& f : *ds->GetLayerByName("SLCONS")) {
        const auto& rings = by_fid[f->GetFID()];
        ASSERT_FALSE(rings.empty()) << "feature " << f->GetFID();
        const StructureKind want = catslc.at(f->GetFieldAsInteger("CATSLC"));
        const std::string name = f->IsFieldSetAndNotNull(f->GetFieldIndex("OBJNAM")) ? f->GetFieldAsString("OBJNAM") : "";
        if (!name.empty()) named.insert(name);
        for (const Polyline* p : rings) {
            EXPECT_EQ(p->hazard.structure, want) << "feature " << f->GetFID();
            EXPECT_EQ(p->hazard.name, name) << "feature " << f->GetFID();
        }
    }
    EXPECT_EQ(named, (std::set<std::string>{"Pier 23", "Pier 24", "Pier 25"}));
    EXPECT_STREQ(to_string(StructureKind::pier), "pier");
    EXPECT_STREQ(to_string(StructureKind::open_face_wharf), "open face wharf");
    EXPECT_STREQ(to_string(StructureKind::shoreline_construction), "structure");
    EXPECT_STREQ(to_string(HazardKind::structure), "structure");
}

/// A GeoJSON FeatureCollection named `layer` (its OGR layer name) of the given features.
std::string write_layer(const t::TempDir& dir, const std::string& layer, const std::string& features) {
    const std::string path = dir.file(layer + ".geojson");
    std::ofstream(path) << R"({"type":"FeatureCollection","name":")" << layer << R"(","features":[)" << features << "]}";
    return path;
}

std::string point_feature(double lon, double lat, const std::string& props) {
    char buf[256];
    std::snprintf(buf, sizeof buf, R"({"type":"Feature","properties":{%s},"geometry":{"type":"Point","coordinates":[%.7f,%.7f]}})",
                  props.c_str(), lon, lat);
    return buf;
}

TEST(StructureImport, MooringBuoysAndChainsAreNoHazardAndEveryCategoryHasItsKind) {
    t::TempDir dir;
    // CATMOR 1..7 and none, 100 m apart along a parallel, in any OGR source with the class's name.
    std::string f;
    for (int k = 0; k <= 7; ++k)
        f += (k ? "," : "") + point_feature(-122.4 + 0.0015 * k, 47.28, k ? R"("CATMOR":)" + std::to_string(k) + R"(,"OBJNAM":"D)" + std::to_string(k) + "\"" : R"("OBJNAM":"D0")");
    const std::string morfac = write_layer(dir, "MORFAC", f);
    // CATSLC as text, as other converters write it: a number, a list, a name, out of range, none.
    const std::string slcons = write_layer(
        dir, "SLCONS",
        point_feature(-122.41, 47.27, R"("CATSLC":"4")") + "," + point_feature(-122.409, 47.27, R"("CATSLC":"6,4")") + "," +
            point_feature(-122.408, 47.27, R"("CATSLC":"open face wharf")") + "," + point_feature(-122.407, 47.27, R"("CATSLC":"99")") + "," +
            point_feature(-122.406, 47.27, R"("name":"Old Dock")"));
    const Coastline c = import_coastline({morfac, slcons});
    ASSERT_EQ(c.layers.size(), 2u);
    EXPECT_EQ(c.layers[0].kind, HazardKind::structure);
    EXPECT_EQ(c.layers[0].features, 8u);
    EXPECT_EQ(c.layers[0].structures, 6u);
    EXPECT_EQ(c.layers[0].not_hazards, 2u) << "CATMOR 6 (chain) and 7 (mooring buoy)";
    std::vector<std::pair<StructureKind, std::string>> got;
    for (const Polyline& p : c.polylines) got.emplace_back(p.hazard.structure, p.hazard.name);
    const std::vector<std::pair<StructureKind, std::string>> want = {
        {StructureKind::mooring_facility, "D0"}, {StructureKind::dolphin, "D1"}, {StructureKind::deviation_dolphin, "D2"},
        {StructureKind::bollard, "D3"}, {StructureKind::tie_up_wall, "D4"}, {StructureKind::post_or_pile, "D5"},
        {StructureKind::pier, ""}, {StructureKind::wharf, ""}, {StructureKind::open_face_wharf, ""},
        {StructureKind::shoreline_construction, ""}, {StructureKind::shoreline_construction, "Old Dock"}};
    EXPECT_EQ(got, want);
    EXPECT_FALSE(is_hazard(StructureKind::mooring_buoy));
    EXPECT_FALSE(is_hazard(StructureKind::chain_wire_cable));
    EXPECT_TRUE(for_every_vessel(HazardKind::structure));
    EXPECT_FALSE(for_every_vessel(HazardKind::danger));
}

TEST(StructureImport, PointsBecomeDiscsAndLinesBandsCircumscribedAsDocumented) {
    t::TempDir dir;
    const double lon0 = -122.4, lat0 = 47.28;
    const Eigen::Vector2d mpd = geo::metres_per_degree(lat0);
    const double dlon = 100 / geo::metres_per_degree(lat0 + 0.01).x();  // a line 100 m long, west to east, 0.01 degrees north
    char line[256];
    std::snprintf(line, sizeof line,
                  R"(,{"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[%.12f,%.12f],[%.12f,%.12f]]}})",
                  lon0, lat0 + 0.01, lon0 + dlon, lat0 + 0.01);
    const std::string path = write_layer(dir, "PONTON", point_feature(lon0, lat0, "") + line);
    const Coastline c = import_coastline({path});
    ASSERT_EQ(c.polylines.size(), 2u);
    const double slack = 1 / std::cos(std::numbers::pi / (4 * structure_quadrant_segments));
    // The disc: every vertex at radius / cos(pi / 32) from the point, 32 of them.
    const Polyline& disc = c.polylines[0];
    EXPECT_EQ(disc.points.size(), 4u * structure_quadrant_segments + 1);
    for (const LonLat& p : disc.points) {
        const double r = std::hypot((p.lon - lon0) * mpd.x(), (p.lat - lat0) * mpd.y());
        EXPECT_NEAR(r, structure_point_radius_m * slack, 1e-6);
    }
    // The band: reaches the half width (x slack) north and south, and as far beyond each end.
    const Polyline& band = c.polylines[1];
    double n = -INFINITY, s = INFINITY, w = INFINITY, e = -INFINITY;
    const double y0 = lat0 + 0.01;
    const Eigen::Vector2d mpd1 = geo::metres_per_degree(y0);
    for (const LonLat& p : band.points) {
        n = std::max(n, (p.lat - y0) * mpd1.y());
        s = std::min(s, (p.lat - y0) * mpd1.y());
        w = std::min(w, (p.lon - lon0) * mpd1.x());
        e = std::max(e, (p.lon - lon0) * mpd1.x());
    }
    const double h = structure_line_half_width_m * slack;
    EXPECT_NEAR(n, h, 1e-6);
    EXPECT_NEAR(s, -h, 1e-6);
    EXPECT_NEAR(w, -h, 1e-6);
    EXPECT_NEAR(e, 100 + h, 1e-6);
    EXPECT_TRUE(band.land_left && disc.land_left);
}

TEST(StructureImport, WholeCellHasItsPiersPontoonsDolphinsAndHulks) {
    const std::string cell = whole_cell();
    if (cell.empty()) GTEST_SKIP() << "US5WA22M.000 not found (set SHOAL_SHARED_DATA)";
    const Coastline c = import_coastline({cell});
    const auto structures = [&](const char* layer) { return layer_named(c, layer).structures; };
    EXPECT_EQ(structures("SLCONS"), ogr_count(cell, "SLCONS").features);
    EXPECT_EQ(structures("PONTON"), ogr_count(cell, "PONTON").features);
    EXPECT_EQ(structures("HULKES"), ogr_count(cell, "HULKES").features);
    EXPECT_EQ(structures("MORFAC"), ogr_count(cell, "MORFAC", "CATMOR NOT IN (6, 7) OR CATMOR IS NULL").features);
    EXPECT_EQ(layer_named(c, "MORFAC").not_hazards, ogr_count(cell, "MORFAC", "CATMOR IN (6, 7)").features);
    // The figures of the task: 717 piers, 30 wharves, 582 pontoons, 103 dolphins (and 11 buoys), 5 hulks.
    std::map<StructureKind, std::set<std::pair<std::uint32_t, std::int64_t>>> features;
    for (const Polyline& p : c.polylines)
        if (p.hazard.kind == HazardKind::structure) features[p.hazard.structure].insert({p.layer, p.fid});
    EXPECT_EQ(features[StructureKind::pier].size(), 717u);
    EXPECT_EQ(features[StructureKind::wharf].size(), 30u);
    EXPECT_EQ(features[StructureKind::pontoon].size(), 582u);
    EXPECT_EQ(features[StructureKind::dolphin].size(), 103u);
    EXPECT_EQ(features[StructureKind::hulk].size(), 5u);
    EXPECT_EQ(features.count(StructureKind::mooring_buoy), 0u);
}

// ---------------------------------------------------------------------------------------------
// Structures as expected-contact areas

geo::LocalFrame tacoma_frame() { return geo::LocalFrame::transverse_mercator({-122.4095, 47.28325}); }

/// The first point of every feature of `layer` (a point's own position, a line's first vertex).
std::vector<LonLat> first_points(const std::string& path, const std::string& layer) {
    GDALDatasetUniquePtr ds = open(path);
    std::vector<LonLat> out;
    for (auto& f : *ds->GetLayerByName(layer.c_str())) {
        const OGRGeometry* g = f->GetGeometryRef();
        if (wkbFlatten(g->getGeometryType()) == wkbPoint) out.push_back({g->toPoint()->getX(), g->toPoint()->getY()});
        else if (wkbFlatten(g->getGeometryType()) == wkbLineString)
            out.push_back({g->toLineString()->getX(0), g->toLineString()->getY(0)});
    }
    return out;
}

TEST(StructureAreas, PontoonsDolphinsAndHulksAreStructuresWithKindAndName) {
    const geo::LocalFrame frame = tacoma_frame();
    std::vector<std::string> warnings;
    const ExpectedAreas areas = ExpectedAreas::load({}, {cut()}, frame, 10.0, &warnings);
    EXPECT_EQ(areas.count(AreaRole::expected), 0u) << "the cut has no berth, harbour or anchorage";
    EXPECT_EQ(areas.count(AreaRole::structure), 84u);
    std::map<std::string, int> kinds;
    std::set<std::string> names;
    for (const ExpectedArea& a : areas.areas()) {
        ++kinds[a.kind];
        if (!a.name.empty()) names.insert(a.kind + " " + a.name);
    }
    EXPECT_EQ(kinds["pontoon"], 15);
    EXPECT_EQ(kinds["dolphin"], 4);
    EXPECT_EQ(kinds["pier"], 49);
    EXPECT_EQ(kinds["wharf"], 2);
    EXPECT_TRUE(names.count("pier Pier 23"));
    // At each dolphin and pontoon: the area found is that one, or a shoreline construction
    // read before it (SLCONS come first) within the tolerance.
    int found_own = 0;
    for (const auto& [layer, kind] : {std::pair<std::string, std::string>{"MORFAC", "dolphin"}, {"PONTON", "pontoon"}})
        for (const LonLat& p : first_points(cut(), layer)) {
            const ExpectedArea* a = areas.find(frame.forward(p), AreaRole::structure);
            ASSERT_NE(a, nullptr) << layer;
            EXPECT_TRUE(a->kind == kind || a->layer == "SLCONS") << a->kind << " in " << a->layer;
            found_own += a->kind == kind;
        }
    EXPECT_GE(found_own, 10);
    // On Pier 23's outline, far from the other piers: the pier, named.
    const ExpectedArea* pier = areas.find(frame.forward({-122.4143010, 47.2847665}), AreaRole::structure);
    ASSERT_NE(pier, nullptr);
    EXPECT_EQ(pier->kind, "pier");
    EXPECT_EQ(pier->name, "Pier 23");
    EXPECT_EQ(areas.find(frame.forward({-122.4150, 47.2870}), AreaRole::structure), nullptr) << "open water";
}

TEST(StructureAreas, WholeCellHasHulksAndNoMooringBuoys) {
    const std::string cell = whole_cell();
    if (cell.empty()) GTEST_SKIP() << "US5WA22M.000 not found (set SHOAL_SHARED_DATA)";
    const geo::LocalFrame frame = geo::LocalFrame::transverse_mercator({-122.45, 47.28});
    const ExpectedAreas areas = ExpectedAreas::load({}, {cell}, frame, 10.0, nullptr);
    std::map<std::string, std::size_t> kinds;
    for (const ExpectedArea& a : areas.areas()) ++kinds[a.kind];
    EXPECT_EQ(kinds["hulk"], 5u);
    EXPECT_EQ(kinds["dolphin"], 103u);
    EXPECT_EQ(kinds.count("mooring buoy"), 0u);
    EXPECT_EQ(kinds["pontoon"], 582u);
    GDALDatasetUniquePtr ds = open(cell);
    for (auto& f : *ds->GetLayerByName("HULKES")) {
        OGRPoint c;
        ASSERT_EQ(f->GetGeometryRef()->Centroid(&c), OGRERR_NONE);
        const ExpectedArea* a = areas.find(frame.forward({c.getX(), c.getY()}), AreaRole::structure);
        ASSERT_NE(a, nullptr);
        EXPECT_TRUE(a->kind == "hulk" || a->layer == "SLCONS" || a->layer == "PONTON") << a->kind;
    }
}

}  // namespace

// Whether a file may be an S-57 chart is first told from its first bytes without GDAL (a check
// of a grid whose sources are GeoJSON may then never load GDAL): the answer is GDAL's S-57
// driver's own, on the committed cells and on their beginnings cut, spoilt byte by byte, cut by
// a NUL or without their DSID, and on random files; and the rule never refuses a file the
// driver claims.
TEST(S57Identify, TheLeaderRuleAnswersAsGdalsDriverAndNeverRefusesWhatItClaims) {
    GDALAllRegister();
    const t::TempDir dir;
    std::vector<std::string> contents;
    std::mt19937 rng(57);
    for (const char* cell : {"coast/US5WA22M_tacoma_cut.000", "coast/US4MD81M_cut.000", "coast/US4MD81M_hazard_cut.000"}) {
        const std::string whole = t::read_text(t::data_path(cell));
        const std::string head = whole.substr(0, 2048);
        contents.push_back(whole);
        for (std::size_t n : {0, 5, 9, 10, 11, 24, 100, 1023, 1024, 1025}) contents.push_back(head.substr(0, n));
        for (std::size_t at = 0; at < 40; ++at) {  // the leader's bytes: each digit, blank and mark, and random ones
            std::string values = at < 24 ? "0123456789 LDAR-" : "";
            for (int k = 0; k < 3; ++k) values += static_cast<char>(rng() % 256);
            for (char v : values) {
                std::string c = head;
                c[at] = v;
                contents.push_back(c);
            }
        }
        for (std::size_t at = 0; at < 200; at += 7) {
            std::string c = head;
            c[at] = '\0';
            contents.push_back(c);
        }
        std::string no_dsid = head;
        for (std::size_t at = no_dsid.find("DSID"); at != std::string::npos; at = no_dsid.find("DSID", at + 1)) no_dsid[at + 3] = 'X';
        contents.push_back(no_dsid);
        std::string far_dsid = head;  // the field names moved beyond the first 1,024 bytes
        far_dsid.insert(24, std::string(1100, '0'));
        contents.push_back(far_dsid);
    }
    for (int k = 0; k < 40; ++k) {
        std::string c(rng() % 64, ' ');
        for (char& ch : c) ch = static_cast<char>(rng() % 256);
        contents.push_back(c);
    }
    int told_without_gdal = 0, claimed = 0;
    for (std::size_t i = 0; i < contents.size(); ++i) {
        const std::string path = dir.file("c" + std::to_string(i) + ".000");
        std::ofstream(path, std::ios::binary) << contents[i];
        const char* const s57_only[] = {"S57", nullptr};
        const bool gdal = GDALIdentifyDriverEx(path.c_str(), GDAL_OF_VECTOR, s57_only, nullptr) != nullptr;
        EXPECT_EQ(ogr::may_be_s57(path), gdal) << "content " << i;
        if (gdal) {
            EXPECT_TRUE(ogr::s57_leader_possible(contents[i])) << "content " << i;
        }
        claimed += gdal;
        told_without_gdal += !ogr::s57_leader_possible(contents[i]);
    }
    EXPECT_GE(claimed, 30);
    EXPECT_GE(told_without_gdal, 60);
}

}  // namespace shoal::coast
