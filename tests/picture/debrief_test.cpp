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

#include "util/gdal_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <map>
#include <set>
#include <sstream>
#include <array>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/picture/debrief.hpp>
#include <shoal/picture/plot.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/report/geojson_report.hpp>
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
    // The rules read in every situation, met or not: A gave way and held on (rule 15 not met);
    // the hostile trainee stood on and kept on (met); A and C had no risk of collision.
    audit::ConductRecord held, kept, no_duty;
    held.track = "A";
    held.track_index = 0;
    held.criterion = rules.id;
    held.other = hostile_id;
    held.situation = "crossing";
    held.role = "give-way";
    held.rules = {"15", "16", "8"};
    held.breached = {"15"};
    held.did = b4.did;
    kept = held;
    kept.track = hostile_id;
    kept.track_index = 1;
    kept.other = "A";
    kept.role = "stand-on";
    kept.rules = {"15", "17"};
    kept.breached = {};
    kept.did = "<b>H</b> kept her course (000) and speed (10.0 kn)";
    no_duty = held;
    no_duty.role = "";
    no_duty.rules = {};
    no_duty.breached = {};
    no_duty.did = "no risk of collision: CPA projected at the start 1.50 nm";
    r.assessment.conduct = {held, no_duty, kept};

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
    // Every situation, met or not, with the rules that applied.
    const auto conduct = with_class(scores, "conduct", "tr");
    ASSERT_EQ(conduct.size(), 3u);
    EXPECT_EQ(all_text(with_class(conduct[0], "rules")[0]), "15, 16, 8");
    EXPECT_EQ(all_text(with_class(conduct[0], "result")[0]), "not met: rule 15");
    EXPECT_EQ(with_class(conduct[0], "not-met").size(), 1u);
    EXPECT_EQ(all_text(with_class(conduct[1], "role")[0]), "no duty");
    EXPECT_EQ(all_text(with_class(conduct[1], "did")[0]), no_duty.did);
    EXPECT_EQ(with_class(conduct[1], "no-duty").size(), 1u);
    EXPECT_EQ(all_text(with_class(conduct[2], "track")[0]), hostile_id);
    EXPECT_EQ(all_text(with_class(conduct[2], "role")[0]), "stand-on");
    EXPECT_EQ(all_text(with_class(conduct[2], "rules")[0]), "15, 17");
    EXPECT_EQ(all_text(with_class(conduct[2], "did")[0]), kept.did);
    EXPECT_EQ(all_text(with_class(conduct[2], "result")[0]), "met");
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
    EXPECT_NE(again.err.find("shoal: error: '" + (folder / "ex2.csv.html").string() + "' exists and shoal did not write it"), std::string::npos)
        << again.err;
    EXPECT_NE(read_text((folder / "ex1_b_.csv.html").string()).find("shoal debrief"), std::string::npos);
    for (const auto& e : fs::directory_iterator(folder)) EXPECT_EQ(e.path().filename().string().find(".shoal.tmp"), std::string::npos);
    // A page not written is an error: said with --quiet too (before: a warning, left out).
    const test::Outcome quiet = shoal("--quiet --debrief '" + folder.string() + "'");
    EXPECT_EQ(quiet.status, 1) << quiet.err;
    EXPECT_NE(quiet.err.find("shoal: error: '" + (folder / "ex2.csv.html").string() + "' exists"), std::string::npos) << quiet.err;
    EXPECT_EQ(read_text((folder / "ex2.csv.html").string()), "my own notes");
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

// ---------------------------------------------------------------- pictures that tell the story

