// The instructor's debrief sheet, from a real exercise audited in the Solent (three ships in one
// file, one of them sailing across the Isle of Wight, two crossing east of it; a fourth ship in
// a second file, another exercise) with a hand-filled assessment: the page read back with
// GDAL's XML parser (it is written well-formed) and checked against the audit result it was
// made from: every trainee's score, every encounter row with its give-way ship, the events in
// time order with a zoomed panel each, hostile track ids escaped, no http(s) address; the file
// names of hostile exercise names; the CLI's --debrief folder (pages, a foreign file kept, a
// page name refused before any work); and the page opened in a real headless Chromium, whose
// screenshot must show the run (land and the grounded track's red in the picture's place).

#include <gtest/gtest.h>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_minixml.h>
#include <gdal_priv.h>

#include "detail/gdal_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/report/debrief.hpp>
#include <shoal/report/report.hpp>
#include "run_shoal.hpp"
#include "test_support.hpp"
#include "xml_support.hpp"

namespace shoal::report {
namespace {

using test::attr;
using test::each_element;

namespace fs = std::filesystem;



/// The document's <html> element (after the doctype), or null.
const CPLXMLNode* html_of(const CPLXMLNode* doc) {
    for (const CPLXMLNode* n = doc; n; n = n->psNext)
        if (n->eType == CXT_Element && std::string(n->pszValue) == "html") return n;
    return nullptr;
}

/// Elements whose class list holds `cls` (and, when given, of tag `tag`).
std::vector<const CPLXMLNode*> with_class(const CPLXMLNode* n, const std::string& cls, const std::string& tag = "") {
    std::vector<const CPLXMLNode*> out;
    each_element(n, [&](const CPLXMLNode* e) {
        const std::string c = " " + attr(e, "class") + " ";
        if (c.find(" " + cls + " ") != std::string::npos && (tag.empty() || tag == e->pszValue)) out.push_back(e);
    });
    return out;
}

const CPLXMLNode* by_id(const CPLXMLNode* n, const std::string& id) {
    const CPLXMLNode* found = nullptr;
    each_element(n, [&](const CPLXMLNode* e) {
        if (!found && attr(e, "id") == id) found = e;
    });
    return found;
}

/// All the text inside an element (its descendants' too), in document order.
std::string all_text(const CPLXMLNode* n) {
    std::string s;
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext) {
        if (c->eType == CXT_Text) s += c->pszValue;
        else if (c->eType == CXT_Element) s += all_text(c);
    }
    return s;
}

std::vector<const CPLXMLNode*> children(const CPLXMLNode* n, const std::string& tag) {
    std::vector<const CPLXMLNode*> out;
    for (const CPLXMLNode* c = n->psChild; c; c = c->psNext)
        if (c->eType == CXT_Element && tag == c->pszValue) out.push_back(c);
    return out;
}

/// A track id no page may let through as markup.
const std::string hostile_id = "C<img src=x onerror=alert(1)>&amp;'";

/// Exercise 1 (one file): A sails south across the Isle of Wight (it grounds), B sails east
/// and C north east of the island, crossing B's track; exercise 2 (another file): D alone.
std::vector<std::string> exercise_files(const test::TempDir& dir) {
    const std::string one = dir.file("ex1 <b>&.csv"), two = dir.file("ex2.csv");
    std::ofstream out(one);
    out << "id,time,lat,lon,sog,cog,heading\n";
    char line[200];
    for (int i = 0; i <= 20; ++i) {
        std::snprintf(line, sizeof line, "A,2024-05-01T10:%02d:00Z,%.4f,-1.3000,11.9,180,180\n", i, 50.78 - 0.01 * i);
        out << line;
    }
    for (int i = 0; i <= 20; ++i) {
        std::snprintf(line, sizeof line, "B,2024-05-01T10:%02d:00Z,50.7400,%.4f,8.5,90,90\n", i, -1.05 + 0.002 * i);
        out << line;
    }
    for (int i = 0; i <= 20; ++i) {
        std::snprintf(line, sizeof line, "%s,2024-05-01T10:%02d:30Z,%.4f,-1.0300,11,0,0\n", hostile_id.c_str(), i, 50.71 + 0.003 * i);
        out << line;
    }
    out.close();
    std::ofstream second(two);
    second << "id,time,lat,lon,sog,cog,heading\n";
    for (int i = 0; i <= 10; ++i) {
        std::snprintf(line, sizeof line, "D,2024-05-01T11:%02d:00Z,50.7300,%.4f,8,90,90\n", i, -1.06 + 0.002 * i);
        second << line;
    }
    return {one, two};
}

grid::CoastGrid solent_grid() {
    grid::BuildRequest request;
    request.cell_m = 400;
    std::vector<std::string> warnings;
    return grid::build_grid({test::data_path("coast/uk_solent_land.geojson")}, request, &warnings);
}

audit::AuditResult exercise_audit(const grid::CoastGrid& g, const std::vector<std::string>& files) {
    audit::AuditOptions options;
    options.jobs = 1;
    options.encounters = true;
    options.exercise_by = audit::ExerciseBy::file;
    options.encounter.ship_margin_m = 400;  // B and C pass within it: close quarters
    return audit::run_audit(files, g, hull::Hull::from_dimensions({50, 10, 5, 5}), "--dims 50,10,5,5", options);
}

std::size_t index_of(const audit::AuditResult& r, const std::string& id) {
    for (std::size_t k = 0; k < r.tracks.size(); ++k)
        if (r.tracks[k].summary.id == id) return k;
    return r.tracks.size();
}

/// A hand-filled assessment (scoring is not the sheet's business): A and C are trainees of
/// exercise 1, D of exercise 2; breaches at times between the other events.
void assess_by_hand(audit::AuditResult& r) {
    const std::string ex1 = r.tracks[index_of(r, "A")].summary.exercise;
    const std::string ex2 = r.tracks[index_of(r, "D")].summary.exercise;
    r.has_assessment = true;
    r.assessment.scores = {{ex1, "A", 35, 2}, {ex1, hostile_id, 0, 0}, {ex2, "D", 7.5, 1}};
    const double t0 = r.tracks[index_of(r, "A")].summary.start_s;
    audit::Breach b1;
    b1.exercise = ex1;
    b1.track = "A";
    b1.criterion = "land-0.5nm";
    b1.kind = audit::CriterionKind::land_clearance;
    b1.start_s = t0 + 90;
    b1.end_s = t0 + 200;
    b1.worst_s = t0 + 150;
    b1.lon = -1.30;
    b1.lat = 50.755;
    b1.value = 120;
    b1.limit = 926;
    b1.penalty = 25;
    b1.detail = "hostile <b>detail</b> & more";
    audit::Breach b2 = b1;
    b2.criterion = "cpa-1nm";
    b2.kind = audit::CriterionKind::cpa;
    b2.track = "A";
    b2.other = "B";
    b2.start_s = b2.end_s = b2.worst_s = t0 + 700;
    b2.penalty = 10;
    audit::Breach b3 = b1;
    b3.exercise = ex2;
    b3.track = "D";
    b3.criterion = "speed-5kn";
    b3.kind = audit::CriterionKind::speed_limit;
    b3.penalty = 7.5;
    b3.lon = -1.05;
    b3.lat = 50.73;
    r.assessment.breaches = {b1, b2, b3};
}

struct Fixture {
    test::TempDir dir;
    grid::CoastGrid grid = solent_grid();
    std::vector<std::string> files = exercise_files(dir);
    audit::AuditResult result = exercise_audit(grid, files);
    RunInfo info;
    Fixture() {
        assess_by_hand(result);
        audit::AuditOptions options;
        info = run_info({test::data_path("coast/uk_solent_land.geojson")}, grid, "--dims 50,10,5,5", options, {});
    }
};

TEST(Debrief, PagePerExerciseListsEveryTraineeEveryEncounterAndEveryEventInTimeOrderEscaped) {
    Fixture f;
    const audit::AuditResult& r = f.result;
    ASSERT_EQ(r.tracks.size(), 4u);
    ASSERT_GE(r.groundings, 1u) << "A crosses the Isle of Wight";
    const std::vector<DebriefPage> pages = debrief_pages(r);
    ASSERT_EQ(pages.size(), 2u) << "two files, two exercises";
    EXPECT_EQ(pages[0].file, "ex1_b_.csv.html");
    EXPECT_EQ(pages[1].file, "ex2.csv.html");
    ASSERT_EQ(pages[0].tracks.size(), 3u);
    const DebriefPage& page = pages[0];
    const std::string ex = page.exercise;
    ASSERT_FALSE(r.situations.empty()) << "B and C cross within the encounter range";

    const std::string html = debrief_html(r, f.grid, f.info, page);
    // Nothing fetched at view time, nothing run.
    EXPECT_EQ(html.find("http:"), std::string::npos);
    EXPECT_EQ(html.find("https:"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
    EXPECT_EQ(html.find("@import"), std::string::npos);
    EXPECT_EQ(html.find("<img"), std::string::npos) << "the hostile id must be escaped";
    EXPECT_EQ(html.find("<b>"), std::string::npos);
    EXPECT_NE(html.find("@page"), std::string::npos);
    EXPECT_NE(html.find("simulated: the chart is the world"), std::string::npos) << "the page says which world";
    EXPECT_NE(html.find("@media print"), std::string::npos);

    std::string error;
    const test::XmlPtr doc = test::parse_xml(html, &error);
    ASSERT_TRUE(doc) << "not well-formed: " << error;
    const CPLXMLNode* root = html_of(doc.get());
    ASSERT_NE(root, nullptr) << "no <html> element";

    // The header names the exercise (as read back: the escaping undone, nothing lost).
    const auto exercise = with_class(root, "exercise");
    ASSERT_EQ(exercise.size(), 1u);
    EXPECT_EQ(all_text(exercise[0]), ex);

    // The picture: the overview of this exercise's three tracks only.
    const CPLXMLNode* picture = by_id(root, "picture");
    ASSERT_NE(picture, nullptr);
    EXPECT_EQ(with_class(picture, "overview", "g").size(), 1u);
    EXPECT_EQ(with_class(picture, "track", "path").size(), 3u);
    EXPECT_GT(with_class(picture, "grounding", "circle").size() + with_class(picture, "grounding", "polygon").size(), 0u);

    // Scores: every trainee of this exercise (and only them), with the penalty given.
    const auto scores = with_class(root, "score", "tr");
    ASSERT_EQ(scores.size(), 2u);
    std::set<std::string> trainees;
    for (const auto* s : scores) trainees.insert(all_text(with_class(s, "track")[0]));
    EXPECT_EQ(trainees, (std::set<std::string>{"A", hostile_id}));
    EXPECT_EQ(all_text(with_class(scores[0], "penalty")[0]), "35.0");

    // Ships: every track of the exercise.
    EXPECT_EQ(with_class(root, "ship", "tr").size(), 3u);

    // Encounters: one row per situation of the exercise, give-way and stand-on as the result says.
    std::vector<const audit::ColregEncounter*> sits;
    for (const auto& c : r.situations)
        if (r.tracks[c.a].summary.exercise == ex) sits.push_back(&c);
    const auto rows = with_class(root, "encounter", "tr");
    ASSERT_EQ(rows.size(), sits.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const auto& c = *sits[k];
        EXPECT_EQ(all_text(with_class(rows[k], "situation")[0]), audit::to_string(c.at_start.situation));
        const std::string& a = r.tracks[c.a].summary.id;
        const std::string& b = r.tracks[c.b].summary.id;
        const std::string give_way = all_text(with_class(rows[k], "give-way")[0]);
        switch (c.at_start.give_way) {
        case audit::Party::a: EXPECT_EQ(give_way, a); break;
        case audit::Party::b: EXPECT_EQ(give_way, b); break;
        case audit::Party::both: EXPECT_EQ(give_way, "both (" + a + ", " + b + ")"); break;
        case audit::Party::neither: EXPECT_EQ(give_way, "neither"); break;
        }
        EXPECT_EQ(all_text(with_class(rows[k], "ships")[0]), a + " \xC3\x97 " + b);
        char cpa[32];
        std::snprintf(cpa, sizeof cpa, "%.0f", c.cpa_start.distance_m);
        EXPECT_EQ(all_text(with_class(rows[k], "cpa")[0]), cpa);
    }

    // Events: every track event, encounter event and breach of the exercise, in time order,
    // each with its zoomed panel.
    std::vector<std::pair<double, std::string>> expected;
    for (const std::size_t ti : page.tracks)
        for (const auto& e : r.tracks[ti].events) expected.emplace_back(e.start_s, audit::to_string(e.kind));
    for (const auto& e : r.encounters.events)
        if (r.tracks[e.a.track].summary.exercise == ex) expected.emplace_back(e.start_s, audit::to_string(e.kind));
    for (const auto& b : r.assessment.breaches)
        if (b.exercise == ex) expected.emplace_back(b.start_s, "breach");
    std::stable_sort(expected.begin(), expected.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    const auto events = with_class(root, "event", "article");
    ASSERT_EQ(events.size(), expected.size());
    std::multiset<std::string> kinds_seen, kinds_expected;
    std::string last_time;
    for (std::size_t k = 0; k < events.size(); ++k) {
        const std::string t = attr(events[k], "data-time");
        EXPECT_EQ(t, iso_time(expected[k].first)) << "event " << k + 1;
        EXPECT_LE(last_time, t) << "events in time order";
        last_time = t;
        kinds_seen.insert(attr(events[k], "data-kind"));
        kinds_expected.insert(expected[k].second);
        const auto figures = children(events[k], "figure");
        ASSERT_EQ(figures.size(), 1u) << "event " << k + 1 << " has its zoomed panel";
        EXPECT_EQ(with_class(figures[0], "zoom", "g").size(), 1u);
        EXPECT_NE(by_id(figures[0], "zoom-" + std::to_string(k + 1)), nullptr);
    }
    EXPECT_EQ(kinds_seen, kinds_expected);
    EXPECT_GE(kinds_seen.count("grounding"), 1u);
    EXPECT_EQ(kinds_seen.count("breach"), 2u);
    // The breach's hostile detail is text, not markup.
    EXPECT_NE(all_text(by_id(root, "events")).find("hostile <b>detail</b> & more"), std::string::npos);
    // The hostile id, read back as text, is there whole.
    EXPECT_NE(all_text(by_id(root, "events")).find(hostile_id), std::string::npos);

    // The second exercise's page holds D only, its score and its breach.
    const test::XmlPtr doc2 = test::parse_xml(debrief_html(r, f.grid, f.info, pages[1]), &error);
    ASSERT_TRUE(doc2) << error;
    EXPECT_EQ(with_class(html_of(doc2.get()), "ship", "tr").size(), 1u);
    EXPECT_EQ(with_class(html_of(doc2.get()), "score", "tr").size(), 1u);
    EXPECT_EQ(with_class(html_of(doc2.get()), "event", "article").size(), r.tracks[index_of(r, "D")].events.size() + 1);
}

TEST(Debrief, TheScoreExplainedCriteriaPerCriterionPassMarkAndWhatEachBreachAskedAndDid) {
    Fixture f;
    audit::AuditResult& r = f.result;
    // The assessment file: named (hostile), three criteria, a pass mark of 30.
    f.info.assessment = "exam <i>&amp;.json";
    r.assessment.source = f.info.assessment;
    r.assessment.pass_mark = 30;
    audit::Criterion land, cpa, rules;
    land.id = "land-0.5nm";
    land.kind = audit::CriterionKind::land_clearance;
    land.limit = 926;
    land.penalty = 25;
    cpa.id = "cpa-1nm";
    cpa.kind = audit::CriterionKind::cpa;
    cpa.limit = 1852;
    cpa.penalty = 10;
    rules.id = "rules <b>of</b> the road";
    rules.kind = audit::CriterionKind::colreg;
    rules.penalty = 50;
    r.assessment.criteria = {land, cpa, rules};
    // A: 25 + 10 + 50 = 85 (fails); the hostile trainee 0 (passes).
    r.assessment.scores[0].penalty = 85;
    r.assessment.scores[0].breaches = 3;
    r.assessment.scores[0].by_criterion = {25, 10, 50};
    r.assessment.scores[0].passed = false;
    r.assessment.scores[1].by_criterion = {0, 0, 0};
    r.assessment.scores[1].passed = true;
    audit::Breach b4 = r.assessment.breaches[1];
    b4.criterion = rules.id;
    b4.kind = audit::CriterionKind::colreg;
    b4.rule = "15";
    b4.penalty = 50;
    b4.asked = "rule 15 (crossing, B on the starboard side): keep out of the way <u>now</u>";
    b4.did = "A kept her course (180) & speed (11.9 kn)";
    r.assessment.breaches[0].asked = "a clearance to land or hazards of at least 926.0 m";
    r.assessment.breaches[0].did = "clearance to land 120.0 m";
    r.assessment.breaches.insert(r.assessment.breaches.begin() + 2, b4);

    const std::vector<DebriefPage> pages = debrief_pages(r);
    const std::string html = debrief_html(r, f.grid, f.info, pages[0]);
    EXPECT_EQ(html.find("<i>"), std::string::npos);
    EXPECT_EQ(html.find("<b>"), std::string::npos);
    EXPECT_EQ(html.find("<u>"), std::string::npos);
    std::string error;
    const test::XmlPtr doc = test::parse_xml(html, &error);
    ASSERT_TRUE(doc) << "not well-formed: " << error;
    const CPLXMLNode* scores = by_id(html_of(doc.get()), "scores");
    ASSERT_NE(scores, nullptr);
    // The file named, the pass mark given.
    const auto file = with_class(scores, "assessment-file");
    ASSERT_EQ(file.size(), 1u);
    EXPECT_EQ(all_text(file[0]), "exam <i>&amp;.json");
    ASSERT_EQ(with_class(scores, "pass-mark").size(), 1u);
    EXPECT_EQ(all_text(with_class(scores, "pass-mark")[0]), "30.0");
    // The criteria, each named with what it asks and its penalty.
    const auto criteria = with_class(scores, "criterion", "tr");
    ASSERT_EQ(criteria.size(), 3u);
    EXPECT_EQ(all_text(with_class(criteria[0], "id")[0]), "land-0.5nm");
    EXPECT_NE(all_text(criteria[0]).find("clearance to land or hazards at least 926.0 m"), std::string::npos) << all_text(criteria[0]);
    EXPECT_NE(all_text(criteria[0]).find("25 per breach"), std::string::npos);
    EXPECT_EQ(all_text(with_class(criteria[2], "id")[0]), "rules <b>of</b> the road");
    EXPECT_EQ(attr(criteria[2], "data-kind"), "colreg");
    EXPECT_NE(all_text(criteria[2]).find("head-on within 5 degrees"), std::string::npos) << all_text(criteria[2]);
    EXPECT_NE(all_text(criteria[2]).find("by at least 30 degrees of course or 50% of speed"), std::string::npos);
    // Each trainee's penalty per criterion, the total and pass or fail.
    const auto rows = with_class(scores, "score", "tr");
    ASSERT_EQ(rows.size(), 2u);
    const auto* a = all_text(with_class(rows[0], "track")[0]) == "A" ? rows[0] : rows[1];
    const auto* h = a == rows[0] ? rows[1] : rows[0];
    const auto by = with_class(a, "by-criterion");
    ASSERT_EQ(by.size(), 3u);
    EXPECT_EQ(all_text(by[0]), "25.0");
    EXPECT_EQ(all_text(by[1]), "10.0");
    EXPECT_EQ(all_text(by[2]), "50.0");
    EXPECT_EQ(all_text(with_class(a, "penalty")[0]), "85.0");
    ASSERT_EQ(with_class(a, "result").size(), 1u);
    EXPECT_EQ(all_text(with_class(a, "result")[0]), "fail");
    EXPECT_EQ(with_class(a, "fail").size(), 1u);
    EXPECT_EQ(all_text(with_class(h, "track")[0]), hostile_id);
    EXPECT_EQ(all_text(with_class(h, "result")[0]), "pass");
    // Why: every breach of this exercise, with what was asked and what happened.
    const auto why = with_class(scores, "breach", "tr");
    ASSERT_EQ(why.size(), 3u);
    EXPECT_EQ(all_text(with_class(why[0], "asked")[0]), "a clearance to land or hazards of at least 926.0 m");
    EXPECT_EQ(all_text(with_class(why[0], "did")[0]), "clearance to land 120.0 m");
    const auto* colreg = why[2];
    EXPECT_EQ(attr(colreg, "data-kind"), "colreg");
    EXPECT_EQ(all_text(with_class(colreg, "rule")[0]), "15");
    EXPECT_EQ(all_text(with_class(colreg, "asked")[0]), b4.asked);
    EXPECT_EQ(all_text(with_class(colreg, "did")[0]), b4.did);
    // Without a pass mark: no verdict.
    r.assessment.pass_mark = NAN;
    const test::XmlPtr none = test::parse_xml(debrief_html(r, f.grid, f.info, pages[0]), nullptr);
    ASSERT_TRUE(none);
    const CPLXMLNode* s2 = by_id(html_of(none.get()), "scores");
    EXPECT_TRUE(with_class(s2, "pass-mark").empty());
    EXPECT_NE(all_text(s2).find("no pass mark"), std::string::npos);
    EXPECT_TRUE(with_class(s2, "pass").empty());
    EXPECT_TRUE(with_class(s2, "fail").empty());
}

TEST(Debrief, UnassessedRunSaysSoAndListsNoScores) {
    Fixture f;
    f.result.has_assessment = false;
    const std::vector<DebriefPage> pages = debrief_pages(f.result);
    const test::XmlPtr doc = test::parse_xml(debrief_html(f.result, f.grid, f.info, pages[0]), nullptr);
    ASSERT_TRUE(doc);
    EXPECT_TRUE(with_class(html_of(doc.get()), "score", "tr").empty());
    EXPECT_NE(all_text(by_id(html_of(doc.get()), "scores")).find("Not assessed"), std::string::npos);
    EXPECT_TRUE(with_class(html_of(doc.get()), "breach").empty());
}

TEST(Debrief, TheShipsTableGivesEachShipsAisTypeAndADashWhenNotKnown) {
    Fixture f;
    const std::vector<DebriefPage> pages = debrief_pages(f.result);
    const DebriefPage& page = pages[0];
    ASSERT_EQ(page.tracks.size(), 3u);
    f.result.tracks[page.tracks[1]].summary.ship_type = 52;  // a tug (ITU-R M.1371 table 53); the others not known
    const test::XmlPtr doc = test::parse_xml(debrief_html(f.result, f.grid, f.info, page), nullptr);
    ASSERT_TRUE(doc);
    const auto rows = with_class(html_of(doc.get()), "ship", "tr");
    ASSERT_EQ(rows.size(), 3u);
    std::vector<std::string> types;
    for (const auto* row : rows) {
        const auto cell = with_class(row, "ship-type");
        ASSERT_EQ(cell.size(), 1u);
        types.push_back(all_text(cell[0]));
    }
    EXPECT_EQ(types, (std::vector<std::string>{"\xE2\x80\x93", "Tug", "\xE2\x80\x93"}));  // an en dash when not known
}

TEST(Debrief, FileNamesAreSafeShortAndApartForHostileExerciseNames) {
    audit::AuditResult r;
    for (const char* e : {"morning/ex1.csv", "afternoon/ex1.csv", ".", "../../etc/passwd", "EX", "ex", "<script>alert(1)</script>", ""}) {
        audit::TrackResult t;
        t.summary.id = "x";
        t.summary.exercise = e;
        r.tracks.push_back(t);
    }
    const auto pages = debrief_pages(r);
    std::vector<std::string> names;
    for (const auto& p : pages) names.push_back(p.file);
    // "" is the run outside exercise mode: "run".
    EXPECT_EQ(names, (std::vector<std::string>{"morning_ex1.csv.html", "afternoon_ex1.csv.html", "exercise.html", "etc_passwd.html",
                                               "EX.html", "ex-2.html", "script_alert_1_script.html", "run.html"}));
    for (const auto& n : names) {
        EXPECT_EQ(n.find('/'), std::string::npos);
        EXPECT_NE(n[0], '.');
        EXPECT_LE(n.size(), 105u);
    }
    audit::AuditResult one;
    audit::TrackResult t;
    t.summary.exercise = std::string(300, 'a');
    one.tracks.push_back(t);
    EXPECT_EQ(debrief_pages(one)[0].file, std::string(100, 'a') + ".html");
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST(Debrief, CliWritesOnePagePerExerciseKeepsAForeignFileAndRefusesAPageName) {
    const test::TempDir dir;
    const std::vector<std::string> files = exercise_files(dir);
    const std::string base = "check --coast " + test::data_path("coast/uk_solent_land.geojson") + " --dims 50,10,5,5 --exercise-by file '" +
                             files[0] + "' '" + files[1] + "' -o '" + dir.file("r.geojson") + "'";
    const fs::path folder = dir.path() / "debrief";
    auto shoal = [&](const std::string& more) { return test::run_shoal(base + " " + more, dir.path() / "cache", dir.path() / "err.txt"); };

    // A page name is refused before any work: no report written.
    const test::Outcome refused = shoal("--debrief '" + dir.file("sheet.html") + "'");
    EXPECT_EQ(refused.status, 2) << refused.err;
    EXPECT_NE(refused.err.find("names a page"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir.file("r.geojson")));

    const test::Outcome ok = shoal("--debrief '" + folder.string() + "'");
    EXPECT_EQ(ok.status, 1) << "A grounds: " << ok.err;
    std::set<std::string> written;
    for (const auto& e : fs::directory_iterator(folder)) written.insert(e.path().filename().string());
    EXPECT_EQ(written, (std::set<std::string>{"ex1_b_.csv.html", "ex2.csv.html"})) << "the pages and nothing else";
    EXPECT_NE(read_text((folder / "ex2.csv.html").string()).find("<h1>Debrief: "), std::string::npos);
    EXPECT_NE(ok.out.find("debrief: 2 pages"), std::string::npos) << ok.out;

    // A file shoal did not write is kept, said, and the other page is still replaced.
    { std::ofstream(folder / "ex2.csv.html") << "my own notes"; }
    const test::Outcome again = shoal("--debrief '" + folder.string() + "'");
    EXPECT_EQ(again.status, 1) << again.err;
    EXPECT_EQ(read_text((folder / "ex2.csv.html").string()), "my own notes");
    EXPECT_NE(again.err.find("shoal did not write it"), std::string::npos) << again.err;
    EXPECT_NE(read_text((folder / "ex1_b_.csv.html").string()).find("shoal debrief"), std::string::npos);
    for (const auto& e : fs::directory_iterator(folder)) EXPECT_EQ(e.path().filename().string().find(".shoal.tmp"), std::string::npos);
}

/// Pixels of `png` (RGB) within `tol` of `rgb` in the rectangle [x0, x1) x [y0, y1).
std::size_t count_colour(GDALDataset& png, int x0, int y0, int x1, int y1, unsigned rgb, int tol) {
    const int w = x1 - x0, h = y1 - y0;
    std::vector<unsigned char> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    int bands[] = {1, 2, 3};
    if (png.RasterIO(GF_Read, x0, y0, w, h, px.data(), w, h, GDT_Byte, 3, bands, 3, 3L * w, 1) != CE_None) {
        ADD_FAILURE() << "the screenshot's pixels cannot be read: " << CPLGetLastErrorMsg();  // not "no pixel of that colour"
        return 0;
    }
    const int r = static_cast<int>((rgb >> 16) & 0xFF), g = static_cast<int>((rgb >> 8) & 0xFF), b = static_cast<int>(rgb & 0xFF);
    std::size_t n = 0;
    for (std::size_t k = 0; k < px.size(); k += 3)
        if (std::abs(px[k] - r) <= tol && std::abs(px[k + 1] - g) <= tol && std::abs(px[k + 2] - b) <= tol) ++n;
    return n;
}

TEST(Debrief, HeadlessChromiumShowsTheRun) {
    const char* chromium = "/usr/bin/chromium";
    if (!fs::exists(chromium)) GTEST_SKIP() << "no /usr/bin/chromium (Debian package chromium, scripts/install-deps.sh)";
    Fixture f;
    const std::vector<DebriefPage> pages = debrief_pages(f.result);
    const std::string page = f.dir.file("page.html"), shot = f.dir.file("shot.png");
    { std::ofstream(page, std::ios::binary) << debrief_html(f.result, f.grid, f.info, pages[0]); }
    const std::string cmd = std::string("timeout 60 ") + chromium + " --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir='" +
                            f.dir.file("profile") + "' --screenshot='" + shot + "' --window-size=1240,1754 'file://" + page + "' >'" +
                            f.dir.file("chromium.log") + "' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read_text(f.dir.file("chromium.log"));
    GDALAllRegister();
    GDALDatasetUniquePtr png(GDALDataset::Open(shot.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    ASSERT_TRUE(png) << "no screenshot: " << read_text(f.dir.file("chromium.log"));
    ASSERT_EQ(png->GetRasterXSize(), 1240);
    ASSERT_GE(png->GetRasterCount(), 3);
    const int h = png->GetRasterYSize();
    // The header comes first: its top 120 px hold text on white, no chart.
    EXPECT_EQ(count_colour(*png, 0, 0, 1240, 120, 0xe8dec3, 6), 0u);
    // Below it the picture: land as the grid sees it (sand), water (pale blue), and the grounded
    // track in red, all in the picture's place.
    const std::size_t land = count_colour(*png, 0, 120, 1240, h, 0xe8dec3, 6);
    const std::size_t water = count_colour(*png, 0, 120, 1240, h, 0xf3f8fc, 4);
    const std::size_t track = count_colour(*png, 0, 120, 1240, h, 0xd62728, 40);
    EXPECT_GT(land, 20000u) << "the Isle of Wight drawn";
    EXPECT_GT(water, 20000u);
    EXPECT_GT(track, 100u) << "the grounded track A in red";
}

}  // namespace
}  // namespace shoal::report
