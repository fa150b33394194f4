// The assessment file: scored criteria read and checked (see include/shoal/exercise/assessment.hpp;
// the scoring itself is assessment.cpp).
#include <shoal/exercise/assessment.hpp>

#include <algorithm>
#include <functional>
#include <set>

#include <nlohmann/json.hpp>

#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>

#include "geo/geos_context.hpp"
#include "util/input_file.hpp"
#include "util/json_message.hpp"
#include "util/parse_util.hpp"

namespace shoal::audit {

const char* to_string(CriterionKind k) noexcept {
    switch (k) {
        case CriterionKind::land_clearance: return "land_clearance";
        case CriterionKind::under_keel_clearance: return "under_keel_clearance";
        case CriterionKind::cpa: return "cpa";
        case CriterionKind::speed_limit: return "speed_limit";
        case CriterionKind::no_entry: return "no_entry";
        case CriterionKind::close_quarters_time: return "close_quarters_time";
        case CriterionKind::colreg: return "colreg";
    }
    return "land_clearance";
}

const char* unit_of(CriterionKind k) noexcept {
    switch (k) {
        case CriterionKind::speed_limit: return "kn";
        case CriterionKind::no_entry:
        case CriterionKind::close_quarters_time: return "s";
        case CriterionKind::land_clearance:
        case CriterionKind::under_keel_clearance:
        case CriterionKind::cpa:
        case CriterionKind::colreg: break;
    }
    return "m";
}

double Criterion::max_limit(CriterionKind k) noexcept {
    switch (k) {
        case CriterionKind::land_clearance: return 10000;
        case CriterionKind::under_keel_clearance: return 2000;
        case CriterionKind::cpa: return 100000;
        case CriterionKind::speed_limit: return 100;
        case CriterionKind::no_entry:
        case CriterionKind::colreg: return 0;
        case CriterionKind::close_quarters_time: break;
    }
    return 7 * 86400.0;
}

const char* to_string(PenaltyPer p) noexcept {
    switch (p) {
        case PenaltyPer::second: return "second";
        case PenaltyPer::metre: return "metre";
        case PenaltyPer::breach: break;
    }
    return "breach";
}

namespace {

using json = nlohmann::json;
using geo::LonLat;
using geo::XY;

bool parse_kind(const std::string& s, CriterionKind& k) {
    for (const CriterionKind c : {CriterionKind::land_clearance, CriterionKind::under_keel_clearance, CriterionKind::cpa,
                                  CriterionKind::speed_limit, CriterionKind::no_entry, CriterionKind::close_quarters_time, CriterionKind::colreg})
        if (s == to_string(c)) {
            k = c;
            return true;
        }
    return false;
}

bool has_area(CriterionKind k) { return k == CriterionKind::speed_limit || k == CriterionKind::no_entry; }

/// The area's ring, closed, checked: at least 3 distinct corners in lon/lat range, a valid polygon (GEOS).
std::vector<LonLat> parse_area(const json& a, const std::function<void(const std::string&)>& fail) {
    if (!a.is_array() || a.size() < 3) fail("\"area\" must be an array of at least 3 [lon, lat] corners");
    std::vector<LonLat> ring;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const json& p = a[i];
        const std::string where = "area[" + std::to_string(i) + "]";
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) fail(where + " is not [lon, lat]");
        const LonLat q{p[0].get<double>(), p[1].get<double>()};
        if (!(q.lon >= -180 && q.lon <= 180) || !(q.lat >= -90 && q.lat <= 90))
            fail(where + " [" + track::detail::fmt(q.lon) + ", " + track::detail::fmt(q.lat) + "] is outside lon -180..180, lat -90..90");
        ring.push_back(q);
    }
    if (!(ring.front() == ring.back())) ring.push_back(ring.front());
    if (ring.size() < 4) fail("\"area\" needs at least 3 distinct corners");
    const geo::GeosContext ctx;
    std::vector<XY> xy;
    for (const LonLat& p : ring) xy.push_back({p.lon, p.lat});
    const geo::GeomPtr poly = geo::make_polygon(ctx, {xy});
    if (GEOSisValid_r(ctx, poly.get()) != 1) {
        char* why = GEOSisValidReason_r(ctx, poly.get());
        const std::string reason = why ? why : "invalid";
        GEOSFree_r(ctx, why);
        fail("\"area\" is not a valid polygon (" + reason + ")");
    }
    return ring;
}

}  // namespace

