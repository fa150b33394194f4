#pragma once
/// The column names of a track's rows, one table for every reader of them: the CSV reader, the
/// vessels table (`--vessels`) and Python's `shoal.audit` (`shoal.DEFAULT_COLUMNS`).

#include <span>
#include <string>
#include <string_view>

namespace shoal::track {

/// A field of a fix or of its vessel and the column names it is known by (normalised:
/// normalise_column_name), the first present winning.
struct ColumnNames {
    std::string_view field;
    std::span<const std::string_view> names;
};

/// Every field, in this order: id, name, time, lat, lon, heading, cog, sog, a, b, c, d (the AIS
/// dimensions: to bow, to stern, to port, to starboard), draught, length, width, mobile_type,
/// ship_type, nav_status. A time column no name of `time` matches may still be one
/// (is_time_column_name).
std::span<const ColumnNames> column_table() noexcept;

/// The names of `field` (one of column_table's; another is a std::logic_error).
std::span<const std::string_view> column_names(std::string_view field);

/// A header name as matched: lower case, blanks and a leading `#` removed ("# Timestamp" -> "timestamp").
std::string normalise_column_name(std::string_view name);

/// Whether a header name (any case) names the time column: `time`, `timestamp`, `datetime`,
/// `date_time` or `basedatetime`, with or without words that say only how the time is written
/// (`utc`, `gmt`, `z`, `iso`, `iso8601`, `epoch`, `unix`), written apart (`TIMESTAMP_UTC`,
/// `Time (UTC)`, `utc-time`, `epoch_time`) or joined on (`DateTimeUTC`, `TimeUTC`); `utc` alone
/// too. Not `local_time`, `eta` or `date` (a local time or a date is not the fix's UTC time).
bool is_time_column_name(std::string_view name);

}  // namespace shoal::track
