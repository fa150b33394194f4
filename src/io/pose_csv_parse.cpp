// parse_pose_csv and append_probe_row: GDAL-free (in shoal_core: the `shoal` executable's probe of
// a grid file reads and writes without loading GDAL); read_pose_csv, which reads through GDAL, is
// in pose_csv.cpp.
#include <shoal/io/pose_csv.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <shoal/track/columns.hpp>
#include <shoal/track/csv_splitter.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

#include "util/fixed_decimal.hpp"
#include "util/parse_util.hpp"

namespace shoal::io {

namespace {

constexpr std::size_t max_messages = 10;

bool parse_double(std::string_view s, double& v, bool decimal_comma) {
    if (s.empty()) return false;
    const char* first = s.data();
    const char* last = s.data() + s.size();
    if (*first == '+') ++first;
    if (track::detail::plain_decimal({first, static_cast<std::size_t>(last - first)}, v)) return true;  // from_chars' number, sooner
    const auto [p, ec] = std::from_chars(first, last, v);
    if (ec == std::errc() && p == last) return true;
    // With ';' or tab separators a decimal comma is read, as in a track file ("60,5").
    if (!decimal_comma || std::count(s.begin(), s.end(), ',') != 1 || s.size() > 64) return false;
    std::string dotted(s);
    std::replace(dotted.begin(), dotted.end(), ',', '.');
    return parse_double(dotted, v, false);
}

/// `text` from its first line that is not blank or a comment ('#' first, after blanks) on, a
/// byte order mark skipped; `*passed` says how many lines were passed over.
std::string_view from_first_row(std::string_view text, std::size_t* passed) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    *passed = 0;
    while (!text.empty()) {
        const std::size_t nl = text.find('\n');
        const std::string_view line = text.substr(0, nl);
        const std::size_t lead = line.find_first_not_of(" \t\r");
        if (lead != std::string_view::npos && line[lead] != '#') break;
        ++*passed;
        text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    }
    return text;
}

/// `text` with its comment lines emptied (their line ends kept, so lines keep their numbers),
/// into `copy` when there are any.
std::string_view without_comments(std::string_view text, std::string& copy) {
    bool any = false;
    for (std::size_t pos = 0; pos < text.size() && !any;) {
        const std::size_t nl = text.find('\n', pos);
        const std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
        const std::size_t lead = line.find_first_not_of(" \t");
        any = lead != std::string_view::npos && line[lead] == '#';
        pos = nl == std::string_view::npos ? text.size() : nl + 1;
    }
    if (!any) return text;
    copy.reserve(text.size());
    for (std::size_t pos = 0; pos < text.size();) {
        const std::size_t nl = text.find('\n', pos);
        const std::size_t end = nl == std::string_view::npos ? text.size() : nl;
        const std::string_view line = text.substr(pos, end - pos);
        const std::size_t lead = line.find_first_not_of(" \t");
        if (!(lead != std::string_view::npos && line[lead] == '#')) copy += line;
        if (nl != std::string_view::npos) copy += '\n';
        pos = end + 1;
    }
    return copy;
}

}  // namespace

