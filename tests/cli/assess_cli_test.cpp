// `shoal check --assess FILE` on a constructed exercise (the passage of assessment_test.cpp,
// as files): the scores and breaches on stdout, in the GeoJSON (shoal.assessment, breach
// features, valid against schemas/report.schema.json) and in the GeoPackage (the breaches
// layer with DateTime fields, the scores table, the layer's style and the QGIS project);
// bad assessment files refused before any work (exit 2) naming the file; the file is an input.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <shoal/geo/local_frame.hpp>
#include <shoal/track/time.hpp>

#include "run_shoal.hpp"
#include "test_support.hpp"

namespace shoal {
namespace {

namespace fs = std::filesystem;
using geo::LonLat;
using geo::XY;
using json = nlohmann::json;
using ::testing::HasSubstr;

const char* const crs = "+proj=tmerc +lat_0=55 +lon_0=5 +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs";
constexpr double t0 = 1714557600;  // 2024-05-01T10:00:00Z

const geo::LocalFrame& frame() {
    static const geo::LocalFrame f = geo::LocalFrame::from_user_crs(crs);
    return f;
}

std::string ring_of(std::initializer_list<XY> pts) {
    std::string ring;
    for (const XY& p : pts) {
        const LonLat q = frame().inverse(p);
        char b[96];
        std::snprintf(b, sizeof b, "%s[%.12f, %.12f]", ring.empty() ? "" : ", ", q.lon, q.lat);
        ring += b;
    }
    return "[" + ring + "]";
}

std::string rect_feature(double x0, double y0, double x1, double y1) {
    return R"({"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [)" +
           ring_of({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}) + "]}}";
}

/// A CSV track: from (x_from, y) to x_to at 5 m/s, SOG 9.72 kn, a fix every 10 s.
void write_track(const fs::path& path, const std::string& id, double x_from, double x_to, double y) {
    std::ofstream out(path);
    out << "id,time,lat,lon,heading,sog\n";
    const double sign = x_to > x_from ? 1 : -1;
    for (int i = 0; i <= 80; ++i) {
        const LonLat p = frame().inverse({x_from + sign * 50.0 * i, y});
        char row[160];
        std::snprintf(row, sizeof row, "%s,%.0f,%.10f,%.10f,%d,9.72\n", id.c_str(), t0 + 10.0 * i, p.lat, p.lon, sign > 0 ? 90 : 270);
        out << row;
    }
}

class AssessCli : public ::testing::Test {
protected:
    void SetUp() override {
        std::ofstream(m_dir.file("coast.geojson")) << R"({"type": "FeatureCollection", "features": [)" << rect_feature(-500, 0, 500, 400)
                                                    << ", " << rect_feature(-3100, 3000, -3000, 3100) << ", "
                                                    << rect_feature(3000, -3100, 3100, -3000) << "]}";
        std::ofstream(m_dir.file("ship.json")) << R"({"name": "box", "length": 60, "beam": 10, "a": 50, "b": 10, "c": 5, "d": 5,
                                                      "contour": [[50, -5], [50, 5], [-10, 5], [-10, -5]]})";
        fs::create_directories(m_dir.path() / "ex1");
        write_track(m_dir.path() / "ex1" / "A.csv", "A", -2000, 2000, -305);
        write_track(m_dir.path() / "ex1" / "B.csv", "B", 2000, -2000, -605);
        std::ofstream(m_dir.file("roles.json")) << R"({"tracks": [{"track": "A", "role": "trainee"}]})";
        const std::string area = ring_of({{0, -600}, {1000, -600}, {1000, -100}, {0, -100}});
        std::ofstream(m_dir.file("assessment.json")) << R"({"criteria": [
            {"id": "land-500", "kind": "land_clearance", "limit": 500, "penalty": 2, "per": "metre"},
            {"id": "speed-8", "kind": "speed_limit", "limit": 8, "penalty": 5, "per": "metre", "area": )"
                                                    << area << R"(, "area_name": "narrows"},
            {"id": "keep-out", "kind": "no_entry", "penalty": 0.5, "per": "second", "area": )"
                                                    << area << R"(},
            {"id": "cpa-926", "kind": "cpa", "limit": 926, "penalty": 10}]})";
    }

    test::Outcome check(const std::string& output, const std::string& assessment = "assessment.json") const {
        const std::string q = "'";
        return test::run_shoal("check --no-progress --coast " + q + m_dir.file("coast.geojson") + q + " --crs '" + crs + "' --ship " + q +
                                   m_dir.file("ship.json") + q + " --exercise-by folder --roles " + q + m_dir.file("roles.json") + q +
                                   " --assess " + q + m_dir.file(assessment) + q + " " + q + (m_dir.path() / "ex1").string() + q + " -o " +
                                   q + m_dir.file(output) + q,
                               m_dir.path() / "cache", m_dir.path() / "err.txt");
    }

    test::TempDir m_dir;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

