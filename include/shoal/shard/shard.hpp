#pragma once
/// Shards of a run (`check --shard I/N`): the run's tracks split by a stable hash of a key, so
/// N processes (or machines) each audit one shard of the same inputs and `merge` puts their
/// reports back together as the report one run would have written.
///
/// The key is the track's id once every file is read and one vessel met in several files is
/// one track (track::merge_same_vessels), so a vessel is never split between shards. In
/// exercise mode (--encounters) the key is the track's exercise (exercise_key), so a shard
/// holds whole exercises: with --exercise-by run the run is one exercise, one shard holds
/// every track and the others none.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace shoal::audit {

/// Which shard of a run: `index` of `count`; count 0 is the whole run (no --shard).
struct Shard {
    unsigned index = 0;
    unsigned count = 0;
    bool active() const noexcept { return count > 0; }
    /// "I/N"; "" for the whole run.
    std::string text() const;
};

/// "I/N" with 0 <= I < N (N at least 1, at most 1000000). Throws InputError naming
/// `AuditOptions::shard` and what is wrong ("'3/3': the index must be under the count 3").
Shard parse_shard(std::string_view text);

/// The key that decides a track's shard: its id; in exercise mode its exercise (exercise_key:
/// "run" for the whole run, else its file or folder), so an exercise is never split.
std::string shard_key(const std::string& track_id, const std::optional<std::string>& exercise);

/// The shard of `key` among `count`: XXH3_64bits of the key's bytes, modulo count. The same on
/// every machine and in every language that has XXH3 (never Python's hash()).
unsigned shard_of(std::string_view key, unsigned count) noexcept;

}  // namespace shoal::audit
