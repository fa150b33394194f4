// Merging shard reports into one run's report (merge/merge_parts.hpp).
#include <shoal/merge/merge_parts.hpp>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <set>

#include "util/gdal_support.hpp"
#include "util/input_file.hpp"
#include "util/json_message.hpp"
#include "report/qgis/chart_layer.hpp"
#include "report/geojson_output.hpp"
#include "report/gpkg_output.hpp"
#include <shoal/report/report_fields.hpp>
#include <shoal/shard/shard.hpp>
#include <shoal/picture/debrief.hpp>
#include <shoal/picture/debrief_record.hpp>
#include <shoal/picture/plot.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/report/geojson_report.hpp>
#include "track/merge.hpp"
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

namespace {

using json = nlohmann::ordered_json;

/// A part: a GeoJSON report of a shard, or a GeoPackage one, whose tables `doc` holds as a
/// GeoJSON part would (its run header, summary, tracks and problems, and the `part` table's
/// positions in `shoal`), so that both are checked by the same rules.
struct Part {
    std::string path;
    json doc;
    GDALDatasetUniquePtr gpkg;  ///< a GeoPackage part, open (null: GeoJSON)
    audit::Shard shard;
    std::size_t set = 0;  ///< which set of inputs
};

/// A row's place in one run's order: compared element by element (positions are whole
/// numbers under 2^53, exact as doubles; an encounter's start time is a double).
using Key = std::vector<double>;

/// A name or value from a part, quoted for a message (cut: a hostile part may hold megabytes in one).
std::string named(const std::string& s) { return "'" + shoal::detail::shortened(s, shoal::detail::max_json_message_bytes) + "'"; }

bool is_gpkg(const std::string& path) { return std::filesystem::path(path).extension() == ".gpkg"; }

/// A part that is not JSON (`why`): named as the GeoPackage its name promises, or as GeoJSON.
InputError not_json(const std::string& path, const std::string& why) {
    if (is_gpkg(path)) return InputError(path + ": not a GeoPackage (not an SQLite file)");
    return InputError(path + ": not a GeoJSON report (" + why + ")");
}

InputError not_a_part(const std::string& path, const std::string& why) {
    return InputError(path + ": not the report of a shard (" + why + "); `shoal check --shard I/N` writes those");
}

/// The shard and the positions every part has (shoal.shard, shoal.part with `keys`).
void read_shard(Part& p, std::initializer_list<const char*> keys) {
    const json& s = p.doc["shoal"];
    if (!s.contains("shard") || !s["shard"].is_string() || !s.contains("part") || !s["part"].is_object()) throw not_a_part(p.path, "no shard in its run header");
    try {
        p.shard = audit::parse_shard(s["shard"].get<std::string>());
    } catch (const InputError& e) {
        throw not_a_part(p.path, std::string("its run header field 'shard': ") + e.what());
    }
    const json& order = s["part"];
    for (const char* k : keys)
        if (!order.contains(k) || !order[k].is_array()) throw not_a_part(p.path, std::string("no part.") + k);
    if (!s.contains("summary") || !s["summary"].is_object()) throw not_a_part(p.path, "no summary in its run header");
    for (const char* k : {"tracks", "problems"})
        if (!s.contains(k) || !s[k].is_array() || s[k].size() != order[k].size())
            throw InputError(p.path + ": its shoal." + k + " and the positions in shoal.part." + k + " do not match (was it edited?)");
}

Part read_geojson_part(const std::string& path, const std::string& text) {
    Part p;
    p.path = path;
    try {
        p.doc = json::parse(text);
    } catch (const json::exception& e) {
        throw not_json(path, shoal::detail::json_error_text(e.what()));
    }
    if (!p.doc.is_object() || !p.doc.contains("shoal") || !p.doc["shoal"].is_object()) throw not_a_part(path, "no \"shoal\" member");
    read_shard(p, {"inputs", "tracks", "features", "problems", "approaches"});
    if (!p.doc.contains("features") || !p.doc["features"].is_array() || p.doc["features"].size() != p.doc["shoal"]["part"]["features"].size())
        throw InputError(path + ": its features and the positions in shoal.part.features do not match (was it edited?)");
    if (const json& s = p.doc["shoal"]; s.contains("assessment")) {  // --assess: the scores and their positions
        const json& a = s["assessment"];
        if (!a.is_object() || !a.contains("criteria") || !a.contains("scores") || !a["scores"].is_array() || !s["part"].contains("scores") ||
            !s["part"]["scores"].is_array() || s["part"]["scores"].size() != a["scores"].size())
            throw InputError(path + ": its shoal.assessment.scores and the positions in shoal.part.scores do not match (was it edited?)");
    }
    return p;
}

/// A feature's fields as JSON (DateTime as ISO 8601 text); null fields as null, or left out when `omit_null`.
json attributes(const OGRFeature& f, bool omit_null) {
    json j = json::object();
    const OGRFeatureDefn& d = *f.GetDefnRef();
    for (int i = 0; i < d.GetFieldCount(); ++i) {
        const OGRFieldDefn& fd = *d.GetFieldDefn(i);
        if (!f.IsFieldSetAndNotNull(i)) {
            if (!omit_null) j[fd.GetNameRef()] = nullptr;
            continue;
        }
        json& v = j[fd.GetNameRef()];
        switch (fd.GetType()) {
            case OFTInteger: case OFTInteger64: v = static_cast<std::int64_t>(f.GetFieldAsInteger64(i)); break;
            case OFTReal: v = f.GetFieldAsDouble(i); break;
            case OFTDateTime: {  // as the writer wrote it (iso_time), for merge's rules that read times
                int y = 0, mo = 0, day = 0, h = 0, mi = 0, tz = 0;
                float sec = 0;
                f.GetFieldAsDateTime(i, &y, &mo, &day, &h, &mi, &sec, &tz);
                const std::optional<double> t = track::utc_seconds(y, mo, day, h, mi, sec);
                v = t ? json(iso_time(*t)) : json(f.GetFieldAsString(i));
                break;
            }
            default: v = std::string(f.GetFieldAsString(i)); break;
        }
    }
    return j;
}

/// The rows of table `name` of a part as JSON objects.
json rows_of(Part& p, const char* name, bool omit_null) {
    OGRLayer* l = p.gpkg->GetLayerByName(name);
    if (!l) throw not_a_part(p.path, std::string("no layer ") + name);
    json rows = json::array();
    l->ResetReading();
    while (OGRFeatureUniquePtr f{l->GetNextFeature()}) rows.push_back(attributes(*f, omit_null));
    return rows;
}

Part read_gpkg_part(const std::string& path) {
    Part p;
    p.path = path;
    shoal::detail::register_drivers();
    const char* const drivers[] = {"GPKG", nullptr};
    CPLErrorReset();
    p.gpkg.reset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers, nullptr, nullptr));
    if (!p.gpkg) throw InputError(path + ": not a GeoPackage report (" + CPLGetLastErrorMsg() + ")");
    OGRLayer* part = p.gpkg->GetLayerByName("part");
    if (!part) throw not_a_part(path, "no table part");
    const OGRFeatureUniquePtr order{part->GetNextFeature()};
    const int field = order ? order->GetFieldIndex("order") : -1;
    json& s = p.doc["shoal"];
    try {
        s = field < 0 ? json() : json::parse(order->GetFieldAsString(field));
    } catch (const json::exception& e) {
        throw InputError(path + ": its table part is not JSON (" + e.what() + "; was it edited?)");
    }
    if (!s.is_object()) throw not_a_part(path, "no positions in its table part");
    s = json{{"part", std::move(s)}};
    const json run = rows_of(p, "run", false), summary = rows_of(p, "summary", false);
    if (run.size() != 1 || summary.size() != 1) throw not_a_part(path, "its tables run and summary are not one row each");
    json header = json::object();
    for (const auto& [k, v] : run[0].items()) header[k] = v;
    // Which layers it has (coast: the chart was readable; encounters: exercise mode) is part of the run.
    std::set<std::string> names;
    for (OGRLayer* l : p.gpkg->GetLayers())
        if (std::string(l->GetName()) != "part") names.insert(l->GetName());
    std::string layers;
    for (const auto& n : names) layers += (layers.empty() ? "" : ",") + n;
    header["layers"] = layers;
    header["summary"] = summary[0];
    header["tracks"] = rows_of(p, "tracks", true);
    header["problems"] = rows_of(p, "problems", true);
    header["part"] = std::move(s["part"]);
    s = std::move(header);
    read_shard(p, {"inputs", "tracks", "problems", "approaches", "events", "encounters", "hulls", "poses"});
    if (p.gpkg->GetLayerByName("breaches"))  // --assess
        for (const char* k : {"breaches", "scores"})
            if (!s["part"].contains(k) || !s["part"][k].is_array()) throw not_a_part(path, std::string("no part.") + k);
    if (!s["part"].contains("project") || !s["part"]["project"].is_object()) throw not_a_part(path, "no part.project");
    return p;
}

