// A regular file's bytes, mapped read-only (util/mapped_file.hpp).
#include "util/mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <shoal/util/error.hpp>

namespace shoal::detail {

MappedFile::MappedFile(const std::string& path, const std::function<std::string(Failure, const std::string&)>& message) {
    m_fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (m_fd < 0) throw InputError(message(Failure::open, std::strerror(errno)));
    const auto fail = [&](const std::string& reason) {
        ::close(m_fd);
        m_fd = -1;
        throw InputError(message(Failure::read, reason));
    };
    struct stat st{};
    if (::fstat(m_fd, &st) != 0) fail(std::strerror(errno));
    if (!S_ISREG(st.st_mode) || st.st_size < 0) fail("not a regular file");
    m_size = static_cast<std::size_t>(st.st_size);
    if (m_size == 0) return;
    void* p = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE, m_fd, 0);
    if (p == MAP_FAILED) {  // a file system that cannot map: read it
        m_copy.resize(m_size);
        std::size_t got = 0;
        while (got < m_size) {
            const ssize_t n = ::read(m_fd, m_copy.data() + got, m_size - got);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) fail(std::strerror(errno));
            if (n == 0) fail("it ends early");
            got += static_cast<std::size_t>(n);
        }
        m_data = m_copy.data();
        return;
    }
    ::madvise(p, m_size, MADV_SEQUENTIAL);
    m_map = p;
    m_data = static_cast<const char*>(p);
}

MappedFile::~MappedFile() {
    if (m_map) ::munmap(m_map, m_size);
    if (m_fd >= 0) ::close(m_fd);
}

}  // namespace shoal::detail
