// The QGIS project beside a GeoJSON report (REPORT.qgz and the layer files it opens), read
// back with GDAL (/vsizip/, cpl_minixml, OGR) as an independent reader; the GeoPackage's
// --no-project and --poses-interval; and the simplified pose outline against GEOS.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "geo/geos_context.hpp"
#include "sweep/pose_outline.hpp"
#include "run_shoal.hpp"
#include "xml_support.hpp"
#include <shoal/hull/hull.hpp>
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using shoal::test::attr;
using shoal::test::each_element;

/// A folder for this run's files, removed when the tests end.
fs::path dir() {
    static const shoal::test::TempDir d;
    return d.path();
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

shoal::test::Outcome shoal(const std::string& args) {
    GDALAllRegister();  // for the tests' own reading (each test may run alone)
    return shoal::test::run_shoal(args, dir() / "cache", dir() / "stderr.txt");
}

/// Two ships in the Solent (as tests/report/qgis/qgis_report_test.py): A southwards across the
/// Isle of Wight (aground), B eastwards clear of land.
std::string tracks() {
    static const std::string path = [] {
        const fs::path p = dir() / "solent-tracks.csv";
        std::ofstream f(p);
        f << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
        char line[128];
        for (int i = 0; i < 21; ++i) {
            std::snprintf(line, sizeof line, "111111111,2024-05-01T10:%02d:00Z,%.4f,-1.3000,11.9,180,180\n", i, 50.78 - 0.01 * i);
            f << line;
        }
        for (int i = 0; i < 11; ++i) {
            std::snprintf(line, sizeof line, "222222222,2024-05-01T10:%02d:00Z,50.7400,%.4f,8,90,90\n", i, -1.05 + 0.002 * i);
            f << line;
        }
        return p.string();
    }();
    return path;
}

std::string check_args(const fs::path& out, const std::string& more = "") {
    return "check --world simulated --coast '" + std::string(SHOAL_TEST_DATA) + "coast/uk_solent_land.geojson' --dims 50,10,5,5 --no-progress '" + tracks() +
           "' -o '" + out.string() + "' " + more;
}

/// The .qgs inside a .qgz, read through GDAL's /vsizip/.
std::string qgs_in(const fs::path& qgz, const std::string& member) {
    VSILFILE* f = VSIFOpenL(("/vsizip/{" + qgz.string() + "}/" + member).c_str(), "rb");
    if (!f) return {};
    std::string text;
    char buf[65536];
    for (std::size_t n; (n = VSIFReadL(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
    VSIFCloseL(f);
    return text;
}

/// Features of the one layer of the vector file at `path` (-1: cannot be opened).
long long feature_count(const fs::path& path) {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds || ds->GetLayerCount() != 1) return -1;
    return ds->GetLayer(0)->GetFeatureCount();
}

/// Every layer file beside the GeoJSON report dir()/STEM.geojson holds the features of the
/// GeoPackage report `g`'s layer (written there by GDAL), field by field, and its geometries
/// to 7 decimals (printf's rounding), each of the layer's type, RFC 7946's way round: shells
/// counter-clockwise, holes clockwise.
void expect_layer_files_hold_the_geopackages(GDALDataset& g, const std::string& stem) {
    for (const char* layer : {"hulls", "poses", "tracks", "coast"}) {
        SCOPED_TRACE(layer);
        GDALDatasetUniquePtr j(GDALDataset::Open((dir() / (stem + "." + std::string(layer) + ".geojson")).c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
        ASSERT_TRUE(j);
        OGRLayer* a = g.GetLayerByName(layer);
        OGRLayer* b = j->GetLayer(0);
        ASSERT_EQ(a->GetFeatureCount(), b->GetFeatureCount());
        const OGRwkbGeometryType type = a->GetGeomType();
        a->ResetReading();
        b->ResetReading();
        for (;;) {
            OGRFeatureUniquePtr fa(a->GetNextFeature()), fb(b->GetNextFeature());
            if (!fa || !fb) {
                EXPECT_EQ(!fa, !fb);
                break;
            }
            ASSERT_EQ(fa->GetFieldCount(), fb->GetFieldCount());
            for (int k = 0; k < fa->GetFieldCount(); ++k)
                EXPECT_STREQ(fa->GetFieldAsString(k), fb->GetFieldAsString(k)) << fa->GetFieldDefnRef(k)->GetNameRef();
            const OGRGeometry* ga = fa->GetGeometryRef();
            const OGRGeometry* gb = fb->GetGeometryRef();
            ASSERT_TRUE(ga && gb);
            EXPECT_EQ(wkbFlatten(gb->getGeometryType()), wkbFlatten(type));
            // Rings as lists of points, each the GeoPackage's rounded, turned as RFC 7946 wants.
            auto rings_of = [](const OGRGeometry* geom) {
                std::vector<std::vector<std::pair<std::string, std::string>>> out;
                auto add = [&](const OGRLineString& ls, int turn) {  // turn: +1 ccw, -1 cw, 0 as it is
                    std::vector<std::pair<std::string, std::string>> pts;
                    double area2 = 0;
                    for (int i = 0; i + 1 < ls.getNumPoints(); ++i) area2 += ls.getX(i) * ls.getY(i + 1) - ls.getX(i + 1) * ls.getY(i);
                    char x[64], y[64];
                    for (int i = 0; i < ls.getNumPoints(); ++i) {
                        std::snprintf(x, sizeof x, "%.7f", ls.getX(i));  // the GeoPackage's rounded; the file's as it is
                        std::snprintf(y, sizeof y, "%.7f", ls.getY(i));
                        pts.push_back({x, y});
                    }
                    if (turn != 0 && area2 != 0 && (area2 > 0) != (turn > 0)) std::reverse(pts.begin(), pts.end());
                    out.push_back(std::move(pts));
                };
                auto polygon = [&](const OGRPolygon& p) {
                    for (int k = 0; k <= p.getNumInteriorRings(); ++k) add(k == 0 ? *p.getExteriorRing() : *p.getInteriorRing(k - 1), k == 0 ? 1 : -1);
                };
                switch (wkbFlatten(geom->getGeometryType())) {
                    case wkbPolygon: polygon(*geom->toPolygon()); break;
                    case wkbMultiPolygon: for (const OGRPolygon* p : *geom->toMultiPolygon()) polygon(*p); break;
                    case wkbLineString: add(*geom->toLineString(), 0); break;
                    case wkbMultiLineString: for (const OGRLineString* l : *geom->toMultiLineString()) add(*l, 0); break;
                    default: ADD_FAILURE() << "geometry type " << geom->getGeometryName();
                }
                return out;
            };
            EXPECT_EQ(rings_of(ga), rings_of(gb));
            if (wkbFlatten(gb->getGeometryType()) == wkbPolygon) {  // as written: the shell counter-clockwise
                const OGRLinearRing* shell = gb->toPolygon()->getExteriorRing();
                EXPECT_FALSE(shell->isClockwise());
            }
        }
    }

}

TEST(GeojsonProject, TheQgzHoldsTheQgsWhoseLayersAreTheFilesBesideTheReport) {
    const fs::path report = dir() / "run.geojson";
    const auto r = shoal(check_args(report));
    ASSERT_EQ(r.status, 1) << r.err;  // ship A runs aground
    const fs::path qgz = dir() / "run.qgz";
    ASSERT_TRUE(fs::exists(qgz)) << r.err;
    EXPECT_EQ(slurp(qgz).substr(0, 4), std::string("PK\x03\x04")) << "a zip";
    const std::string qgs = qgs_in(qgz, "run.qgs");
    ASSERT_FALSE(qgs.empty()) << "the .qgz holds run.qgs";
    std::string error;
    const shoal::test::XmlPtr doc = shoal::test::parse_xml(qgs, &error);
    ASSERT_TRUE(doc) << error;

    // The layer tree, top first; each layer's source a file beside the report, by relative path.
    std::vector<std::string> order;
    std::map<std::string, std::string> source;  // layer name -> datasource
    std::map<std::string, const CPLXMLNode*> maplayer;
    for (const CPLXMLNode* n = doc.get(); n; n = n->psNext)
        each_element(n, [&](const CPLXMLNode* e) {
            const std::string name = e->pszValue;
            if (name == "layer-tree-layer") order.push_back(attr(e, "name"));
            if (name == "maplayer") {
                const std::string layer = CPLGetXMLValue(e, "layername", "");
                source[layer] = CPLGetXMLValue(e, "datasource", "");
                maplayer[layer] = e;
            }
        });
    EXPECT_EQ(order, (std::vector<std::string>{"events", "hulls", "poses", "tracks", "coast"}));
    // (Each with its geometry type: QGIS opens an OGR layer with no feature, e.g. no events, as a table.)
    const std::map<std::string, std::string> expected{{"events", "./run.geojson|geometrytype=Point"},
                                                      {"hulls", "./run.hulls.geojson|geometrytype=Polygon"},
                                                      {"poses", "./run.poses.geojson|geometrytype=Polygon"},
                                                      {"tracks", "./run.tracks.geojson|geometrytype=MultiLineString"},
                                                      {"coast", "./run.coast.geojson|geometrytype=MultiPolygon"}};
    EXPECT_EQ(source, expected);
    for (const auto& [layer, src] : expected) {
        const fs::path file = dir() / src.substr(2, src.find('|') - 2);
        EXPECT_GT(feature_count(file), 0) << file << " opens with OGR and has features";
        if (layer != "events") {
            const fs::path qml = fs::path(file).replace_extension(".qml");  // run.poses.qml: QGIS's default style of run.poses.geojson
            EXPECT_NE(slurp(qml).find("<renderer-v2"), std::string::npos) << qml << " is a QGIS style";
        }
    }
    // The poses replay the run: their temporal settings are in the project's layer.
    ASSERT_TRUE(maplayer.count("poses"));
    const CPLXMLNode* temporal = CPLGetXMLNode(maplayer["poses"], "temporal");
    ASSERT_NE(temporal, nullptr);
    EXPECT_EQ(attr(temporal, "startField"), "time");
    EXPECT_EQ(attr(temporal, "endField"), "until");
    EXPECT_EQ(attr(temporal, "enabled"), "1");
    const CPLXMLNode* qgis = CPLSearchXMLNode(doc.get(), "=qgis");
    ASSERT_NE(qgis, nullptr);
    EXPECT_STREQ(CPLGetXMLValue(qgis, "ProjectTimeSettings.TemporalRange.start", ""), "2024-05-01T10:00:00Z");
    EXPECT_STREQ(CPLGetXMLValue(qgis, "ProjectTimeSettings.TemporalRange.end", ""), "2024-05-01T10:20:00Z");
    EXPECT_STREQ(CPLGetXMLValue(qgis, "projectCrs.spatialrefsys.authid", ""), "EPSG:32630");

    // The poses file: the same rows as the GeoPackage's poses layer (one writer for both).
    const fs::path gpkg = dir() / "run.gpkg";
    ASSERT_EQ(shoal(check_args(gpkg)).status, 1);
    GDALDatasetUniquePtr g(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    ASSERT_TRUE(g);
    EXPECT_EQ(g->GetLayerByName("poses")->GetFeatureCount(), feature_count(dir() / "run.poses.geojson"));
    EXPECT_EQ(g->GetLayerByName("coast")->GetFeatureCount(), feature_count(dir() / "run.coast.geojson"));
    expect_layer_files_hold_the_geopackages(*g, "run");

    // The same run, the same bytes (GDAL's zip stamps no date).
    const std::string before = slurp(qgz);
    ASSERT_EQ(shoal(check_args(report)).status, 1);
    EXPECT_EQ(slurp(qgz), before);
}

/// Layer files of many features are written in blocks on threads: any number of threads
/// writes the same bytes, and they still hold the GeoPackage's features in its order.
TEST(GeojsonProject, LayerFilesOfManyBlocksAreTheSameOnAnyNumberOfThreads) {
    const fs::path csv = dir() / "many.csv";
    {
        std::ofstream f(csv);
        f << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
        char line[128];
        for (int v = 0; v < 6; ++v)  // eastwards along the Solent, some across the Isle of Wight
            for (int i = 0; i < 1500; ++i) {
                std::snprintf(line, sizeof line, "%d,%.0f,%.5f,%.5f,9,90,90\n", 311000000 + v, 1714557600.0 + 10.0 * i, 50.62 + 0.03 * v,
                              -1.6 + 0.0004 * i);
                f << line;
            }
    }
    std::vector<std::string> texts;
    for (const char* jobs : {"1", "3"}) {
        const std::string stem = std::string("many") + jobs;
        const std::string args = "check --world simulated --coast '" + std::string(SHOAL_TEST_DATA) + "coast/uk_solent_land.geojson' --dims 50,10,5,5 --no-progress '" +
                                 csv.string() + "' --poses-interval 0 --jobs " + jobs + " -o '";
        const auto r = shoal(args + (dir() / (stem + ".geojson")).string() + "'");
        ASSERT_LE(r.status, 1) << r.err;
        std::string text;
        for (const char* layer : {"poses", "tracks", "hulls", "coast"}) text += slurp(dir() / (stem + "." + layer + ".geojson"));
        texts.push_back(text);
        ASSERT_LE(shoal(args + (dir() / (stem + ".gpkg")).string() + "'").status, 1);
        GDALDatasetUniquePtr g(GDALDataset::Open((dir() / (stem + ".gpkg")).c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
        ASSERT_TRUE(g);
        EXPECT_EQ(g->GetLayerByName("poses")->GetFeatureCount(), 9000) << "a pose at every fix";
        expect_layer_files_hold_the_geopackages(*g, stem);
    }
    EXPECT_GT(texts[0].size(), std::size_t{4} << 20) << "a few megabytes: many blocks of 16,384 points";
    EXPECT_TRUE(texts[0] == texts[1]) << "one thread and three write the same bytes";
}

TEST(GeojsonProject, AFileShoalDidNotWriteIsLeftAloneAndNoProjectIsWritten) {
    const fs::path report = dir() / "theirs.geojson";
    const fs::path foreign = dir() / "theirs.poses.geojson";
    { std::ofstream(foreign) << "{\"type\": \"FeatureCollection\", \"features\": []}\n"; }
    const auto r = shoal(check_args(report));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("theirs.poses.geojson' exists and was not written by shoal"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(foreign), "{\"type\": \"FeatureCollection\", \"features\": []}\n");
    EXPECT_FALSE(fs::exists(dir() / "theirs.qgz"));
    EXPECT_FALSE(fs::exists(dir() / "theirs.tracks.geojson"));
    EXPECT_TRUE(fs::exists(report));
    EXPECT_TRUE(fs::exists(dir() / "theirs.qml")) << "the report's own style is still written";

    // A project QGIS saved over shoal's (no mark in its .qgs) is the user's now: left alone.
    fs::remove(foreign);
    ASSERT_EQ(shoal(check_args(report)).status, 1);
    const fs::path qgz = dir() / "theirs.qgz";
    ASSERT_TRUE(fs::exists(qgz));
    {
        void* z = CPLCreateZip(qgz.c_str(), nullptr);
        ASSERT_NE(z, nullptr);
        const std::string qgs = "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n<qgis version=\"3.22.16\"/>\n";
        ASSERT_EQ(CPLCreateFileInZip(z, "theirs.qgs", nullptr), CE_None);
        ASSERT_EQ(CPLWriteFileInZip(z, qgs.data(), static_cast<int>(qgs.size())), CE_None);
        CPLCloseFileInZip(z);
        CPLCloseZip(z);
    }
    const std::string saved = slurp(qgz);
    const auto again = shoal(check_args(report));
    EXPECT_NE(again.err.find("theirs.qgz' exists and was not written by shoal"), std::string::npos) << again.err;
    EXPECT_EQ(slurp(qgz), saved);
}

TEST(GeojsonProject, AnOutputThatIsAnInputIsRefusedBeforeAnyWork) {
    // The poses file of the report named as a track file: refused at once (exit 2), nothing written.
    const fs::path report = dir() / "loop.geojson";
    { std::ofstream(dir() / "loop.poses.geojson") << "{}"; }
    const auto r = shoal(check_args(report, "'" + (dir() / "loop.poses.geojson").string() + "'"));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("loop.poses.geojson"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(report));
}

TEST(GeojsonProject, AReportNameHoldingAPipeIsRefusedBeforeAnyWorkUnlessItHasNoProject) {
    // Before: `-o 'a|b.geojson'` (or .gpkg) wrote a QGIS project whose layers were all invalid:
    // QGIS's OGR provider reads '|' in a data source as the start of the layer's options.
    for (const char* name : {"day|1.geojson", "day|1.gpkg"}) {
        const fs::path report = dir() / name;
        const auto r = shoal(check_args(report));
        EXPECT_EQ(r.status, 2) << name << "\n" << r.err;
        EXPECT_NE(r.err.find("shoal: usage error: -o '" + report.string() + "': a report whose name holds '|' would get a QGIS project none of "
                             "whose layers QGIS can open"),
                  std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("or give --no-project"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(report)) << name;
        EXPECT_FALSE(fs::exists(dir() / "day|1.qgz")) << name;
        // Without a project there is no data source to name the file: written.
        const auto plain = shoal(check_args(report, "--no-project"));
        EXPECT_EQ(plain.status, 1) << name << "\n" << plain.err;
        EXPECT_TRUE(fs::exists(report)) << name;
    }
    // A '|' in a folder's name is no harm: the project names its files relative to itself.
    fs::create_directories(dir() / "runs|may");
    const fs::path inside = dir() / "runs|may" / "day.geojson";
    const auto ok = shoal(check_args(inside));
    EXPECT_EQ(ok.status, 1) << ok.err;
    EXPECT_TRUE(fs::exists(dir() / "runs|may" / "day.qgz"));
}

TEST(NoProject, OnlyTheEventsTracksAndHulls) {
    const fs::path report = dir() / "plain.geojson";
    ASSERT_EQ(shoal(check_args(report, "--no-project")).status, 1);
    EXPECT_TRUE(fs::exists(report));
    EXPECT_TRUE(fs::exists(dir() / "plain.qml"));
    for (const char* side : {"plain.qgz", "plain.poses.geojson", "plain.coast.geojson", "plain.tracks.geojson", "plain.hulls.geojson"})
        EXPECT_FALSE(fs::exists(dir() / side)) << side;
    // A run with a project, then one without: the earlier project is left, and said to be stale.
    const fs::path again = dir() / "again.geojson";
    ASSERT_EQ(shoal(check_args(again, "")).status, 1);
    ASSERT_TRUE(fs::exists(dir() / "again.qgz"));
    const auto without = shoal(check_args(again, "--no-project"));
    EXPECT_EQ(without.status, 1);
    EXPECT_NE(without.err.find("QGIS project files of an earlier run are beside the report"), std::string::npos) << without.err;
    EXPECT_NE(without.err.find("(--no-project)"), std::string::npos) << without.err;

    const fs::path gpkg = dir() / "plain.gpkg";
    ASSERT_EQ(shoal(check_args(gpkg, "--no-project")).status, 1);
    GDALDatasetUniquePtr g(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    ASSERT_TRUE(g);
    EXPECT_EQ(g->GetLayerByName("poses"), nullptr);
    EXPECT_EQ(g->GetLayerByName("coast"), nullptr);
    EXPECT_NE(g->GetLayerByName("events"), nullptr);
    OGRLayer* projects = g->ExecuteSQL("SELECT count(*) FROM sqlite_master WHERE name = 'qgis_projects'", nullptr, nullptr);
    ASSERT_NE(projects, nullptr);
    OGRFeatureUniquePtr f(projects->GetNextFeature());
    EXPECT_EQ(f->GetFieldAsInteger64(0), 0) << "no stored project";
    g->ReleaseResultSet(projects);
}

TEST(PosesInterval, ACoarserIntervalKeepsFewerPosesAndZeroEveryFix) {
    const auto poses = [](const std::string& value) -> long long {
        const fs::path gpkg = dir() / ("interval-" + value + ".gpkg");
        if (shoal(check_args(gpkg, "--poses-interval " + value)).status != 1) return -1;
        GDALDatasetUniquePtr g(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
        return g ? g->GetLayerByName("poses")->GetFeatureCount() : -1;
    };
    // 32 fixes a minute apart; every fix at 0, fewer at the default (120 s), fewer still at 600 s.
    const long long every = poses("0"), fine = poses("120"), coarse = poses("600");
    EXPECT_EQ(every, 32);
    EXPECT_LT(fine, every);
    EXPECT_LT(coarse, fine);
    EXPECT_GE(coarse, 4) << "first and last fix of each track at least";
}

TEST(ShardMerge, WithNoProjectOrAPosesIntervalTheMergeIsTheSingleRunByteForByte) {
    // The thinning and the outline depend on the track and the options only: shards merge to one run's bytes.
    for (const std::string& options : {std::string("--no-project"), std::string("--poses-interval 0"), std::string("--poses-interval 600")}) {
        SCOPED_TRACE(options);
        const fs::path single = dir() / "single", merged = dir() / "merged";
        fs::create_directories(single);
        fs::create_directories(merged);
        ASSERT_EQ(shoal(check_args(single / "r.gpkg", options)).status, 1);
        for (int i = 0; i < 2; ++i)
            ASSERT_EQ(shoal(check_args(dir() / ("part" + std::to_string(i) + ".gpkg"), options + " --shard " + std::to_string(i) + "/2")).status < 2, true);
        const auto m = shoal("merge '" + (dir() / "part0.gpkg").string() + "' '" + (dir() / "part1.gpkg").string() + "' -o '" +
                             (merged / "r.gpkg").string() + "'");
        ASSERT_EQ(m.status, 1) << m.err;
        EXPECT_TRUE(slurp(single / "r.gpkg") == slurp(merged / "r.gpkg")) << "the merged GeoPackage is the single run's";
    }
    // Parts made with another interval are not one run's (the run header's poses_interval_s).
    ASSERT_LT(shoal(check_args(dir() / "other1.gpkg", "--poses-interval 600 --shard 1/2")).status, 2);
    ASSERT_LT(shoal(check_args(dir() / "other0.gpkg", "--shard 0/2")).status, 2);
    const auto mixed = shoal("merge '" + (dir() / "other0.gpkg").string() + "' '" + (dir() / "other1.gpkg").string() + "' -o '" +
                             (dir() / "mixed.gpkg").string() + "'");
    EXPECT_EQ(mixed.status, 2);
    EXPECT_NE(mixed.err.find("'poses_interval_s' is 120.0 in"), std::string::npos) << mixed.err;
    // A merged GeoJSON report has its style beside it, but no project (docs/user-guide.md, shoal merge).
    for (int i = 0; i < 2; ++i)
        ASSERT_LT(shoal(check_args(dir() / ("gpart" + std::to_string(i) + ".geojson"), "--shard " + std::to_string(i) + "/2")).status, 2);
    EXPECT_FALSE(fs::exists(dir() / "gpart0.qgz")) << "a shard's GeoJSON part gets no project";
    const auto m = shoal("merge '" + (dir() / "gpart0.geojson").string() + "' '" + (dir() / "gpart1.geojson").string() + "' -o '" +
                         (dir() / "gmerged.geojson").string() + "'");
    ASSERT_EQ(m.status, 1) << m.err;
    EXPECT_TRUE(fs::exists(dir() / "gmerged.qml"));
    EXPECT_FALSE(fs::exists(dir() / "gmerged.qgz"));
}

// --- the simplified pose outline, against GEOS ---

/// A lon/lat ring (closed) simplified by pose_outline_corners in local metres around its first
/// vertex (an equirectangular frame, true to far under a millimetre over a hull).
std::vector<shoal::geo::LonLat> outline_of(const std::vector<shoal::geo::LonLat>& ring) {
    constexpr double metres_per_deg = 6371008.8 * M_PI / 180;
    const double lon0 = ring[0].lon, lat0 = ring[0].lat, kx = std::cos(lat0 * M_PI / 180) * metres_per_deg;
    std::vector<shoal::geo::XY> xy;
    for (const auto& p : ring) xy.push_back({(p.lon - lon0) * kx, (p.lat - lat0) * metres_per_deg});
    std::vector<shoal::geo::LonLat> out;
    for (const std::size_t i : shoal::audit::pose_outline_corners(xy)) out.push_back(ring[i]);
    out.push_back(out.front());
    return out;
}

std::vector<shoal::geo::LonLat> ring_at(const shoal::hull::Hull& h, double lat0, double heading_deg) {
    // The hull's contour turned to `heading_deg` and put at lat0, 25 E (an equirectangular frame).
    constexpr double m = 6371008.8 * M_PI / 180;
    const double a = heading_deg * M_PI / 180;
    std::vector<shoal::geo::LonLat> ring;
    for (const auto& p : h.contour()) {
        const double north = p.x * std::cos(a) - p.y * std::sin(a), east = p.x * std::sin(a) + p.y * std::cos(a);
        ring.push_back({25 + east / (m * std::cos(lat0 * M_PI / 180)), lat0 + north / m});
    }
    ring.push_back(ring.front());
    return ring;
}

TEST(PoseOutline, WithinOnePercentOfTheLengthOfTheOutlineByGeosHausdorffAndFewerPoints) {
    using shoal::geo::XY;
    for (const char* dims : {"100,20,10,10", "50,10,5,5", "300,50,25,25", "12,3,2,2"})
        for (double heading : {0.0, 37.0, 90.0, 211.5}) {
            const shoal::hull::Hull h = shoal::hull::Hull::from_dims_string(dims);
            const auto ring = ring_at(h, 60.1, heading);
            const auto out = outline_of(ring);
            SCOPED_TRACE(std::string(dims) + " heading " + std::to_string(heading));
            ASSERT_EQ(ring.size(), 37u);
            EXPECT_LT(out.size(), 20u) << "36 points come out as fewer";
            EXPECT_GE(out.size(), shoal::audit::pose_outline_min_corners + 1);
            EXPECT_EQ(out.front(), ring.front()) << "the bow tip is kept";
            EXPECT_EQ(out.back(), out.front()) << "closed";
            // A subsequence of the outline's own vertices, in order.
            std::size_t k = 0;
            for (std::size_t i = 0; i + 1 < out.size(); ++i) {
                while (k < ring.size() && !(ring[k] == out[i])) ++k;
                EXPECT_LT(k, ring.size()) << "vertex " << i << " is one of the outline's, in order";
            }
            // GEOS as the oracle: the Hausdorff distance, in local metres, within 1 % of the length.
            constexpr double m = 6371008.8 * M_PI / 180;
            const double kx = std::cos(60.1 * M_PI / 180) * m;
            const auto local = [&](const std::vector<shoal::geo::LonLat>& r) {
                std::vector<XY> xy;
                for (const auto& p : r) xy.push_back({(p.lon - 25) * kx, (p.lat - 60.1) * m});
                return xy;
            };
            shoal::geo::GeosContext ctx;
            const auto a = shoal::geo::make_polygon(ctx, {local(ring)}), b = shoal::geo::make_polygon(ctx, {local(out)});
            double hausdorff = 0;
            ASSERT_EQ(GEOSHausdorffDistance_r(ctx, a.get(), b.get(), &hausdorff), 1);
            // The length is the outline's longest vertex-to-vertex distance: at most the diagonal of its box.
            const auto d = h.dimensions();
            const double diagonal = std::hypot(d.a + d.b, d.c + d.d);
            EXPECT_LE(hausdorff, 0.01 * diagonal) << "diagonal " << diagonal;
            EXPECT_GT(hausdorff, 0) << "something was simplified";
            EXPECT_EQ(GEOSisValid_r(ctx, b.get()), 1) << "a valid polygon";
        }
}

TEST(PoseOutline, RandomNotchedOutlinesComeOutSimpleWithinOnePercentAndTheirOwnVertices) {
    // Star-shaped outlines of 20-200 points with deep, narrow notches and spikes (where a
    // Douglas-Peucker shortcut can cross another part of the ring): whichever simplifier
    // answers, the outline that comes out is valid for GEOS, within 1 % of the length by GEOS's
    // Hausdorff distance, and a subsequence of the outline's own vertices from the first.
    using shoal::geo::XY;
    std::mt19937_64 rng(2026);
    std::uniform_real_distribution<double> unit(0, 1);
    constexpr double m = 6371008.8 * M_PI / 180;
    const double kx = std::cos(60.1 * M_PI / 180) * m;
    shoal::geo::GeosContext ctx;
    int simplified = 0, valid = 0;
    for (int k = 0; k < 300; ++k) {
        const int n = 20 + static_cast<int>(rng() % 180);
        std::vector<XY> xy;
        const double stretch = 1 + 3 * unit(rng);  // long and thin, or round
        for (int i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n;
            double r = 40 + 0.3 * unit(rng);
            if (unit(rng) < 0.1) r *= 0.1 + 0.3 * unit(rng);  // a notch
            else if (unit(rng) < 0.05) r *= 1.5;              // a spike
            xy.push_back({r * std::cos(a) * stretch, r * std::sin(a)});
        }
        xy.push_back(xy.front());
        const auto poly = shoal::geo::make_polygon(ctx, {xy});
        if (GEOSisValid_r(ctx, poly.get()) != 1) continue;  // only simple outlines are hulls
        ++valid;
        std::vector<shoal::geo::LonLat> ring;
        for (const XY& p : xy) ring.push_back({25 + p.x / kx, 60.1 + p.y / m});
        const auto out = outline_of(ring);
        SCOPED_TRACE("outline " + std::to_string(k) + " of " + std::to_string(n) + " points");
        ASSERT_GE(out.size(), shoal::audit::pose_outline_min_corners + 1);
        EXPECT_EQ(out.front(), ring.front());
        EXPECT_EQ(out.back(), out.front());
        std::size_t at = 0;
        for (std::size_t i = 0; i + 1 < out.size(); ++i) {
            while (at < ring.size() && !(ring[at] == out[i])) ++at;
            ASSERT_LT(at, ring.size()) << "vertex " << i << " is one of the outline's, in order";
        }
        std::vector<XY> back;
        for (const auto& q : out) back.push_back({(q.lon - 25) * kx, (q.lat - 60.1) * m});
        const auto b = shoal::geo::make_polygon(ctx, {back});
        EXPECT_EQ(GEOSisValid_r(ctx, b.get()), 1) << "a simple ring";
        double hausdorff = 0, length = 0;
        ASSERT_EQ(GEOSHausdorffDistance_r(ctx, poly.get(), b.get(), &hausdorff), 1);
        for (const XY& p : xy)
            for (const XY& q : xy) length = std::max(length, std::hypot(p.x - q.x, p.y - q.y));
        EXPECT_LE(hausdorff, 0.0101 * length);
        simplified += out.size() < ring.size();
    }
    EXPECT_GT(valid, 250);
    EXPECT_GT(simplified, 200);
}

TEST(PoseOutline, ASliverThatDouglasPeuckerWouldCollapseKeepsItsCorners) {
    // 100 m long, 0.5 m wide, 21 points a side: Douglas-Peucker at 1 m leaves three points (no
    // ring); the topology-preserving simplifier keeps four corners.
    constexpr double m = 6371008.8 * M_PI / 180;
    const double kx = std::cos(60.1 * M_PI / 180) * m;
    std::vector<shoal::geo::LonLat> ring;
    for (int i = 0; i <= 20; ++i) ring.push_back({25 + 5.0 * i / kx, 60.1});
    for (int i = 20; i >= 0; --i) ring.push_back({25 + 5.0 * i / kx, 60.1 + 0.5 / m});
    ring.push_back(ring.front());
    const auto out = outline_of(ring);
    ASSERT_GE(out.size(), shoal::audit::pose_outline_min_corners + 1);
    EXPECT_LT(out.size(), ring.size());
    EXPECT_EQ(out.front(), ring.front());
    EXPECT_EQ(out.back(), out.front());
    for (const shoal::geo::LonLat corner : {ring[20], ring[21], ring[41]})
        EXPECT_NE(std::find(out.begin(), out.end(), corner), out.end()) << "a corner is kept";
}

TEST(PoseOutline, AFourCorneredOutlineIsKeptWhole) {
    const std::vector<shoal::geo::LonLat> box{{25, 60}, {25.001, 60}, {25.001, 60.0002}, {25, 60.0002}, {25, 60}};
    EXPECT_EQ(outline_of(box), box);
    // A rectangle with a point 1 mm off one side: the point goes, the four corners stay.
    const std::vector<shoal::geo::LonLat> bumped{{25, 60}, {25.0005, 60.00000001}, {25.001, 60}, {25.001, 60.0002}, {25, 60.0002}, {25, 60}};
    const auto out = outline_of(bumped);
    EXPECT_EQ(out, box);
}

}  // namespace
