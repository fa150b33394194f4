#include <shoal/track/reader.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <span>
#include <sstream>

#include <shoal/track/columns.hpp>
#include <shoal/track/csv_reader.hpp>
#include <shoal/track/nmea_reader.hpp>
#include <shoal/track/ogr_reader.hpp>
#include <shoal/track/vessels_table.hpp>
#include "util/standard_input.hpp"
#include "util/gdal_input.hpp"
#include "util/input_file.hpp"
#include "util/parse_util.hpp"
#include "track/stream_readers.hpp"
#include <shoal/util/error.hpp>

namespace shoal::track {

namespace fs = std::filesystem;

namespace {

constexpr const char* not_a_track_format =
    ": not a track format shoal reads (CSV with a header, GPX, GeoJSON, NMEA 0183)";

std::string lower_extension(const fs::path& p) {
    std::string ext = p.extension().string();
    for (char& c : ext)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return ext;
}

constexpr std::array<std::string_view, 9> track_extensions{".csv", ".gpx", ".geojson", ".json", ".nmea", ".log", ".txt", ".zip", ".gz"};

bool is_track_extension(const std::string& ext) {
    return std::find(track_extensions.begin(), track_extensions.end(), ext) != track_extensions.end();
}

/// ".csv .gpx ... .gz", for messages.
std::string track_extensions_text() {
    std::string s;
    for (const std::string_view e : track_extensions) (s += s.empty() ? "" : " ") += e;
    return s;
}

}  // namespace

std::string read_file(const std::string& path) {
    try {
        return shoal::detail::read_input(path);
    } catch (const shoal::detail::InputOpenError& e) {
        throw InputError(path + ": cannot read (" + e.reason + ")");
    }
}

namespace {

/// Whether the first 4 KB of a file hold NUL bytes as a binary file's do: on its first line, or
/// more than a few. A text file with a line or two damaged by a NUL is text (before, one NUL
/// in its first 4 KB cost the whole file): that line is a bad row of its reader.
bool looks_binary(std::string_view head) {
    head = head.substr(0, 4096);
    const std::size_t nul = head.find('\0');
    if (nul == std::string_view::npos) return false;
    const std::size_t first_line_end = head.find('\n');
    return first_line_end == std::string_view::npos || nul < first_line_end || std::count(head.begin(), head.end(), '\0') > 4;
}

}  // namespace

std::string sniff_format(std::string_view content, const std::string& path) {
    if (content.substr(0, 3) == "\xEF\xBB\xBF") content.remove_prefix(3);
    const std::string ext = path.empty() ? std::string() : lower_extension(path);
    const std::string_view head = content.substr(0, 4096);
    if (looks_binary(head)) return {};
    const std::size_t first = content.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) return {};
    const char c = content[first];
    // A NUL is a damaged line (a bad row) only in the formats read line by line: a GPX or
    // GeoJSON file with one is binary, as before (its parser would stop at it, the rest lost).
    const bool nul = head.find('\0') != std::string_view::npos;
    if (c == '<') return !nul && (head.find("<gpx") != std::string_view::npos || ext == ".gpx") ? "gpx" : "";
    if (c == '{') return nul ? "" : "geojson";

    // NMEA when most of the first 20 lines that are not blank or '#' comments hold a sentence.
    std::size_t lines = 0, sentences = 0, pos = 0;
    std::string_view first_line;
    while (pos < content.size() && lines < 20) {
        std::size_t end = content.find_first_of("\r\n", pos);  // (a log with CR line ends too)
        if (end == std::string_view::npos) end = content.size();
        const std::string_view line = detail::trim(content.substr(pos, end - pos));
        if (first_line.empty()) first_line = line;
        pos = end + 1;
        if (line.empty() || line.front() == '#') continue;
        ++lines;
        sentences += holds_nmea_sentence(line) ? 1 : 0;
    }
    if (sentences > 0 && 2 * sentences >= lines) return "nmea";
    if (first_line.find_first_of(",;\t") != std::string_view::npos) return "csv";
    return {};
}

