#include <algorithm>
#include <cmath>
#include <cstdio>

#include <shoal/report/geojson_report.hpp>
#include <shoal/report/summary.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::report {

namespace {
/// The summary lists at most this many situations, and as many encounters (a crowd's report
/// lists thousands).
constexpr std::size_t table_lines = 50;
}  // namespace

std::string summary_table(const audit::AuditResult& r, SummaryDetail detail) {
    std::string out;
    char line[1024];
    if (r.world == audit::World::real)
        std::snprintf(line, sizeof line,
                      "world: real (the chart is a model: a contact is a grounding when the vessel's motion says so)%s\n",
                      std::isfinite(r.chart_tolerance_m) ? (", chart tolerance " + std::to_string(static_cast<int>(std::lround(r.chart_tolerance_m))) + " m").c_str() : "");
    else
        std::snprintf(line, sizeof line, "world: simulated (the chart is the world: a contact under way is a grounding)\n");
    out += line;
    // The counts of each kind first (what a day of traffic comes to), then the tracks.
    std::snprintf(line, sizeof line,
                  "events: %zu grounding%s, %zu alongside, %zu in_contact_at_start, %zu expected_contact, %zu chart_disagrees, %zu close_pass%s\n",
                  r.groundings, r.groundings == 1 ? "" : "s", r.alongside, r.contacts_at_start, r.expected_contacts, r.chart_disagreements,
                  r.close_passes, r.close_passes == 1 ? "" : "es");
    out += line;
    if (r.has_encounters) {
        std::snprintf(line, sizeof line, "encounter events: %zu collision%s, %zu close_quarters\n", r.collisions, r.collisions == 1 ? "" : "s",
                      r.close_quarters);
        out += line;
    }
    std::snprintf(line, sizeof line,
                  "total: %zu files, %zu tracks, %zu fixes (%zu poses checked), %zu groundings, %zu close passes, %zu uncovered fixes, %zu bad rows skipped\n",
                  r.files.size(), r.tracks.size(), r.fixes, r.poses, r.groundings, r.close_passes, r.uncovered_fixes, r.skipped_rows);
    out += line;
    std::snprintf(line, sizeof line, "fixes: %zu wild fixes dropped, %zu jumps, %zu fixes with no heading known (judged by the hull's circle)\n",
                  r.wild_fixes, r.jumps, r.unknown_heading_fixes);
    out += line;
    std::snprintf(line, sizeof line, "%-24s %9s %9s %7s %9s %5s %8s %5s %5s %10s  %s\n", "track", "fixes", "uncovered", "aground",
                  "alongside", "start", "expected", "close", "wild", "least m", "file");
    out += line;
    // Without --verbose, the tracks with events only (on a day of AIS, thousands have none,
    // many of them outside the chart): those left out are counted below the table.
    std::size_t quiet = 0, quiet_uncovered = 0, quiet_wild = 0;
    for (const auto& t : r.tracks) {
        const auto& s = t.summary;
        if (detail != SummaryDetail::verbose && t.events.empty()) {
            ++quiet;
            if (s.uncovered_fixes > 0) ++quiet_uncovered;
            if (!s.wild_fixes.empty()) ++quiet_wild;
            continue;
        }
        char least[32];
        if (std::isfinite(s.min_clearance_m)) std::snprintf(least, sizeof least, "%.1f", s.min_clearance_m);
        else std::snprintf(least, sizeof least, "-");
        std::snprintf(line, sizeof line, "%-24.24s %9zu %9zu %7zu %9zu %5zu %8zu %5zu %5zu %10s  %s\n", printable(s.id).c_str(), s.fixes,
                      s.uncovered_fixes, s.groundings, s.alongside, s.contacts_at_start, s.expected_contacts, s.close_passes,
                      s.wild_fixes.size(), least, printable(s.file).c_str());
        out += line;
    }
    if (quiet) {
        std::snprintf(line, sizeof line, "(%zu more track%s without events, %zu of them with fixes outside the chart, %zu with wild fixes: --verbose lists every track)\n",
                      quiet, quiet == 1 ? "" : "s", quiet_uncovered, quiet_wild);
        out += line;
    }
    if (!r.places.empty()) {
        std::size_t berths = 0, water = 0;
        for (const auto& p : r.places) ++(p.kind == audit::LearnedPlace::Kind::berth ? berths : water);
        std::snprintf(line, sizeof line, "learned from the traffic: %zu berths (places where vessels stay), %zu cells of water the chart lacks (vessels under way on charted land)\n",
                      berths, water);
        out += line;
    }
    // Every grounding: who, when, where, and why.
    for (const auto& t : r.tracks)
        for (const auto& e : t.events) {
            if (e.kind != audit::EventKind::grounding) continue;
            const std::string who = t.summary.name.empty() ? t.summary.id : t.summary.id + " " + t.summary.name;
            std::string when = iso_time(e.start_s);
            if (std::isfinite(e.evidence.start_not_before_s) && e.start_s - e.evidence.start_not_before_s > 60)
                when = "between " + iso_time(e.evidence.start_not_before_s) + " and " + iso_time(e.start_s);
            char speed[64] = "speed unknown";
            if (std::isfinite(e.speed_kn)) std::snprintf(speed, sizeof speed, "%.1f kn (%s)", e.speed_kn, track::to_string(e.speed_source));
            std::snprintf(line, sizeof line, "  grounding %s  %s at %.5f, %.5f: %s, %.0f s in contact, penetration %.1f m, grade %d: %s\n",
                          when.c_str(), printable(who).c_str(), e.ship.lat, e.ship.lon, speed, e.end_s - e.start_s, e.penetration_m,
                          e.evidence.grade, printable(e.evidence.reason).c_str());
            out += line;
        }
    if (r.has_encounters) {
        const auto within = static_cast<std::size_t>(std::count_if(r.encounters.approaches.begin(), r.encounters.approaches.end(),
                                                                   [](const audit::ClosestApproach& a) { return std::isfinite(a.clearance_m); }));
        std::snprintf(line, sizeof line, "encounters: %zu exercise%s, %zu collisions, %zu close quarters, %zu pairs came within the threshold (%.0f m)\n",
                      r.exercises, r.exercises == 1 ? "" : "s", r.collisions, r.close_quarters, within + r.unlisted.approached,
                      r.encounters.threshold_m);
        out += line;
        std::snprintf(line, sizeof line, "situations: %zu pairs came within the encounter range\n", r.situations_found());
        out += line;
        if (r.unlisted.pairs > 0) {
            std::snprintf(line, sizeof line,
                          "not listed: %zu pairs (%zu collisions, %zu close quarters, %zu situations), each ship listing those it came closest to\n",
                          r.unlisted.pairs, r.unlisted.collisions, r.unlisted.close_quarters, r.unlisted.situations);
            out += line;
        }
        // One line each, up to table_lines of each kind: the report has them all.
        const auto more = [&](std::size_t n, const char* what) {
            if (n <= table_lines) return;
            std::snprintf(line, sizeof line, "  ... %zu more %s in the report\n", n - table_lines, what);
            out += line;
        };
        std::size_t lines = 0;
        for (const auto& c : r.situations) {
            if (lines++ == table_lines) break;
            const std::string& a = r.tracks.at(c.a).summary.id;
            const std::string& b = r.tracks.at(c.b).summary.id;
            const auto who = [&](audit::Party p) -> std::string {
                return p == audit::Party::a ? a : p == audit::Party::b ? b : p == audit::Party::both ? "both" : "neither";
            };
            const audit::Manoeuvre& act = c.at_start.give_way == audit::Party::b ? c.action_b : c.action_a;
            std::string acted = c.a_stopped || c.b_stopped ? std::string(", not under way: ") + (c.a_stopped ? a : "") +
                                                                 (c.a_stopped && c.b_stopped ? ", " : "") + (c.b_stopped ? b : "")
                                                           : "";
            if (c.at_start.give_way == audit::Party::a || c.at_start.give_way == audit::Party::b)
                acted = std::isnan(act.time_s) ? ", give-way did not alter" : ", give-way altered " + iso_time(act.time_s).substr(11);
            std::snprintf(line, sizeof line, "  %-10s %s  [%s] %s x %s  give-way %s, CPA %.0f m in %.0f s, closest %.0f m at %s%s\n",
                          audit::to_string(c.at_start.situation), iso_time(c.start_s).c_str(), printable(r.tracks.at(c.a).summary.exercise).c_str(),
                          printable(a).c_str(), printable(b).c_str(), printable(who(c.at_start.give_way)).c_str(), c.cpa_start.distance_m,
                          c.cpa_start.time_s, c.closest_m, iso_time(c.closest_s).substr(11).c_str(), acted.c_str());
            out += line;
        }
        more(r.situations.size(), "situations");
        lines = 0;
        for (const auto& e : r.encounters.events) {
            if (lines++ == table_lines) break;
            std::snprintf(line, sizeof line, "  %-14s %s - %s  %s x %s  least %.1f m\n", audit::to_string(e.kind),
                          iso_time(e.start_s).c_str(), iso_time(e.end_s).c_str(), r.tracks.at(e.a.track).summary.id.c_str(),
                          r.tracks.at(e.b.track).summary.id.c_str(), e.min_clearance_m);
            out += line;
        }
        more(r.encounters.events.size(), "collisions and close quarters");
    }
    if (r.has_assessment) {  // --assess: one line per trainee's score, then one per breach
        std::snprintf(line, sizeof line, "assessment: %zu criteria, %zu trainees scored, %zu breaches\n", r.assessment.criteria.size(),
                      r.assessment.scores.size(), r.assessment.breaches.size());
        out += line;
        for (const auto& s : r.assessment.scores) {
            std::snprintf(line, sizeof line, "  score  [%s] %s  penalty %.2f, %zu breach%s", printable(s.exercise).c_str(), printable(s.track).c_str(),
                          s.penalty, s.breaches, s.breaches == 1 ? "" : "es");
            out += line;
            if (std::isfinite(r.assessment.pass_mark)) {
                std::snprintf(line, sizeof line, ": %s (pass mark %.2f)", s.passed ? "pass" : "fail", r.assessment.pass_mark);
                out += line;
            }
            out += "\n";
        }
        for (const auto& b : r.assessment.breaches) {
            // Built whole: a colreg breach's sentence can be longer than the line buffer.
            std::snprintf(line, sizeof line, " at %.6f, %.6f\n", b.lat, b.lon);
            out += "  breach [" + printable(b.exercise) + "] " + printable(b.track) + "  " + printable(b.detail) + line;
        }
    }
    for (const auto& f : r.files)
        if (!f.error.empty()) out += "unreadable: " + printable(f.error) + "\n";
    for (const auto& e : r.errors) out += "track failed: " + printable(e.track + " in " + e.file + ": " + e.message) + "\n";
    return out;
}

}  // namespace shoal::report
