#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "detail/qgis_styles.hpp"
#include <shoal/report/report.hpp>
#include <shoal/version.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/atomic_file.hpp>

namespace shoal::report {

using json = nlohmann::ordered_json;

std::string iso_time(double t) { return track::format_iso8601(t, 3); }

std::string event_label(const audit::Event& e) {
    using audit::EventKind;
    std::string s = e.kind == EventKind::grounding          ? "aground "
                    : e.kind == EventKind::alongside        ? "alongside "
                    : e.kind == EventKind::contact_at_start ? "in contact at start "
                    : e.kind == EventKind::expected_contact ? "contact in " + (e.area_kind.empty() ? std::string("area") : e.area_kind) + " "
                                                            : "close ";
    if (audit::is_contact(e.kind) && e.hit != coast::HazardKind::land) {
        s += e.hit == coast::HazardKind::danger ? coast::to_string(e.danger) : coast::to_string(e.hit);
        if (std::isfinite(e.charted_depth_m)) {
            char depth[32];
            std::snprintf(depth, sizeof depth, " %.1f m", e.charted_depth_m);
            s += depth;
        }
        s += " ";
    }
    return s + iso_time(e.start_s).substr(11);
}

namespace {

double round_to(double v, double decimals) {
    const double k = std::pow(10.0, decimals);
    return std::round(v * k) / k;
}

/// Metres with millimetres, or null for "beyond the search limit".
json metres(double v) { return std::isfinite(v) ? json(round_to(v, 3)) : json(nullptr); }

}  // namespace

std::string wild_fix_message(const audit::TrackSummary& t, const track::WildFix& w) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " line %zu: fix at %.6f, %.6f (", w.line, w.position.lat, w.position.lon);
    return t.file + buf + iso_time(w.time_s) + ") of track '" + t.id + "' dropped as an outlier: " + w.why;
}

