#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <exception>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <system_error>
#include <thread>
#include <type_traits>
#include <variant>
#include <vector>

#include "util/fixed_decimal.hpp"
#include "util/parallel.hpp"
#include "report/qgis/qgis_styles.hpp"
#include "report/qgis/chart_layer.hpp"
#include "report/geojson_output.hpp"
#include "report/json_text.hpp"
#include "report/gpkg_output.hpp"
#include "report/qgis/qgis_project.hpp"
#include "report/part_order.hpp"
#include <shoal/report/report_fields.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/report/geojson_report.hpp>
#include <shoal/report/gpkg_report.hpp>
#include <shoal/version.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>
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
                    : e.kind == EventKind::chart_disagrees  ? "chart disagrees "
                                                            : "close ";
    if (audit::is_contact(e.kind) && e.hit != coast::HazardKind::land) {
        s += e.hit == coast::HazardKind::danger                               ? coast::to_string(e.danger)
             : e.hit == coast::HazardKind::structure && !e.structure.empty() ? e.structure
                                                                              : coast::to_string(e.hit);
        if (e.hit == coast::HazardKind::structure && !e.hit_name.empty()) s += " '" + e.hit_name + "'";
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

/// Writes the report to a sink as nlohmann's dump(1) of the whole document would, one
/// member or element at a time (only one feature a thread is ever held as JSON; the events'
/// features are made on threads, a few blocks of them held as text: values()), in pieces of
/// about a mebibyte.
class Stream {
public:
    explicit Stream(const StagedOutput::Sink& sink) : m_sink(sink) { m_buf.reserve(chunk + 4096); }
    ~Stream() = default;
    Stream(const Stream&) = delete;
    Stream& operator=(const Stream&) = delete;

    void put(std::string_view s) {
        m_buf += s;
        if (m_buf.size() >= chunk) flush();
    }
    void flush() {
        if (!m_buf.empty()) m_sink(m_buf);
        m_buf.clear();
    }
    /// A field's value (a scalar: the same text at any depth).
    void scalar(const fields::Value& v) {
        append_json_value(m_buf, v);
        if (m_buf.size() >= chunk) flush();
    }
    /// A value nested `depth` levels deep (see render).
    void value(const json& j, int depth) {
        render(j, depth, m_buf);
        if (m_buf.size() >= chunk) flush();
    }
    /// Appends to `out` what value(j, depth) writes: j's dump(1) with every line after the
    /// first indented by `depth` (JSON strings hold no raw newline).
    static void render(const json& j, int depth, std::string& out) {
        const std::string d = j.dump(1, ' ', false, json::error_handler_t::replace);  // (json_text.cpp: bytes that are not UTF-8)
        std::size_t from = 0;
        for (std::size_t nl; (nl = d.find('\n', from)) != std::string::npos; from = nl + 1) {
            out.append(d, from, nl + 1 - from);
            out.append(spaces, static_cast<std::size_t>(depth));
        }
        out.append(d, from);
    }
    /// Elements 0 .. n-1 of an open array nested `depth` levels deep, each the text `make(k,
    /// out)` appends (what value(element k, depth + 1) writes): made a block at a time on
    /// `jobs` threads, written in order.
    void values(std::size_t n, int depth, unsigned jobs, const std::function<void(std::size_t, std::string&)>& make) {
        constexpr std::size_t block = 512;
        const unsigned threads = detail::thread_count(jobs);
        const std::size_t blocks = (n + block - 1) / block, window = 4 * std::size_t{threads};
        std::vector<std::vector<std::string>> text(std::min(blocks, window));
        std::vector<std::exception_ptr> failed(text.size());
        for (std::size_t b0 = 0; b0 < blocks; b0 += window) {
            const std::size_t m = std::min(window, blocks - b0);
            detail::parallel_for(m, threads, [&](std::size_t i, unsigned) {
                std::vector<std::string>& out = text[i];
                out.clear();
                try {
                    for (std::size_t k = (b0 + i) * block, end = std::min(n, k + block); k < end; ++k)
                        make(k, out.emplace_back());
                } catch (...) {
                    failed[i] = std::current_exception();
                }
            });
            for (std::size_t i = 0; i < m; ++i) {
                if (failed[i]) std::rethrow_exception(failed[i]);
                for (const std::string& v : text[i]) {
                    item(depth);
                    put(v);
                }
            }
        }
    }

    /// An object or an array nested `depth` levels deep, its members or elements written by
    /// the caller between open and close: item() before each.
    void open(char bracket) {
        m_first.push_back(true);
        put(std::string_view(&bracket, 1));
    }
    void item(int depth) {
        put(m_first.back() ? "\n" : ",\n");
        m_first.back() = false;
        put(std::string_view(spaces, static_cast<std::size_t>(depth + 1)));
    }
    void key(int depth, const char* name) {
        item(depth);
        append_json_string(m_buf, name);
        put(": ");
    }
    void close(char bracket, int depth) {
        if (!m_first.back()) {  // nlohmann writes an empty object or array as {} or []
            put("\n");
            put(std::string_view(spaces, static_cast<std::size_t>(depth)));
        }
        m_first.pop_back();
        put(std::string_view(&bracket, 1));
    }

private:
    static constexpr std::size_t chunk = std::size_t{1} << 20;
    static constexpr const char* spaces = "        ";  // deep enough for the report's nesting (4)
    const StagedOutput::Sink& m_sink;
    std::string m_buf;
    std::vector<bool> m_first;
};

/// Appends what Stream::render(feature, depth) would write of the GeoJSON Point feature at `p`
/// (rounded to the coordinates' decimals) with `row`'s fields as its properties, as text:
/// nlohmann's dump(1) of the feature (its keys in order, ": " after each, members and
/// elements a line each indented one space a level, an empty object {}), every line after
/// the first indented `depth` more.
template <class Row>
void append_point_feature(std::string& out, geo::LonLat p, const std::vector<fields::Field<Row>>& table, const Row& row, const audit::AuditResult& r,
                          int depth) {
    using fields::round_to, fields::coordinate_decimals;
    auto line = [&](int level) {
        out += '\n';
        out.append(static_cast<std::size_t>(depth + level), ' ');
    };
    out += '{';
    line(1);
    out += "\"type\": \"Feature\",";
    line(1);
    out += "\"geometry\": {";
    line(2);
    out += "\"type\": \"Point\",";
    line(2);
    out += "\"coordinates\": [";
    line(3);
    append_json_value(out, round_to(p.lon, coordinate_decimals));
    out += ',';
    line(3);
    append_json_value(out, round_to(p.lat, coordinate_decimals));
    line(2);
    out += ']';
    line(1);
    out += "},";
    line(1);
    out += "\"properties\": {";
    bool any = false;
    for (const auto& f : table) {
        if (f.present && !f.present(r)) continue;
        if (any) out += ',';
        any = true;
        line(2);
        out += '"';  // a name is printable ASCII with no quote or backslash (ReportFields.EveryTableNamesEachFieldOnce)
        out += f.name;
        out += "\": ";
        append_json_value(out, fields::value_of(f, row));
    }
    if (any) line(1);
    out += '}';
    line(0);
    out += '}';
}

/// The members of one row (every field of the table, in order) into an open object.
template <class Row>
void members_of(Stream& out, int depth, const std::vector<fields::Field<Row>>& table, const Row& row, const audit::AuditResult& r,
                bool omit_null = false) {
    for (const auto& f : table) {
        if (f.present && !f.present(r)) continue;
        fields::Value v = fields::value_of(f, row);
        if (omit_null && std::holds_alternative<std::monostate>(v)) continue;
        out.key(depth, f.name);
        out.scalar(v);
    }
}

/// An array of rows as objects at `depth`.
template <class Row, class Rows>
void array_of(Stream& out, int depth, const std::vector<fields::Field<Row>>& table, const Rows& rows, const audit::AuditResult& r,
              bool omit_null = false) {
    out.open('[');
    for (const auto& row : rows) {
        out.item(depth);
        out.open('{');
        members_of(out, depth + 1, table, row, r, omit_null);
        out.close('}', depth + 1);
    }
    out.close(']', depth);
}

void write_report(const audit::AuditResult& r, const RunInfo& info, const StagedOutput::Sink& sink) {
    const fields::RunRow run{r, info};
    Stream out(sink);
    out.open('{');
    out.key(0, "type");
    out.put("\"FeatureCollection\"");
    out.key(0, "shoal");
    out.open('{');
    members_of(out, 1, fields::run_fields(), run, r);
    if (r.has_encounters) {
        std::vector<fields::ApproachRow> rows;
        rows.reserve(r.encounters.approaches.size());
        for (const auto& a : r.encounters.approaches) rows.push_back({r, a});
        out.key(1, "closest_approaches");
        array_of(out, 2, fields::approach_fields(), rows, r);
    }
    if (r.has_assessment) {  // --assess: the criteria and the trainees' scores (breaches are features)
        std::vector<fields::CriterionRow> criteria;
        for (const auto& c : r.assessment.criteria) criteria.push_back({c});
        std::vector<fields::ScoreRow> scores;
        for (const auto& s : r.assessment.scores) scores.push_back({r, s});
        out.key(1, "assessment");
        out.open('{');
        out.key(2, "criteria");
        array_of(out, 3, fields::criterion_fields(), criteria, r);
        out.key(2, "scores");
        array_of(out, 3, fields::score_fields(), scores, r);
        out.close('}', 2);
    }
    out.key(1, "summary");
    out.open('{');
    members_of(out, 2, fields::summary_fields(), run, r);
    out.close('}', 2);
    out.key(1, "tracks");
    array_of(out, 2, fields::track_fields(), fields::track_rows(r), r);
    out.key(1, "problems");
    array_of(out, 2, fields::problem_fields(), fields::problem_rows(r), r, true);
    if (r.shard.active()) {
        out.key(1, "part");
        out.value(part_order(r, false, info.chart_lonlat), 2);  // where its rows go, for merge
    }
    out.close('}', 1);
    out.key(0, "features");
    out.open('[');
    std::vector<std::pair<const audit::TrackSummary*, const audit::Event*>> events;
    for (const auto& t : r.tracks)
        for (const auto& e : t.events) events.emplace_back(&t.summary, &e);
    out.values(events.size(), 1, info.jobs, [&](std::size_t k, std::string& text) {
        const auto [t, e] = events[k];
        append_point_feature(text, e->point, fields::event_fields(), fields::EventRow{*t, *e}, r, 2);
    });
    std::string text;
    for (const auto& e : r.encounters.events) {
        out.item(1);
        text.clear();
        append_point_feature(text, e.point, fields::encounter_fields(), fields::EncounterRow{r, e}, r, 2);
        out.put(text);
    }
    for (const auto& b : r.assessment.breaches) {
        out.item(1);
        text.clear();
        append_point_feature(text, {b.lon, b.lat}, fields::breach_fields(), fields::BreachRow{r, b}, r, 2);
        out.put(text);
    }
    out.close(']', 1);
    out.close('}', 0);
    out.put("\n");
    out.flush();
}

}  // namespace