double seconds(const json& iso) { return *track::parse_iso8601(iso.get<std::string>()) - t0; }

TEST_F(AssessCli, AColregCriterionAndAPassMarkInTheReportValidAgainstTheSchemas) {
    // A (trainee) east along y = -305, B (target) west along y = -605, both 5 m/s: within 2 nm
    // at about 30 s, B 4.6 degrees off A's bow, reciprocal courses: head-on (within 10 degrees),
    // CPA 300 m, under 926 m. Neither turns: A breaches rule 14 at the closest approach (400 s).
    std::ofstream(m_dir.file("colreg.json")) << R"({"pass_mark": 55, "criteria": [
        {"id": "cpa-926", "kind": "cpa", "limit": 926, "penalty": 10},
        {"id": "rules", "kind": "colreg", "penalty": 50, "head_on_deg": 10}]})";
    const test::Outcome r = check("colreg.geojson", "colreg.json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("rules: rule 14, head-on with B (give-way)"));
    EXPECT_THAT(r.out, HasSubstr("A kept her course (090) and speed (9.7 kn)"));
    EXPECT_THAT(r.out, HasSubstr("] A  penalty 60.00, 2 breaches: fail (pass mark 55.00)\n"));
    const json doc = json::parse(slurp(m_dir.file("colreg.geojson")));
    EXPECT_EQ(doc["shoal"]["pass_mark"], 55);
    ASSERT_EQ(doc["shoal"]["assessment"]["scores"].size(), 1u);
    EXPECT_EQ(doc["shoal"]["assessment"]["scores"][0]["penalty"], 60);
    EXPECT_EQ(doc["shoal"]["assessment"]["scores"][0]["passed"], false);
    std::vector<json> colreg;
    for (const json& f : doc["features"])
        if (f["properties"]["kind"] == "breach" && f["properties"]["criterion_kind"] == "colreg") colreg.push_back(f["properties"]);
    ASSERT_EQ(colreg.size(), 1u);
    EXPECT_EQ(colreg[0]["rule"], "14");
    EXPECT_EQ(colreg[0]["other_track"], "B");
    EXPECT_NEAR(seconds(colreg[0]["worst"]), 400, 1);
    EXPECT_THAT(colreg[0]["asked"].get<std::string>(), HasSubstr("both ships alter course to starboard"));
    // Both files match their schemas.
    const std::string schemas = std::string(SHOAL_TEST_DATA) + "../../schemas/";
    for (const auto& [file, schema] : {std::pair{m_dir.file("colreg.geojson"), schemas + "report.schema.json"},
                                       std::pair{m_dir.file("colreg.json"), schemas + "assessment.schema.json"}}) {
        const std::string cmd = "/usr/bin/python3 -c \"import json,sys,jsonschema; jsonschema.validate(json.load(open(sys.argv[1])), "
                                "json.load(open(sys.argv[2])))\" '" + file + "' '" + schema + "' 2>&1";
        FILE* pipe = ::popen(cmd.c_str(), "r");
        ASSERT_TRUE(pipe);
        std::string out;
        char buf[512];
        while (std::fgets(buf, sizeof buf, pipe)) out += buf;
        EXPECT_EQ(::pclose(pipe), 0) << file << ": " << out;
    }
}

