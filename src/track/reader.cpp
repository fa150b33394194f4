#include <shoal/track/reader.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include <shoal/track/csv_reader.hpp>
#include <shoal/track/nmea_reader.hpp>
#include <shoal/track/ogr_reader.hpp>
#include "detail/parse_util.hpp"
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

bool is_track_extension(const std::string& ext) {
    static constexpr std::array<std::string_view, 7> exts{".csv", ".gpx", ".geojson", ".json", ".nmea", ".log", ".txt"};
    return std::find(exts.begin(), exts.end(), ext) != exts.end();
}

struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};

}  // namespace

std::string read_file(const std::string& path) {
    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
    if (!f) throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
    std::string out;
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (!ec && size > 0) out.reserve(static_cast<std::size_t>(size));
    std::array<char, 1 << 16> buf;
    for (;;) {
        const std::size_t n = std::fread(buf.data(), 1, buf.size(), f.get());
        out.append(buf.data(), n);
        if (n < buf.size()) break;
    }
    if (std::ferror(f.get())) throw InputError(path + ": cannot read (read error)");
    return out;
}

std::string sniff_format(std::string_view content, const std::string& path) {
    if (content.substr(0, 3) == "\xEF\xBB\xBF") content.remove_prefix(3);
    const std::string ext = path.empty() ? std::string() : lower_extension(path);
    const std::string_view head = content.substr(0, 4096);
    if (head.find('\0') != std::string_view::npos) return {};  // binary
    const std::size_t first = content.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) return {};
    const char c = content[first];
    if (c == '<') return head.find("<gpx") != std::string_view::npos || ext == ".gpx" ? "gpx" : "";
    if (c == '{') return "geojson";

    // NMEA when most of the first 20 lines that are not blank or '#' comments hold a sentence.
    std::size_t lines = 0, sentences = 0, pos = 0;
    std::string_view first_line;
    while (pos < content.size() && lines < 20) {
        std::size_t end = content.find('\n', pos);
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

/// A file's format, from its beginning: enough of it that sniff_format decides as it would on
/// the whole file (the first 4 KB, and the first 20 lines that are not blank or comments).
struct Sniffed {
    std::string format;
    std::string head;   ///< the bytes read
    bool whole = false; ///< head is the whole file
};

Sniffed sniff_file(const std::string& path) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (!fs::exists(status)) throw InputError(path + ": no such file");
    if (fs::is_directory(status)) throw InputError(path + ": is a folder, not a track file");
    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
    if (!f) throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
    Sniffed out;
    std::size_t scanned = 0, lines = 0;  // complete lines looked at; those sniff_format counts
    for (;;) {
        const std::size_t old = out.head.size(), want = std::max<std::size_t>(1 << 16, old);
        out.head.resize(old + want);
        const std::size_t got = std::fread(out.head.data() + old, 1, want, f.get());
        out.head.resize(old + got);
        if (got < want) {
            if (std::ferror(f.get())) throw InputError(path + ": cannot read (" + std::strerror(errno) + ")");
            out.whole = true;
            break;
        }
        for (std::size_t end; lines < 20 && (end = out.head.find('\n', scanned)) != std::string::npos; scanned = end + 1) {
            const std::string_view line = detail::trim(std::string_view(out.head).substr(scanned, end - scanned));
            if (!line.empty() && line.front() != '#') ++lines;
        }
        if (lines >= 20 && out.head.size() >= 4096 + 3) break;
    }
    const std::size_t bom = out.head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    if (out.whole && out.head.find_first_not_of(" \t\r\n", bom) == std::string::npos) throw InputError(path + ": empty file");
    out.format = sniff_format(out.head, path);
    if (out.format.empty()) throw InputError(path + not_a_track_format);
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

/// Every format but CSV, read whole.
TrackFile read_whole(const std::string& path, Sniffed&& sniffed, const ReadOptions& options) {
    const std::string content = sniffed.whole ? std::move(sniffed.head) : read_file(path);
    if (sniffed.format == "nmea") return read_nmea_text(content, path, options);
    if (sniffed.format == "gpx") return read_gpx(path, options);
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
    Sniffed sniffed = sniff_file(path);
    TrackFile out = sniffed.format == "csv" ? read_csv(path, options) : read_whole(path, std::move(sniffed), options);
    keep_tracks_with_fixes(out, path);
    return out;
}

PackedTrackFile read_tracks_packed(const std::string& path, const ReadOptions& options) {
    Sniffed sniffed = sniff_file(path);
    PackedTrackFile out;
    if (sniffed.format == "csv") {
        out = read_csv_packed(path, options);
    } else {
        TrackFile whole = read_whole(path, std::move(sniffed), options);
        out.report = std::move(whole.report);
        out.format = std::move(whole.format);
        for (Track& t : whole.tracks) out.tracks.push_back(PackedTrack::pack(std::move(t)));
    }
    keep_tracks_with_fixes(out, path);
    return out;
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& paths, std::vector<std::string>* warnings) {
    std::vector<std::string> out;
    std::vector<fs::path> seen;  // the files taken so far, as canonical paths
    auto warn = [&](const std::string& w) {
        if (warnings) warnings->push_back(w);
    };
    // A file met again (named twice, or by a symlink, or in a folder also given) is read once.
    auto take = [&](const std::string& file) {
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(file, ec);
        if (!ec) {
            for (std::size_t i = 0; i < seen.size(); ++i)
                if (seen[i] == canonical) {
                    warn("'" + file + "' is the file '" + out[i] + "' given before: read once");
                    return;
                }
        }
        seen.push_back(ec ? fs::path(file) : canonical);
        out.push_back(file);
    };
    for (const std::string& p : paths) {
        std::error_code ec;
        const auto status = fs::status(p, ec);
        if (!fs::exists(status)) {
            if (ec && ec != std::errc::no_such_file_or_directory)
                throw InputError(p + ": cannot read (" + ec.message() + ")");
            throw InputError(p + ": no such file or folder");
        }
        if (!fs::is_directory(status)) {
            take(p);
            continue;
        }
        std::vector<std::string> found;
        for (fs::directory_iterator it(p, ec), end; !ec && it != end; it.increment(ec)) {
            const fs::directory_entry& entry = *it;
            std::error_code entry_ec;
            // A bad entry (a symlink loop, a dangling link, no permission) costs that entry.
            const bool regular = entry.is_regular_file(entry_ec);
            const std::string name = entry.path().filename().string();
            if (!is_track_extension(lower_extension(entry.path()))) continue;
            if (entry_ec) {
                warn(entry.path().string() + ": cannot read (" + entry_ec.message() + "); skipped");
                continue;
            }
            if (!regular) continue;
            if (name.size() >= 12 && lower_extension(entry.path()) == ".csv" &&
                name.compare(name.size() - 12, 12, "_vessels.csv") == 0)
                continue;  // AIS static data, read with read_vessels
            found.push_back(entry.path().string());
        }
        if (ec) throw InputError(p + ": cannot list the folder (" + ec.message() + ")");
        if (found.empty())
            throw InputError(p + ": folder holds no track files (.csv .gpx .geojson .json .nmea .log .txt)");
        std::sort(found.begin(), found.end());
        for (const std::string& f : found) take(f);
    }
    return out;
}

std::map<std::string, VesselInfo> read_vessels(const std::string& path) {
    const std::string text = read_file(path);
    CsvSplitter split(text);
    std::vector<std::string_view> f;
    if (split.separator() == '\0' || !split.next(f)) throw InputError(path + ": not a vessels CSV file (no header)");
    constexpr std::size_t absent = static_cast<std::size_t>(-1);
    std::vector<std::string> names;
    for (const auto h : f) names.push_back(normalise_column_name(h));
    auto col = [&](std::initializer_list<std::string_view> candidates) {
        for (const auto c : candidates)
            for (std::size_t i = 0; i < names.size(); ++i)
                if (names[i] == c) return i;
        return absent;
    };
    const std::size_t mmsi = col({"mmsi"});
    if (mmsi == absent) throw InputError(path + ": vessels file without an 'mmsi' column");
    const std::size_t name = col({"name", "vesselname", "vessel_name", "shipname"});
    const std::size_t type = col({"shiptype", "ship_type", "vesseltype", "ship type"});
    const std::size_t draught = col({"draught_m", "draught", "draft"});
    const std::array<std::size_t, 4> dims{col({"to_bow_m", "to_bow", "a"}), col({"to_stern_m", "to_stern", "b"}),
                                          col({"to_port_m", "to_port", "c"}), col({"to_stbd_m", "to_stbd", "d"})};
    auto number = [&](std::size_t c) -> double {
        double v = NAN;
        if (c == absent || c >= f.size() || !detail::parse_double(f[c], v)) return NAN;
        return v;
    };
    std::map<std::string, VesselInfo> out;
    while (split.next(f)) {
        if (mmsi >= f.size() || f[mmsi].empty()) continue;
        VesselInfo& v = out[std::string(f[mmsi])];
        if (v.name.empty() && name != absent && name < f.size()) v.name = to_utf8(f[name]);
        if (!v.dims) {
            std::array<double, 4> d{};
            bool ok = true;
            for (std::size_t k = 0; k < 4; ++k) {
                d[k] = number(dims[k]);
                ok = ok && std::isfinite(d[k]) && d[k] > 0.0;
            }
            if (ok) v.dims = hull::Dimensions{d[0], d[1], d[2], d[3]};
        }
        if (std::isnan(v.draught_m)) {
            const double d = number(draught);
            if (std::isfinite(d) && d > 0.0) v.draught_m = d;
        }
        if (v.ship_type < 0) {
            const double t = number(type);
            if (std::isfinite(t) && t > 0.0 && t < 1000.0) v.ship_type = static_cast<int>(t);
        }
    }
    return out;
}

}  // namespace shoal::track
