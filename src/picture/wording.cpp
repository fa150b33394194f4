// Events and times in words (see include/shoal/picture/wording.hpp and picture/event_phrases.hpp):
// one wording for the picture's tooltips and titles and the debrief's pages.
#include <shoal/picture/wording.hpp>

#include <cmath>
#include <cstdio>
#include <string_view>
#include <vector>

#include <shoal/report/geojson_report.hpp>
#include "picture/event_phrases.hpp"

namespace shoal::report {

std::string fixed_text(double v, int decimals, const char* not_finite) {
    if (!std::isfinite(v)) return not_finite;
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    if (std::string_view(b).find_first_not_of("-0.") == std::string_view::npos && b[0] == '-') return b + 1;  // no "-0.0"
    return b;
}

std::string clock_text(double t, const char* unknown) {
    const std::string s = iso_time(t);
    return s.size() >= 19 ? s.substr(11, 8) + "Z" : unknown;
}

std::string date_clock_text(double t) {
    const std::string s = iso_time(t);
    return s.size() >= 19 ? s.substr(0, 10) + " " + s.substr(11, 8) + "Z" : "?";
}

namespace detail {

using audit::Event;
using audit::EventKind;

std::string plural(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// "3 groundings", "2 alongside", "37 in contact at the start", "1 expected contact", "8 close passes".
std::string count_text(EventKind k, std::size_t n) {
    switch (k) {
    case EventKind::grounding: return plural(n, "grounding", "groundings");
    case EventKind::alongside: return plural(n, "alongside", "alongside");
    case EventKind::contact_at_start: return plural(n, "in contact at the start", "in contact at the start");
    case EventKind::expected_contact: return plural(n, "expected contact", "expected contacts");
    case EventKind::close_pass: return plural(n, "close pass", "close passes");
    case EventKind::chart_disagrees: return plural(n, "where the chart disagrees", "where the chart disagrees");
    }
    return std::to_string(n);
}

/// What was hit when it is not land: "shallow 3.6 m", "rock", "wreck 2.1 m", "pier 'Pier 25'";
/// "" for land.
std::string hazard_text(const Event& e) {
    if (e.hit == coast::HazardKind::land) return {};
    std::string s = e.hit == coast::HazardKind::danger      ? coast::to_string(e.danger)
                    : e.hit == coast::HazardKind::structure ? e.structure
                                                            : coast::to_string(e.hit);
    if (s.empty()) s = coast::to_string(e.hit);
    // (Appended piece by piece: `" " + text` built a string by inserting at its front, where
    // GCC 12 at -O3 warns -Wrestrict, a false positive.)
    if (e.hit == coast::HazardKind::structure && !e.hit_name.empty()) s.append(" '").append(e.hit_name).append("'");
    if (std::isfinite(e.charted_depth_m)) s.append(" ").append(fixed_text(e.charted_depth_m, 1)).append(" m");
    return s;
}

/// The kind in words: "grounding", "alongside (not a grounding)", "in contact at the first fix
/// (not seen begin)", "contact in berth Pier 3", "close pass".
std::string kind_words(const Event& e) {
    switch (e.kind) {
    case EventKind::grounding: return "grounding";
    case EventKind::alongside: return "alongside (not a grounding)";
    case EventKind::contact_at_start: return "in contact at the first fix (not seen begin)";
    case EventKind::expected_contact: {
        std::string s = "contact in " + (e.area_kind.empty() ? std::string("area") : e.area_kind);
        if (!e.area_name.empty()) s += " " + e.area_name;
        return s;
    }
    case EventKind::close_pass: return "close pass";
    case EventKind::chart_disagrees: return "the chart disagrees with the traffic (not a grounding)";
    }
    return audit::to_string(e.kind);
}

/// "9.8 kn SOG", "0.3 kn from positions", "speed unknown".
std::string speed_text(const Event& e) {
    if (!std::isfinite(e.speed_kn) || e.speed_source == track::SpeedSource::none) return "speed unknown";
    return fixed_text(e.speed_kn, 1) + (e.speed_source == track::SpeedSource::sog ? " kn SOG" : " kn from positions");
}

/// " at contact" (a contact whose speed is known), " at least clearance" (a close pass's), "".
std::string speed_when(const Event& e) {
    if (!std::isfinite(e.speed_kn) || e.speed_source == track::SpeedSource::none) return {};
    return audit::is_contact(e.kind) ? " at contact" : " at least clearance";
}

/// "heading 182°" (with its source when `source`), "heading unknown (hull circle)" when no
/// heading was known; a heading is printed only when it is finite.
std::string heading_text(const Event& e, bool source) {
    if (e.orientation_unknown) return "heading unknown (hull circle)";
    if (!std::isfinite(e.heading_deg)) return "heading unknown";
    double h = std::fmod(e.heading_deg, 360.0);
    if (h < 0) h += 360;
    if (h >= 359.5) h = 0;
    std::string s = "heading " + fixed_text(h, 0) + "\xC2\xB0";
    if (source) {
        switch (e.heading_source) {
        case track::HeadingSource::heading: s += " (true heading)"; break;
        case track::HeadingSource::cog: s += " (COG)"; break;
        case track::HeadingSource::positions: s += " (from positions)"; break;
        case track::HeadingSource::previous: s += " (held from an earlier fix)"; break;
        case track::HeadingSource::none: break;
        }
    }
    return s;
}

/// "penetration 1.2 m" (contacts), "least clearance 12.3 m" (close passes).
std::string depth_text(const Event& e) {
    if (audit::is_contact(e.kind)) return "penetration " + fixed_text(e.penetration_m, 1) + " m";
    return "least clearance " + fixed_text(e.min_clearance_m, 1) + " m";
}

/// "track 230123456 AAVA" (the name only when it says more than the id).
std::string track_text(const audit::TrackSummary& t) {
    std::string s = "track " + t.id;
    if (!t.name.empty() && t.name != t.id) s += " " + t.name;
    return s;
}

/// The evidence for the kind, for tooltips: "stopped after 40 s; reference point 3.2 m inside
/// land; AIS status moored; structure pier; ...".
std::string evidence_text(const Event& e) {
    std::vector<std::string> parts;
    if (audit::is_contact(e.kind)) {
        if (e.stopped_before) parts.push_back("stopped before contact");
        parts.push_back(std::isfinite(e.stopped_after_s) ? "stopped after " + duration_words(e.stopped_after_s)
                                                         : std::string("did not stop (in this piece)"));
        if (std::isfinite(e.reference_inside_m)) {
            const std::string what = e.hit == coast::HazardKind::land        ? "land"
                                     : e.hit == coast::HazardKind::shallow   ? "the shallow area"
                                     : e.hit == coast::HazardKind::structure ? "the structure"
                                                                             : "the danger";
            parts.push_back(e.reference_inside_m >= 0
                                ? "reference point " + fixed_text(e.reference_inside_m, 1) + " m inside " + what
                                : "reference point " + fixed_text(-e.reference_inside_m, 1) + " m outside " + what + " (in water)");
        }
    }
    if (e.nav_status != track::nav_status_unknown) {
        const std::string st = track::nav_status_text(e.nav_status);
        parts.push_back("AIS status " + (st.empty() ? std::to_string(e.nav_status) : st));
    }
    if (e.reported_aground) parts.push_back("AIS reported aground");
    if (!e.structure.empty()) parts.push_back("structure " + e.structure);
    if (e.kind == EventKind::contact_at_start && !e.unseen_after.empty()) parts.push_back("not seen begin: after " + e.unseen_after);
    if (!e.area_name.empty() || !e.area_kind.empty())
        parts.push_back("area " + (e.area_kind.empty() ? std::string("area") : e.area_kind) +
                        (e.area_name.empty() ? "" : " " + e.area_name));
    if (e.fix_line > 0) parts.push_back("fix line " + std::to_string(e.fix_line));
    std::string s;
    for (const auto& p : parts) s += (s.empty() ? "" : "; ") + p;
    return s;
}

}  // namespace detail

using namespace detail;

/// "0 s", "4.2 s", "42 s", "3 min 07 s", "2 h 05 min".
std::string duration_words(double s) {
    if (!std::isfinite(s) || s < 0) return "duration unknown";
    char b[48];
    if (s < 0.05) return "0 s";
    if (s < 9.95) std::snprintf(b, sizeof b, "%.1f s", s);
    else if (s < 59.5) std::snprintf(b, sizeof b, "%.0f s", s);
    else if (s < 3600) {
        const long t = std::lround(s);
        std::snprintf(b, sizeof b, "%ld min %02ld s", t / 60, t % 60);
    } else {
        const long t = std::lround(s / 60);
        std::snprintf(b, sizeof b, "%ld h %02ld min", t / 60, t % 60);
    }
    return b;
}

/// The event's full description (tooltips): track, kind, times, speed, depth or clearance,
/// heading, and the evidence for the kind.
std::string event_description(const audit::TrackSummary& t, const audit::Event& ev) {
    std::string s = "track " + t.id + (t.name.empty() || t.name == t.id ? "" : " (" + t.name + ")");
    s += ": " + kind_words(ev);
    const std::string hazard = audit::is_contact(ev.kind) ? hazard_text(ev) : "";
    if (!hazard.empty()) s += ", " + hazard;
    s += " from " + iso_time(ev.start_s) + " to " + iso_time(ev.end_s) + " (" + duration_words(ev.end_s - ev.start_s) + "); " +
         speed_text(ev) + speed_when(ev) + "; " + depth_text(ev) + "; " +
         heading_text(ev, true);
    const std::string evidence = evidence_text(ev);
    if (!evidence.empty()) s += "; " + evidence;
    if (ev.evidence.grade > 0) s += "; grade " + std::to_string(ev.evidence.grade) + ": " + ev.evidence.reason;
    return s;
}

std::string exercise_time_text(double t, double start_s) {
    if (!std::isfinite(t) || !std::isfinite(start_s)) return "T+?";
    const double d = t - start_s;
    const auto s = static_cast<long>(std::floor(std::fabs(d) + 1e-6));  // cut, not rounded, as clock_text
    char b[48];
    if (s < 3600) std::snprintf(b, sizeof b, "T%c%ld:%02ld", d < 0 ? '-' : '+', s / 60, s % 60);
    else std::snprintf(b, sizeof b, "T%c%ld:%02ld:%02ld", d < 0 ? '-' : '+', s / 3600, s / 60 % 60, s % 60);
    return b;
}

}  // namespace shoal::report