/// A part, GeoJSON or GeoPackage (an SQLite file).
Part read_part(const std::string& path) {
    // Only a regular file can be a GeoPackage (SQLite needs a file): a stream (a FIFO, a pipe,
    // standard input) is not opened to look, so read_json_object_input still sees it whole.
    if (std::filesystem::is_regular_file(path)) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw InputError(path + ": cannot be read (not readable)");
        static const char sqlite[] = "SQLite format 3";  // and its NUL: the first 16 bytes of every SQLite file
        char head[sizeof sqlite] = {};
        in.read(head, sizeof head);
        if (in.gcount() == sizeof head && std::equal(head, head + sizeof head, sqlite)) return read_gpkg_part(path);
    }
    std::string text;
    try {
        text = shoal::detail::read_json_object_input(path, max_part_bytes, "a shard's report");
    } catch (const shoal::detail::InputOpenError& e) {
        throw InputError(path + ": cannot be read (" + e.reason + ")");
    } catch (const shoal::detail::NotJsonObject& e) {
        throw not_json(path, e.reason);
    }
    return read_geojson_part(path, text);
}

bool is_layer_or_table(const std::string& key) { return key == "summary" || key == "tracks" || key == "problems" || key == "assessment"; }
bool is_merge_only(const std::string& key) { return key == "shard" || key == "part"; }