namespace {

/// A colreg criterion's parameters: name, member of ConductOptions, least and greatest value.
struct ColregParameter {
    const char* name;
    double ConductOptions::*member;
    double least, greatest;
    bool least_open;  ///< the least value itself is refused
};
constexpr ColregParameter colreg_parameters[] = {
    {"range_m", &ConductOptions::range_m, 0, 100000, true},
    {"head_on_deg", &ConductOptions::head_on_deg, 0, 22.4, false},
    {"cpa_m", &ConductOptions::cpa_m, 0, 100000, true},
    {"early_range_m", &ConductOptions::early_range_m, 0, 100000, false},
    {"min_course_deg", &ConductOptions::min_course_deg, 0, 180, true},
    {"min_speed_change", &ConductOptions::min_speed_change, 0, 10, true},
    {"action_course_deg", &ConductOptions::action_course_deg, 0, 180, true},
    {"action_speed_change", &ConductOptions::action_speed_change, 0, 10, true},
    {"sustain_s", &ConductOptions::sustain_s, 0, 3600, false},
};

bool is_colreg_parameter(const std::string& key) {
    for (const ColregParameter& p : colreg_parameters)
        if (key == p.name) return true;
    return false;
}

ConductOptions parse_colreg(const json& c, const std::function<void(const std::string&)>& bad) {
    ConductOptions o;
    for (const ColregParameter& p : colreg_parameters) {
        if (!c.contains(p.name)) continue;
        if (!c[p.name].is_number()) bad(std::string("\"") + p.name + "\" must be a number");
        const double v = c[p.name].get<double>();
        if (!std::isfinite(v) || v < p.least || (p.least_open && v == p.least) || v > p.greatest)
            bad(std::string("\"") + p.name + "\" must be " + (p.least_open ? "> " : ">= ") + track::detail::fmt(p.least) + " and <= " +
                track::detail::fmt(p.greatest) + " (got " + track::detail::fmt(v) + ")");
        o.*p.member = v;
    }
    if (o.early_range_m > o.range_m)
        bad("\"early_range_m\" (" + track::detail::fmt(o.early_range_m) + ") is beyond \"range_m\" (" + track::detail::fmt(o.range_m) +
            "): no action could be early");
    return o;
}

}  // namespace

