// The QGIS project's XML through the one markup escaper (report/markup.hpp): names a run can
// carry (a report file name, exercise names from a column) read back whole from the .qgs by
// GDAL's XML parser, and a name the XML cannot hold (a control character, invalid UTF-8) no
// longer makes the project ill-formed.
#include <gtest/gtest.h>

#include <cpl_conv.h>
#include <cpl_minixml.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "report/qgis/qgis_project.hpp"
#include "report/qgis/qgis_styles.hpp"
#include "temp_dir.hpp"
#include "xml_support.hpp"

namespace shoal::report {
namespace {

/// The first element named `name` below `n` (depth first), or null.
const CPLXMLNode* find(const CPLXMLNode* n, const std::string& name) {
    for (; n; n = n->psNext) {
        if (n->eType == CXT_Element && name == n->pszValue) return n;
        if (const CPLXMLNode* f = find(n->psChild, name)) return f;
    }
    return nullptr;
}

/// Every "name" attribute of the elements named `element` below `n`, in document order.
void names_of(const CPLXMLNode* n, const std::string& element, std::vector<std::string>& out) {
    for (; n; n = n->psNext) {
        if (n->eType == CXT_Element && element == n->pszValue) out.push_back(test::attr(n, "name"));
        if (n->eType == CXT_Element) names_of(n->psChild, element, out);
    }
}

TEST(QgisProject, NamesWithMarkupReadBackWholeAndTheForbiddenOnesLeaveItWellFormed) {
    ProjectView view;
    view.x0 = -1.5, view.y0 = 50.6, view.x1 = -1.1, view.y1 = 50.9;
    view.exercises = {"Ann's <run> & \"B\"", std::string("bell\x07") + "end", std::string("bad\xFF") + "byte"};
    const std::vector<ProjectLayer> layers = {{"events", "Point", "./r&d's.geojson"}, {"tracks", "Line", "./r&d's.tracks.geojson"}};
    const std::string qgs = qgis_project_xml(layers, "r&d's <report>", view);

    std::string error;
    const test::XmlPtr doc = test::parse_xml(qgs, &error);
    ASSERT_TRUE(doc) << "the project is not well-formed XML: " << error;

    const CPLXMLNode* title = find(doc.get(), "title");
    ASSERT_TRUE(title && title->psChild);
    EXPECT_EQ(std::string(title->psChild->pszValue), "shoal report r&d's <report>");

    std::vector<std::string> groups;
    names_of(doc.get(), "layer-tree-group", groups);
    // The root group has no name; then the exclusive group and one group per exercise.
    const std::vector<std::string> want = {"", "exercises", "exercise Ann's <run> & \"B\"", "exercise bell end",
                                           "exercise bad\xEF\xBF\xBD" "byte"};
    EXPECT_EQ(groups, want);

    // An exercise's subset keeps its quotes as QGIS writes them: `'` stays (attributes are all
    // in double quotes), `"` is &quot;.
    EXPECT_NE(qgs.find("|subset=&quot;exercise&quot; = 'Ann''s &lt;run&gt; &amp; &quot;B&quot;'"), std::string::npos);
    EXPECT_EQ(qgs.find("&apos;"), std::string::npos);
}

/// The text between `open` and `close` in `s` (after `from`), or "".
std::string between(const std::string& s, const std::string& open, const std::string& close, std::size_t from = 0) {
    const std::size_t a = s.find(open, from);
    if (a == std::string::npos) return "";
    const std::size_t b = s.find(close, a + open.size());
    return b == std::string::npos ? "" : s.substr(a + open.size(), b - a - open.size());
}

/// What GDAL's OSR says of EPSG:`epsg`, in the project's <spatialrefsys> (the writer's own
/// code before it went without GDAL: the independent answer).
std::string osr_srs_xml(int epsg) {
    OGRSpatialReference s;
    s.importFromEPSG(epsg);
    char* proj4 = nullptr;
    s.exportToProj4(&proj4);
    const std::string p4 = proj4 ? proj4 : "";
    CPLFree(proj4);
    const char* name = s.GetName();
    return "<spatialrefsys><proj4>" + p4 + "</proj4><srid>" + std::to_string(epsg) + "</srid><authid>EPSG:" + std::to_string(epsg) +
           "</authid><description>" + (name ? name : "") + "</description><geographicflag>" + (s.IsGeographic() ? "true" : "false") +
           "</geographicflag></spatialrefsys>";
}

/// The map's extent for the box (lon, lat) in EPSG:`epsg` through OGR's coordinate transformation,
/// as the writer computed it with GDAL: the box's edges sampled, 5 % and at least 500 m added.
std::string ogr_extent(int epsg, double x0, double y0, double x1, double y1) {
    OGRSpatialReference wgs, utm;
    wgs.importFromEPSG(4326);
    wgs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    utm.importFromEPSG(epsg);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&wgs, &utm));
    double e0 = INFINITY, n0 = INFINITY, e1 = -INFINITY, n1 = -INFINITY;
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j <= 10; ++j) {
            if (i != 0 && i != 10 && j != 0 && j != 10) continue;
            double e = x0 + (x1 - x0) * i / 10, n = y0 + (y1 - y0) * j / 10;
            if (!ct->Transform(1, &e, &n)) continue;
            e0 = std::min(e0, e), n0 = std::min(n0, n), e1 = std::max(e1, e), n1 = std::max(n1, n);
        }
    const double pad = std::max({(e1 - e0) * 0.05, (n1 - n0) * 0.05, 500.0});
    char ext[256];
    std::snprintf(ext, sizeof ext, "<xmin>%.1f</xmin><ymin>%.1f</ymin><xmax>%.1f</xmax><ymax>%.1f</ymax>", e0 - pad, n0 - pad, e1 + pad, n1 + pad);
    return ext;
}