/// The run header (the scalars of `shoal`) and the top level must agree, field by field.
void check_same_run(const Part& a, const Part& b) {
    const auto differ = [&](const std::string& field, const json* va, const json* vb) {
        const auto show = [](const json* v) { return v ? shoal::detail::shortened(v->dump()) : std::string("missing"); };
        return InputError("the parts are not of one run: " + field + " is " + show(va) + " in " + named(a.path) + " but " + show(vb) +
                          " in " + named(b.path) + " (merge parts checked with the same version, grid, ship and rules)");
    };
    const auto compare = [&](const json& ja, const json& jb, const std::string& prefix, bool top) {
        for (const auto& [k, v] : ja.items()) {
            if (top ? k == "shoal" || k == "features" : is_merge_only(k) || is_layer_or_table(k) || v.is_array()) continue;
            if (!jb.contains(k)) throw differ(prefix + named(k), &v, nullptr);
            if (jb[k] != v) throw differ(prefix + named(k), &v, &jb[k]);
        }
        for (const auto& [k, v] : jb.items())
            if (!ja.contains(k)) throw differ(prefix + named(k), nullptr, &v);
    };
    compare(a.doc, b.doc, "", true);
    compare(a.doc["shoal"], b.doc["shoal"], "", false);
    // --assess (GeoJSON): the same criteria; the scores are rows.
    const json& sa = a.doc["shoal"];
    const json& sb = b.doc["shoal"];
    if (sa.contains("assessment") != sb.contains("assessment"))
        throw differ(named("assessment"), sa.contains("assessment") ? &sa["assessment"] : nullptr, sb.contains("assessment") ? &sb["assessment"] : nullptr);
    if (sa.contains("assessment") && sa["assessment"].value("criteria", json()) != sb["assessment"].value("criteria", json()))
        throw differ(named("assessment") + ".criteria", &sa["assessment"]["criteria"], &sb["assessment"]["criteria"]);
}

