#include <shoal/report/report_fields.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <shoal/grid/coast_grid.hpp>
#include <shoal/report/geojson_report.hpp>
#include "track/ship_type.hpp"
#include <shoal/track/track.hpp>
#include <shoal/version.hpp>

#include "report/qgis/chart_layer.hpp"

namespace shoal::report::fields {

double round_to(double v, int decimals) {
    // 10^0 .. 10^22 are doubles exactly, which pow gives (ReportFields.RoundingTakesPowersOfTenExactly).
    static constexpr double powers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const double k = decimals >= 0 && decimals <= 22 ? powers[decimals] : std::pow(10.0, decimals);
    return std::round(v * k) / k;
}

namespace {

/// A fingerprint of the criteria as read (every field, numbers to the last bit): the run
/// header carries it so that merge refuses parts scored against different criteria, whatever
/// the format (a GeoPackage keeps only the file's path otherwise).
std::string criteria_fingerprint(const std::vector<audit::Criterion>& criteria, double pass_mark) {
    std::string key;
    char num[40];
    const auto add = [&](double v) {
        std::snprintf(num, sizeof num, "%a;", v);
        key += num;
    };
    for (const audit::Criterion& c : criteria) {
        key += c.id + '\0' + audit::to_string(c.kind) + '\0' + audit::to_string(c.per) + '\0' + c.area_name + '\0';
        add(c.limit);
        add(c.penalty);
        for (const geo::LonLat& p : c.area) {
            add(p.lon);
            add(p.lat);
        }
        if (c.kind == audit::CriterionKind::colreg) {
            const audit::ConductOptions& o = c.colreg;
            for (const double v : {o.range_m, o.head_on_deg, o.cpa_m, o.early_range_m, o.min_course_deg, o.min_speed_change, o.action_course_deg,
                                   o.action_speed_change, o.sustain_s})
                add(v);
        }
        key += '\n';
    }
    if (std::isfinite(pass_mark)) {  // absent from the key when there is none (fingerprints of older runs unchanged)
        key += "pass_mark";
        add(pass_mark);
    }
    return grid::fingerprint_hex(XXH3_64bits(key.data(), key.size()));
}

// Values are built through these, never from a bare `const char*` (which would make a bool).
Value text(std::string s) { return Value(std::move(s)); }
Value count(std::size_t n) { return static_cast<std::int64_t>(n); }
const Value null{};

bool exercise(const audit::AuditResult& r) { return r.has_encounters; }
bool sharded(const audit::AuditResult& r) { return r.shard.active(); }
bool assessed(const audit::AuditResult& r) { return r.has_assessment; }

/// The COLREG situation of pair (a, b) (a < b), or null (AuditResult::situations is by (a, b)).
const audit::ColregEncounter* situation_of(const audit::AuditResult& r, std::size_t a, std::size_t b) {
    const auto it = std::lower_bound(r.situations.begin(), r.situations.end(), std::make_pair(a, b),
                                     [](const audit::ColregEncounter& c, const std::pair<std::size_t, std::size_t>& k) {
                                         return std::make_pair(c.a, c.b) < k;
                                     });
    return it != r.situations.end() && it->a == a && it->b == b ? &*it : nullptr;
}
/// A party of the pair as track ids: "both" is the two ids, "neither" null.
Value party(const audit::AuditResult& r, const audit::ColregEncounter* c, audit::Party p) {
    if (!c) return std::monostate{};
    const std::string& a = r.tracks.at(c->a).summary.id;
    const std::string& b = r.tracks.at(c->b).summary.id;
    switch (p) {
        case audit::Party::a: return Value(a);
        case audit::Party::b: return Value(b);
        case audit::Party::both: return Value(a + ", " + b);
        case audit::Party::neither: break;
    }
    return std::monostate{};
}
Value action_text(const audit::Manoeuvre& m) {
    if (std::isnan(m.time_s)) return Value(std::string("none"));
    return Value(std::string(m.course && m.speed ? "course and speed" : m.course ? "course" : "speed"));
}

using audit::is_contact;
using E = EventRow;
using C = EncounterRow;
using T = TrackRow;
using H = HullRow;
using P = ProblemRow;
using A = ApproachRow;
using R = RunRow;
constexpr Type text_t = Type::text, integer = Type::integer, real = Type::real, boolean = Type::boolean, datetime = Type::datetime;
constexpr const char *none = "", *metres = "m", *seconds = "s", *knots = "kn", *degrees = "deg", *wgs84 = "degrees (WGS84)",
                      *utc = "ISO 8601 UTC";

}  // namespace

std::string encounter_label(const audit::Encounter& e) {
    return std::string(e.kind == audit::EncounterKind::collision ? "collision " : "close quarters ") + iso_time(e.start_s).substr(11);
}

const std::vector<Field<EventRow>>& event_fields() {
    static const std::vector<Field<EventRow>> f = {
        {"track", text_t, none, -1, [](const E& x) { return text(x.track.id); }},
        {"name", text_t, none, -1, [](const E& x) { return text(x.track.name); }},
        {"kind", text_t, none, -1, [](const E& x) { return text(audit::to_string(x.event.kind)); }},
        {"hit", text_t, none, -1, [](const E& x) { return text(coast::to_string(x.event.hit)); }},
        {"charted_depth_m", real, metres, 2,
         [](const E& x) { return x.event.hit != coast::HazardKind::land ? Value(x.event.charted_depth_m) : null; }},
        {"danger", text_t, none, -1, [](const E& x) { return text(coast::to_string(x.event.danger)); }},
        {"hit_name", text_t, none, -1, [](const E& x) { return text(x.event.hit_name); }},
        {"start", datetime, utc, -1, [](const E& x) { return text(iso_time(x.event.start_s)); }},
        {"end", datetime, utc, -1, [](const E& x) { return text(iso_time(x.event.end_s)); }},
        {"duration_s", real, seconds, 3, [](const E& x) { return Value(x.event.end_s - x.event.start_s); }},
        {"min_clearance_m", real, metres, 3, [](const E& x) { return Value(x.event.min_clearance_m); }},
        {"penetration_m", real, metres, 3, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.penetration_m) : null; }},
        {"ship_lat", real, wgs84, coordinate_decimals, [](const E& x) { return Value(x.event.ship.lat); }},
        {"ship_lon", real, wgs84, coordinate_decimals, [](const E& x) { return Value(x.event.ship.lon); }},
        {"heading", real, degrees, 1, [](const E& x) { return Value(x.event.heading_deg); }},
        {"heading_source", text_t, none, -1, [](const E& x) { return text(track::to_string(x.event.heading_source)); }},
        {"orientation", text_t, none, -1, [](const E& x) { return text(x.event.orientation_unknown ? "unknown (hull circle)" : "hull"); }},
        {"speed_kn", real, knots, 2, [](const E& x) { return Value(x.event.speed_kn); }},
        {"speed_source", text_t, none, -1, [](const E& x) { return text(track::to_string(x.event.speed_source)); }},
        {"stopped_before", boolean, none, -1, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.stopped_before) : null; }},
        {"stopped_after_s", real, seconds, 1, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.stopped_after_s) : null; }},
        {"reference_inside_m", real, metres, 2,
         [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.reference_inside_m) : null; }},
        {"nav_status", integer, none, -1,
         [](const E& x) { return x.event.nav_status == track::nav_status_unknown ? null : Value(std::int64_t{x.event.nav_status}); }},
        {"nav_status_text", text_t, none, -1, [](const E& x) { return text(track::nav_status_text(x.event.nav_status)); }},
        {"reported_aground", boolean, none, -1, [](const E& x) { return Value(x.event.reported_aground); }},
        {"unseen_after", text_t, none, -1, [](const E& x) { return text(x.event.unseen_after); }},
        {"area", text_t, none, -1, [](const E& x) { return text(x.event.area_kind); }},
        {"area_name", text_t, none, -1, [](const E& x) { return text(x.event.area_name); }},
        {"structure", text_t, none, -1, [](const E& x) { return text(x.event.structure); }},
        {"grade", integer, none, -1,
         [](const E& x) { return x.event.evidence.grade > 0 ? Value(std::int64_t{x.event.evidence.grade}) : null; }},
        {"reason", text_t, none, -1, [](const E& x) { return text(x.event.evidence.reason); }},
        {"disagreement", text_t, none, -1, [](const E& x) { return text(x.event.evidence.disagreement); }},
        {"start_not_before", datetime, utc, -1,
         [](const E& x) {
             const double nb = x.event.evidence.start_not_before_s;
             return is_contact(x.event.kind) && std::isfinite(nb) ? text(iso_time(nb)) : null;
         }},
        {"start_uncertainty_s", real, seconds, 1,
         [](const E& x) {
             const double nb = x.event.evidence.start_not_before_s;
             return is_contact(x.event.kind) && std::isfinite(nb) ? Value(x.event.start_s - nb) : null;
         }},
        {"speed_before_kn", real, knots, 2, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.speed_before_kn) : null; }},
        {"speed_before_age_s", real, seconds, 1,
         [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.speed_before_age_s) : null; }},
        {"speed_after_kn", real, knots, 2, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.speed_after_kn) : null; }},
        {"speed_after_age_s", real, seconds, 1,
         [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.speed_after_age_s) : null; }},
        {"stop_distance_m", real, metres, 1, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.stop_distance_m) : null; }},
        {"stay_s", real, seconds, 1, [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.stay_s) : null; }},
        {"deceleration_kn_s", real, "kn/s", 3,
         [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.deceleration_kn_s) : null; }},
        {"berth_stays", integer, none, -1, [](const E& x) { return is_contact(x.event.kind) ? count(x.event.evidence.berth_stays) : null; }},
        {"pieces", integer, none, -1, [](const E& x) { return is_contact(x.event.kind) ? count(x.event.evidence.pieces) : null; }},
        {"within_chart_tolerance", boolean, none, -1,
         [](const E& x) { return is_contact(x.event.kind) ? Value(x.event.evidence.within_chart_tolerance) : null; }},
        {"fix_index", integer, none, -1, [](const E& x) { return count(x.event.fix_index); }},
        {"fix_line", integer, none, -1, [](const E& x) { return count(x.event.fix_line); }},
        {"file", text_t, none, -1, [](const E& x) { return text(x.track.file); }},
        {"hull", text_t, none, -1, [](const E& x) { return text(x.track.hull); }},
        {"label", text_t, none, -1, [](const E& x) { return text(event_label(x.event)); }},
        {"exercise", text_t, none, -1, [](const E& x) { return text(x.track.exercise); }, exercise},
        {"role", text_t, none, -1, [](const E& x) { return text(audit::to_string(x.track.role)); }, exercise},
    };
    return f;
}

