// The SVG picture of an audit, drawn from a real run (two vessels in the Solent, one of them
// sailing across the Isle of Wight) and from audits built by hand with every kind of event,
// read back with GDAL's XML parser: well-formed SVG, one marker per event, the events' times
// as text, a scale bar that measures the hull right, an arrow to true north where grid north
// differs, zoomed panels for groundings first (then the other contacts by severity, then
// close passes) titled with the kind and the speed at contact, an unknown heading drawn
// dashed and said, the headline counting each kind; an empty audit still gives a picture.

#include <gtest/gtest.h>

#include <cpl_error.h>
#include <cpl_minixml.h>

#include "util/gdal_support.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/picture/plot.hpp>
#include <shoal/report/geojson_report.hpp>
#include <shoal/track/track.hpp>
#include "test_support.hpp"
#include "xml_support.hpp"
#include <shoal/util/error.hpp>

namespace shoal::report {
namespace {

using test::attr;
using test::each_element;

constexpr const char* svg_ns = "http://www.w3.org/2000/svg";


const CPLXMLNode* root_element(const CPLXMLNode* doc) {
    for (const CPLXMLNode* n = doc; n; n = n->psNext)
        if (n->eType == CXT_Element && n->pszValue[0] != '?') return n;
    return nullptr;
}


/// The text directly inside an element.
std::string inner_text(const CPLXMLNode* n) {
    std::string s;
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Text) s += c->pszValue;
    return s;
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

std::size_t event_count(const audit::AuditResult& r) {
    std::size_t n = 0;
    for (const auto& t : r.tracks) n += t.events.size();
    return n;
}

TEST(PlotSvg, SolentRunDrawsEveryEventItsTimeAndAZoomedPanelPerEventUpToTheLimit) {
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid();
    const audit::AuditResult r = solent_audit(g, dir);
    ASSERT_GE(r.groundings, 1u) << "vessel A crosses the Isle of Wight";

    const std::string svg = plot_svg(r, g);
    std::string error;
    const test::XmlPtr doc = test::parse_xml(svg, &error);
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
    const std::size_t panels = std::min<std::size_t>(PlotOptions{}.max_zoom_panels, event_count(r));
    EXPECT_EQ(with_class(root, "panel zoom").size(), panels);
    EXPECT_EQ(with_class(root, "scale-bar").size(), 1 + panels) << "one per panel";
    EXPECT_EQ(with_class(root, "north-arrow").size(), 1 + panels) << "one per panel";
    // The first panel is the first grounding's.
    const CPLXMLNode* first = panel(root, "zoom-1");
    ASSERT_NE(first, nullptr);
    EXPECT_FALSE(with_class(first, "contact grounding").empty());
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

    const test::XmlPtr doc = test::parse_xml(plot_svg(r, g), nullptr);
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
    const test::XmlPtr doc = test::parse_xml(svg, &error);
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
    EXPECT_TRUE(has_text_containing(root, "0 groundings, 0 close passes")) << "the other kinds only when there are some";
}

TEST(PlotSvg, AThousandsOfVesselsCrowdGetsLabelsThatNeverOverlapAndStayInThePanel) {
    // The labels are placed with a grid of buckets (so that a crowd costs linear time); the
    // independent answer is the brute-force test of every placed label against every other.
    const test::TempDir dir;
    const std::string path = dir.file("crowd.csv");
    {
        std::ofstream out(path);
        out << "mmsi,timestamp,lat,lon,sog,cog,heading\n";
        std::uint64_t state = 14;
        auto uniform = [&] {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            return static_cast<double>(state >> 11) / 9007199254740992.0;
        };
        char row[160];
        for (int k = 0; k < 2000; ++k) {
            const double lat = 50.60 + 0.12 * uniform(), lon = -1.15 + 0.3 * uniform();
            for (int i = 0; i < 3; ++i) {
                std::snprintf(row, sizeof row, "%d,2024-05-01T10:%02d:00Z,%.5f,%.5f,5,0,0\n", 200000000 + k, i, lat + 0.0005 * i, lon);
                out << row;
            }
        }
    }
    const grid::CoastGrid g = solent_grid();
    audit::AuditOptions options;
    options.jobs = 1;
    const audit::AuditResult r = audit::run_audit({path}, g, hull::Hull::from_dimensions({20, 5, 4, 4}), "--dims 20,5,4,4", options);
    ASSERT_EQ(r.tracks.size(), 2000u);
    const std::string svg = plot_svg(r, g, PlotOptions{3, 1200});
    std::string error;
    const test::XmlPtr doc = test::parse_xml(svg, &error);
    ASSERT_TRUE(doc) << error;
    const CPLXMLNode* root = root_element(doc.get());
    const CPLXMLNode* overview = panel(root, "overview");
    ASSERT_NE(overview, nullptr);
    struct Box {
        double x0, y0, x1, y1;
    };
    std::vector<Box> boxes;
    for (const char* cls : {"label track-id", "label event-time"})
        for (const CPLXMLNode* l : with_class(overview, cls)) {
            const CPLXMLNode* rect = nullptr;
            each_element(l, [&](const CPLXMLNode* n) {
                if (!rect && std::string(n->pszValue) == "rect") rect = n;
            });
            ASSERT_NE(rect, nullptr);
            const double x = std::stod(attr(rect, "x")), y = std::stod(attr(rect, "y"));
            boxes.push_back({x, y, x + std::stod(attr(rect, "width")), y + std::stod(attr(rect, "height"))});
        }
    EXPECT_GT(boxes.size(), 100u) << "the crowd gets labels where they fit";
    EXPECT_LT(boxes.size(), 2000u) << "and not where they do not";
    std::size_t overlapping = 0;
    for (std::size_t a = 0; a < boxes.size(); ++a)
        for (std::size_t b = a + 1; b < boxes.size(); ++b) {
            // Coordinates are rounded to 0.1 px in the SVG: a shared edge may look 0.1 px over.
            const double e = 0.11;
            if (boxes[a].x0 + e < boxes[b].x1 && boxes[b].x0 + e < boxes[a].x1 && boxes[a].y0 + e < boxes[b].y1 && boxes[b].y0 + e < boxes[a].y1)
                ++overlapping;
        }
    EXPECT_EQ(overlapping, 0u);
}

TEST(PlotSvg, ZoomedPanelsStopAtTheLimitAndTheRestAreCounted) {
    const test::TempDir dir;
    const grid::CoastGrid g = solent_grid();
    const audit::AuditResult r = solent_audit(g, dir);
    ASSERT_GE(r.groundings, 1u);
    const test::XmlPtr doc = test::parse_xml(plot_svg(r, g, PlotOptions{0, 1200}), nullptr);
    ASSERT_TRUE(doc);
    const CPLXMLNode* root = root_element(doc.get());
    EXPECT_EQ(with_class(root, "panel zoom").size(), 0u);
    EXPECT_EQ(with_class(root, "event grounding").size(), r.groundings) << "the overview still marks them all";
    EXPECT_TRUE(with_class(root, "section").empty()) << "no heading over no panels";
    const std::string note = std::to_string(event_count(r)) + " more not drawn: " + std::to_string(r.groundings) +
                             (r.groundings == 1 ? " grounding" : " groundings");
    EXPECT_TRUE(has_text_containing(root, note)) << note;
}

// ---------------------------------------------------------------- audits built by hand

constexpr double t0 = 1714557600;  // 2024-05-01T10:00:00Z

/// A ring of a 60 m x 10 m hull pointing north (or the hull's circle, 36 points of radius
/// 31 m, when `circle`) around `at`.
std::vector<geo::LonLat> hull_ring(geo::LonLat at, bool circle) {
    const double m_lat = 1 / 111320.0, m_lon = 1 / (111320.0 * std::cos(at.lat * std::numbers::pi / 180));
    std::vector<geo::LonLat> ring;
    if (circle) {
        for (int k = 0; k <= 36; ++k) {
            const double a = 2 * std::numbers::pi * (k % 36) / 36;
            ring.push_back({at.lon + 31 * std::sin(a) * m_lon, at.lat + 31 * std::cos(a) * m_lat});
        }
    } else {
        for (auto [x, y] : {std::pair{-5.0, -10.0}, {5.0, -10.0}, {5.0, 45.0}, {0.0, 50.0}, {-5.0, 45.0}, {-5.0, -10.0}})
            ring.push_back({at.lon + x * m_lon, at.lat + y * m_lat});
    }
    return ring;
}

/// An event `km` km south of 50.78 N on 1.30 W (the events 2 km apart: one per zoomed panel).
audit::Event hand_event(audit::EventKind kind, double km, double start, double duration, double figure_m, double speed_kn,
                        track::SpeedSource source) {
    audit::Event e;
    e.kind = kind;
    e.start_s = t0 + start;
    e.end_s = t0 + start + duration;
    e.point = {-1.30, 50.78 - km / 111.32};
    e.ship = e.point;
    e.heading_deg = 182;
    e.heading_source = track::HeadingSource::cog;
    e.hull = hull_ring(e.point, false);
    if (audit::is_contact(kind)) e.penetration_m = figure_m;
    else e.min_clearance_m = figure_m;
    e.speed_kn = speed_kn;
    e.speed_source = source;
    return e;
}

audit::TrackResult hand_track(const std::string& id, const std::string& name, std::vector<audit::Event> events) {
    audit::TrackResult t;
    t.summary.id = id;
    t.summary.name = name;
    t.summary.fixes = 2;
    std::vector<geo::LonLat> line;
    if (!events.empty()) line.push_back({events.front().ship.lon, events.front().ship.lat + 0.005});  // from 550 m north
    for (const auto& e : events) {
        line.push_back(e.ship);
        switch (e.kind) {
        case audit::EventKind::grounding: ++t.summary.groundings; break;
        case audit::EventKind::alongside: ++t.summary.alongside; break;
        case audit::EventKind::contact_at_start: ++t.summary.contacts_at_start; break;
        case audit::EventKind::expected_contact: ++t.summary.expected_contacts; break;
        case audit::EventKind::close_pass: ++t.summary.close_passes; break;
        case audit::EventKind::chart_disagrees: ++t.summary.chart_disagreements; break;
        }
    }
    t.summary.lines.push_back(line);
    t.events = std::move(events);
    return t;
}

/// Three tracks with every kind of event, in report order (each track's in time order):
/// A: an alongside (0.5 m), a grounding at +900 s, a deeper alongside (1.5 m);
/// B: a grounding at +200 s (the first in time), a contact in a berth, two close passes (30 m, 10 m);
/// C: only a contact at its first fix.
audit::AuditResult hand_audit() {
    using K = audit::EventKind;
    using S = track::SpeedSource;
    audit::AuditResult r;
    audit::Event along_shallow = hand_event(K::alongside, 0, 100, 600, 0.5, 0.3, S::positions);
    along_shallow.stopped_before = true;
    along_shallow.nav_status = track::nav_status_moored;
    along_shallow.structure = "pier";
    audit::Event late_grounding = hand_event(K::grounding, 2, 900, 42, 0.8, 7.1, S::sog);
    audit::Event along_deep = hand_event(K::alongside, 4, 1000, 3700, 1.5, 0.3, S::positions);
    r.tracks.push_back(hand_track("A", "ALPHA", {along_shallow, late_grounding, along_deep}));

    audit::Event early_grounding = hand_event(K::grounding, 6, 200, 95, 1.2, 9.8, S::sog);
    early_grounding.stopped_after_s = 40;
    early_grounding.reference_inside_m = 12.5;
    audit::Event berth = hand_event(K::expected_contact, 8, 300, 50, 0.4, 0.2, S::sog);
    berth.area_kind = "berth";
    berth.area_name = "Pier 7";
    audit::Event wide = hand_event(K::close_pass, 10, 400, 60, 30, 8, S::sog);
    audit::Event near = hand_event(K::close_pass, 12, 500, 60, 10, NAN, S::none);
    r.tracks.push_back(hand_track("B", "BRAVO", {early_grounding, berth, wide, near}));

    audit::Event at_start = hand_event(K::contact_at_start, 14, 0, 120, 3, 0, S::sog);
    at_start.unseen_after = "track start";
    r.tracks.push_back(hand_track("C", "CHARLIE", {at_start}));

    for (const auto& t : r.tracks) {
        r.fixes += t.summary.fixes;
        r.groundings += t.summary.groundings;
        r.alongside += t.summary.alongside;
        r.contacts_at_start += t.summary.contacts_at_start;
        r.expected_contacts += t.summary.expected_contacts;
        r.close_passes += t.summary.close_passes;
    }
    r.first_fix_s = t0;
    r.last_fix_s = t0 + 5000;
    return r;
}

/// Some text of zoomed panel `id` (its title is inside it) contains `needle`.
bool panel_says(const CPLXMLNode* svg, const std::string& id, const std::string& needle) {
    const CPLXMLNode* p = panel(svg, id);
    return p && has_text_containing(p, needle);
}

TEST(PlotSvg, GroundingsComeFirstThenTheOtherContactsBySeverityThenClosePassesAllTitledWithKindAndSpeed) {
    const grid::CoastGrid g = solent_grid();
    const audit::AuditResult r = hand_audit();
    const std::string svg = plot_svg(r, g);
    std::string error;
    const test::XmlPtr doc = test::parse_xml(svg, &error);
    ASSERT_TRUE(doc) << error;
    const CPLXMLNode* root = root_element(doc.get());

    EXPECT_EQ(with_class(root, "panel zoom").size(), 8u) << "every event has a panel";
    // One marker per event, each kind its own.
    EXPECT_EQ(with_class(root, "event grounding").size(), 2u);
    EXPECT_EQ(with_class(root, "event alongside").size(), 2u);
    EXPECT_EQ(with_class(root, "event in_contact_at_start").size(), 1u);
    EXPECT_EQ(with_class(root, "event expected_contact").size(), 1u);
    EXPECT_EQ(with_class(root, "event close_pass").size(), 2u);

    // Panel n's own contact marker says whose panel it is (the events are 2 km apart).
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"grounding", "from 2024-05-01 10:03:20Z"},     // B's, first in time
        {"grounding", "from 2024-05-01 10:15:00Z"},     // A's
        {"alongside", "penetration 1.5 m"},              // the deeper one first
        {"alongside", "penetration 0.5 m"},
        {"in_contact_at_start", "in contact at the first fix (not seen begin)"},
        {"expected_contact", "contact in berth Pier 7"},
        {"close_pass", "least clearance 10.0 m"},        // least clearance first
        {"close_pass", "least clearance 30.0 m"},
    };
    for (std::size_t n = 0; n < expected.size(); ++n) {
        const std::string id = "zoom-" + std::to_string(n + 1);
        const CPLXMLNode* p = panel(root, id);
        ASSERT_NE(p, nullptr) << id;
        EXPECT_EQ(with_class(p, "contact " + expected[n].first).size(), 1u) << id;
        EXPECT_TRUE(has_text_containing(p, expected[n].second)) << id << ": " << expected[n].second;
    }
    // Titles: track and name, kind in words, speed at contact with its source, duration.
    EXPECT_TRUE(panel_says(root, "zoom-1", "(1) track B BRAVO"));
    EXPECT_TRUE(panel_says(root, "zoom-1", "9.8 kn SOG at contact"));
    EXPECT_TRUE(panel_says(root, "zoom-1", "for 1 min 35 s"));
    EXPECT_TRUE(panel_says(root, "zoom-2", "7.1 kn SOG"));
    EXPECT_TRUE(panel_says(root, "zoom-3", "alongside (not a grounding)"));
    EXPECT_TRUE(panel_says(root, "zoom-3", "0.3 kn from positions at contact"));
    EXPECT_TRUE(panel_says(root, "zoom-3", "for 1 h 02 min"));
    EXPECT_TRUE(panel_says(root, "zoom-7", "speed unknown"));
    EXPECT_TRUE(panel_says(root, "zoom-1", "heading 182\xC2\xB0"));

