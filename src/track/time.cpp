#include <shoal/track/time.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>

namespace shoal::track {

namespace {

constexpr std::array<double, 10> pow10{1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

std::string_view trim(std::string_view s) noexcept {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n'))
        s.remove_suffix(1);
    return s;
}

bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }

/// A forward-only reader over a time text.
class Cursor {
public:
    explicit Cursor(std::string_view s) noexcept : m_s(s) {}
    bool done() const noexcept { return m_i >= m_s.size(); }
    char peek() const noexcept { return done() ? '\0' : m_s[m_i]; }
    bool eat(char c) noexcept {
        if (peek() != c) return false;
        ++m_i;
        return true;
    }
    /// Exactly `n` digits.
    bool digits(std::size_t n, int& out) noexcept {
        if (m_i + n > m_s.size()) return false;
        int v = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const char c = m_s[m_i + k];
            if (!is_digit(c)) return false;
            v = v * 10 + (c - '0');
        }
        m_i += n;
        out = v;
        return true;
    }
    /// One or two digits (day and month of day-first dates, hours of some logs).
    bool digits_1_2(int& out) noexcept {
        if (!is_digit(peek())) return false;
        out = m_s[m_i++] - '0';
        if (is_digit(peek())) out = out * 10 + (m_s[m_i++] - '0');
        return true;
    }
    /// `.fff` or `,fff` after the seconds: the fraction (up to 9 digits kept, more ignored).
    bool fraction(double& out) noexcept {
        out = 0.0;
        if (peek() != '.' && peek() != ',') return true;
        ++m_i;
        if (!is_digit(peek())) return false;
        std::int64_t v = 0;
        std::size_t n = 0;
        while (is_digit(peek())) {
            if (n < 9) {
                v = v * 10 + (m_s[m_i] - '0');
                ++n;
            }
            ++m_i;
        }
        out = static_cast<double>(v) / pow10[n];
        return true;
    }
    std::string_view rest() const noexcept { return m_s.substr(std::min(m_i, m_s.size())); }

private:
    std::string_view m_s;
    std::size_t m_i = 0;
};

/// `hh:mm[:ss[.fff]]` into seconds since midnight (validated).
bool clock(Cursor& c, double& out) noexcept {
    int h = 0, mi = 0, s = 0;
    if (!c.digits(2, h) || !c.eat(':') || !c.digits(2, mi)) return false;
    double frac = 0.0;
    if (c.eat(':')) {
        if (!c.digits(2, s) || !c.fraction(frac)) return false;
    }
    if (h > 23 || mi > 59 || s > 59) return false;
    out = h * 3600.0 + mi * 60.0 + s + frac;
    return true;
}

/// A zone designator and nothing after it: none, `Z`, ` UTC`, `+hh:mm`, `+hhmm`, `+hh`.
/// Writes the offset east of UTC in seconds.
bool zone(Cursor& c, double& offset_s) noexcept {
    offset_s = 0.0;
    if (c.done()) return true;
    if (c.eat('Z') || c.eat('z')) return c.done();
    const std::string_view rest = c.rest();
    if (rest == " UTC" || rest == " GMT" || rest == "UTC" || rest == " Z") return true;
    const char sign = c.peek();
    if (sign != '+' && sign != '-') return false;
    c.eat(sign);
    int h = 0, mi = 0;
    if (!c.digits(2, h)) return false;
    if (!c.done()) {
        c.eat(':');
        if (!c.digits(2, mi)) return false;
    }
    if (!c.done() || h > 23 || mi > 59) return false;
    offset_s = (sign == '-' ? -1.0 : 1.0) * (h * 3600.0 + mi * 60.0);
    return true;
}

}  // namespace