std::string geojson(const audit::AuditResult& r, const RunInfo& info) {
    std::string text;
    write_report(r, info, [&](std::string_view piece) { text += piece; });
    return text;
}

namespace {

/// Where a GeoJSON report's QGIS style goes: REPORT.qml beside it (not beside stdout, a device or a pipe).
std::string style_path(const std::string& report) {
    std::error_code ec;
    if (is_standard_output(report) || is_system_path(report)) return {};
    if (const auto st = std::filesystem::status(report, ec); std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) return {};
    return std::filesystem::path(report).replace_extension(".qml").string();
}

/// The files of a GeoJSON report's QGIS project beside REPORT.geojson: REPORT.qgz (holding
/// REPORT.qgs), and for each map layer it lacks REPORT.LAYER.geojson and REPORT.LAYER.qml.
struct ProjectFiles {
    std::string qgz, qgs_member;
    struct Layer {
        MapLayer which;
        std::string geojson, qml;
    };
    std::vector<Layer> layers;
};

constexpr MapLayer side_layers[] = {MapLayer::hulls, MapLayer::poses, MapLayer::tracks, MapLayer::learned, MapLayer::coast};  // top of the map first

ProjectFiles project_files(const std::string& report) {
    ProjectFiles f;
    const std::filesystem::path p(report);
    f.qgz = std::filesystem::path(p).replace_extension(".qgz").string();
    f.qgs_member = p.stem().string() + ".qgs";
    for (MapLayer l : side_layers) {
        const std::string name = name_of(l);
        f.layers.push_back({l, std::filesystem::path(p).replace_extension("." + name + ".geojson").string(),
                            std::filesystem::path(p).replace_extension("." + name + ".qml").string()});
    }
    return f;
}

}  // namespace

