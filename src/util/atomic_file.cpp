#include <shoal/util/atomic_file.hpp>

#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include <shoal/util/error.hpp>

namespace shoal {

namespace fs = std::filesystem;

namespace {

/// The list of temporary files in progress: fixed slots, so a signal handler can read it
/// without allocating or locking. state: 0 free, 1 being filled, 2 listed.
constexpr std::size_t max_path = 4096;
struct Slot {
    std::atomic<int> state{0};
    std::array<char, max_path> path{};
};
static_assert(std::atomic<int>::is_always_lock_free);
std::array<Slot, 16> g_in_progress;

void unlink_with_suffix(const char* path, const char* suffix) noexcept {
    std::array<char, max_path + 16> buf;
    const std::size_t n = std::strlen(path), k = std::strlen(suffix);
    if (n + k + 1 > buf.size()) return;
    std::memcpy(buf.data(), path, n);
    std::memcpy(buf.data() + n, suffix, k + 1);
    ::unlink(buf.data());
}

/// Writes straight to a device or pipe: there is no folder to hold a temporary beside it.
void write_directly(const std::string& path, std::string_view bytes) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw InputError("cannot write '" + path + "': " + std::strerror(errno));
    bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() && std::fflush(f) == 0;
    int err = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) {
        ok = false;
        err = errno;
    }
    if (!ok) throw InputError("cannot write '" + path + "': " + std::strerror(err));
}

}  // namespace

TempFileInProgress::TempFileInProgress(const std::string& path) noexcept {
    if (path.size() + 1 > max_path) return;
    for (std::size_t i = 0; i < g_in_progress.size(); ++i) {
        int free = 0;
        if (!g_in_progress[i].state.compare_exchange_strong(free, 1)) continue;
        std::memcpy(g_in_progress[i].path.data(), path.c_str(), path.size() + 1);
        g_in_progress[i].state.store(2);
        m_slot = static_cast<int>(i);
        return;
    }
}

TempFileInProgress::~TempFileInProgress() {
    if (m_slot >= 0) g_in_progress[static_cast<std::size_t>(m_slot)].state.store(0);
}

void remove_temp_files_in_progress() noexcept {
    for (Slot& s : g_in_progress) {
        if (s.state.load() != 2) continue;
        ::unlink(s.path.data());
        for (const char* suffix : {"-journal", "-wal", "-shm"}) unlink_with_suffix(s.path.data(), suffix);
    }
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
    if (path.empty() || path == "-") {
        if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
            throw InputError(std::string("cannot write to stdout: ") + std::strerror(errno));
        return;
    }
    const fs::path target(path);
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + path + "': folder '" + dir.string() + "' does not exist");
    const auto status = fs::status(target, ec);
    if (fs::is_directory(status)) throw InputError("cannot write '" + path + "': it is a directory");
    if (fs::exists(status) && !fs::is_regular_file(status)) {
        write_directly(path, bytes);
        return;
    }
    std::random_device rd;
    char suffix[40];
    std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%08x", static_cast<long>(::getpid()), rd());
    std::string name(1, '.');  // appended, not "." + string: GCC 12 -O3 warns falsely (-Wrestrict) on that
    name += target.filename().string();
    name += suffix;
    const fs::path tmp = dir / name;
    const TempFileInProgress listed(tmp.string());
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError("cannot write '" + path + "': " + std::strerror(errno));
    bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() && std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
    int err = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) {
        ok = false;
        err = errno;
    }
    if (!ok) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + path + "': " + std::strerror(err));
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + path + "': " + ec.message());
    }
}

}  // namespace shoal