namespace {

/// Why sniff_format() told no format, where the beginning says: a NUL byte (binary, or a text
/// file with a damaged line: where), or a first line without a separator (comment lines before
/// a CSV header); "" otherwise.
std::string why_not_a_track_format(std::string_view head) {
    if (head.substr(0, 3) == "\xEF\xBB\xBF") head.remove_prefix(3);
    const std::size_t lead = head.find_first_not_of(" \t\r\n");
    const bool whole_document = lead != std::string_view::npos && (head[lead] == '<' || head[lead] == '{');  // (GPX, GeoJSON)
    if (const std::size_t nul = head.substr(0, 4096).find('\0'); nul != std::string_view::npos && (whole_document || looks_binary(head))) {
        const std::size_t line = 1 + static_cast<std::size_t>(std::count(head.begin(), head.begin() + static_cast<std::ptrdiff_t>(nul), '\n'));
        return ": a NUL byte on line " + std::to_string(line) + " (byte " + std::to_string(nul + 1) +
               "): a binary file, or a text file with a damaged line there";
    }
    const std::size_t first = head.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos || head[first] == '<' || head[first] == '{') return "";
    std::string_view line = head.substr(first, head.find_first_of("\r\n", first) - first);
    if (line.find_first_of(",;\t") != std::string_view::npos) return "";
    line = detail::utf8_prefix(line, 60);  // (cut between UTF-8 characters: the message goes into the report's JSON)
    return ": its first line ('" + std::string(line) + "') holds no ',', ';' or tab" +
           (line.front() == '#' ? " (a CSV file's header must be its first line: remove the comment lines before it)" : "");
}

/// A file's format, from its beginning: enough of it that sniff_format decides as it would on
/// the whole file (the first 4 KB, and the first 20 lines that are not blank or comments).
struct Sniffed {
    std::string format;
    std::string head;   ///< the bytes read
    bool whole = false; ///< head is the whole file
};

/// Opens `path` once, for the sniff and the reading. Throws InputError.
std::unique_ptr<shoal::detail::InputFile> open_track_file(const std::string& path) {
    try {
        return std::make_unique<shoal::detail::InputFile>(path);
    } catch (const shoal::detail::InputOpenError& e) {
        if (e.reason == "is a folder") throw InputError(path + ": is a folder, not a track file");
        if (e.reason == "no such file" || e.reason.starts_with("cannot read") || e.reason.starts_with("a zip")) throw;
        throw InputError(path + ": cannot read (" + e.reason + ")");
    }
}

/// Reads the file's beginning from `in` (at most shoal::detail::max_sniff_bytes).
Sniffed sniff_file(shoal::detail::InputFile& in) {
    const std::string& path = in.path();
    Sniffed out;
    std::size_t scanned = 0, lines = 0;  // complete lines looked at; those sniff_format counts
    for (;;) {
        const std::size_t old = out.head.size();
        const std::size_t want = std::min(std::max<std::size_t>(1 << 16, old), shoal::detail::max_sniff_bytes - old);
        if (in.append(out.head, want) < want) {
            out.whole = true;
            break;
        }
        for (std::size_t end; lines < 20 && (end = out.head.find('\n', scanned)) != std::string::npos; scanned = end + 1) {
            const std::string_view line = detail::trim(std::string_view(out.head).substr(scanned, end - scanned));
            if (!line.empty() && line.front() != '#') ++lines;
        }
        if (lines >= 20 && out.head.size() >= 4096 + 3) break;
        if (out.head.size() >= shoal::detail::max_sniff_bytes) break;  // decided on what is there
        // Binary, XML and JSON are told by the first 4 KB alone (so /dev/zero stops here).
        const std::size_t first = out.head.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
        if (out.head.size() >= 4096 + 3 && (looks_binary(std::string_view(out.head).substr(out.head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0)) ||
                                            (first != std::string::npos && (out.head[first] == '<' || out.head[first] == '{'))))
            break;
    }
    const std::size_t bom = out.head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    if (out.whole && out.head.find_first_not_of(" \t\r\n", bom) == std::string::npos) throw InputError(path + ": empty file");
    out.format = sniff_format(out.head, path);
    if (out.format.empty()) throw InputError(path + not_a_track_format + why_not_a_track_format(out.head));
    return out;
}

/// Throws when a file gave no fix at all; drops tracks left without a fix (all their rows
/// skipped: the report counted them).
template <typename File>
void keep_tracks_with_fixes(File& out, const std::string& path) {
    std::size_t fixes = 0;
    for (const auto& t : out.tracks) fixes += t.fixes.size();
    if (fixes == 0) {
        std::string msg = path + ": no usable fix (" + std::to_string(out.report.rows) + " rows read, " +
                          std::to_string(out.report.skipped) + " skipped)";
        if (out.format == "nmea" && out.report.skipped == 0)
            msg += ": the log holds no RMC, GGA or GLL position and no AIS position report";
        if (!out.report.messages.empty()) msg += "; first problem: " + out.report.messages.front();
        throw InputError(msg);
    }
    std::erase_if(out.tracks, [](const auto& t) { return t.fixes.empty(); });
}