void check_project_name(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    if (name.find('|') != std::string::npos)
        throw UsageError("-o '" + path + "': a report whose name holds '|' would get a QGIS project none of whose layers QGIS can open (its data "
                         "sources name the file, and QGIS reads '|' as the start of a layer's options); choose a name without '|', or give "
                         "--no-project");
}

namespace {

/// Whether `head` (a JSON text's beginning) is an object with a member `key` whose value is an
/// object, among the members that begin within it: the top level's members are read in turn,
/// each other value passed over (strings with their escapes, nested arrays and objects). A
/// `"shoal"` deeper down (a feature's property) or inside a string is not one.
bool top_level_object_member(std::string_view head, std::string_view key) {
    std::size_t i = 0;
    const std::size_t n = head.size();
    if (head.substr(0, 3) == "\xEF\xBB\xBF") i = 3;  // a byte-order mark
    auto blank = [&] {
        while (i < n && (head[i] == ' ' || head[i] == '\t' || head[i] == '\n' || head[i] == '\r')) ++i;
    };
    // Past the string that starts at i (a quote); false when it does not end within head.
    auto skip_string = [&] {
        for (++i; i < n; ++i) {
            if (head[i] == '\\') ++i;
            else if (head[i] == '"') {
                ++i;
                return true;
            }
        }
        return false;
    };
    blank();
    if (i >= n || head[i] != '{') return false;
    ++i;
    int depth = 1;       // of the containers open at i
    bool at_key = true;  // a top-level member's key comes next
    while (i < n) {
        blank();
        if (i >= n) return false;
        const char c = head[i];
        if (depth == 1 && at_key) {
            if (c == '}') return false;
            if (c != '"') return false;  // not JSON: not shoal's
            const std::size_t start = i + 1;
            if (!skip_string()) return false;
            const std::string_view name = head.substr(start, i - 1 - start);
            blank();
            if (i >= n || head[i] != ':') return false;
            ++i;
            blank();
            if (name == key) return i < n && head[i] == '{';
            at_key = false;
            continue;
        }
        if (c == '"') {
            if (!skip_string()) return false;
        } else if (c == '{' || c == '[') {
            ++depth;
            ++i;
        } else if (c == '}' || c == ']') {
            if (--depth == 0) return false;
            ++i;
        } else {
            if (c == ',' && depth == 1) at_key = true;
            ++i;
        }
    }
    return false;
}

}  // namespace

