// GeoJSON tracks, read with nlohmann::json (no GDAL: the GPX reader, with OGR, is gpx_reader.cpp).
#include <shoal/track/ogr_reader.hpp>

#include <map>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "util/json_message.hpp"
#include "util/parse_util.hpp"
#include <shoal/track/row_rules.hpp>
#include "track/stream_readers.hpp"
#include "track/track_set.hpp"
#include <shoal/track/csv_reader.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>

namespace shoal::track {

namespace {

using nlohmann::json;
using detail::TrackSet;

// ---------------------------------------------------------------------------------------------
// GeoJSON with nlohmann::json

/// A JSON id value as text: strings as they are, integers without a fraction.
std::string id_text(const json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
    if (v.is_number_float()) {
        const double d = v.get<double>();
        if (d == std::floor(d) && std::fabs(d) < 1e15) return std::to_string(static_cast<long long>(d));
        return v.dump();
    }
    return {};
}

const json* member(const json& obj, const char* key) {
    if (!obj.is_object()) return nullptr;
    const auto it = obj.find(key);
    return it == obj.end() || it->is_null() ? nullptr : &*it;
}

/// Epoch seconds of a JSON time: ISO 8601 (or another form parse_time reads, with a date)
/// or a number (seconds; milliseconds when > 1e11).
std::optional<double> json_time(const json& v) {
    if (v.is_string()) {
        const auto t = parse_time(v.get_ref<const std::string&>());
        if (!t || t->date_missing) return std::nullopt;
        return t->seconds;
    }
    if (v.is_number()) {
        const double d = v.get<double>();
        if (!std::isfinite(d)) return std::nullopt;
        return d > 1e11 ? d / 1000.0 : d;
    }
    return std::nullopt;
}

std::string json_text(const json& v) {
    std::string s = v.dump();
    return s.size() > 40 ? s.substr(0, 40) + "..." : s;
}

double json_number(const json& props, const char* key) {
    const json* v = member(props, key);
    return v && v->is_number() ? v->get<double>() : NAN;
}

class GeoJsonReader {
public:
    GeoJsonReader(std::string_view text, const std::string& file, const ReadOptions& options)
        : m_text(text), m_file(file), m_options(options), m_set(m_out, m_file) {
        m_out.format = "geojson";
        m_out.report.max_messages = options.max_messages;
    }

