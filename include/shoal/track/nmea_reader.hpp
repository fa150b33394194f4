#pragma once
/// NMEA 0183 logs: the own ship's track (id = the file's stem), then one track per MMSI of the
/// AIS messages in the log (id = the MMSI). One vessel, one track: when the own ship's `!AIVDO`
/// reports give one MMSI, its GPS fixes are joined into that MMSI's track (time order, a time
/// both hold kept once as the GPS fix, said in ReadReport::messages) and its own track is left
/// without fixes (read_tracks drops it); `!AIVDO` of two MMSIs join neither, said.
///
/// Sentences used, from any talker (GP, GN, II, IN, ...): RMC (date, time, position, SOG, COG;
/// status V skipped), GGA (time, position; fix quality 0 skipped), GLL (position, time; status V
/// skipped), HDT (true heading), VTG (true COG, SOG), ZDA (date). Anything before the `$` on a
/// line (a receive time, a tag block) is ignored for them; other sentences are ignored; a
/// checksum `*hh` is verified when present (a mismatch skips the line, with a message).
///
/// AIS `!--VDM`/`!--VDO` (ais.hpp): position reports become fixes of their MMSI's track, static
/// data (types 5, 19, 24) gives it its name, A/B/C/D and draught. A message's time is its line's
/// tag block `c:` or receive time before the sentence, else the latest `$PGHP` header (one that
/// is not a valid time is a skipped line, and dates nothing), else the log's own clock: the
/// receiver's time in the last RMC, GGA, GLL or ZDA before it, with the latest date. A void
/// sentence (RMC status V, GGA quality 0, GLL status V) still tells the time once a valid time
/// has set the clock and while it follows it (not back, not a day ahead); one that does not, and
/// an RMC, GGA or ZDA without a time, stop the clock until the next time. Reports with no time are dropped, counted in ReadReport::skipped and said in
/// one message for the file (never dated by an older time); a log whose AIS reports have none
/// and that has no other fix is refused (InputError). Types shoal does not read are counted in
/// one note of ReadReport::messages.
///
/// Dates: RMC and ZDA give them. Times of day from GGA/GLL take the latest date, with midnight
/// rollover (the time of day falling by more than 12 h). Times met before the first date take
/// that date; a log without any date uses ReadOptions::date_s, else 1970-01-01 and says so in
/// the report. Position sentences with the same time (GGA + RMC, or several talkers) make one
/// fix: the first position, SOG/COG filled in by the others. HDT and VTG, which carry no time,
/// fill the values still missing in the latest fix. ReadReport::rows counts sentences (`$`, `!`).

#include <string>
#include <string_view>

#include <shoal/track/reader.hpp>

namespace shoal::track {

/// Reads NMEA text (a whole file's bytes); `file` names it in messages and gives the track id.
/// A line over 1 MiB is skipped (counted, said), as read_tracks does; read_tracks reads a log
/// line by line from blocks, never whole.
TrackFile read_nmea_text(std::string_view text, const std::string& file, const ReadOptions& options = {});
TrackFile read_nmea(const std::string& path, const ReadOptions& options = {});

/// True when `line` holds an NMEA sentence (`$` or `!`, 5 or 6 letters or digits of address, a
/// comma) anywhere: the test read_tracks uses to recognise a log.
bool holds_nmea_sentence(std::string_view line) noexcept;

}  // namespace shoal::track