bool is_shoal_geojson_report(const std::string& path) { return top_level_object_member(file_head(path, 4096), "shoal"); }

std::vector<OutputSpec> report_outputs(const std::string& path, const std::string& format, bool project) {
    std::vector<OutputSpec> out{{path, "-o", "the report", format == "gpkg" ? WrittenByShoal(is_shoal_gpkg_report) : WrittenByShoal(is_shoal_geojson_report)}};
    // A GeoPackage's stored project, and the project beside a GeoJSON report in a file.
    if (project && !is_standard_output(path) && (format == "gpkg" || !style_path(path).empty())) check_project_name(path);
    if (format == "gpkg") return out;
    if (std::string style = style_path(path); !style.empty()) {
        out.push_back({std::move(style), "-o", "the QGIS style of the report"});
        if (project) {
            const ProjectFiles f = project_files(path);
            out.push_back({f.qgz, "-o", "the QGIS project of the report"});
            for (const auto& l : f.layers) {
                out.push_back({l.geojson, "-o", std::string("the ") + name_of(l.which) + " layer of the report"});
                out.push_back({l.qml, "-o", std::string("the QGIS style of the ") + name_of(l.which) + " layer"});
            }
        }
    }
    return out;
}

namespace {

/// `v` as append_coordinate writes it, for `v` not finite or under 4e8 in size: at most 18
/// bytes at `at`; returns their end.
char* put_coordinate(char* at, double v) {
    if (!std::isfinite(v)) return std::copy_n("null", 4, at);
    static_assert(fields::coordinate_decimals == 7, "small_coordinate's bound is for 7 decimals");
    at = detail::put_fixed(at, v, 7);
    const char* const first = at - 7;  // the first decimal: one is kept at least
    while (at - 1 > first && at[-1] == '0') --at;
    return at;
}

/// Whether put_coordinate writes `v`.
bool small_coordinate(double v) { return !(std::fabs(v) >= 4e8); }

}  // namespace

void append_coordinate(std::string& out, double v) {
    if (small_coordinate(v)) {
        char buf[24];
        out.append(buf, static_cast<std::size_t>(put_coordinate(buf, v) - buf));
        return;
    }
    if (!std::isfinite(v)) {
        out += "null";
        return;
    }
    char buf[400];
    const auto printed = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, fields::coordinate_decimals);
    const char* end = printed.ptr;
    while (end[-1] == '0') --end;
    if (end[-1] == '.') ++end;  // "24.0": still a number with a fraction
    out.append(buf, static_cast<std::size_t>(end - buf));
}

void PositionWriter::put(char before, geo::LonLat p) {
    if (m_n > sizeof m_buf - 48) flush();
    char* at = m_buf + m_n;
    if (before) *at++ = before;
    if (small_coordinate(p.lon) && small_coordinate(p.lat)) {
        *at++ = '[';
        at = put_coordinate(at, p.lon);
        *at++ = ',';
        at = put_coordinate(at, p.lat);
        *at++ = ']';
        m_n = static_cast<std::size_t>(at - m_buf);
        return;
    }
    m_n = static_cast<std::size_t>(at - m_buf);
    flush();
    m_out += '[';
    append_coordinate(m_out, p.lon);
    m_out += ',';
    append_coordinate(m_out, p.lat);
    m_out += ']';
}

void PositionWriter::put(char c) {
    if (m_n == sizeof m_buf) flush();
    m_buf[m_n++] = c;
}

void PositionWriter::flush() {
    m_out.append(m_buf, m_n);
    m_n = 0;
}

