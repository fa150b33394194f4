#pragma once
/// A voyage track: time-ordered position fixes of one vessel, as read from any track format.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <shoal/geo/point.hpp>
#include <shoal/hull/hull.hpp>

namespace shoal::track {

/// Which value the heading used for a fix came from (said in the report).
enum class HeadingSource : std::uint8_t {
    heading,    ///< true heading from the source (valid; AIS 511 is not)
    cog,        ///< course over ground, the vessel moving
    positions,  ///< bearing between successive positions, the vessel moving, no COG given
    previous,   ///< held from the previous fix (stopped, or nothing else known)
    none,       ///< nothing known at all (no heading, COG or motion yet): the orientation is unknown
};
const char* to_string(HeadingSource s) noexcept;

/// Where the speed used for a fix came from (said in the report).
enum class SpeedSource : std::uint8_t {
    sog,        ///< speed over ground from the source
    positions,  ///< from the displacement over a window of time (see resolve_motion)
    positions_over_sog,  ///< from positions: the SOG given was belied by them (e.g. 0 while moving)
    none,       ///< a track of one fix: nothing known
};
const char* to_string(SpeedSource s) noexcept;

/// AIS navigational status (ITU-R M.1371 message 1-3, field "navigational status"): 0 under
/// way using engine ... 5 moored, 6 aground ... 15 not defined; `nav_status_unknown` when the
/// source has no such field.
inline constexpr std::uint8_t nav_status_unknown = 255;
inline constexpr std::uint8_t nav_status_at_anchor = 1;
inline constexpr std::uint8_t nav_status_moored = 5;
inline constexpr std::uint8_t nav_status_aground = 6;
/// "under way using engine", "moored", "aground", ...; "" for nav_status_unknown.
const char* nav_status_text(std::uint8_t status) noexcept;
/// The status from a number 0-15 or the text of DMA's export ("Under way using engine",
/// "Moored", "Aground", ...; case-insensitive); nav_status_unknown for anything else.
std::uint8_t parse_nav_status(std::string_view text) noexcept;

struct Fix {
    double time_s = NAN;             ///< seconds since 1970-01-01T00:00:00Z
    geo::LonLat position;
    double heading_deg = NAN;        ///< true heading from the source; NAN when unknown
    double cog_deg = NAN;            ///< course over ground; NAN when unknown
    double sog_kn = NAN;             ///< speed over ground, knots; NAN when unknown
    std::size_t line = 0;            ///< 1-based line (CSV, NMEA, GPX: its tag's) or point number (GeoJSON) in the file
    std::uint8_t nav_status = nav_status_unknown;  ///< AIS navigational status when the source gives it
    /// Set by drop_wild_fixes(): a jump that persists separates this fix from the one before, so
    /// a new piece of track starts here (nothing is swept across the jump), as after a gap.
    bool jump_before = false;
    double heading_used_deg = NAN;   ///< set by resolve_headings()
    HeadingSource heading_source = HeadingSource::none;
    double speed_used_kn = NAN;      ///< set by resolve_motion(): SOG, else from positions
    SpeedSource speed_source = SpeedSource::none;
    /// Set by resolve_motion(): the vessel has stayed within the stop diameter for at least the
    /// stop duration up to this fix (judged from this and earlier fixes only).
    bool stopped = false;
    /// Set by resolve_motion(): the time of the first fix of the longest stay (all fixes within
    /// the stop diameter) that ends at this fix.
    double stay_since_s = NAN;
};

struct Track {
    std::string id;     ///< MMSI, name or track id; the file's stem when it holds one unnamed track
    std::string name;   ///< vessel name when the source gives one
    std::string file;   ///< file it was read from
    std::vector<Fix> fixes;                 ///< sorted by time, duplicates dropped
    std::optional<hull::Dimensions> dims;   ///< AIS A,B,C,D when the source gives all four > 0
    double draught_m = NAN;
    std::string dims_source;     ///< where `dims` came from ("AIS static messages", "vessels file F", ...)
    std::string draught_source;  ///< where `draught_m` came from
    int ship_type = -1;          ///< AIS ship and cargo type 1-255 (ship_type.hpp); -1 not known (AIS 0 "not available" included)
    std::string ship_type_source;  ///< where `ship_type` came from
    /// The value of the exercise column (ReadOptions::exercise_column), "" when none is read.
    /// Tracks are keyed by (exercise, id): one vessel id in two exercises is two tracks.
    std::string exercise;
    /// The role from the role column (ReadOptions::role_column): "trainee", "target", or ""
    /// when none is read.
    std::string role;
};

/// The role a role value names: "trainee" for trainee, own, own ship, own_ship; "target" for
/// target (any case, blanks around ignored); nullptr for anything else.
const char* role_value(std::string_view text) noexcept;

/// What reading a file found, for the user: counts and the first few problems.
struct ReadReport {
    std::size_t rows = 0;        ///< data rows / sentences / points read
    std::size_t skipped = 0;     ///< bad rows skipped (each also counted in messages, up to a limit)
    std::size_t duplicates = 0;  ///< repeated fixes dropped (same time, same vessel)
    std::size_t reordered = 0;   ///< fixes found out of time order (the track was sorted)
    std::vector<std::string> messages;  ///< "FILE line N: what is wrong; row skipped", the first few
    std::size_t max_messages = 10;
    std::size_t skips_said = 0;  ///< skipped rows a message of `messages` tells of (the rest are only counted)
    /// Read from standard input, a pipe or a FIFO: the XXH3-64 of the content read (decompressed)
    /// and its size in bytes, which the part's fingerprints hold for a file that cannot be read
    /// again; none for a file.
    std::optional<std::pair<std::uint64_t, std::size_t>> stream_digest;
    /// Counts a skipped row and keeps its message while under the limit.
    void skip(const std::string& message);
    /// Counts `count` skipped rows that one message tells of (always kept).
    void skip_all(std::size_t count, const std::string& message);
};

/// Sorts fixes by time (stable), drops exact duplicates in time (counted in `report`).
void normalise(Track& track, ReadReport& report);

/// Heading per fix: true heading where valid, else COG when moving (speed_used_kn >= `moving_kn`
/// when resolve_motion() has run; else SOG, else the speed between neighbouring positions),
/// else when moving the course made good (bearing towards the first later fix at least 50 m
/// away among the next 256, else from the latest earlier one), else the previous heading. A fix before
/// any heading is known gets HeadingSource::none (heading_used_deg 0, to be ignored: the
/// orientation is unknown). Fills heading_used_deg and heading_source.
/// The last known heading is not carried across a gap over `max_gap_s` or a jump
/// (Fix::jump_before): after them the orientation is unknown again until seen.
/// `hold_at_rest` false (the real world): a fix not moving with neither heading nor COG gets no
/// heading (HeadingSource::none): a vessel at rest may have swung, whatever its course was.
void resolve_headings(Track& track, double moving_kn = 0.5, double max_gap_s = INFINITY, bool hold_at_rest = true);

/// Great-circle distance in metres (haversine, mean Earth radius).
double distance_m(geo::LonLat a, geo::LonLat b) noexcept;

/// Bounds of distance_m(a, b), its rounding included, without a sine: lower <= distance_m(a, b)
/// <= upper. For the tests that only compare a distance with a limit (wild fixes, the heading's
/// baseline): a bound on the right side of the limit decides the comparison as distance_m would.
/// Lower: R |dlat| (the haversine's first term alone). Upper: R (|dlat| + c |dlon|), the length
/// of a path along a meridian and then along the parallel of the endpoint farther from the
/// equator (a great circle is no longer), c = 1 - x^2/2 + x^4/24 >= cos x at that latitude x,
/// |dlon| the shorter way round. Both widened by 1e-9 of themselves and 1 micrometre, far beyond
/// the rounding of either computation. {0, INFINITY} (nothing proved) when a latitude is beyond a
/// pole, the longitudes are more than 360 degrees apart, a value is not a number, or the path is
/// over 0.9 of half the circumference (near the antipode the haversine rounds by decimetres).
struct DistanceBounds {
    double lower = 0;
    double upper = INFINITY;
};
DistanceBounds distance_bounds_m(geo::LonLat a, geo::LonLat b) noexcept;

}  // namespace shoal::track