const std::vector<Field<EncounterRow>>& encounter_fields() {
    static const auto a = [](const C& x) -> const audit::TrackSummary& { return x.result.tracks.at(x.encounter.a.track).summary; };
    static const auto b = [](const C& x) -> const audit::TrackSummary& { return x.result.tracks.at(x.encounter.b.track).summary; };
    static const std::vector<Field<EncounterRow>> f = {
        {"track", text_t, none, -1, [](const C& x) { return text(a(x).id); }},
        {"name", text_t, none, -1, [](const C& x) { return text(a(x).name); }},
        {"kind", text_t, none, -1, [](const C& x) { return text(audit::to_string(x.encounter.kind)); }},
        {"hit", text_t, none, -1, [](const C&) { return text("ship"); }},
        {"charted_depth_m", real, metres, 2, [](const C&) { return null; }},
        {"danger", text_t, none, -1, [](const C&) { return text(""); }},
        {"start", datetime, utc, -1, [](const C& x) { return text(iso_time(x.encounter.start_s)); }},
        {"end", datetime, utc, -1, [](const C& x) { return text(iso_time(x.encounter.end_s)); }},
        {"duration_s", real, seconds, 3, [](const C& x) { return Value(x.encounter.end_s - x.encounter.start_s); }},
        {"min_clearance_m", real, metres, 3, [](const C& x) { return Value(x.encounter.min_clearance_m); }},
        {"penetration_m", real, metres, 3, [](const C&) { return null; }},
        {"ship_lat", real, wgs84, coordinate_decimals, [](const C& x) { return Value(x.encounter.a.position.lat); }},
        {"ship_lon", real, wgs84, coordinate_decimals, [](const C& x) { return Value(x.encounter.a.position.lon); }},
        {"heading", real, degrees, 1, [](const C& x) { return Value(x.encounter.a.heading_deg); }},
        {"fix_index", integer, none, -1, [](const C& x) { return count(x.encounter.a.fix_index); }},
        {"other_track", text_t, none, -1, [](const C& x) { return text(b(x).id); }},
        {"other_name", text_t, none, -1, [](const C& x) { return text(b(x).name); }},
        {"other_lat", real, wgs84, coordinate_decimals, [](const C& x) { return Value(x.encounter.b.position.lat); }},
        {"other_lon", real, wgs84, coordinate_decimals, [](const C& x) { return Value(x.encounter.b.position.lon); }},
        {"other_heading", real, degrees, 1, [](const C& x) { return Value(x.encounter.b.heading_deg); }},
        {"other_fix_index", integer, none, -1, [](const C& x) { return count(x.encounter.b.fix_index); }},
        {"distance_m", real, metres, 3, [](const C& x) { return Value(x.encounter.distance_m); }},
        {"label", text_t, none, -1, [](const C& x) { return text(encounter_label(x.encounter)); }},
        {"exercise", text_t, none, -1, [](const C& x) { return text(a(x).exercise); }, exercise},
        {"situation", text_t, none, -1,
         [](const C& x) {
             const auto* c = situation_of(x.result, x.encounter.a.track, x.encounter.b.track);
             return c ? text(audit::to_string(c->at_start.situation)) : null;
         },
         exercise},
        {"give_way", text_t, none, -1,
         [](const C& x) {
             const auto* c = situation_of(x.result, x.encounter.a.track, x.encounter.b.track);
             return party(x.result, c, c ? c->at_start.give_way : audit::Party::neither);
         },
         exercise},
        {"stand_on", text_t, none, -1,
         [](const C& x) {
             const auto* c = situation_of(x.result, x.encounter.a.track, x.encounter.b.track);
             return party(x.result, c, c ? c->at_start.stand_on : audit::Party::neither);
         },
         exercise},
    };
    return f;
}

