#include <cmath>
#include <nlohmann/json.hpp>

#include "report/qgis_styles.hpp"
#include "report/report.hpp"
#include "track/time.hpp"
#include "util/atomic_file.hpp"

namespace shoal::report {

using json = nlohmann::ordered_json;

std::string iso_time(double t) { return track::format_iso8601(t, 3); }

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
    p["label"] = std::string(e.kind == audit::EventKind::grounding ? "aground " : "close ") + iso_time(e.start_s).substr(11);
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

}  // namespace

std::string geojson(const audit::AuditResult& r, const RunInfo& info) {
    json doc;
    doc["type"] = "FeatureCollection";
    json shoal;
    shoal["version"] = "0.1.0";
    shoal["coast"] = info.coast;
    shoal["frame"] = info.frame;
    shoal["cell_m"] = info.cell_m;
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
    doc["features"] = features;
    return doc.dump(1) + "\n";
}

void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info) {
    write_file_atomically(path, geojson(result, info));
    if (path != "-" && !path.empty()) write_sidecar_style(path, "events");
}

}  // namespace shoal::report
