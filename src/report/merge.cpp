// Merging shard reports into one run's report (report/merge.hpp).
#include <shoal/report/merge.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "detail/input_file.hpp"
#include "detail/json_message.hpp"
#include "report/geojson_output.hpp"
#include "report/report_fields.hpp"
#include <shoal/audit/shard.hpp>
#include <shoal/report/report.hpp>
#include <shoal/track/merge.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

namespace {

using json = nlohmann::ordered_json;

struct Part {
    std::string path;
    json doc;
    audit::Shard shard;
    std::size_t set = 0;  ///< which set of inputs
};

/// A name or value from a part, quoted for a message (cut: a hostile part may hold megabytes in one).
std::string named(const std::string& s) { return "'" + shoal::detail::shortened(s, 240) + "'"; }

Part read_part(const std::string& path) {
    Part p;
    p.path = path;
    if (std::filesystem::path(path).extension() == ".gpkg")
        throw InputError(path + ": a GeoPackage part; merge reads the GeoJSON reports of shards (check --shard I/N -o PART.geojson)");
    std::string text;
    try {
        text = shoal::detail::read_json_object_input(path, max_part_bytes, "a shard's report");
    } catch (const shoal::detail::InputOpenError& e) {
        throw InputError(path + ": cannot be read (" + e.reason + ")");
    } catch (const shoal::detail::NotJsonObject& e) {
        throw InputError(path + ": not a GeoJSON report (" + e.reason + ")");
    }
    try {
        p.doc = json::parse(text);
    } catch (const json::exception& e) {
        throw InputError(path + ": not a GeoJSON report (" + shoal::detail::json_error_text(e.what()) + ")");
    }
    const auto not_part = [&](const std::string& why) {
        return InputError(path + ": not the report of a shard (" + why + "); `shoal check --shard I/N` writes those");
    };
    if (!p.doc.is_object() || !p.doc.contains("shoal") || !p.doc["shoal"].is_object()) throw not_part("no \"shoal\" member");
    const json& s = p.doc["shoal"];
    if (!s.contains("shard") || !s["shard"].is_string() || !s.contains("part") || !s["part"].is_object()) throw not_part("no shard in its run header");
    try {
        p.shard = audit::parse_shard(s["shard"].get<std::string>());
    } catch (const InputError& e) {
        throw not_part(std::string("its run header field 'shard': ") + e.what());
    }
    const json& order = s["part"];
    for (const char* k : {"inputs", "tracks", "features", "problems"})
        if (!order.contains(k) || !order[k].is_array()) throw not_part(std::string("no part.") + k);
    for (const char* k : {"tracks", "problems"})
        if (!s.contains(k) || !s[k].is_array() || s[k].size() != order[k].size())
            throw InputError(path + ": its shoal." + k + " and the positions in shoal.part." + k + " do not match (was it edited?)");
    if (!p.doc.contains("features") || !p.doc["features"].is_array() || p.doc["features"].size() != order["features"].size())
        throw InputError(path + ": its features and the positions in shoal.part.features do not match (was it edited?)");
    return p;
}

bool is_layer_or_table(const std::string& key) { return key == "summary" || key == "tracks" || key == "problems"; }
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
}

