// The SVG picture of an audit, drawn from a real run (two vessels in the Solent, one of them
// sailing across the Isle of Wight) and read back with GDAL's XML parser: well-formed SVG,
// one marker per event, the events' times as text, a scale bar that measures the hull right,
// an arrow to true north where grid north differs, one zoomed panel per grounding; an empty
// audit still gives a picture.

#include <gtest/gtest.h>

#include <cpl_error.h>
#include <cpl_minixml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "audit/audit.hpp"
#include "grid/grid_cache.hpp"
#include "hull/hull.hpp"
#include "report/plot.hpp"
#include "report/report.hpp"
#include "test_support.hpp"
#include "util/error.hpp"

namespace shoal::report {
namespace {

constexpr const char* svg_ns = "http://www.w3.org/2000/svg";

struct XmlDeleter {
    void operator()(CPLXMLNode* n) const noexcept { CPLDestroyXMLNode(n); }
};
using XmlPtr = std::unique_ptr<CPLXMLNode, XmlDeleter>;

/// The parsed document, or null (with GDAL's message in `error`) when it is not well-formed.
XmlPtr parse(const std::string& svg, std::string* error) {
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    XmlPtr doc(CPLParseXMLString(svg.c_str()));
    CPLPopErrorHandler();
    if (!doc && error) *error = CPLGetLastErrorMsg();
    return doc;
}

const CPLXMLNode* root_element(const CPLXMLNode* doc) {
    for (const CPLXMLNode* n = doc; n; n = n->psNext)
        if (n->eType == CXT_Element && n->pszValue[0] != '?') return n;
    return nullptr;
}

std::string attr(const CPLXMLNode* n, const char* name) {
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Attribute && std::string(c->pszValue) == name && c->psChild) return c->psChild->pszValue;
    return {};
}

/// The text directly inside an element.
std::string inner_text(const CPLXMLNode* n) {
    std::string s;
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Text) s += c->pszValue;
    return s;
}

/// Every element under `n` (and `n`), depth first.
void each_element(const CPLXMLNode* n, const std::function<void(const CPLXMLNode*)>& f) {
    if (n->eType != CXT_Element) return;
    f(n);
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext) each_element(c, f);
}

std::vector<const CPLXMLNode*> with_class(const CPLXMLNode* n, const std::string& cls) {
    std::vector<const CPLXMLNode*> out;
    each_element(n, [&](const CPLXMLNode* e) {
        if (attr(e, "class") == cls) out.push_back(e);
    });
    return out;
}

std::vector<std::string> texts(const CPLXMLNode* n) {
    std::vector<std::string> out;
    each_element(n, [&](const CPLXMLNode* e) {
        if (std::string(e->pszValue) == "text") out.push_back(inner_text(e));
    });
    return out;
}

bool has_text_containing(const CPLXMLNode* n, const std::string& needle) {
    for (const auto& t : texts(n))
        if (t.find(needle) != std::string::npos) return true;
    return false;
}

/// Two vessels in the Solent, as in the CLI tests: A sails south across the Isle of Wight (it
/// grounds), B stays in open water east of the island.
std::string solent_tracks(const test::TempDir& dir) {
    const std::string path = dir.file("solent-tracks.csv");
    std::ofstream out(path);
    out << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
    char row[160];
    for (int i = 0; i <= 20; ++i) {
        std::snprintf(row, sizeof row, "111111111,2024-05-01T10:%02d:00Z,%.4f,-1.3000,11.9,180,511\n", i, 50.78 - 0.01 * i);
        out << row;
    }
    for (int i = 0; i <= 10; ++i) {
        std::snprintf(row, sizeof row, "222222222,2024-05-01T10:%02d:00Z,50.7400,%.4f,8,90,90\n", i, -1.05 + 0.002 * i);
        out << row;
    }
    return path;
}

grid::CoastGrid solent_grid(const std::string& crs = "") {
    grid::BuildRequest request;
    request.cell_m = 400;
    request.crs = crs;
    std::vector<std::string> warnings;
    return grid::build_grid({test::data_path("coast/uk_solent_land.geojson")}, request, &warnings);
}

audit::AuditResult solent_audit(const grid::CoastGrid& g, const test::TempDir& dir) {
    audit::AuditOptions options;
    options.jobs = 1;
    return audit::run_audit({solent_tracks(dir)}, g, hull::Hull::from_dimensions({50, 10, 5, 5}), "--dims 50,10,5,5", options);
}

/// "translate(x,y) rotate(a)" -> a.
double rotation_of(const CPLXMLNode* n) {
    const std::string t = attr(n, "transform");
    const auto at = t.find("rotate(");
    return at == std::string::npos ? NAN : std::stod(t.substr(at + 7));
}