TEST_F(AssessCli, ScoresAndBreachesOnStdoutAndInTheGeoJson) {
    const std::string before = slurp(m_dir.file("assessment.json"));
    const test::Outcome r = check("report.geojson");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(m_dir.file("assessment.json")), before) << "the assessment file is an input";
    const std::string exercise = (m_dir.path() / "ex1").string();
    // stdout: the summary line, one line per score, one per breach.
    EXPECT_THAT(r.out, HasSubstr("assessment: 4 criteria, 1 trainees scored, 4 breaches\n"));
    // (The land clearance is the hull's: 300 m to within millimetres, so its penalty 400 to within a few hundredths.)
    EXPECT_THAT(r.out, HasSubstr("  score  [" + exercise + "] A  penalty 518."));
    EXPECT_THAT(r.out, HasSubstr(", 4 breaches\n"));
    EXPECT_THAT(r.out, HasSubstr("  breach [" + exercise + "] A  land-500: clearance to land 300.0 m, under 500.0 m, 10:03:30Z-10:09:42Z (372 s); penalty 40"));
    EXPECT_THAT(r.out, HasSubstr("  breach [" + exercise + "] A  cpa-926: CPA to B 300.0 m, under 926.0 m, 10:05:12Z-10:08:08Z (175 s); penalty 10.00"));
    EXPECT_THAT(r.out, HasSubstr("  breach [" + exercise + "] A  speed-8: speed 9.72 kn over the limit of 8.00 kn in narrows, 10:06:40Z-10:10:00Z (200 s); penalty 8.60"));
    EXPECT_THAT(r.out, HasSubstr("  breach [" + exercise + "] A  keep-out: inside a no-entry area, 10:06:40Z-10:10:00Z (200 s); penalty 100.00"));

    const json doc = json::parse(slurp(m_dir.file("report.geojson")));
    const json& a = doc["shoal"]["assessment"];
    ASSERT_EQ(a["criteria"].size(), 4u);
    EXPECT_EQ(a["criteria"][1], (json{{"id", "speed-8"}, {"kind", "speed_limit"}, {"limit", 8.0}, {"unit", "kn"}, {"penalty", 5.0}, {"per", "metre"},
                                      {"area_name", "narrows"}}));
    EXPECT_TRUE(a["criteria"][0]["area_name"].is_null());
    ASSERT_EQ(a["scores"].size(), 1u);
    EXPECT_EQ(a["scores"][0]["exercise"], exercise);
    EXPECT_EQ(a["scores"][0]["track"], "A");
    EXPECT_EQ(a["scores"][0]["breaches"], 4);
    EXPECT_NEAR(a["scores"][0]["penalty"].get<double>(), 518.6, 0.1);
    EXPECT_EQ(doc["shoal"]["summary"]["breaches"], 4);
    EXPECT_EQ(doc["shoal"]["summary"]["trainees_scored"], 1);
    EXPECT_EQ(doc["shoal"]["assessment_file"], m_dir.file("assessment.json"));
    std::vector<json> breaches;
    for (const json& f : doc["features"])
        if (f["properties"]["kind"] == "breach") breaches.push_back(f);
    ASSERT_EQ(breaches.size(), 4u);
    const json& land = breaches[0]["properties"];
    EXPECT_EQ(land["criterion"], "land-500");
    EXPECT_EQ(land["criterion_kind"], "land_clearance");
    EXPECT_NEAR(seconds(land["start"]), 210, 0.1);
    EXPECT_NEAR(seconds(land["end"]), 582, 0.1);
    EXPECT_NEAR(land["value"].get<double>(), 300, 0.05);
    EXPECT_EQ(land["unit"], "m");
    EXPECT_TRUE(land["other_track"].is_null());
    const json& cpa = breaches[1]["properties"];
    EXPECT_EQ(cpa["criterion"], "cpa-926");
    EXPECT_EQ(cpa["other_track"], "B");
    EXPECT_NEAR(seconds(cpa["worst"]), 400, 1e-3);
    EXPECT_NEAR(cpa["duration_s"].get<double>(), 2 * 87.606, 1e-3);
    // The point: the trainee at the worst moment (x = 0 at t0 + 400).
    const XY at = frame().forward({breaches[1]["geometry"]["coordinates"][0].get<double>(), breaches[1]["geometry"]["coordinates"][1].get<double>()});
    EXPECT_NEAR(at.x, 0, 0.05);
    EXPECT_NEAR(at.y, -305, 0.05);
    EXPECT_EQ(breaches[2]["properties"]["criterion"], "speed-8");
    EXPECT_EQ(breaches[3]["properties"]["criterion"], "keep-out");
    EXPECT_NEAR(breaches[3]["properties"]["value"].get<double>(), 200, 1e-3);

    // The report matches its schema (Debian's python3-jsonschema).
    const std::string schema = std::string(SHOAL_TEST_DATA) + "../../schemas/report.schema.json";
    const std::string cmd = "/usr/bin/python3 -c \"import json,sys,jsonschema; jsonschema.validate(json.load(open(sys.argv[1])), "
                            "json.load(open(sys.argv[2])))\" '" +
                            m_dir.file("report.geojson") + "' '" + schema + "' 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    ASSERT_TRUE(pipe);
    std::string out;
    char buf[512];
    while (std::fgets(buf, sizeof buf, pipe)) out += buf;
    EXPECT_EQ(::pclose(pipe), 0) << out;
}

