#pragma once
/// A run's fixes shuffled by vessel into partitions on disk, so that a cluster reads each track
/// file once (one task per input) and audits each vessel whole (one task per partition), and
/// `merge` puts the parts back together as the report one run writes (docs/scale-out.md).
///
///   1. write_partitions, one task per input (a file, a folder, a zip as given): the input's
///      files read with shoal's own readers (every format, zip, gzip, AIS log), their tracks
///      hashed by vessel id (audit::shard_of of the id, as `--shard` hashes it) into `count`
///      partition files; beside them an index: each file's name, size and fingerprint, what
///      reading it found (its bad rows, by file and line: the report's problems), and every
///      track's id in file order (the run's track positions).
///   2. read_partition, one task per partition: partition I of every input, the vessels met in
///      several files merged into one track as one run merges them, each at its position among
///      the run's tracks, and every file's FileResult: what a `--shard I/N` run would have read.
///   3. In the real world the evidence of the run's traffic is every vessel's: traffic_of_partition
///      (one task per partition) gives each track's stays and fixes over land, written with
///      write_traffic; the audit of a partition reads them all (read_traffic, small).
///
/// The files are machine-local (raw packed fixes, this build's layout, checked by a version
/// header): written and read by the same shoal on the cluster, never kept or exchanged.

#include <cstddef>
#include <functional>
#include <utility>
#include <cstdint>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>

namespace shoal::audit {

/// Writes folder `dir` (created, atomically: a temporary folder renamed; refused when it exists)
/// holding index.bin and part-00000.bin .. part-(count-1).bin for the track files of `input`
/// (track::expand_inputs of it; vessels tables in a folder or zip are not tracks and are left
/// to `--vessels`, as the audit finds them itself). A file that cannot be read is kept in the
/// index with its error, as one run lists it. `fingerprint(file)` gives a file's size and
/// fingerprint as read, for the run header (report::read_file_fingerprint). Throws InputError when
/// `dir` exists or cannot be written, UsageError for count 0.
struct PartitionSummary {
    std::size_t files = 0, tracks = 0, fixes = 0, bytes_read = 0;  ///< bytes_read: the files' sizes
};
PartitionSummary write_partitions(const std::string& dir, const std::string& input, const track::ReadOptions& options, unsigned count,
                                  unsigned jobs, const std::function<std::pair<long long, std::string>(const FileResult&)>& fingerprint);

/// Partition `shard.index` of the folders `dirs` (one per input of the run, in its order, each
/// written by write_partitions with `shard.count` partitions for input `inputs[k]`): its tracks
/// as one run reads them (one vessel of several files one track), every file's FileResult, and
/// in `positions` each track's position among all the run's tracks; `all_ids` every track id of
/// the run. Throws InputError when a folder is missing, of another input, another count or
/// another shoal, or was read with other `options` than the run's (its files were read when
/// the partitions were written: the message names the first option that differs).
ReadResult read_partition(const std::vector<std::string>& dirs, const std::vector<std::string>& inputs, const track::ReadOptions& options,
                          Shard shard, std::vector<std::size_t>& positions, std::vector<std::string>* all_ids = nullptr);

/// Real world: the traffic of each track of `read` (its stays, its fixes under way over land),
/// prepared as the audit prepares a track (outliers dropped, motion resolved); a track whose
/// input is bad is left out (the audit of its partition reports it).
std::vector<TrackResult> traffic_of_partition(ReadResult& read, const grid::CoastGrid& grid, const hull::Hull& default_hull,
                                              const AuditOptions& options);

/// What a partition's traffic was made of, and so what the audit that reads it must be made
/// of too: the partitions (every folder's index: its inputs' names, sizes, fingerprints, read
/// options and track ids), the grid (its fingerprint) and the default hull (its label), as 16
/// hex digits of XXH3. Throws InputError when an index cannot be read.
std::string traffic_key(const std::vector<std::string>& dirs, std::uint64_t grid_fingerprint, const std::string& hull_label);

/// Writes (atomically; only over a traffic file shoal wrote) and reads the traffic of
/// partitions: ids, stays and fixes over land, under `key` (traffic_key).
void write_traffic(const std::string& path, const std::vector<TrackResult>& traffic, Shard shard, const std::string& key);
/// Every file of `paths` (the traffic of partitions 0..N-1 of `shard.count`, in order): the
/// traffic of every partition's tracks but `shard.index`'s own (its sweep gathers those), in
/// partition order. Throws InputError naming a missing, foreign or incomplete file, or one
/// made under another `key` (other partitions, grid or hull).
std::vector<TrackResult> read_traffic(const std::vector<std::string>& paths, Shard shard, const std::string& key);

/// audit_tracks of partition `read` (positions from read_partition), the run's other vessels'
/// traffic taken from `traffic` (read_traffic of every partition; this one's own are skipped by
/// position) instead of being computed: the part `check --shard I/N` writes, from the partitions.
AuditResult audit_partition(ReadResult read, std::vector<std::size_t> positions, std::vector<TrackResult> traffic,
                            const grid::CoastGrid& grid, const hull::Hull& default_hull, const std::string& hull_label,
                            const AuditOptions& options);

}  // namespace shoal::audit
