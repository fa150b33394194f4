#pragma once
/// Writing a whole file so that a reader sees the old file or the new one, never half:
/// write a temporary file in the same folder, flush it to disk, rename it over the target.

#include <string>
#include <string_view>

namespace shoal {

/// Writes `bytes` to `path` atomically; an empty path or "-" writes to stdout. Throws
/// InputError naming the path (folder missing, disk full, ...), leaving no temporary behind.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace shoal
