#include <shoal/track/nmea_reader.hpp>

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstdio>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "util/input_file.hpp"
#include "util/parse_util.hpp"
#include <shoal/track/row_rules.hpp>
#include "stream_readers.hpp"
#include <shoal/track/ais.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>

namespace shoal::track {

namespace {

constexpr double kmh_per_kn = 1.852;

bool is_alnum_upper(char c) noexcept { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); }

/// Whether a sentence begins at `text[i]`: `$` or `!`, 4 to 6 letters or digits of address, a comma.
bool sentence_at(std::string_view text, std::size_t i) noexcept {
    if (i >= text.size() || (text[i] != '$' && text[i] != '!')) return false;
    std::size_t k = i + 1;
    while (k < text.size() && is_alnum_upper(text[k])) ++k;
    const std::size_t len = k - i - 1;
    return len >= 4 && len <= 6 && k < text.size() && text[k] == ',';
}

/// The line ends of a log. A log whose first line ends in a lone "\r" (written with CR line
/// ends, as some loggers and old Mac programs write: read at "\n" alone it was one line, of
/// which only the first sentence was read, without a word) has its lines end at "\r", "\r\n"
/// or "\n"; any other at "\n" alone, as grep, sed and editors count them (a "\r\r\n" is one
/// line end there). A stream's blocks may cut a "\r\n" in two.
class LineEnds {
public:
    /// The first line end in `piece` at or after `from`: its position (npos: none) and its
    /// length in `length` (2 for "\r\n").
    std::size_t find(std::string_view piece, std::size_t from, std::size_t& length) {
        if (m_cr_lines < 0)  // told by the first line end: CRs not followed by an LF ("\r" last in the piece: taken so)
            if (std::size_t end = piece.find_first_of("\r\n", from); end != std::string_view::npos) {
                while (end < piece.size() && piece[end] == '\r') ++end;
                m_cr_lines = end < piece.size() && piece[end] == '\n' ? 0 : 1;
            }
        length = 1;
        if (m_cr_lines != 1) return piece.find('\n', from);
        const std::size_t end = piece.find_first_of("\r\n", from);
        if (end == std::string_view::npos) return end;
        length = piece[end] == '\r' && end + 1 < piece.size() && piece[end + 1] == '\n' ? 2 : 1;
        m_cr_last = piece[end] == '\r' && end + 1 == piece.size();
        return end;
    }
    /// Whether the next piece begins with the "\n" of a "\r\n" whose "\r" ended the last one
    /// (then it is no line).
    bool ends_last_line(std::string_view piece) {
        if (piece.empty()) return false;
        const bool lf = m_cr_last && piece[0] == '\n';
        m_cr_last = false;
        return lf;
    }

private:
    int m_cr_lines = -1;  ///< 1: lines end at a CR too; 0: at LF alone; -1: no line end seen yet
    bool m_cr_last = false;
};

/// Digits only, as an int.
bool parse_int(std::string_view s, int& out) noexcept {
    s = detail::trim(s);
    if (s.empty()) return false;
    for (const char c : s)
        if (c < '0' || c > '9') return false;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc{} && ptr == s.data() + s.size();
}

/// `hhmmss[.sss]` as seconds since midnight.
bool parse_hhmmss(std::string_view s, double& tod) noexcept {
    s = detail::trim(s);
    int h = 0, m = 0, sec = 0;
    if (s.size() < 6 || !parse_int(s.substr(0, 2), h) || !parse_int(s.substr(2, 2), m) || !parse_int(s.substr(4, 2), sec))
        return false;
    double frac = 0.0;
    if (s.size() > 6) {
        if (s[6] != '.') return false;
        double scale = 0.1;
        for (const char c : s.substr(7)) {
            if (c < '0' || c > '9') return false;
            frac += (c - '0') * scale;
            scale *= 0.1;
        }
    }
    if (h > 23 || m > 59 || sec > 59) return false;
    tod = h * 3600.0 + m * 60.0 + sec + frac;
    return true;
}

/// `ddmm.mmmm` + `N`/`S` (or `dddmm.mmmm` + `E`/`W`) as signed degrees.
bool parse_coordinate(std::string_view value, std::string_view hemisphere, bool latitude, double& out) noexcept {
    double v = 0.0;
    if (!detail::parse_double(value, v) || !(v >= 0.0)) return false;
    const double degrees = std::floor(v / 100.0);
    const double minutes = v - degrees * 100.0;
    out = degrees + minutes / 60.0;
    if (minutes >= 60.0 || out > (latitude ? 90.0 : 180.0)) return false;  // 9000.5 N is past the pole
    hemisphere = detail::trim(hemisphere);
    if (hemisphere == (latitude ? "S" : "W")) {
        out = -out;
    } else if (hemisphere != (latitude ? "N" : "E")) {
        return false;
    }
    return true;
}

/// Splits the sentence body (between `$` and `*`) at commas.
void split_fields(std::string_view body, std::vector<std::string_view>& fields) {
    fields.clear();
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = body.find(',', start);
        if (comma == std::string_view::npos) {
            fields.push_back(body.substr(start));
            return;
        }
        fields.push_back(body.substr(start, comma - start));
        start = comma + 1;
    }
}