    // Section headings in order, each over its panels.
    std::vector<std::string> sections;
    for (const CPLXMLNode* s : with_class(root, "section")) sections.push_back(inner_text(s));
    EXPECT_EQ(sections, (std::vector<std::string>{"Groundings", "Other contacts (not groundings)", "Close passes"}));

    // Tooltips carry the evidence.
    bool evidence = false, structure = false;
    for (const CPLXMLNode* m : with_class(root, "event grounding"))
        each_element(m, [&](const CPLXMLNode* e) {
            const std::string t = inner_text(e);
            if (std::string(e->pszValue) == "title" && t.find("stopped after 40 s") != std::string::npos &&
                t.find("reference point 12.5 m inside land") != std::string::npos && t.find("9.8 kn SOG") != std::string::npos)
                evidence = true;
        });
    for (const CPLXMLNode* m : with_class(root, "event alongside"))
        each_element(m, [&](const CPLXMLNode* e) {
            const std::string t = inner_text(e);
            if (std::string(e->pszValue) == "title" && t.find("AIS status moored") != std::string::npos &&
                t.find("structure pier") != std::string::npos)
                structure = true;
        });
    EXPECT_TRUE(evidence);
    EXPECT_TRUE(structure);

    // Only a track with a grounding is red; C (a contact at its first fix only) has its own colour.
    const CPLXMLNode* overview = panel(root, "overview");
    ASSERT_NE(overview, nullptr);
    std::string stroke_a, stroke_c;
    for (const CPLXMLNode* t : with_class(overview, "track"))
        each_element(t, [&](const CPLXMLNode* e) {
            if (std::string(e->pszValue) != "title") return;
            if (inner_text(e).starts_with("track A")) stroke_a = attr(t, "stroke");
            if (inner_text(e).starts_with("track C")) stroke_c = attr(t, "stroke");
        });
    EXPECT_EQ(stroke_a, "#d62728");
    EXPECT_FALSE(stroke_c.empty());
    EXPECT_NE(stroke_c, stroke_a);
    const auto legend = with_class(root, "legend");
    ASSERT_EQ(legend.size(), 1u);
    for (const char* item : {"track with contacts, no grounding", "alongside (not a grounding)", "in contact at the first fix",
                             "contact in a berth or harbour area", "close pass"})
        EXPECT_TRUE(has_text_containing(legend[0], item)) << "the legend lists what is drawn: " << item;
    EXPECT_FALSE(has_text_containing(legend[0], "heading unknown")) << "no hull circle drawn";
}

