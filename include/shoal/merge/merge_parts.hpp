#pragma once
/// Merging the reports of a run's shards (`check --shard I/N`) into the report one run would
/// have written, byte for byte: GeoJSON parts into a GeoJSON report, GeoPackage parts into a
/// GeoPackage (the same file as `check -o` of the same file name writes: the rows copied into
/// the GeoPackage writer's own layers, in the same order, with the same QGIS project).
///
/// Parts are grouped by the inputs they read (every shard of a run reads every file): each
/// group must be a complete set of shards (each I of one N exactly once); several groups (one
/// per file, as the Dask driver runs them) are put one after another in the order given, and
/// must not share a file or a vessel (one run would have merged the vessel's tracks).
///
/// The rules, generic over the report's members so that new fields and layers merge too:
/// - the top level and the run header (every member of `shoal` that is not an object or an
///   array) must be equal in every part, except `shard`, which the merged report drops;
/// - `summary`: each field combined as its table says (report_fields.hpp: Merge: added up,
///   counted once per set of inputs, earliest, latest);
/// - `tracks`, `features`, `problems`, `closest_approaches` (and the GeoPackage's events,
///   encounters, hulls, poses): rows put back in one run's order by the positions each part
///   lists in its `shoal.part` member or `part` table (report/part_order.hpp: tracks in the
///   order they were read, a track's rows after the earlier tracks', encounters after every
///   track's in one run's order; a file's problems once per set of inputs, then failed
///   tracks', then tracks' in track order);
/// - the GeoPackage's `coast`: each tile's features once (from the first part that has it), in
///   tile order; `run`: part 0's row without its `shard`;
/// - any other array of `shoal` concatenated in part order.

#include <cstddef>
#include <string>
#include <vector>

namespace shoal::report {

/// What a merge gave, for the exit status and the table.
struct MergeSummary {
    std::size_t parts = 0, tracks = 0, events = 0, groundings = 0, collisions = 0;
    std::size_t pages = 0;           ///< debrief pages written
    /// The pages not written, a message each (a file of that name that shoal did not write):
    /// the merge's failure (exit 2), not a warning.
    std::vector<std::string> pages_refused;
    bool pages_left_out = false;  ///< !pages_refused.empty() (kept for callers of 0.2.0)
};

/// The whole run's other outputs, made at the merge from the parts' debrief records
/// (debrief_record.hpp; `check --shard I/N --debrief-record` writes them): the pages and the
/// picture one `check --debrief FOLDER --plot FILE` of the whole run writes.
struct MergeOptions {
    std::string debrief;             ///< --debrief FOLDER ("" none)
    std::string plot;                ///< --plot FILE ("" none)
    /// --coast: the grid (or its sources) to draw on, instead of the --coast the shards were
    /// given; checked against the run's grid fingerprint.
    std::vector<std::string> coast;
};

/// The largest part read (1 GiB, as a GeoJSON track file); a larger one, or an endless source
/// such as /dev/zero (refused at its first byte, which is not '{'), is not read further.
inline constexpr std::size_t max_part_bytes = std::size_t{1} << 30;

/// The merged GeoJSON report of the GeoJSON part reports at `parts` (in that order). Throws
/// InputError naming the part and what is wrong: unreadable, not a shard's report (or a
/// GeoPackage one), a run
/// header field that differs ("the parts are not of one run: 'step_m' is 5.0 in 'a' but 2.0 in 'b'"), a shard missing or given
/// twice, two sets of inputs sharing a file or a vessel.
std::string merge_geojson(const std::vector<std::string>& parts, MergeSummary* summary = nullptr);

/// The merged report written at `output`: a GeoPackage (.gpkg) from GeoPackage parts, else
/// merge_geojson's (with its QGIS style beside it); parts of the other format are refused. The
/// outputs are checked against the parts first (none may be a part), staged and put in place
/// together. Warnings (a style not replaced) go into `warnings` when given.
///
/// With `options.debrief` or `options.plot`: every part's debrief record is read (a part
/// without one: UsageError naming it and how to write it; a record of another part, or records
/// of different runs: InputError), the records joined as one run's (join_debrief_records), the
/// run's grid loaded again (load_recorded_grid), and the pages and the picture staged with the
/// report, all put in place together.
MergeSummary merge_reports(const std::vector<std::string>& parts, const std::string& output, std::vector<std::string>* warnings = nullptr,
                           const MergeOptions& options = {});

}  // namespace shoal::report