Assessment Assessment::parse(const std::string& text, const std::string& source) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {  // a syntax error, or a number too large for a double (out_of_range 406)
        throw InputError("assessment file '" + source + "': not JSON: " + shoal::detail::json_error_text(e.what()));
    }
    auto fail = [&](const std::string& what) { throw InputError("assessment file '" + source + "': " + what); };
    if (!j.is_object()) fail("not a JSON object");
    for (const auto& [key, _] : j.items())
        if (key != "criteria" && key != "$schema" && key != "description" && key != "pass_mark") fail("unknown member '" + shoal::detail::shortened(key) + "'");
    if (!j.contains("criteria") || !j["criteria"].is_array()) fail("no \"criteria\" array");
    if (j["criteria"].empty()) fail("\"criteria\" is empty: nothing to assess");
    Assessment a;
    a.source = source;
    if (j.contains("pass_mark")) {
        if (!j["pass_mark"].is_number()) fail("\"pass_mark\" must be a number (the largest penalty that passes)");
        a.pass_mark = j["pass_mark"].get<double>();
        if (!std::isfinite(a.pass_mark) || a.pass_mark < 0) fail("\"pass_mark\" must be >= 0 (got " + track::detail::fmt(a.pass_mark) + ")");
    }
    std::set<std::string> ids;
    std::size_t n = 0;
    for (const json& c : j["criteria"]) {
        std::string where = "criteria[" + std::to_string(n++) + "]";
        auto bad = [&](const std::string& what) { fail(where + ": " + what); };
        if (!c.is_object()) bad("not an object");
        Criterion cr;
        if (c.contains("id")) {
            if (!c["id"].is_string() || c["id"].get<std::string>().empty()) bad("\"id\" must be a non-empty string");
            cr.id = c["id"].get<std::string>();
            where += " (id '" + shoal::detail::shortened(cr.id) + "')";
        }
        for (const auto& [key, _] : c.items())
            if (key != "id" && key != "kind" && key != "limit" && key != "penalty" && key != "per" && key != "area" && key != "area_name" &&
                key != "description" && !is_colreg_parameter(key))
                bad("unknown member '" + shoal::detail::shortened(key) + "'");
        if (!c.contains("kind") || !c["kind"].is_string() || !parse_kind(c["kind"].get<std::string>(), cr.kind))
            bad("\"kind\" must be one of land_clearance, under_keel_clearance, cpa, speed_limit, no_entry, close_quarters_time, colreg");
        const bool explicit_id = !cr.id.empty();
        if (!explicit_id) {
            cr.id = std::string(to_string(cr.kind)) + "-" + std::to_string(n);
            where += " (id '" + cr.id + "')";
        }
        if (!ids.insert(cr.id).second)
            bad(explicit_id ? "id '" + shoal::detail::shortened(cr.id) + "' is given twice (or is an earlier criterion's default id, kind-position)"
                            : "its default id '" + cr.id + "' (kind-position) is the id another criterion gives: give this one an \"id\"");
        if (cr.kind != CriterionKind::colreg)
            for (const auto& [key, _] : c.items())
                if (is_colreg_parameter(key)) bad("\"" + key + "\" is a parameter of a colreg criterion only");
        if (cr.kind == CriterionKind::no_entry) {
            if (c.contains("limit") && !(c["limit"].is_number() && c["limit"].get<double>() == 0))
                bad("a no_entry criterion has no \"limit\" (any time inside is a breach)");
        } else if (cr.kind == CriterionKind::colreg) {
            if (c.contains("limit")) bad("a colreg criterion has no \"limit\" (its parameters say how each rule is read)");
            cr.colreg = parse_colreg(c, bad);
        } else {
            if (!c.contains("limit") || !c["limit"].is_number()) bad(std::string("\"limit\" must be a number (") + unit_of(cr.kind) + ")");
            cr.limit = c["limit"].get<double>();
            if (!std::isfinite(cr.limit) || cr.limit < 0) bad("\"limit\" must be >= 0 (got " + track::detail::fmt(cr.limit) + ")");
            if (cr.limit > Criterion::max_limit(cr.kind))
                bad("\"limit\" must be at most " + track::detail::fmt(Criterion::max_limit(cr.kind)) + " " + unit_of(cr.kind) + " (got " +
                    track::detail::fmt(cr.limit) + ")");
            if (cr.kind != CriterionKind::close_quarters_time && cr.kind != CriterionKind::speed_limit && cr.limit == 0)
                bad("\"limit\" 0 m can never be breached");
        }
        if (!c.contains("penalty") || !c["penalty"].is_number()) bad("\"penalty\" must be a number");
        cr.penalty = c["penalty"].get<double>();
        if (!std::isfinite(cr.penalty) || cr.penalty < 0) bad("\"penalty\" must be >= 0 (got " + track::detail::fmt(cr.penalty) + ")");
        if (cr.penalty > Criterion::max_penalty)
            bad("\"penalty\" must be at most " + track::detail::fmt(Criterion::max_penalty) + " (got " + track::detail::fmt(cr.penalty) + ")");
        if (c.contains("per")) {
            const std::string per = c["per"].is_string() ? c["per"].get<std::string>() : "";
            if (per == "breach") cr.per = PenaltyPer::breach;
            else if (per == "second") cr.per = PenaltyPer::second;
            else if (per == "metre") cr.per = PenaltyPer::metre;
            else bad("\"per\" must be \"breach\", \"second\" or \"metre\"");
            if (cr.kind == CriterionKind::colreg && cr.per != PenaltyPer::breach)
                bad("a colreg criterion is charged per breach (\"per\": \"breach\")");
            if (cr.per == PenaltyPer::metre && (cr.kind == CriterionKind::no_entry || cr.kind == CriterionKind::close_quarters_time))
                bad(std::string("\"per\": \"metre\" means nothing for ") + to_string(cr.kind) + " (use \"breach\" or \"second\")");
        }
        if (has_area(cr.kind)) {
            if (!c.contains("area")) bad(std::string("a ") + to_string(cr.kind) + " criterion needs an \"area\" ([[lon, lat], ...])");
            cr.area = parse_area(c["area"], bad);
            // The area is scored in the run's local metres, true over a few hundred km: an area
            // of a continent would fold in that frame and score nothing.
            const auto [lon0, lon1] = std::minmax_element(cr.area.begin(), cr.area.end(), [](const LonLat& p, const LonLat& q) { return p.lon < q.lon; });
            const auto [lat0, lat1] = std::minmax_element(cr.area.begin(), cr.area.end(), [](const LonLat& p, const LonLat& q) { return p.lat < q.lat; });
            const double span = std::max(lon1->lon - lon0->lon, lat1->lat - lat0->lat);
            if (span > Criterion::max_area_span_deg)
                bad("\"area\" spans " + track::detail::fmt(span) + " degrees: at most " + track::detail::fmt(Criterion::max_area_span_deg) +
                    " (the waters of an exercise, scored in the run's local metres)");
            if (c.contains("area_name")) {
                if (!c["area_name"].is_string()) bad("\"area_name\" must be a string");
                cr.area_name = c["area_name"].get<std::string>();
            }
        } else if (c.contains("area") || c.contains("area_name")) {
            bad(std::string("a ") + to_string(cr.kind) + " criterion has no \"area\"");
        }
        a.criteria.push_back(std::move(cr));
    }
    return a;
}

Assessment Assessment::load(const std::string& path) {
    return parse(shoal::detail::read_json_settings(path, max_file_bytes, "an assessment file", "assessment file"), path);
}

}  // namespace shoal::audit
