#pragma once
/// Exercises and roles. In exercise mode the tracks of a run are grouped into exercises and
/// ship-to-ship encounters are found within an exercise only, never across two:
///
/// - `ExerciseBy::run` (the default, as before): the whole run is one exercise, named "run".
/// - `ExerciseBy::file`: each track file is an exercise, named by the file as given.
/// - `ExerciseBy::folder`: the tracks of one folder are an exercise, named by the folder
///   ("." for files given without one).
/// - `ExerciseBy::column`: the exercise of each fix is the value of a column (a CSV column or
///   a GeoJSON property, track::ReadOptions::exercise_column), named by that value: one file
///   may hold several exercises, and one vessel id in two exercises is two tracks
///   (Track::exercise).
///
/// Each track has a role: a *trainee* (own ship, the bridge being assessed) or a *target*
/// (traffic played by the instructor). Targets are checked against trainees only: pairs of two
/// targets are not reported. A track's role comes from an exercise file (Roles), from a role
/// column (track::ReadOptions::role_column, Track::role), or both: role_of() says which wins.
/// With neither, every track is a trainee.
/// exercise_key() is what a shard of a batch keys on, so that an exercise is never split.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <shoal/sweep/role.hpp>
#include <shoal/track/track.hpp>

namespace shoal::audit {

enum class ExerciseBy { run, file, folder, column };

/// "run", "file", "folder", "column".
const char* to_string(ExerciseBy by) noexcept;
/// How the exercises of a run were made, for the report: to_string(by), and for a column
/// "column:NAME".
std::string exercise_by_text(ExerciseBy by, const std::string& column);

/// How tracks are grouped, as `--exercise-by` gives it.
struct ExerciseGrouping {
    ExerciseBy by = ExerciseBy::run;
    std::string column;  ///< ExerciseBy::column: the column's name (not empty); else ""
};
/// Parses "run", "file", "folder" or "column:NAME" (NAME not empty, kept as given); throws
/// UsageError naming AuditOptions::exercise_by otherwise.
ExerciseGrouping parse_exercise_grouping(const std::string& s);
/// parse_exercise_grouping(s).by.
ExerciseBy parse_exercise_by(const std::string& s);

/// The exercise of a track read from `file` (as given to the reader: Track::file) whose
/// exercise column gave `column_value` (Track::exercise; used by ExerciseBy::column only).
std::string exercise_key(ExerciseBy by, const std::string& file, const std::string& column_value = {});
/// The exercise of `track`: exercise_key(by, track.file, track.exercise).
std::string exercise_key(ExerciseBy by, const track::Track& track);

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
    std::string source;                ///< the file read (parse's `source`), for messages

    /// Throws InputError for the first entry that names no track of `tracks` (each a track's
    /// id and its exercise key): a typo would otherwise leave a trainee unscored, in silence.
    void check_entries_name_tracks(const std::vector<std::pair<std::string, std::string>>& tracks) const;

    /// The largest exercise file read (16 MiB: some 300,000 entries); a larger one, or an
    /// endless source such as /dev/zero, is refused at that limit.
    static constexpr std::size_t max_file_bytes = std::size_t{16} << 20;

    /// Reads an exercise file (a file, a pipe, standard input `-`; gzip read decompressed);
    /// throws InputError naming the file and the entry that is wrong.
    static Roles load(const std::string& path);
    /// Parses the JSON text of an exercise file (`source` names it in messages).
    static Roles parse(const std::string& text, const std::string& source);

    /// The role of `track` in `exercise` by this file: the entry of that exercise, else an
    /// entry without one, else default_role.
    Role role_of(const std::string& exercise, const std::string& track) const;
    /// The role an entry gives `track` in `exercise` (of that exercise, else one without);
    /// none when no entry names it.
    std::optional<Role> entry_role(const std::string& exercise, const std::string& track) const;
};

/// The role of a track in exercise mode, from an exercise file (may be null) and the track's
/// role column value (Track::role: "trainee", "target", or "" when none was read). The file's
/// entry for the track wins; then the column; then the file's default_role; with neither, a
/// trainee. So a role column gives every track its role, and an exercise file given beside it
/// corrects the tracks it names.
Role role_of(const Roles* roles, const std::string& exercise, const track::Track& track);

}  // namespace shoal::audit