class NmeaReader {
public:
    NmeaReader(const std::string& file, const ReadOptions& options)
        : m_file(file), m_options(options), m_ais([this](std::size_t line, const std::string& what) { skip_at(line, what); }) {
        m_out.format = "nmea";
        m_out.report.max_messages = options.max_messages;
        Track& t = m_out.tracks.emplace_back();
        t.id = detail::file_stem(file);
        t.file = file;
    }

    /// The next line of the log (without its line end).
    void feed(std::string_view text) {
        ++m_line;
        line(detail::trim(text));
    }

    /// The next line of the log is longer than shoal::detail::max_line_bytes: skipped, never held.
    void too_long() {
        ++m_line;
        ++m_out.report.rows;
        skip_at(m_line, "longer than " + shoal::detail::size_text(shoal::detail::max_line_bytes) + ", the longest line shoal reads; line",
                false);
    }

    /// After the last line: the tracks and what reading found.
    TrackFile finish() {
        m_ais.finish();
        date_pending();
        ais_summary();
        for (Track& t : m_out.tracks) normalise(t, m_out.report);
        join_own_ship();
        return std::move(m_out);
    }

private:
    std::vector<Fix>& fixes() { return m_out.tracks.front().fixes; }

    void skip(const std::string& what) { skip_at(m_line, what); }
    void skip_at(std::size_t line, const std::string& what, bool sentence = true) {
        m_out.report.skip(m_file + " line " + std::to_string(line) + ": " + what + (sentence ? "; sentence skipped" : " skipped"));
    }

    /// The sentences of a line: more than one when a logger ran them together ("...*6C$GPRMC,...",
    /// a line end lost; before, all but the first were lost without a word). Each after the
    /// first begins at a '$' or '!' that starts a sentence (neither is ever in a field) past the
    /// checksum of the one before, or at the tag block before it.
    void line(std::string_view text) {
        for (;;) {
            const std::size_t first = text.find_first_of("$!");
            if (first == std::string_view::npos) return;
            // Only after the sentence's own checksum: a line that holds no '*' before the next
            // '$' is one sentence, valid by its checksum ("$SDVLW,$SDVLW,,N,...*59", as a real
            // log has it) or not (one cut short before another: its checksum fails, as before;
            // taken alone it would be read without one, its last field cut).
            const std::size_t star = text.find('*', first);
            if (star == std::string_view::npos) return one_sentence(text);
            std::size_t next = star + 1;
            while ((next = text.find_first_of("$!", next)) != std::string_view::npos && !sentence_at(text, next)) ++next;
            if (next == std::string_view::npos) return one_sentence(text);
            std::size_t cut = next;
            if (const std::size_t close = text.find_last_not_of(" \t", next - 1); close > first && text[close] == '\\')
                if (const std::size_t open = text.rfind('\\', close - 1); open != std::string_view::npos && open > first) cut = open;
            one_sentence(text.substr(0, cut));
            text.remove_prefix(cut);
        }
    }

    void one_sentence(std::string_view text) {
        const std::size_t start = text.find_first_of("$!");
        if (start == std::string_view::npos) return;
        std::string_view sentence = text.substr(start);
        ++m_out.report.rows;
        if (sentence.front() == '!') {  // AIS: other vessels (VDM), or this one (VDO) as a track of its MMSI
            if (ais::LineDecoder::is_ais(text)) ais_line(text);
            return;
        }
        std::string_view body;
        if (std::string problem; !ais::checksum_ok(sentence.substr(1), body, problem)) {
            skip(problem);
            return;
        }
        split_fields(body, m_f);
        const std::string_view address = m_f[0];
        if (address == "PGHP") {
            pghp();
            return;
        }
        if (address.size() < 5 || address.size() > 6 || address.front() == 'P') return;  // proprietary
        for (const char c : address)
            if (!is_alnum_upper(c)) return;
        const std::string_view type = address.substr(address.size() - 3);
        if (type == "RMC") rmc();
        else if (type == "GGA") gga();
        else if (type == "GLL") gll();
        else if (type == "HDT") hdt();
        else if (type == "VTG") vtg();
        else if (type == "ZDA") zda();
    }

