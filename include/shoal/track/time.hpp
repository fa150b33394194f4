#pragma once
/// Time stamps as track files write them, to and from *epoch seconds*: seconds since
/// 1970-01-01T00:00:00Z, UTC, leap seconds ignored (POSIX time).
///
/// Forms read (leading and trailing blanks ignored):
/// - ISO 8601 with date and time: `2014-08-15T19:00:00`, `2014-08-15 19:00:00.042Z`,
///   `2014-08-15T21:00:00+02:00` (also `+0200`, `+02`, a trailing ` UTC`); no zone = UTC.
///   A date alone is not a time.
/// - Epoch numbers: seconds when > 1e8 (after 1973-03-03), milliseconds when > 1e11.
/// - Day-first `dd/mm/yyyy hh:mm[:ss[.fff]]` (Danish Maritime Authority export), UTC.
/// - Time of day only, `[T]hh:mm[:ss[.fff]][Z]`: the date is missing and the caller supplies it.
/// Impossible values (month 13, hour 25, minute 60, 30 February) are rejected, not wrapped.

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace shoal::track {

inline constexpr double seconds_per_day = 86400.0;

/// A parsed time field. When `date_missing`, `seconds` is the time of day (seconds since
/// midnight, in [0, 86400)) and the caller must supply the date.
struct TimeValue {
    double seconds = NAN;
    bool date_missing = false;
};

/// Any of the forms above; nullopt when `text` is none of them or names an impossible time.
std::optional<TimeValue> parse_time(std::string_view text) noexcept;

/// ISO 8601 date and time (see above); nullopt otherwise.
std::optional<double> parse_iso8601(std::string_view text) noexcept;
/// `dd/mm/yyyy hh:mm[:ss[.fff]]`, UTC; nullopt otherwise.
std::optional<double> parse_day_first(std::string_view text) noexcept;
/// A plain number: epoch seconds when > 1e8, epoch milliseconds when > 1e11; nullopt otherwise.
std::optional<double> parse_epoch(std::string_view text) noexcept;
/// `[T]hh:mm[:ss[.fff]][Z]`: seconds since midnight; nullopt otherwise.
std::optional<double> parse_time_of_day(std::string_view text) noexcept;
/// A day `YYYY-MM-DD` (blanks around it ignored): epoch seconds of its midnight, UTC; nullopt
/// otherwise (for logs whose times carry no date: ReadOptions::date_s).
std::optional<double> parse_date(std::string_view text) noexcept;

/// The times a fix may carry: from 1980-01-01 (before GPS week 0 and AIS) to 2100-01-01, UTC.
/// A dated time outside is a corrupt field or a wrong unit (microseconds read as milliseconds,
/// say) and costs its row; times of day without a date are dated later and not judged here.
inline constexpr double earliest_fix_time_s = 315532800.0;  // 1980-01-01T00:00:00Z
inline constexpr double latest_fix_time_s = 4102444800.0;   // 2100-01-01T00:00:00Z
inline constexpr const char* fix_time_range = "1980-2099";
inline bool plausible_fix_time(double t) noexcept { return t >= earliest_fix_time_s && t < latest_fix_time_s; }

/// True for a real day of the proleptic Gregorian calendar (years 1-9999).
bool valid_date(int year, int month, int day) noexcept;
/// Days from 1970-01-01 to the given date (negative before); no range check.
std::int64_t days_from_civil(int year, int month, int day) noexcept;
/// Epoch seconds of the UTC time; nullopt when any part is out of range
/// (valid_date, hour 0-23, minute 0-59, second in [0, 60)).
std::optional<double> utc_seconds(int year, int month, int day, int hour, int minute, double second) noexcept;
/// Midnight (UTC) of the day holding epoch second `t`.
double day_start(double t) noexcept;

/// `2014-08-15T19:00:00Z`; when `t` rounded to `decimals` (0-9) fraction digits is not a whole
/// second, the fraction follows with exactly `decimals` digits: `2014-08-15T19:00:00.042Z`.
/// Empty string for NaN or infinity.
std::string format_iso8601(double t, int decimals = 3);

/// Dates times of day met in file order (NMEA sentences, `Thh:mm:ss` CSV rows). Each time of
/// day gets a *day number*: 0 at the start, +1 at each midnight rollover (the time of day falls
/// by more than 12 h), and the previous day for a straggler just before midnight. Full times
/// seen along the way (RMC/ZDA dates, dated rows) tie day numbers to dates; times before the
/// first date use that first date.
class DayClock {
public:
    /// Day number of a time of day (seconds since midnight) met at this point of the file.
    std::int64_t day_of(double tod) noexcept {
        if (std::isnan(m_last_tod)) {
            m_last_tod = tod;
            return m_day;
        }
        if (tod < m_last_tod - seconds_per_day / 2) {
            ++m_day;
        } else if (tod > m_last_tod + seconds_per_day / 2) {
            return m_day - 1;  // a late sentence from before midnight
        }
        m_last_tod = tod;
        return m_day;
    }
    /// The day number day_of(tod) would give, without taking the time in.
    std::int64_t peek_day(double tod) const noexcept {
        if (std::isnan(m_last_tod)) return m_day;
        if (tod < m_last_tod - seconds_per_day / 2) return m_day + 1;
        if (tod > m_last_tod + seconds_per_day / 2) return m_day - 1;
        return m_day;
    }
    /// A full time (epoch seconds) met at this point of the file: fixes the date of its day
    /// number. Returns that day number.
    std::int64_t date_seen(double t) noexcept {
        const double midnight = day_start(t);
        const std::int64_t day = day_of(t - midnight);
        m_base = midnight - static_cast<double>(day) * seconds_per_day;
        if (std::isnan(m_first_base)) m_first_base = m_base;
        return day;
    }
    bool has_date() const noexcept { return !std::isnan(m_base); }
    /// Epoch seconds of a time of day on day number `day`, with the latest date known.
    double resolve(std::int64_t day, double tod) const noexcept {
        return m_base + static_cast<double>(day) * seconds_per_day + tod;
    }
    /// The same, for times met before any date: the first date seen, else `fallback_midnight`.
    double resolve_early(std::int64_t day, double tod, double fallback_midnight) const noexcept {
        const double base = std::isnan(m_first_base) ? fallback_midnight : m_first_base;
        return base + static_cast<double>(day) * seconds_per_day + tod;
    }

private:
    std::int64_t m_day = 0;
    double m_last_tod = NAN;
    double m_base = NAN;        ///< midnight of day number 0 per the latest date
    double m_first_base = NAN;  ///< the same per the first date
};

}  // namespace shoal::track