namespace {

/// The QGIS style REPORT.qml staged beside a GeoJSON report at `path`, unless a file of that
/// name exists that shoal did not write (a warning then), or `path` is not a regular file.
void stage_style_beside(const std::string& path, std::vector<StagedOutput>& out, std::vector<std::string>* warnings) {
    if (const std::string style = style_path(path); !style.empty()) {
        std::string warning;
        if (std::optional<StagedOutput> s = stage_sidecar_style(style, "events", warning)) out.push_back(std::move(*s));
        else if (warnings) warnings->push_back(std::move(warning));
    }
}

void append_position(std::string& out, geo::LonLat p) {
    PositionWriter w(out);
    w.put('\0', p);
    w.flush();
}

/// Writes a ring's GeoJSON coordinates, running counter-clockwise (`ccw`: a polygon's shell)
/// or clockwise (a hole), as RFC 7946 has them. `ring` is closed.
void put_ring(PositionWriter& w, const std::vector<geo::LonLat>& ring, bool ccw) {
    double area2 = 0;  // twice the signed area in degrees: > 0 counter-clockwise
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) area2 += ring[i].lon * ring[i + 1].lat - ring[i + 1].lon * ring[i].lat;
    const bool reverse = area2 != 0 && (area2 > 0) != ccw;
    w.put('[');
    for (std::size_t k = 0; k < ring.size(); ++k) w.put(k ? ',' : '\0', ring[reverse ? ring.size() - 1 - k : k]);
    w.put(']');
}

/// Appends a ring's coordinates (put_ring).
void append_ring(std::string& out, const std::vector<geo::LonLat>& ring, bool ccw) {
    PositionWriter w(out);
    put_ring(w, ring, ccw);
    w.flush();
}

/// Appends a polygon's coordinates: its shell, then its holes.
void append_polygon(std::string& out, const std::vector<std::vector<geo::LonLat>>& rings) {
    PositionWriter w(out);
    w.put('[');
    for (std::size_t k = 0; k < rings.size(); ++k) {
        if (k) w.put(',');
        put_ring(w, rings[k], k == 0);
    }
    w.put(']');
    w.flush();
}

}  // namespace

template <class Row>
void append_object(std::string& out, const std::vector<fields::Field<Row>>& table, const Row& row, const audit::AuditResult& r) {
    // The text nlohmann's dump() writes of the row's fields as a JSON object (the table's
    // order; names are unique in a table), appended field by field: built as a JSON object
    // and dumped, a pose row took 10,500 instructions, the third of a day of AIS's writing.
    out += '{';
    bool first = true;
    for (const auto& f : table) {
        if (f.present && !f.present(r)) continue;
        if (!first) out += ',';
        first = false;
        out += '"';  // a name is printable ASCII with no quote or backslash (ReportFields.EveryTableNamesEachFieldOnce)
        out += f.name;
        out += "\":";
        append_json_value(out, fields::value_of(f, row));
    }
    out += '}';
}
template void append_object(std::string&, const std::vector<fields::Field<fields::TrackRow>>&, const fields::TrackRow&, const audit::AuditResult&);
template void append_object(std::string&, const std::vector<fields::Field<fields::HullRow>>&, const fields::HullRow&, const audit::AuditResult&);
template void append_object(std::string&, const std::vector<fields::Field<fields::PoseRow>>&, const fields::PoseRow&, const audit::AuditResult&);
template void append_object(std::string&, const std::vector<fields::Field<fields::CoastRow>>&, const fields::CoastRow&, const audit::AuditResult&);
template void append_object(std::string&, const std::vector<fields::Field<fields::LearnedRow>>&, const fields::LearnedRow&, const audit::AuditResult&);