/// An instructor's exercise east of the Isle of Wight, every fix made here by dead reckoning
/// (10 s apart, 30 min, from 10:00:00Z): the trainee T1 sails east at 10 kn and turns to
/// starboard (140) from 10:08:00 to 10:14:00, then back to 090; the target C1 sails north at
/// 10 kn across her bow (T1 gives way); the target H1 sails west at 9 kn south of T1's track.
struct Story {
    struct Ship {
        std::string id, role;
        double lat, lon, sog;
        std::function<double(double)> heading;  ///< of seconds from the start
        std::vector<std::array<double, 3>> fixes{};  ///< time from the start, lat, lon
    };
    std::vector<Ship> ships{
        {"T1", "trainee", 50.735, -1.08, 10, [](double t) { return t >= 480 && t < 840 ? 140.0 : 90.0; }},
        {"C1", "target", 50.695, -1.025, 10, [](double) { return 0.0; }},
        {"H1", "target", 50.715, -0.93, 9, [](double) { return 270.0; }},
    };
    Story() {
        for (Ship& s : ships) {
            double lat = s.lat, lon = s.lon;
            for (int i = 0; i <= 180; ++i) {
                const double t = 10.0 * i, h = s.heading(t) * M_PI / 180, v = s.sog * 1852 / 3600 * 10;
                s.fixes.push_back({t, lat, lon});
                lat += v * std::cos(h) / 111200;
                lon += v * std::sin(h) / (111320 * std::cos(lat * M_PI / 180));
            }
        }
    }
    void write(const std::string& path) const {
        std::ofstream out(path);
        out << "id,role,time,lat,lon,sog,cog,heading\n";
        char line[200];
        for (const Ship& s : ships)
            for (const auto& f : s.fixes) {
                const int t = static_cast<int>(f[0]);
                const double h = s.heading(f[0]);
                std::snprintf(line, sizeof line, "%s,%s,2024-05-01T10:%02d:%02dZ,%.6f,%.6f,%.0f,%.1f,%.1f\n", s.id.c_str(), s.role.c_str(), t / 60,
                              t % 60, f[1], f[2], s.sog, h, h);
                out << line;
            }
    }
    /// The least distance (m) between two ships' reference points, by brute force: positions
    /// linear between the fixes, every 0.5 s, metres on a sphere of radius 6371 km (equirectangular
    /// at the pair's mean latitude): an answer found apart from shoal's local frame.
    std::pair<double, double> closest(const std::string& a, const std::string& b) const {
        const Ship* x = nullptr;
        const Ship* y = nullptr;
        for (const Ship& s : ships) {
            if (s.id == a) x = &s;
            if (s.id == b) y = &s;
        }
        auto at = [](const Ship& s, double t) {
            const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(t / 10), s.fixes.size() - 2);
            const double f = (t - s.fixes[k][0]) / 10;
            return std::pair{s.fixes[k][1] + f * (s.fixes[k + 1][1] - s.fixes[k][1]), s.fixes[k][2] + f * (s.fixes[k + 1][2] - s.fixes[k][2])};
        };
        double best = INFINITY, when = 0;
        for (double t = 0; t <= 1800; t += 0.5) {
            const auto [la, lo] = at(*x, t);
            const auto [lb, ob] = at(*y, t);
            const double r = 6371000, m = (la + lb) / 2 * M_PI / 180;
            const double d = r * std::hypot((lb - la) * M_PI / 180, (ob - lo) * M_PI / 180 * std::cos(m));
            if (d < best) best = d, when = t;
        }
        return {best, when};
    }
};

const char* const story_assessment = R"({"criteria": [
 {"id": "cpa-0.5nm", "kind": "cpa", "limit": 926, "penalty": 10},
 {"id": "rules", "kind": "colreg", "penalty": 20},
 {"id": "bembridge-6kn", "kind": "speed_limit", "limit": 6, "penalty": 5,
  "area": [[-1.06,50.70],[-1.04,50.70],[-1.04,50.715],[-1.06,50.715]], "area_name": "Bembridge approach"},
 {"id": "closed", "kind": "no_entry", "penalty": 1, "per": "second",
  "area": [[-1.00,50.72],[-0.98,50.72],[-0.98,50.735],[-1.00,50.735]], "area_name": "Firing range"}
], "pass_mark": 30})";

/// The story audited by the CLI as an instructor runs it: roles from the file's column, the
/// assessment, the picture and the debrief.
struct StoryRun {
    test::TempDir dir;
    Story story;
    test::Outcome outcome;
    std::string plot, page;
    StoryRun() {
        story.write(dir.file("ex1.csv"));
        std::ofstream(dir.file("assess.json")) << story_assessment;
        outcome = test::run_shoal("check --coast " + test::data_path("coast/uk_solent_land.geojson") +
                                      " --dims 60,12,6,6 --role-column role --assess '" + dir.file("assess.json") + "' --plot '" +
                                      dir.file("plot.svg") + "' --debrief '" + dir.file("debrief") + "' -o '" + dir.file("r.geojson") + "' '" +
                                      dir.file("ex1.csv") + "'",
                                  dir.path() / "cache", dir.path() / "err.txt");
        plot = read_text(dir.file("plot.svg"));
        page = read_text((dir.path() / "debrief" / "run.html").string());
    }
};