// The project's coordinate systems and its map extent, made without GDAL, are what GDAL's OSR
// and OGR's transformation make: every UTM zone north and south, and WGS 84 for a world chart.
TEST(QgisProject, SpatialReferencesAreWhatOsrSaysOfTheirEpsgCodes) {
    std::mt19937_64 rng(20261207);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int zones = 0;
    for (int zone = 1; zone <= 60; ++zone)
        for (const bool south : {false, true})
            for (int k = 0; k < 3; ++k) {
                // A chart within the zone, up to a few degrees across (the centre decides the zone).
                const double lon_c = zone * 6.0 - 183.0 + 5.8 * (u(rng) - 0.5);
                const double lat_c = (south ? -1 : 1) * (0.01 + 80 * u(rng));
                const double w = 0.01 + 6 * u(rng), h = 0.01 + 4 * u(rng);
                ProjectView view;
                view.chart.extend(geo::XY{lon_c - w / 2, lat_c - h / 2});
                view.chart.extend(geo::XY{lon_c + w / 2, lat_c + h / 2});
                const std::string qgs = qgis_project_xml({}, "r", view);
                const int epsg = (south ? 32700 : 32600) + zone;
                ASSERT_EQ(between(qgs, "<projectCrs>", "</projectCrs>"), osr_srs_xml(epsg)) << "zone " << zone << (south ? "S" : "N");
                EXPECT_EQ(between(qgs, "<destinationsrs>", "</destinationsrs>"), osr_srs_xml(epsg));
                ASSERT_EQ(between(qgs, "<extent>", "</extent>"),
                          ogr_extent(epsg, lon_c - w / 2, lat_c - h / 2, lon_c + w / 2, lat_c + h / 2))
                    << "zone " << zone << (south ? "S" : "N") << " chart " << lon_c << ", " << lat_c << " (" << w << " x " << h << ")";
                ++zones;
            }
    EXPECT_EQ(zones, 360);
    // A chart wider than four zones: EPSG:4326, each layer's <srs> too; 5 % of the widest side
    // (17 degrees) around it, no further than the world.
    ProjectView world;
    world.chart.extend(geo::XY{-170, -60});
    world.chart.extend(geo::XY{170, 70});
    const std::string qgs = qgis_project_xml({{"events", "Point", "./r.geojson"}}, "r", world);
    EXPECT_EQ(between(qgs, "<projectCrs>", "</projectCrs>"), osr_srs_xml(4326));
    EXPECT_EQ(between(qgs, "<srs>", "</srs>"), osr_srs_xml(4326));
    EXPECT_EQ(between(qgs, "<extent>", "</extent>"), "<xmin>-180.000000</xmin><ymin>-77.000000</ymin><xmax>180.000000</xmax><ymax>87.000000</ymax>");
}

