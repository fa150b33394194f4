#pragma once
// Where the benchmarks find the shared data (../shared/data, $SHOAL_SHARED_DATA or --data DIR)
// and which coastlines they run on: every GSHHG land file and the S-57 cell.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace shoal::bench {

namespace fs = std::filesystem;

inline std::string default_data_dir() {
    if (const char* env = std::getenv("SHOAL_SHARED_DATA"); env && *env) return env;
    return (fs::path(SHOAL_SOURCE_DIR) / ".." / "shared" / "data").lexically_normal().string();
}

struct CoastFile {
    std::string name;
    std::string path;
};

inline std::vector<CoastFile> find_coasts(const std::string& dir) {
    std::vector<CoastFile> out;
    const fs::path gshhg = fs::path(dir) / "coast" / "gshhg";
    std::error_code ec;
    if (fs::is_directory(gshhg, ec))
        for (const auto& e : fs::directory_iterator(gshhg, ec)) {
            const std::string f = e.path().filename().string();
            const std::string suffix = "_land.geojson";
            if (f.size() > suffix.size() && f.compare(f.size() - suffix.size(), suffix.size(), suffix) == 0)
                out.push_back({f.substr(0, f.size() - suffix.size()), e.path().string()});
        }
    std::sort(out.begin(), out.end(), [](const CoastFile& a, const CoastFile& b) { return a.name < b.name; });
    const fs::path s57 = fs::path(dir) / "coast" / "s57" / "US4MD81M" / "US4MD81M.000";
    if (fs::exists(s57, ec)) out.push_back({"s57_US4MD81M", s57.string()});
    return out;
}

}  // namespace shoal::bench