namespace {

/// Writes the features `feature(k, out)` appends for k in [0, n), one a line, comma-separated:
/// in blocks on `jobs` threads, handed to `sink` in order of k. A block holds features of
/// some 16,000 points in all (`points(k)`: feature k's), so that the blocks held at once, four
/// a thread, are a few megabytes whatever the features (a year's track is one feature).
template <class Points, class Feature>
void write_features(std::size_t n, unsigned jobs, const Points& points, const Feature& feature, const StagedOutput::Sink& sink) {
    constexpr std::size_t block_points = 16384;
    std::vector<std::size_t> starts;  // the first feature of each block
    for (std::size_t k = 0, in_block = block_points; k < n; ++k) {
        if (in_block >= block_points) {
            starts.push_back(k);
            in_block = 0;
        }
        in_block += std::max<std::size_t>(1, points(k));
    }
    starts.push_back(n);
    const std::size_t blocks = starts.size() - 1;
    const unsigned threads = detail::thread_count(jobs);
    const std::size_t window = 4 * std::size_t{threads};
    std::vector<std::string> text(std::min(blocks, window));
    std::vector<std::exception_ptr> failed(text.size());
    for (std::size_t b0 = 0; b0 < blocks; b0 += window) {
        const std::size_t m = std::min(window, blocks - b0);
        detail::parallel_for(m, threads, [&](std::size_t i, unsigned) {
            std::string& out = text[i];
            out.clear();
            try {
                for (std::size_t k = starts[b0 + i]; k < starts[b0 + i + 1]; ++k) {
                    out += k ? ",\n{\"type\":\"Feature\",\"properties\":" : "\n{\"type\":\"Feature\",\"properties\":";
                    feature(k, out);
                    out += "}}";
                }
            } catch (...) {
                failed[i] = std::current_exception();
            }
        });
        for (std::size_t i = 0; i < m; ++i) {
            if (failed[i]) std::rethrow_exception(failed[i]);
            sink(text[i]);
        }
    }
}

/// A layer's feature: its properties, then `"geometry":{"type":TYPE,"coordinates":` (the
/// caller appends the coordinates; write_features closes the feature).
template <class Row>
void open_feature(std::string& out, const std::vector<fields::Field<Row>>& table, const Row& row, const audit::AuditResult& r, const char* type) {
    append_object(out, table, row, r);
    out += ",\"geometry\":{\"type\":\"";
    out += type;
    out += "\",\"coordinates\":";
}

/// A map layer of the report (tracks, hulls, poses, coast) as a GeoJSON FeatureCollection
/// (RFC 7946: WGS84 longitude, latitude to 7 decimals, shells counter-clockwise), marked as
/// shoal's in its "description"; one feature per line, written as it is made (write_features).
/// The features, their properties and geometries are those of the GeoPackage's layer
/// (gpkg_report.cpp).
void write_layer(MapLayer which, const audit::AuditResult& r, const RunInfo& info, const StagedOutput::Sink& sink) {
    sink("{\n\"type\": \"FeatureCollection\",\n\"name\": " + json(name_of(which)).dump() + ",\n\"description\": " +
         json(std::string(sidecar_mark)).dump() + ",\n\"features\": [");
    switch (which) {
        case MapLayer::tracks: {
            const std::vector<fields::TrackRow> rows = fields::track_rows(r);
            auto points = [&](std::size_t k) {
                std::size_t n = 0;
                for (const auto& piece : rows[k].track.lines) n += piece.size();
                return n;
            };
            write_features(rows.size(), info.jobs, points, [&](std::size_t k, std::string& out) {
                const fields::TrackRow& t = rows[k];
                open_feature(out, fields::track_fields(), t, r, "MultiLineString");
                PositionWriter w(out);
                w.put('[');
                for (std::size_t j = 0; j < t.track.lines.size(); ++j) {
                    const auto& piece = t.track.lines[j];
                    if (j) w.put(',');
                    w.put('[');
                    for (std::size_t i = 0; i < piece.size(); ++i) w.put(i ? ',' : '\0', piece[i]);
                    if (piece.size() == 1) w.put(',', piece[0]);  // a piece of one fix: a line of no length
                    w.put(']');
                }
                w.put(']');
                w.flush();
            }, sink);
            break;
        }
        case MapLayer::hulls: {
            const std::vector<fields::HullRow> rows = fields::hull_rows(r);
            write_features(rows.size(), info.jobs, [&](std::size_t k) { return rows[k].ring.size(); }, [&](std::size_t k, std::string& out) {
                open_feature(out, fields::hull_fields(), rows[k], r, "Polygon");
                out += '[';
                append_ring(out, rows[k].ring, true);
                out += ']';
            }, sink);
            break;
        }
        case MapLayer::poses: {
            std::vector<std::size_t> before{0};  // poses of the tracks before track k
            for (const auto& t : r.tracks) before.push_back(before.back() + t.poses.size());
            auto pose = [&](std::size_t k) -> std::pair<std::size_t, const audit::Pose*> {
                const auto t = static_cast<std::size_t>(std::upper_bound(before.begin(), before.end(), k) - before.begin()) - 1;
                return {t, &r.tracks[t].poses[k - before[t]]};
            };
            write_features(before.back(), info.jobs, [&](std::size_t k) { return pose(k).second->hull.size(); }, [&](std::size_t k, std::string& out) {
                const auto [t, pp] = pose(k);
                const audit::Pose& p = *pp;
                open_feature(out, fields::pose_fields(), fields::PoseRow{r.tracks[t].summary, p}, r, "Polygon");
                out += '[';
                append_ring(out, p.hull, true);
                out += ']';
            }, sink);
            break;
        }
        case MapLayer::learned: {
            write_features(r.places.size(), info.jobs, [](std::size_t) { return std::size_t{1}; }, [&](std::size_t k, std::string& out) {
                open_feature(out, fields::learned_fields(), fields::LearnedRow{r.places[k]}, r, "Point");
                append_position(out, r.places[k].position);
            }, sink);
            break;
        }
        case MapLayer::coast: {
            const coast::Coastline* chart = chart_of(info);
            if (!chart) throw LibraryError("the coast layer without a chart");
            const std::vector<ChartFeature> rows = chart_features_near(r, *chart, info.jobs);
            auto points = [&](std::size_t k) {
                std::size_t n = 0;
                for (const auto& polygon : rows[k].polygons)
                    for (const auto& ring : polygon) n += ring.size();
                return n;
            };
            write_features(rows.size(), info.jobs, points, [&](std::size_t k, std::string& out) {
                const ChartFeature& c = rows[k];
                open_feature(out, fields::coast_fields(), fields::coast_row(c), r, "MultiPolygon");
                out += '[';
                for (std::size_t j = 0; j < c.polygons.size(); ++j) {
                    if (j) out += ',';
                    append_polygon(out, c.polygons[j]);
                }
                out += ']';
            }, sink);
            break;
        }
    }
    sink("\n]\n}\n");
}

/// A map layer of the report as GeoJSON at `path` (write_layer).
StagedOutput stage_layer_file(const std::string& path, MapLayer which, const audit::AuditResult& r, const RunInfo& info) {
    StagedOutput out(path);
    if (out.direct()) throw InputError("cannot write '" + path + "': the layer files of a QGIS project must be regular files");
    out.write_streamed([&](const StagedOutput::Sink& sink) { write_layer(which, r, info, sink); });
    return out;
}

/// The layer files `layers`, staged in that order: each file by a thread of its own (at most
/// RunInfo::jobs files at once; they share nothing but the result they read), and each file's
/// blocks of features by RunInfo::jobs threads (write_features). More threads than cores, but
/// one file's thread waits on its disk (the fsync of a file of hundreds of megabytes) while
/// the others write (on 2 cores, the near-coast set's report and layers took 0.95 s so, 1.32 s
/// with the files one after another). The coast layer is begun first: it may wait for its chart
/// (RunInfo::chart_later) and has work on one thread (the tiles of few tracks) the other files
/// can go on beside; none is staged for it when the chart cannot be read (chart_of() null).
/// The first failure is thrown once every file is done (the others' temporary files are
/// removed with them).
std::vector<std::optional<StagedOutput>> stage_layer_files(const std::vector<const ProjectFiles::Layer*>& layers, const audit::AuditResult& r,
                                                           const RunInfo& info) {
    const std::size_t n = layers.size();
    std::vector<std::size_t> order;  // the coast layer first, then the others as given
    for (std::size_t k = 0; k < n; ++k)
        if (layers[k]->which == MapLayer::coast) order.push_back(k);
    for (std::size_t k = 0; k < n; ++k)
        if (layers[k]->which != MapLayer::coast) order.push_back(k);
    std::vector<std::optional<StagedOutput>> staged(n);
    std::vector<std::exception_ptr> failed(n);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < n;) {
            const std::size_t k = order[i];
            try {
                if (layers[k]->which == MapLayer::coast && !chart_of(info)) continue;
                staged[k].emplace(stage_layer_file(layers[k]->geojson, layers[k]->which, r, info));
            } catch (...) {
                failed[k] = std::current_exception();
            }
        }
    };
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t threads = std::min<std::size_t>(n, info.jobs ? info.jobs : cores);
    std::vector<std::thread> pool;
    try {
        for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    } catch (const std::system_error&) {  // no thread to be had: fewer do the work
    }
    work();
    for (std::thread& t : pool) t.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
    return staged;
}