/// Sorts rows by key (stable: rows of equal keys stay in part order), as one run orders them.
template <class Row>
void sort_rows(std::vector<std::pair<Key, Row>>& rows) {
    std::stable_sort(rows.begin(), rows.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
}
json in_order(std::vector<std::pair<Key, json>> rows) {
    sort_rows(rows);
    json out = json::array();
    for (auto& r : rows) out.push_back(std::move(r.second));
    return out;
}

InputError edited(const Part& p, const char* what, const std::string& is_not) {
    return InputError(p.path + ": an entry of shoal.part." + what + " is not " + is_not + " (was it edited?)");
}

std::size_t position_of(const json& v, const Part& p, const char* what) {
    if (!v.is_number_unsigned()) throw edited(p, what, "a whole number");
    return v.get<std::size_t>();
}
double as_key(std::size_t n) { return static_cast<double>(n); }

/// A track's, or a row of a track's: its track's position.
Key track_key(const json& o, const Part& p, const char* what) { return {as_key(p.set), as_key(position_of(o, p, what))}; }

/// A feature's (GeoJSON features, GeoPackage events, encounters, hulls, breaches): a track's
/// position (its events first, in track order), or an encounter's key [start_s, position of a,
/// position of b, kind] (after every track's, in the order one run sorts encounters), or a
/// breach's [trainee position] (last, by trainee; a trainee's in part order).
Key feature_key(const json& o, const Part& p, const char* what) {
    if (!o.is_array()) return {0, as_key(p.set), as_key(position_of(o, p, what))};
    if (o.size() == 1) return {2, as_key(p.set), as_key(position_of(o[0], p, what))};
    if (o.size() != 4 || !o[0].is_number() || !o[3].is_number_unsigned()) throw edited(p, what, "a track position or [start, a, b, kind]");
    return {1, o[0].get<double>(), as_key(p.set), as_key(position_of(o[1], p, what)), as_key(position_of(o[2], p, what)), o[3].get<double>()};
}

/// A closest approach's: [position of a, position of b].
Key approach_key(const json& o, const Part& p, const char* what) {
    if (!o.is_array() || o.size() != 2) throw edited(p, what, "[a, b]");
    return {as_key(p.set), as_key(position_of(o[0], p, what)), as_key(position_of(o[1], p, what))};
}

/// The group of part p's problem i (0: a file's, 1: a failed track's, 2: a track's), from shoal.part.problems.
std::size_t problem_group(const Part& p, std::size_t i) {
    const json& o = p.doc["shoal"]["part"]["problems"][i];  // as many as shoal.problems (read_shard)
    if (!o.is_array() || o.size() != 2 || !o[0].is_number_unsigned() || o[0].get<std::size_t>() > 2) throw edited(p, "problems", "[group, position]");
    return o[0].get<std::size_t>();
}

/// The problems of the files a part read (group 0), in its order.
std::vector<json> file_problems(const Part& p) {
    const json& all = p.doc["shoal"]["problems"];
    std::vector<json> out;
    for (std::size_t i = 0; i < all.size(); ++i)
        if (problem_group(p, i) == 0) out.push_back(all[i]);
    return out;
}

/// The keys of part k's problems: a file's problems once per set of inputs (nullopt in the
/// other parts of the set, which must list the same), then failed tracks', then tracks'.
std::vector<std::optional<Key>> problem_keys(const std::vector<Part>& parts, std::size_t k, const std::vector<std::size_t>& first_of_set) {
    const Part& p = parts[k];
    const json& s = p.doc["shoal"];
    const Part& first = parts[first_of_set[p.set]];
    // The problems of the files (group 0), in order: the same list in every part of a set, compared
    // whole (not entry by entry at the positions of one part, which a part listing fewer would
    // read past), whatever the order of the parts.
    if (&first != &p && file_problems(first) != file_problems(p))
        throw InputError(named(p.path) + " and " + named(first.path) +
                         " read the same inputs but list different problems with them: were the files changed between them?");
    std::vector<std::optional<Key>> keys;
    for (std::size_t i = 0; i < s["problems"].size(); ++i) {
        const auto group = problem_group(p, i);
        if (group == 0) keys.push_back(&first == &p ? std::optional<Key>(Key{0, as_key(p.set), 0, as_key(i)}) : std::nullopt);
        else keys.push_back(Key{as_key(group), as_key(p.set), as_key(position_of(s["part"]["problems"][i][1], p, "problems")), as_key(i)});
    }
    return keys;
}

json merged_summary(const std::vector<Part>& parts, const std::vector<std::size_t>& first_of_set) {
    const json& s0 = parts[0].doc["shoal"]["summary"];
    json out = json::object();
    for (const auto& item : s0.items()) {
        // Not a structured binding: clang 14 cannot capture one in the lambda below.
        const std::string& name = item.key();
        const auto& table = fields::summary_fields();
        const auto f = std::find_if(table.begin(), table.end(), [&](const auto& x) { return name == x.name; });
        if (f == table.end())
            throw InputError(parts[0].path + ": summary field " + named(name) + " is not one this shoal knows how to merge (a report of another version?)");
        const auto value = [&](const Part& p) -> const json& {
            const json& s = p.doc["shoal"]["summary"];
            if (!s.is_object() || !s.contains(name)) throw InputError(p.path + ": its summary has no " + named(name));
            return s[name];
        };
        switch (f->merge) {
            case fields::Merge::sum:
            case fields::Merge::per_input: {
                std::int64_t total = 0;
                double real = 0;
                bool is_real = false, any = false;
                for (std::size_t k = 0; k < parts.size(); ++k) {
                    const json& v = value(parts[k]);
                    if (f->merge == fields::Merge::per_input) {
                        const Part& first = parts[first_of_set[parts[k].set]];
                        if (v != value(first))
                            throw InputError("summary field " + named(name) + " is " + shoal::detail::shortened(v.dump()) + " in " + named(parts[k].path) + " but " +
                                             shoal::detail::shortened(value(first).dump()) + " in " + named(first.path) + ", shards of the same inputs: were the files changed between them?");
                        if (&first != &parts[k]) continue;
                    }
                    if (v.is_null()) continue;
                    if (!v.is_number()) throw InputError(parts[k].path + ": summary field " + named(name) + " is not a number");
                    any = true;
                    if (v.is_number_integer()) total += v.get<std::int64_t>();
                    else {
                        is_real = true;
                        real += v.get<double>();
                    }
                }
                out[name] = !any ? json(nullptr) : is_real ? json(real + static_cast<double>(total)) : json(total);
                break;
            }
            case fields::Merge::min_time:
            case fields::Merge::max_time: {
                json best = value(parts[0]);  // when no part has a time: what they all say (no fix: "")
                double best_s = 0;
                bool found = false;
                for (const Part& p : parts) {
                    const json& v = value(p);
                    if (v.is_null() || v == "") continue;
                    const auto t = v.is_string() ? track::parse_iso8601(v.get<std::string>()) : std::nullopt;
                    if (!t) throw InputError(p.path + ": summary field " + named(name) + " is not an ISO 8601 time: " + shoal::detail::shortened(v.dump()));
                    if (!found || (f->merge == fields::Merge::min_time ? *t < best_s : *t > best_s)) {
                        best = v;
                        best_s = *t;
                        found = true;
                    }
                }
                out[name] = best;
                break;
            }
        }
    }
    return out;
}



/// Parts must be of the format of the report they are merged into.
void check_formats(const std::vector<Part>& parts, bool gpkg) {
    for (const Part& p : parts)
        if ((p.gpkg != nullptr) != gpkg)
            throw InputError(p.path + (gpkg ? ": a GeoJSON part; a GeoPackage report (-o REPORT.gpkg) is merged from GeoPackage parts (check --shard I/N -o PART.gpkg)"
                                            : ": a GeoPackage part; a GeoJSON report is merged from GeoJSON parts (check --shard I/N -o PART.geojson), "
                                              "or write the merged report as .gpkg"));
}

/// The parts, read and checked: one run's, complete sets of shards.
struct Plan {
    std::vector<Part> parts;
    std::vector<std::size_t> first_of_set;  ///< the first part of each set of inputs
};

/// The parts at `paths`, of the format of the output (`gpkg`), checked.
Plan plan_merge(const std::vector<std::string>& paths, bool gpkg) {
    if (paths.empty()) throw UsageError("merge: no parts given");
    Plan plan;
    std::vector<Part>& parts = plan.parts;
    for (const auto& p : paths) parts.push_back(read_part(p));
    check_formats(parts, gpkg);
    for (std::size_t k = 1; k < parts.size(); ++k) check_same_run(parts[0], parts[k]);

    // Sets of inputs, in the order first met; each a complete set of shards.
    std::vector<std::string> set_inputs;
    std::vector<std::size_t>& first_of_set = plan.first_of_set;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const std::string key = parts[k].doc["shoal"]["part"]["inputs"].dump();
        const auto it = std::find(set_inputs.begin(), set_inputs.end(), key);
        parts[k].set = static_cast<std::size_t>(it - set_inputs.begin());
        if (it == set_inputs.end()) {
            set_inputs.push_back(key);
            first_of_set.push_back(k);
        }
    }
    std::map<std::string, std::size_t> file_set;  // every file read, and its set
    for (std::size_t s = 0; s < set_inputs.size(); ++s) {
        const Part& first = parts[first_of_set[s]];
        const unsigned n = first.shard.count;
        std::vector<const Part*> seen(n, nullptr);
        for (const Part& p : parts) {
            if (p.set != s) continue;
            if (p.shard.count != n)
                throw InputError("the parts of the same inputs have different shard counts: " + named(first.path) + " is shard " +
                                 audit::Shard{first.shard.index, n}.text() + ", " + named(p.path) + " is shard " + audit::Shard{p.shard.index, p.shard.count}.text());
            if (seen[p.shard.index])
                throw InputError("shard " + audit::Shard{p.shard.index, n}.text() + " is given twice: " + named(seen[p.shard.index]->path) + " and " +
                                 named(p.path));
            seen[p.shard.index] = &p;
        }
        // The same inputs, as they were: each file's size and fingerprint (before: the names only,
        // and shards of a file that grew between their runs merged into a report of neither).
        for (const Part& p : parts) {
            if (p.set != s || &p == &first) continue;
            const json& fa = first.doc["shoal"]["part"].value("fingerprints", json());
            const json& fb = p.doc["shoal"]["part"].value("fingerprints", json());
            const json& names = first.doc["shoal"]["part"]["inputs"];
            if (!fa.is_array() || !fb.is_array() || fa.size() != names.size() || fb.size() != names.size())
                throw not_a_part(fa.is_array() && fa.size() == names.size() ? p.path : first.path, "no part.fingerprints for its inputs");
            for (std::size_t i = 0; i < names.size(); ++i)
                if (fa[i] != fb[i]) {
                    const auto what = [](const json& v) {
                        if (!v.is_array() || v.size() != 2) return shoal::detail::shortened(v.dump());
                        return (v[0].is_number() ? v[0].dump() : std::string("?")) + " bytes, fingerprint " + shoal::detail::shortened(v[1].dump());
                    };
                    const std::string name = names[i].is_string() ? names[i].get<std::string>() : names[i].dump();
                    // Standard input or a pipe: its content as read is what differs.
                    const bool stream = name == "-" || name.starts_with("/dev/") || name.starts_with("/proc/") || name.starts_with("/vsistdin");
                    throw InputError("the parts are not of one run: input " + named(name) + " is " + what(fa[i]) + " in " + named(first.path) +
                                     " but " + what(fb[i]) + " in " + named(p.path) +
                                     (stream ? ": the shards read other contents from it; feed every shard the same"
                                             : ": the file changed between the shards' runs; check every shard of it again"));
                }
        }
        for (unsigned i = 0; i < n; ++i)
            if (!seen[i])
                throw InputError("shard " + audit::Shard{i, n}.text() + " is missing: the parts of the inputs of " + named(first.path) +
                                 " must be every shard 0 to " + std::to_string(n - 1) + " of " + std::to_string(n) + ", each once");
        if (const json by = first.doc["shoal"].value("exercise_by", json()); set_inputs.size() > 1 && by.is_string() && by != "file")
            throw InputError(named(first.path) + " is of exercises by " + by.get<std::string>() +
                             " (--encounters), which one run of separate files would group otherwise: its parts must be shards of the same inputs");
        for (const auto& f : first.doc["shoal"]["part"]["inputs"]) {
            const std::string file = f.is_string() ? f.get<std::string>() : f.dump();
            const auto [it, fresh] = file_set.emplace(file, s);
            if (!fresh && it->second != s)
                throw InputError("file " + named(file) + " is read by " + named(parts[first_of_set[it->second]].path) + " and by " +
                                 named(first.path) + ": one run reads a file once; merge parts of separate files, or shards of one run");
        }
    }
    // A vessel seen by two sets would have been one track in one run.
    std::map<std::string, const Part*> vessel_part;
    std::map<std::string, std::size_t> vessel_set;
    for (const Part& p : parts) {
        if (p.doc["shoal"].value("exercise_by", json()) == "file") continue;  // exercises by file: never merged across files
        for (const auto& t : p.doc["shoal"]["tracks"]) {
            if (!t.is_object() || !t.contains("track") || !t["track"].is_string()) continue;
            const std::string id = t["track"].get<std::string>();
            if (!track::is_vessel_id(id)) continue;
            const auto [it, fresh] = vessel_set.emplace(id, p.set);
            if (fresh) vessel_part[id] = &p;
            else if (it->second != p.set)
                throw InputError("vessel " + shoal::detail::shortened(id) + " has tracks in " + named(vessel_part[id]->path) + " and in " + named(p.path) +
                                 ", which read different files: one run would have merged them into one track. Check those files in one run "
                                 "(shards of all of them: --shard I/N) instead of one run per file");
        }
    }
    std::set<std::pair<std::size_t, std::size_t>> track_seen;
    for (const Part& p : parts)
        for (const json& o : p.doc["shoal"]["part"]["tracks"]) {
            const std::size_t pos = position_of(o, p, "tracks");
            if (!track_seen.emplace(p.set, pos).second)
                throw InputError(p.path + ": the track at position " + std::to_string(pos) + " is in another part as well (shards of different runs?)");
        }
    return plan;
}

