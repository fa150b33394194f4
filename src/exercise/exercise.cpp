// Exercises and roles (see include/shoal/exercise/exercise.hpp).
#include <shoal/exercise/exercise.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include <shoal/util/error.hpp>

#include "util/input_file.hpp"
#include "util/json_message.hpp"

namespace shoal::audit {

const char* to_string(ExerciseBy by) noexcept {
    switch (by) {
        case ExerciseBy::file: return "file";
        case ExerciseBy::folder: return "folder";
        case ExerciseBy::column: return "column";
        case ExerciseBy::run: break;
    }
    return "run";
}

std::string exercise_by_text(ExerciseBy by, const std::string& column) {
    return by == ExerciseBy::column ? "column:" + column : std::string(to_string(by));
}

ExerciseGrouping parse_exercise_grouping(const std::string& s) {
    if (s == "run") return {ExerciseBy::run, {}};
    if (s == "file") return {ExerciseBy::file, {}};
    if (s == "folder") return {ExerciseBy::folder, {}};
    if (s.rfind("column:", 0) == 0) {
        std::string name = s.substr(7);
        if (name.find_first_not_of(" \t") == std::string::npos)
            throw UsageError("AuditOptions::exercise_by '" + s + "' names no column: give column:NAME, e.g. column:exercise");
        return {ExerciseBy::column, std::move(name)};
    }
    throw UsageError("AuditOptions::exercise_by '" + s + "' is none of run, file, folder, column:NAME");
}

ExerciseBy parse_exercise_by(const std::string& s) { return parse_exercise_grouping(s).by; }

std::string exercise_key(ExerciseBy by, const std::string& file, const std::string& column_value) {
    switch (by) {
        case ExerciseBy::column: return column_value;
        case ExerciseBy::file: return file;
        case ExerciseBy::folder: {
            const std::string folder = std::filesystem::path(file).parent_path().string();
            return folder.empty() ? "." : folder;
        }
        case ExerciseBy::run: break;
    }
    return "run";
}

std::string exercise_key(ExerciseBy by, const track::Track& track) { return exercise_key(by, track.file, track.exercise); }

Roles Roles::parse(const std::string& text, const std::string& source) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {  // a syntax error, or a number too large for a double (out_of_range 406)
        throw InputError("exercise file '" + source + "': not JSON: " + shoal::detail::json_error_text(e.what()));
    }
    auto fail = [&](const std::string& what) { throw InputError("exercise file '" + source + "': " + what); };
    if (!j.is_object()) fail("not a JSON object");
    for (const auto& [key, _] : j.items())
        if (key != "default_role" && key != "tracks" && key != "$schema" && key != "description") fail("unknown member '" + key + "'");
    Roles r;
    r.source = source;
    if (j.contains("default_role")) {
        if (!j["default_role"].is_string() || !parse_role(j["default_role"].get<std::string>(), r.default_role))
            fail("default_role must be \"trainee\" or \"target\"");
    }
    if (!j.contains("tracks") || !j["tracks"].is_array()) fail("no \"tracks\" array");
    std::size_t n = 0;
    for (const auto& e : j["tracks"]) {
        const std::string where = "tracks[" + std::to_string(n++) + "]";
        if (!e.is_object()) fail(where + " is not an object");
        for (const auto& [key, _] : e.items())
            if (key != "track" && key != "exercise" && key != "role") fail(where + ": unknown member '" + key + "'");
        Entry entry;
        if (!e.contains("track") || !e["track"].is_string() || e["track"].get<std::string>().empty()) fail(where + ": no \"track\" (a track id)");
        entry.track = e["track"].get<std::string>();
        if (e.contains("exercise")) {
            if (!e["exercise"].is_string()) fail(where + ": \"exercise\" must be a string");
            entry.exercise = e["exercise"].get<std::string>();
        }
        if (!e.contains("role") || !e["role"].is_string() || !parse_role(e["role"].get<std::string>(), entry.role))
            fail(where + " (track '" + entry.track + "'): \"role\" must be \"trainee\" or \"target\"");
        r.entries.push_back(std::move(entry));
    }
    return r;
}

Roles Roles::load(const std::string& path) {
    return parse(shoal::detail::read_json_settings(path, max_file_bytes, "an exercise file", "exercise file"), path);
}

std::optional<Role> Roles::entry_role(const std::string& exercise, const std::string& track) const {
    const Entry* any = nullptr;
    for (const Entry& e : entries) {
        if (e.track != track) continue;
        if (e.exercise == exercise) return e.role;
        if (e.exercise.empty() && !any) any = &e;
    }
    if (any) return any->role;
    return std::nullopt;
}

void Roles::check_entries_name_tracks(const std::vector<std::pair<std::string, std::string>>& tracks) const {
    std::set<std::string> ids;
    std::set<std::pair<std::string, std::string>> keyed;
    for (const auto& [id, exercise] : tracks) {
        ids.insert(id);
        keyed.insert({id, exercise});
    }
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Entry& e = entries[i];
        if (e.exercise.empty() ? ids.contains(e.track) : keyed.contains({e.track, e.exercise})) continue;
        std::string read;
        std::size_t n = 0;
        for (const std::string& id : ids)
            if (n++ < 5) read += (read.empty() ? "'" : ", '") + shoal::detail::shortened(id, 80) + "'";
        if (ids.size() > 5) read += " and " + std::to_string(ids.size() - 5) + " more";
        const bool id_known = ids.contains(e.track);
        throw InputError("exercise file '" + source + "': tracks[" + std::to_string(i) + "] names track '" + shoal::detail::shortened(e.track, 80) + "'" +
                         (e.exercise.empty() ? std::string() : " in exercise '" + shoal::detail::shortened(e.exercise, 200) + "'") +
                         (id_known ? ", which that exercise has no track of" : ", which no track read has") + " (it would make it a " + to_string(e.role) +
                         "; tracks read: " + (read.empty() ? std::string("none") : read) + "): a typo? Every entry must name a track of the run");
    }
}

Role Roles::role_of(const std::string& exercise, const std::string& track) const {
    return entry_role(exercise, track).value_or(default_role);
}

Role role_of(const Roles* roles, const std::string& exercise, const track::Track& track) {
    if (roles)
        if (const std::optional<Role> r = roles->entry_role(exercise, track.id)) return *r;
    if (!track.role.empty()) return track.role == "target" ? Role::target : Role::trainee;
    return roles ? roles->default_role : Role::trainee;
}

}  // namespace shoal::audit
