// parse_pose_csv: GDAL-free (in shoal_core: the `shoal` executable's probe of a grid file
// parses poses without loading GDAL); read_pose_csv, which reads through GDAL, is in pose_csv.cpp.
#include <shoal/io/pose_csv.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string_view>

#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::io {

namespace {

constexpr std::size_t max_messages = 10;

/// The fields of `line` (separated by ',', ';' or a tab, quotes dropped, each trimmed of
/// blanks) as views into `line`, or into `unquoted` when the line holds quotes.
void split(std::string_view line, std::string& unquoted, std::vector<std::string_view>& out) {
    out.clear();
    if (line.find('"') != std::string_view::npos) {
        unquoted.clear();
        for (char c : line)
            if (c != '"') unquoted += c;
        line = unquoted;
    }
    auto trimmed = [](std::string_view f) {
        const auto b = f.find_first_not_of(" \t");
        if (b == std::string_view::npos) return std::string_view{};
        return f.substr(b, f.find_last_not_of(" \t") - b + 1);
    };
    std::size_t from = 0;
    for (std::size_t k = 0; k < line.size(); ++k) {
        const char c = line[k];
        if (c == ',' || c == ';' || c == '\t') {
            out.push_back(trimmed(line.substr(from, k - from)));
            from = k + 1;
        }
    }
    out.push_back(trimmed(line.substr(from)));
}

bool parse_double(std::string_view s, double& v) {
    if (s.empty()) return false;
    const char* first = s.data();
    const char* last = s.data() + s.size();
    if (*first == '+') ++first;
    const auto [p, ec] = std::from_chars(first, last, v);
    return ec == std::errc() && p == last;
}

std::string lower(std::string_view v) {
    std::string s(v);
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

PoseFile parse_pose_csv(const std::string& text, const std::string& name) {
    PoseFile out;
    int col_lat = 0, col_lon = 1, col_hdg = 2;
    bool first = true;
    std::size_t lineno = 0;
    auto bad = [&](const std::string& why) {
        ++out.skipped;
        if (out.errors.size() < max_messages) out.errors.push_back(name + " line " + std::to_string(lineno) + ": " + why + "; row skipped");
    };
    std::string unquoted;
    std::vector<std::string_view> f;
    const std::string_view all(text);
    for (std::size_t pos = 0; pos < all.size();) {
        const std::size_t nl = all.find('\n', pos);
        std::string_view line = all.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
        pos = nl == std::string_view::npos ? all.size() : nl + 1;
        ++lineno;
        if (lineno == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 BOM
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::size_t lead = line.find_first_not_of(" \t");
        if (lead == std::string_view::npos || line[lead] == '#') continue;
        split(line, unquoted, f);
        if (first) {
            first = false;
            const bool header = std::any_of(line.begin(), line.end(), [](unsigned char c) { return std::isalpha(c) && c != 'e' && c != 'E'; });
            if (header) {
                col_lat = col_lon = col_hdg = -1;
                for (int i = 0; i < static_cast<int>(f.size()); ++i) {
                    const std::string h = lower(f[static_cast<std::size_t>(i)]);
                    if (h == "lat" || h == "latitude") col_lat = i;
                    else if (h == "lon" || h == "lng" || h == "long" || h == "longitude") col_lon = i;
                    else if (h == "heading" || h == "hdg" || h == "heading_deg") col_hdg = i;
                }
                if (col_lat < 0 || col_lon < 0 || col_hdg < 0)
                    throw InputError(name + " line 1: the header needs columns lat, lon and heading (got '" + std::string(line) + "')");
                continue;
            }
        }
        const int need = std::max({col_lat, col_lon, col_hdg});
        if (static_cast<int>(f.size()) <= need) {
            bad("expected at least " + std::to_string(need + 1) + " fields, got " + std::to_string(f.size()));
            continue;
        }
        PoseRow r;
        r.line = lineno;
        const std::string_view slat = f[static_cast<std::size_t>(col_lat)];
        const std::string_view slon = f[static_cast<std::size_t>(col_lon)];
        const std::string_view shdg = f[static_cast<std::size_t>(col_hdg)];
        if (!parse_double(slat, r.lat) || !std::isfinite(r.lat) || std::fabs(r.lat) > 90) {
            bad("latitude '" + std::string(slat) + "' is not a number in [-90, 90]");
            continue;
        }
        if (!parse_double(slon, r.lon) || !std::isfinite(r.lon) || std::fabs(r.lon) > 180) {
            bad("longitude '" + std::string(slon) + "' is not a number in [-180, 180]");
            continue;
        }
        if (!parse_double(shdg, r.heading_deg) || !std::isfinite(r.heading_deg)) {
            bad("heading '" + std::string(shdg) + "' is not a number of degrees");
            continue;
        }
        r.heading_deg = std::fmod(r.heading_deg, 360.0);
        if (r.heading_deg < 0) r.heading_deg += 360.0;
        out.poses.push_back(r);
    }
    return out;
}

bool is_probe_output(const std::string& path) { return file_head(path, probe_output_header.size()) == probe_output_header; }

}  // namespace shoal::io