const CPLXMLNode* panel(const CPLXMLNode* svg, const std::string& id) {
    const CPLXMLNode* found = nullptr;
    each_element(svg, [&](const CPLXMLNode* e) {
        if (attr(e, "id") == id) found = e;
    });
    return found;
}

TEST(PlotSvg, SolentRunDrawsEveryEventItsTimeAndOneZoomedPanelPerGrounding) {
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid();
    const audit::AuditResult r = solent_audit(g, dir);
    ASSERT_GE(r.groundings, 1u) << "vessel A crosses the Isle of Wight";

    const std::string svg = plot_svg(r, g);
    std::string error;
    const XmlPtr doc = parse(svg, &error);
    ASSERT_TRUE(doc) << "not well-formed XML: " << error;
    const CPLXMLNode* root = root_element(doc.get());
    ASSERT_NE(root, nullptr);
    EXPECT_STREQ(root->pszValue, "svg");
    EXPECT_EQ(attr(root, "xmlns"), svg_ns);
    EXPECT_EQ(attr(root, "version"), "1.1");
    EXPECT_FALSE(attr(root, "viewBox").empty());

    EXPECT_EQ(with_class(root, "panel overview").size(), 1u);
    EXPECT_EQ(with_class(root, "event grounding").size(), r.groundings);
    EXPECT_EQ(with_class(root, "event close_pass").size(), r.close_passes);
    EXPECT_EQ(with_class(root, "panel zoom").size(), r.groundings);
    EXPECT_EQ(with_class(root, "scale-bar").size(), 1 + r.groundings) << "one per panel";
    EXPECT_EQ(with_class(root, "north-arrow").size(), 1 + r.groundings) << "one per panel";
    EXPECT_FALSE(with_class(root, "coastline").empty());
    EXPECT_FALSE(with_class(root, "land").empty());
    EXPECT_EQ(with_class(root, "legend").size(), 1u);
    for (const auto& t : r.tracks)
        for (const auto& e : t.events) {
            const std::string hhmmss = iso_time(e.start_s).substr(11, 8) + "Z";
            EXPECT_TRUE(has_text_containing(root, hhmmss)) << "time of the " << audit::to_string(e.kind) << " of " << t.summary.id;
        }
    // Every panel draws inside its own clip path, and every clip path it names exists.
    for (const char* cls : {"panel overview", "panel zoom"})
        for (const CPLXMLNode* p : with_class(root, cls)) {
            const std::string id = attr(p, "id");
            bool clipped = false, defined = false;
            each_element(p, [&](const CPLXMLNode* e) {
                if (attr(e, "clip-path") == "url(#clip-" + id + ")") clipped = true;
                if (std::string(e->pszValue) == "clipPath" && attr(e, "id") == "clip-" + id) defined = true;
            });
            EXPECT_TRUE(clipped && defined) << id;
        }
    EXPECT_TRUE(has_text_containing(root, "111111111")) << "the grounded track's id";
}

TEST(PlotSvg, ArrowPointsToTrueNorthAndScaleBarMeasuresTheShipInAFrameWithConvergenceAndScale) {
    // A transverse Mercator 4.3 degrees east of the Solent with scale 0.8: grid north is about
    // 3.3 degrees off true north there and a local metre is 0.8 true metres.
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid("+proj=tmerc +lat_0=0 +lon_0=3 +k=0.8 +x_0=500000 +y_0=0 +datum=WGS84 +units=m +no_defs");
    const audit::AuditResult r = solent_audit(g, dir);
    ASSERT_GE(r.groundings, 1u);
    const audit::Event* first = nullptr;
    for (const auto& t : r.tracks)
        for (const auto& e : t.events)
            if (!first && e.kind == audit::EventKind::grounding) first = &e;
    ASSERT_NE(first, nullptr);

    const XmlPtr doc = parse(plot_svg(r, g), nullptr);
    ASSERT_TRUE(doc);
    const CPLXMLNode* zoom = panel(root_element(doc.get()), "zoom-1");
    ASSERT_NE(zoom, nullptr);

    // True north from two points projected straight through the frame (page y is down, so the
    // arrow turns clockwise by the angle from local +y to local north).
    const geo::XY a = g.frame().forward(first->point);
    const geo::XY b = g.frame().forward({first->point.lon, first->point.lat + 1e-4});
    const double expected_deg = std::atan2(b.x - a.x, b.y - a.y) * 180 / std::numbers::pi;
    EXPECT_GT(std::fabs(expected_deg), 2.5) << "the test needs a frame whose grid north is well off true north";
    const auto arrows = with_class(zoom, "north-arrow");
    ASSERT_EQ(arrows.size(), 1u);
    EXPECT_NEAR(rotation_of(arrows[0]), expected_deg, 0.05);

    // The scale bar in true metres against the hull footprint (60 m long) drawn in the same panel.
    const auto hulls = with_class(zoom, "hull grounding");
    ASSERT_FALSE(hulls.empty());
    std::vector<geo::XY> pts;
    {
        const std::string list = attr(hulls.back(), "points");  // the event's own hull is drawn last
        double x = 0, y = 0;
        int used = 0;
        for (const char* p = list.c_str(); std::sscanf(p, "%lf,%lf%n", &x, &y, &used) == 2; p += used) pts.push_back({x, y});
    }
    double hull_px = 0;
    for (const auto& p : pts)
        for (const auto& q : pts) hull_px = std::max(hull_px, geo::distance(p, q));
    const auto bars = with_class(zoom, "bar");
    const auto captions = with_class(zoom, "caption");
    ASSERT_EQ(bars.size(), 1u);
    ASSERT_EQ(captions.size(), 1u);
    const double bar_px = std::stod(attr(bars[0], "width"));
    const std::string caption = inner_text(captions[0]);
    double length = std::stod(caption);
    if (caption.find("km") != std::string::npos) length *= 1000;
    EXPECT_NEAR(bar_px / length, hull_px / 60.0, 0.03 * hull_px / 60.0) << caption << " is " << bar_px << " px; the hull " << hull_px << " px";
}