const std::vector<Field<TrackRow>>& track_fields() {
    static const std::vector<Field<TrackRow>> f = {
        {"track", text_t, none, -1, [](const T& x) { return text(x.track.id); }},
        {"name", text_t, none, -1, [](const T& x) { return text(x.track.name); }},
        {"file", text_t, none, -1, [](const T& x) { return text(x.track.file); }},
        {"hull", text_t, none, -1, [](const T& x) { return text(x.track.hull); }},
        {"draught_m", real, metres, 2, [](const T& x) { return Value(x.track.draught_m); }},
        {"draught_source", text_t, none, -1, [](const T& x) { return text(x.track.draught_source); }},
        {"ship_type", integer, none, -1, [](const T& x) { return x.track.ship_type < 0 ? null : Value(std::int64_t{x.track.ship_type}); }},
        {"ship_type_text", text_t, none, -1,
         [](const T& x) { return x.track.ship_type < 0 ? null : text(track::ship_type_text(x.track.ship_type)); }},
        {"ship_type_source", text_t, none, -1, [](const T& x) { return text(x.track.ship_type_source); }},
        {"limiting_depth_m", real, metres, 2, [](const T& x) { return Value(x.track.limiting_depth_m); }},
        {"limiting_depth_source", text_t, none, -1, [](const T& x) { return text(x.track.limiting_depth_source); }},
        {"fixes", integer, none, -1, [](const T& x) { return count(x.track.fixes); }},
        {"skipped_rows", integer, none, -1, [](const T& x) { return count(x.skipped_rows); }},
        {"uncovered_fixes", integer, none, -1, [](const T& x) { return count(x.track.uncovered_fixes); }},
        {"segments", integer, none, -1, [](const T& x) { return count(x.track.segments); }},
        {"gaps", integer, none, -1, [](const T& x) { return count(x.track.gaps); }},
        {"poses", integer, none, -1, [](const T& x) { return count(x.track.poses); }},
        {"groundings", integer, none, -1, [](const T& x) { return count(x.track.groundings); }},
        {"alongside", integer, none, -1, [](const T& x) { return count(x.track.alongside); }},
        {"contacts_at_start", integer, none, -1, [](const T& x) { return count(x.track.contacts_at_start); }},
        {"expected_contacts", integer, none, -1, [](const T& x) { return count(x.track.expected_contacts); }},
        {"chart_disagreements", integer, none, -1, [](const T& x) { return count(x.track.chart_disagreements); }},
        {"cadence_s", real, seconds, 1, [](const T& x) { return Value(x.track.cadence_s); }},
        {"close_passes", integer, none, -1, [](const T& x) { return count(x.track.close_passes); }},
        {"wild_fixes", integer, none, -1, [](const T& x) { return count(x.track.wild_fixes.size()); }},
        {"jumps", integer, none, -1, [](const T& x) { return count(x.track.jumps); }},
        {"unknown_heading_fixes", integer, none, -1, [](const T& x) { return count(x.track.unknown_heading_fixes); }},
        {"min_clearance_m", real, metres, 3, [](const T& x) { return Value(x.track.min_clearance_m); }},
        {"distance_m", real, metres, 1, [](const T& x) { return Value(x.track.distance_m); }},
        {"start", datetime, utc, -1, [](const T& x) { return text(iso_time(x.track.start_s)); }},
        {"end", datetime, utc, -1, [](const T& x) { return text(iso_time(x.track.end_s)); }},
        {"exercise", text_t, none, -1, [](const T& x) { return text(x.track.exercise); }, exercise},
        {"role", text_t, none, -1, [](const T& x) { return text(audit::to_string(x.track.role)); }, exercise},
    };
    return f;
}