    std::string_view field(std::size_t i) const noexcept { return i < m_f.size() ? detail::trim(m_f[i]) : std::string_view{}; }

    double number(std::size_t i) const noexcept {
        double v = NAN;
        if (!detail::parse_double(field(i), v)) return NAN;
        return v;
    }

    /// Latitude from fields i, i+1 and longitude from i+2, i+3; false after a skip message.
    bool position(std::size_t i, const char* type, geo::LonLat& p) {
        if (field(i).empty() || field(i + 2).empty()) {
            skip(std::string(type) + " without a position");
            return false;
        }
        if (!parse_coordinate(field(i), field(i + 1), true, p.lat)) {
            skip(std::string(type) + " latitude " + detail::quoted(field(i)) + "," + std::string(field(i + 1).substr(0, 8)) + " is not valid");
            return false;
        }
        if (!parse_coordinate(field(i + 2), field(i + 3), false, p.lon)) {
            skip(std::string(type) + " longitude " + detail::quoted(field(i + 2)) + "," + std::string(field(i + 3).substr(0, 8)) +
                 " is not valid");
            return false;
        }
        return true;
    }

    bool time_of_day(std::size_t i, const char* type, double& tod) {
        if (parse_hhmmss(field(i), tod)) return true;
        skip(field(i).empty() ? std::string(type) + " without a time"
                              : std::string(type) + " time " + detail::quoted(field(i)) + " is not hhmmss");
        return false;
    }

    /// A position at a time of day; `day` from the clock. Same time as the latest fix: one fix.
    void add_fix(std::int64_t day, double tod, geo::LonLat p, double sog_kn, double cog_deg) {
        auto& fx = fixes();
        if (!fx.empty() && day == m_last_day && tod == m_last_tod) {
            Fix& f = fx.back();
            if (std::isnan(f.sog_kn)) f.sog_kn = sog_kn;
            if (std::isnan(f.cog_deg)) f.cog_deg = cog_deg;
            return;
        }
        Fix f;
        f.position = p;
        f.sog_kn = sog_kn;
        f.cog_deg = cog_deg;
        f.line = m_line;
        if (m_clock.has_date())
            f.time_s = m_clock.resolve(day, tod);
        else
            m_pending.push_back({fx.size(), day, tod});
        fx.push_back(f);
        m_last_day = day;
        m_last_tod = tod;
    }

    // The log's clock, which dates the AIS sentences that carry no time of their own: the
    // receiver's time in every RMC, GGA, GLL and ZDA, resolved with the latest date. A void
    // sentence (RMC status V, GGA quality 0, GLL status V: the GPS has no fix) still gives the
    // receiver's time, trusted once a valid time has set the clock and as long as it follows
    // it (a receiver restarted on its default date, 1980-01-06, does not). A sentence of the
    // clock without a usable time (RMC, GGA, ZDA) stops it until the next time: the AIS
    // sentences in between are not dated by an older time (ais_line).

    /// The receiver's clock read at this line: time of day `tod` on day number `day`.
    void clock_at(std::int64_t day, double tod) {
        m_clock_s = m_clock.has_date() ? m_clock.resolve(day, tod) : NAN;
        if (std::isnan(m_clock_s)) m_clock_why = "no date in the log before them (RMC or ZDA with a date)";
        else m_clock_last_s = m_clock_s;
    }
    /// The same with a full date: returns its day number.
    std::int64_t clock_dated(double t) {
        m_clock_s = m_clock_last_s = t;
        return m_clock.date_seen(t);
    }
    /// A sentence of the clock without a usable time: `why` says what it gave.
    void clock_lost(const std::string& why) {
        if (std::isnan(m_clock_s) && !m_clock_why.empty()) return;  // keeps the first cause
        m_clock_s = NAN;
        m_clock_why = "the log's clock stopped at line " + std::to_string(m_line) + " (" + why + ")";
    }
    /// A void sentence's time: `dated` epoch seconds when it has a date, else NAN and the time
    /// of day `tod`. Taken in when it follows the clock (not back, not a day ahead of its last
    /// time), else the clock stops.
    void void_time(double dated, double tod, const char* what) {
        const double t = !std::isnan(dated) ? dated : m_clock.has_date() ? m_clock.resolve(m_clock.peek_day(tod), tod) : NAN;
        if (std::isfinite(m_clock_last_s) && t >= m_clock_last_s - 1.0 && t <= m_clock_last_s + seconds_per_day) {
            if (!std::isnan(dated)) clock_dated(dated);
            else clock_at(m_clock.day_of(tod), tod);
            return;
        }
        if (std::isnan(m_clock_last_s)) {
            clock_lost(std::string(what) + " before any valid time: the receiver's clock may not be set");
        } else {
            clock_lost(std::string(what) + " at " + (std::isnan(t) ? "an undated time" : format_iso8601(t, 0)) +
                       ", which does not follow the log's last time " + format_iso8601(m_clock_last_s, 0));
        }
    }