/// Whether GDAL finds `member` in the zip at `path` and its first 4 KiB hold shoal's mark: what
/// is_shoal_qgz said when it read the zip through GDAL's /vsizip/ (the independent answer).
bool gdal_says_shoal(const std::string& path, const std::string& member) {
    VSILFILE* f = VSIFOpenL(("/vsizip/{" + path + "}/" + member).c_str(), "rb");
    if (!f) return false;
    std::string head(4096, '\0');
    head.resize(VSIFReadL(head.data(), 1, head.size(), f));
    VSIFCloseL(f);
    return head.find(sidecar_mark) != std::string::npos;
}

/// A zip of `members` (name, content) written by GDAL, deflated or stored.
std::string gdal_zip_of(const std::vector<std::pair<std::string, std::string>>& members, bool compressed) {
    const std::string zip = "/vsimem/qgz_test_many.zip";
    void* z = CPLCreateZip(zip.c_str(), nullptr);
    const char* options[] = {compressed ? nullptr : "COMPRESSED=NO", nullptr};  // deflated: GDAL's default
    for (const auto& [name, content] : members) {
        EXPECT_EQ(CPLCreateFileInZip(z, name.c_str(), const_cast<char**>(options)), CE_None);
        EXPECT_EQ(CPLWriteFileInZip(z, content.data(), static_cast<int>(content.size())), CE_None);
        EXPECT_EQ(CPLCloseFileInZip(z), CE_None);
    }
    EXPECT_EQ(CPLCloseZip(z), CE_None);
    vsi_l_offset n = 0;
    GByte* bytes = VSIGetMemFileBuffer(zip.c_str(), &n, FALSE);
    std::string out(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(n));
    VSIUnlink(zip.c_str());
    return out;
}

/// `qgs` zipped as `member` by GDAL's own zip writer with its defaults (what the report's .qgz
/// was before it went without GDAL).
std::string gdal_zip(const std::string& member, const std::string& qgs) { return gdal_zip_of({{member, qgs}}, true); }