const std::vector<Field<HullRow>>& hull_fields() {
    static const std::vector<Field<HullRow>> f = {
        {"track", text_t, none, -1, [](const H& x) { return text(x.track); }},
        {"kind", text_t, none, -1, [](const H& x) { return text(x.kind); }},
        {"hit", text_t, none, -1, [](const H& x) { return x.hit ? text(x.hit) : null; }},
        {"start", datetime, utc, -1, [](const H& x) { return text(iso_time(x.start_s)); }},
        {"label", text_t, none, -1, [](const H& x) { return text(x.label); }},
        {"exercise", text_t, none, -1, [](const H& x) { return text(x.exercise); }, exercise},
    };
    return f;
}

const std::vector<Field<PoseRow>>& pose_fields() {
    using X = PoseRow;
    static const std::vector<Field<PoseRow>> f = {
        {"track", text_t, none, -1, [](const X& x) { return text(x.track.id); }},
        {"name", text_t, none, -1, [](const X& x) { return text(x.track.name); }},
        {"time", datetime, utc, -1, [](const X& x) { return text(iso_time(x.pose.time_s)); }},
        {"until", datetime, utc, -1, [](const X& x) { return text(iso_time(x.pose.until_s)); }},
        {"speed_kn", real, knots, 2, [](const X& x) { return Value(x.pose.speed_kn); }},
        {"heading", real, degrees, 1, [](const X& x) { return Value(x.pose.heading_deg); }},
        {"clearance_m", real, metres, 3, [](const X& x) { return x.pose.covered ? Value(x.pose.clearance_m) : null; }},
        {"contact", boolean, none, -1, [](const X& x) { return Value(x.pose.contact); }},
        {"covered", boolean, none, -1, [](const X& x) { return Value(x.pose.covered); }},
        {"fix_index", integer, none, -1, [](const X& x) { return count(x.pose.fix_index); }},
        {"fix_line", integer, none, -1, [](const X& x) { return count(x.pose.fix_line); }},
        {"exercise", text_t, none, -1, [](const X& x) { return text(x.track.exercise); }, exercise},
    };
    return f;
}

CoastRow coast_row(const ChartFeature& c) {
    return {tile_key(c.tile), coast::to_string(c.kind), coast::to_string(c.danger), c.kind == coast::HazardKind::land ? NAN : c.depth_m};
}

const std::vector<Field<CoastRow>>& coast_fields() {
    using X = CoastRow;
    static const std::vector<Field<CoastRow>> f = {
        {"tile", text_t, none, -1, [](const X& x) { return text(x.tile); }},
        {"kind", text_t, none, -1, [](const X& x) { return text(x.kind); }},
        {"danger", text_t, none, -1, [](const X& x) { return text(x.danger); }},
        {"depth_m", real, metres, 2, [](const X& x) { return Value(x.depth_m); }},
    };
    return f;
}

const std::vector<Field<ProblemRow>>& problem_fields() {
    static const std::vector<Field<ProblemRow>> f = {
        {"file", text_t, none, -1, [](const P& x) { return text(x.file); }},
        {"track", text_t, none, -1, [](const P& x) { return x.track.empty() ? null : text(x.track); }},
        {"line", integer, none, -1, [](const P& x) { return x.line ? count(x.line) : null; }},
        {"message", text_t, none, -1, [](const P& x) { return text(x.message); }},
    };
    return f;
}

