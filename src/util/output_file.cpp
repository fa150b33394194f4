#include <shoal/util/output_file.hpp>

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <unordered_map>
#include <random>
#include <utility>

#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>

namespace shoal {

namespace fs = std::filesystem;

bool is_standard_output(const std::string& path) noexcept {
    return path.empty() || path == "-" || path == "/dev/stdout" || path == "/dev/fd/1" || path == "/proc/self/fd/1";
}

bool is_system_path(const std::string& path) noexcept { return path.rfind("/dev/", 0) == 0 || path.rfind("/proc/", 0) == 0; }

namespace {

constexpr std::string_view temp_mark = ".shoal.tmp-";

fs::path folder_of(const std::string& path) {
    const fs::path p(path);
    return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

/// Flushes the open file `f` (and fsyncs it when `sync`), then closes it; false (errno in
/// `err`) on failure.
bool flush_and_close(std::FILE* f, bool sync, int& err) {
    bool ok = std::fflush(f) == 0 && (!sync || ::fsync(::fileno(f)) == 0);
    err = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) {
        ok = false;
        err = errno;
    }
    return ok;
}

/// The real file behind a GDAL virtual path: `/vsigzip/d/t.csv.gz` is `d/t.csv.gz`,
/// `/vsizip/d/a.zip/m.csv` is `d/a.zip`; other paths as they are.
std::string behind_virtual(const std::string& path) {
    if (path.rfind("/vsi", 0) != 0) return path;
    const std::size_t slash = path.find('/', 1);
    if (slash == std::string::npos) return path;
    std::string rest = path.substr(slash + 1);
    if (!rest.empty() && rest.front() == '{') return path;  // /vsizip/{...}: no plain file to name
    std::string lower = rest;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (const std::size_t zip = lower.find(".zip/"); zip != std::string::npos) rest.resize(zip + 4);
    return rest;
}

/// The writer's pid in a temporary's name "PREFIX<pid>-...", or 0.
long pid_in(std::string_view name, std::string_view prefix) {
    if (name.substr(0, prefix.size()) != prefix) return 0;
    long pid = 0;
    std::size_t i = prefix.size();
    for (; i < name.size() && name[i] >= '0' && name[i] <= '9' && pid < 100'000'000; ++i) pid = pid * 10 + (name[i] - '0');
    return i < name.size() && name[i] == '-' ? pid : 0;
}

}  // namespace

std::string temporary_prefix(const std::string& target) {
    std::string name(1, '.');  // appended, not "." + string: GCC 12 -O3 warns falsely (-Wrestrict) on that
    name += fs::path(target).filename().string();
    name += temp_mark;
    return name;
}

void check_output_place(const std::string& path) {
    if (is_standard_output(path)) return;
    const fs::path dir = folder_of(path);
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError("cannot write '" + path + "': folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(path, ec)) throw InputError("cannot write '" + path + "': it is a directory");
}

namespace {

/// What same_file compares of a path, worked out once: its absolute, normal path (empty when
/// that failed), and its device and inode when it exists (stat follows links, as
/// fs::equivalent does). Standard output is its own kind.
struct FileKey {
    bool standard_output = false;
    std::string canonical;
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
};

FileKey file_key(const std::string& path) {
    FileKey k;
    if (is_standard_output(path)) {
        k.standard_output = true;
        return k;
    }
    const std::string real = behind_virtual(path);
    std::error_code ec;
    // fs::absolute without an error_code throws for "" (behind `/vsistdin/`, which names no file).
    const fs::path absolute = real.empty() ? fs::path() : fs::absolute(real, ec);
    const fs::path c = ec || absolute.empty() ? fs::path() : fs::weakly_canonical(absolute, ec);
    if (!ec && !c.empty()) k.canonical = c.string();
    struct stat st {};
    if (::stat(real.c_str(), &st) == 0) {
        k.exists = true;
        k.dev = st.st_dev;
        k.ino = st.st_ino;
    }
    return k;
}

/// Paths by their keys: which of those added first is the same file as a key (same_file's
/// rule), in constant time, so that checking n outputs against each other and m inputs costs
/// n + m keys (before: n^2 / 2 + n m calls of same_file, each stat and readlink of every
/// component of both paths: 1,000 debrief pages took half a minute).
class FileIndex {
public:
    void add(const FileKey& k, std::size_t i) {
        if (k.standard_output) m_stdout.emplace(i);
        if (!k.canonical.empty()) m_by_path.emplace(k.canonical, i);
        if (k.exists) m_by_inode.emplace(std::make_pair(k.dev, k.ino), i);
    }
    /// The first index added of the same file as `k`, if any.
    std::optional<std::size_t> find(const FileKey& k) const {
        std::optional<std::size_t> best;
        const auto take = [&](std::size_t i) {
            if (!best || i < *best) best = i;
        };
        if (k.standard_output) {
            if (m_stdout) take(*m_stdout);
            return best;
        }
        if (const auto it = m_by_path.find(k.canonical); !k.canonical.empty() && it != m_by_path.end()) take(it->second);
        if (const auto it = m_by_inode.find({k.dev, k.ino}); k.exists && it != m_by_inode.end()) take(it->second);
        return best;
    }

private:
    std::optional<std::size_t> m_stdout;
    std::unordered_map<std::string, std::size_t> m_by_path;
    std::map<std::pair<dev_t, ino_t>, std::size_t> m_by_inode;
};

}  // namespace

std::string file_head(const std::string& path, std::size_t n) {
    std::string head(n, '\0');
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "";
    head.resize(std::fread(head.data(), 1, n, f));
    std::fclose(f);
    return head;
}

void check_outputs(const std::vector<OutputSpec>& outputs, const std::vector<std::string>& inputs) {
    std::optional<FileIndex> input_index;  // built when an output exists (only then can it be an input)
    FileIndex output_index;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const OutputSpec& o = outputs[i];
        check_output_place(o.path);
        const FileKey key = file_key(o.path);
        if (!key.standard_output && key.exists) {
            if (!input_index) {
                input_index.emplace();
                for (std::size_t j = 0; j < inputs.size(); ++j)
                    if (!inputs[j].empty()) input_index->add(file_key(inputs[j]), j);
            }
            if (const auto j = input_index->find(key))
                throw UsageError("the output '" + o.path + "' is the input '" + inputs[*j] + "': writing it would destroy the input; choose another " +
                                 o.option);
        }
        if (o.ours && !key.standard_output && key.exists) {
            std::error_code ec;
            const auto st = fs::status(o.path, ec);
            if (fs::is_regular_file(st) && fs::file_size(o.path, ec) > 0 && !ec && !o.ours(o.path))
                throw UsageError("'" + o.path + "' exists and is not a file shoal wrote (" + o.role +
                                 "): shoal replaces only its own files; remove it first, or choose another " + o.option);
        }
        if (const auto j = output_index.find(key))
            throw UsageError(o.option + " '" + o.path + "' is " + outputs[*j].role + " " + outputs[*j].option + " '" + outputs[*j].path +
                             "': choose another file for " + o.role);
        output_index.add(key, i);
    }
}

std::size_t remove_stale_temporaries(const std::string& target) {
    if (is_standard_output(target)) return 0;
    const std::string prefix = temporary_prefix(target);
    const fs::path dir = folder_of(target);
    std::size_t removed = 0;
    DIR* d = ::opendir(dir.c_str());
    if (!d) return 0;
    std::vector<std::string> stale;
    while (const dirent* e = ::readdir(d)) {
        const long pid = pid_in(e->d_name, prefix);
        // kill(pid, 0): ESRCH means no such process; EPERM means it lives (another user's).
        if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) stale.emplace_back(e->d_name);
    }
    ::closedir(d);
    for (const std::string& name : stale) {
        std::error_code ec;
        if (fs::is_regular_file(fs::symlink_status(dir / name, ec)) && fs::remove(dir / name, ec)) ++removed;
    }
    return removed;
}