    /// RMC `ddmmyy` as epoch seconds at time of day `tod`; NAN when it is not a valid date.
    double rmc_date(double tod) const noexcept {
        const std::string_view date = field(9);
        int dd = 0, mm = 0, yy = 0;
        if (date.size() != 6 || !parse_int(date.substr(0, 2), dd) || !parse_int(date.substr(2, 2), mm) ||
            !parse_int(date.substr(4, 2), yy))
            return NAN;
        const int year = yy < 80 ? 2000 + yy : 1900 + yy;
        if (!valid_date(year, mm, dd)) return NAN;
        return static_cast<double>(days_from_civil(year, mm, dd)) * seconds_per_day + tod;
    }

    void rmc() {
        double tod = 0.0;
        std::int64_t day = 0;
        const bool timed = parse_hhmmss(field(1), tod);
        const bool valid = field(2) == "A" && field(12) != "N";
        // A date written but impossible (32 May, 29 February 2023, month 13): neither the fix nor
        // the AIS sentences after it are dated by the log's older date (before: silently).
        if (timed && !field(9).empty() && std::isnan(rmc_date(tod))) {
            clock_lost("RMC of an impossible date " + std::string(detail::quoted(field(9))));
            skip("RMC date " + std::string(detail::quoted(field(9))) +
                 " is not a valid date ddmmyy (the AIS sentences after it are not dated by an older date)");
            return;
        }
        if (!timed) {
            clock_lost("RMC without a time");
        } else if (!valid) {  // the receiver's clock still
            void_time(rmc_date(tod), tod, "a void RMC's time");
        } else if (const double t = rmc_date(tod); std::isnan(t)) {
            day = m_clock.day_of(tod);
            clock_at(day, tod);
        } else {
            day = clock_dated(t);
        }
        const std::string_view status = field(2);
        if (status != "A") {
            skip("RMC status " + detail::quoted(status) + " (no valid fix)");
            return;
        }
        if (field(12) == "N") {
            skip("RMC mode N (no valid fix)");
            return;
        }
        geo::LonLat p;
        if (!time_of_day(1, "RMC", tod) || !position(3, "RMC", p)) return;
        add_fix(day, tod, p, valid_sog(number(7)), valid_cog(number(8)));
    }

    void gga() {
        double tod = 0.0;
        std::int64_t day = 0;
        const bool timed = parse_hhmmss(field(1), tod);
        const std::string_view quality = field(6);
        const bool valid = !quality.empty() && quality != "0";
        if (!timed) {
            clock_lost("GGA without a time");
        } else if (!valid) {
            void_time(NAN, tod, "a void GGA's time");
        } else {
            day = m_clock.day_of(tod);
            clock_at(day, tod);
        }
        if (!valid) {
            skip("GGA fix quality " + detail::quoted(quality) + " (no fix)");
            return;
        }
        geo::LonLat p;
        if (!time_of_day(1, "GGA", tod) || !position(2, "GGA", p)) return;
        add_fix(day, tod, p, NAN, NAN);
    }

    void gll() {
        double tod = 0.0;
        std::int64_t day = 0;
        const bool timed = parse_hhmmss(field(5), tod);
        const bool valid = field(6) != "V" && field(7) != "N";
        if (timed && !valid) {  // (a GLL of NMEA 1.5 has no time: it leaves the clock as it is)
            void_time(NAN, tod, "a void GLL's time");
        } else if (timed) {
            day = m_clock.day_of(tod);
            clock_at(day, tod);
        }
        if (!valid) {
            skip("GLL status V (no valid fix)");
            return;
        }
        geo::LonLat p;
        if (!time_of_day(5, "GLL", tod) || !position(1, "GLL", p)) return;
        add_fix(day, tod, p, NAN, NAN);
    }