    TrackFile read() {
        json doc;
        try {
            doc = json::parse(m_text.begin(), m_text.end());
        } catch (const json::exception& e) {  // also a number too large for a double
            throw InputError(m_file + ": not valid JSON: " + shoal::detail::json_error_text(e.what()));
        }
        const json* type = member(doc, "type");
        if (!type || !type->is_string())
            throw InputError(m_file +
                             ": not a track format shoal reads (CSV with a header, GPX, GeoJSON, NMEA 0183): "
                             "JSON without a GeoJSON 'type'");
        check_crs(doc);
        std::vector<const json*> features;
        if (*type == "FeatureCollection") {
            const json* list = member(doc, "features");
            if (!list || !list->is_array()) throw InputError(m_file + ": FeatureCollection without a 'features' array");
            for (const json& f : *list) features.push_back(&f);
        } else if (*type == "Feature") {
            features.push_back(&doc);
        } else {
            throw InputError(m_file + ": a bare " + type->get<std::string>() +
                             " geometry has no times; shoal reads Features with per-vertex times or timed Points");
        }
        std::size_t lines = 0;
        for (const json* f : features) {
            const json* g = member(*f, "geometry");
            const json* gt = g ? member(*g, "type") : nullptr;
            if (gt && (*gt == "LineString" || *gt == "MultiLineString")) ++lines;
        }
        m_single_line = lines == 1;
        for (std::size_t k = 0; k < features.size(); ++k) {
            // A line that cannot be read (times that do not match its vertices, none at all, no
            // coordinates) costs that feature, said, not the file: line() finds these before it
            // takes a fix.
            try {
                feature(*features[k], k + 1);
            } catch (const InputError& e) {
                ++m_out.report.rows;
                m_out.report.skip(std::string(e.what()) + "; feature skipped");
            }
        }
        for (const auto& [what, wanted, field, seen] : {std::tuple{"exercise", &m_options.exercise_column, "ReadOptions::exercise_column", m_exercise_seen},
                                                        std::tuple{"role", &m_options.role_column, "ReadOptions::role_column", m_role_seen}})
            if (!wanted->empty() && !seen && !features.empty())
                throw InputError(m_file + ": no feature has the property '" + *wanted + "', the " + what + " column (" + field + ")");
        for (Track& t : m_out.tracks) {
            const auto it = m_roles.find(t.exercise + '\0' + t.id);
            if (it != m_roles.end() && !it->second.other.empty()) {
                m_out.report.messages.push_back(m_file + ": track '" + t.id + "'" + (t.exercise.empty() ? "" : " of exercise '" + t.exercise + "'") +
                                                ": its features disagree on the role (" + t.role + " in feature " + std::to_string(it->second.first) +
                                                ", " + it->second.other + " in feature " + std::to_string(it->second.other_at) + " of property '" +
                                                m_options.role_column + "'): it is taken as a target");
                t.role = "target";
            }
        }
        for (Track& t : m_out.tracks) normalise(t, m_out.report);
        return std::move(m_out);
    }

private:
    void check_crs(const json& doc) const {
        const json* crs = member(doc, "crs");
        const json* props = crs ? member(*crs, "properties") : nullptr;
        const json* name = props ? member(*props, "name") : nullptr;
        if (!name || !name->is_string()) return;
        const std::string& n = name->get_ref<const std::string&>();
        if (n.find("CRS84") != std::string::npos || n.find("4326") != std::string::npos) return;
        throw InputError(m_file + ": crs '" + n + "' is not WGS84 longitude/latitude (RFC 7946 GeoJSON)");
    }

    std::string where(std::size_t k) const { return m_file + " feature " + std::to_string(k); }

    std::string id_of(const json& feature, const json& props, std::size_t k, bool line) const {
        for (const char* key : {"id", "mmsi", "vessel", "name"})
            if (const json* v = member(props, key))
                if (std::string s = id_text(*v); !s.empty()) return s;
        if (!line) return detail::file_stem(m_file);  // a Point's feature id names the point, not the vessel
        if (const json* v = member(feature, "id"))
            if (std::string s = id_text(*v); !s.empty()) return s;
        if (m_single_line) return detail::file_stem(m_file);
        return detail::file_stem(m_file) + ":feature" + std::to_string(k);
    }

    static std::string name_of(const json& props) {
        for (const char* key : {"name", "vesselname", "vessel_name"})
            if (const json* v = member(props, key); v && v->is_string()) return v->get<std::string>();
        return {};
    }

    /// The property named `wanted` as columns are matched (any case, a leading `#` and blanks
    /// ignored), or null (also for a null value); `seen` set when the feature has it at all.
    static const json* named_property(const json& props, const std::string& wanted, bool& seen) {
        const std::string n = normalise_column_name(wanted);
        for (const auto& [key, value] : props.items())
            if (normalise_column_name(key) == n) {
                seen = true;
                return value.is_null() ? nullptr : &value;
            }
        return nullptr;
    }

    /// Feature `k`'s exercise and role (ReadOptions::exercise_column, role_column); false (the
    /// feature skipped and said) when one is read and the feature's is missing or not valid.
    bool exercise_and_role(const json& props, std::size_t k, std::string& exercise, const char*& role) {
        auto bad = [&](const std::string& what) {
            ++m_out.report.rows;
            m_out.report.skip(where(k) + ": " + what + "; feature skipped");
            return false;
        };
        if (!m_options.exercise_column.empty()) {
            const json* v = named_property(props, m_options.exercise_column, m_exercise_seen);
            if (v && !v->is_string() && !v->is_number()) return bad("exercise " + json_text(*v) + " (property '" + m_options.exercise_column + "') is not a text");
            exercise = v ? std::string(detail::trim(id_text(*v))) : std::string();  // blanks around it ignored, as in a CSV
            if (exercise.empty()) return bad("no exercise (property '" + m_options.exercise_column + "' is missing or empty)");
        }
        if (!m_options.role_column.empty()) {
            const json* v = named_property(props, m_options.role_column, m_role_seen);
            role = v && v->is_string() ? role_value(v->get_ref<const std::string&>()) : nullptr;
            if (!v) return bad("no role (property '" + m_options.role_column + "' is missing)");
            if (!role) return bad("role " + json_text(*v) + " (property '" + m_options.role_column + "') is neither trainee (own, own ship) nor target");
        }
        return true;
    }

