#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <type_traits>
#include <variant>

#include "detail/qgis_styles.hpp"
#include "report/geojson_output.hpp"
#include "report/report_fields.hpp"
#include <shoal/report/report.hpp>
#include <shoal/version.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/output_file.hpp>

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

std::string wild_fix_message(const audit::TrackSummary& t, const track::WildFix& w) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " line %zu: fix at %.6f, %.6f (", w.line, w.position.lat, w.position.lon);
    return t.file + buf + iso_time(w.time_s) + ") of track '" + t.id + "' dropped as an outlier: " + w.why;
}

namespace {

json to_json(const fields::Value& v) {
    return std::visit([](const auto& x) -> json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>) return nullptr;
        else return x;
    }, v);
}

/// One row of a layer as a JSON object: every field of the table, in its order. `omit_null`:
/// fields whose value is null are left out (problems: "track" and "line" only when known).
template <class Row>
json object_of(const std::vector<fields::Field<Row>>& table, const Row& row, const audit::AuditResult& r, bool omit_null = false) {
    json j = json::object();
    for (const auto& f : table) {
        if (f.present && !f.present(r)) continue;
        fields::Value v = fields::value_of(f, row);
        if (omit_null && std::holds_alternative<std::monostate>(v)) continue;
        j[f.name] = to_json(v);
    }
    return j;
}

json point_feature(geo::LonLat p, json properties) {
    using fields::round_to, fields::coordinate_decimals;
    json f;
    f["type"] = "Feature";
    f["geometry"] = {{"type", "Point"}, {"coordinates", {round_to(p.lon, coordinate_decimals), round_to(p.lat, coordinate_decimals)}}};
    f["properties"] = std::move(properties);
    return f;
}

}  // namespace

std::string geojson(const audit::AuditResult& r, const RunInfo& info) {
    const fields::RunRow run{r, info};
    json doc;
    doc["type"] = "FeatureCollection";
    json shoal = object_of(fields::run_fields(), run, r);
    if (r.has_encounters) {
        json approaches = json::array();
        for (const auto& a : r.encounters.approaches) approaches.push_back(object_of(fields::approach_fields(), fields::ApproachRow{r, a}, r));
        shoal["closest_approaches"] = approaches;
    }
    shoal["summary"] = object_of(fields::summary_fields(), run, r);
    json tracks = json::array();
    for (const auto& t : fields::track_rows(r)) tracks.push_back(object_of(fields::track_fields(), t, r));
    shoal["tracks"] = tracks;
    json problems = json::array();
    for (const auto& p : fields::problem_rows(r)) problems.push_back(object_of(fields::problem_fields(), p, r, true));
    shoal["problems"] = problems;

    // A shard's report (--shard) also says where each of its rows goes in one run's order,
    // for `merge`: each track's position among the run's tracks, each feature's track
    // position (-1: a feature of the run, after the tracks'), each problem's group and
    // position (report_fields.hpp: ProblemRow).
    const bool part = r.shard.active();
    json order_tracks = json::array(), order_features = json::array(), order_problems = json::array(), inputs = json::array();
    const auto position = [&](std::size_t k) { return k < r.track_positions.size() ? r.track_positions[k] : k; };
    json features = json::array();
    for (std::size_t k = 0; k < r.tracks.size(); ++k) {
        const auto& t = r.tracks[k];
        if (part) order_tracks.push_back(position(k));
        for (const auto& e : t.events) {
            features.push_back(point_feature(e.point, object_of(fields::event_fields(), fields::EventRow{t.summary, e}, r)));
            if (part) order_features.push_back(position(k));
        }
    }
    for (const auto& e : r.encounters.events) {
        features.push_back(point_feature(e.point, object_of(fields::encounter_fields(), fields::EncounterRow{r, e}, r)));
        if (part) order_features.push_back(-1);
    }
    if (part) {
        for (const auto& p : fields::problem_rows(r)) order_problems.push_back(json::array({p.group, p.position}));
        for (const auto& f : r.files) inputs.push_back(f.file);
        shoal["part"] = {{"inputs", inputs}, {"tracks", order_tracks}, {"features", order_features}, {"problems", order_problems}};
    }
    doc["shoal"] = shoal;
    doc["features"] = features;
    return doc.dump(1) + "\n";
}

namespace {

/// Where a GeoJSON report's QGIS style goes: REPORT.qml beside it (not beside stdout, a device or a pipe).
std::string style_path(const std::string& report) {
    std::error_code ec;
    if (is_standard_output(report) || is_system_path(report)) return {};
    if (const auto st = std::filesystem::status(report, ec); std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) return {};
    return std::filesystem::path(report).replace_extension(".qml").string();
}

}  // namespace

std::vector<OutputSpec> report_outputs(const std::string& path, const std::string& format) {
    std::vector<OutputSpec> out{{path, "-o", "the report"}};
    if (format != "gpkg")
        if (std::string style = style_path(path); !style.empty()) out.push_back({std::move(style), "-o", "the QGIS style of the report"});
    return out;
}

std::vector<StagedOutput> stage_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info,
                                        std::vector<std::string>* warnings) {
    return stage_geojson_text(path, geojson(result, info), warnings);
}

std::vector<StagedOutput> stage_geojson_text(const std::string& path, std::string_view text, std::vector<std::string>* warnings) {
    std::vector<StagedOutput> out;
    out.emplace_back(path);
    out.back().write(text);
    if (const std::string style = style_path(path); !style.empty()) {
        std::string warning;
        if (std::optional<StagedOutput> s = stage_sidecar_style(style, "events", warning)) out.push_back(std::move(*s));
        else if (warnings) warnings->push_back(std::move(warning));
    }
    return out;
}

void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info, std::vector<std::string>* warnings) {
    std::vector<StagedOutput> staged = stage_geojson(path, result, info, warnings);
    commit_all(staged);
}

}  // namespace shoal::report