    void hdt() {
        const double h = valid_heading(number(1));
        if (std::isnan(h) || fixes().empty()) return;
        Fix& f = fixes().back();
        if (std::isnan(f.heading_deg)) f.heading_deg = h;
    }

    void vtg() {
        double cog = NAN, sog = NAN;
        if (field(2) == "T" || field(2) == "" || field(4) == "M") {  // NMEA 2.x: value,T,value,M,value,N,value,K
            if (field(9) == "N") return;                              // mode: not valid
            cog = number(1);
            sog = number(5);
            if (std::isnan(sog) && std::isfinite(number(7))) sog = number(7) / kmh_per_kn;
        } else {  // NMEA 1.5: cog true, cog magnetic, knots, km/h
            cog = number(1);
            sog = number(3);
        }
        cog = valid_cog(cog);
        sog = valid_sog(sog);
        if (fixes().empty()) return;
        Fix& f = fixes().back();
        if (std::isnan(f.cog_deg)) f.cog_deg = cog;
        if (std::isnan(f.sog_kn)) f.sog_kn = sog;
    }

    void zda() {
        double tod = 0.0;
        if (!parse_hhmmss(field(1), tod)) {  // ZDA gives no fix: nothing to skip, but the clock stops
            clock_lost("ZDA without a time");
            return;
        }
        int d = 0, m = 0, y = 0;
        const bool ok = parse_int(field(2), d) && parse_int(field(3), m) && parse_int(field(4), y);
        if (ok && field(4).size() == 2) y += y < 80 ? 2000 : 1900;  // some devices write a 2-digit year
        if (ok && valid_date(y, m, d)) {
            clock_dated(static_cast<double>(days_from_civil(y, m, d)) * seconds_per_day + tod);
            return;
        }
        // A date written but impossible (day 32, 31 February, year 0 or 99999, not a number): the
        // AIS sentences after it are not dated by the log's older date (before: silently).
        if (!field(2).empty() || !field(3).empty() || !field(4).empty()) {
            const std::string date = std::string(detail::quoted(field(2))) + "," + std::string(detail::quoted(field(3))) + "," +
                                     std::string(detail::quoted(field(4)));
            clock_lost("ZDA of an impossible date " + date);
            skip("ZDA date (day, month, year) " + date + " is not a valid date (the AIS sentences after it are not dated by an older date)");
            return;
        }
        clock_at(m_clock.day_of(tod), tod);
    }

    /// DMA's time header before each AIS sentence: `$PGHP,1,yyyy,mm,dd,hh,mm,ss,ms,...`. One
    /// that is not a time (a field not a number, month 13, hour 25, 30 February) is said, and
    /// the sentences after it are not dated by the header before it.
    void pghp() {
        if (field(1) != "1") return;  // not a time header (type 1 is the only one DMA writes)
        m_ghp_s = NAN;
        m_ghp_why = "the $PGHP header at line " + std::to_string(m_line) + " is not a valid time";
        static constexpr const char* names[7] = {"year", "month", "day", "hour", "minute", "second", "millisecond"};
        static constexpr int high[7] = {9999, 12, 31, 23, 59, 59, 999};
        int v[7] = {};
        for (std::size_t i = 0; i < 7; ++i) {
            if (!parse_int(field(i + 2), v[i])) {
                skip("$PGHP time header: " + std::string(names[i]) + " " + detail::quoted(field(i + 2)) +
                     " is not a number (the AIS sentences after it are not dated by it)");
                return;
            }
        }
        std::string wrong;
        for (std::size_t i = 1; i < 7 && wrong.empty(); ++i)
            if (v[i] > high[i] || (i <= 2 && v[i] < 1)) wrong = std::string(names[i]) + " " + std::to_string(v[i]);
        const auto t = utc_seconds(v[0], v[1], v[2], v[3], v[4], v[5] + v[6] / 1000.0);
        if (!t && wrong.empty()) wrong = "day " + std::to_string(v[2]) + " of month " + std::to_string(v[1]);
        if (!wrong.empty() || !t) {
            char text[64];
            std::snprintf(text, sizeof text, "%04d-%02d-%02d %02d:%02d:%02d.%03d", v[0], v[1], v[2], v[3], v[4], v[5], v[6]);
            skip("$PGHP time header " + std::string(text) + " is not a valid time (" + wrong +
                 "; the AIS sentences after it are not dated by it)");
            return;
        }
        m_ghp_s = *t;
        m_ghp_why.clear();
    }

