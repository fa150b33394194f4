#pragma once
/// Every input file (tracks, ship files, pose files) is opened once and read front to back: a
/// plain file or stream with the system's calls, anything else through GDAL's virtual file
/// layer (util/gdal_input.hpp: VSIFOpenL / VSIFReadL). Internal.
///
/// - `-` and `/vsistdin/` are standard input; other `/vsi...` paths are given to GDAL as they are.
/// - Content that starts with the gzip magic bytes is read decompressed (`/vsigzip/`), and a zip
///   (magic `PK\3\4`) of one member is read as that member (`/vsizip/FILE/MEMBER`), whatever the
///   file's name; a zip of several members is refused here (expand_inputs lists its members).
/// - A stream (a pipe, a FIFO, standard input, a terminal, a device) is never opened twice: the
///   bytes looked at to recognise it are kept and read again from memory. A compressed stream is
///   read whole into memory first (its compressed bytes: gzip and zip need them).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <shoal/util/error.hpp>

namespace shoal::detail {

/// The longest line a line-based reader (CSV, NMEA) holds; longer lines are bad rows.
inline constexpr std::size_t max_line_bytes = std::size_t{1} << 20;
/// The most bytes looked at to recognise a track format, and the longest CSV header line.
inline constexpr std::size_t max_sniff_bytes = std::size_t{16} << 20;

/// The most compressed bytes read from a stream (a gzip or zip on a pipe or standard input is
/// read whole into memory first: gzip and zip readers need it); a longer one is refused.
inline constexpr std::size_t max_compressed_stream_bytes = std::size_t{1} << 30;

/// "1 MiB", "64 KiB", "1234 bytes".
std::string size_text(std::size_t bytes);

/// An input that could not be opened; `reason` says why ("no such file", "is a folder",
/// "Permission denied", ...), what() is "PATH: REASON".
struct InputOpenError : InputError {
    InputOpenError(const std::string& path, std::string why) : InputError(path + ": " + why), reason(std::move(why)) {}
    std::string reason;
};

/// True for `-` and the paths GDAL reads itself (`/vsi...`).
bool is_virtual_path(const std::string& path) noexcept;

/// Whether `s` ends with `suffix` (given in lower case), ASCII letters compared in any case.
bool lower_ends_with(const std::string& s, std::string_view suffix) noexcept;

/// The members of a zip file (its files, not its folders, in any sub-folder), each as the
/// `/vsizip/` path GDAL reads it by, sorted; empty when `path` is not a zip (by its magic bytes).
/// A member whose name holds a `..` component (GDAL does not list those) is said in `notes`,
/// and is a member when GDAL reads it.
std::vector<std::string> zip_members(const std::string& path, std::vector<std::string>* notes = nullptr);

/// The names in a zip file's central directory (ZIP64 too), as written; empty when it has none
/// that can be read. Reads at most 64 KiB of its end and 64 MiB of directory. `directory_read`,
/// when given, says whether the end record and the central directory were found and read (false:
/// not a zip, or a corrupt or truncated one).
std::vector<std::string> zip_entry_names(const std::string& path, bool* directory_read = nullptr);

/// An entry of a zip's central directory: its name as written, its method (0 stored, 8
/// deflated), its packed size and where its local header is (ZIP64's where they need it).
struct ZipEntry {
    std::string name;
    unsigned method = 0;
    std::uint64_t packed = 0, local_header = 0;
};
/// zip_entry_names' entries, whole.
std::vector<ZipEntry> zip_directory(const std::string& path, bool* directory_read = nullptr);

/// The first `n` bytes of `path` as they are (nothing unpacked), fewer when it is shorter, ""
/// when it cannot be opened: a plain file read with the system's calls, a `/vsi` path by GDAL.
std::string read_head(const std::string& path, std::size_t n);
/// Up to `n` bytes of `path` from byte `at` on, as they are (read_head's from 0).
std::string read_at(const std::string& path, std::uint64_t at, std::size_t n);

/// Whether `path` is a regular file (through GDAL for a `/vsi` path; `-` is none).
bool is_regular_input(const std::string& path);
/// Whether `path` exists (through GDAL for a `/vsi` path: a member of a zip, a gzip; `-` is a
/// file of that name, as a path), and whether it is a folder (a zip's folder too).
bool input_exists(const std::string& path);
bool is_folder_input(const std::string& path);

/// Hands the bytes of the regular file `path` (nothing unpacked) to `block`, a block of up to
/// `block_bytes` at a time, and returns true; false, handing nothing, when `path` is not a
/// regular file (a FIFO would wait for a writer, a device never end) or cannot be opened.
bool read_blocks(const std::string& path, std::size_t block_bytes, const std::function<void(const char*, std::size_t)>& block);

class InputFile {
public:
    /// Opens `path` (see above). Throws InputOpenError.
    explicit InputFile(const std::string& path);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    /// Appends up to `n` bytes to `out` and returns how many: fewer than `n` only at the end.
    /// Throws InputError "PATH: cannot read (...)".
    std::size_t append(std::string& out, std::size_t n);
    /// Appends the rest of the file; more than `limit` bytes in all (with what was read
    /// before, `already`) throws InputError "PATH: larger than LIMIT, the most WHAT may be".
    void append_all(std::string& out, std::size_t limit = static_cast<std::size_t>(-1), const char* what = "an input",
                    std::size_t already = 0);

