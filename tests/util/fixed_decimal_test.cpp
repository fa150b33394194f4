#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "util/fixed_decimal.hpp"

namespace {

using shoal::detail::append_fixed;
using shoal::detail::fits_fixed;
using shoal::detail::max_fixed_decimals;

std::string printf_fixed(double v, int decimals) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

std::string to_chars_fixed(double v, int decimals) {
    char buf[512];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
    EXPECT_EQ(ec, std::errc());
    return {buf, end};
}

}  // namespace

/// Every number of decimals, on random values of every size, the exact halves of the last
/// decimal (ties to even), their neighbours, signed zeros, negatives that round to zero and
/// either side of the fast path's limit: what glibc's printf and std::to_chars write (two
/// formatters of their own), byte for byte.
TEST(FixedDecimal, WritesWhatPrintfAndToCharsWrite) {
    std::mt19937_64 rng(40);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::size_t fast = 0, halves = 0;
    for (int d = 0; d <= max_fixed_decimals; ++d) {
        std::vector<double> values{0.0, -0.0, 0.5, -0.5, 1.5, 2.5, -2.5, 1e-12, -1e-12, 180.0, -180.0, 90.0, 359.95, 24.525563};
        const double scale = std::pow(10.0, d);
        const double limit = 4503599627370496.0 / scale;  // 2^52 / 10^d
        for (int i = 0; i < 20000; ++i) values.push_back(unit(rng) * std::pow(10.0, i % 30 - 14));
        for (int i = 0; i < 20000; ++i) values.push_back(unit(rng) * 200);  // latitudes, longitudes, headings, clearances
        for (int i = 0; i < 5000; ++i) values.push_back(std::round(unit(rng) * 200 * scale) / scale);  // read from d decimals
        for (int i = 0; i < 5000; ++i) values.push_back(-std::fabs(unit(rng)) * 0.49 / scale);  // "-0.0..."
        // Exact halves of the last decimal: (2j + 1) / 2^(d + 1) times 10^d is (2j + 1) 5^d / 2.
        for (int j = -3000; j < 3000; ++j) {
            const double h = std::ldexp(2.0 * j + 1, -(d + 1));
            values.push_back(h);
            values.push_back(std::nextafter(h, INFINITY));
            values.push_back(std::nextafter(h, -INFINITY));
        }
        for (const double f : {0.25, 0.4999999, 0.5, 0.9999999, 1.0, 1.0000001, 2.0})
            for (const double s : {1.0, -1.0}) {
                values.push_back(s * limit * f);
                values.push_back(std::nextafter(s * limit * f, 0.0));
            }
        for (const double v : values) {
            std::string got;
            append_fixed(got, v, d);
            ASSERT_EQ(got, printf_fixed(v, d)) << "the double " << v << " with " << d << " decimals";
            ASSERT_EQ(got, to_chars_fixed(v, d)) << "the double " << v << " with " << d << " decimals";
            fast += fits_fixed(v, d);
            halves += std::fabs(v * scale - std::round(v * scale)) == 0.5;
        }
    }
    EXPECT_GT(fast, 500000u) << "the fast path hardly taken";
    EXPECT_GT(halves, 30000u) << "too few exact halves to test the ties";
    // What put_fixed cannot write goes to std::to_chars.
    for (const double v : std::vector<double>{INFINITY, -INFINITY, NAN, 1e300, -1e300, 4503599627370496.0}) {
        EXPECT_FALSE(fits_fixed(v, 3)) << v;
        std::string got;
        append_fixed(got, v, 3);
        EXPECT_EQ(got, to_chars_fixed(v, 3)) << v;
    }
}