    Track& vessel(std::uint32_t mmsi) {
        const auto [it, added] = m_vessels.try_emplace(mmsi, m_out.tracks.size());
        if (added) {
            Track& t = m_out.tracks.emplace_back();
            t.id = std::to_string(mmsi);
            t.file = m_file;
        }
        return m_out.tracks[it->second];
    }

    /// A line holding an AIS sentence. Times: the line's own (tag block `c:`, receive time
    /// before the sentence), else the latest `$PGHP`, else the log's clock (the last dated RMC
    /// or ZDA).
    void ais_line(std::string_view text) {
        ais::Decoded d;
        if (!m_ais.line(text, m_line, d)) return;
        const ais::Message& m = d.message;
        if (d.own) own_mmsi(m.mmsi);
        Track& t = vessel(m.mmsi);
        if (t.name.empty() && !m.name.empty()) t.name = m.name;
        if (!t.dims && m.dims) {
            t.dims = m.dims;
            t.dims_source = "AIS static data (message " + std::to_string(m.type) + ")";
        }
        if (std::isnan(t.draught_m) && std::isfinite(m.draught_m)) {
            t.draught_m = m.draught_m;
            t.draught_source = "AIS static data (message 5)";
        }
        if (t.ship_type < 0 && m.ship_type > 0) {  // 0: not available
            t.ship_type = m.ship_type;
            t.ship_type_source = "AIS static data (message " + std::to_string(m.type) + ")";
        }
        if (!m.is_position_report()) return;
        ++m_ais_reports;
        const std::string what = "AIS type " + std::to_string(m.type) + " (MMSI " + t.id + ")";
        if (!m.position) {
            skip_at(d.line, what + ": position not available (lon 181, lat 91, or off the globe)");
            return;
        }
        double time_s = d.time_s;
        if (std::isnan(time_s)) time_s = m_ghp_s;
        if (std::isnan(time_s)) time_s = m_clock_s;
        if (std::isnan(time_s)) {  // said once for the file (ais_summary)
            if (m_ais_undated++ == 0) {
                m_undated_first = d.line;
                m_undated_why = !m_ghp_why.empty() ? m_ghp_why : m_clock_why.empty() ? "before the log's first time" : m_clock_why;
            }
            m_undated_last = d.line;
            return;
        }
        if (!plausible_fix_time(time_s)) {
            skip_at(d.line, what + ": time " + format_iso8601(time_s, 0) + " is outside the years " + fix_time_range);
            return;
        }
        Fix f;
        f.time_s = time_s;
        f.position = *m.position;
        f.sog_kn = m.sog_kn;
        f.cog_deg = m.cog_deg;
        f.heading_deg = m.heading_deg;
        f.nav_status = m.nav_status;
        f.line = d.line;
        t.fixes.push_back(f);
    }

    /// Farther apart than any ship is long (the GPS antenna and the transponder's are on one
    /// hull): the GPS fix and the own AIS report of one time are not one position.
    static constexpr double own_apart_m = 500;

    /// An MMSI of the own ship's AIS messages (!AIVDO).
    void own_mmsi(std::uint32_t mmsi) {
        if (std::find(m_own.begin(), m_own.end(), mmsi) != m_own.end()) return;
        if (m_own.size() < max_own_said) m_own.push_back(mmsi);
        else m_own_more = true;
    }