namespace {

json event_properties(const audit::TrackSummary& t, const audit::Event& e) {
    json p;
    p["track"] = t.id;
    p["name"] = t.name;
    p["kind"] = audit::to_string(e.kind);
    p["hit"] = coast::to_string(e.hit);
    p["charted_depth_m"] = e.hit != coast::HazardKind::land && std::isfinite(e.charted_depth_m) ? json(round_to(e.charted_depth_m, 2)) : json(nullptr);
    p["danger"] = coast::to_string(e.danger);
    p["start"] = iso_time(e.start_s);
    p["end"] = iso_time(e.end_s);
    p["duration_s"] = round_to(e.end_s - e.start_s, 3);
    p["min_clearance_m"] = metres(e.min_clearance_m);
    p["penetration_m"] = audit::is_contact(e.kind) ? metres(e.penetration_m) : json(nullptr);
    p["ship_lat"] = round_to(e.ship.lat, 7);
    p["ship_lon"] = round_to(e.ship.lon, 7);
    p["heading"] = std::isfinite(e.heading_deg) ? json(round_to(e.heading_deg, 1)) : json(nullptr);
    p["heading_source"] = track::to_string(e.heading_source);
    p["orientation"] = e.orientation_unknown ? "unknown (hull circle)" : "hull";
    p["speed_kn"] = std::isfinite(e.speed_kn) ? json(round_to(e.speed_kn, 2)) : json(nullptr);
    p["speed_source"] = track::to_string(e.speed_source);
    const bool contact = audit::is_contact(e.kind);
    p["stopped_before"] = contact ? json(e.stopped_before) : json(nullptr);
    p["stopped_after_s"] = contact && std::isfinite(e.stopped_after_s) ? json(round_to(e.stopped_after_s, 1)) : json(nullptr);
    p["reference_inside_m"] = contact && std::isfinite(e.reference_inside_m) ? json(round_to(e.reference_inside_m, 2)) : json(nullptr);
    p["nav_status"] = e.nav_status == track::nav_status_unknown ? json(nullptr) : json(e.nav_status);
    p["nav_status_text"] = track::nav_status_text(e.nav_status);
    p["reported_aground"] = e.reported_aground;
    p["unseen_after"] = e.unseen_after;
    p["area"] = e.area_kind;
    p["area_name"] = e.area_name;
    p["structure"] = e.structure;
    p["fix_index"] = e.fix_index;
    p["fix_line"] = e.fix_line;
    p["file"] = t.file;
    p["hull"] = t.hull;
    p["label"] = event_label(e);
    return p;
}

json track_summary(const audit::TrackSummary& t) {
    json j;
    j["track"] = t.id;
    j["name"] = t.name;
    j["file"] = t.file;
    j["hull"] = t.hull;
    j["fixes"] = t.fixes;
    j["uncovered_fixes"] = t.uncovered_fixes;
    j["segments"] = t.segments;
    j["gaps"] = t.gaps;
    j["poses"] = t.poses;
    j["groundings"] = t.groundings;
    j["alongside"] = t.alongside;
    j["contacts_at_start"] = t.contacts_at_start;
    j["expected_contacts"] = t.expected_contacts;
    j["close_passes"] = t.close_passes;
    j["wild_fixes"] = t.wild_fixes.size();
    j["jumps"] = t.jumps;
    j["unknown_heading_fixes"] = t.unknown_heading_fixes;
    j["min_clearance_m"] = metres(t.min_clearance_m);
    j["distance_m"] = round_to(t.distance_m, 1);
    j["start"] = iso_time(t.start_s);
    j["end"] = iso_time(t.end_s);
    return j;
}

/// Properties of a ship-to-ship encounter: the same core fields as an event (of ship a), plus
/// the other ship.
json encounter_properties(const audit::AuditResult& r, const audit::Encounter& e) {
    const auto& ta = r.tracks.at(e.a.track).summary;
    const auto& tb = r.tracks.at(e.b.track).summary;
    json p;
    p["track"] = ta.id;
    p["name"] = ta.name;
    p["kind"] = audit::to_string(e.kind);
    p["hit"] = "ship";
    p["charted_depth_m"] = nullptr;
    p["danger"] = "";
    p["start"] = iso_time(e.start_s);
    p["end"] = iso_time(e.end_s);
    p["duration_s"] = round_to(e.end_s - e.start_s, 3);
    p["min_clearance_m"] = metres(e.min_clearance_m);
    p["penetration_m"] = nullptr;
    p["ship_lat"] = round_to(e.a.position.lat, 7);
    p["ship_lon"] = round_to(e.a.position.lon, 7);
    p["heading"] = round_to(e.a.heading_deg, 1);
    p["fix_index"] = e.a.fix_index;
    p["other_track"] = tb.id;
    p["other_name"] = tb.name;
    p["other_lat"] = round_to(e.b.position.lat, 7);
    p["other_lon"] = round_to(e.b.position.lon, 7);
    p["other_heading"] = round_to(e.b.heading_deg, 1);
    p["other_fix_index"] = e.b.fix_index;
    p["distance_m"] = round_to(e.distance_m, 3);
    p["label"] = std::string(e.kind == audit::EncounterKind::collision ? "collision " : "close quarters ") + iso_time(e.start_s).substr(11);
    return p;
}

}  // namespace

