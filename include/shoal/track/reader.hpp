#pragma once
/// Reading track files of any format shoal knows: CSV with a header, GPX, GeoJSON, NMEA 0183.
/// The format is found from the content (and the extension when the content is ambiguous), so
/// a renamed file still reads. Every track comes back normalised (sorted by time, repeated
/// times dropped) but not split at gaps: the audit does that (--max-gap).

#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/hull/hull.hpp>
#include <shoal/track/packed_track.hpp>
#include <shoal/track/track.hpp>
#include <shoal/util/error.hpp>

namespace shoal::track {

struct ReadOptions {
    /// Date for logs and rows that give only a time of day and no date anywhere in the file:
    /// any epoch second of that day (UTC); its time of day is ignored. Without it such times are
    /// dated 1970-01-01 and the report says so.
    std::optional<double> date_s;
    /// Problems kept word for word in ReadReport::messages; the rest are only counted.
    std::size_t max_messages = 10;
    /// A vessel with Length and Width but no A,B,C,D (MarineCadastre) gets a hull of that size
    /// with the position reference taken amidships. Off by default: the reference is not known,
    /// and an antenna aft of amidships puts the true bow up to half a length further ahead, so a
    /// bow-first grounding can be missed (tests/data/tracks/ais_cases/aground_at_speed.csv).
    bool hull_from_length_width = false;
    /// Exercise mode, `--exercise-by column:NAME`: the exercise of each fix is the value of the
    /// CSV column (GeoJSON property) of this name, matched as other columns are (any case, a
    /// leading `#` and blanks ignored); tracks are keyed by (exercise, id), so one vessel id in
    /// two exercises is two tracks (Track::exercise). A row whose value is empty is a bad row;
    /// a CSV file without the column, a GeoJSON file none of whose features has it, and a GPX
    /// or NMEA file (they have no columns) are an InputError naming the file and the column.
    /// "": none read.
    std::string exercise_column;
    /// Exercise mode, `--role-column NAME`: each track's role from the column (property) of this
    /// name (Track::role; values as track::role_value reads them). A row with any other value,
    /// or none, is a bad row; a file without the column is an InputError, as for the exercise
    /// column. A track whose rows give both roles is a target (the rows disagree: the track is
    /// not scored as a trainee on a guess), said in ReadReport::messages. "": none read.
    std::string role_column;
    /// Threads a CSV file too big to be read whole (over 1 MiB) is read with: 2 or more, one
    /// reads, splits and parses its rows while another makes the tracks of them (the same
    /// tracks, fixes and messages as with 1). The audit gives 2 to as many files as `--jobs`
    /// leaves jobs free (jobs minus files).
    unsigned threads = 1;
};

/// All tracks of one file, what reading it found, and the format it was read as
/// ("csv", "nmea", "gpx", "geojson").
struct TrackFile {
    std::vector<Track> tracks;
    ReadReport report;
    std::string format;
};

/// The same with the fixes packed (see packed_track.hpp): what a batch holds while it is read.
struct PackedTrackFile {
    std::vector<PackedTrack> tracks;
    ReadReport report;
    std::string format;
};

/// Reads `path` as whichever track format its content is. Throws InputError when the file
/// cannot be read, is empty, is no track format ("FILE: not a track format shoal reads (CSV
/// with a header, GPX, GeoJSON, NMEA 0183)"), is broken beyond single rows, or yields no fix.
TrackFile read_tracks(const std::string& path, const ReadOptions& options = {});
/// The same with the fixes packed, a CSV file read in blocks (never whole): for big batches,
/// whose memory is then about 32 bytes per fix.
PackedTrackFile read_tracks_packed(const std::string& path, const ReadOptions& options = {});
/// Unpacks every track (freeing the packed fixes as it goes).
TrackFile unpack(PackedTrackFile&& packed);

/// The track format of a file's content: "csv", "nmea", "gpx", "geojson", or "" when none.
/// `path` only breaks ties (its extension); the content decides.
std::string sniff_format(std::string_view content, const std::string& path = {});

/// Files named on a command line, with each folder replaced by the track files directly in it
/// (extensions .csv .gpx .geojson .json .nmea .log .txt .zip .gz, any case, not vessels tables
/// (is_vessels_table), sorted by name; not recursive). Files are kept as given, whatever their extension. A file met again
/// (named twice, by a symlink to it, or inside a folder also given) is kept once; a folder entry
/// that cannot be read (a symlink loop, a dangling link) is skipped; both are said in `warnings`.
/// Throws InputError for a path that does not exist and for a folder without track files.
/// The vessels tables (CSV files by their header, is_vessels_table) met in folders and in zips read as folders go to
/// `vessels_files` when given.
std::vector<std::string> expand_inputs(const std::vector<std::string>& paths, std::vector<std::string>* warnings = nullptr,
                                       std::vector<std::string>* vessels_files = nullptr);

/// The whole file as bytes. Throws InputError "FILE: cannot read (reason)".
std::string read_file(const std::string& path);

}  // namespace shoal::track