    /// One vessel, one track: the own ship's GPS fixes (RMC, GGA, GLL: the first track) and its
    /// own AIS reports (!AIVDO, by their MMSI) are one vessel, joined into the MMSI's track in
    /// time order; a time both hold is kept once, as the GPS fix (its heading, COG and SOG filled
    /// from the report when it lacks them). Own reports of more than one MMSI join nothing (the
    /// GPS fixes could be any of them's), and that is said. Run on normalised tracks.
    void join_own_ship() {
        Track& gps = m_out.tracks.front();
        if (m_own.empty() || gps.fixes.empty()) return;
        const std::string mmsis = [&] {
            std::string out;
            for (const std::uint32_t m : m_own) out += (out.empty() ? "" : ", ") + std::to_string(m);
            return out + (m_own_more ? ", ..." : "");
        }();
        if (m_own.size() > 1) {
            m_out.report.messages.push_back(m_file + ": its own AIS reports (!AIVDO) give " + (m_own_more ? "more than " : "") +
                                            std::to_string(m_own.size()) + " MMSIs (" + mmsis + "): its GPS fixes (RMC, GGA, GLL) stay the track '" +
                                            gps.id + "', joined to none of them (they may be one vessel)");
            return;
        }
        Track& ais = vessel(m_own.front());
        Track& own = m_out.tracks.front();  // (vessel() may have grown the list)
        const std::size_t from_gps = own.fixes.size(), from_ais = ais.fixes.size();
        std::vector<Fix> joined;
        joined.reserve(from_gps + from_ais);
        std::size_t both = 0;
        // Times held by both whose positions are farther apart than any ship is long: said (the
        // GPS fix is kept; the transponder's position may be another's).
        std::size_t apart = 0, worst_line = 0;
        double worst_m = 0;
        auto a = own.fixes.begin(), b = ais.fixes.begin();
        while (a != own.fixes.end() || b != ais.fixes.end()) {
            if (b == ais.fixes.end() || (a != own.fixes.end() && a->time_s < b->time_s)) {
                joined.push_back(*a++);
            } else if (a == own.fixes.end() || b->time_s < a->time_s) {
                joined.push_back(*b++);
            } else {  // the same time: the GPS fix, what it lacks from the report
                Fix f = *a++;
                if (const double d = distance_m(f.position, b->position); d > own_apart_m) {
                    ++apart;
                    if (d > worst_m) worst_m = d, worst_line = b->line;
                }
                if (std::isnan(f.heading_deg)) f.heading_deg = b->heading_deg;
                if (std::isnan(f.cog_deg)) f.cog_deg = b->cog_deg;
                if (std::isnan(f.sog_kn)) f.sog_kn = b->sog_kn;
                if (f.nav_status == nav_status_unknown) f.nav_status = b->nav_status;
                ++b;
                joined.push_back(f);
                ++both;
            }
        }
        m_out.report.messages.push_back(m_file + ": the own ship's GPS fixes (RMC, GGA, GLL: " + std::to_string(from_gps) +
                                        ") and its own AIS reports (!AIVDO of MMSI " + mmsis + ": " + std::to_string(from_ais) +
                                        ") are one vessel: one track '" + ais.id + "' of " + std::to_string(joined.size()) + " fixes" +
                                        (both ? ", " + std::to_string(both) + " times held by both kept once (the GPS fix)" : std::string()) +
                                        (apart ? "; at " + std::to_string(apart) + " of them the two are more than " + std::to_string(static_cast<int>(own_apart_m)) +
                                                     " m apart (the most " + std::to_string(static_cast<long long>(std::lround(worst_m))) +
                                                     " m, the AIS report at line " + std::to_string(worst_line) +
                                                     "): the GPS fix kept; is the transponder's position this ship's?"
                                               : std::string()));
        ais.fixes = std::move(joined);
        own.fixes.clear();  // (a track without fixes: read_tracks drops it)
    }

    /// Refuses a log of AIS positions none of which can be dated; says the reports that could
    /// not be dated, once; notes the types not read.
    void ais_summary() {
        std::size_t fixes = 0;
        for (const Track& t : m_out.tracks) fixes += t.fixes.size();
        if (fixes == 0 && m_ais_undated > 0 && m_ais_undated == m_ais_reports)
            throw InputError(m_file + ": AIS position reports without any time source (no tag block c:, receive time before "
                                      "the sentences, $PGHP header or dated RMC/ZDA): the AIS second field alone cannot date a fix");
        if (m_ais_undated > 0)
            m_out.report.skip_all(m_ais_undated,
                                  m_file + ": " + std::to_string(m_ais_undated) + " AIS position report" + (m_ais_undated == 1 ? "" : "s") +
                                      " without a time dropped (line" +
                                      (m_ais_undated == 1 ? " " + std::to_string(m_undated_first)
                                                          : "s " + std::to_string(m_undated_first) + "-" + std::to_string(m_undated_last)) +
                                      "; the first: " + m_undated_why +
                                      "): no tag block c:, receive time, $PGHP header or time of the log's clock (RMC, GGA, ZDA) dates them");
        std::size_t skipped = 0;
        std::string types;
        for (const auto& [type, n] : m_ais.skipped_types()) {
            skipped += n;
            types += (types.empty() ? "" : ", ") + std::to_string(n) + " of type " + std::to_string(type);
        }
        if (skipped > 0)
            m_out.report.messages.push_back(m_file + ": " + std::to_string(skipped) +
                                            " AIS messages of types shoal does not read ignored (" + types + ")");
    }