    const std::string& path() const noexcept { return m_path; }
    /// Non-empty when a compressed stream (gzip, zip) broke off or was damaged part way: what
    /// was decompressed before is what the readers saw, as if the file ended there.
    const std::string& damage() const noexcept { return m_damage; }
    /// A path GDAL opens to read the same content again (for OGR drivers, which need a path),
    /// or "" for a stream, which cannot be read twice.
    const std::string& gdal_path() const noexcept { return m_gdal_path; }
    /// Standard input, a pipe, a FIFO (read once): the XXH3-64 of the content handed out so far
    /// (decompressed, as the readers saw it) and its size in bytes, which fingerprint what was
    /// read where no file can be read again; nullopt for a file.
    std::optional<std::pair<std::uint64_t, std::size_t>> stream_digest() const;

private:
    void open_content(const std::string& path);
    void open(const std::string& path);
    void close() noexcept;
    void close_handle() noexcept;  ///< the file or stream open now (not a compressed stream's memory)
    std::size_t read_raw(char* data, std::size_t n);

    std::string m_path;

    std::string m_damage;       ///< as given, for messages
    std::string m_gdal_path;  ///< what is open now, when it can be opened again
    int m_fd = -1;             ///< a plain file or stream (standard input: m_stdin), or
    bool m_stdin = false;      ///< m_fd is standard input, never closed here
    void* m_vsi = nullptr;     ///< what GDAL opened (gdal_input::open)
    std::string m_kept;       ///< bytes read to recognise the content, given back first
    std::size_t m_kept_pos = 0;
    std::string m_memory;     ///< a compressed stream, read whole
    std::string m_mem_name;   ///< its /vsimem/ name
    struct ContentHash;
    std::unique_ptr<ContentHash> m_hash;  ///< a stream's content handed out so far (stream_digest)
};

/// The whole content of `path`, at most `limit` bytes (see InputFile::append_all).
std::string read_input(const std::string& path, std::size_t limit = static_cast<std::size_t>(-1),
                       const char* what = "an input");

/// Content that is not a JSON object: its first byte that is not blank (nor a UTF-8 byte order
/// mark) is not '{'. `reason` says which byte it is; what() is "PATH: not JSON (REASON)".
struct NotJsonObject : InputError {
    NotJsonObject(const std::string& path, std::string why) : InputError(path + ": not JSON (" + why + ")"), reason(std::move(why)) {}
    std::string reason;
};

/// read_input for a JSON object (an exercise file, a shard's report): the first block (64 KiB)
/// is looked at first, and content that does not begin with '{' throws NotJsonObject there, so
/// a device (/dev/zero, /dev/urandom) or a binary file is refused at once instead of read on to
/// `limit`. InputOpenError when it cannot be opened; InputError at the limit.
std::string read_json_object_input(const std::string& path, std::size_t limit, const char* what);

/// read_json_object_input for a file of settings (an exercise file, an assessment file): its
/// failures thrown as InputError "LABEL 'PATH': cannot be read (...)" or "...: not JSON: ...".
std::string read_json_settings(const std::string& path, std::size_t limit, const char* what, const std::string& label);

/// A /vsimem/ file holding `bytes` while it lives, for GDAL drivers that need a path.
class MemoryFile {
public:
    explicit MemoryFile(std::string bytes, const std::string& extension);
    ~MemoryFile();
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;
    const std::string& path() const noexcept { return m_name; }

private:
    std::string m_bytes;
    std::string m_name;
};

}  // namespace shoal::detail
