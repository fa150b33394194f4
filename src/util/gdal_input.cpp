// Reading inputs through GDAL's virtual file layer (util/gdal_input.hpp): the one part of
// reading an input that needs GDAL.
#include "util/gdal_input.hpp"

#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>

#include <atomic>
#include <cerrno>
#include <cstdio>

#include "util/gdal_support.hpp"
#include "util/input_file.hpp"

namespace shoal::detail {

namespace gdal_input {

Stat stat(const std::string& path) {
    register_drivers();
    QuietErrors quiet;
    VSIStatBufL st;
    Stat out;
    if (VSIStatL(path.c_str(), &st) != 0) return out;
    out.exists = true;
    out.folder = VSI_ISDIR(st.st_mode);
    out.regular = VSI_ISREG(st.st_mode);
    return out;
}

void* open(const std::string& path, int& err, std::string& message) {
    register_drivers();
    QuietErrors quiet;
    errno = 0;
    VSILFILE* fp = VSIFOpenL(path.c_str(), "rb");
    err = fp ? 0 : errno;
    message = fp ? std::string() : QuietErrors::last();
    return fp;
}

std::size_t read(void* handle, char* data, std::size_t n, std::string& failure) {
    QuietErrors quiet;
    auto* fp = static_cast<VSILFILE*>(handle);
    std::size_t total = 0;
    while (total < n) {
        const std::size_t got = VSIFReadL(data + total, 1, n - total, fp);
        total += got;
        if (got == 0) break;
    }
    failure = total < n && CPLGetLastErrorType() >= CE_Failure ? QuietErrors::last("read error") : std::string();
    return total;
}

bool seek(void* handle, std::uint64_t offset, bool to_end) {
    return VSIFSeekL(static_cast<VSILFILE*>(handle), to_end ? 0 : static_cast<vsi_l_offset>(offset), to_end ? SEEK_END : SEEK_SET) == 0;
}

std::uint64_t tell(void* handle) { return static_cast<std::uint64_t>(VSIFTellL(static_cast<VSILFILE*>(handle))); }

void close(void* handle) noexcept {
    if (handle) VSIFCloseL(static_cast<VSILFILE*>(handle));
}

std::string memory_file(char* data, std::size_t n, const std::string& extension) {
    register_drivers();
    static std::atomic<unsigned long> counter{0};
    std::string name = "/vsimem/shoal-input-" + std::to_string(counter.fetch_add(1)) + extension;
    VSIFCloseL(VSIFileFromMemBuffer(name.c_str(), reinterpret_cast<GByte*>(data), static_cast<vsi_l_offset>(n), FALSE));
    return name;
}

void unlink(const std::string& name) noexcept { VSIUnlink(name.c_str()); }

std::vector<std::string> zip_files(const std::string& root) {
    register_drivers();
    QuietErrors quiet;
    std::vector<std::string> out;
    char** names = VSIReadDirRecursive(root.c_str());
    for (char** n = names; n && *n; ++n) {
        const std::string member = root + "/" + *n;
        VSIStatBufL st;
        if (VSIStatL(member.c_str(), &st) == 0 && VSI_ISREG(st.st_mode)) out.push_back(member);
    }
    CSLDestroy(names);
    return out;
}

}  // namespace gdal_input

MemoryFile::MemoryFile(std::string bytes, const std::string& extension)
    : m_bytes(std::move(bytes)), m_name(gdal_input::memory_file(m_bytes.data(), m_bytes.size(), extension)) {}

MemoryFile::~MemoryFile() { gdal_input::unlink(m_name); }

}  // namespace shoal::detail