/// A track whose AIS dimensions no ship has loses them (it takes the default hull), said once
/// for the file.
template <typename File>
void drop_impossible_dims(File& out, const std::string& path) {
    std::size_t count = 0;
    std::string example;
    for (auto& t : out.tracks) {
        if (!t.dims || hull::Hull::plausible(*t.dims)) continue;
        if (count++ == 0) {
            std::ostringstream os;
            os << *t.dims;
            example = t.id + " (" + os.str() + ")";
        }
        t.dims.reset();
    }
    if (count == 0) return;
    out.report.messages.push_back(path + ": " + std::to_string(count) + (count == 1 ? " track gives" : " tracks give") +
                                  " AIS dimensions larger than any ship (length A+B over " + detail::fmt(hull::Hull::max_length_m) +
                                  " m or beam C+D over " + detail::fmt(hull::Hull::max_beam_m) + " m) or under a hull's " +
                                  detail::fmt(hull::Hull::min_extent_m) + " m, e.g. " + example +
                                  ": the default hull is used for them");
}

/// GPX and NMEA have no columns: with an exercise or role column to read, such a file is
/// refused, naming the column (ReadOptions::exercise_column, role_column).
void check_columns_readable(const std::string& path, const std::string& format, const ReadOptions& options) {
    if (format != "gpx" && format != "nmea") return;
    const std::string what = format == "gpx" ? "a GPX file" : "an NMEA log";
    if (!options.exercise_column.empty())
        throw InputError(path + ": " + what + " has no column '" + options.exercise_column +
                         "', the exercise column (ReadOptions::exercise_column); columns are read from CSV files and GeoJSON properties");
    if (!options.role_column.empty())
        throw InputError(path + ": " + what + " has no column '" + options.role_column +
                         "', the role column (ReadOptions::role_column); columns are read from CSV files and GeoJSON properties");
}

/// GeoJSON and GPX are read whole (at most this much); CSV and NMEA in blocks.
constexpr std::size_t max_whole_bytes = std::size_t{1} << 30;

TrackFile read_whole(shoal::detail::InputFile& in, Sniffed&& sniffed, const ReadOptions& options) {
    const std::string& path = in.path();
    if (sniffed.format == "nmea") return detail::read_nmea_stream(in, std::move(sniffed.head), sniffed.whole, options);
    std::string content = std::move(sniffed.head);
    if (sniffed.format == "gpx" && !in.gdal_path().empty()) return detail::read_gpx_at(in.gdal_path(), path, options);
    if (!sniffed.whole) in.append_all(content, max_whole_bytes, sniffed.format == "gpx" ? "a GPX file" : "a GeoJSON file", content.size());
    if (sniffed.format == "gpx") {
        const shoal::detail::MemoryFile memory(std::move(content), ".gpx");  // a stream: OGR needs a path
        return detail::read_gpx_at(memory.path(), path, options);
    }
    return read_geojson_text(content, path, options);
}

}  // namespace

TrackFile unpack(PackedTrackFile&& packed) {
    TrackFile out;
    out.report = std::move(packed.report);
    out.format = std::move(packed.format);
    out.tracks.reserve(packed.tracks.size());
    for (PackedTrack& t : packed.tracks) {
        out.tracks.push_back(t.unpack());
        t.release_fixes();
    }
    return out;
}

TrackFile read_tracks(const std::string& path, const ReadOptions& options) {
    const auto in = open_track_file(path);
    Sniffed sniffed = sniff_file(*in);
    check_columns_readable(path, sniffed.format, options);
    TrackFile out = sniffed.format == "csv" ? unpack(detail::read_csv_stream(*in, std::move(sniffed.head), sniffed.whole, options))
                                            : read_whole(*in, std::move(sniffed), options);
    if (!in->damage().empty()) out.report.messages.push_back(path + ": " + in->damage() + "; the rows before it are kept");
    out.report.stream_digest = in->stream_digest();
    keep_tracks_with_fixes(out, path);
    drop_impossible_dims(out, path);
    return out;
}

