// The rules a row of a table of fixes is read by (track/row_rules.hpp).
#include <shoal/track/row_rules.hpp>

#include <shoal/track/time.hpp>

#include "util/parse_util.hpp"

namespace shoal::track {

std::string not_a_vessel_message(std::string_view mobile_type) { return "not a vessel (Type of mobile " + detail::quoted(mobile_type) + ")"; }

std::string invalid_time_message(std::string_view text) {
    return "time " + detail::quoted(text) + " is not a valid time (ISO 8601, epoch seconds, dd/mm/yyyy hh:mm:ss or hh:mm:ss)";
}

std::string undated_time_message(std::string_view text) {
    return "time " + detail::quoted(text) + " is a time of day without a date (give full times)";
}

std::string implausible_time_message(std::string_view text) {
    return "time " + detail::quoted(text) + " is outside the years " + fix_time_range + " (a wrong unit, or a corrupt field?)";
}

std::string implausible_time_message(double seconds) {
    return "time " + detail::fmt(seconds) + " (seconds since 1970) is outside the years " + fix_time_range + " (a wrong unit, or a corrupt field?)";
}

bool position_problem_text(double lat, double lon, std::string& what) {
    if (!std::isfinite(lat)) {
        what = "latitude " + detail::fmt(lat) + " is not a number";
        return true;
    }
    if (!std::isfinite(lon)) {
        what = "longitude " + detail::fmt(lon) + " is not a number";
        return true;
    }
    if (lat == 91.0) {
        what = "latitude 91 (AIS: not available)";
        return true;
    }
    if (lon == 181.0) {
        what = "longitude 181 (AIS: not available)";
        return true;
    }
    if (std::fabs(lat) > 90.0) {
        what = "latitude " + detail::fmt(lat) + " is outside [-90, 90]";
        return true;
    }
    if (std::fabs(lon) > 180.0) {
        what = "longitude " + detail::fmt(lon) + " is outside [-180, 180]";
        return true;
    }
    return false;
}

std::optional<hull::Dimensions> dims_from_abcd(double a, double b, double c, double d) noexcept {
    for (double v : {a, b, c, d})
        if (!(std::isfinite(v) && v > 0.0)) return std::nullopt;
    return hull::Dimensions{a, b, c, d};
}

std::optional<hull::Dimensions> dims_from_length_width(double length, double width) noexcept {
    if (!(std::isfinite(length) && std::isfinite(width) && length > 0.0 && width > 0.0)) return std::nullopt;
    return hull::Dimensions{length / 2, length / 2, width / 2, width / 2};
}

}  // namespace shoal::track