/// The QGIS project REPORT.qgz beside a GeoJSON report and the layer files it opens, unless
/// one of those files exists that shoal did not write (a warning then, and none is staged).
void stage_project_beside(const std::string& path, const audit::AuditResult& r, const RunInfo& info, std::vector<StagedOutput>& out,
                          std::vector<std::string>* warnings) {
    if (style_path(path).empty()) return;  // stdout, a device
    const ProjectFiles f = project_files(path);
    std::vector<std::string> files{f.qgz};
    for (const auto& l : f.layers) files.insert(files.end(), {l.geojson, l.qml});
    // A shard's part gets none: merge does not read one (docs/user-guide.md, shoal merge). An
    // earlier run's project left beside the report would show that run: said, not deleted.
    if (!info.project || r.shard.active()) {
        std::size_t stale = 0;
        for (const std::string& file : files) {
            std::error_code ec;
            if (std::filesystem::exists(file, ec) && (file == f.qgz ? is_shoal_qgz(file, f.qgs_member) : is_shoal_sidecar(file))) ++stale;
        }
        if (stale && warnings)
            warnings->push_back(std::to_string(stale) + " QGIS project files of an earlier run are beside the report (" + f.qgz +
                                " and its layer files), not rewritten by this one (" + (r.shard.active() ? "a shard" : "--no-project") +
                                "): they show that run; delete them");
        return;
    }
    for (const std::string& file : files) {
        std::error_code ec;
        if (!std::filesystem::exists(file, ec)) continue;
        const bool ours = file == f.qgz ? is_shoal_qgz(file, f.qgs_member) : is_shoal_sidecar(file);
        if (!ours) {
            if (warnings)
                warnings->push_back("'" + file + "' exists and was not written by shoal: left as it is, so the report has no QGIS project " +
                                    f.qgz + " beside it (move that file, or write the report elsewhere)");
            return;
        }
    }
    // Each source names its geometry type (an OGR layer of a GeoJSON file with no feature has
    // none, and QGIS would open it as a table, dropping it from the map).
    const std::string name = std::filesystem::path(path).filename().string();
    bool any_event = !r.encounters.events.empty() || !r.assessment.breaches.empty();
    for (const auto& t : r.tracks) any_event = any_event || !t.events.empty();
    std::vector<ProjectLayer> layers{{"events", "Point", "./" + name + "|geometrytype=Point", any_event}};
    std::vector<const ProjectFiles::Layer*> written;
    for (const auto& l : f.layers)
        if ((l.which != MapLayer::coast || info.chart || info.chart_later.valid()) && (l.which != MapLayer::learned || r.world == audit::World::real))
            written.push_back(&l);
    std::vector<std::optional<StagedOutput>> files_out = stage_layer_files(written, r, info);
    for (std::size_t k = 0; k < written.size(); ++k) {
        const auto& l = *written[k];
        if (!files_out[k]) continue;  // the coast layer of a chart that could not be read
        out.push_back(std::move(*files_out[k]));
        std::string warning;  // checked above: shoal's, or none
        if (std::optional<StagedOutput> s = stage_sidecar_style(l.qml, name_of(l.which), warning)) out.push_back(std::move(*s));
        const char* type = l.which == MapLayer::tracks    ? "MultiLineString"
                           : l.which == MapLayer::coast   ? "MultiPolygon"
                           : l.which == MapLayer::learned ? "Point"
                                                          : "Polygon";
        // A layer file with no feature has no field to filter on.
        bool any = true;
        if (l.which == MapLayer::hulls) any = !fields::hull_rows(r).empty();
        if (l.which == MapLayer::tracks || l.which == MapLayer::poses) {
            any = false;
            for (const auto& t : r.tracks) any = any || (l.which == MapLayer::tracks ? !t.summary.lines.empty() : !t.poses.empty());
        }
        layers.push_back({name_of(l.which), l.which == MapLayer::tracks ? "Line" : l.which == MapLayer::learned ? "Point" : "Polygon",
                          "./" + std::filesystem::path(l.geojson).filename().string() + "|geometrytype=" + type, any});
    }
    StagedOutput qgz(f.qgz);
    qgz.write(qgz_of(f.qgs_member, qgis_project_xml(layers, name, project_view(r, info.chart_lonlat))));
    out.push_back(std::move(qgz));
}

}  // namespace