/// The numbers in "CPA 646 m 10:12:02Z" labels, in document order.
std::vector<double> cpa_metres(const CPLXMLNode* n) {
    std::vector<double> out;
    for (const auto* l : with_class(n, "cpa-distance")) {
        double m = NAN;
        if (std::sscanf(all_text(l).c_str(), "CPA %lf m", &m) == 1) out.push_back(m);
    }
    return out;
}

/// The points of a <polygon>.
std::vector<std::pair<double, double>> polygon_points(const CPLXMLNode* p) {
    std::vector<std::pair<double, double>> out;
    std::string pts = attr(p, "points");
    for (char& c : pts)
        if (c == ',') c = ' ';
    std::istringstream in(pts);
    double x, y;
    while (in >> x >> y) out.emplace_back(x, y);
    return out;
}

TEST(DebriefPictures, TheTraineeInHerColourWithArrowsAndTicksTheAreasTheClosestApproachesAndTheManoeuvres) {
    StoryRun run;
    ASSERT_EQ(run.outcome.status, 0) << run.outcome.err;
    ASSERT_FALSE(run.plot.empty());
    ASSERT_FALSE(run.page.empty());
    // The situations shoal found (stdout), and the closest approaches found here by brute force.
    EXPECT_NE(run.outcome.out.find("T1 x C1  give-way T1"), std::string::npos) << run.outcome.out;
    const auto [cpa_c1, when_c1] = run.story.closest("T1", "C1");
    const auto [cpa_h1, when_h1] = run.story.closest("T1", "H1");
    ASSERT_LT(cpa_c1, 3704);
    ASSERT_LT(cpa_h1, 3704);

    for (const std::string* text : {&run.plot, &run.page}) {
        SCOPED_TRACE(text == &run.plot ? "--plot" : "--debrief");
        std::string error;
        const test::XmlPtr doc = test::parse_xml(*text, &error);
        ASSERT_TRUE(doc) << error;
        const CPLXMLNode* top = nullptr;  // <svg> or <html>, after the declaration or doctype
        for (const CPLXMLNode* n = doc.get(); n; n = n->psNext)
            if (n->eType == CXT_Element && n->pszValue[0] != '?' && n->pszValue[0] != '!') top = n;
        ASSERT_NE(top, nullptr);
        const CPLXMLNode* overview = by_id(top, "overview");
        ASSERT_NE(overview, nullptr);
        // Every id once in the document (a link or a clip path to an id held twice takes the first).
        std::map<std::string, int> id_count;
        each_element(top, [&](const CPLXMLNode* e) {
            if (const std::string id = attr(e, "id"); !id.empty()) ++id_count[id];
        });
        for (const auto& [id, count] : id_count) EXPECT_EQ(count, 1) << "id '" << id << "'";
        // The trainee's track alone in her blue, the targets in grey.
        const auto trainee = with_class(overview, "trainee", "path");
        ASSERT_EQ(trainee.size(), 1u);
        EXPECT_EQ(attr(trainee[0], "stroke"), "#0a58ca");
        EXPECT_NE(all_text(trainee[0]).find("T1"), std::string::npos);
        EXPECT_EQ(with_class(overview, "track", "path").size(), 3u);
        // Direction arrows: the first (on the leg east) points east: its tip right of its base.
        const auto arrows = with_class(overview, "direction", "polygon");
        ASSERT_GE(arrows.size(), 3u);
        const auto first = polygon_points(arrows[0]);
        ASSERT_EQ(first.size(), 3u);
        EXPECT_GT(first[0].first, first[1].first + 5);
        EXPECT_GT(first[0].first, first[2].first + 5);
        EXPECT_NEAR(first[1].second + first[2].second, 2 * first[0].second, 1.0) << "pointing along the track, not across";
        // Time ticks: 30 min of exercise, a tick every 5 min from T+5 to T+30, each saying when.
        std::set<std::string> minutes;
        for (const auto* t : with_class(overview, "time-tick", "line")) {
            minutes.insert(attr(t, "data-minutes"));
            EXPECT_NE(all_text(t).find("T+" + attr(t, "data-minutes") + ":00 10:"), std::string::npos) << all_text(t);
        }
        EXPECT_EQ(minutes, (std::set<std::string>{"5", "10", "15", "20", "25", "30"}));
        bool five = false;
        for (const auto* t : with_class(overview, "time-tick", "line")) five = five || all_text(t) == "T1: T+5:00 10:05:00Z UTC";
        EXPECT_TRUE(five) << "the T+5 tick at 10:05:00Z";
        // The areas drawn and named.
        ASSERT_EQ(with_class(overview, "no-entry", "polygon").size(), 1u);
        ASSERT_EQ(with_class(overview, "speed-limit", "polygon").size(), 1u);
        std::set<std::string> names;
        for (const auto* l : with_class(overview, "area-name")) names.insert(all_text(l));
        EXPECT_EQ(names, (std::set<std::string>{"Firing range (no entry)", "Bembridge approach (speed limit 6.0 kn)"}));
        // The closest approaches: both hulls and the line, the distance as the brute force finds it.
        const auto cpas = with_class(overview, "cpa", "g");
        ASSERT_EQ(cpas.size(), 2u);
        for (const auto* c : cpas) {
            EXPECT_EQ(with_class(c, "cpa-hull", "polygon").size(), 2u);
            EXPECT_EQ(with_class(c, "cpa-line", "line").size(), 1u);
        }
        std::vector<double> metres = cpa_metres(overview);
        std::sort(metres.begin(), metres.end());
        ASSERT_EQ(metres.size(), 2u);
        EXPECT_NEAR(metres[0], std::min(cpa_c1, cpa_h1), 5);
        EXPECT_NEAR(metres[1], std::max(cpa_c1, cpa_h1), 5);
        if (text == &run.page) {
            // The rules read in both of T1's situations (both crossings): give-way to C1 from
            // her port side, her 50-degree turn to starboard begun 1.31 nm off yet passing
            // 0.35 nm from C1 (rule 16); stand-on for H1, her turn back to port begun 1.69 nm
            // off while H1 could still act (rule 17).
            const auto conduct = with_class(by_id(top, "scores"), "conduct", "tr");
            ASSERT_EQ(conduct.size(), 2u);
            EXPECT_EQ(all_text(with_class(conduct[0], "other")[0]), "C1");
            EXPECT_EQ(all_text(with_class(conduct[0], "situation")[0]), "crossing");
            EXPECT_EQ(all_text(with_class(conduct[0], "role")[0]), "give-way");
            EXPECT_EQ(all_text(with_class(conduct[0], "rules")[0]), "15, 16, 8");
            EXPECT_EQ(all_text(with_class(conduct[0], "did")[0]), "T1 altered course 50 degrees to starboard from 10:08:00Z, 1.31 nm from C1");
            EXPECT_EQ(all_text(with_class(conduct[0], "result")[0]), "not met: rule 16");
            EXPECT_EQ(all_text(with_class(conduct[1], "other")[0]), "H1");
            EXPECT_EQ(all_text(with_class(conduct[1], "role")[0]), "stand-on");
            EXPECT_EQ(all_text(with_class(conduct[1], "rules")[0]), "15, 17");
            EXPECT_EQ(all_text(with_class(conduct[1], "result")[0]), "not met: rule 17");
        }
        // The manoeuvres: T1's turns at 10:08:00 and 10:14:00.
        std::set<std::string> turns;
        for (const auto* m : with_class(overview, "manoeuvre", "g")) {
            EXPECT_EQ(attr(m, "data-track"), "T1");
            const std::string t = all_text(m);
            turns.insert(t.substr(t.find(" at ") + 4, 9));
        }
        EXPECT_EQ(turns, (std::set<std::string>{"10:08:00Z", "10:14:00Z"}));
        // A panel per closest approach (ids cpa-1, cpa-2): both hulls, each along her heading then
        // (C1 north: taller than wide on the page; H1 west: wider), the line and the distance.
        for (const char* id : {"cpa-1", "cpa-2"}) {
            const CPLXMLNode* panel = by_id(top, id);
            ASSERT_NE(panel, nullptr) << id;
            const auto hulls = with_class(panel, "cpa", "polygon");
            ASSERT_EQ(hulls.size(), 2u) << id;
            ASSERT_EQ(with_class(panel, "cpa-line", "line").size(), 1u);
            const auto ids = with_class(panel, "track-id", "g");
            ASSERT_EQ(ids.size(), 2u);
            const std::string other = all_text(ids[1]);
            ASSERT_TRUE(other == "C1" || other == "H1") << other;
            EXPECT_EQ(all_text(ids[0]), "T1") << "the trainee first";
            double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
            for (const auto& [x, y] : polygon_points(hulls[1])) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            if (other == "C1") EXPECT_GT(y1 - y0, 2 * (x1 - x0)) << id;
            else EXPECT_GT(x1 - x0, 2 * (y1 - y0)) << id;
            const std::vector<double> m = cpa_metres(panel);
            ASSERT_EQ(m.size(), 1u);
            EXPECT_NEAR(m[0], other == "C1" ? cpa_c1 : cpa_h1, 5);
        }
    }
    // The debrief's event headings give exercise time beside UTC.
    EXPECT_NE(run.page.find("<span class=\"exercise-time\">T+"), std::string::npos);
    // (the brute force's moment to its 0.5 s step: a second either side)
    bool found = false;
    for (const double d : {-1.0, 0.0, 1.0}) {
        const int s = static_cast<int>(std::floor(when_c1 + d));
        char at[32];
        std::snprintf(at, sizeof at, "(T+%d:%02d)", s / 60, s % 60);
        found = found || run.page.find(at) != std::string::npos;
    }
    EXPECT_TRUE(found) << "the closest approach to C1 in exercise time, near T+" << when_c1 << " s";
}

