#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "report/qgis_styles.hpp"
#include "report/report.hpp"
#include "track/time.hpp"
#include "util/atomic_file.hpp"

namespace shoal::report {

using json = nlohmann::ordered_json;

std::string iso_time(double t) { return track::format_iso8601(t, 3); }

std::string event_label(const audit::Event& e) {
    std::string s = e.kind == audit::EventKind::grounding ? "aground " : "close ";
    if (e.kind == audit::EventKind::grounding && e.hit != coast::HazardKind::land) {
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
    p["penetration_m"] = e.kind == audit::EventKind::grounding ? metres(e.penetration_m) : json(nullptr);
    p["ship_lat"] = round_to(e.ship.lat, 7);
    p["ship_lon"] = round_to(e.ship.lon, 7);
    p["heading"] = round_to(e.heading_deg, 1);
    p["heading_source"] = track::to_string(e.heading_source);
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
    j["close_passes"] = t.close_passes;
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
    shoal["version"] = "0.1.0";
    shoal["coast"] = info.coast;
    shoal["frame"] = info.frame;
    shoal["cell_m"] = info.cell_m;
    shoal["limiting_depth_m"] = std::isfinite(info.limiting_depth_m) ? json(info.limiting_depth_m) : json(nullptr);
    shoal["grid_fingerprint"] = info.grid_fingerprint;
    shoal["ship"] = info.ship;
    shoal["step_m"] = info.sweep.step_m;
    shoal["margin_m"] = info.sweep.margin_m;
    shoal["max_gap_s"] = info.sweep.max_gap_s;
    json summary;
    summary["files"] = r.files.size();
    summary["tracks"] = r.tracks.size();
    summary["tracks_failed"] = r.errors.size();
    summary["fixes"] = r.fixes;
    summary["poses"] = r.poses;
    summary["skipped_rows"] = r.skipped_rows;
    summary["uncovered_fixes"] = r.uncovered_fixes;
    summary["events"] = r.groundings + r.close_passes;
    summary["groundings"] = r.groundings;
    summary["close_passes"] = r.close_passes;
    summary["first_fix"] = iso_time(r.first_fix_s);
    summary["last_fix"] = iso_time(r.last_fix_s);
    if (r.has_encounters) {
        summary["collisions"] = r.collisions;
        summary["close_quarters"] = r.close_quarters;
        summary["events"] = r.groundings + r.close_passes + r.collisions + r.close_quarters;
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

void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info) {
    write_file_atomically(path, geojson(result, info));
    // The style goes beside a report file, not beside a device (-o /dev/null) or a pipe.
    std::error_code ec;
    if (path != "-" && !path.empty() && std::filesystem::is_regular_file(path, ec)) write_sidecar_style(path, "events");
}

}  // namespace shoal::report