TEST(PlotSvg, EmptyAuditStillDrawsTheOverviewOfTheChart) {
    const grid::CoastGrid g = solent_grid();
    const std::string svg = plot_svg(audit::AuditResult{}, g, PlotOptions{12, 800});
    std::string error;
    const XmlPtr doc = parse(svg, &error);
    ASSERT_TRUE(doc) << error;
    const CPLXMLNode* root = root_element(doc.get());
    EXPECT_EQ(attr(root, "xmlns"), svg_ns);
    EXPECT_EQ(attr(root, "width"), "800");
    EXPECT_EQ(with_class(root, "panel overview").size(), 1u);
    EXPECT_EQ(with_class(root, "panel zoom").size(), 0u);
    EXPECT_EQ(with_class(root, "event grounding").size(), 0u);
    EXPECT_EQ(with_class(root, "scale-bar").size(), 1u);
    EXPECT_EQ(with_class(root, "north-arrow").size(), 1u);
    EXPECT_FALSE(with_class(root, "coastline").empty()) << "the whole chart is in view";
    EXPECT_TRUE(has_text_containing(root, "0 tracks"));
}

TEST(PlotSvg, ZoomedPanelsStopAtTheLimitAndTheRestAreCounted) {
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid();
    const audit::AuditResult r = solent_audit(g, dir);
    ASSERT_GE(r.groundings, 1u);
    const XmlPtr doc = parse(plot_svg(r, g, PlotOptions{0, 1200}), nullptr);
    ASSERT_TRUE(doc);
    const CPLXMLNode* root = root_element(doc.get());
    EXPECT_EQ(with_class(root, "panel zoom").size(), 0u);
    EXPECT_EQ(with_class(root, "event grounding").size(), r.groundings) << "the overview still marks them all";
    const std::string note = std::to_string(r.groundings) + (r.groundings == 1 ? " more grounding not drawn" : " more groundings not drawn");
    EXPECT_TRUE(has_text_containing(root, note)) << note;
}

TEST(PlotSvg, TextFromTheDataIsEscapedAndBadUtf8Replaced) {
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid();
    audit::AuditResult r = solent_audit(g, dir);
    ASSERT_FALSE(r.tracks.empty());
    for (auto& t : r.tracks)
        if (t.summary.groundings > 0) t.summary.id = "A&B <x> \"q\" 'z' \xff\x01";
    const std::string svg = plot_svg(r, g);
    EXPECT_NE(svg.find("A&amp;B &lt;x&gt; &quot;q&quot; &apos;z&apos; \xEF\xBF\xBD "), std::string::npos);
    std::string error;
    const XmlPtr doc = parse(svg, &error);
    ASSERT_TRUE(doc) << error;
    EXPECT_TRUE(has_text_containing(root_element(doc.get()), "A&B <x>"));
}

TEST(PlotSvg, WritesTheFileAndRefusesANonsenseWidth) {
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid();
    const std::string path = dir.file("plot.svg");
    write_plot_svg(path, audit::AuditResult{}, g);
    const auto bytes = test::read_bytes(path);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), plot_svg(audit::AuditResult{}, g));
    EXPECT_THROW(plot_svg(audit::AuditResult{}, g, PlotOptions{12, 100}), UsageError);
    EXPECT_THROW(plot_svg(audit::AuditResult{}, g, PlotOptions{12, NAN}), UsageError);
}

}  // namespace
}  // namespace shoal::report
