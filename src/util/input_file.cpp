#include "util/input_file.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "util/gdal_input.hpp"
#include "util/json_message.hpp"

namespace shoal::detail {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t magic_bytes = 4;

bool starts_with(const std::string& s, std::string_view prefix) noexcept { return s.compare(0, prefix.size(), prefix) == 0; }

bool is_stdin(const std::string& path) noexcept { return path == "-" || starts_with(path, "/vsistdin"); }

bool is_gzip(const std::string& head) noexcept { return starts_with(head, "\x1f\x8b"); }

bool is_zip(const std::string& head) noexcept {
    return starts_with(head, std::string_view("PK\x03\x04", 4)) || starts_with(head, std::string_view("PK\x05\x06", 4));
}

/// What kind of thing `path` is; throws InputOpenError for none or a folder.
enum class Kind { file, stream };
Kind kind_of(const std::string& path) {
    if (is_stdin(path)) return Kind::stream;
    if (is_virtual_path(path)) {
        const gdal_input::Stat st = gdal_input::stat(path);
        if (!st.exists) throw InputOpenError(path, "no such file");
        if (st.folder) throw InputOpenError(path, "is a folder");
        return Kind::file;
    }
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status)) {
        if (ec && ec != std::errc::no_such_file_or_directory) throw InputOpenError(path, "cannot read (" + ec.message() + ")");
        throw InputOpenError(path, "no such file");
    }
    if (fs::is_directory(status)) throw InputOpenError(path, "is a folder");
    return fs::is_regular_file(status) ? Kind::file : Kind::stream;
}

/// A file to read at offsets: a plain file by the system's calls, a `/vsi` path by GDAL's.
class RandomAccess {
public:
    explicit RandomAccess(const std::string& path) {
        if (is_virtual_path(path)) {
            int err = 0;
            std::string message;
            m_vsi = gdal_input::open(path, err, message);
        } else {
            m_fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        }
    }
    ~RandomAccess() {
        if (m_fd >= 0) ::close(m_fd);
        gdal_input::close(m_vsi);
    }
    RandomAccess(const RandomAccess&) = delete;
    RandomAccess& operator=(const RandomAccess&) = delete;
    bool is_open() const noexcept { return m_fd >= 0 || m_vsi; }
    /// The size in bytes; false when it cannot be told.
    bool size(std::uint64_t& out) {
        if (m_vsi) {
            if (!gdal_input::seek(m_vsi, 0, true)) return false;
            out = gdal_input::tell(m_vsi);
            return true;
        }
        struct stat st {};
        if (::fstat(m_fd, &st) != 0) return false;
        out = static_cast<std::uint64_t>(st.st_size);
        return true;
    }
    /// Up to `n` bytes from `at` (fewer at the end, none when it cannot be read there).
    std::string read_at(std::uint64_t at, std::size_t n) {
        std::string b(n, '\0');
        std::size_t got = 0;
        if (m_vsi) {
            std::string failure;
            if (!gdal_input::seek(m_vsi, at, false)) return std::string();
            got = gdal_input::read(m_vsi, b.data(), n, failure);
        } else {
            while (got < n) {
                const ssize_t r = ::pread(m_fd, b.data() + got, n - got, static_cast<off_t>(at + got));
                if (r < 0 && errno == EINTR) continue;
                if (r <= 0) break;
                got += static_cast<std::size_t>(r);
            }
        }
        b.resize(got);
        return b;
    }

private:
    int m_fd = -1;
    void* m_vsi = nullptr;
};

}  // namespace