bool valid_date(int year, int month, int day) noexcept {
    if (year < 1 || year > 9999 || month < 1 || month > 12 || day < 1) return false;
    static constexpr std::array<int, 12> days{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    const int last = days[static_cast<std::size_t>(month - 1)] + (month == 2 && leap ? 1 : 0);
    return day <= last;
}

// Howard Hinnant's days_from_civil.
std::int64_t days_from_civil(int year, int month, int day) noexcept {
    const std::int64_t y = static_cast<std::int64_t>(year) - (month <= 2 ? 1 : 0);
    const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
    const std::int64_t yoe = y - era * 400;
    const std::int64_t mp = (month + 9) % 12;
    const std::int64_t doy = (153 * mp + 2) / 5 + day - 1;
    const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

std::optional<double> utc_seconds(int year, int month, int day, int hour, int minute, double second) noexcept {
    if (!valid_date(year, month, day) || hour < 0 || hour > 23 || minute < 0 || minute > 59 ||
        !(second >= 0.0 && second < 60.0))
        return std::nullopt;
    return static_cast<double>(days_from_civil(year, month, day)) * seconds_per_day + hour * 3600.0 + minute * 60.0 +
           second;
}

double day_start(double t) noexcept { return std::floor(t / seconds_per_day) * seconds_per_day; }

std::optional<double> parse_iso8601(std::string_view text) noexcept {
    Cursor c(trim(text));
    int y = 0, mo = 0, d = 0;
    if (!c.digits(4, y) || !c.eat('-') || !c.digits(2, mo) || !c.eat('-') || !c.digits(2, d)) return std::nullopt;
    if (!(c.eat('T') || c.eat('t') || c.eat(' '))) return std::nullopt;  // a date alone is not a time
    double tod = 0.0, offset = 0.0;
    if (!clock(c, tod) || !zone(c, offset) || !valid_date(y, mo, d)) return std::nullopt;
    return static_cast<double>(days_from_civil(y, mo, d)) * seconds_per_day + tod - offset;
}

std::optional<double> parse_date(std::string_view text) noexcept {
    Cursor c(trim(text));
    int y = 0, mo = 0, d = 0;
    if (!c.digits(4, y) || !c.eat('-') || !c.digits(2, mo) || !c.eat('-') || !c.digits(2, d) || !c.done() || !valid_date(y, mo, d))
        return std::nullopt;
    return static_cast<double>(days_from_civil(y, mo, d)) * seconds_per_day;
}

std::optional<double> parse_day_first(std::string_view text) noexcept {
    Cursor c(trim(text));
    int d = 0, mo = 0, y = 0;
    if (!c.digits_1_2(d) || !c.eat('/') || !c.digits_1_2(mo) || !c.eat('/') || !c.digits(4, y) || !c.eat(' '))
        return std::nullopt;
    while (c.eat(' ')) {
    }
    double tod = 0.0, offset = 0.0;
    if (!clock(c, tod) || !zone(c, offset) || !valid_date(y, mo, d)) return std::nullopt;
    return static_cast<double>(days_from_civil(y, mo, d)) * seconds_per_day + tod - offset;
}

std::optional<double> parse_epoch(std::string_view text) noexcept {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(v)) return std::nullopt;
    if (v > 1e11) return v / 1000.0;
    if (v > 1e8) return v;
    return std::nullopt;
}

std::optional<double> parse_time_of_day(std::string_view text) noexcept {
    Cursor c(trim(text));
    if (!c.eat('T')) c.eat('t');
    double tod = 0.0;
    if (!clock(c, tod)) return std::nullopt;
    if (!c.eat('Z')) c.eat('z');
    if (!c.done()) return std::nullopt;
    return tod;
}

std::optional<TimeValue> parse_time(std::string_view text) noexcept {
    text = trim(text);
    if (text.size() < 5) return std::nullopt;
    std::optional<double> t;
    if (text.size() >= 10 && text[4] == '-') {
        t = parse_iso8601(text);
    } else if (text[1] == '/' || text[2] == '/') {
        t = parse_day_first(text);
    } else if (text[0] == 'T' || text[0] == 't' || text[2] == ':') {
        if (auto tod = parse_time_of_day(text)) return TimeValue{*tod, true};
        return std::nullopt;
    } else {
        t = parse_epoch(text);
    }
    if (!t) return std::nullopt;
    return TimeValue{*t, false};
}

std::string format_iso8601(double t, int decimals) {
    if (!std::isfinite(t)) return {};
    decimals = std::clamp(decimals, 0, 9);
    const auto scale = static_cast<std::int64_t>(pow10[static_cast<std::size_t>(decimals)]);
    // Whole units of 10^-decimals s, rounded once, so that 59.9996 s becomes the next minute.
    const double scaled = std::round(t * static_cast<double>(scale));
    if (!(std::fabs(scaled) < 9.2e18)) return {};
    const auto ticks = static_cast<std::int64_t>(scaled);
    std::int64_t secs = ticks / scale;
    std::int64_t frac = ticks % scale;
    if (frac < 0) {
        frac += scale;
        secs -= 1;
    }
    std::int64_t days = secs / 86400;
    std::int64_t sod = secs % 86400;
    if (sod < 0) {
        sod += 86400;
        days -= 1;
    }
    // Howard Hinnant's civil_from_days.
    const std::int64_t z = days + 719468;
    const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
    const std::int64_t doe = z - era * 146097;
    const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const std::int64_t mp = (5 * doy + 2) / 153;
    const std::int64_t d = doy - (153 * mp + 2) / 5 + 1;
    const std::int64_t m = mp < 10 ? mp + 3 : mp - 9;
    const std::int64_t y = yoe + era * 400 + (m <= 2 ? 1 : 0);

    // Digits written here (snprintf's "%04lld-%02lld-..." cost most of a microsecond a time,
    // and the report's layers write two times a pose); a year outside 0-9999 as snprintf does.
    char buf[64];
    char* p = buf;
    auto digits = [&p](std::int64_t v, int width) {
        for (int k = width - 1; k >= 0; --k, v /= 10) p[k] = static_cast<char>('0' + v % 10);
        p += width;
    };
    if (y >= 0 && y <= 9999) {
        digits(y, 4);
    } else {
        const int n = std::snprintf(buf, sizeof buf, "%04lld", static_cast<long long>(y));
        p += std::clamp(n, 0, 40);
    }
    *p++ = '-';
    digits(m, 2);
    *p++ = '-';
    digits(d, 2);
    *p++ = 'T';
    digits(sod / 3600, 2);
    *p++ = ':';
    digits(sod / 60 % 60, 2);
    *p++ = ':';
    digits(sod % 60, 2);
    if (frac != 0) {
        *p++ = '.';
        digits(frac, decimals);
    }
    *p++ = 'Z';
    return std::string(buf, p);
}

}  // namespace shoal::track
