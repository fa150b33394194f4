#pragma once
// A double in fixed notation with a given number of decimals, as std::to_chars(fixed, decimals)
// and printf("%.*f") write it (the exact value rounded, ties to even), without their cost: a
// probe's row and a report's coordinates are mostly numbers. The report's coordinates
// (report/geojson_report.cpp) and the probe's rows (io/pose_csv_parse.cpp) write them here.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <system_error>

namespace shoal::detail {

/// The most decimals put_fixed writes.
inline constexpr int max_fixed_decimals = 9;

inline constexpr double fixed_scale[max_fixed_decimals + 1] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
inline constexpr std::uint64_t fixed_unit[max_fixed_decimals + 1] = {1,      10,      100,      1000,      10000,
                                                                     100000, 1000000, 10000000, 100000000, 1000000000};

/// Whether put_fixed writes `v` with `decimals`: 0 to max_fixed_decimals, and |v| * 10^decimals
/// (rounded) under 2^52 (so not NaN or infinite).
inline bool fits_fixed(double v, int decimals) noexcept {
    return decimals >= 0 && decimals <= max_fixed_decimals && std::fabs(v) * fixed_scale[decimals] < 4503599627370496.0;
}

/// `v` with `decimals` digits after the point (and no point for none), "-" first when its sign
/// bit is set ("-0.000" for a negative that rounds to zero, as printf), for `v` that
/// fits_fixed: at most 27 bytes at `at`; returns their end.
inline char* put_fixed(char* at, double v, int decimals) noexcept {
    const double a = std::fabs(v), scale = fixed_scale[decimals];
    // The nearest integer to a * 10^decimals, ties to even, as printf rounds: p = a * scale is
    // rounded, e its exact error (fma). p can only land on a half when a * scale is at or near
    // it (halves are doubles under 2^52), and then e says on which side a * scale is. (p is
    // under 2^52: adding and taking away 2^52 rounds it to the nearest integer, ties to even,
    // in the default rounding mode, as nearbyint does, without a call.)
    const double p = a * scale;
    constexpr double two52 = 4503599627370496.0;
    double r = (p + two52) - two52;
    if (std::fabs(p - r) == 0.5) {
        const double e = std::fma(a, scale, -p);
        if (e != 0) r = e > 0 ? p + 0.5 : p - 0.5;
    }
    const auto n = static_cast<std::uint64_t>(r);
    if (std::signbit(v)) *at++ = '-';
    const std::uint64_t unit = fixed_unit[decimals];
    at = std::to_chars(at, at + 20, n / unit).ptr;
    if (decimals == 0) return at;
    *at++ = '.';
    std::uint64_t frac = n % unit;
    for (int k = decimals - 1; k >= 0; --k, frac /= 10) at[k] = static_cast<char>('0' + frac % 10);
    return at + decimals;
}

/// Appends `v` with `decimals` digits after the point, as std::to_chars(fixed, decimals) writes
/// it: put_fixed where it fits, else std::to_chars ("inf", "nan", huge numbers).
inline void append_fixed(std::string& out, double v, int decimals) {
    if (fits_fixed(v, decimals)) {
        char buf[32];
        out.append(buf, static_cast<std::size_t>(put_fixed(buf, v, decimals) - buf));
        return;
    }
    char buf[400];  // any double in fixed notation with up to 60 decimals
    if (decimals < 0 || decimals > 60) throw std::logic_error("append_fixed: decimals out of range");
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
    if (ec != std::errc()) throw std::logic_error("append_fixed: a number too long to write");
    out.append(buf, end);
}

}  // namespace shoal::detail