PoseFile parse_pose_csv(const std::string& text, const std::string& name) {
    PoseFile out;
    int col_lat = 0, col_lon = 1, col_hdg = 2;
    std::size_t header_fields = 0;  // 0: no header
    bool first = true;
    std::size_t lineno = 0;
    auto bad = [&](const std::string& why) {
        ++out.skipped;
        if (out.errors.size() < max_messages) out.errors.push_back(name + " line " + std::to_string(lineno) + ": " + why + "; row skipped");
    };
    // Split as the track reader splits (track::CsvSplitter: RFC 4180 quotes, one separator, the
    // one of ',', ';' and tab the first row holds most), from the first row that is not blank
    // or a comment; later comment lines are emptied.
    std::size_t passed = 0;
    std::string copy;
    const std::string_view rows = without_comments(from_first_row(text, &passed), copy);
    track::CsvSplitter split(rows);
    const bool decimal_comma = split.separator() == ';' || split.separator() == '\t';  // ('\0': none on the first row, ',' splits)
    std::vector<std::string_view> f;
    for (std::size_t from = 0; split.next(f); from = split.consumed()) {
        lineno = passed + split.line();
        // A line of blanks (and tabs, when they separate) is passed over, as an empty one.
        if (std::all_of(f.begin(), f.end(), [](std::string_view s) { return s.empty(); }) &&
            rows.substr(from, split.consumed() - from).find_first_not_of(" \t\r\n") == std::string_view::npos)
            continue;
        if (first) {
            first = false;
            std::string_view line = rows.substr(from, split.consumed() - from);
            while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
            const bool header = std::any_of(line.begin(), line.end(), [](unsigned char c) { return std::isalpha(c) && c != 'e' && c != 'E'; });
            if (header) {
                // The columns by the track files' names (track/columns.hpp), the first name present winning.
                std::vector<std::string> names;
                for (const std::string_view h : f) names.push_back(track::normalise_column_name(h));
                const auto column = [&](std::string_view field) {
                    for (const std::string_view n : track::column_names(field))
                        for (std::size_t i = 0; i < names.size(); ++i)
                            if (names[i] == n) return static_cast<int>(i);
                    return -1;
                };
                header_fields = f.size();
                col_lat = column("lat");
                col_lon = column("lon");
                col_hdg = column("heading");
                if (col_lat < 0 || col_lon < 0 || col_hdg < 0)
                    throw InputError(name + " line 1: the header needs columns lat, lon and heading (got '" + std::string(line) + "')");
                continue;
            }
        }
        if (split.quote_not_closed()) {
            bad(std::string(track::quote_not_closed_message));
            continue;
        }
        const int need = std::max({col_lat, col_lon, col_hdg});
        if (static_cast<int>(f.size()) <= need) {
            bad("expected at least " + std::to_string(need + 1) + " fields, got " + std::to_string(f.size()));
            continue;
        }
        // More fields than the header names (or than lat, lon, heading without one), one of
        // them not blank: which is which is not known ("60,24,24,9,90", decimal commas in a
        // comma-separated file, read as the pose 60, 24, 24 before).
        const std::size_t known = header_fields > 0 ? header_fields : 3;
        if (std::any_of(f.begin() + static_cast<std::ptrdiff_t>(std::min(known, f.size())), f.end(),
                        [](std::string_view v) { return v.find_first_not_of(" \t") != std::string_view::npos; })) {
            bad("has " + std::to_string(f.size()) + " fields, " + (header_fields > 0 ? "the header " : "a row without a header ") +
                std::to_string(known) +
                (decimal_comma ? " (a separator inside an unquoted field?)" : " (a decimal comma in a comma-separated file?)"));
            continue;
        }
        PoseRow r;
        r.line = lineno;
        const std::string_view slat = f[static_cast<std::size_t>(col_lat)];
        const std::string_view slon = f[static_cast<std::size_t>(col_lon)];
        const std::string_view shdg = f[static_cast<std::size_t>(col_hdg)];
        if (!parse_double(slat, r.lat, decimal_comma) || !std::isfinite(r.lat) || std::fabs(r.lat) > 90) {
            bad("latitude '" + std::string(slat) + "' is not a number in [-90, 90]");
            continue;
        }
        if (!parse_double(slon, r.lon, decimal_comma) || !std::isfinite(r.lon) || std::fabs(r.lon) > 180) {
            bad("longitude '" + std::string(slon) + "' is not a number in [-180, 180]");
            continue;
        }
        if (!parse_double(shdg, r.heading_deg, decimal_comma) || !std::isfinite(r.heading_deg)) {
            bad("heading '" + std::string(shdg) + "' is not a number of degrees");
            continue;
        }
        // AIS's "not available" (an AIS export's heading column): taken as 151 degrees, the
        // answer would be for a pose nobody had. Other headings are taken modulo 360.
        if (r.heading_deg == 511) {
            bad("heading 511 is AIS's \"not available\": probe needs the ship's heading");
            continue;
        }
        r.heading_deg = std::fmod(r.heading_deg, 360.0) + 0.0;  // (+ 0.0: -0 and -360 are 0, not "-0.0")
        if (r.heading_deg < 0) r.heading_deg += 360.0;
        out.poses.push_back(r);
    }
    // Nothing but blanks and comments (a zero-byte file, an export that failed): not a pose
    // file, as an empty track file is not a track file. A header alone is an empty set.
    if (first) throw InputError(name + ": empty file (no header and no poses)");
    return out;
}

void append_probe_row(std::string& out, const PoseRow& pose, bool claimed, bool collision, double clearance_m, bool covered) {
    detail::append_fixed(out, pose.lat, 7);
    out += ',';
    detail::append_fixed(out, pose.lon, 7);
    out += ',';
    detail::append_fixed(out, pose.heading_deg, 1);
    if (claimed) {
        out += collision ? ",1," : ",0,";
        detail::append_fixed(out, clearance_m, 3);
        out += covered ? ",1\n" : ",0\n";
    } else {
        out += ",,,0\n";
    }
}

bool is_probe_output(const std::string& path) { return file_head(path, probe_output_header.size()) == probe_output_header; }

}  // namespace shoal::io