StagedOutput::StagedOutput(std::string target) : m_target(std::move(target)) {
    if (is_standard_output(m_target)) return;
    // /dev/stdout, /dev/fd/N, /proc/self/fd/N: written straight to what they stand for, never
    // replaced (renaming over /dev/stdout would replace the link itself).
    if (is_system_path(m_target)) return;
    check_output_place(m_target);
    std::error_code ec;
    if (const auto st = fs::status(m_target, ec); fs::exists(st) && !fs::is_regular_file(st)) return;  // a device, a pipe
    // A symlink is written through: its target is replaced, the link stays a link.
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(m_target, ec)); ++hops) {
        fs::path link = fs::read_symlink(m_target, ec);
        if (ec) break;
        if (link.is_relative()) link = folder_of(m_target) / link;
        m_target = link.lexically_normal().string();
    }
    remove_stale_temporaries(m_target);
    std::random_device rd;
    char suffix[40];
    std::snprintf(suffix, sizeof suffix, "%ld-%08x", static_cast<long>(::getpid()), rd());
    std::string name = temporary_prefix(m_target);
    name += suffix;
    name += fs::path(m_target).extension().string();
    m_temp = (folder_of(m_target) / name).string();
    m_listed = std::make_unique<TempFileInProgress>(m_temp);
}

