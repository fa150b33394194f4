#include <shoal/util/atomic_file.hpp>

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>

#include <shoal/util/output_file.hpp>

namespace shoal {

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
    StagedOutput out(path);
    out.write(bytes);
    out.commit();
}

}  // namespace shoal