TEST(PlotSvg, PanelsLeftOutAreCountedByKind) {
    const grid::CoastGrid g = solent_grid();
    const test::XmlPtr doc = test::parse_xml(plot_svg(hand_audit(), g, PlotOptions{3, 1200}), nullptr);
    ASSERT_TRUE(doc);
    const CPLXMLNode* root = root_element(doc.get());
    EXPECT_EQ(with_class(root, "panel zoom").size(), 3u);
    EXPECT_FALSE(with_class(panel(root, "zoom-1"), "contact grounding").empty());
    EXPECT_FALSE(with_class(panel(root, "zoom-2"), "contact grounding").empty());
    EXPECT_FALSE(with_class(panel(root, "zoom-3"), "contact alongside").empty());
    std::vector<std::string> sections;
    for (const CPLXMLNode* s : with_class(root, "section")) sections.push_back(inner_text(s));
    EXPECT_EQ(sections, (std::vector<std::string>{"Groundings", "Other contacts (not groundings): first 1 of 4"}));
    const auto notes = with_class(root, "note");
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(inner_text(notes[0]),
              "5 more not drawn: 1 alongside, 1 in contact at the start, 1 expected contact, 2 close passes (at most 3 zoomed "
              "panels; see the report for all)");
}

TEST(PlotSvg, UnknownHeadingIsDrawnDashedAndSaidNeverAsHeadingZero) {
    const grid::CoastGrid g = solent_grid();
    audit::Event e = hand_event(audit::EventKind::grounding, 6, 0, 30, 2, 6.5, track::SpeedSource::positions);
    e.orientation_unknown = true;
    e.heading_deg = NAN;
    e.heading_source = track::HeadingSource::none;
    e.hull = hull_ring(e.point, true);
    audit::Event e2 = hand_event(audit::EventKind::alongside, 2, 500, 30, 1, 0.1, track::SpeedSource::sog);
    e2.orientation_unknown = true;
    e2.heading_deg = 0;  // whatever it holds, it is not printed
    e2.hull = hull_ring(e2.point, true);
    audit::AuditResult r;
    r.tracks.push_back(hand_track("U", "UNKNOWN HEADING", {e, e2}));
    r.groundings = 1;
    r.alongside = 1;
    const std::string svg = plot_svg(r, g);
    std::string error;
    const test::XmlPtr doc = test::parse_xml(svg, &error);
    ASSERT_TRUE(doc) << error;
    const CPLXMLNode* root = root_element(doc.get());

    for (const char* id : {"zoom-1", "zoom-2"}) {
        const CPLXMLNode* zoom = panel(root, id);
        ASSERT_NE(zoom, nullptr) << id;
        bool dashed = false;
        each_element(zoom, [&](const CPLXMLNode* n) {
            if (attr(n, "class").starts_with("hull ") && !attr(n, "stroke-dasharray").empty()) dashed = true;
        });
        EXPECT_TRUE(dashed) << id << ": the hull's circle is drawn dashed";
        const auto labels = with_class(zoom, "label heading-unknown");
        ASSERT_EQ(labels.size(), 1u) << id;
        EXPECT_TRUE(has_text_containing(labels[0], "heading unknown (hull circle)"));
        EXPECT_TRUE(has_text_containing(zoom, "heading unknown (hull circle)")) << id << ": the title says it too";
    }
    EXPECT_TRUE(has_text_containing(root, "hull circle: heading unknown")) << "the legend";
    EXPECT_EQ(svg.find("heading 0"), std::string::npos);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("heading \xC2\xB0"), std::string::npos);
}