    void date_pending() {
        if (m_pending.empty()) return;
        double fallback = 0.0;
        if (!m_clock.has_date()) {
            if (m_options.date_s) {
                fallback = day_start(*m_options.date_s);
            } else {
                m_out.report.messages.push_back(
                    m_file + ": no date in the log (no RMC or ZDA with a date): times are times of day only, "
                             "dated 1970-01-01 (give the date to place them)");
            }
        }
        for (const Pending& p : m_pending) fixes()[p.fix].time_s = m_clock.resolve_early(p.day, p.tod, fallback);
    }

    struct Pending {
        std::size_t fix;
        std::int64_t day;
        double tod;
    };

    std::string m_file;
    const ReadOptions& m_options;
    TrackFile m_out;
    std::size_t m_line = 0;
    std::vector<std::string_view> m_f;
    DayClock m_clock;
    std::vector<Pending> m_pending;
    std::int64_t m_last_day = 0;
    double m_last_tod = NAN;
    double m_clock_s = NAN;  ///< the log's clock: the latest time of RMC, GGA, GLL or ZDA; NAN when it has none
    double m_clock_last_s = NAN;  ///< the last time the clock gave (never NAN again once it gave one)
    std::string m_clock_why;  ///< why m_clock_s is NAN, once it has been read
    double m_ghp_s = NAN;    ///< the last $PGHP
    std::string m_ghp_why;   ///< why m_ghp_s is NAN after a $PGHP header that is not a valid time
    ais::LineDecoder m_ais;
    std::unordered_map<std::uint32_t, std::size_t> m_vessels;  ///< MMSI -> index in m_out.tracks
    std::size_t m_ais_reports = 0, m_ais_undated = 0;
    static constexpr std::size_t max_own_said = 4;
    std::vector<std::uint32_t> m_own;  ///< the MMSIs of the own ship's AIS messages (!AIVDO), the first few
    bool m_own_more = false;           ///< and more than those
    std::size_t m_undated_first = 0, m_undated_last = 0;  ///< the lines of the first and the last undated report
    std::string m_undated_why;                            ///< why the first had no time
};

}  // namespace

bool holds_nmea_sentence(std::string_view line) noexcept {
    for (std::size_t i = line.find_first_of("$!"); i != std::string_view::npos; i = line.find_first_of("$!", i + 1))
        if (sentence_at(line, i)) return true;
    return false;
}

TrackFile read_nmea_text(std::string_view text, const std::string& file, const ReadOptions& options) {
    NmeaReader reader(file, options);
    LineEnds ends;
    for (std::size_t pos = 0; pos < text.size();) {
        std::size_t length = 1;
        std::size_t end = ends.find(text, pos, length);
        if (end == std::string_view::npos) end = text.size();
        if (end - pos > shoal::detail::max_line_bytes) reader.too_long();
        else reader.feed(text.substr(pos, end - pos));
        pos = end + length;
    }
    return reader.finish();
}

namespace detail {

TrackFile read_nmea_stream(shoal::detail::InputFile& in, std::string head, bool whole, const ReadOptions& options, std::size_t block) {
    constexpr std::size_t max_line = shoal::detail::max_line_bytes;
    NmeaReader reader(in.path(), options);
    std::string partial;    // the bytes of a line that runs past the end of a block
    bool dropping = false;  // the current line is over max_line: its bytes are not kept
    LineEnds ends;
    auto take = [&](std::string_view chunk) {
        if (ends.ends_last_line(chunk)) chunk.remove_prefix(1);
        while (!chunk.empty()) {
            std::size_t length = 1;
            const std::size_t nl = ends.find(chunk, 0, length);
            const std::string_view part = chunk.substr(0, nl == std::string_view::npos ? chunk.size() : nl);
            if (!dropping && partial.size() + part.size() > max_line) {
                dropping = true;
                std::string().swap(partial);
            }
            if (nl == std::string_view::npos) {
                if (!dropping) partial.append(part);
                return;
            }
            if (dropping) {
                reader.too_long();
            } else if (partial.empty()) {
                reader.feed(part);
            } else {
                partial.append(part);
                reader.feed(partial);
            }
            partial.clear();
            dropping = false;
            chunk.remove_prefix(nl + length);
        }
    };
    take(head);
    std::string().swap(head);
    std::string buffer;
    for (bool eof = whole; !eof;) {
        buffer.clear();
        eof = in.append(buffer, block) < block;
        take(buffer);
    }
    if (dropping) reader.too_long();
    else if (!partial.empty()) reader.feed(partial);
    return reader.finish();
}

}  // namespace detail

TrackFile read_nmea(const std::string& path, const ReadOptions& options) {
    const std::string text = read_file(path);
    return read_nmea_text(text, path, options);
}

}  // namespace shoal::track
