#pragma once
/// The rules a row of a table of fixes is read by, whatever holds the table: a CSV file's row
/// (track/csv_reader.hpp) or a DataFrame's row handed over by the Python module. Which rows are
/// no vessel's, which times and positions are refused and in which words, which values of
/// heading, course and speed mean "not available", and which static values (dimensions,
/// draught, ship type) a track takes from its rows. Both readers apply these, so a row one of
/// them refuses the other refuses too, with the same message.

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include <shoal/hull/hull.hpp>

namespace shoal::track {

/// False for the rows of DMA's export that are no vessel's: "Type of mobile" Base Station or AtoN.
inline bool is_vessel_row(std::string_view mobile_type) noexcept { return mobile_type != "Base Station" && mobile_type != "AtoN"; }
/// "not a vessel (Type of mobile 'AtoN')".
std::string not_a_vessel_message(std::string_view mobile_type);

/// "time '...' is not a valid time (ISO 8601, epoch seconds, dd/mm/yyyy hh:mm:ss or hh:mm:ss)".
std::string invalid_time_message(std::string_view text);
/// "time '...' is a time of day without a date (give full times)": a table whose times of day
/// no date completes (the Python module's; a CSV file's take their date from its other rows).
std::string undated_time_message(std::string_view text);
/// "time '...' is outside the years 1980-2099 (a wrong unit, or a corrupt field?)".
std::string implausible_time_message(std::string_view text);
/// The same for a time given as seconds since 1970: "time 1e+12 (seconds since 1970) is outside ...".
std::string implausible_time_message(double seconds);

/// Why a latitude/longitude pair cannot be a position (AIS's "not available" values, out of
/// range, not a number), in `what`; false when it can be.
bool position_problem_text(double lat, double lon, std::string& what);
inline bool position_problem(double lat, double lon, std::string& what) {
    if (std::fabs(lat) <= 90.0 && std::fabs(lon) <= 180.0) return false;  // (NaN compares false: to the full test)
    return position_problem_text(lat, lon, what);
}

/// Heading, COG and SOG as AIS defines their ranges; NAN for "not available" and nonsense.
inline double valid_heading(double h) noexcept {
    if (!(h >= 0.0 && h <= 360.0)) return NAN;  // AIS 511 = not available
    return h == 360.0 ? 0.0 : h;
}
inline double valid_cog(double c) noexcept { return c >= 0.0 && c < 360.0 ? c : NAN; }  // AIS 360 = n/a
inline double valid_sog(double s) noexcept { return s >= 0.0 && s < 102.3 ? s : NAN; }  // AIS 102.3 = n/a

/// A track's static values from its rows: the first row that gives a usable value sets it.
/// Dimensions A, B, C, D (each finite and > 0), with their source's name.
std::optional<hull::Dimensions> dims_from_abcd(double a, double b, double c, double d) noexcept;
inline constexpr const char* dims_from_abcd_source = "A,B,C,D columns";
/// Length and width alone (MarineCadastre): the reference point is not known; taken amidships,
/// the hull reaches half the length fore and aft.
std::optional<hull::Dimensions> dims_from_length_width(double length, double width) noexcept;
inline constexpr const char* dims_from_length_width_source = "Length and Width columns (reference point taken amidships)";
/// A draught (finite, > 0).
inline bool usable_draught(double v) noexcept { return std::isfinite(v) && v > 0.0; }
inline constexpr const char* draught_source = "draught column";
/// The AIS ship type, a whole number 1-255 (0: not available; a text such as DMA's "Cargo" is
/// not the number); -1 when `v` is none.
inline int ship_type_number(double v) noexcept { return v >= 1.0 && v <= 255.0 && v == std::floor(v) ? static_cast<int>(v) : -1; }
inline constexpr const char* ship_type_source = "ship type column";

}  // namespace shoal::track