// The .qgz, made with zlib, is the zip GDAL's writer made, byte for byte: names in ASCII, in
// CP437 and beyond it (the Unicode path field), contents empty, text, incompressible and large;
// GDAL reads the project back from it. is_shoal_qgz, reading the zip's directory with zlib, says
// what GDAL's /vsizip/ says, on shoal's zips, other zips and damaged ones.
TEST(QgisProject, TheQgzIsTheZipGdalWrites) {
    CPLPushErrorHandler(CPLQuietErrorHandler);  // GDAL warns of characters CP437 lacks
    std::mt19937_64 rng(7);
    const std::string mark(sidecar_mark);
    std::string xml = "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n" + mark + "\n<qgis>";
    while (xml.size() < 200000) xml += "<layer id=\"shoal_" + std::to_string(rng() % 1000) + "\" source=\"./r.geojson\"/>\n";
    std::string noise(300000, '\0');
    for (char& c : noise) c = static_cast<char>(rng());
    const std::vector<std::string> contents = {"", "x", mark, xml, noise, std::string(3 << 20, 'a') + xml, std::string(5000, ' ') + mark};
    const std::vector<std::string> members = {"r.qgs", "Hämeenlinna_Ørsted_ÿ.qgs", "łódź 港 report.qgs", std::string("bad\xFF\xFEutf8.qgs"),
                                              std::string(300, 'n') + ".qgs"};
    test::TempDir dir;
    const std::string path = dir.file("t.qgz");
    const auto agree = [&](const std::string& bytes, const std::string& member, const std::string& what) {
        std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
        EXPECT_EQ(is_shoal_qgz(path, member), gdal_says_shoal(path, member)) << what << ", member " << member;
    };
    int shoals = 0;
    for (const std::string& member : members)
        for (const std::string& content : contents) {
            const std::string ours = qgz_of(member, content);
            ASSERT_EQ(ours, gdal_zip(member, content)) << member << ", " << content.size() << " bytes";
            agree(ours, member, "shoal's zip of " + std::to_string(content.size()) + " bytes");
            agree(ours, member + "x", "another member's name");
            std::ofstream(path, std::ios::binary | std::ios::trunc) << ours;
            shoals += is_shoal_qgz(path, member);
        }
    EXPECT_EQ(shoals, 2 * 5);  // the mark in the first 4 KiB (`mark` and `xml`), under each of the five names
    // Zips that shoal did not write: the project second of three members, stored, or both.
    for (const bool compressed : {true, false})
        agree(gdal_zip_of({{"a.txt", "hello"}, {"r.qgs", xml}, {"b/c.qgs", mark}}, compressed), "r.qgs", compressed ? "deflated, second" : "stored, second");
    agree(gdal_zip_of({{"r.qgs", "<qgis>QGIS saved over it</qgis>"}}, true), "r.qgs", "QGIS's own project");
    // A directory entry r.qgs pointing at the local header of another member, which holds a
    // shoal project: no such member for GDAL (the names differ), nor for shoal.
    {
        std::string z = gdal_zip_of({{"backup/r_old.qgs", xml}, {"r.qgs", noise}}, true);  // r.qgs longer, packed, than the other
        const std::size_t second = z.find(std::string_view("PK\x01\x02", 4), z.find(std::string_view("PK\x01\x02", 4)) + 4);
        ASSERT_NE(second, std::string::npos);
        z.replace(second + 42, 4, std::string(4, '\0'));  // its local header: the first member's
        agree(z, "r.qgs", "a directory entry pointing at another member");
        std::ofstream(path, std::ios::binary | std::ios::trunc) << z;
        EXPECT_FALSE(is_shoal_qgz(path, "r.qgs"));
    }
    // Damaged: cut short (no directory), its data spoilt, junk, empty.
    const std::string whole = qgz_of("r.qgs", xml);
    std::string spoilt = whole;
    for (std::size_t k = 60; k < 2000; ++k) spoilt[k] = static_cast<char>(rng());
    for (const std::string& bad : {whole.substr(0, 40), whole.substr(0, whole.size() - 30), spoilt, std::string(9000, 'P'), std::string()})
        agree(bad, "r.qgs", "damaged, " + std::to_string(bad.size()) + " bytes");
    // GDAL reads the project back, under its own name.
    std::ofstream(path, std::ios::binary | std::ios::trunc) << qgz_of("Hämeenlinna.qgs", xml);
    VSILFILE* f = VSIFOpenL(("/vsizip/{" + path + "}/Hämeenlinna.qgs").c_str(), "rb");
    ASSERT_NE(f, nullptr);
    std::string back(xml.size() + 10, '\0');
    back.resize(VSIFReadL(back.data(), 1, back.size(), f));
    VSIFCloseL(f);
    EXPECT_EQ(back, xml);
    EXPECT_TRUE(is_shoal_qgz(path, "Hämeenlinna.qgs"));
    EXPECT_FALSE(is_shoal_qgz(dir.path().string(), "r.qgs"));  // a folder
    CPLPopErrorHandler();
}

}  // namespace
}  // namespace shoal::report