StagedOutput::StagedOutput(StagedOutput&& o) noexcept
    : m_target(std::move(o.m_target)), m_temp(std::exchange(o.m_temp, {})), m_listed(std::move(o.m_listed)) {}

StagedOutput& StagedOutput::operator=(StagedOutput&& o) noexcept {
    if (this != &o) {
        discard();
        m_target = std::move(o.m_target);
        m_temp = std::exchange(o.m_temp, {});
        m_listed = std::move(o.m_listed);
    }
    return *this;
}

StagedOutput::~StagedOutput() { discard(); }

void StagedOutput::discard() noexcept {
    if (!m_temp.empty()) {
        ::unlink(m_temp.c_str());
        for (const char* companion : {"-journal", "-wal", "-shm"}) ::unlink((m_temp + companion).c_str());
    }
    m_temp.clear();
    m_listed.reset();
}

void StagedOutput::write(std::string_view bytes) {
    write_streamed([bytes](const Sink& sink) { sink(bytes); });
}

void StagedOutput::write_streamed(const std::function<void(const Sink&)>& produce) {
    if (is_standard_output(m_target)) {
        produce([](std::string_view bytes) {
            if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size())
                throw InputError(std::string("cannot write to stdout: ") + std::strerror(errno));
        });
        if (std::fflush(stdout) != 0) throw InputError(std::string("cannot write to stdout: ") + std::strerror(errno));
        return;
    }
    const std::string& path = direct() ? m_target : m_temp;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    int err = 0;
    if (!f) {
        err = errno;
        discard();
        throw InputError("cannot write '" + m_target + "': " + std::strerror(err));
    }
    // A staged file is fsynced before it is put in place (flush_and_close): its pages are
    // handed to the disk every few megabytes as it is written, so that the fsync at its end
    // waits for the last of them, not for all (hundreds of megabytes of layer files waited
    // 0.1-0.3 s on a day of AIS, while nothing else was left to do). A hint only: what it
    // cannot do, the fsync does.
    constexpr std::size_t hand_over = std::size_t{8} << 20;
    std::size_t written = 0, handed = 0;
    try {
        produce([&](std::string_view bytes) {
            if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
                throw InputError("cannot write '" + m_target + "': " + std::strerror(errno));
            written += bytes.size();
#if defined(__linux__)
            if (!direct() && written - handed >= hand_over) {
                if (std::fflush(f) != 0) throw InputError("cannot write '" + m_target + "': " + std::strerror(errno));
                ::sync_file_range(::fileno(f), static_cast<off_t>(handed), static_cast<off_t>(written - handed), SYNC_FILE_RANGE_WRITE);
                handed = written;
            }
#endif
        });
    } catch (...) {
        std::fclose(f);
        discard();
        throw;
    }
    if (!flush_and_close(f, !direct(), err)) {
        discard();
        throw InputError("cannot write '" + m_target + "': " + std::strerror(err));
    }
}

void StagedOutput::commit() {
    if (direct()) return;
    std::error_code ec;
    fs::rename(m_temp, m_target, ec);
    if (ec) {
        discard();
        throw InputError("cannot write '" + m_target + "': " + ec.message());
    }
    m_temp.clear();
    m_listed.reset();
}

void commit_all(std::vector<StagedOutput>& outputs) {
    sigset_t hold, old;
    sigemptyset(&hold);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&hold, sig);
    ::pthread_sigmask(SIG_BLOCK, &hold, &old);
    try {
        for (StagedOutput& o : outputs) o.commit();
    } catch (...) {
        ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
        throw;
    }
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
}

}  // namespace shoal
