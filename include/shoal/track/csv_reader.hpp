#pragma once
/// CSV tracks with a header row. Columns are found by name, case-insensitively (a leading `#`
/// and blanks ignored):
///
/// | role | names (the first present wins) |
/// |---|---|
/// | id | track_id, mmsi, id, vessel, vessel_id, then name, vesselname, vessel_name, shipname |
/// | time | time, timestamp, basedatetime, time_utc, datetime, date_time, utc |
/// | lat / lon | lat, latitude / lon, lng, long, longitude |
/// | heading | heading, hdg, heading_deg, true_heading, trueheading |
/// | cog / sog | cog, course, cog_deg / sog, speed, sog_kn, sog_knots |
/// | AIS A,B,C,D | a, b, c, d or to_bow_m, to_stern_m, to_port_m, to_stbd_m (also without _m) |
/// | draught / name | draught, draught_m, draft / vesselname, vessel_name, name, shipname |
///
/// This covers the generic layout, the MarineCadastre AIS export, the Danish Maritime Authority
/// export (`# Timestamp` day-first, `Type of mobile`: base stations and AtoN rows are skipped) and
/// shoal's decoded fixes layout (`source,timestamp,mmsi,...`, where `Thh:mm:ss` has no date).
/// Unknown values become NAN: heading outside [0, 360] (AIS 511), COG outside [0, 360) (AIS 360),
/// SOG outside [0, 102.3) (AIS 102.3). A row without a valid position (NaN, inf, |lat| > 90,
/// |lon| > 180, AIS 91/181) or time is skipped and reported. Without an id column the file is one
/// track named after the file's stem. Tracks come out in the order their ids first appear.

#include <cstddef>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/track/columns.hpp>
#include <shoal/track/csv_splitter.hpp>
#include <shoal/track/reader.hpp>

namespace shoal::track {

/// `text` unchanged when it is valid UTF-8, else read as Latin-1 and converted to UTF-8.
std::string to_utf8(std::string_view text);

/// Reads CSV text (a whole file's bytes); `file` names it in messages and gives the track id
/// when there is no id column. Throws InputError when the header lacks a time, latitude or
/// longitude column.
TrackFile read_csv_text(std::string_view text, const std::string& file, const ReadOptions& options = {});
TrackFile read_csv(const std::string& path, const ReadOptions& options = {});

/// The same with the fixes packed (32 bytes each), the file read in blocks rather than whole:
/// memory holds the fixes, not the file's text, so a big AIS export reads in bounded memory.
PackedTrackFile read_csv_packed(const std::string& path, const ReadOptions& options = {});
PackedTrackFile read_csv_text_packed(std::string_view text, const std::string& file, const ReadOptions& options = {});

}  // namespace shoal::track
