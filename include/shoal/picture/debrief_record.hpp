#pragma once
/// The debrief record of a shard: what the debrief pages (debrief.hpp) and the picture
/// (plot.hpp) need from a shard's audit, written beside its report part so that `shoal merge
/// --debrief FOLDER --plot FILE` makes the pages and the picture one `check` of the whole run
/// writes, byte for byte (a shard holds only its part of the tracks, so it never writes them
/// itself: every shard would write the same pages over the others').
///
/// `shoal check --shard I/N -o PART --debrief-record` writes the record at
/// debrief_record_path(PART) (PART.debrief.cbor), staged and put in place with the part. The
/// file is the line "shoal debrief record 1\n" (shoal's mark and the format's version), then
/// CBOR (RFC 8949: NaN and infinity kept exactly, unlike JSON text) of an object holding:
/// - `part`: the size and fingerprint (XXH3) of the part's bytes as written, so that a record
///   is never read with another part (of another run, or the part written again since);
/// - `shard`, `info` (the run header the pages print: RunInfo's coast, frame, cell, grid
///   fingerprint, ship, margin, step, limiting depth, ukc, world, berths and the exercise
///   rules) and `grid` (the `--coast` inputs and the grid options, to load the grid again);
/// - `result`: the shard's tracks (summaries, events and the poses as kept), their positions
///   in one run's order (AuditResult::track_positions), the tracks that failed, the files read
///   with their errors, and in exercise mode the encounters (events and closest approaches),
///   the COLREG situations and the assessment (criteria, pass mark, source, scores, breaches),
///   every index into the tracks the shard's own.
///
/// join_debrief_records puts the records of a complete set of shards together as one run's
/// AuditResult: tracks in the order of their positions, every index into them renumbered
/// (encounters' a/b, closest approaches, situations, scores' and breaches' track_index), the
/// lists sorted as the audit sorts them (encounter events by start, a, b, kind; approaches and
/// situations by a, b; scores and breaches by trainee, each trainee's in its shard's order),
/// and the run's counts recounted from the tracks as the audit counts them.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

/// The first line of every record: shoal's mark and the format's version.
inline constexpr std::string_view debrief_record_mark = "shoal debrief record 1\n";

/// Where the record of the part at `part` goes: `part` + ".debrief.cbor".
std::string debrief_record_path(const std::string& part);

/// The grid a run used, as `check` was given it: loaded again by the merge.
struct GridSpec {
    std::vector<std::string> coast;  ///< the --coast inputs (a grid file, or coastline sources)
    grid::BuildRequest request;      ///< --cell, --crs, --layer, ... (what a build from sources takes)
};

/// The record of a shard's audit `result` as bytes (the mark, then CBOR); `part` is the size
/// and fingerprint of its part (file_size_and_fingerprint).
std::string debrief_record(const audit::AuditResult& result, const RunInfo& info, const GridSpec& grid,
                           const std::pair<long long, std::string>& part);

/// The record of the part staged in `part` (its bytes as written, fingerprinted from the
/// temporary), staged at debrief_record_path(part.target()). Throws UsageError when the part is
/// not staged in a file (standard output, a device): its record could not be matched to it.
/// An existing file there that is not a record (no mark) is not replaced: InputError.
StagedOutput stage_debrief_record(const StagedOutput& part, const audit::AuditResult& result, const RunInfo& info, const GridSpec& grid);

/// One record, read.
struct DebriefRecord {
    std::string path;  ///< the record's
    audit::Shard shard;
    std::pair<long long, std::string> part;  ///< the part's size and fingerprint, as written
    RunInfo info;      ///< the fields the pages print (see above)
    GridSpec grid;
    audit::AuditResult result;  ///< the shard's (see above); its counts not filled
};

/// A record's bytes (as debrief_record writes them), read: the mark, then the CBOR. `path`
/// names it in messages. Throws InputError when it is not a record or is damaged (it is not
/// checked against its part here: read_debrief_record does that).
DebriefRecord parse_debrief_record(std::string_view bytes, const std::string& path);

/// The record of the part at `part` (at debrief_record_path(part)), checked against the part:
/// its bytes must be those the record was written with. Throws UsageError when there is none
/// ("... has no debrief record: write it with check --shard I/N --debrief-record"), InputError
/// when it is not a record, is damaged, or is of another part.
DebriefRecord read_debrief_record(const std::string& part);

/// The records of the parts of a merge, in one run's order: `sets[k]` is record k's set of
/// inputs (merge.hpp), `first_of_set[k]` whether it is the first part of its set (its files
/// are the set's). Tracks go in the order (set, position). Throws InputError when records
/// disagree on what the pages print (the run header, the criteria).
audit::AuditResult join_debrief_records(std::vector<DebriefRecord> records, const std::vector<std::size_t>& sets,
                                        const std::vector<bool>& first_of_set);

/// The grid of the records' run: `coast` when given (else the --coast inputs as the shards were
/// given them) loaded with the shards' grid options, and checked against the run's grid
/// fingerprint. Throws InputError naming the inputs when it cannot be loaded or is another grid.
grid::CoastGrid load_recorded_grid(const DebriefRecord& record, const std::vector<std::string>& coast = {});

}  // namespace shoal::report
