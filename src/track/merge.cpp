#include "track/merge.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

namespace shoal::track {

bool is_vessel_id(const std::string& id) noexcept {
    return id.size() == 9 && std::all_of(id.begin(), id.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

std::vector<std::string> merge_same_vessels(std::vector<PackedTrack>& tracks, const std::function<std::string(const PackedTrack&)>& exercise_of) {
    std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> by_id;  // (exercise, id): never across exercises
    for (std::size_t k = 0; k < tracks.size(); ++k)
        if (is_vessel_id(tracks[k].id)) by_id[{exercise_of ? exercise_of(tracks[k]) : tracks[k].exercise, tracks[k].id}].push_back(k);
    std::vector<std::string> messages;
    std::vector<bool> gone(tracks.size(), false);
    for (const auto& [key, ks] : by_id) {
        if (ks.size() < 2) continue;
        const std::string& id = key.second;
        // Merged packed, in place: the other tracks' fixes appended to the first's (packing is
        // exact: each fix packs again to the values it unpacked to), sorted and made unique as
        // normalise(Track&) does; no whole track unpacked, copied and packed again.
        PackedTrack& merged = tracks[ks[0]];
        std::string files = tracks[ks[0]].file;
        std::string role_note;
        for (std::size_t i = 1; i < ks.size(); ++i) {
            const PackedTrack& other = tracks[ks[i]];
            for (std::size_t f = 0; f < other.size(); ++f) merged.push_back(other.fix(f));
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
            if (merged.role.empty()) {
                merged.role = other.role;
            } else if (!other.role.empty() && other.role != merged.role && role_note.empty()) {
                role_note = "; its files disagree on the role (" + merged.role + " in " + tracks[ks[0]].file + ", " + other.role + " in " +
                            other.file + "): it is taken as a target";
            }
            files += " + " + other.file;
            gone[ks[i]] = true;
            tracks[ks[i]].release_fixes();
        }
        ReadReport report;
        normalise(merged, report);
        merged.file = files;
        if (!role_note.empty()) merged.role = "target";
        messages.push_back("vessel " + id + (key.first.empty() ? "" : " of exercise '" + key.first + "'") + " is in " + std::to_string(ks.size()) + " files (" + files + "): merged into one track of " +
                           std::to_string(merged.fixes.size()) + " fixes" +
                           (report.duplicates ? ", " + std::to_string(report.duplicates) + " fixes held twice kept once" : std::string()) +
                           role_note);
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