std::vector<StagedOutput> stage_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info,
                                        std::vector<std::string>* warnings) {
    std::vector<StagedOutput> out;
    out.emplace_back(path);
    // The report on a thread of its own while the QGIS project's layer files are written
    // (not with RunInfo::jobs 1: one thread was asked for).
    std::exception_ptr report_failed;
    auto write = [&] {
        try {
            out.front().write_streamed([&](const StagedOutput::Sink& sink) { write_report(result, info, sink); });
        } catch (...) {
            report_failed = std::current_exception();
        }
    };
    std::thread report;
    try {
        if (info.jobs == 1) write();
        else report = std::thread(write);
    } catch (const std::system_error&) {  // no thread to be had: written here
        write();
    }
    std::exception_ptr beside_failed;
    std::vector<StagedOutput> beside;
    try {
        stage_style_beside(path, beside, warnings);
        stage_project_beside(path, result, info, beside, warnings);
    } catch (...) {
        beside_failed = std::current_exception();
    }
    if (report.joinable()) report.join();
    if (report_failed) std::rethrow_exception(report_failed);
    if (beside_failed) std::rethrow_exception(beside_failed);
    for (StagedOutput& s : beside) out.push_back(std::move(s));
    return out;
}

std::vector<StagedOutput> stage_geojson_text(const std::string& path, std::string_view text, std::vector<std::string>* warnings) {
    std::vector<StagedOutput> out;
    out.emplace_back(path);
    out.back().write(text);
    stage_style_beside(path, out, warnings);
    return out;
}

void write_geojson(const std::string& path, const audit::AuditResult& result, const RunInfo& info, std::vector<std::string>* warnings) {
    std::vector<StagedOutput> staged = stage_geojson(path, result, info, warnings);
    commit_all(staged);
}

}  // namespace shoal::report