const std::vector<Field<ApproachRow>>& approach_fields() {
    static const auto sit = [](const A& x) { return situation_of(x.result, x.approach.a, x.approach.b); };
    static const std::vector<Field<ApproachRow>> f = {
        {"track", text_t, none, -1, [](const A& x) { return text(x.result.tracks.at(x.approach.a).summary.id); }},
        {"other_track", text_t, none, -1, [](const A& x) { return text(x.result.tracks.at(x.approach.b).summary.id); }},
        {"time", datetime, utc, -1, [](const A& x) { return text(iso_time(x.approach.time_s)); }},
        {"clearance_m", real, metres, 3, [](const A& x) { return Value(x.approach.clearance_m); }},
        {"distance_m", real, metres, 3, [](const A& x) { return Value(x.approach.distance_m); }},
        {"ship_lat", real, wgs84, coordinate_decimals, [](const A& x) { return Value(x.approach.a_position.lat); }},
        {"ship_lon", real, wgs84, coordinate_decimals, [](const A& x) { return Value(x.approach.a_position.lon); }},
        {"other_lat", real, wgs84, coordinate_decimals, [](const A& x) { return Value(x.approach.b_position.lat); }},
        {"other_lon", real, wgs84, coordinate_decimals, [](const A& x) { return Value(x.approach.b_position.lon); }},
        {"exercise", text_t, none, -1, [](const A& x) { return text(x.result.tracks.at(x.approach.a).summary.exercise); }},
        {"situation", text_t, none, -1, [](const A& x) { const auto* c = sit(x); return c ? text(audit::to_string(c->at_start.situation)) : null; }},
        {"give_way", text_t, none, -1, [](const A& x) { const auto* c = sit(x); return party(x.result, c, c ? c->at_start.give_way : audit::Party::neither); }},
        {"stand_on", text_t, none, -1, [](const A& x) { const auto* c = sit(x); return party(x.result, c, c ? c->at_start.stand_on : audit::Party::neither); }},
        {"situation_start", datetime, utc, -1, [](const A& x) { const auto* c = sit(x); return c ? text(iso_time(c->start_s)) : null; }},
        {"situation_end", datetime, utc, -1, [](const A& x) { const auto* c = sit(x); return c ? text(iso_time(c->end_s)) : null; }},
        {"bearing_deg", real, degrees, 1, [](const A& x) { const auto* c = sit(x); return c ? Value(c->at_start.bearing_of_b_deg) : null; }},
        {"other_bearing_deg", real, degrees, 1, [](const A& x) { const auto* c = sit(x); return c ? Value(c->at_start.bearing_of_a_deg) : null; }},
        {"cpa_m", real, metres, 1, [](const A& x) { const auto* c = sit(x); return c ? Value(c->cpa_start.distance_m) : null; }},
        {"tcpa_s", real, seconds, 1, [](const A& x) { const auto* c = sit(x); return c ? Value(c->cpa_start.time_s) : null; }},
        {"closest_distance_m", real, metres, 1, [](const A& x) { const auto* c = sit(x); return c ? Value(c->closest_m) : null; }},
        {"closest_time", datetime, utc, -1, [](const A& x) { const auto* c = sit(x); return c ? text(iso_time(c->closest_s)) : null; }},
        {"track_action", text_t, none, -1, [](const A& x) { const auto* c = sit(x); return c ? action_text(c->action_a) : null; }},
        {"track_action_time", text_t, utc, -1,
         [](const A& x) { const auto* c = sit(x); return c && !std::isnan(c->action_a.time_s) ? text(iso_time(c->action_a.time_s)) : null; }},
        {"other_action", text_t, none, -1, [](const A& x) { const auto* c = sit(x); return c ? action_text(c->action_b) : null; }},
        {"other_action_time", text_t, utc, -1,
         [](const A& x) { const auto* c = sit(x); return c && !std::isnan(c->action_b.time_s) ? text(iso_time(c->action_b.time_s)) : null; }},
    };
    return f;
}

