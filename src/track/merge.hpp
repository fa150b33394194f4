#pragma once
/// One vessel, one track: the same vessel met in several files (one AIS feed split across two
/// receivers' files, or a day's export given beside the hour it holds) is merged into one
/// track, and a fix that two files both hold (the same time) is kept once.

#include <functional>
#include <string>
#include <vector>

#include <shoal/track/packed_track.hpp>

namespace shoal::track {

/// True for an id that names a vessel whatever the file: an MMSI (nine digits). Other ids (GPX
/// track names such as "ACTIVE LOG", file stems) name a track of one file only and are never
/// merged.
bool is_vessel_id(const std::string& id) noexcept;

/// Merges the tracks of `tracks` (in file order) that share a vessel id (is_vessel_id) and come
/// from different files into the first of them, in time order, a time met twice kept once (as
/// normalise does); the merged track's `file` names every file ("a.csv + b.csv"). Tracks of
/// different exercises are never merged: `exercise_of` gives a track's exercise (its file, its
/// folder; null: Track::exercise, from an exercise column). Files that give the vessel
/// different roles (Track::role) make it a target, said in its message.
/// Returns one message per merged vessel.
std::vector<std::string> merge_same_vessels(std::vector<PackedTrack>& tracks,
                                            const std::function<std::string(const PackedTrack&)>& exercise_of = {});

}  // namespace shoal::track
