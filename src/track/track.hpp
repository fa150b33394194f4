#pragma once
/// A voyage track: time-ordered position fixes of one vessel, as read from any track format.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geo/point.hpp"
#include "hull/hull.hpp"

namespace shoal::track {

/// Which value the heading used for a fix came from (said in the report).
enum class HeadingSource : std::uint8_t {
    heading,    ///< true heading from the source (valid; AIS 511 is not)
    cog,        ///< course over ground, the vessel moving
    positions,  ///< bearing between successive positions, the vessel moving, no COG given
    previous,   ///< held from the previous fix (stopped, or nothing else known)
    none,       ///< nothing known at all (no heading, COG or motion yet): 0 assumed
};
const char* to_string(HeadingSource s) noexcept;

struct Fix {
    double time_s = NAN;             ///< seconds since 1970-01-01T00:00:00Z
    geo::LonLat position;
    double heading_deg = NAN;        ///< true heading from the source; NAN when unknown
    double cog_deg = NAN;            ///< course over ground; NAN when unknown
    double sog_kn = NAN;             ///< speed over ground, knots; NAN when unknown
    std::size_t line = 0;            ///< 1-based line (CSV, NMEA) or point number (GPX, GeoJSON) in the file
    double heading_used_deg = NAN;   ///< set by resolve_headings()
    HeadingSource heading_source = HeadingSource::none;
};

struct Track {
    std::string id;     ///< MMSI, name or track id; the file's stem when it holds one unnamed track
    std::string name;   ///< vessel name when the source gives one
    std::string file;   ///< file it was read from
    std::vector<Fix> fixes;                 ///< sorted by time, duplicates dropped
    std::optional<hull::Dimensions> dims;   ///< AIS A,B,C,D when the source gives all four > 0
    double draught_m = NAN;
};

/// What reading a file found, for the user: counts and the first few problems.
struct ReadReport {
    std::size_t rows = 0;        ///< data rows / sentences / points read
    std::size_t skipped = 0;     ///< bad rows skipped (each also counted in messages, up to a limit)
    std::size_t duplicates = 0;  ///< repeated fixes dropped (same time, same vessel)
    std::size_t reordered = 0;   ///< fixes found out of time order (the track was sorted)
    std::vector<std::string> messages;  ///< "FILE line N: what is wrong; row skipped", the first few
    std::size_t max_messages = 10;
    /// Counts a skipped row and keeps its message while under the limit.
    void skip(const std::string& message);
};

/// Sorts fixes by time (stable), drops exact duplicates in time (counted in `report`).
void normalise(Track& track, ReadReport& report);

/// Heading per fix: true heading where valid, else COG when moving (SOG >= `moving_kn`, or
/// positions moving when SOG is unknown), else the bearing between positions when moving,
/// else the previous heading. Fills heading_used_deg and heading_source.
void resolve_headings(Track& track, double moving_kn = 0.5);

}  // namespace shoal::track