std::string geojson(const audit::AuditResult& r, const RunInfo& info) {
    json doc;
    doc["type"] = "FeatureCollection";
    json shoal;
    shoal["version"] = SHOAL_VERSION_STRING;
    shoal["coast"] = info.coast;
    shoal["frame"] = info.frame;
    shoal["cell_m"] = info.cell_m;
    shoal["limiting_depth_m"] = std::isfinite(info.limiting_depth_m) ? json(info.limiting_depth_m) : json(nullptr);
    shoal["grid_fingerprint"] = info.grid_fingerprint;
    shoal["ship"] = info.ship;
    shoal["step_m"] = info.sweep.step_m;
    shoal["margin_m"] = info.sweep.margin_m;
    shoal["max_gap_s"] = info.sweep.max_gap_s;
    shoal["berthing_speed_kn"] = info.sweep.berthing_speed_kn;
    shoal["stop_diameter_m"] = info.sweep.stop_diameter_m;
    shoal["stop_duration_s"] = info.sweep.stop_duration_s;
    shoal["speed_window_s"] = info.sweep.speed_window_s;
    shoal["max_speed_kn"] = info.wild.max_speed_kn;
    shoal["berths"] = info.berths;
    json summary;
    summary["files"] = r.files.size();
    summary["tracks"] = r.tracks.size();
    summary["tracks_failed"] = r.errors.size();
    summary["fixes"] = r.fixes;
    summary["poses"] = r.poses;
    summary["skipped_rows"] = r.skipped_rows;
    summary["uncovered_fixes"] = r.uncovered_fixes;
    const std::size_t contacts = r.groundings + r.alongside + r.contacts_at_start + r.expected_contacts;
    summary["events"] = contacts + r.close_passes;
    summary["groundings"] = r.groundings;
    summary["alongside"] = r.alongside;
    summary["contacts_at_start"] = r.contacts_at_start;
    summary["expected_contacts"] = r.expected_contacts;
    summary["close_passes"] = r.close_passes;
    summary["wild_fixes"] = r.wild_fixes;
    summary["jumps"] = r.jumps;
    summary["unknown_heading_fixes"] = r.unknown_heading_fixes;
    summary["first_fix"] = iso_time(r.first_fix_s);
    summary["last_fix"] = iso_time(r.last_fix_s);
    if (r.has_encounters) {
        summary["collisions"] = r.collisions;
        summary["close_quarters"] = r.close_quarters;
        summary["events"] = contacts + r.close_passes + r.collisions + r.close_quarters;
        shoal["ship_margin_m"] = info.ship_margin_m;
        json approaches = json::array();
        for (const auto& a : r.encounters.approaches)
            approaches.push_back({{"track", r.tracks.at(a.a).summary.id},
                                  {"other_track", r.tracks.at(a.b).summary.id},
                                  {"time", iso_time(a.time_s)},
                                  {"clearance_m", metres(a.clearance_m)},
                                  {"distance_m", round_to(a.distance_m, 3)},
                                  {"ship_lat", round_to(a.a_position.lat, 7)},
                                  {"ship_lon", round_to(a.a_position.lon, 7)},
                                  {"other_lat", round_to(a.b_position.lat, 7)},
                                  {"other_lon", round_to(a.b_position.lon, 7)}});
        shoal["closest_approaches"] = approaches;
    }
    shoal["summary"] = summary;
    json tracks = json::array();
    for (const auto& t : r.tracks) tracks.push_back(track_summary(t.summary));
    shoal["tracks"] = tracks;
    json problems = json::array();
    for (const auto& f : r.files) {
        if (!f.error.empty()) problems.push_back({{"file", f.file}, {"message", f.error}});
        for (const auto& m : f.read.messages) problems.push_back({{"file", f.file}, {"message", m}});
    }
    for (const auto& e : r.errors) problems.push_back({{"file", e.file}, {"track", e.track}, {"message", e.message}});
    for (const auto& t : r.tracks)
        for (const auto& w : t.summary.wild_fixes)
            problems.push_back({{"file", t.summary.file}, {"track", t.summary.id}, {"line", w.line},
                                {"message", wild_fix_message(t.summary, w)}});
    shoal["problems"] = problems;
    doc["shoal"] = shoal;

    json features = json::array();
    for (const auto& t : r.tracks)
        for (const auto& e : t.events) {
            json f;
            f["type"] = "Feature";
            f["geometry"] = {{"type", "Point"}, {"coordinates", {round_to(e.point.lon, 7), round_to(e.point.lat, 7)}}};
            f["properties"] = event_properties(t.summary, e);
            features.push_back(std::move(f));
        }
    for (const auto& e : r.encounters.events) {
        json f;
        f["type"] = "Feature";
        f["geometry"] = {{"type", "Point"}, {"coordinates", {round_to(e.point.lon, 7), round_to(e.point.lat, 7)}}};
        f["properties"] = encounter_properties(r, e);
        features.push_back(std::move(f));
    }
    doc["features"] = features;
    return doc.dump(1) + "\n";
}

void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info, std::vector<std::string>* warnings) {
    write_file_atomically(path, geojson(result, info));
    // The style goes beside a report file, not beside a device (-o /dev/null) or a pipe.
    std::error_code ec;
    if (path != "-" && !path.empty() && std::filesystem::is_regular_file(path, ec))
        if (std::string w = write_sidecar_style(path, "events"); !w.empty() && warnings) warnings->push_back(std::move(w));
}

}  // namespace shoal::report