std::size_t count_of(const json& summary, const char* name) {
    return summary.contains(name) && summary[name].is_number_integer() ? summary[name].get<std::size_t>() : 0;
}

MergeSummary summary_of(std::size_t parts, std::size_t tracks, const json& s) {
    MergeSummary m;
    m.parts = parts;
    m.tracks = tracks;
    m.events = count_of(s, "events");
    m.groundings = count_of(s, "groundings");
    m.collisions = count_of(s, "collisions");
    return m;
}

/// The merged GeoJSON report of GeoJSON parts.
std::string merged_geojson(Plan& plan, MergeSummary* summary) {
    std::vector<Part>& parts = plan.parts;
    std::vector<std::pair<Key, json>> tracks, features, problems, approaches, scores;
    std::map<std::string, json> run_layers;  // other arrays of `shoal`, in part order
    for (std::size_t k = 0; k < parts.size(); ++k) {
        Part& p = parts[k];
        json& s = p.doc["shoal"];
        const json& order = s["part"];
        if (s.contains("assessment"))
            for (std::size_t i = 0; i < s["assessment"]["scores"].size(); ++i)
                scores.push_back({track_key(order["scores"][i], p, "scores"), std::move(s["assessment"]["scores"][i])});
        for (std::size_t i = 0; i < s["tracks"].size(); ++i) tracks.push_back({track_key(order["tracks"][i], p, "tracks"), std::move(s["tracks"][i])});
        for (std::size_t i = 0; i < p.doc["features"].size(); ++i)
            features.push_back({feature_key(order["features"][i], p, "features"), std::move(p.doc["features"][i])});
        const auto keys = problem_keys(parts, k, plan.first_of_set);
        for (std::size_t i = 0; i < keys.size(); ++i)
            if (keys[i]) problems.push_back({*keys[i], s["problems"][i]});
        for (auto& [name, v] : s.items()) {
            if (!v.is_array() || is_layer_or_table(name) || is_merge_only(name)) continue;
            if (name == "closest_approaches") {
                if (v.size() != order["approaches"].size())
                    throw InputError(p.path + ": its shoal.closest_approaches and the positions in shoal.part.approaches do not match (was it edited?)");
                for (std::size_t i = 0; i < v.size(); ++i) approaches.push_back({approach_key(order["approaches"][i], p, "approaches"), std::move(v[i])});
                continue;
            }
            json& all = run_layers[name];
            if (all.is_null()) all = json::array();
            for (auto& row : v) all.push_back(std::move(row));
        }
    }
    const std::size_t n_tracks = tracks.size();

    // The report: part 0's members, in its order, merged.
    json doc = json::object();
    for (const auto& [k, v] : parts[0].doc.items()) {
        if (k == "features") doc[k] = in_order(std::move(features));
        else if (k != "shoal") doc[k] = v;
        else {
            json s = json::object();
            for (const auto& [name, value] : v.items()) {
                if (is_merge_only(name)) continue;
                if (name == "summary") s[name] = merged_summary(parts, plan.first_of_set);
                else if (name == "tracks") s[name] = in_order(std::move(tracks));
                else if (name == "problems") s[name] = in_order(std::move(problems));
                else if (name == "closest_approaches") s[name] = in_order(std::move(approaches));
                else if (name == "assessment") s[name] = {{"criteria", value["criteria"]}, {"scores", in_order(std::move(scores))}};
                else if (value.is_array()) s[name] = std::move(run_layers[name]);
                else s[name] = value;
            }
            doc[k] = std::move(s);
        }
    }
    if (summary) *summary = summary_of(parts.size(), n_tracks, doc["shoal"]["summary"]);
    return doc.dump(1, ' ', false, json::error_handler_t::replace) + "\n";
}