const std::vector<Field<RunRow>>& run_fields() {
    static const std::vector<Field<RunRow>> f = {
        {"version", text_t, none, -1, [](const R&) { return text(SHOAL_VERSION_STRING); }},
        {"coast", text_t, none, -1, [](const R& x) { return text(x.info.coast); }},
        {"frame", text_t, none, -1, [](const R& x) { return text(x.info.frame); }},
        {"cell_m", real, metres, -1, [](const R& x) { return Value(x.info.cell_m); }},
        {"limiting_depth_m", real, metres, -1, [](const R& x) { return Value(x.info.limiting_depth_m); }},
        {"limiting_depth_source", text_t, none, -1, [](const R& x) { return text(x.info.limiting_depth_source); }},
        {"ukc_m", real, metres, -1, [](const R& x) { return Value(x.info.ukc_m); }},
        {"grid_fingerprint", text_t, none, -1, [](const R& x) { return text(x.info.grid_fingerprint); }},
        {"chart_fingerprint", text_t, none, -1, [](const R& x) { return text(x.info.chart_fingerprint); }},
        {"ship", text_t, none, -1, [](const R& x) { return text(x.info.ship); }},
        {"step_m", real, metres, -1, [](const R& x) { return Value(x.info.sweep.step_m); }},
        {"margin_m", real, metres, -1, [](const R& x) { return Value(x.info.sweep.margin_m); }},
        {"max_gap_s", real, seconds, -1, [](const R& x) { return Value(x.info.sweep.max_gap_s); }},
        {"berthing_speed_kn", real, knots, -1, [](const R& x) { return Value(x.info.sweep.berthing_speed_kn); }},
        {"stop_diameter_m", real, metres, -1, [](const R& x) { return Value(x.info.sweep.stop_diameter_m); }},
        {"stop_duration_s", real, seconds, -1, [](const R& x) { return Value(x.info.sweep.stop_duration_s); }},
        {"speed_window_s", real, seconds, -1, [](const R& x) { return Value(x.info.sweep.speed_window_s); }},
        {"poses_interval_s", real, seconds, -1, [](const R& x) { return Value(x.info.sweep.pose_interval_s); }},
        {"max_speed_kn", real, knots, -1, [](const R& x) { return Value(x.info.wild.max_speed_kn); }},
        {"world", text_t, none, -1, [](const R& x) { return text(audit::to_string(x.info.world)); }},
        {"chart_tolerance_m", real, metres, -1, [](const R& x) { return Value(x.info.evidence.chart_tolerance_m); }},
        {"berth_radius_m", real, metres, -1, [](const R& x) { return Value(x.info.evidence.berth_radius_m); }},
        {"ground_time_s", real, seconds, -1, [](const R& x) { return Value(x.info.evidence.ground_stay_s); }},
        {"berths", text_t, none, -1, [](const R& x) { return text(x.info.berths); }},
        {"berths_fingerprint", text_t, none, -1, [](const R& x) { return text(x.info.berths_fingerprint); }},
        {"berth_tolerance_m", real, metres, -1, [](const R& x) { return Value(x.info.berth_tolerance_m); }},
        {"ship_fingerprint", text_t, none, -1, [](const R& x) { return text(x.info.ship_fingerprint); }},
        {"vessels", text_t, none, -1, [](const R& x) { return text(x.info.vessels); }},
        {"vessels_fingerprint", text_t, none, -1, [](const R& x) { return text(x.info.vessels_fingerprint); }},
        {"hull_from_length_width", boolean, none, -1, [](const R& x) { return Value(x.info.hull_from_length_width); }},
        {"date", text_t, none, -1, [](const R& x) { return text(x.info.date); }},
        {"ship_margin_m", real, metres, -1, [](const R& x) { return Value(x.info.ship_margin_m); }, exercise},
        {"exercise_by", text_t, none, -1, [](const R& x) { return text(x.info.exercise_by); }, exercise},
        {"roles", text_t, none, -1, [](const R& x) { return text(x.info.roles); }, exercise},
        {"roles_fingerprint", text_t, none, -1, [](const R& x) { return text(x.info.roles_fingerprint); }, exercise},
        {"role_column", text_t, none, -1, [](const R& x) { return text(x.info.role_column); }, exercise},
        {"encounter_range_m", real, metres, -1, [](const R& x) { return Value(x.info.encounter_range_m); }, exercise},
        {"assessment_file", text_t, none, -1, [](const R& x) { return text(x.info.assessment); }, assessed},
        {"assessment_fingerprint", text_t, none, -1, [](const R& x) { return text(criteria_fingerprint(x.result.assessment.criteria, x.result.assessment.pass_mark)); }, assessed},
        {"pass_mark", real, none, -1, [](const R& x) { return std::isfinite(x.result.assessment.pass_mark) ? Value(x.result.assessment.pass_mark) : null; }, assessed},
        {"max_encounters_per_ship", integer, none, -1, [](const R& x) { return count(x.info.max_encounters_per_ship); }, exercise},
        {"shard", text_t, none, -1, [](const R& x) { return text(x.result.shard.text()); }, sharded},
    };
    return f;
}

