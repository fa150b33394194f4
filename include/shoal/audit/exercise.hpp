#pragma once
/// Exercises and roles. In exercise mode the tracks of a run are grouped into exercises and
/// ship-to-ship encounters are found within an exercise only, never across two:
///
/// - `ExerciseBy::run` (the default, as before): the whole run is one exercise, named "run".
/// - `ExerciseBy::file`: each track file is an exercise, named by the file as given.
/// - `ExerciseBy::folder`: the tracks of one folder are an exercise, named by the folder
///   ("." for files given without one).
///
/// Each track has a role: a *trainee* (own ship, the bridge being assessed) or a *target*
/// (traffic played by the instructor). Targets are checked against trainees only: pairs of two
/// targets are not reported. Without a roles file every track is a trainee.
/// exercise_key() is what a shard of a batch keys on, so that an exercise is never split.

#include <cstddef>
#include <string>
#include <vector>

#include <shoal/track/track.hpp>

namespace shoal::audit {

enum class ExerciseBy { run, file, folder };

/// "run", "file", "folder".
const char* to_string(ExerciseBy by) noexcept;
/// Parses "run", "file" or "folder"; throws UsageError naming AuditOptions::exercise_by otherwise.
ExerciseBy parse_exercise_by(const std::string& s);

/// The exercise of a track read from `file` (as given to the reader: Track::file).
std::string exercise_key(ExerciseBy by, const std::string& file);
/// The exercise of `track`: exercise_key(by, track.file).
std::string exercise_key(ExerciseBy by, const track::Track& track);

enum class Role { trainee, target };
const char* to_string(Role r) noexcept;  ///< "trainee", "target"

/// Roles of tracks, from an exercise file (JSON, schemas/exercise.schema.json):
///
///     {"default_role": "target",
///      "tracks": [{"track": "own-1", "role": "trainee"},
///                 {"track": "own-1", "exercise": "morning/ex2", "role": "target"}]}
///
/// An entry with an `exercise` applies in that exercise only and wins over one without. Role
/// values: "trainee" (also "own", "own ship", "own_ship"), "target" (case does not matter).
struct Roles {
    struct Entry {
        std::string track, exercise;  ///< exercise "": any
        Role role = Role::trainee;
    };
    std::vector<Entry> entries;
    Role default_role = Role::target;  ///< for tracks no entry names

    /// The largest exercise file read (16 MiB: some 300,000 entries); a larger one, or an
    /// endless source such as /dev/zero, is refused at that limit.
    static constexpr std::size_t max_file_bytes = std::size_t{16} << 20;

    /// Reads an exercise file (a file, a pipe, standard input `-`; gzip read decompressed);
    /// throws InputError naming the file and the entry that is wrong.
    static Roles load(const std::string& path);
    /// Parses the JSON text of an exercise file (`source` names it in messages).
    static Roles parse(const std::string& text, const std::string& source);

    Role role_of(const std::string& exercise, const std::string& track) const;
};

/// Parses a role value ("trainee", "own", "own ship", "own_ship", "target"; any case); false if
/// it is none of them.
bool parse_role(const std::string& s, Role& role);

}  // namespace shoal::audit
