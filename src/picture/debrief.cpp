#include <shoal/picture/debrief.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string_view>
#include <tuple>

#include <shoal/picture/plot.hpp>
#include <shoal/report/geojson_report.hpp>
#include "track/ship_type.hpp"
#include <shoal/util/error.hpp>
#include <shoal/version.hpp>

namespace shoal::report {

namespace {

namespace fs = std::filesystem;

constexpr const char* generator_mark = "<meta name=\"generator\" content=\"shoal debrief\"/>";

std::string esc(std::string_view s) { return markup_text(s); }

/// A number for the page: an en dash when not finite (plain text: escaped like any other).
std::string fixed(double v, int decimals) { return fixed_text(v, decimals, "\xE2\x80\x93"); }

// ---------------------------------------------------------------- file names

/// ASCII letters, digits, '.', '-' and '_' kept, anything else '_' (runs of it as one), no
/// leading dots, dashes or underscores, at most 100 bytes.
std::string safe_stem(const std::string& s) {
    std::string out;
    for (const char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        const bool keep = c < 0x80 && (std::isalnum(c) || c == '.' || c == '-' || c == '_');
        if (keep && ch != '_') out += ch;
        else if (out.empty() || out.back() != '_') out += '_';
    }
    const std::size_t first = out.find_first_not_of("._-");
    out = first == std::string::npos ? std::string() : out.substr(first);
    if (out.size() > 100) out.resize(100);
    while (!out.empty() && (out.back() == '.' || out.back() == '_')) out.pop_back();
    return out.empty() ? "exercise" : out;
}

/// The path components of an exercise name ("a/b/c" -> a, b, c), "." and empty ones left out.
std::vector<std::string> components(const std::string& name) {
    std::vector<std::string> out;
    std::string part;
    for (const char ch : name + "/") {
        if (ch == '/' || ch == '\\') {
            if (!part.empty() && part != ".") out.push_back(part);
            part.clear();
        } else {
            part += ch;
        }
    }
    return out;
}

std::string lower(std::string s) {
    for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return s;
}

/// File names for `names` (see the header): the last k components, k as small as keeps them apart.
std::vector<std::string> file_names(const std::vector<std::string>& names) {
    std::vector<std::vector<std::string>> parts;
    std::size_t most = 1;
    for (const auto& n : names) {
        parts.push_back(components(n));
        most = std::max(most, parts.back().size());
    }
    auto stem = [&](std::size_t i, std::size_t k) {
        const auto& p = parts[i];
        std::string s;
        for (std::size_t c = p.size() > k ? p.size() - k : 0; c < p.size(); ++c) s += (s.empty() ? "" : "_") + p[c];
        return safe_stem(s);
    };
    std::vector<std::string> stems;
    for (std::size_t k = 1; k <= most; ++k) {
        stems.clear();
        std::set<std::string> seen;
        bool apart = true;
        for (std::size_t i = 0; i < names.size(); ++i) {
            stems.push_back(stem(i, k));
            apart = seen.insert(lower(stems.back())).second && apart;
        }
        if (apart) break;
    }
    std::set<std::string> taken;
    std::vector<std::string> out;
    for (const std::string& s : stems) {
        std::string name = s;
        for (int n = 2; !taken.insert(lower(name)).second; ++n) name = s + "-" + std::to_string(n);
        out.push_back(name + ".html");
    }
    return out;
}

// ---------------------------------------------------------------- what the page lists

/// One line of the events section: a track event, a ship-to-ship encounter or a breach.
struct Item {
    double time_s = 0;
    int order = 0;  ///< among equal times: contacts, encounters, close passes, breaches
    std::string kind;       ///< data-kind: an EventKind name, "collision", "close_quarters", "breach"
    std::string heading;    ///< "grounding", "collision", "breach of cpa-1", ...
    std::string who;        ///< the track(s)
    std::string text;       ///< the description
    ZoomSpec zoom;
};

std::string track_words(const audit::TrackSummary& t) {
    return t.name.empty() || t.name == t.id ? t.id : t.id + " (" + t.name + ")";
}

std::string kind_heading(audit::EventKind k) {
    switch (k) {
    case audit::EventKind::grounding: return "Grounding";
    case audit::EventKind::alongside: return "Alongside (not a grounding)";
    case audit::EventKind::contact_at_start: return "In contact at the first fix";
    case audit::EventKind::expected_contact: return "Contact in an expected-contact area";
    case audit::EventKind::close_pass: return "Close pass";
    case audit::EventKind::chart_disagrees: return "The chart disagrees with the traffic (not a grounding)";
    }
    return "Event";
}

/// A criterion's kind in words, and the unit of its value.
std::pair<const char*, const char*> criterion_words(audit::CriterionKind k) {
    switch (k) {
    case audit::CriterionKind::land_clearance: return {"clearance to land or hazards", "m"};
    case audit::CriterionKind::under_keel_clearance: return {"under-keel clearance", "m"};
    case audit::CriterionKind::cpa: return {"closest approach to another ship", "m"};
    case audit::CriterionKind::speed_limit: return {"speed limit in an area", "kn"};
    case audit::CriterionKind::no_entry: return {"no entry into an area", ""};
    case audit::CriterionKind::close_quarters_time: return {"time in close quarters", "s"};
    case audit::CriterionKind::colreg: return {"conduct under the collision rules (COLREG 8, 13-17)", "m"};
    }
    return {"criterion", ""};
}

/// What a criterion asks, in words: its kind, limit and parameters.
std::string criterion_asks(const audit::Criterion& c) {
    const auto [words, unit] = criterion_words(c.kind);
    std::string s = words;
    auto deg = [](double v) { return fixed(v, v == std::round(v) ? 0 : 1) + " degrees"; };
    auto nm = [](double m) { return fixed(m / 1852, 2) + " nm"; };
    switch (c.kind) {
        case audit::CriterionKind::land_clearance:
        case audit::CriterionKind::under_keel_clearance:
        case audit::CriterionKind::cpa: s += " at least " + fixed(c.limit, 1) + " " + unit; break;
        case audit::CriterionKind::speed_limit: s += " at most " + fixed(c.limit, 1) + " kn"; break;
        case audit::CriterionKind::no_entry: break;
        case audit::CriterionKind::close_quarters_time: s += " at most " + fixed(c.limit, 0) + " s per encounter"; break;
        case audit::CriterionKind::colreg: {
            const audit::ConductOptions& o = c.colreg;
            s += ": situations judged from " + nm(o.range_m) + ", head-on within " + deg(o.head_on_deg) + ", overtaking from 112.5 to 247.5 degrees; "
                 "the rules ask something when the CPA is under " + nm(o.cpa_m) + "; the give-way ship acts from at least " + nm(o.early_range_m) +
                 " off, by at least " + deg(o.min_course_deg) + " of course or " + fixed(100 * o.min_speed_change, 0) + "% of speed, and passes " +
                 nm(o.cpa_m) + " clear; the stand-on ship keeps her course and speed until the give-way ship is plainly not acting";
            break;
        }
    }
    if (!c.area_name.empty()) s += " in " + c.area_name;
    return s;
}

std::string penalty_words(const audit::Criterion& c) {
    const char* per = "breach";
    switch (c.per) {
        case audit::PenaltyPer::second: per = "second"; break;
        case audit::PenaltyPer::metre: per = c.kind == audit::CriterionKind::speed_limit ? "knot over" : "metre short"; break;
        case audit::PenaltyPer::breach: break;
    }
    return fixed(c.penalty, c.penalty == std::round(c.penalty) ? 0 : 2) + " per " + per;
}

/// The size of a track's hull (the longest chord of the first pose outline that has one),
/// metres in the grid's frame; 0 unknown.
double hull_length(const audit::TrackResult& t, const geo::LocalFrame& frame) {
    for (const audit::Pose& p : t.poses) {
        std::vector<geo::XY> pts;
        for (const geo::LonLat& q : p.hull) {
            try {
                pts.push_back(frame.forward(q));
            } catch (const InputError&) {  // a point the frame cannot take: left out
            }
        }
        double m = 0;
        for (std::size_t a = 0; a < pts.size(); ++a)
            for (std::size_t b = a + 1; b < pts.size(); ++b) m = std::max(m, geo::distance(pts[a], pts[b]));
        if (m > 0) return m;
    }
    return 0;
}

/// Fills the pages' lists of encounters, approaches, situations, breaches and scores, one pass
/// over each of the run's lists (DebriefPage::indexed).
void index_pages(const audit::AuditResult& r, std::vector<DebriefPage>& pages) {
    constexpr std::size_t none = static_cast<std::size_t>(-1);
    std::vector<std::size_t> page_of(r.tracks.size(), none);
    std::map<std::string, std::size_t> by_exercise;
    for (std::size_t k = 0; k < pages.size(); ++k) {
        pages[k].indexed = true;
        by_exercise.emplace(pages[k].exercise, k);
        for (const std::size_t ti : pages[k].tracks)
            if (ti < page_of.size()) page_of[ti] = k;
    }
    // The page both tracks are on, or none.
    const auto pair_page = [&](std::size_t a, std::size_t b) {
        return a < page_of.size() && b < page_of.size() && page_of[a] == page_of[b] ? page_of[a] : none;
    };
    // An exercise's page: "" is the whole run's ("run").
    const auto exercise_page = [&](const std::string& e) {
        const auto it = by_exercise.find(e.empty() ? "run" : e);
        return it == by_exercise.end() ? none : it->second;
    };
    for (std::size_t i = 0; i < r.encounters.events.size(); ++i)
        if (const auto k = pair_page(r.encounters.events[i].a.track, r.encounters.events[i].b.track); k != none) pages[k].encounters.push_back(i);
    for (std::size_t i = 0; i < r.encounters.approaches.size(); ++i)
        if (const auto k = pair_page(r.encounters.approaches[i].a, r.encounters.approaches[i].b); k != none) pages[k].approaches.push_back(i);
    for (std::size_t i = 0; i < r.situations.size(); ++i)
        if (const auto k = pair_page(r.situations[i].a, r.situations[i].b); k != none) pages[k].situations.push_back(i);
    for (std::size_t i = 0; i < r.assessment.breaches.size(); ++i)
        if (const auto k = exercise_page(r.assessment.breaches[i].exercise); k != none) pages[k].breaches.push_back(i);
    for (std::size_t i = 0; i < r.assessment.scores.size(); ++i)
        if (const auto k = exercise_page(r.assessment.scores[i].exercise); k != none) pages[k].scores.push_back(i);
}

/// `page` with its lists (DebriefPage::indexed): as it is when debrief_pages made it, else found
/// by the same rules.
DebriefPage indexed(const audit::AuditResult& r, const DebriefPage& page) {
    if (page.indexed) return page;
    std::vector<DebriefPage> one{page};
    index_pages(r, one);
    return one[0];
}

std::vector<Item> page_items(const audit::AuditResult& r, const grid::CoastGrid& g, const DebriefPage& page) {
    std::vector<Item> items;
    std::map<std::string, std::size_t> by_id;  // track id -> index, within the page
    for (const std::size_t ti : page.tracks) by_id.emplace(r.tracks[ti].summary.id, ti);
    for (const std::size_t ti : page.tracks) {
        const auto& t = r.tracks[ti];
        for (const audit::Event& e : t.events) {
            Item it;
            it.time_s = e.start_s;
            it.order = audit::is_contact(e.kind) ? 0 : 2;
            it.kind = audit::to_string(e.kind);
            it.heading = kind_heading(e.kind);
            it.who = track_words(t.summary) + (r.has_encounters && t.summary.role == audit::Role::target ? " [target]" : "");
            it.text = event_description(t.summary, e);
            it.zoom.tracks = {ti};
            it.zoom.event = &e;
            it.zoom.centre = e.point;
            it.zoom.start_s = e.start_s - 120;
            it.zoom.end_s = e.end_s + 120;
            it.zoom.tooltip = it.text;
            items.push_back(std::move(it));
        }
    }
    if (r.has_encounters)
        for (const std::size_t ei : page.encounters) {
            const audit::Encounter& e = r.encounters.events[ei];
            const auto& a = r.tracks[e.a.track].summary;
            const auto& b = r.tracks[e.b.track].summary;
            Item it;
            it.time_s = e.start_s;
            it.order = 1;
            it.kind = audit::to_string(e.kind);
            it.heading = e.kind == audit::EncounterKind::collision ? "Collision" : "Close quarters";
            it.who = track_words(a) + " and " + track_words(b);
            it.text = it.heading + " of " + it.who + " from " + iso_time(e.start_s) + " to " + iso_time(e.end_s) + " (" +
                      duration_words(e.end_s - e.start_s) + "); least hull-to-hull clearance " + fixed(e.min_clearance_m, 1) +
                      " m, reference points " + fixed(e.distance_m, 0) + " m apart";
            it.zoom.tracks = {e.a.track, e.b.track};
            it.zoom.hulls = {e.a.hull, e.b.hull};
            it.zoom.centre = e.point;
            it.zoom.start_s = e.start_s - 120;
            it.zoom.end_s = e.end_s + 120;
            it.zoom.kind = it.kind;
            it.zoom.time_label = clock_text(e.start_s, "?");
            it.zoom.tooltip = it.text;
            double hull_m = 0;
            for (const auto* ship : {&e.a, &e.b}) {
                std::vector<geo::XY> pts;
                for (const geo::LonLat& q : ship->hull) pts.push_back(g.frame().forward(q));
                for (std::size_t i = 0; i < pts.size(); ++i)
                    for (std::size_t j = i + 1; j < pts.size(); ++j) hull_m = std::max(hull_m, geo::distance(pts[i], pts[j]));
            }
            it.zoom.size_m = std::max({8 * hull_m, 2.5 * e.distance_m, 100.0});
            items.push_back(std::move(it));
        }
    if (r.has_assessment)
        for (const std::size_t bi : page.breaches) {
            const audit::Breach& b = r.assessment.breaches[bi];
            const auto t = by_id.find(b.track);
            Item it;
            it.time_s = std::isfinite(b.start_s) ? b.start_s : b.worst_s;
            it.order = 3;
            it.kind = "breach";
            const auto [words, unit] = criterion_words(b.kind);
            it.heading = "Breach of " + b.criterion + (b.rule.empty() ? std::string() : ", rule " + b.rule) + " (" + words + ")";
            it.who = t != by_id.end() ? track_words(r.tracks[t->second].summary) : b.track;
            if (!b.other.empty()) it.who += " with " + b.other;
            std::string text = it.heading + " by " + it.who;
            if (std::isfinite(b.start_s)) {
                text += " from " + iso_time(b.start_s);
                if (std::isfinite(b.end_s) && b.end_s > b.start_s) text += " to " + iso_time(b.end_s) + " (" + duration_words(b.end_s - b.start_s) + ")";
            }
            if (b.kind == audit::CriterionKind::colreg && std::isfinite(b.value))
                text += "; closest approach " + fixed(b.value, 0) + " m (the criterion asks at least " + fixed(b.limit, 0) + " m when acting)";
            else if (std::isfinite(b.value))
                text += "; worst " + fixed(b.value, 1) + (*unit ? std::string(" ") + unit : "") + " against a limit of " + fixed(b.limit, 1) +
                        (*unit ? std::string(" ") + unit : "") + (std::isfinite(b.worst_s) ? " at " + clock_text(b.worst_s, "?") : "");
            text += "; penalty " + fixed(b.penalty, 1);
            if (!b.asked.empty() || !b.did.empty()) text += ". Asked: " + b.asked + ". What happened: " + b.did;
            else if (!b.detail.empty()) text += "; " + b.detail;
            it.text = text;
            if (t != by_id.end()) {
                it.zoom.tracks = {t->second};
                if (const auto o = by_id.find(b.other); !b.other.empty() && o != by_id.end()) it.zoom.tracks.push_back(o->second);
                it.zoom.centre = {b.lon, b.lat};
                it.zoom.start_s = std::isfinite(b.start_s) ? b.start_s : b.worst_s;
                it.zoom.end_s = std::isfinite(b.end_s) ? b.end_s : b.worst_s;
                it.zoom.kind = "breach";
                it.zoom.time_label = std::isfinite(b.worst_s) ? "worst " + clock_text(b.worst_s, "?") : "";
                it.zoom.tooltip = text;
                const double hull_m = hull_length(r.tracks[t->second], g.frame());
                it.zoom.size_m = std::max({hull_m > 0 ? 8 * hull_m : 800.0, b.kind == audit::CriterionKind::cpa || b.kind == audit::CriterionKind::colreg ? 2.5 * b.value : 0.0,
                                           b.kind == audit::CriterionKind::land_clearance ? 3 * b.limit : 0.0, 100.0});
                if (!std::isfinite(it.zoom.size_m)) it.zoom.size_m = 0;
            }
            items.push_back(std::move(it));
        }
    std::stable_sort(items.begin(), items.end(), [](const Item& x, const Item& y) {
        if (x.time_s != y.time_s && !std::isnan(x.time_s) && !std::isnan(y.time_s)) return x.time_s < y.time_s;
        if (std::isnan(x.time_s) != std::isnan(y.time_s)) return !std::isnan(x.time_s);
        return x.order < y.order;
    });
    return items;
}

// ---------------------------------------------------------------- the page

/// The page's style: screen and A4 print, nothing fetched.
constexpr const char* page_style = R"(
@page { size: A4; margin: 12mm; }
* { box-sizing: border-box; }
body { font-family: "DejaVu Sans", Verdana, Arial, Helvetica, sans-serif; font-size: 10.5pt; color: #222222; margin: 16px auto; max-width: 1040px; padding: 0 12px; }
h1 { font-size: 18pt; margin: 0 0 4px 0; }
h2 { font-size: 13pt; margin: 18px 0 6px 0; border-bottom: 1px solid #999999; }
h3 { font-size: 11pt; margin: 0 0 4px 0; }
table { border-collapse: collapse; width: 100%; margin: 4px 0 10px 0; font-size: 9.5pt; }
th, td { border: 1px solid #bbbbbb; padding: 3px 5px; text-align: left; vertical-align: top; }
th { background: #eeeeee; }
td.num { text-align: right; white-space: nowrap; }
table.facts th { width: 22%; }
svg { max-width: 100%; height: auto; display: block; }
.picture svg { margin: 0 auto; }
.none { color: #555555; font-style: italic; }
article.event { display: flex; gap: 12px; align-items: flex-start; border-top: 1px solid #dddddd; padding: 8px 0; break-inside: avoid; page-break-inside: avoid; }
article.event .words { flex: 1 1 50%; }
article.event figure { flex: 0 0 auto; margin: 0; width: 340px; max-width: 48%; }
div.cpa-panels { display: flex; flex-wrap: wrap; gap: 12px; }
figure.cpa { margin: 0; width: 340px; max-width: 100%; break-inside: avoid; page-break-inside: avoid; }
figure.cpa figcaption { font-size: 9pt; }
.exercise-time { color: #555555; font-weight: normal; }
td.pass { color: #1a7f37; font-weight: bold; }
td.fail { color: #b42318; font-weight: bold; }
p.verdict { margin: 2px 0 6px 0; }
.kind { display: inline-block; width: 10px; height: 10px; margin-right: 6px; border-radius: 2px; }
footer { margin-top: 18px; font-size: 8.5pt; color: #555555; }
tr { break-inside: avoid; page-break-inside: avoid; }
@media print {
  body { max-width: none; margin: 0; padding: 0; font-size: 9.5pt; }
  section#picture { break-after: page; page-break-after: always; }
  h2 { break-after: avoid; page-break-after: avoid; }
  section { break-inside: auto; }
}
)";

/// An <svg> element for inline use: the namespace the HTML parser gives it anyway is left out,
/// so the page names no http(s) address at all.
std::string inline_svg(std::string svg) {
    const std::string ns = " xmlns=\"http://www.w3.org/2000/svg\"";
    if (const auto at = svg.find(ns); at != std::string::npos) svg.erase(at, ns.size());
    return svg;
}

std::string party_ids(const audit::AuditResult& r, const audit::ColregEncounter& c, audit::Party p) {
    const std::string& a = r.tracks.at(c.a).summary.id;
    const std::string& b = r.tracks.at(c.b).summary.id;
    switch (p) {
    case audit::Party::a: return a;
    case audit::Party::b: return b;
    case audit::Party::both: return "both (" + a + ", " + b + ")";
    case audit::Party::neither: break;
    }
    return "neither";
}

std::string action_words(const audit::Manoeuvre& m) {
    if (std::isnan(m.time_s)) return "none";
    return std::string(m.course && m.speed ? "course and speed" : m.course ? "course" : "speed") + " at " + clock_text(m.time_s, "?");
}

/// "3 min 20 s" for a TCPA, "opening (40 s ago)" when the ships were already opening.
std::string tcpa_words(double s) {
    if (!std::isfinite(s)) return "&#8211;";
    return s < 0 ? "opening (" + duration_words(-s) + " ago)" : duration_words(s);
}

void row(std::string& out, const char* th, const std::string& td_escaped) {
    out += "<tr><th>";
    out += th;
    out += "</th><td>" + td_escaped + "</td></tr>\n";
}

}  // namespace

std::vector<DebriefPage> debrief_pages(const audit::AuditResult& result) {
    std::vector<DebriefPage> pages;
    std::map<std::string, std::size_t> at;
    for (std::size_t ti = 0; ti < result.tracks.size(); ++ti) {
        const std::string& e = result.tracks[ti].summary.exercise;
        const std::string name = e.empty() ? "run" : e;
        auto [it, fresh] = at.emplace(name, pages.size());
        if (fresh) {
            DebriefPage& fresh_page = pages.emplace_back();
            fresh_page.exercise = name;
        }
        pages[it->second].tracks.push_back(ti);
    }
    if (pages.empty()) pages.emplace_back().exercise = "run";
    std::vector<std::string> names;
    for (const auto& p : pages) names.push_back(p.exercise);
    const std::vector<std::string> files = file_names(names);
    for (std::size_t k = 0; k < pages.size(); ++k) pages[k].file = files[k];
    index_pages(result, pages);
    return pages;
}

std::string debrief_html(const audit::AuditResult& result, const grid::CoastGrid& grid, const RunInfo& info, const DebriefPage& page_given,
                         const DebriefOptions& options) {
    const audit::AuditResult& r = result;
    const DebriefPage page = indexed(r, page_given);
    std::string out;
    out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n";
    out += generator_mark;
    out += "\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<title>Debrief: " + esc(page.exercise) +
           "</title>\n<style>" + std::string(page_style) + "</style>\n</head>\n<body>\n";

    // Header: exercise, time span, chart and grid, hull and rules.
    double first = NAN, last = NAN;
    std::size_t trainees = 0, targets = 0;
    for (const std::size_t ti : page.tracks) {
        const auto& s = r.tracks[ti].summary;
        if (std::isfinite(s.start_s)) first = std::isnan(first) ? s.start_s : std::min(first, s.start_s);
        if (std::isfinite(s.end_s)) last = std::isnan(last) ? s.end_s : std::max(last, s.end_s);
        (s.role == audit::Role::target ? targets : trainees) += 1;
    }
    out += "<header>\n<h1>Debrief: " + esc(page.exercise) + "</h1>\n<table class=\"facts\">\n";
    row(out, "Exercise", "<span class=\"exercise\">" + esc(page.exercise) + "</span>");
    row(out, "Time span",
        std::isfinite(first) ? esc(date_clock_text(first) + " to " + date_clock_text(last) + " (" + duration_words(last - first) +
                                   "); exercise time T+ counts from the first fix, " + date_clock_text(first))
                             : "no fixes");
    row(out, "Ships",
        esc(std::to_string(page.tracks.size()) + " tracks" +
            (r.has_encounters ? ": " + std::to_string(trainees) + " trainee" + (trainees == 1 ? "" : "s") + ", " + std::to_string(targets) +
                                    " target" + (targets == 1 ? "" : "s")
                              : "")));
    row(out, "Chart", esc(info.coast));
    row(out, "World", info.world == audit::World::simulated
                          ? esc("simulated: the chart is the world (a contact under way is a grounding)")
                          : esc("real: the chart is a model (a contact is a grounding when the vessel's motion says so)"));
    row(out, "Grid", esc(info.frame + "; cells of " + fixed(info.cell_m, 0) + " m; fingerprint " + info.grid_fingerprint));
    row(out, "Hull", esc(info.ship));
    std::string rules = "close pass under " + fixed(info.sweep.margin_m, 1) + " m; step " + fixed(info.sweep.step_m, 2) + " m; limiting depth " +
                        (std::isfinite(info.limiting_depth_m) ? fixed(info.limiting_depth_m, 1) + " m (" + info.limiting_depth_source + ")"
                                                              : std::string("land only")) +
                        "; under-keel clearance " + fixed(info.ukc_m, 1) + " m";
    if (r.has_encounters)
        rules += "; close quarters under " + fixed(info.ship_margin_m, 1) + " m; COLREG situations within " +
                 fixed(info.encounter_range_m, 0) + " m; exercises by " + info.exercise_by +
                 (info.roles.empty() && info.role_column.empty() ? std::string("; every track a trainee")
                  : "; roles from " + info.roles + (info.roles.empty() || info.role_column.empty() ? "" : " and ") +
                        (info.role_column.empty() ? "" : "column " + info.role_column));
    if (!info.berths.empty()) rules += "; expected-contact areas " + info.berths;
    row(out, "Rules", esc(rules));
    out += "</table>\n</header>\n";

    // The picture of the run.
    PlotOptions plot;
    plot.width_px = options.picture_width_px;
    plot.tracks = page.tracks;
    out += "<section id=\"picture\" class=\"picture\">\n<h2>The run</h2>\n";
    if (page.tracks.empty()) out += "<p class=\"none\">No track was audited.</p>\n";
    else out += inline_svg(overview_svg(r, grid, plot));
    out += "</section>\n";

    // Scores.
    out += "<section id=\"scores\">\n<h2>Scores</h2>\n";
    if (!r.has_assessment) {
        out += "<p class=\"none\">Not assessed (run check with --assess FILE).</p>\n";
    } else {
        std::vector<const audit::Score*> scores;
        for (const std::size_t si : page.scores) scores.push_back(&r.assessment.scores[si]);
        // The criteria, from the assessment file.
        const auto& criteria = r.assessment.criteria;
        const std::string file = !info.assessment.empty() ? info.assessment : r.assessment.source;
        const bool has_mark = std::isfinite(r.assessment.pass_mark);
        out += "<p class=\"assessment\">Scored against <span class=\"assessment-file\">" + esc(file.empty() ? "an assessment file" : file) +
               "</span>: " + std::to_string(criteria.size()) + " criteri" + (criteria.size() == 1 ? "on" : "a") + "; " +
               (has_mark ? "a trainee passes with a penalty of at most <span class=\"pass-mark\">" + fixed(r.assessment.pass_mark, 1) + "</span>."
                         : std::string("no pass mark.")) +
               "</p>\n";
        out += "<table class=\"criteria\">\n<thead><tr><th>Criterion</th><th>What it asks</th><th>Penalty</th></tr></thead>\n<tbody>\n";
        for (const audit::Criterion& c : criteria)
            out += "<tr class=\"criterion\" data-kind=\"" + esc(audit::to_string(c.kind)) + "\"><td class=\"id\">" + esc(c.id) + "</td><td>" +
                   esc(criterion_asks(c)) + "</td><td>" + esc(penalty_words(c)) + "</td></tr>\n";
        out += "</tbody>\n</table>\n";
        if (scores.empty()) out += "<p class=\"none\">No trainee in this exercise.</p>\n";
        else {
            out += "<table class=\"scores\">\n<thead><tr><th>Trainee</th><th>Name</th>";
            for (const audit::Criterion& c : criteria) out += "<th class=\"criterion\">" + esc(c.id) + "</th>";
            out += "<th>Penalty</th><th>Breaches</th><th>Result</th></tr></thead>\n<tbody>\n";
            for (const audit::Score* s : scores) {
                std::string name;
                for (const std::size_t ti : page.tracks)
                    if (r.tracks[ti].summary.id == s->track) name = r.tracks[ti].summary.name;
                out += "<tr class=\"score\"><td class=\"track\">" + esc(s->track) + "</td><td>" + esc(name) + "</td>";
                for (std::size_t c = 0; c < criteria.size(); ++c)
                    out += "<td class=\"num by-criterion\">" + (c < s->by_criterion.size() ? fixed(s->by_criterion[c], 1) : std::string("&#8211;")) + "</td>";
                out += "<td class=\"num penalty\">" + fixed(s->penalty, 1) + "</td><td class=\"num\">" + std::to_string(s->breaches) + "</td>" +
                       (!has_mark ? std::string("<td class=\"result\">&#8211;</td>")
                        : s->passed ? std::string("<td class=\"result pass\">pass</td>")
                                    : std::string("<td class=\"result fail\">fail</td>")) +
                       "</tr>\n";
            }
            out += "</tbody>\n</table>\n";
            // Why: each breach, what was asked and what happened.
            std::string why;
            for (const std::size_t bi : page.breaches) {
                const audit::Breach& b = r.assessment.breaches[bi];
                why += "<tr class=\"breach\" data-kind=\"" + esc(audit::to_string(b.kind)) + "\"><td class=\"track\">" + esc(b.track) +
                       "</td><td>" + esc(b.criterion) + "</td><td class=\"rule\">" + (b.rule.empty() ? std::string("&#8211;") : esc(b.rule)) +
                       "</td><td>" + esc(clock_text(std::isfinite(b.worst_s) ? b.worst_s : b.start_s, "?")) + "</td><td class=\"asked\">" +
                       esc(b.asked) + "</td><td class=\"did\">" + esc(b.did) + "</td><td class=\"num\">" + fixed(b.penalty, 1) + "</td></tr>\n";
            }
            // The rules that applied in every situation of a trainee, met or not.
            std::string conduct;
            std::set<std::size_t> on_page(page.tracks.begin(), page.tracks.end());
            for (const audit::ConductRecord& c : r.assessment.conduct) {
                if (!on_page.count(c.track_index)) continue;
                std::string applied, not_met;
                for (std::size_t j = 0; j < c.rules.size(); ++j) applied += (j ? ", " : "") + c.rules[j];
                for (std::size_t j = 0; j < c.breached.size(); ++j) not_met += (j ? ", " : "") + c.breached[j];
                const bool met = c.breached.empty();
                conduct += "<tr class=\"conduct\"><td class=\"track\">" + esc(c.track) + "</td><td>" + esc(c.criterion) + "</td><td class=\"other\">" +
                           esc(c.other) + "</td><td>" + esc(clock_text(c.start_s, "?")) + "</td><td class=\"situation\">" + esc(c.situation) +
                           "</td><td class=\"role\">" + (c.role.empty() ? std::string("no duty") : esc(c.role)) + "</td><td class=\"rules\">" +
                           (applied.empty() ? std::string("&#8211;") : esc(applied)) + "</td><td class=\"did\">" + esc(c.did) + "</td>" +
                           (c.rules.empty() ? std::string("<td class=\"result no-duty\">&#8211;</td>")
                            : met           ? std::string("<td class=\"result met\">met</td>")
                                            : "<td class=\"result not-met\">not met: rule " + esc(not_met) + "</td>") +
                           "</tr>\n";
            }
            if (!conduct.empty())
                out += "<h3>Conduct under the rules: every situation</h3>\n<table class=\"conduct\">\n<thead><tr><th>Trainee</th><th>Criterion</th>"
                       "<th>With</th><th>Start</th><th>Situation</th><th>Role</th><th>Rules that applied</th><th>What the ship did</th>"
                       "<th>Result</th></tr></thead>\n<tbody>\n" +
                       conduct + "</tbody>\n</table>\n";
            if (!why.empty())
                out += "<h3>Why: each breach</h3>\n<table class=\"breaches\">\n<thead><tr><th>Trainee</th><th>Criterion</th><th>Rule</th><th>When</th>"
                       "<th>What was asked</th><th>What happened</th><th>Penalty</th></tr></thead>\n<tbody>\n" +
                       why + "</tbody>\n</table>\n";
        }
    }
    // The ships.
    out += "<h2>Ships</h2>\n<table class=\"ships\">\n<thead><tr><th>Track</th><th>Name</th><th>Type</th><th>Role</th><th>Fixes</th><th>From</th>"
           "<th>To</th><th>Sailed (nm)</th><th>Groundings</th><th>Close passes</th><th>Least clearance (m)</th></tr></thead>\n<tbody>\n";
    for (const std::size_t ti : page.tracks) {
        const auto& s = r.tracks[ti].summary;
        out += "<tr class=\"ship\"><td class=\"track\">" + esc(s.id) + "</td><td>" + esc(s.name) + "</td><td class=\"ship-type\">" +
               (s.ship_type < 0 ? std::string("&#8211;") : esc(track::ship_type_text(s.ship_type))) + "</td><td>" +
               (r.has_encounters ? audit::to_string(s.role) : "&#8211;") + "</td><td class=\"num\">" + std::to_string(s.fixes) +
               "</td><td>" + esc(clock_text(s.start_s, "?")) + "</td><td>" + esc(clock_text(s.end_s, "?")) + "</td><td class=\"num\">" +
               fixed(s.distance_m / 1852, 2) + "</td><td class=\"num\">" + std::to_string(s.groundings) + "</td><td class=\"num\">" +
               std::to_string(s.close_passes) + "</td><td class=\"num\">" + fixed(s.min_clearance_m, 1) +
               "</td></tr>\n";
    }
    out += "</tbody>\n</table>\n";
    if (r.has_encounters && targets > 0)
        out += "<p class=\"none\">Groundings of targets are listed but not scored.</p>\n";
    out += "</section>\n";

    // Events in time order, each with its zoomed panel.
    std::vector<Item> items = page_items(r, grid, page);
    out += "<section id=\"events\">\n<h2>Events in time order</h2>\n";
    if (items.empty()) out += "<p class=\"none\">No grounding, contact, close pass, collision, close quarters or breach.</p>\n";
    std::size_t panels = 0;
    for (std::size_t n = 0; n < items.size(); ++n) {
        Item& it = items[n];
        out += "<article class=\"event\" id=\"event-" + std::to_string(n + 1) + "\" data-kind=\"" + esc(it.kind) + "\" data-time=\"" +
               esc(std::isfinite(it.time_s) ? iso_time(it.time_s) : "") + "\">\n<div class=\"words\">\n<h3><span class=\"kind\" style=\"background:" +
               kind_colour(it.kind) + "\"></span>" + std::to_string(n + 1) + ". " + esc(clock_text(it.time_s, "?")) + " <span class=\"exercise-time\">" +
               esc(exercise_time_text(it.time_s, first)) + "</span> " + esc(it.heading) +
               "</h3>\n<p class=\"who\">" + esc(it.who) + "</p>\n<p class=\"what\">" + esc(it.text) + "</p>\n</div>\n";
        if (!it.zoom.tracks.empty() && panels < options.max_zoom_panels) {
            it.zoom.id = "zoom-" + std::to_string(n + 1);
            ++panels;
            out += "<figure>" + inline_svg(zoom_svg(r, grid, it.zoom, options.zoom_width_px, plot)) + "</figure>\n";
        }
        out += "</article>\n";
    }
    if (panels < items.size() && items.size() > options.max_zoom_panels)
        out += "<p class=\"none\">Zoomed panels for the first " + std::to_string(options.max_zoom_panels) + " events only.</p>\n";
    out += "</section>\n";

    // Encounters.
    out += "<section id=\"encounters\">\n<h2>Encounters</h2>\n";
    std::vector<const audit::ColregEncounter*> sits;
    for (const std::size_t ci : page.situations) sits.push_back(&r.situations[ci]);
    if (!r.has_encounters) out += "<p class=\"none\">Not in exercise mode (<code>--encounters</code>): no encounters sought.</p>\n";
    else if (sits.empty())
        out += "<p class=\"none\">No pair came within " + fixed(info.encounter_range_m, 0) + " m.</p>\n";
    else {
        out += "<table class=\"encounters\">\n<thead><tr><th>Situation</th><th>Start</th><th>Ships</th><th>Give-way</th><th>Stand-on</th>"
               "<th>Bearings (&#176;)</th><th>CPA at start (m)</th><th>TCPA at start</th><th>Closest approach</th>"
               "<th>Least hull clearance (m)</th><th>Actions</th></tr></thead>\n<tbody>\n";
        for (const audit::ColregEncounter* c : sits) {
            const std::string& a = r.tracks[c->a].summary.id;
            const std::string& b = r.tracks[c->b].summary.id;
            double hull_clearance = NAN;
            for (const std::size_t ai : page.approaches) {
                const auto& ap = r.encounters.approaches[ai];
                if (ap.a == c->a && ap.b == c->b) hull_clearance = ap.clearance_m;
            }
            std::string actions = a + ": " + action_words(c->action_a) + "; " + b + ": " + action_words(c->action_b);
            if (c->a_stopped || c->b_stopped)
                actions += "; not under way at the start: " + std::string(c->a_stopped ? a : "") + (c->a_stopped && c->b_stopped ? ", " : "") +
                           (c->b_stopped ? b : "");
            out += "<tr class=\"encounter\"><td class=\"situation\">" + esc(audit::to_string(c->at_start.situation)) + "</td><td>" +
                   esc(date_clock_text(c->start_s)) + "</td><td class=\"ships\">" + esc(a) + " &#215; " + esc(b) + "</td><td class=\"give-way\">" +
                   esc(party_ids(r, *c, c->at_start.give_way)) + "</td><td class=\"stand-on\">" + esc(party_ids(r, *c, c->at_start.stand_on)) +
                   "</td><td class=\"num\">" + fixed(c->at_start.bearing_of_b_deg, 0) + " / " + fixed(c->at_start.bearing_of_a_deg, 0) +
                   "</td><td class=\"num cpa\">" + fixed(c->cpa_start.distance_m, 0) + "</td><td class=\"num tcpa\">" + tcpa_words(c->cpa_start.time_s) +
                   "</td><td class=\"closest\">" + fixed(c->closest_m, 0) + " m at " + esc(clock_text(c->closest_s, "?")) + "</td><td class=\"num\">" +
                   fixed(hull_clearance, 1) + "</td><td class=\"actions\">" + esc(actions) + "</td></tr>\n";
        }
        out += "</tbody>\n</table>\n<p class=\"none\">Bearings: of the second ship from the first / of the first from the second, "
               "relative to each one's heading. CPA and TCPA: if both had kept their course and speed from the start.</p>\n";
        // Each closest approach: both hulls at that moment, the line between the ships, the distance.
        out += "<h3>Closest approaches</h3>\n<div class=\"cpa-panels\">\n";
        for (std::size_t n = 0; n < page.situations.size(); ++n) {
            const std::size_t ci = page.situations[n];
            const audit::ColregEncounter& c = r.situations[ci];
            const std::string svg = n < options.max_zoom_panels ? cpa_svg(r, grid, ci, options.zoom_width_px, plot) : std::string();
            out += "<figure class=\"cpa\" id=\"closest-approach-" + std::to_string(n + 1) + "\">" + (svg.empty() ? std::string() : inline_svg(svg)) +
                   "<figcaption>" + std::to_string(n + 1) + ". " + esc(r.tracks[c.a].summary.id) + " &#215; " + esc(r.tracks[c.b].summary.id) + ", " +
                   esc(audit::to_string(c.at_start.situation)) + ": closest approach <span class=\"cpa-distance\">" + fixed(c.closest_m, 0) +
                   " m</span> at " + esc(clock_text(c.closest_s, "?")) + " (" + esc(exercise_time_text(c.closest_s, first)) + ")</figcaption></figure>\n";
        }
        out += "</div>\n";
    }
    out += "</section>\n";
    out += "<footer>Written by shoal " + esc(SHOAL_VERSION_STRING) + " (<code>shoal check --debrief</code>).</footer>\n</body>\n</html>\n";
    return out;
}

void check_debrief_folder(const std::string& folder) {
    if (is_standard_output(folder)) throw UsageError("the debrief needs a folder (one page per exercise), not standard output");
    const std::string ext = lower(fs::path(folder).extension().string());
    std::error_code ec;
    if ((ext == ".html" || ext == ".htm") && !fs::is_directory(folder, ec))
        throw UsageError("the debrief folder '" + folder + "' names a page; give a folder: it receives one page per exercise, <exercise>.html");
    if (fs::exists(folder, ec)) {
        if (!fs::is_directory(folder, ec)) throw InputError("cannot write the debrief into '" + folder + "': it is not a folder");
        return;
    }
    fs::path parent = fs::path(folder).parent_path();
    if (parent.empty()) parent = ".";
    if (!fs::is_directory(parent, ec))
        throw InputError("cannot write the debrief into '" + folder + "': folder '" + parent.string() + "' does not exist");
}

std::vector<OutputSpec> debrief_outputs(const std::string& folder, const std::vector<DebriefPage>& pages) {
    std::vector<OutputSpec> out;
    for (const auto& p : pages) out.push_back({(fs::path(folder) / p.file).string(), "--debrief", "the debrief of " + p.exercise});
    return out;
}

std::vector<StagedOutput> stage_debrief(const std::string& folder, const audit::AuditResult& result, const grid::CoastGrid& grid,
                                        const RunInfo& info, const std::vector<std::string>& inputs,
                                        const std::vector<OutputSpec>& others, const DebriefOptions& options,
                                        std::vector<std::string>* refused) {
    check_debrief_folder(folder);
    std::error_code ec;
    if (!fs::is_directory(folder, ec) && !fs::create_directory(folder, ec) && !fs::is_directory(folder))
        throw InputError("cannot create the debrief folder '" + folder + "': " + ec.message());
    const std::vector<DebriefPage> pages = debrief_pages(result);
    std::vector<OutputSpec> all = others;
    for (OutputSpec& s : debrief_outputs(folder, pages)) all.push_back(std::move(s));
    check_outputs(all, inputs);
    std::vector<StagedOutput> out;
    for (const DebriefPage& page : pages) {
        const std::string path = (fs::path(folder) / page.file).string();
        if (fs::exists(path, ec)) {
            std::ifstream in(path, std::ios::binary);
            std::string head(512, '\0');
            in.read(head.data(), static_cast<std::streamsize>(head.size()));
            head.resize(static_cast<std::size_t>(in.gcount()));
            if (head.find(generator_mark) == std::string::npos) {
                if (refused)
                    refused->push_back("'" + path + "' exists and shoal did not write it: the debrief of exercise '" + page.exercise +
                                        "' was not written (move the file away)");
                continue;
            }
        }
        StagedOutput& s = out.emplace_back(path);
        s.write(debrief_html(result, grid, info, page, options));
    }
    return out;
}

}  // namespace shoal::report
