#pragma once
/// The track readers' entry points for a file already opened (util/input_file.hpp), used by
/// read_tracks after it has recognised the format from the same handle. Internal to src/track.

#include <string>

#include <shoal/track/reader.hpp>
#include "util/input_file.hpp"

namespace shoal::track::detail {

/// Reads a CSV track file from `in` in blocks: `head` holds its first bytes already read
/// (`whole`: all of them). A line over shoal::detail::max_line_bytes is a bad row, dropped
/// without being held; a first line that long is an InputError. Read in blocks of `block`
/// bytes; with ReadOptions::threads >= 2 (and more than `head`), split and parsed on a thread
/// of its own while this one makes the tracks.
PackedTrackFile read_csv_stream(shoal::detail::InputFile& in, std::string head, bool whole, const ReadOptions& options,
                                std::size_t block = std::size_t{1} << 20);

/// Reads an NMEA log from `in` line by line in blocks of `block` bytes (`head`, `whole` as for
/// read_csv_stream): what it holds is the tracks, never the text, so a log of millions of bad
/// lines costs what its good ones do. A line over shoal::detail::max_line_bytes is a skipped
/// line, never held.
TrackFile read_nmea_stream(shoal::detail::InputFile& in, std::string head, bool whole, const ReadOptions& options,
                           std::size_t block = std::size_t{1} << 20);

/// Reads the GPX file GDAL opens at `gdal_path`; `file` names it in messages and track ids.
TrackFile read_gpx_at(const std::string& gdal_path, const std::string& file, const ReadOptions& options);

}  // namespace shoal::track::detail