/// Runs headless Chromium on `url` at `width` x `height`; the screenshot, or null.
GDALDatasetUniquePtr screenshot(const test::TempDir& dir, const std::string& url, int width, int height, const std::string& name) {
    const std::string shot = dir.file(name + ".png");
    const std::string cmd = "timeout 90 /usr/bin/chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir='" +
                            dir.file("profile-" + name) + "' --screenshot='" + shot + "' --window-size=" + std::to_string(width) + "," +
                            std::to_string(height) + " '" + url + "' >'" + dir.file(name + ".log") + "' 2>&1";
    if (std::system(cmd.c_str()) != 0) {
        ADD_FAILURE() << read_text(dir.file(name + ".log"));
        return nullptr;
    }
    GDALAllRegister();
    return GDALDatasetUniquePtr(GDALDataset::Open(shot.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
}

TEST(DebriefPictures, HeadlessChromiumAtTwoWidthsShowsTheTraineeTheAreasAndTheClosestApproaches) {
    if (!fs::exists("/usr/bin/chromium")) GTEST_SKIP() << "no /usr/bin/chromium (Debian package chromium, scripts/install-deps.sh)";
    StoryRun run;
    ASSERT_EQ(run.outcome.status, 0) << run.outcome.err;
    const std::string page = "file://" + (run.dir.path() / "debrief" / "run.html").string();
    // The whole page (a window taller than it) at a desktop and a narrow width.
    for (const int width : {1240, 700}) {
        SCOPED_TRACE("width " + std::to_string(width));
        const GDALDatasetUniquePtr png = screenshot(run.dir, page, width, 7000, "page-" + std::to_string(width));
        ASSERT_TRUE(png);
        ASSERT_EQ(png->GetRasterXSize(), width);
        const int h = png->GetRasterYSize();
        // The trainee's blue (track, arrows, ticks, her hull in the panels), the no-entry area's
        // pale red over the water and the speed-limit area's pale amber, somewhere on the page.
        EXPECT_GT(count_colour(*png, 0, 0, width, h, 0x0a58ca, 30), 300u) << "the trainee's track in her blue";
        EXPECT_GT(count_colour(*png, 0, 0, width, h, 0xefdee2, 4), 500u) << "the no-entry area filled";
        EXPECT_GT(count_colour(*png, 0, 0, width, h, 0xf2ecdd, 4), 500u) << "the speed-limit area filled";
    }
    // The picture alone (--plot), at two widths: the trainee's blue in the overview and in the
    // closest approaches' panels below it.
    for (const int width : {1240, 800}) {
        SCOPED_TRACE("plot width " + std::to_string(width));
        const GDALDatasetUniquePtr png = screenshot(run.dir, "file://" + run.dir.file("plot.svg"), width, 2600, "plot-" + std::to_string(width));
        ASSERT_TRUE(png);
        const int h = png->GetRasterYSize();
        EXPECT_GT(count_colour(*png, 0, 0, width, h, 0x0a58ca, 30), 300u);
    }
}

}  // namespace
}  // namespace shoal::report