/// The features of layer `name` of every part, each with its key (`key` of the part's
/// positions `what`), in one run's order.
template <class KeyOf>
std::vector<std::pair<Key, OGRFeatureUniquePtr>> gpkg_rows(std::vector<Part>& parts, const char* name, const char* what, KeyOf key) {
    std::vector<std::pair<Key, OGRFeatureUniquePtr>> rows;
    for (Part& p : parts) {
        OGRLayer* in = p.gpkg->GetLayerByName(name);
        if (!in) throw not_a_part(p.path, std::string("no layer ") + name);
        const json* order = what ? &p.doc["shoal"]["part"][what] : nullptr;
        if (order && static_cast<std::size_t>(in->GetFeatureCount()) != order->size())
            throw InputError(p.path + ": its layer " + name + " and the positions in its table part (" + what + ") do not match (was it edited?)");
        in->ResetReading();
        for (std::size_t i = 0; OGRFeatureUniquePtr f{in->GetNextFeature()}; ++i) rows.push_back({key(p, order ? (*order)[i] : json(), f.get()), std::move(f)});
    }
    sort_rows(rows);
    return rows;
}

/// Writes `rows` (features of parts) into `out`, as the single run's writer would: the same
/// fields by name (fields a part has that the report has not, e.g. run.shard, are left out).
void put_rows(OGRLayer* out, const std::vector<std::pair<Key, OGRFeatureUniquePtr>>& rows) {
    for (const auto& [key, f] : rows) {
        OGRFeature g(out->GetLayerDefn());
        g.SetFrom(f.get(), TRUE);
        if (out->CreateFeature(&g) != OGRERR_NONE)
            throw LibraryError(std::string("writing a feature to layer ") + out->GetName() + ": " + CPLGetLastErrorMsg());
    }
}

/// The tile of a coast feature, from its key ("RrrrrCcccc", report/qgis/chart_layer.hpp: tile_key).
Key tile_key_of(const Part& p, const OGRFeature& f) {
    const std::string key = f.GetFieldAsString("tile");
    const std::optional<ChartTile> t = parse_tile_key(key);
    if (!t) throw InputError(p.path + ": coast tile " + named(key) + " is not RrrrrCcccc (was it edited?)");
    return {static_cast<double>(t->col), static_cast<double>(t->row)};  // ChartTile's order, as the writer's set
}