PackedTrackFile read_tracks_packed(const std::string& path, const ReadOptions& options) {
    const auto in = open_track_file(path);
    Sniffed sniffed = sniff_file(*in);
    check_columns_readable(path, sniffed.format, options);
    PackedTrackFile out;
    if (sniffed.format == "csv") {
        out = detail::read_csv_stream(*in, std::move(sniffed.head), sniffed.whole, options);
    } else {
        TrackFile whole = read_whole(*in, std::move(sniffed), options);
        out.report = std::move(whole.report);
        out.format = std::move(whole.format);
        for (Track& t : whole.tracks) out.tracks.push_back(PackedTrack::pack(std::move(t)));
    }
    if (!in->damage().empty()) out.report.messages.push_back(path + ": " + in->damage() + "; the rows before it are kept");
    out.report.stream_digest = in->stream_digest();
    keep_tracks_with_fixes(out, path);
    drop_impossible_dims(out, path);
    return out;
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& paths, std::vector<std::string>* warnings,
                                       std::vector<std::string>* vessels_files) {
    std::vector<std::string> out;
    std::vector<std::string> seen;  // the files taken so far: canonical paths, or virtual paths as given
    auto warn = [&](const std::string& w) {
        if (warnings) warnings->push_back(w);
    };
    // A file met again (named twice, or by a symlink, or in a folder also given) is read once.
    auto take = [&](const std::string& file) {
        std::string key = file;
        // Standard input by any of its names is one stream: read once (a second read would
        // race the first for the same bytes).
        if (shoal::detail::reads_standard_input(file)) {
            key = "standard input";
        } else if (!shoal::detail::is_virtual_path(file)) {
            std::error_code ec;
            const fs::path canonical = fs::weakly_canonical(file, ec);
            if (!ec) key = canonical.string();
        }
        for (std::size_t i = 0; i < seen.size(); ++i)
            if (seen[i] == key) {
                warn("'" + file + "' is the file '" + out[i] + "' given before: read once");
                return;
            }
        seen.push_back(std::move(key));
        out.push_back(file);
    };
    // A table of AIS static data (read with read_vessels) or a track file: told by the header's
    // columns, never by the name (a track file named *_vessels.csv is a track file).
    auto is_vessels_file = [](const std::string& path) { return lower_extension(path) == ".csv" && is_vessels_table(path); };
    // A zip of several files is a folder of them (its track files, in any sub-folder).
    auto take_file = [&](const std::string& file) {
        std::vector<std::string> notes;
        const std::vector<std::string> members = shoal::detail::zip_members(file, &notes);
        for (const std::string& n : notes) warn(n);
        if (members.size() <= 1) {
            take(file);
            return;
        }
        std::size_t found = 0, forks = 0;
        for (const std::string& m : members) {
            if (!is_track_extension(lower_extension(m))) continue;
            // A zip made by macOS holds a resource fork (__MACOSX/.../._NAME) per file: not data.
            if (m.find("/__MACOSX/") != std::string::npos || fs::path(m).filename().string().starts_with("._")) {
                ++forks;
                continue;
            }
            if (is_vessels_file(m)) {  // AIS static data, joined as one in a folder is
                if (vessels_files) vessels_files->push_back(m);
                continue;
            }
            take(m);
            ++found;
        }
        if (forks) warn(file + ": " + std::to_string(forks) + " macOS resource forks (__MACOSX/, ._NAME) skipped");
        if (found == 0) throw InputError(file + ": zip holds no track files (" + track_extensions_text() + ")");
    };
    for (const std::string& p : paths) {
        if (shoal::detail::is_virtual_path(p)) {
            if (p == "-" || p.starts_with("/vsistdin")) {
                take(p);  // never looked at before it is read
                continue;
            }
            const shoal::detail::gdal_input::Stat st = shoal::detail::gdal_input::stat(p);
            if (!st.exists) throw InputError(p + ": no such file or folder");
            if (st.folder) throw InputError(p + ": is a folder inside a virtual file; name its files");
            take_file(p);
            continue;
        }
        std::error_code ec;
        const auto status = fs::status(p, ec);
        if (!fs::exists(status)) {
            if (ec && ec != std::errc::no_such_file_or_directory)
                throw InputError(p + ": cannot read (" + ec.message() + ")");
            throw InputError(p + ": no such file or folder");
        }
        if (!fs::is_directory(status)) {
            take_file(p);
            continue;
        }
        std::vector<std::string> found;
        for (fs::directory_iterator it(p, ec), end; !ec && it != end; it.increment(ec)) {
            const fs::directory_entry& entry = *it;
            std::error_code entry_ec;
            // A bad entry (a symlink loop, a dangling link, no permission) costs that entry.
            const bool regular = entry.is_regular_file(entry_ec);
            if (!is_track_extension(lower_extension(entry.path()))) continue;
            if (entry_ec) {
                warn(entry.path().string() + ": cannot read (" + entry_ec.message() + "); skipped");
                continue;
            }
            if (!regular) continue;
            if (is_vessels_file(entry.path().string())) {  // AIS static data, read with read_vessels
                if (vessels_files) vessels_files->push_back(entry.path().string());
                continue;
            }
            found.push_back(entry.path().string());
        }
        if (ec) throw InputError(p + ": cannot list the folder (" + ec.message() + ")");
        if (found.empty()) throw InputError(p + ": folder holds no track files (" + track_extensions_text() + ")");
        std::sort(found.begin(), found.end());
        for (const std::string& f : found) take_file(f);
    }
    return out;
}

}  // namespace shoal::track