    /// A feature's role for its track: the first gives the track's; a different one later is a
    /// disagreement, said (and the track taken as a target) once the file is read.
    void take_role(Track& t, const char* role, std::size_t k) {
        if (!role) return;
        RoleSeen& seen = m_roles[t.exercise + '\0' + t.id];
        if (t.role.empty()) {
            t.role = role;
            seen.first = k;
        } else if (t.role != role && seen.other.empty()) {
            seen.other = role;
            seen.other_at = k;
        }
    }

    void feature(const json& f, std::size_t k) {
        static const json empty = json::object();
        const json* props_ptr = member(f, "properties");
        const json& props = props_ptr && props_ptr->is_object() ? *props_ptr : empty;
        std::string exercise;
        const char* role = nullptr;
        if (!exercise_and_role(props, k, exercise, role)) return;
        const json* g = member(f, "geometry");
        const json* type = g ? member(*g, "type") : nullptr;
        if (!type || !type->is_string()) {
            ++m_out.report.rows;
            m_out.report.skip(where(k) + ": no geometry; feature skipped");
            return;
        }
        if (*type == "Point") return point(f, props, *g, k, exercise, role);
        if (*type == "LineString" || *type == "MultiLineString") return line(f, props, *g, k, exercise, role);
        ++m_out.report.rows;
        m_out.report.skip(where(k) + ": a " + type->get<std::string>() + " is not a track; feature skipped");
    }

    /// Position of a coordinate array; false (after a message) when it is not a valid one.
    bool position(const json& c, const std::string& at, geo::LonLat& p) {
        if (!c.is_array() || c.size() < 2 || !c[0].is_number() || !c[1].is_number()) {
            m_out.report.skip(at + "coordinates " + json_text(c) + " are not [lon, lat]; point skipped");
            return false;
        }
        p = {c[0].get<double>(), c[1].get<double>()};
        if (std::string what; position_problem(p.lat, p.lon, what)) {
            m_out.report.skip(at + what + "; point skipped");
            return false;
        }
        return true;
    }

    void point(const json& f, const json& props, const json& g, std::size_t k, const std::string& exercise, const char* role) {
        ++m_out.report.rows;
        ++m_point;
        const std::string at = where(k) + ": ";
        const json* tv = member(props, "time");
        if (!tv) tv = member(props, "timestamp");
        if (!tv) {
            m_out.report.skip(at + "Point without a 'time' or 'timestamp' property; point skipped");
            return;
        }
        const auto t = json_time(*tv);
        if (!t) {
            m_out.report.skip(at + "time " + json_text(*tv) + " is not a valid time; point skipped");
            return;
        }
        if (!plausible_fix_time(*t)) {
            m_out.report.skip(at + "time " + json_text(*tv) + " is outside the years " + fix_time_range + "; point skipped");
            return;
        }
        Fix fix;
        const json* coords = member(g, "coordinates");
        if (!position(coords ? *coords : json(), at, fix.position)) return;
        fix.time_s = *t;
        fix.line = m_point;
        double h = json_number(props, "heading");
        if (std::isnan(h)) h = json_number(props, "heading_deg");
        fix.heading_deg = valid_heading(h);
        double c = json_number(props, "cog");
        if (std::isnan(c)) c = json_number(props, "cog_deg");
        fix.cog_deg = valid_cog(c);
        double s = json_number(props, "sog");
        if (std::isnan(s)) s = json_number(props, "sog_kn");
        fix.sog_kn = valid_sog(s);
        Track& track = m_set.get(id_of(f, props, k, false), name_of(props), exercise);
        take_role(track, role, k);
        track.fixes.push_back(fix);
    }