/// Sorts rows by key (stable), as one run orders them.
template <class Key>
json in_order(std::vector<std::pair<Key, json>> rows) {
    std::stable_sort(rows.begin(), rows.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    json out = json::array();
    for (auto& r : rows) out.push_back(std::move(r.second));
    return out;
}

std::size_t position_of(const json& v, const Part& p, const char* what) {
    if (!v.is_number_unsigned()) throw InputError(p.path + ": a position in shoal.part." + what + " is not a whole number (was it edited?)");
    return v.get<std::size_t>();
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

}  // namespace

std::string merge_geojson(const std::vector<std::string>& paths, MergeSummary* summary) {
    if (paths.empty()) throw UsageError("merge: no parts given");
    std::vector<Part> parts;
    for (const auto& p : paths) parts.push_back(read_part(p));
    for (std::size_t k = 1; k < parts.size(); ++k) check_same_run(parts[0], parts[k]);

    // Sets of inputs, in the order first met; each a complete set of shards.
    std::vector<std::string> set_inputs;
    std::vector<std::size_t> first_of_set;
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
        for (unsigned i = 0; i < n; ++i)
            if (!seen[i])
                throw InputError("shard " + audit::Shard{i, n}.text() + " is missing: the parts of the inputs of " + named(first.path) +
                                 " must be every shard 0 to " + std::to_string(n - 1) + " of " + std::to_string(n) + ", each once");
        if (set_inputs.size() > 1 && first.doc["shoal"]["part"].value("exercise", false))
            throw InputError(named(first.path) + " is an exercise (--encounters), which one run checks whole: its parts must be shards of the same inputs, not of separate files");
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
    for (const Part& p : parts)
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

    // The rows, in one run's order.
    using Key = std::tuple<std::size_t, std::size_t, std::size_t, std::size_t>;
    std::vector<std::pair<Key, json>> tracks, features, problems;
    std::set<std::pair<std::size_t, std::size_t>> track_seen;
    std::map<std::string, json> run_layers;  // other arrays of `shoal`, in part order
    for (std::size_t k = 0; k < parts.size(); ++k) {
        Part& p = parts[k];
        json& s = p.doc["shoal"];
        const json& order = s["part"];
        for (std::size_t i = 0; i < s["tracks"].size(); ++i) {
            const std::size_t pos = position_of(order["tracks"][i], p, "tracks");
            if (!track_seen.emplace(p.set, pos).second)
                throw InputError(p.path + ": the track at position " + std::to_string(pos) + " is in another part as well (shards of different runs?)");
            tracks.push_back({Key{p.set, pos, 0, 0}, std::move(s["tracks"][i])});
        }
        for (std::size_t i = 0; i < p.doc["features"].size(); ++i) {
            const json& o = order["features"][i];
            const bool of_run = o.is_number_integer() && o.get<std::int64_t>() < 0;
            Key key = of_run ? Key{1, k, i, 0} : Key{0, p.set, position_of(o, p, "features"), 0};
            features.push_back({key, std::move(p.doc["features"][i])});
        }
        for (std::size_t i = 0; i < s["problems"].size(); ++i) {
            const json& o = order["problems"][i];
            if (!o.is_array() || o.size() != 2 || !o[0].is_number_unsigned() || o[0].get<std::size_t>() > 2)
                throw InputError(p.path + ": an entry of shoal.part.problems is not [group, position] (was it edited?)");
            const auto group = o[0].get<std::size_t>();
            if (group == 0) {
                if (first_of_set[p.set] == k) problems.push_back({Key{0, p.set, 0, i}, s["problems"][i]});
                else if (s["problems"][i] != parts[first_of_set[p.set]].doc["shoal"]["problems"][i])
                    throw InputError(named(p.path) + " and " + named(parts[first_of_set[p.set]].path) +
                                     " read the same inputs but list different problems with them: were the files changed between them?");
                continue;
            }
            problems.push_back({Key{group, p.set, position_of(o[1], p, "problems"), i}, std::move(s["problems"][i])});
        }
        for (auto& [name, v] : s.items())
            if (v.is_array() && !is_layer_or_table(name) && !is_merge_only(name)) {
                json& all = run_layers[name];
                if (all.is_null()) all = json::array();
                for (auto& row : v) all.push_back(std::move(row));
            }
    }

    // The report: part 0's members, in its order, merged.
    json doc = json::object();
    for (const auto& [k, v] : parts[0].doc.items()) {
        if (k == "features") doc[k] = in_order(std::move(features));
        else if (k != "shoal") doc[k] = v;
        else {
            json s = json::object();
            for (const auto& [name, value] : v.items()) {
                if (is_merge_only(name)) continue;
                if (name == "summary") s[name] = merged_summary(parts, first_of_set);
                else if (name == "tracks") s[name] = in_order(std::move(tracks));
                else if (name == "problems") s[name] = in_order(std::move(problems));
                else if (value.is_array()) s[name] = std::move(run_layers[name]);
                else s[name] = value;
            }
            doc[k] = std::move(s);
        }
    }
    if (summary) {
        const json& s = doc["shoal"]["summary"];
        const auto count = [&](const char* name) { return s.contains(name) && s[name].is_number_integer() ? s[name].get<std::size_t>() : 0; };
        summary->parts = parts.size();
        summary->tracks = doc["shoal"]["tracks"].size();
        summary->events = count("events");
        summary->groundings = count("groundings");
        summary->collisions = count("collisions");
    }
    return doc.dump(1) + "\n";
}

MergeSummary merge_reports(const std::vector<std::string>& parts, const std::string& output, std::vector<std::string>* warnings) {
    if (std::filesystem::path(output).extension() == ".gpkg")
        throw UsageError("merge writes GeoJSON reports (from the GeoJSON reports of shards): -o " + named(output) +
                         " is a GeoPackage; write the merged report as .geojson");
    check_outputs(report_outputs(output, "geojson"), parts);
    MergeSummary summary;
    const std::string text = merge_geojson(parts, &summary);
    std::vector<StagedOutput> staged = stage_geojson_text(output, text, warnings);
    commit_all(staged);
    return summary;
}

}  // namespace shoal::report