/// The merged GeoPackage report of GeoPackage parts, staged at `output`, written by the
/// GeoPackage writer's own frame and layers (report/gpkg_output.hpp).
StagedOutput staged_merged_gpkg(Plan& plan, const std::string& output, MergeSummary* summary) {
    std::vector<Part>& parts = plan.parts;
    GDALDataset& first = *parts[0].gpkg;
    audit::AuditResult shape;  // what decides which layers and fields the report has
    shape.has_encounters = first.GetLayerByName("encounters") != nullptr;
    shape.has_assessment = first.GetLayerByName("breaches") != nullptr;
    shape.world = first.GetLayerByName("learned") ? audit::World::real : audit::World::simulated;
    const bool chart = first.GetLayerByName("coast") != nullptr;
    // The poses layer and the stored project go together (check --no-project: neither).
    const bool project = first.GetLayerByName("poses") != nullptr;
    if (project) check_project_name(output);  // the stored QGIS project names the file
    ProjectView view;
    for (const Part& p : parts) {
        const json& v = p.doc["shoal"]["part"]["project"];
        const auto number = [&](const json& x, double none) { return x.is_number() ? x.get<double>() : none; };
        const json& e = v.value("extent", json::array());
        if (!e.is_array() || e.size() != 4) throw edited(p, "project", "{extent: [x0, y0, x1, y1], ...}");
        ProjectView part{number(e[0], INFINITY), number(e[1], INFINITY), number(e[2], -INFINITY), number(e[3], -INFINITY), {},
                         number(v.value("first_fix_s", json()), NAN), number(v.value("last_fix_s", json()), NAN), {}};
        // The chart's box: the same in every part of a run (none in a part written before it was kept).
        const json& c = v.value("chart", json::array());
        if (c.is_array() && c.size() == 4)
            part.chart = {number(c[0], INFINITY), number(c[1], INFINITY), number(c[2], -INFINITY), number(c[3], -INFINITY)};
        for (const json& x : v.value("exercises", json::array()))
            if (x.is_string()) part.exercises.push_back(x.get<std::string>());
        view.add(part);
    }
    const json merged = merged_summary(parts, plan.first_of_set);

    const auto by_track = [](const char* what) { return [what](const Part& p, const json& o, const OGRFeature*) { return track_key(o, p, what); }; };
    const auto by_feature = [](const char* what) { return [what](const Part& p, const json& o, const OGRFeature*) { return feature_key(o, p, what); }; };
    const auto fill = [&](GDALDataset& ds) {
        const GpkgLayers out = make_gpkg_layers(ds, shape, chart, project);
        if (ds.StartTransaction() != OGRERR_NONE) throw LibraryError("GeoPackage transaction failed");
        put_rows(out.events, gpkg_rows(parts, "events", "events", by_feature("events")));
        if (out.encounters) put_rows(out.encounters, gpkg_rows(parts, "encounters", "encounters", by_feature("encounters")));
        if (out.breaches) put_rows(out.breaches, gpkg_rows(parts, "breaches", "breaches", by_feature("breaches")));
        const auto tracks = gpkg_rows(parts, "tracks", "tracks", by_track("tracks"));
        if (summary) *summary = summary_of(parts.size(), tracks.size(), merged);
        put_rows(out.tracks, tracks);
        put_rows(out.hulls, gpkg_rows(parts, "hulls", "hulls", by_feature("hulls")));
        if (out.poses) put_rows(out.poses, gpkg_rows(parts, "poses", "poses", by_track("poses")));
        if (out.coast) {
            // A tile's features are the same in every part that has the tile: taken from the first.
            std::map<Key, const Part*> tile_part;
            auto rows = gpkg_rows(parts, "coast", nullptr, [&](const Part& p, const json&, const OGRFeature* f) {
                Key tile = tile_key_of(p, *f);
                const Part*& owner = tile_part.emplace(tile, &p).first->second;
                tile.push_back(owner == &p ? 0 : 1);  // 1: a copy, dropped below
                return tile;
            });
            rows.erase(std::remove_if(rows.begin(), rows.end(), [](const auto& r) { return r.first.back() != 0; }), rows.end());
            put_rows(out.coast, rows);
        }
        if (out.learned) {
            // What the traffic taught is the same in every shard of a set of inputs (each learns
            // from every track read): the first part of each set gives it.
            std::vector<std::pair<Key, OGRFeatureUniquePtr>> rows;
            for (const std::size_t k : plan.first_of_set) {
                OGRLayer* in = parts[k].gpkg->GetLayerByName("learned");
                if (!in) throw not_a_part(parts[k].path, "no layer learned");
                in->ResetReading();
                for (std::size_t i = 0; OGRFeatureUniquePtr f{in->GetNextFeature()}; ++i)
                    rows.push_back({Key{as_key(parts[k].set), as_key(i)}, std::move(f)});
            }
            put_rows(out.learned, rows);
        }
        {
            std::vector<std::pair<Key, OGRFeatureUniquePtr>> rows;
            for (std::size_t k = 0; k < parts.size(); ++k) {
                const auto keys = problem_keys(parts, k, plan.first_of_set);
                OGRLayer* in = parts[k].gpkg->GetLayerByName("problems");
                in->ResetReading();
                for (std::size_t i = 0; OGRFeatureUniquePtr f{in->GetNextFeature()}; ++i)
                    if (i < keys.size() && keys[i]) rows.push_back({*keys[i], std::move(f)});
            }
            sort_rows(rows);
            put_rows(out.problems, rows);
        }
        if (out.approaches)
            put_rows(out.approaches, gpkg_rows(parts, "closest_approaches", "approaches",
                                               [](const Part& p, const json& o, const OGRFeature*) { return approach_key(o, p, "approaches"); }));
        if (out.scores) put_rows(out.scores, gpkg_rows(parts, "scores", "scores", by_track("scores")));
        // The run: part 0's row (without its shard); the summary: part 0's row, merged.
        std::vector<std::pair<Key, OGRFeatureUniquePtr>> run, sum;
        OGRLayer* run_in = first.GetLayerByName("run");
        OGRLayer* sum_in = first.GetLayerByName("summary");
        run_in->ResetReading();
        sum_in->ResetReading();
        run.push_back({Key{}, OGRFeatureUniquePtr{run_in->GetNextFeature()}});
        sum.push_back({Key{}, OGRFeatureUniquePtr{sum_in->GetNextFeature()}});
        put_rows(out.run, run);
        OGRFeature& s = *sum[0].second;
        for (const auto& [name, v] : merged.items()) {
            const int i = s.GetFieldIndex(name.c_str());
            if (i < 0 || v.is_null()) continue;  // null in every part: part 0's, as it is
            if (v.is_number_integer()) s.SetField(i, static_cast<GIntBig>(v.get<std::int64_t>()));
            else if (v.is_number()) s.SetField(i, v.get<double>());
            else if (v.is_string()) s.SetField(i, v.get<std::string>().c_str());
        }
        put_rows(out.summary, sum);
        if (ds.CommitTransaction() != OGRERR_NONE) throw LibraryError("GeoPackage commit failed: " + std::string(CPLGetLastErrorMsg()));
    };
    return stage_gpkg_with(output, fill, project ? &view : nullptr);
}

}  // namespace

