#pragma once
/// A regular file's bytes, mapped read-only (not copied: the kernel's page cache is read in
/// place); read into memory instead on a file system that cannot map. For the files shoal reads
/// whole and in place: grid files, partition files.

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace shoal::detail {

class MappedFile {
public:
    enum class Failure { open, read };
    /// Throws InputError(message(failure, reason)) when the file cannot be opened (`reason`:
    /// the system's words) or read (`reason`: the system's words, or "not a regular file").
    MappedFile(const std::string& path, const std::function<std::string(Failure, const std::string& reason)>& message);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    std::span<const char> bytes() const noexcept { return {m_data, m_size}; }

private:
    int m_fd = -1;
    void* m_map = nullptr;
    const char* m_data = nullptr;
    std::size_t m_size = 0;
    std::vector<char> m_copy;
};

}  // namespace shoal::detail
