#pragma once
// The tracks of one file by (exercise, id), shared by the GPX and GeoJSON readers. Internal.

#include <string>
#include <unordered_map>

#include <shoal/track/track.hpp>

namespace shoal::track::detail {

/// Tracks of one file by (exercise, id), in the order they first appear; the exercise is ""
/// unless ReadOptions::exercise_column is read.
class TrackSet {
public:
    TrackSet(TrackFile& out, const std::string& file) : m_out(out), m_file(file) {}
    Track& get(const std::string& id, const std::string& name = {}, const std::string& exercise = {}) {
        auto [it, added] = m_index.try_emplace(exercise + '\0' + id, m_out.tracks.size());
        if (added) {
            Track& t = m_out.tracks.emplace_back();
            t.id = id;
            t.file = m_file;
            t.exercise = exercise;
        }
        Track& t = m_out.tracks[it->second];
        if (t.name.empty()) t.name = name;
        return t;
    }

private:
    TrackFile& m_out;
    const std::string& m_file;
    std::unordered_map<std::string, std::size_t> m_index;
};

}  // namespace shoal::track::detail