    /// The per-vertex time array of a line, flattened over the parts of a MultiLineString.
    static const json* time_array(const json& props, std::string& key) {
        for (const char* name : {"times", "coordTimes", "timestamps"})
            if (const json* v = member(props, name); v && v->is_array()) {
                key = name;
                return v;
            }
        if (const json* cp = member(props, "coordinateProperties"))
            if (const json* v = member(*cp, "times"); v && v->is_array()) {
                key = "coordinateProperties.times";
                return v;
            }
        return nullptr;
    }

    void line(const json& f, const json& props, const json& g, std::size_t k, const std::string& exercise, const char* role) {
        const json* coords = member(g, "coordinates");
        if (!coords || !coords->is_array()) throw InputError(where(k) + ": line without a 'coordinates' array");
        std::vector<const json*> vertices;
        if (g["type"] == "LineString") {
            for (const json& c : *coords) vertices.push_back(&c);
        } else {
            for (const json& part : *coords)
                if (part.is_array())
                    for (const json& c : part) vertices.push_back(&c);
        }
        std::string key;
        std::vector<const json*> times;
        if (const json* arr = time_array(props, key)) {
            for (const json& v : *arr) {
                if (v.is_array()) {
                    for (const json& w : v) times.push_back(&w);
                } else {
                    times.push_back(&v);
                }
            }
            if (times.size() != vertices.size())
                throw InputError(where(k) + ": '" + key + "' has " + std::to_string(times.size()) + " times for " +
                                 std::to_string(vertices.size()) + " vertices");
        } else {
            const bool all_m = !vertices.empty() && std::all_of(vertices.begin(), vertices.end(), [](const json* c) {
                return c->is_array() && c->size() >= 4;
            });
            if (!all_m)
                throw InputError(where(k) + " ('" + id_of(f, props, k, true) +
                                 "'): line without times; shoal needs a property array 'times', 'coordTimes', "
                                 "'timestamps' or 'coordinateProperties.times', or [lon, lat, z, m] with m = epoch seconds");
            key = "m";
            for (const json* c : vertices) times.push_back(&(*c)[3]);
        }
        Track& track = m_set.get(id_of(f, props, k, true), name_of(props), exercise);
        take_role(track, role, k);
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            ++m_out.report.rows;
            ++m_point;
            const std::string at = where(k) + " vertex " + std::to_string(i + 1) + ": ";
            const auto t = json_time(*times[i]);
            if (!t) {
                m_out.report.skip(at + key + " " + json_text(*times[i]) + " is not a valid time; point skipped");
                continue;
            }
            if (!plausible_fix_time(*t)) {
                m_out.report.skip(at + key + " " + json_text(*times[i]) + " is outside the years " + fix_time_range + "; point skipped");
                continue;
            }
            Fix fix;
            if (!position(*vertices[i], at, fix.position)) continue;
            fix.time_s = *t;
            fix.line = m_point;
            track.fixes.push_back(fix);
        }
    }

    std::string_view m_text;
    std::string m_file;
    const ReadOptions& m_options;
    TrackFile m_out;
    TrackSet m_set;
    std::size_t m_point = 0;
    bool m_single_line = false;
    bool m_exercise_seen = false, m_role_seen = false;  ///< some feature has the property
    struct RoleSeen {
        std::size_t first = 0, other_at = 0;  ///< feature numbers
        std::string other;                    ///< the other role, when one disagreed
    };
    std::map<std::string, RoleSeen> m_roles;  ///< by (exercise, id)
};

}  // namespace

TrackFile read_geojson_text(std::string_view text, const std::string& file, const ReadOptions& options) {
    try {
        return GeoJsonReader(text, file, options).read();
    } catch (const json::exception& e) {  // a value of a type the reader did not check: bad input all the same
        throw InputError(file + ": unexpected JSON: " + shoal::detail::json_error_text(e.what()));
    }
}

TrackFile read_geojson(const std::string& path, const ReadOptions& options) {
    const std::string text = read_file(path);
    return read_geojson_text(text, path, options);
}

}  // namespace shoal::track
