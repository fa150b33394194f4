#pragma once
/// Small text helpers shared by the track readers (internal to src/track).

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>



namespace shoal::track::detail {

inline std::string_view trim(std::string_view s) noexcept {
    // Most fields have no blank at either end (every blank is at most ' '): nothing to look for.
    if (!s.empty() && static_cast<unsigned char>(s.front()) > ' ' && static_cast<unsigned char>(s.back()) > ' ') return s;
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n'))
        s.remove_suffix(1);
    return s;
}

/// A decimal number (leading '+' allowed, "nan"/"inf" read as such); false when `s` is empty
/// or not entirely a number. With `decimal_comma`, "55,84" reads as 55.84.
/// A plain decimal, `-`, 1 to 15 digits, `.` and at least one digit after it (or none, and no
/// `.`), read as its digits over a power of ten: both are exact doubles (under 2^53 and 1e22),
/// so the one division is rounded once, to the double nearest the text, the value
/// std::from_chars gives. False (`out` untouched) for anything else, left to from_chars.
inline bool plain_decimal(std::string_view s, double& out) noexcept {
    static constexpr double powers[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
    const char* p = s.data();
    const char* const end = p + s.size();
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    const char* const first = p;
    std::uint64_t digits = 0;
    for (unsigned d; p != end && (d = static_cast<unsigned char>(*p) - unsigned{'0'}) < 10; ++p) digits = digits * 10 + d;
    const std::size_t before = static_cast<std::size_t>(p - first);
    std::size_t after = 0;
    if (before == 0) return false;
    if (p != end) {
        if (*p != '.') return false;
        const char* const point = ++p;
        for (unsigned d; p != end && (d = static_cast<unsigned char>(*p) - unsigned{'0'}) < 10; ++p) digits = digits * 10 + d;
        after = static_cast<std::size_t>(p - point);
        if (after == 0 || p != end) return false;
    }
    if (before + after > 15) return false;
    const double v = static_cast<double>(digits) / powers[after];
    out = negative ? -v : v;
    return true;
}

inline bool parse_double(std::string_view s, double& out, bool decimal_comma = false) noexcept {
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    if (s.empty()) return false;
    if (plain_decimal(s, out)) return true;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec == std::errc{} && ptr == s.data() + s.size()) return true;
    if (!decimal_comma || s.size() >= 64) return false;
    std::array<char, 64> buf{};
    std::size_t commas = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        buf[i] = s[i] == ',' ? '.' : s[i];
        commas += s[i] == ',' ? 1 : 0;
    }
    if (commas != 1) return false;
    const auto r = std::from_chars(buf.data(), buf.data() + s.size(), out);
    return r.ec == std::errc{} && r.ptr == buf.data() + s.size();
}

/// The file name without folders and the last extension: the id of a one-track file.
inline std::string file_stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

/// Shortest text of a double that reads back the same ("91", "12.5", "nan").
inline std::string fmt(double v) {
    std::array<char, 32> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    return {buf.data(), r.ptr};
}

/// The first `n` bytes of `s` or fewer, not cut inside a UTF-8 character (a message quoting a
/// field goes into the report's JSON).
inline std::string_view utf8_prefix(std::string_view s, std::size_t n) {
    if (s.size() <= n) return s;
    while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
    return s.substr(0, n);
}

/// A field's text for a message: at most 40 bytes (a whole UTF-8 character less), quoted.
inline std::string quoted(std::string_view s) {
    std::string out(1, '\'');  // appended, not "'" + string: GCC 12 -O3 warns falsely (-Wrestrict) on that
    out += utf8_prefix(s, 40);
    out += s.size() > 40 ? "...'" : "'";
    return out;
}

}  // namespace shoal::track::detail
