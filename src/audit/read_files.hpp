#pragma once
/// Reading a run's track files on several threads: one place for the batch (audit.cpp) and for
/// the partitions (partition.cpp).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/track/reader.hpp>

namespace shoal::audit {

/// Reads `files` on `jobs` threads into `read[k]` (packed tracks) and `results[k]` (the file's
/// name, format, read report, track count, or its error): a file that cannot be read costs
/// that file (InputError, out of memory), the others are read. The jobs the files leave free
/// each read a big file with a second thread (ReadOptions::threads), the first files first.
/// `after(k)`, when given, runs on the worker once file k is read (or failed). Any other
/// exception (a bug, a library failure) is thrown again on the calling thread once every
/// worker has finished.
void read_track_files(const std::vector<std::string>& files, const track::ReadOptions& options, unsigned jobs,
                      std::vector<track::PackedTrackFile>& read, std::vector<FileResult>& results,
                      const std::function<void(std::size_t)>& after = {});

}  // namespace shoal::audit