TEST(PlotSvg, HeadlineCountsEachKind) {
    const grid::CoastGrid g = solent_grid();
    const test::XmlPtr doc = test::parse_xml(plot_svg(hand_audit(), g), nullptr);
    ASSERT_TRUE(doc);
    const auto summary = with_class(root_element(doc.get()), "summary");
    ASSERT_EQ(summary.size(), 1u);
    EXPECT_EQ(inner_text(summary[0]),
              "3 tracks, 6 fixes, 2 groundings, 1 in contact at the start, 2 alongside, 1 expected contact, 2 close passes");

    audit::AuditResult r = hand_audit();  // the counts as the run gives them
    r.groundings = 1;
    r.contacts_at_start = 37;
    r.alongside = 2;
    r.expected_contacts = 0;
    r.close_passes = 8;
    const test::XmlPtr doc2 = test::parse_xml(plot_svg(r, g), nullptr);
    ASSERT_TRUE(doc2);
    EXPECT_TRUE(has_text_containing(root_element(doc2.get()), "1 grounding, 37 in contact at the start, 2 alongside, 8 close passes"));
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
    const test::XmlPtr doc = test::parse_xml(svg, &error);
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

/// The file at `path` after writing `text` there.
const std::string& written(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

TEST(OwnFiles, AReportIsToldByItsTopLevelShoalMemberNotByTheWordAnywhere) {
    const test::TempDir dir;
    const std::string f = dir.file("r.geojson");
    auto ours = [&](const std::string& text) { return is_shoal_geojson_report(written(f, text)); };
    // As shoal writes it (dump(1)), compact, after a byte-order mark, with strings before it.
    EXPECT_TRUE(ours("{\n \"type\": \"FeatureCollection\",\n \"shoal\": {\n  \"version\": \"0.2.0\"\n }\n}\n"));
    EXPECT_TRUE(ours("{\"type\":\"FeatureCollection\",\"shoal\":{\"version\":\"0.2.0\"},\"features\":[]}"));
    EXPECT_TRUE(ours("\xEF\xBB\xBF  {\"shoal\" : {}}"));
    EXPECT_TRUE(ours("{\"d\":\"a \\\" b \\\\\",\"n\":[1,{\"x\":[2]}],\"shoal\":{\"v\":1}}"));
    // Someone's hazard file: "shoal" a feature's property (before: replaced by the report).
    EXPECT_FALSE(ours("{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{\"name\":\"Harmaja\",\"shoal\":true},"
                      "\"geometry\":null}]}"));
    EXPECT_FALSE(ours("{\"type\":\"FeatureCollection\",\"features\":[{\"properties\":{\"shoal\":{\"depth\":2}}}]}"));
    EXPECT_FALSE(ours("{\"name\":\"x\",\"shoal\":true}"));                      // not an object
    EXPECT_FALSE(ours("{\"description\":\"\\\"shoal\\\": {\",\"x\":1}"));        // inside a string
    EXPECT_FALSE(ours("{\"description\":\"\\\"\",\"shoal\\\"\":{}}"));          // a key "shoal\"" is not "shoal"
    EXPECT_FALSE(ours("[{\"shoal\":{}}]"));
    EXPECT_FALSE(ours("{\"a\":{\"shoal\":{}}}"));
    EXPECT_FALSE(ours("{\"a\":1}\n{\"shoal\":{}}"));                             // after the object
    EXPECT_FALSE(ours("{\"pad\":\"" + std::string(5000, 'x') + "\",\"shoal\":{}}"));  // past 4 KiB
    EXPECT_FALSE(ours(""));
    EXPECT_FALSE(ours("shoal"));
}

TEST(OwnFiles, APictureIsToldByItsRootsFirstChildTitleNotByATitleAnywhere) {
    const test::TempDir dir;
    const std::string f = dir.file("p.svg");
    auto ours = [&](const std::string& text) { return is_shoal_picture(written(f, text)); };
    EXPECT_TRUE(ours(plot_svg(audit::AuditResult{}, solent_grid())));  // as shoal writes it
    EXPECT_TRUE(ours("<svg viewBox=\"0 0 1 1\" data-x='a>b'>\n  <title>shoal audit: 1 track</title></svg>"));
    // Someone's drawing (before: replaced by the picture).
    EXPECT_FALSE(ours("<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n<g><title>shoal audit area</title></g>\n</svg>"));
    EXPECT_FALSE(ours("<svg><desc>d</desc><title>shoal audit</title></svg>"));
    EXPECT_FALSE(ours("<svgx><title>shoal audit</title></svgx>"));
    EXPECT_FALSE(ours("<svg><title>my shoal audit</title></svg>"));
    EXPECT_FALSE(ours("<html><title>shoal audit</title></html>"));
}

}  // namespace
}  // namespace shoal::report
