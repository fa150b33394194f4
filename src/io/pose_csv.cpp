#include <shoal/io/pose_csv.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>

#include <shoal/util/error.hpp>
#include "detail/input_file.hpp"

namespace shoal::io {

namespace {

/// Most bytes a pose file may hold (some eight million poses).
constexpr std::size_t max_pose_file_bytes = std::size_t{1} << 28;

constexpr std::size_t max_messages = 10;

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : line) {
        if (c == ',' || c == ';' || c == '\t') {
            out.push_back(cur);
            cur.clear();
        } else if (c != '"') {
            cur += c;
        }
    }
    out.push_back(cur);
    for (auto& s : out) {
        const auto b = s.find_first_not_of(" \t");
        const auto e = s.find_last_not_of(" \t");
        s = b == std::string::npos ? "" : s.substr(b, e - b + 1);
    }
    return out;
}

bool parse_double(const std::string& s, double& v) {
    if (s.empty()) return false;
    const char* first = s.data();
    if (*first == '+') ++first;
    const auto [p, ec] = std::from_chars(first, s.data() + s.size(), v);
    return ec == std::errc() && p == s.data() + s.size();
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace

PoseFile parse_pose_csv(const std::string& text, const std::string& name) {
    PoseFile out;
    int col_lat = 0, col_lon = 1, col_hdg = 2;
    bool first = true;
    std::istringstream in(text);
    std::string line;
    std::size_t lineno = 0;
    auto bad = [&](const std::string& why) {
        ++out.skipped;
        if (out.errors.size() < max_messages) out.errors.push_back(name + " line " + std::to_string(lineno) + ": " + why + "; row skipped");
    };
    while (std::getline(in, line)) {
        ++lineno;
        if (lineno == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
        const std::vector<std::string> f = split(line);
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
                    throw InputError(name + " line 1: the header needs columns lat, lon and heading (got '" + line + "')");
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
        const std::string& slat = f[static_cast<std::size_t>(col_lat)];
        const std::string& slon = f[static_cast<std::size_t>(col_lon)];
        const std::string& shdg = f[static_cast<std::size_t>(col_hdg)];
        if (!parse_double(slat, r.lat) || !std::isfinite(r.lat) || std::fabs(r.lat) > 90) {
            bad("latitude '" + slat + "' is not a number in [-90, 90]");
            continue;
        }
        if (!parse_double(slon, r.lon) || !std::isfinite(r.lon) || std::fabs(r.lon) > 180) {
            bad("longitude '" + slon + "' is not a number in [-180, 180]");
            continue;
        }
        if (!parse_double(shdg, r.heading_deg) || !std::isfinite(r.heading_deg)) {
            bad("heading '" + shdg + "' is not a number of degrees");
            continue;
        }
        r.heading_deg = std::fmod(r.heading_deg, 360.0);
        if (r.heading_deg < 0) r.heading_deg += 360.0;
        out.poses.push_back(r);
    }
    return out;
}

PoseFile read_pose_csv(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError("'" + path + "': no such file or directory");
    if (std::filesystem::is_directory(path, ec)) throw InputError("'" + path + "' is a directory, not a CSV file");
    std::string text;
    try {
        text = detail::read_input(path, max_pose_file_bytes, "a pose file");
    } catch (const detail::InputOpenError& e) {
        throw InputError("cannot open '" + path + "' (" + e.reason + ")");
    }
    return parse_pose_csv(text, path);
}

}  // namespace shoal::io
