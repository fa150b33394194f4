#pragma once
/// Writing a whole file so that a reader sees the old file or the new one, never half:
/// write a temporary file in the same folder, flush it to disk, rename it over the target
/// (a StagedOutput, <shoal/util/output_file.hpp>, which also removes stale temporaries).

#include <string>
#include <string_view>

namespace shoal {

/// Writes `bytes` to `path` atomically; an empty path or "-" writes to stdout. A path that
/// exists and is neither a regular file nor a folder (a device such as /dev/null or /dev/full,
/// a pipe) is written to directly: no temporary beside it, no rename over it. Throws
/// InputError naming the path (folder missing, disk full, ...), leaving no temporary behind.
/// The same as `StagedOutput out(path); out.write(bytes); out.commit();`.
void write_file_atomically(const std::string& path, std::string_view bytes);

/// A temporary file being written now, listed for the length of this object's life so that
/// `remove_temp_files_in_progress` (a signal handler) can delete it if the process is
/// interrupted. Register before creating the file; at most 16 at once (more are not listed).
class TempFileInProgress {
public:
    explicit TempFileInProgress(const std::string& path) noexcept;
    ~TempFileInProgress();
    TempFileInProgress(const TempFileInProgress&) = delete;
    TempFileInProgress& operator=(const TempFileInProgress&) = delete;

private:
    int m_slot = -1;
};

/// Deletes every temporary file listed now, with SQLite's `-journal`, `-wal` and `-shm`
/// companions. Async-signal-safe: meant for a SIGINT/SIGTERM handler that then exits.
void remove_temp_files_in_progress() noexcept;

}  // namespace shoal