TEST_F(AssessCli, TheGeoPackageHasABreachesLayerAScoresTableAndTheirStyleAndProject) {
    const test::Outcome r = check("report.gpkg");
    ASSERT_EQ(r.status, 0) << r.err;
    GDALAllRegister();
    const GDALDatasetUniquePtr ds(GDALDataset::Open(m_dir.file("report.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    ASSERT_TRUE(ds);
    OGRLayer* breaches = ds->GetLayerByName("breaches");
    ASSERT_TRUE(breaches);
    EXPECT_EQ(wkbFlatten(breaches->GetGeomType()), wkbPoint);
    EXPECT_EQ(breaches->GetFeatureCount(), 4);
    const OGRFeatureDefn* d = breaches->GetLayerDefn();
    for (const char* f : {"start", "end", "worst"}) {
        const int i = d->GetFieldIndex(f);
        ASSERT_GE(i, 0) << f;
        EXPECT_EQ(d->GetFieldDefn(i)->GetType(), OFTDateTime) << f;
    }
    breaches->ResetReading();
    const OGRFeatureUniquePtr first(breaches->GetNextFeature());
    EXPECT_STREQ(first->GetFieldAsString("criterion"), "land-500");
    EXPECT_NEAR(first->GetFieldAsDouble("penalty"), 400, 0.1);
    OGRLayer* scores = ds->GetLayerByName("scores");
    ASSERT_TRUE(scores);
    EXPECT_EQ(scores->GetGeomType(), wkbNone);
    ASSERT_EQ(scores->GetFeatureCount(), 1);
    scores->ResetReading();
    const OGRFeatureUniquePtr s(scores->GetNextFeature());
    EXPECT_STREQ(s->GetFieldAsString("track"), "A");
    EXPECT_NEAR(s->GetFieldAsDouble("penalty"), 518.6, 0.1);
    EXPECT_EQ(s->GetFieldAsInteger("breaches"), 4);
    // The layer's style in layer_styles, and the layer in the stored QGIS project.
    OGRLayer* styled = ds->ExecuteSQL("SELECT styleQML FROM layer_styles WHERE f_table_name = 'breaches'", nullptr, nullptr);
    ASSERT_TRUE(styled);
    ASSERT_EQ(styled->GetFeatureCount(), 1);
    const OGRFeatureUniquePtr style(styled->GetNextFeature());
    EXPECT_THAT(style->GetFieldAsString(0), HasSubstr("criterion_kind"));
    ds->ReleaseResultSet(styled);
    // The stored project (a .qgz, hex, in qgis_projects) read with Python's sqlite3 and zipfile.
    const std::string cmd = "/usr/bin/python3 -c \"import sqlite3,zipfile,io,sys; c=sqlite3.connect(sys.argv[1]).execute("
                            "'select content from qgis_projects').fetchone()[0]; z=zipfile.ZipFile(io.BytesIO(bytes.fromhex(c))); "
                            "print(z.read(z.namelist()[0]).decode())\" '" +
                            m_dir.file("report.gpkg") + "' 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    ASSERT_TRUE(pipe);
    std::string project;
    char buf[4096];
    for (std::size_t k; (k = std::fread(buf, 1, sizeof buf, pipe)) > 0;) project.append(buf, k);
    EXPECT_EQ(::pclose(pipe), 0) << project;
    EXPECT_THAT(project, HasSubstr("layername=breaches"));
    // In exercise mode the breaches are in the exercise's group (the first), filtered to it.
    EXPECT_THAT(project, HasSubstr("layer-tree-layer id=\"shoal_breaches_1\""));
    EXPECT_THAT(project, HasSubstr("layername=breaches|subset=&quot;exercise&quot; = '"));
}

TEST_F(AssessCli, ABadAssessmentFileIsRefusedBeforeAnyWork) {
    std::ofstream(m_dir.file("bad.json")) << R"({"criteria": [{"id": "x", "kind": "cpa", "limit": "far", "penalty": 1}]})";
    const test::Outcome r = check("report.geojson", "bad.json");
    EXPECT_EQ(r.status, 2);
    EXPECT_THAT(r.err, HasSubstr("assessment file '" + m_dir.file("bad.json") + "': criteria[0] (id 'x'): \"limit\" must be a number (m)"));
    EXPECT_FALSE(fs::exists(m_dir.file("report.geojson")));
    // The assessment file is an input: -o onto it is refused, the file kept.
    const std::string before = slurp(m_dir.file("assessment.json"));
    const test::Outcome same = check("assessment.json");
    EXPECT_EQ(same.status, 2);
    EXPECT_EQ(slurp(m_dir.file("assessment.json")), before);
}

}  // namespace
}  // namespace shoal