std::string merge_geojson(const std::vector<std::string>& paths, MergeSummary* summary) {
    Plan plan = plan_merge(paths, false);
    return merged_geojson(plan, summary);
}

MergeSummary merge_reports(const std::vector<std::string>& parts, const std::string& output, std::vector<std::string>* warnings,
                           const MergeOptions& options) {
    const bool gpkg = is_gpkg(output);
    const bool pages = !options.debrief.empty() || !options.plot.empty();
    // The inputs: the parts and, for the pages, their records.
    std::vector<std::string> inputs = parts;
    if (pages)
        for (const std::string& p : parts) inputs.push_back(debrief_record_path(p));
    std::vector<OutputSpec> outputs = report_outputs(output, gpkg ? "gpkg" : "geojson", false);  // a merged GeoJSON report has no project (docs/user-guide.md)
    if (!options.plot.empty()) outputs.push_back({options.plot, "--plot", "the picture", is_shoal_picture});
    check_outputs(outputs, inputs);
    if (!options.debrief.empty()) check_debrief_folder(options.debrief);
    MergeSummary summary;
    Plan plan = plan_merge(parts, gpkg);
    // The records, read and checked before anything is written.
    std::vector<DebriefRecord> records;
    std::vector<std::size_t> sets;
    std::vector<bool> first_of_set;
    if (pages)
        for (std::size_t k = 0; k < plan.parts.size(); ++k) {
            const Part& p = plan.parts[k];
            DebriefRecord& r = records.emplace_back(read_debrief_record(p.path));
            if (r.shard.text() != p.shard.text())
                throw InputError("'" + r.path + "' is the record of shard " + r.shard.text() + ", but '" + p.path + "' is shard " + p.shard.text());
            const json& listed = p.doc["shoal"]["part"]["tracks"];
            bool same = listed.size() == r.result.track_positions.size();
            for (std::size_t i = 0; same && i < listed.size(); ++i)
                same = listed[i].is_number_unsigned() && listed[i].get<std::size_t>() == r.result.track_positions[i];
            if (!same) throw InputError("'" + r.path + "' does not hold the tracks of its part '" + p.path + "' (was one of them edited?)");
            sets.push_back(p.set);
            first_of_set.push_back(plan.first_of_set[p.set] == k);
        }
    std::vector<StagedOutput> staged;
    if (gpkg) staged.push_back(staged_merged_gpkg(plan, output, &summary));
    else staged = stage_geojson_text(output, merged_geojson(plan, &summary), warnings);
    if (pages) {
        const grid::CoastGrid grid = load_recorded_grid(records.front(), options.coast);
        const RunInfo info = records.front().info;
        const audit::AuditResult run = join_debrief_records(std::move(records), sets, first_of_set);
        if (!options.plot.empty()) {
            StagedOutput& picture = staged.emplace_back(options.plot);
            picture.write(plot_svg(run, grid));
        }
        if (!options.debrief.empty()) {
            std::vector<StagedOutput> sheets = stage_debrief(options.debrief, run, grid, info, inputs, outputs, {}, &summary.pages_refused);
            summary.pages_left_out = !summary.pages_refused.empty();
            summary.pages = sheets.size();
            for (StagedOutput& s : sheets) staged.push_back(std::move(s));
        }
    }
    commit_all(staged);
    return summary;
}

}  // namespace shoal::report
