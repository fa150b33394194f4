#include <shoal/track/merge.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

namespace shoal::track {

bool is_vessel_id(const std::string& id) noexcept {
    return id.size() == 9 && std::all_of(id.begin(), id.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

std::vector<std::string> merge_same_vessels(std::vector<PackedTrack>& tracks) {
    std::map<std::string, std::vector<std::size_t>> by_id;
    for (std::size_t k = 0; k < tracks.size(); ++k)
        if (is_vessel_id(tracks[k].id)) by_id[tracks[k].id].push_back(k);
    std::vector<std::string> messages;
    std::vector<bool> gone(tracks.size(), false);
    for (const auto& [id, ks] : by_id) {
        if (ks.size() < 2) continue;
        Track merged = tracks[ks[0]].unpack();
        std::string files = tracks[ks[0]].file;
        for (std::size_t i = 1; i < ks.size(); ++i) {
            const PackedTrack& other = tracks[ks[i]];
            const Track t = other.unpack();
            merged.fixes.insert(merged.fixes.end(), t.fixes.begin(), t.fixes.end());
            if (merged.name.empty()) merged.name = other.name;
            if (!merged.dims) {
                merged.dims = other.dims;
                merged.dims_source = other.dims_source;
            }
            if (std::isnan(merged.draught_m)) {
                merged.draught_m = other.draught_m;
                merged.draught_source = other.draught_source;
            }
            if (merged.ship_type < 0) {
                merged.ship_type = other.ship_type;
                merged.ship_type_source = other.ship_type_source;
            }
            files += " + " + other.file;
            gone[ks[i]] = true;
        }
        ReadReport report;
        normalise(merged, report);
        merged.file = files;
        messages.push_back("vessel " + id + " is in " + std::to_string(ks.size()) + " files (" + files + "): merged into one track of " +
                           std::to_string(merged.fixes.size()) + " fixes" +
                           (report.duplicates ? ", " + std::to_string(report.duplicates) + " fixes held twice kept once" : std::string()));
        tracks[ks[0]] = PackedTrack::pack(std::move(merged));
    }
    std::size_t kept = 0;
    for (std::size_t k = 0; k < tracks.size(); ++k)
        if (!gone[k]) {
            if (kept != k) tracks[kept] = std::move(tracks[k]);
            ++kept;
        }
    tracks.resize(kept);
    return messages;
}

}  // namespace shoal::track