const std::vector<Field<RunRow>>& summary_fields() {
    static const auto contacts = [](const audit::AuditResult& r) {
        return r.groundings + r.alongside + r.contacts_at_start + r.expected_contacts;
    };
    static const std::vector<Field<RunRow>> f = {
        {"files", integer, none, -1, [](const R& x) { return count(x.result.files.size()); }, nullptr, Merge::per_input},
        {"tracks", integer, none, -1, [](const R& x) { return count(x.result.tracks.size()); }},
        {"tracks_failed", integer, none, -1, [](const R& x) { return count(x.result.errors.size()); }},
        {"fixes", integer, none, -1, [](const R& x) { return count(x.result.fixes); }},
        {"poses", integer, none, -1, [](const R& x) { return count(x.result.poses); }},
        {"skipped_rows", integer, none, -1, [](const R& x) { return count(x.result.skipped_rows); }, nullptr, Merge::per_input},
        {"uncovered_fixes", integer, none, -1, [](const R& x) { return count(x.result.uncovered_fixes); }},
        {"events", integer, none, -1,
         [](const R& x) {
             const auto& r = x.result;
             return count(contacts(r) + r.close_passes + (r.has_encounters ? r.collisions + r.close_quarters : 0));
         }},
        {"groundings", integer, none, -1, [](const R& x) { return count(x.result.groundings); }},
        {"alongside", integer, none, -1, [](const R& x) { return count(x.result.alongside); }},
        {"contacts_at_start", integer, none, -1, [](const R& x) { return count(x.result.contacts_at_start); }},
        {"expected_contacts", integer, none, -1, [](const R& x) { return count(x.result.expected_contacts); }},
        {"chart_disagreements", integer, none, -1, [](const R& x) { return count(x.result.chart_disagreements); }},
        // Every shard learns from every track read: counted once per set of inputs.
        {"learned_berths", integer, none, -1,
         [](const R& x) { return count(static_cast<std::size_t>(std::count_if(x.result.places.begin(), x.result.places.end(), [](const auto& p) {
             return p.kind == audit::LearnedPlace::Kind::berth;
         }))); }, nullptr, Merge::per_input},
        {"water_cells", integer, none, -1,
         [](const R& x) { return count(static_cast<std::size_t>(std::count_if(x.result.places.begin(), x.result.places.end(), [](const auto& p) {
             return p.kind == audit::LearnedPlace::Kind::water;
         }))); }, nullptr, Merge::per_input},
        {"close_passes", integer, none, -1, [](const R& x) { return count(x.result.close_passes); }},
        {"wild_fixes", integer, none, -1, [](const R& x) { return count(x.result.wild_fixes); }},
        {"jumps", integer, none, -1, [](const R& x) { return count(x.result.jumps); }},
        {"unknown_heading_fixes", integer, none, -1, [](const R& x) { return count(x.result.unknown_heading_fixes); }},
        {"first_fix", datetime, utc, -1, [](const R& x) { return text(iso_time(x.result.first_fix_s)); }, nullptr, Merge::min_time},
        {"last_fix", datetime, utc, -1, [](const R& x) { return text(iso_time(x.result.last_fix_s)); }, nullptr, Merge::max_time},
        {"collisions", integer, none, -1, [](const R& x) { return count(x.result.collisions); }, exercise},
        {"close_quarters", integer, none, -1, [](const R& x) { return count(x.result.close_quarters); }, exercise},
        {"exercises", integer, none, -1, [](const R& x) { return count(x.result.exercises); }, exercise},
        {"situations", integer, none, -1, [](const R& x) { return count(x.result.situations_found()); }, exercise},
        {"pairs_not_listed", integer, none, -1, [](const R& x) { return count(x.result.unlisted.pairs); }, exercise},
        {"collisions_not_listed", integer, none, -1, [](const R& x) { return count(x.result.unlisted.collisions); }, exercise},
        {"close_quarters_not_listed", integer, none, -1, [](const R& x) { return count(x.result.unlisted.close_quarters); }, exercise},
        {"trainees_scored", integer, none, -1, [](const R& x) { return count(x.result.assessment.scores.size()); }, assessed},
        {"breaches", integer, none, -1, [](const R& x) { return count(x.result.assessment.breaches.size()); }, assessed},
    };
    return f;
}

const std::vector<Field<BreachRow>>& breach_fields() {
    using B = BreachRow;
    static const auto track = [](const B& x) -> const audit::TrackSummary& { return x.result.tracks.at(x.breach.track_index).summary; };
    static const std::vector<Field<BreachRow>> f = {
        {"track", text_t, none, -1, [](const B& x) { return text(x.breach.track); }},
        {"name", text_t, none, -1, [](const B& x) { return text(track(x).name); }},
        {"kind", text_t, none, -1, [](const B&) { return text("breach"); }},
        {"exercise", text_t, none, -1, [](const B& x) { return text(x.breach.exercise); }},
        {"criterion", text_t, none, -1, [](const B& x) { return text(x.breach.criterion); }},
        {"criterion_kind", text_t, none, -1, [](const B& x) { return text(audit::to_string(x.breach.kind)); }},
        {"start", datetime, utc, -1, [](const B& x) { return text(iso_time(x.breach.start_s)); }},
        {"end", datetime, utc, -1, [](const B& x) { return text(iso_time(x.breach.end_s)); }},
        {"duration_s", real, seconds, 3, [](const B& x) { return Value(x.breach.end_s - x.breach.start_s); }},
        {"worst", datetime, utc, -1, [](const B& x) { return text(iso_time(x.breach.worst_s)); }},
        {"value", real, none, 3, [](const B& x) { return Value(x.breach.value); }},
        {"limit", real, none, 3, [](const B& x) { return Value(x.breach.limit); }},
        {"unit", text_t, none, -1, [](const B& x) { return text(audit::unit_of(x.breach.kind)); }},
        {"penalty", real, none, 3, [](const B& x) { return Value(x.breach.penalty); }},
        {"other_track", text_t, none, -1, [](const B& x) { return x.breach.other.empty() ? null : text(x.breach.other); }},
        {"rule", text_t, none, -1, [](const B& x) { return x.breach.rule.empty() ? null : text(x.breach.rule); }},
        {"asked", text_t, none, -1, [](const B& x) { return text(x.breach.asked); }},
        {"did", text_t, none, -1, [](const B& x) { return text(x.breach.did); }},
        {"detail", text_t, none, -1, [](const B& x) { return text(x.breach.detail); }},
        {"label", text_t, none, -1, [](const B& x) { return text(x.breach.criterion + " " + iso_time(x.breach.start_s).substr(11)); }},
    };
    return f;
}

