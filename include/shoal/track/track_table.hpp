#pragma once
/// Rows of fixes into tracks, one per vessel: the tracks of one file (or one DataFrame) as its
/// rows come. A row's vessel id names its track (with an exercise column, its exercise and id:
/// one vessel in two exercises is two tracks); tracks stand in the order their ids first
/// appear; a file without an id column is one track named by the file. A row's static values
/// go to its track by the row rules (row_rules.hpp): each is kept from the first row that gives a
/// usable one. The CSV reader assembles a file's tracks with it, and the Python module a
/// DataFrame's, so both make the same tracks of the same rows.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/hull/hull.hpp>
#include <shoal/track/packed_track.hpp>

namespace shoal::track {

class TrackTable {
public:
    /// Tracks are made in `tracks` (which must outlive the table), each with `file` as its file;
    /// `has_id`: the rows carry vessel ids (else every row is the one track named by the file);
    /// `by_exercise`: tracks are (exercise, id).
    TrackTable(std::vector<PackedTrack>& tracks, std::string file, bool has_id, bool by_exercise);
    ~TrackTable();
    TrackTable(const TrackTable&) = delete;
    TrackTable& operator=(const TrackTable&) = delete;

    /// The index in `tracks` of the track of (`exercise`, `id`), made when first met (its id and
    /// exercise as UTF-8). `exercise` is ignored unless by_exercise.
    std::size_t track_for(std::string_view id, std::string_view exercise = {});

private:
    struct Index;
    std::vector<PackedTrack>& m_tracks;
    std::string m_file;
    bool m_has_id, m_by_exercise;
    std::unique_ptr<Index> m_index;
};

/// A row's static values offered to its track: each is taken when the track has none yet and
/// the value is usable (row_rules.hpp), with the source the report names.
void offer_name(PackedTrack& t, std::string_view name);
void offer_dims(PackedTrack& t, const std::optional<hull::Dimensions>& dims, const char* source);
void offer_draught(PackedTrack& t, double draught_m);
void offer_ship_type(PackedTrack& t, double ship_type);

}  // namespace shoal::track
