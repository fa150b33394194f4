#pragma once
/// What reading an input needs of GDAL's virtual file layer (VSI), and only that: `/vsi...`
/// paths, gzip and zip content, a compressed stream held in memory, a zip's listing. Internal.
///
/// Defined with GDAL in util/gdal_input.cpp, a file of their own so that a program without GDAL
/// could define them otherwise (docs/performance.md, "What a check without GDAL needs"). Plain
/// files and streams are read with the system's calls, in util/input_file.cpp.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shoal::detail::gdal_input {

/// What GDAL says of a `/vsi` path: whether it exists, and is a folder or a regular file.
struct Stat {
    bool exists = false;
    bool folder = false;
    bool regular = false;
};
Stat stat(const std::string& path);

/// GDAL's VSIFOpenL of `path` for reading, its messages kept quiet: a handle, or null with
/// `err` (errno) and `message` (GDAL's last message) saying why.
void* open(const std::string& path, int& err, std::string& message);
/// Up to `n` bytes into `data`: fewer only at the end, or when reading failed (`failure` GDAL's
/// message then, "" otherwise).
std::size_t read(void* handle, char* data, std::size_t n, std::string& failure);
/// Seeks to `offset` from the start, or to the end (`to_end`); false when it cannot.
bool seek(void* handle, std::uint64_t offset, bool to_end);
std::uint64_t tell(void* handle);
void close(void* handle) noexcept;

/// A `/vsimem/` file over `data` (not copied: it must stay while the name is used), named
/// with `extension`; `unlink` removes it.
std::string memory_file(char* data, std::size_t n, const std::string& extension);
void unlink(const std::string& name) noexcept;

/// The regular files under the `/vsizip/` folder `root`, as GDAL lists them
/// (VSIReadDirRecursive), each as `root/NAME`, in GDAL's order.
std::vector<std::string> zip_files(const std::string& root);

}  // namespace shoal::detail::gdal_input
