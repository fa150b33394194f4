// Where a shard's rows go in one run's report (report/part_order.hpp).
#include "report/part_order.hpp"

#include "report/qgis/qgis_project.hpp"
#include <shoal/report/report_fields.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/report/run_info.hpp>

namespace shoal::report {

using json = nlohmann::ordered_json;

json part_order(const audit::AuditResult& r, bool gpkg, const geo::Box& chart) {
    const auto position = [&](std::size_t k) { return fields::position_in_run(r.track_positions, k); };
    const auto encounter_key = [&](const audit::Encounter& e) {
        return json::array({e.start_s, position(e.a.track), position(e.b.track), static_cast<unsigned>(e.kind)});
    };
    json inputs = json::array(), tracks = json::array(), features = json::array(), problems = json::array(), approaches = json::array();
    json events = json::array(), encounters = json::array(), hulls = json::array(), poses = json::array();
    // Each input's size and fingerprint: shards of a file that changed between their runs are
    // not of one run (merge compares them within a set of inputs).
    json fingerprints = json::array();
    for (const auto& f : r.files) {
        inputs.push_back(f.file);
        if (!f.fingerprint.empty()) {  // known where the file was read (partitions): not read again here
            fingerprints.push_back(json::array({f.size, f.fingerprint}));
            continue;
        }
        // Standard input or a pipe by the content as it was read (before: the name alone, and
        // shards fed other contents merged).
        const auto [size, fingerprint] = read_file_fingerprint(f);
        fingerprints.push_back(json::array({size, fingerprint}));
    }
    for (std::size_t k = 0; k < r.tracks.size(); ++k) {
        tracks.push_back(position(k));
        for (std::size_t e = 0; e < r.tracks[k].events.size(); ++e) events.push_back(position(k));
        for (std::size_t p = 0; p < r.tracks[k].poses.size(); ++p) poses.push_back(position(k));
    }
    for (const auto& e : r.encounters.events) encounters.push_back(encounter_key(e));
    // fields::hull_rows' order: each track event's hull, then both ships' hulls of each encounter.
    hulls = events;
    for (const auto& k : encounters) hulls.insert(hulls.end(), 2, k);
    // --assess: a breach's key is [its trainee's position] (one run lists them by track, then
    // time); a score's, its trainee's position.
    json breaches = json::array(), scores = json::array();
    for (const auto& b : r.assessment.breaches) breaches.push_back(json::array({position(b.track_index)}));
    for (const auto& s : r.assessment.scores) scores.push_back(position(s.track_index));
    features = events;
    features.insert(features.end(), encounters.begin(), encounters.end());
    features.insert(features.end(), breaches.begin(), breaches.end());
    for (const auto& p : fields::problem_rows(r)) problems.push_back(json::array({p.group, p.position}));
    for (const auto& a : r.encounters.approaches) approaches.push_back(json::array({position(a.a), position(a.b)}));
    json out = {{"inputs", inputs}, {"fingerprints", std::move(fingerprints)}, {"tracks", tracks}};
    if (!gpkg) out["features"] = std::move(features);
    out["problems"] = std::move(problems);
    out["approaches"] = std::move(approaches);
    if (r.has_assessment) out["scores"] = std::move(scores);
    if (gpkg) {
        if (r.has_assessment) out["breaches"] = std::move(breaches);
        const ProjectView v = project_view(r, chart);
        out["events"] = std::move(events);
        out["encounters"] = std::move(encounters);
        out["hulls"] = std::move(hulls);
        out["poses"] = std::move(poses);
        out["project"] = {{"extent", json::array({v.x0, v.y0, v.x1, v.y1})},
                          {"chart", json::array({v.chart.minx, v.chart.miny, v.chart.maxx, v.chart.maxy})},
                          {"first_fix_s", v.first_fix_s},
                          {"last_fix_s", v.last_fix_s}};
        if (!v.exercises.empty()) out["project"]["exercises"] = v.exercises;
    }
    return out;
}

}  // namespace shoal::report