const std::vector<Field<LearnedRow>>& learned_fields() {
    using L = LearnedRow;
    static const std::vector<Field<LearnedRow>> f = {
        {"kind", text_t, none, -1, [](const L& x) { return text(audit::to_string(x.place.kind)); }},
        {"vessels", integer, none, -1, [](const L& x) { return count(x.place.vessels); }},
        {"count", integer, none, -1, [](const L& x) { return count(x.place.count); }},
        {"hours", real, "h", 2, [](const L& x) { return x.place.kind == audit::LearnedPlace::Kind::berth ? Value(x.place.hours) : null; }},
        {"size_m", real, metres, 1, [](const L& x) { return Value(x.place.size_m); }},
        {"first", datetime, utc, -1, [](const L& x) { return std::isfinite(x.place.first_s) ? text(iso_time(x.place.first_s)) : null; }},
        {"last", datetime, utc, -1, [](const L& x) { return std::isfinite(x.place.last_s) ? text(iso_time(x.place.last_s)) : null; }},
        {"lat", real, wgs84, coordinate_decimals, [](const L& x) { return Value(x.place.position.lat); }},
        {"lon", real, wgs84, coordinate_decimals, [](const L& x) { return Value(x.place.position.lon); }},
        {"label", text_t, none, -1,
         [](const L& x) {
             const auto n = std::to_string(x.place.vessels);
             return text(x.place.kind == audit::LearnedPlace::Kind::berth ? "berth: " + std::to_string(x.place.count) + " stays, " + n + " vessels"
                                                                            : "water: " + n + " vessels under way");
         }},
    };
    return f;
}

const std::vector<Field<ScoreRow>>& score_fields() {
    using S = ScoreRow;
    static const std::vector<Field<ScoreRow>> f = {
        {"exercise", text_t, none, -1, [](const S& x) { return text(x.score.exercise); }},
        {"track", text_t, none, -1, [](const S& x) { return text(x.score.track); }},
        {"name", text_t, none, -1, [](const S& x) { return text(x.result.tracks.at(x.score.track_index).summary.name); }},
        {"penalty", real, none, 3, [](const S& x) { return Value(x.score.penalty); }},
        {"breaches", integer, none, -1, [](const S& x) { return count(x.score.breaches); }},
        {"passed", boolean, none, -1,
         [](const S& x) { return std::isfinite(x.result.assessment.pass_mark) ? Value(x.score.passed) : null; }},
    };
    return f;
}

const std::vector<Field<CriterionRow>>& criterion_fields() {
    using K = CriterionRow;
    static const std::vector<Field<CriterionRow>> f = {
        {"id", text_t, none, -1, [](const K& x) { return text(x.criterion.id); }},
        {"kind", text_t, none, -1, [](const K& x) { return text(audit::to_string(x.criterion.kind)); }},
        {"limit", real, none, -1, [](const K& x) { return Value(x.criterion.limit); }},
        {"unit", text_t, none, -1, [](const K& x) { return text(audit::unit_of(x.criterion.kind)); }},
        {"penalty", real, none, -1, [](const K& x) { return Value(x.criterion.penalty); }},
        {"per", text_t, none, -1, [](const K& x) { return text(audit::to_string(x.criterion.per)); }},
        {"area_name", text_t, none, -1, [](const K& x) { return x.criterion.area.empty() ? null : text(x.criterion.area_name); }},
    };
    return f;
}

std::vector<TrackRow> track_rows(const audit::AuditResult& r) {
    std::map<std::string, std::size_t> skipped_by_file;
    for (const auto& f : r.files) skipped_by_file[f.file] = f.read.skipped;
    std::vector<TrackRow> rows;
    rows.reserve(r.tracks.size());
    for (const auto& t : r.tracks) rows.push_back({t.summary, skipped_by_file[t.summary.file]});
    return rows;
}

std::vector<HullRow> hull_rows(const audit::AuditResult& r) {
    std::vector<HullRow> rows;
    for (const auto& t : r.tracks)
        for (const auto& e : t.events)
            rows.push_back({t.summary.id, audit::to_string(e.kind), coast::to_string(e.hit), e.start_s, event_label(e), e.hull, t.summary.exercise});
    for (const auto& e : r.encounters.events)
        for (const audit::ShipAt* ship : {&e.a, &e.b})
            rows.push_back({r.tracks.at(ship->track).summary.id, audit::to_string(e.kind), nullptr, e.start_s, encounter_label(e), ship->hull,
                            r.tracks.at(ship->track).summary.exercise});
    return rows;
}

std::vector<ProblemRow> problem_rows(const audit::AuditResult& r) {
    std::vector<ProblemRow> rows;
    for (const auto& f : r.files) {
        if (!f.error.empty()) rows.push_back({f.file, "", 0, f.error});
        for (const auto& m : f.read.messages) rows.push_back({f.file, "", 0, m});
    }
    for (std::size_t k = 0; k < r.errors.size(); ++k) {
        const auto& e = r.errors[k];
        rows.push_back({e.file, e.track, 0, e.message, 1, position_in_run(r.error_positions, k)});
    }
    for (std::size_t k = 0; k < r.tracks.size(); ++k) {
        const auto& t = r.tracks[k];
        for (const auto& w : t.summary.wild_fixes)
            rows.push_back({t.summary.file, t.summary.id, w.line, wild_fix_message(t.summary, w), 2, position_in_run(r.track_positions, k)});
    }
    return rows;
}

}  // namespace shoal::report::fields