std::string size_text(std::size_t bytes) {
    if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
    if (bytes >= (std::size_t{1} << 10) && bytes % (std::size_t{1} << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
    return std::to_string(bytes) + " bytes";
}

bool is_virtual_path(const std::string& path) noexcept { return path == "-" || starts_with(path, "/vsi"); }

bool lower_ends_with(const std::string& s, std::string_view suffix) noexcept {
    if (s.size() < suffix.size()) return false;
    for (std::size_t i = 0; i < suffix.size(); ++i) {
        char c = s[s.size() - suffix.size() + i];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != suffix[i]) return false;
    }
    return true;
}

std::vector<std::string> zip_entry_names(const std::string& path, bool* directory_read) {
    std::vector<std::string> names;
    for (ZipEntry& e : zip_directory(path, directory_read)) names.push_back(std::move(e.name));
    return names;
}

std::vector<ZipEntry> zip_directory(const std::string& path, bool* directory_read) {
    std::vector<ZipEntry> names;
    if (directory_read) *directory_read = false;
    RandomAccess file(path);
    if (!file.is_open()) return names;
    const auto read_at = [&](std::uint64_t at, std::size_t n) { return file.read_at(at, n); };
    const auto u16 = [](const std::string& b, std::size_t at) -> std::uint64_t {
        return static_cast<unsigned char>(b[at]) | static_cast<std::uint64_t>(static_cast<unsigned char>(b[at + 1])) << 8;
    };
    const auto u32 = [&](const std::string& b, std::size_t at) { return u16(b, at) | u16(b, at + 2) << 16; };
    const auto u64 = [&](const std::string& b, std::size_t at) { return u32(b, at) | u32(b, at + 4) << 32; };
    std::uint64_t size = 0;
    if (!file.size(size)) return names;
    // The end of central directory record: in the last 22 bytes + a comment of at most 65,535.
    const std::size_t tail_n = static_cast<std::size_t>(std::min<std::uint64_t>(size, 22 + 65535));
    const std::string tail = read_at(size - tail_n, tail_n);
    if (tail.size() != tail_n || tail_n < 22) return names;
    std::size_t eocd = std::string::npos;
    for (std::size_t i = tail_n - 22 + 1; i-- > 0;)
        if (tail.compare(i, 4, std::string_view("PK\x05\x06", 4)) == 0) {
            eocd = i;
            break;
        }
    if (eocd == std::string::npos) return names;
    std::uint64_t count = u16(tail, eocd + 10), cd_size = u32(tail, eocd + 12), cd_at = u32(tail, eocd + 16);
    if ((count == 0xFFFF || cd_size == 0xFFFFFFFF || cd_at == 0xFFFFFFFF) && eocd >= 20 &&
        tail.compare(eocd - 20, 4, std::string_view("PK\x06\x07", 4)) == 0) {  // ZIP64
        const std::string rec = read_at(u64(tail, eocd - 20 + 8), 56);
        if (rec.size() != 56 || rec.compare(0, 4, std::string_view("PK\x06\x06", 4)) != 0) return names;
        count = u64(rec, 32);
        cd_size = u64(rec, 40);
        cd_at = u64(rec, 48);
    }
    // Bounded: the central directory read once, at most 64 MiB (some 500,000 names).
    if (cd_size > (std::uint64_t{64} << 20) || cd_at > size || cd_size > size - cd_at) return names;
    const std::string cd = read_at(cd_at, static_cast<std::size_t>(cd_size));
    if (cd.size() != cd_size) return names;
    if (directory_read) *directory_read = true;
    for (std::size_t at = 0, k = 0; k < count && at + 46 <= cd.size(); ++k) {
        if (cd.compare(at, 4, std::string_view("PK\x01\x02", 4)) != 0) break;
        const std::size_t n = u16(cd, at + 28), extra = u16(cd, at + 30), comment = u16(cd, at + 32);
        if (at + 46 + n > cd.size()) break;
        // The packed size and the local header's offset, from the ZIP64 field when they are
        // 0xFFFFFFFF (the unpacked size is read only to find where they stand in it).
        std::uint64_t packed = u32(cd, at + 20), unpacked = u32(cd, at + 24), local = u32(cd, at + 42);
        const std::size_t extra_at = at + 46 + n, extra_end = std::min(extra_at + extra, cd.size());
        for (std::size_t x = extra_at; x + 4 <= extra_end;) {
            const std::size_t id = u16(cd, x), len = u16(cd, x + 2);
            if (x + 4 + len > extra_end) break;
            if (id == 1) {
                std::size_t v = x + 4;
                for (std::uint64_t* field : {&unpacked, &packed, &local})
                    if (*field == 0xFFFFFFFF && v + 8 <= x + 4 + len) *field = u64(cd, v), v += 8;
            }
            x += 4 + len;
        }
        names.push_back({cd.substr(at + 46, n), static_cast<unsigned>(u16(cd, at + 10)), packed, local});
        at += 46 + n + extra + comment;
    }
    return names;
}

std::string read_head(const std::string& path, std::size_t n) { return read_at(path, 0, n); }

std::string read_at(const std::string& path, std::uint64_t at, std::size_t n) {
    RandomAccess file(path);
    return file.is_open() ? file.read_at(at, n) : std::string();
}

bool is_regular_input(const std::string& path) {
    if (is_virtual_path(path)) return path != "-" && gdal_input::stat(path).regular;
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

bool input_exists(const std::string& path) {
    if (path != "-" && is_virtual_path(path)) return gdal_input::stat(path).exists;
    std::error_code ec;
    return fs::exists(path, ec);
}

bool is_folder_input(const std::string& path) {
    if (path != "-" && is_virtual_path(path)) return gdal_input::stat(path).folder;
    std::error_code ec;
    return fs::is_directory(path, ec);
}

bool read_blocks(const std::string& path, std::size_t block_bytes, const std::function<void(const char*, std::size_t)>& block) {
    if (!is_regular_input(path)) return false;
    RandomAccess file(path);
    if (!file.is_open()) return false;
    for (std::uint64_t at = 0;;) {
        const std::string b = file.read_at(at, block_bytes);
        if (b.empty()) return true;
        block(b.data(), b.size());
        at += b.size();
    }
}

bool has_parent_component(std::string_view name) noexcept {
    for (std::size_t at = 0; at <= name.size();) {
        const std::size_t end = std::min(name.find_first_of("/\\", at), name.size());
        if (name.substr(at, end - at) == "..") return true;
        at = end + 1;
    }
    return false;
}

std::vector<std::string> zip_members(const std::string& path, std::vector<std::string>* notes) {
    std::vector<std::string> out;
    if (is_stdin(path)) return out;
    if (!is_virtual_path(path)) {
        std::error_code ec;
        if (!fs::is_regular_file(path, ec)) return out;  // never open a pipe to look at it
    }
    // Its first bytes read as they are (a plain file without GDAL): GDAL lists only a zip.
    if (!is_zip(read_head(path, magic_bytes))) return out;
    // GDAL finds the archive in a /vsizip/ path by its .zip extension; braces name any other,
    // and a zip inside a zip (whose path already holds a ".zip/", where GDAL would cut it).
    const bool bare = lower_ends_with(path, ".zip") && !starts_with(path, "/vsizip/");
    const std::string root = bare ? "/vsizip/" + path : "/vsizip/{" + path + "}";
    out = gdal_input::zip_files(root);
    // GDAL leaves out of its listing every member whose name holds a '..' component (unzip would
    // put it outside the folder): said, and read when GDAL reads it (only read, never extracted).
    std::size_t climbing = 0;
    for (const std::string& name : zip_entry_names(path)) {
        if (name.empty() || name.back() == '/' || !has_parent_component(name)) continue;
        const std::string member = root + "/" + name;
        const bool readable = gdal_input::stat(member).regular;
        if (readable && std::find(out.begin(), out.end(), member) == out.end()) out.push_back(member);
        if (notes && climbing++ < 10)  // the first ten, then a count (a hostile zip may hold 500,000)
            notes->push_back(path + ": member '" + shortened(name, 240) + "' has '..' in its path (extracted, it would land outside the zip's folder): " +
                             (readable ? "read in place, never extracted" : "GDAL cannot read it; skipped"));
    }
    if (notes && climbing > 10) notes->push_back(path + ": " + std::to_string(climbing - 10) + " more members with '..' in their paths");
    std::sort(out.begin(), out.end());
    return out;
}

struct InputFile::ContentHash {
    XXH3_state_t state{};
    std::size_t bytes = 0;
    ContentHash() { XXH3_64bits_reset(&state); }
};

std::optional<std::pair<std::uint64_t, std::size_t>> InputFile::stream_digest() const {
    if (!m_hash) return std::nullopt;
    return std::pair{XXH3_64bits_digest(&m_hash->state), m_hash->bytes};
}

InputFile::InputFile(const std::string& path) : m_path(path) {
    try {
        open_content(path);
    } catch (...) {
        close();
        throw;
    }
}

void InputFile::close_handle() noexcept {
    if (m_fd >= 0 && !m_stdin) ::close(m_fd);  // standard input stays open
    m_fd = -1;
    m_stdin = false;
    gdal_input::close(m_vsi);
    m_vsi = nullptr;
}

void InputFile::close() noexcept {
    close_handle();
    if (!m_mem_name.empty()) gdal_input::unlink(m_mem_name);
    m_mem_name.clear();
}

void InputFile::open_content(const std::string& path) {
    const bool stream = kind_of(path) == Kind::stream;
    if (stream) m_hash = std::make_unique<ContentHash>();
    open(is_stdin(path) ? std::string("-") : path);  // `-`, /vsistdin, /vsistdin/NAME: standard input
    if (stream) m_gdal_path.clear();
    // Compressed content, recognised by its magic bytes: a zip in a zip or a gzip in a zip is
    // unpacked too, up to three layers deep.
    for (int depth = 0; depth < 3; ++depth) {
        m_kept.clear();
        m_kept_pos = 0;
        while (m_kept.size() < magic_bytes) {
            char c[magic_bytes];
            const std::size_t got = read_raw(c, magic_bytes - m_kept.size());
            if (got == 0) break;
            m_kept.append(c, got);
        }
        if (!is_gzip(m_kept) && !is_zip(m_kept)) break;
        std::string base = m_gdal_path;
        if (base.empty()) {  // a stream: gzip and zip readers need it in memory
            m_memory = m_kept;
            m_kept.clear();
            append_all(m_memory, max_compressed_stream_bytes, "a compressed stream (gzip or zip on a pipe)", m_memory.size());
            m_hash = std::make_unique<ContentHash>();  // the content is what is decompressed from it, not these bytes
            m_mem_name = gdal_input::memory_file(m_memory.data(), m_memory.size(), is_zip(m_memory) ? ".zip" : ".gz");
            base = m_mem_name;
        }
        const bool zip = is_zip(m_kept.empty() ? m_memory : m_kept);
        close_handle();
        if (!zip) {
            open("/vsigzip/" + base);
            continue;
        }
        const std::vector<std::string> members = zip_members(base);
        if (members.empty()) {
            // An empty zip, or one whose directory (at its end) is missing or broken: a truncated
            // download, a zip still being written, a file that only starts like a zip.
            bool directory_read = false;
            const std::size_t entries = zip_entry_names(base, &directory_read).size();
            if (!directory_read)
                throw InputOpenError(path, "not a readable zip file: it starts like a zip but its directory (at the end of the file) is "
                                           "missing or corrupt (truncated? still being written?)");
            throw InputOpenError(path, entries == 0 ? std::string("an empty zip file (no file in it)")
                                                    : "a zip file with no file GDAL can read in it (" + std::to_string(entries) +
                                                          " entries: folders, or files it cannot unpack)");
        }
        if (members.size() > 1 && starts_with(base, "/vsimem/"))
            throw InputOpenError(path, "a zip of " + std::to_string(members.size()) +
                                           " files on a pipe or standard input: shoal reads one file from a stream; save the zip "
                                           "to a file and give that (its files are read as a folder), or pipe one file of it "
                                           "(unzip -p ZIP " + members.front().substr(members.front().rfind('/') + 1) + ")");
        if (members.size() > 1) {
            const std::string shown = starts_with(base, "/vsimem/") ? std::string("/vsizip/FILE/") : "/vsizip/" + path + "/";
            throw InputOpenError(path, "a zip of " + std::to_string(members.size()) + " files: name one (" + shown +
                                           members.front().substr(members.front().rfind('/') + 1) +
                                           "), or give the zip as an input folder");
        }
        open(members.front());
    }
}

InputFile::~InputFile() { close(); }

void InputFile::open(const std::string& path) {
    if (path == "-") {  // standard input, read as it comes
        m_fd = STDIN_FILENO;
        m_stdin = true;
        m_gdal_path = "/vsistdin/";
        return;
    }
    int err = 0;
    std::string gdal;
    if (is_virtual_path(path)) {
        m_vsi = gdal_input::open(path, err, gdal);
    } else {  // a plain file or stream: the system's calls
        do m_fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        while (m_fd < 0 && errno == EINTR);
        err = m_fd < 0 ? errno : 0;
    }
    if (m_fd < 0 && !m_vsi) throw InputOpenError(m_path, err ? std::string(std::strerror(err)) : gdal.empty() ? "cannot open" : gdal);
    m_gdal_path = path;
}

std::size_t InputFile::read_raw(char* data, std::size_t n) {
    std::size_t total = 0;
    if (m_fd >= 0) {
        while (total < n) {
            const ssize_t got = ::read(m_fd, data + total, n - total);
            if (got < 0 && errno == EINTR) continue;
            if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {  // a non-blocking pipe handed down: wait for it
                pollfd p{m_fd, POLLIN, 0};
                ::poll(&p, 1, -1);
                continue;
            }
            if (got < 0) throw InputError(m_path + ": cannot read (" + std::strerror(errno) + ")");
            if (got == 0) break;
            total += static_cast<std::size_t>(got);
        }
        return total;
    }
    std::string failure;
    total = gdal_input::read(m_vsi, data, n, failure);
    if (total < n && !failure.empty()) {
        const std::string why = failure;
        // A compressed stream cut short or damaged part way: keep what came before it (a bad
        // row costs that row, not the file), and say so.
        if (m_gdal_path.rfind("/vsigzip/", 0) == 0 || m_gdal_path.rfind("/vsizip/", 0) == 0) {
            std::string said = why;  // GDAL prefixes its source location: "In file X, at line N, ..."
            if (said.rfind("In file ", 0) == 0)
                if (const std::size_t at = said.find(", at line "); at != std::string::npos)
                    if (const std::size_t comma = said.find(", ", at + 10); comma != std::string::npos) said = said.substr(comma + 2);
            if (m_damage.empty()) m_damage = "the compressed data break off or are damaged (" + said + ")";
            return total;
        }
        throw InputError(m_path + ": cannot read (" + why + ")");
    }
    return total;
}

std::size_t InputFile::append(std::string& out, std::size_t n) {
    const std::size_t old = out.size();
    const std::size_t from_kept = std::min(n, m_kept.size() - m_kept_pos);
    out.append(m_kept, m_kept_pos, from_kept);
    m_kept_pos += from_kept;
    std::size_t got = 0;
    if (from_kept < n) {
        out.resize(old + n);
        got = read_raw(out.data() + old + from_kept, n - from_kept);
        out.resize(old + from_kept + got);
    }
    if (m_hash) {  // what the readers are handed, once each byte
        XXH3_64bits_update(&m_hash->state, out.data() + old, from_kept + got);
        m_hash->bytes += from_kept + got;
    }
    return from_kept + got;
}

void InputFile::append_all(std::string& out, std::size_t limit, const char* what, std::size_t already) {
    constexpr std::size_t block = std::size_t{1} << 20;
    std::size_t total = already;
    for (;;) {
        // Never more than one byte past the limit: enough to know it is passed.
        const std::size_t want = limit == static_cast<std::size_t>(-1) ? block : std::min(block, limit - std::min(limit, total) + 1);
        const std::size_t got = append(out, want);
        total += got;
        if (total > limit)
            throw InputError(m_path + ": larger than " + size_text(limit) + ", the most " + what + " may be; not read further");
        if (got < want) return;
    }
}

std::string read_input(const std::string& path, std::size_t limit, const char* what) {
    InputFile in(path);
    std::string out;
    // A regular file's room taken at once (with the last block read into it): not grown by
    // doubling, each step copying what was read (a partition file of 50 MB read by every task).
    std::error_code ec;
    if (!is_virtual_path(path))
        if (const auto size = std::filesystem::file_size(path, ec); !ec && size < limit) out.reserve(static_cast<std::size_t>(size) + (std::size_t{1} << 20) + 1);
    in.append_all(out, limit, what);
    return out;
}

std::string read_json_object_input(const std::string& path, std::size_t limit, const char* what) {
    constexpr std::size_t head = std::size_t{64} << 10;
    InputFile in(path);
    std::string out;
    std::size_t first = std::string::npos;
    std::size_t got = head;
    while (first == std::string::npos && got == head) {  // blanks only so far: look further
        got = in.append(out, std::min(head, limit - std::min(limit, out.size()) + 1));
        if (out.size() > limit)
            throw InputError(path + ": larger than " + size_text(limit) + ", the most " + what + " may be; not read further");
        first = out.find_first_not_of(" \t\r\n", starts_with(out, "\xEF\xBB\xBF") ? 3 : 0);
    }
    if (first == std::string::npos) return out;  // blanks only: the JSON parser says "empty"
    if (out[first] != '{') {
        char byte[48];
        const auto c = static_cast<unsigned char>(out[first]);
        if (c >= 0x21 && c < 0x7f) std::snprintf(byte, sizeof byte, "it begins with '%c', not '{'", c);
        else std::snprintf(byte, sizeof byte, "it begins with the byte 0x%02X, not '{'", c);
        throw NotJsonObject(path, byte);
    }
    if (got == head) in.append_all(out, limit, what, out.size());
    return out;
}

std::string read_json_settings(const std::string& path, std::size_t limit, const char* what, const std::string& label) {
    try {
        return read_json_object_input(path, limit, what);
    } catch (const InputOpenError& e) {
        throw InputError(label + " '" + path + "': cannot be read (" + e.reason + ")");
    } catch (const NotJsonObject& e) {
        throw InputError(label + " '" + path + "': not JSON: " + e.reason);
    }
}

}  // namespace shoal::detail
