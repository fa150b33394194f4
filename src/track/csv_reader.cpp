#include <shoal/track/csv_reader.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <thread>
#include <unordered_map>

#include "util/parse_util.hpp"
#include "track/stream_readers.hpp"
#include <shoal/track/row_rules.hpp>
#include <shoal/track/track_table.hpp>
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>

namespace shoal::track {

using detail::trim;

std::string to_utf8(std::string_view text) {
    // Validate UTF-8 (no overlongs or surrogates needed for this purpose: structure only).
    bool valid = true;
    for (std::size_t i = 0; i < text.size() && valid;) {
        const auto c = static_cast<unsigned char>(text[i]);
        std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
        if (len == 0 || (len == 2 && c < 0xC2) || i + len > text.size()) {
            valid = false;
            break;
        }
        for (std::size_t k = 1; k < len; ++k)
            if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) valid = false;
        i += len;
    }
    if (valid) return std::string(text);
    std::string out;
    out.reserve(text.size() * 2);
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x80) {
            out += ch;
        } else {
            out += static_cast<char>(0xC0 | (c >> 6));
            out += static_cast<char>(0x80 | (c & 0x3F));
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Tracks

namespace {

constexpr std::size_t absent = static_cast<std::size_t>(-1);

struct Columns {
    std::size_t id = absent, name = absent, time = absent, lat = absent, lon = absent;
    std::size_t heading = absent, cog = absent, sog = absent;
    std::array<std::size_t, 4> dims{absent, absent, absent, absent};
    std::size_t draught = absent, mobile_type = absent, nav_status = absent;
    std::size_t ship_type = absent;  ///< AIS ship type as a number (MarineCadastre's VesselType); DMA's text is not read
    std::size_t length = absent, width = absent;  ///< MarineCadastre's Length and Width, metres
    std::size_t exercise = absent, role = absent;  ///< ReadOptions::exercise_column, role_column
    std::size_t required = 0;  ///< fields a row needs: 1 + the largest required index
};

std::size_t find_column(const std::vector<std::string>& names, std::span<const std::string_view> candidates) {
    for (const std::string_view c : candidates)
        for (std::size_t i = 0; i < names.size(); ++i)
            if (names[i] == c) return i;
    return absent;
}

std::string join(const std::vector<std::string_view>& fields) {
    std::string s;
    for (std::size_t i = 0; i < fields.size() && i < 30; ++i) {  // at most 30 fields of 40 bytes: one line
        if (i) s += ',';
        s += detail::utf8_prefix(fields[i], 40);
        if (fields[i].size() > 40) s += "...";
    }
    return s;
}

Columns map_columns(const std::vector<std::string_view>& header, const std::string& file, const ReadOptions& options) {
    std::vector<std::string> names;
    names.reserve(header.size());
    for (const auto h : header) names.push_back(normalise_column_name(h));
    Columns c;
    c.id = find_column(names, column_names("id"));  // mmsi before a possible row id
    c.name = find_column(names, column_names("name"));
    if (c.id == absent) c.id = c.name;
    // The usual names first, in this order (a file with both "time" and "timestamp" keeps its
    // "time"), then the first column any spelling of a time names (is_time_column_name).
    c.time = find_column(names, column_names("time"));
    for (std::size_t i = 0; i < names.size() && c.time == absent; ++i)
        if (is_time_column_name(names[i])) c.time = i;
    c.lat = find_column(names, column_names("lat"));
    c.lon = find_column(names, column_names("lon"));
    c.heading = find_column(names, column_names("heading"));
    c.cog = find_column(names, column_names("cog"));
    c.sog = find_column(names, column_names("sog"));
    c.dims = {find_column(names, column_names("a")), find_column(names, column_names("b")),
              find_column(names, column_names("c")), find_column(names, column_names("d"))};
    if (std::find(c.dims.begin(), c.dims.end(), absent) != c.dims.end()) c.dims = {absent, absent, absent, absent};
    c.draught = find_column(names, column_names("draught"));
    c.length = find_column(names, column_names("length"));
    c.width = find_column(names, column_names("width"));
    c.mobile_type = find_column(names, column_names("mobile_type"));
    c.ship_type = find_column(names, column_names("ship_type"));
    c.nav_status = find_column(names, column_names("nav_status"));

    std::string missing;
    if (c.time == absent) missing = "time (time, timestamp, datetime or basedatetime, in any case, with or without utc, gmt, epoch: TIMESTAMP_UTC, Time (UTC))";
    else if (c.lat == absent) missing = "latitude (lat, latitude)";
    else if (c.lon == absent) missing = "longitude (lon, lng, long, longitude)";
    if (!missing.empty())
        throw InputError(file +
                         ": not a track format shoal reads (CSV with a header, GPX, GeoJSON, NMEA 0183): "
                         "the header has no " + missing + " column; header: " + join(header));
    // Exercise mode: the columns named by the user must be there.
    auto named = [&](const std::string& wanted, const char* what, const char* field) {
        if (wanted.empty()) return absent;
        const std::string n = normalise_column_name(wanted);
        const std::string_view wanted_name[] = {n};
        const std::size_t at = find_column(names, wanted_name);
        if (at == absent)
            throw InputError(file + ": the header has no column '" + wanted + "', the " + what + " column (" + field + "); header: " + join(header));
        return at;
    };
    c.exercise = named(options.exercise_column, "exercise", "ReadOptions::exercise_column");
    c.role = named(options.role_column, "role", "ReadOptions::role_column");
    c.required = 1 + std::max({c.time, c.lat, c.lon, c.id == absent ? 0 : c.id, c.exercise == absent ? 0 : c.exercise, c.role == absent ? 0 : c.role});
    return c;
}

/// A fix waiting for a date: its time of day and day number.
struct Pending {
    std::size_t track, fix;
    std::int64_t day;
    double tod;
};

/// The fields that give a vessel's data (name, dimensions, draught, ship type); a row keeps
/// those the file has, in this order (CsvRowParser::vessel_slot).
enum VesselField : unsigned { vessel_name, vessel_a, vessel_b, vessel_c, vessel_d, vessel_length, vessel_width, vessel_draught, vessel_ship_type, vessel_fields };

constexpr std::size_t no_skip = static_cast<std::size_t>(-1);

/// What one record says as far as it can be told without the records before it: a bad row's
/// message, or its fix, vessel and fields. Its views point into its ParsedBlock.
struct ParsedRow {
    double seconds = 0;          ///< the time read: epoch seconds, or of the day when date_missing
    bool date_missing = false;
    bool long_row = false;       ///< over the line limit (a bad row, said after its fields' problems)
    std::size_t line = 0;
    geo::LonLat position;
    std::string_view heading, cog, sog, nav_status;  ///< fields, empty where the file has no such column
    std::string_view id, exercise;
    const char* role = nullptr;  ///< role_value() of the role column; null when not read
    std::size_t skip = no_skip;  ///< a bad row: its message in ParsedBlock::skips
    std::size_t quoted_line_ends = 0;  ///< line ends inside its quoted fields (CsvSplitter::quoted_line_ends)
};

/// The records read from one block of a CSV file, in file order: what the thread that splits
/// and parses hands to the one that assembles tracks.
struct ParsedBlock {
    std::string text;               ///< the block's bytes (the rows' views point into them)
    std::deque<std::string> owned;  ///< fields not in `text` (unescaped, or of a long record)
    std::vector<ParsedRow> rows;
    /// The vessel fields of every row not skipped by the parser, CsvRowParser::vessel_count()
    /// a row, row after row.
    std::vector<std::string_view> vessel;
    std::vector<std::string> skips;
    void clear() {
        text.clear();
        owned.clear();
        rows.clear();
        vessel.clear();
        skips.clear();
    }
};

/// Splits a CSV track file given whole or in blocks (see CsvSplitter) into records and parses
/// each into a ParsedRow: feed() each block. What a row means for its track (which track, its
/// date, role, vessel data) is CsvTrackAssembler's, which takes the blocks in order.
class CsvRowParser {
public:
    CsvRowParser(const std::string& file, const ReadOptions& options) : m_file(file), m_options(options) {}

    /// Reads the records `text` holds into `out`; returns the bytes taken (the rest must come
    /// again, followed by more, in the next call). The first text must hold the first line, or
    /// be `complete` (the whole file, or its last block). The rows' views point into `text`,
    /// or into `out`.
    std::size_t feed(std::string_view text, bool complete, ParsedBlock& out) {
        if (m_split) m_split->more(text, complete);
        else m_split.emplace(text, complete);
        std::vector<std::string_view>& f = m_fields;
        if (!m_header_read) {
            if (m_split->separator() == '\0' || !m_split->next(f)) {
                if (m_split->separator() != '\0' && !complete) return m_split->consumed();  // a header going on
                throw InputError(m_file + ": not a track format shoal reads (CSV with a header, GPX, GeoJSON, NMEA 0183)" +
                                 (m_split->separator() == '\0' ? ": the first line has no ',', ';' or tab" : ""));
            }
            m_cols = map_columns(f, m_file, m_options);
            m_header_fields = f.size();
            m_decimal_comma = m_split->separator() != ',';
            m_header_read = true;
            const std::array<std::size_t, vessel_fields> cols{m_cols.name,   m_cols.dims[0], m_cols.dims[1], m_cols.dims[2],   m_cols.dims[3],
                                                              m_cols.length, m_cols.width,   m_cols.draught, m_cols.ship_type};
            for (unsigned k = 0; k < vessel_fields; ++k) {
                if (cols[k] == absent) continue;
                m_vessel_slot[k] = m_vessel_cols.size();
                m_vessel_cols.push_back(cols[k]);
            }
        }
        // A record over the line limit is a bad row wherever it lies, whole in a block or at the
        // end of the file without a line end (the stream reader catches longer ones unheld).
        // (consumed() is the position in `text`; blank lines before a record are not its own.)
        for (std::size_t from = m_split->consumed(); m_split->next(f); from = m_split->consumed()) {
            std::string_view rec = text.substr(from, m_split->consumed() - from);
            while (!rec.empty() && (rec.front() == '\n' || rec.front() == '\r')) rec.remove_prefix(1);
            if (!rec.empty() && rec.back() == '\n') rec.remove_suffix(1);
            if (!rec.empty() && rec.back() == '\r') rec.remove_suffix(1);
            m_long_row = rec.size() > shoal::detail::max_line_bytes;
            m_quoted_line_ends = m_split->quoted_line_ends();
            if (m_split->quote_not_closed()) skip(out, std::string(quote_not_closed_message));
            else if (const std::size_t nul = rec.find('\0'); nul != std::string_view::npos)  // (an id with one was a vessel of its own)
                skip(out, "a NUL byte at its byte " + std::to_string(nul + 1) + ": a damaged line");
            else parse(f, m_split->unescaped(), out);
            m_quoted_line_ends = 0;
            m_long_row = false;
        }
        return m_split->consumed();
    }

    bool header_read() const noexcept { return m_header_read; }
    char separator() const noexcept { return m_split ? m_split->separator() : ','; }
    /// The header's columns and its decimal comma (set by the first feed()).
    const Columns& columns() const noexcept { return m_cols; }
    /// How many vessel fields the file has (each row's share of ParsedBlock::vessel), and where
    /// field `w` lies in a row's share (`absent`: the file has no such column).
    std::size_t vessel_count() const noexcept { return m_vessel_cols.size(); }
    std::size_t vessel_slot(VesselField w) const noexcept { return m_vessel_slot[w]; }
    bool decimal_comma() const noexcept { return m_decimal_comma; }

    /// A record longer than the line limit, its fields cut short: a bad row, reported with its
    /// first problem, else as too long (its line is the pending record's: the splitter stopped
    /// before it).
    void long_record(const std::vector<std::string>& fields, bool quote_not_closed, ParsedBlock& out) {
        if (quote_not_closed) {
            skip(out, std::string(quote_not_closed_message));
            return;
        }
        std::vector<std::string_view> f;
        for (const std::string& s : fields) f.push_back(out.owned.emplace_back(s));
        m_long_row = true;
        parse(f, false, out);  // the fields are in `out` already
        m_long_row = false;
    }

private:
    void skip(ParsedBlock& out, const std::string& what) {
        out.rows.emplace_back().skip = out.skips.size();
        out.skips.push_back(m_file + " line " + std::to_string(m_split->line()) + ": " + what + "; row skipped");
    }

    /// Field `col` (empty when absent), kept in `out` when `copy` (a record whose unescaped
    /// fields live in the splitter only until its next record).
    [[gnu::always_inline]] static std::string_view field(const std::vector<std::string_view>& f, std::size_t col, bool copy, ParsedBlock& out) {
        if (col >= f.size() || f[col].empty()) return {};
        return copy ? keep(f[col], out) : f[col];
    }
    [[gnu::noinline]] static std::string_view keep(std::string_view v, ParsedBlock& out) { return out.owned.emplace_back(v); }

    /// Record `f`; `copy`: its fields do not outlive the splitter's next record.
    void parse(const std::vector<std::string_view>& f, bool copy, ParsedBlock& out) {
        if (f.size() < m_cols.required) {
            skip(out, "has " + std::to_string(f.size()) + " fields, the header needs " + std::to_string(m_cols.required));
            return;
        }
        // More fields than the header names, one of them not blank: which field is which is
        // not known (a decimal comma in a comma-separated file read "60,24" as two fields; a
        // name with a comma shifted every field after it). Blank ones (a trailing separator)
        // are nothing. (A record over the line limit, its fields cut short, is said as that.)
        if (!m_long_row)
            for (std::size_t i = m_header_fields; i < f.size(); ++i)
                if (!detail::trim(f[i]).empty()) {
                    skip(out, "has " + std::to_string(f.size()) + " fields, the header " + std::to_string(m_header_fields) +
                                  (m_decimal_comma ? " (a separator inside an unquoted field?)"
                                                   : " (a decimal comma in a comma-separated file, or a comma inside an unquoted field?)"));
                    return;
                }
        if (m_cols.mobile_type != absent && m_cols.mobile_type < f.size()) {
            const std::string_view type = f[m_cols.mobile_type];
            if (!is_vessel_row(type)) {
                skip(out, not_a_vessel_message(type));
                return;
            }
        }
        if (m_cols.id != absent && f[m_cols.id].empty()) {
            skip(out, "no vessel id");
            return;
        }
        if (m_cols.exercise != absent && f[m_cols.exercise].empty()) {
            skip(out, "no exercise (column '" + m_options.exercise_column + "' is empty)");
            return;
        }
        const char* role = nullptr;
        if (m_cols.role != absent) {
            role = role_value(f[m_cols.role]);
            if (!role) {
                skip(out, f[m_cols.role].empty() ? "no role (column '" + m_options.role_column + "' is empty)"
                                                 : "role " + detail::quoted(f[m_cols.role]) + " (column '" + m_options.role_column +
                                                       "') is neither trainee (own, own ship) nor target");
                return;
            }
        }
        const std::string_view time_text = f[m_cols.time];
        if (time_text.empty()) {
            skip(out, "no time");
            return;
        }
        const auto time = parse_time(time_text);
        if (!time) {
            skip(out, invalid_time_message(time_text));
            return;
        }
        if (!time->date_missing && !plausible_fix_time(time->seconds)) {
            skip(out, implausible_time_message(time_text));
            return;
        }
        geo::LonLat position;
        if (!detail::parse_double(f[m_cols.lat], position.lat, m_decimal_comma)) {
            skip(out, f[m_cols.lat].empty() ? "no latitude" : "latitude " + detail::quoted(f[m_cols.lat]) + " is not a number");
            return;
        }
        if (!detail::parse_double(f[m_cols.lon], position.lon, m_decimal_comma)) {
            skip(out, f[m_cols.lon].empty() ? "no longitude" : "longitude " + detail::quoted(f[m_cols.lon]) + " is not a number");
            return;
        }
        if (std::string what; position_problem(position.lat, position.lon, what)) {
            skip(out, what);
            return;
        }
        // The other numbers are read by the assembling thread (add()), which has less to do.
        ParsedRow& r = out.rows.emplace_back();
        r.seconds = time->seconds;
        r.date_missing = time->date_missing;
        r.position = position;
        r.line = m_split->line();
        r.long_row = m_long_row;
        r.quoted_line_ends = m_quoted_line_ends;
        r.heading = field(f, m_cols.heading, copy, out);
        r.cog = field(f, m_cols.cog, copy, out);
        r.sog = field(f, m_cols.sog, copy, out);
        r.nav_status = field(f, m_cols.nav_status, copy, out);
        if (m_cols.id != absent) r.id = field(f, m_cols.id, copy, out);
        if (m_cols.exercise != absent) r.exercise = field(f, m_cols.exercise, copy, out);
        r.role = role;
        const std::size_t at = out.vessel.size();
        out.vessel.resize(at + m_vessel_cols.size());
        std::string_view* v = out.vessel.data() + at;
        for (const std::size_t col : m_vessel_cols) *v++ = field(f, col, copy, out);
    }

    std::optional<CsvSplitter> m_split;
    std::vector<std::string_view> m_fields;
    std::size_t m_quoted_line_ends = 0;  // of the record being parsed
    bool m_long_row = false;
    bool m_header_read = false;
    const std::string& m_file;
    const ReadOptions& m_options;
    Columns m_cols;
    std::vector<std::size_t> m_vessel_cols;  ///< the columns of the vessel fields the file has, in VesselField order
    std::array<std::size_t, vessel_fields> m_vessel_slot = [] {
        std::array<std::size_t, vessel_fields> a{};
        a.fill(absent);
        return a;
    }();
    bool m_decimal_comma = false;
    std::size_t m_header_fields = 0;  ///< the header's fields: a row with more that are not blank is a bad row
};

/// Makes the tracks of a CSV file from its parsed records, taken in file order (apply() each
/// block), then finish(). Fixes are packed as they come.
class CsvTrackAssembler {
public:
    /// `parser`'s columns are read once its first block (the header's) has been applied.
    CsvTrackAssembler(const std::string& file, const ReadOptions& options, const CsvRowParser& parser)
        : m_file(file), m_options(options), m_parser(parser) {
        m_out.format = "csv";
        m_out.report.max_messages = options.max_messages;
    }

    void apply(const ParsedBlock& b) {
        if (b.rows.empty()) return;  // (a header still going on: the parser's columns are not set)
        const std::size_t k = m_parser.vessel_count();
        const std::string_view* vessel = b.vessel.data();
        for (const ParsedRow& r : b.rows) {
            ++m_out.report.rows;
            if (r.skip != no_skip) {
                m_out.report.skip(b.skips[r.skip]);
            } else {
                if (r.quoted_line_ends > 0 && !r.long_row && m_quoted_rows++ == 0) m_first_quoted = {r.line, r.quoted_line_ends};
                add(r, vessel);
                vessel += k;
            }
        }
    }

    PackedTrackFile finish() {
        date_pending();
        // Rows that held line ends inside quotes are read as RFC 4180 says, each one row: said,
        // since a stray quote closed by another a few lines on joins those rows so.
        if (m_quoted_rows > 0)
            m_out.report.messages.push_back(m_file + ": " + std::to_string(m_quoted_rows) + (m_quoted_rows == 1 ? " row holds" : " rows hold") +
                                            " line ends inside quotes, each read as one row (the first on line " + std::to_string(m_first_quoted.first) +
                                            ", over " + std::to_string(m_first_quoted.second + 1) +
                                            " lines); a stray quote (\") closed by another on a later line joins the rows between so");
        for (const RoleConflict& c : m_role_conflicts) {
            PackedTrack& t = m_out.tracks[c.track];
            m_out.report.messages.push_back(m_file + ": track '" + t.id + "'" + (t.exercise.empty() ? "" : " of exercise '" + t.exercise + "'") +
                                            ": its rows disagree on the role (" + t.role + " on line " + std::to_string(c.first_line) + ", " +
                                            c.other + " on line " + std::to_string(c.other_line) + " of column '" + m_options.role_column +
                                            "'): it is taken as a target");
            t.role = "target";
        }
        normalise(m_out.tracks, m_out.report, m_options.threads);
        return std::move(m_out);
    }

private:
    const Columns& cols() const noexcept { return m_parser.columns(); }

    double number(std::string_view text) const {
        double v = NAN;
        if (!detail::parse_double(text, v, m_parser.decimal_comma())) return NAN;
        return v;
    }

    void skip(std::size_t line, const std::string& what) {
        m_out.report.skip(m_file + " line " + std::to_string(line) + ": " + what + "; row skipped");
    }

    /// Row `r`, whose vessel fields are `vessel` (ParsedBlock::vessel).
    void add(const ParsedRow& r, const std::string_view* vessel) {
        const Columns& c = cols();
        Fix fix;
        fix.position = r.position;
        if (c.heading != absent) fix.heading_deg = valid_heading(number(r.heading));
        if (c.cog != absent) fix.cog_deg = valid_cog(number(r.cog));
        if (c.sog != absent) fix.sog_kn = valid_sog(number(r.sog));
        if (c.nav_status != absent) fix.nav_status = parse_nav_status(r.nav_status);
        fix.line = r.line;
        if (r.long_row) {
            skip(r.line, "longer than " + shoal::detail::size_text(shoal::detail::max_line_bytes) + ", the longest line shoal reads");
            return;
        }
        const std::size_t ti = track_for(r.id, r.exercise);
        PackedTrack& t = m_out.tracks[ti];
        vessel_data(t, vessel);
        if (r.role) take_role(ti, r.role, fix.line);
        if (m_clocks.size() <= ti) m_clocks.resize(ti + 1);
        DayClock& clock = m_clocks[ti];
        if (!r.date_missing) {
            clock.date_seen(r.seconds);
            if (std::isnan(m_first_date)) m_first_date = day_start(r.seconds);
            fix.time_s = r.seconds;
        } else {
            const std::int64_t day = clock.day_of(r.seconds);
            if (clock.has_date())
                fix.time_s = clock.resolve(day, r.seconds);
            else
                m_pending.push_back({ti, t.size(), day, r.seconds});
        }
        t.push_back(fix);
    }

    /// The track of (exercise, id); `exercise` is "" unless the exercise column is read.
    std::size_t track_for(std::string_view id, std::string_view exercise) {
        if (!m_table) m_table.emplace(m_out.tracks, m_file, cols().id != absent, cols().exercise != absent);
        return m_table->track_for(id, exercise);
    }

    void vessel_data(PackedTrack& t, const std::string_view* fields) {
        auto at = [&](VesselField w) {
            const std::size_t k = m_parser.vessel_slot(w);
            return k == absent ? std::string_view{} : fields[k];
        };
        // Each number parsed only while the track still lacks what it gives.
        const Columns& c = cols();
        if (c.name != absent && t.name.empty()) offer_name(t, at(vessel_name));
        if (c.dims[0] != absent && !t.dims)
            offer_dims(t, dims_from_abcd(number(at(vessel_a)), number(at(vessel_b)), number(at(vessel_c)), number(at(vessel_d))),
                       dims_from_abcd_source);
        if (m_options.hull_from_length_width && c.length != absent && c.width != absent && !t.dims)
            offer_dims(t, dims_from_length_width(number(at(vessel_length)), number(at(vessel_width))), dims_from_length_width_source);
        if (c.draught != absent && std::isnan(t.draught_m)) offer_draught(t, number(at(vessel_draught)));
        if (c.ship_type != absent && t.ship_type < 0) offer_ship_type(t, number(at(vessel_ship_type)));
    }

    /// A row's role for track `ti` (its row on `line`): the first gives the track's; a
    /// different one later is a disagreement, said (and the track taken as a target) in finish().
    void take_role(std::size_t ti, const char* role, std::size_t line) {
        PackedTrack& t = m_out.tracks[ti];
        if (m_role_lines.size() <= ti) m_role_lines.resize(ti + 1, 0);
        if (t.role.empty()) {
            t.role = role;
            m_role_lines[ti] = line;
            return;
        }
        if (t.role == role || m_role_lines[ti] == absent) return;  // absent: said already, with the first row that disagreed
        m_role_conflicts.push_back({ti, m_role_lines[ti], line, role});
        m_role_lines[ti] = absent;
    }

    /// Times of day met before their vessel's first dated row take that row's date; a vessel
    /// without dated rows takes the file's first date, else ReadOptions::date_s, else 1970-01-01.
    void date_pending() {
        if (m_pending.empty()) return;
        double fallback = m_first_date;
        if (std::isnan(fallback)) {
            if (m_options.date_s) {
                fallback = day_start(*m_options.date_s);
            } else {
                fallback = 0.0;
                m_out.report.messages.push_back(
                    m_file + ": times are times of day only and the file has no date; they are dated 1970-01-01 "
                             "(give the date to place them)");
            }
        }
        for (const Pending& p : m_pending) {
            PackedTrack& t = m_out.tracks[p.track];
            Fix f = t.fix(p.fix);
            f.time_s = m_clocks[p.track].resolve_early(p.day, p.tod, fallback);
            t.set(p.fix, f);
        }
    }

    const std::string& m_file;
    const ReadOptions& m_options;
    const CsvRowParser& m_parser;
    PackedTrackFile m_out;
    std::size_t m_quoted_rows = 0;                              // rows that held line ends inside quotes
    std::pair<std::size_t, std::size_t> m_first_quoted{0, 0};  // the first: its line and line ends
    std::optional<TrackTable> m_table;  ///< made at the first row, once the header has given the columns
    struct RoleConflict {
        std::size_t track, first_line, other_line;
        std::string other;
    };
    std::vector<std::size_t> m_role_lines;  ///< per track: the line that gave its role
    std::vector<RoleConflict> m_role_conflicts;
    std::vector<DayClock> m_clocks;  ///< per track: rows of one vessel come from one recording
    double m_first_date = NAN;       ///< midnight of the file's first dated row
    std::vector<Pending> m_pending;
};

}  // namespace

PackedTrackFile read_csv_text_packed(std::string_view text, const std::string& file, const ReadOptions& options) {
    CsvRowParser parser(file, options);
    CsvTrackAssembler tracks(file, options, parser);
    // In pieces of 1 MiB or more (a record or a first line that does not fit widens its piece),
    // so that the parsed rows held are a piece's, not the whole text's.
    constexpr std::size_t piece = std::size_t{1} << 20;
    ParsedBlock block;
    std::size_t at = 0, size = std::min(piece, text.size());
    while (size < text.size() && !CsvSplitter::holds_first_line(text.substr(0, size))) size = std::min(text.size(), size * 2);
    for (;;) {
        const bool complete = at + size == text.size();
        const std::size_t taken = parser.feed(text.substr(at, size), complete, block);
        tracks.apply(block);
        block.clear();
        if (complete) break;
        at += taken;
        size = taken > 0 ? std::min(piece, text.size() - at) : std::min(text.size() - at, 2 * size);
    }
    return tracks.finish();
}

TrackFile read_csv_text(std::string_view text, const std::string& file, const ReadOptions& options) {
    return unpack(read_csv_text_packed(text, file, options));
}

namespace {

/// A record longer than the line limit, read to its end without holding it: the first bytes of
/// each field (quoting as CsvSplitter reads it) and the line breaks it held.
struct LongRecord {
    std::vector<std::string> fields;
    std::size_t newlines = 0;  ///< its line end included (none when the file ends in it)
    /// A quoted field met a line end: the record ends there, as CsvSplitter::quote_not_closed
    /// ends a line whose quote does not close (a stray quote in a record this long would
    /// otherwise take in every row up to the next quote).
    bool quote_not_closed = false;
};

/// Reads the record at the start of `buf` (then of what `more` appends to it, until `more`
/// returns false at the end of the file); leaves in `buf` what follows the record.
template <typename More>
LongRecord read_long_record(std::string& buf, char sep, More&& more) {
    constexpr std::size_t keep = 256, max_fields = 4096;  // enough for every check and message
    LongRecord r;
    std::string field;
    bool quoted = false, quote_seen = false, after_quote = false, started = false;
    auto end_field = [&] {
        if (r.fields.size() < max_fields) r.fields.push_back(quoted || after_quote || quote_seen ? field : std::string(trim(field)));
        field.clear();
        quoted = quote_seen = after_quote = started = false;
    };
    for (;;) {
        for (std::size_t i = 0; i < buf.size(); ++i) {
            const char c = buf[i];
            if (quote_seen) {  // after a quote inside quotes: "" is a quote, else the field's quotes end
                quote_seen = false;
                if (c == '"') {
                    if (field.size() < keep) field += c;
                    continue;
                }
                quoted = false;
                after_quote = true;
            }
            if (quoted) {
                if (c == '\n') {
                    r.quote_not_closed = true;
                    end_field();
                    ++r.newlines;
                    buf.erase(0, i + 1);
                    return r;
                }
                if (c == '"') quote_seen = true;
                else if (field.size() < keep) field += c;
                continue;
            }
            if (c == sep || c == '\n') {
                end_field();
                if (c == '\n') {
                    ++r.newlines;
                    buf.erase(0, i + 1);
                    return r;
                }
                continue;
            }
            if (after_quote) continue;  // text after a closing quote is dropped, as CsvSplitter does
            if (c == '"' && !started) {
                quoted = true;
                started = true;
                continue;
            }
            if (c != ' ') started = true;
            if (field.size() < keep) field += c;
        }
        buf.clear();
        if (!more()) break;
    }
    end_field();
    return r;
}

/// Parsed blocks on their way from the thread that splits a file to the one that assembles its
/// tracks, and back empty (so at most `count` blocks are ever held). close() ends the file;
/// cancel() stops the splitting thread at its next block (the assembling one failed).
class BlockQueue {
public:
    explicit BlockQueue(std::size_t count) {
        for (std::size_t k = 0; k < count; ++k) m_free.push_back(std::make_unique<ParsedBlock>());
    }
    struct Cancelled {};

    /// An empty block to fill (waits for one); throws Cancelled after cancel().
    std::unique_ptr<ParsedBlock> take() {
        std::unique_lock lock(m_mutex);
        m_changed.wait(lock, [&] { return m_cancelled || !m_free.empty(); });
        if (m_cancelled) throw Cancelled{};
        auto b = std::move(m_free.back());
        m_free.pop_back();
        return b;
    }
    void push(std::unique_ptr<ParsedBlock> b) {
        {
            const std::lock_guard lock(m_mutex);
            m_full.push_back(std::move(b));
        }
        m_changed.notify_all();
    }
    /// The next filled block in order; null once closed and drained.
    std::unique_ptr<ParsedBlock> pop() {
        std::unique_lock lock(m_mutex);
        m_changed.wait(lock, [&] { return m_closed || !m_full.empty(); });
        if (m_full.empty()) return nullptr;
        auto b = std::move(m_full.front());
        m_full.pop_front();
        return b;
    }
    void recycle(std::unique_ptr<ParsedBlock> b) {
        b->clear();
        {
            const std::lock_guard lock(m_mutex);
            m_free.push_back(std::move(b));
        }
        m_changed.notify_all();
    }
    void close() {
        {
            const std::lock_guard lock(m_mutex);
            m_closed = true;
        }
        m_changed.notify_all();
    }
    void cancel() {
        {
            const std::lock_guard lock(m_mutex);
            m_cancelled = true;
        }
        m_changed.notify_all();
    }

private:
    std::mutex m_mutex;
    std::condition_variable m_changed;
    std::vector<std::unique_ptr<ParsedBlock>> m_free;
    std::deque<std::unique_ptr<ParsedBlock>> m_full;
    bool m_closed = false, m_cancelled = false;
};

}  // namespace

PackedTrackFile detail::read_csv_stream(shoal::detail::InputFile& in, std::string head, bool whole, const ReadOptions& options,
                                        std::size_t block) {
    constexpr std::size_t max_line = shoal::detail::max_line_bytes, max_first_line = shoal::detail::max_sniff_bytes;
    const std::string& path = in.path();
    // The head comes in blocks too, so that a long line in it is found as in the rest.
    std::string buf;
    std::size_t head_pos = 0;
    bool eof = false, in_done = whole;
    // A file with CR line ends (a spreadsheet's "CSV (Macintosh)", old Mac programs): each CR
    // a line end, as an editor shows it (before: one line, "no usable fix (0 rows read)").
    // Told by its first line end: CRs not followed by an LF ("\r\r\n" is one line end, as
    // editors count it; -1: none read yet).
    int cr_lines = -1;
    auto read_more = [&] {
        const std::size_t from_head = std::min(block, head.size() - head_pos);
        buf.append(head, head_pos, from_head);
        head_pos += from_head;
        if (head_pos == head.size()) {  // freed once read
            std::string().swap(head);
            head_pos = 0;
        }
        if (from_head < block) {
            const std::size_t want = block - from_head;
            if (in_done || in.append(buf, want) < want) in_done = eof = true;
        }
        if (cr_lines < 0)
            if (std::size_t end = buf.find_first_of("\r\n"); end != std::string::npos) {
                while (end < buf.size() && buf[end] == '\r') ++end;
                if (end < buf.size() || eof) cr_lines = end < buf.size() && buf[end] == '\n' ? 0 : 1;
            }
        if (cr_lines == 1) std::replace(buf.begin(), buf.end(), '\r', '\n');
    };
    const auto too_long = [&] {
        return InputError(path + ": not a track format shoal reads (CSV with a header, GPX, GeoJSON, NMEA 0183): its first line is longer than " +
                          shoal::detail::size_text(max_first_line) + ", the longest header shoal reads");
    };
    CsvRowParser parser(path, options);
    CsvTrackAssembler tracks(path, options, parser);

    // Splits the file into blocks of parsed records, handed in order to `emit`; `take` gives
    // an empty block. A block holds its bytes: what it did not take goes on in `buf`.
    auto split = [&](auto&& take, auto&& emit) {
        read_more();
        while (!eof && !CsvSplitter::holds_first_line(buf)) {
            if (buf.size() > max_first_line) throw too_long();
            read_more();
        }
        auto feed = [&] {
            std::unique_ptr<ParsedBlock> b = take();
            b->text.swap(buf);
            const std::size_t taken = parser.feed(b->text, eof, *b);
            buf.assign(b->text, taken);
            emit(std::move(b));
        };
        feed();
        while (!eof) {
            if (buf.size() > max_line) {  // a record that long: a bad row, read to its end but not held
                if (!parser.header_read()) {
                    if (buf.size() > max_first_line) throw too_long();
                    read_more();
                    feed();
                    continue;
                }
                const LongRecord r = read_long_record(buf, parser.separator(), [&] {
                    if (eof) return false;
                    read_more();
                    return true;
                });
                std::unique_ptr<ParsedBlock> b = take();
                parser.long_record(r.fields, r.quote_not_closed, *b);
                emit(std::move(b));
                buf.insert(0, r.newlines, '\n');  // blank lines: the splitter counts the lines the record held
            }
            if (!eof) read_more();
            feed();
        }
    };

    if (whole || options.threads < 2) {  // one thread: each block assembled as soon as it is parsed
        auto block_used = std::make_unique<ParsedBlock>();
        split([&] { return std::move(block_used); },
              [&](std::unique_ptr<ParsedBlock> b) {
                  tracks.apply(*b);
                  b->clear();
                  block_used = std::move(b);
              });
        return tracks.finish();
    }
    // Two threads: one reads, splits and parses the blocks, this one makes the tracks of them.
    BlockQueue queue(4);
    std::exception_ptr failed;
    std::thread splitter([&] {
        try {
            split([&] { return queue.take(); }, [&](std::unique_ptr<ParsedBlock> b) { queue.push(std::move(b)); });
        } catch (const BlockQueue::Cancelled&) {
        } catch (...) {
            failed = std::current_exception();
        }
        queue.close();
    });
    try {
        while (std::unique_ptr<ParsedBlock> b = queue.pop()) {
            tracks.apply(*b);
            queue.recycle(std::move(b));
        }
    } catch (...) {
        queue.cancel();
        splitter.join();
        throw;
    }
    splitter.join();
    if (failed) std::rethrow_exception(failed);
    return tracks.finish();
}

PackedTrackFile read_csv_packed(const std::string& path, const ReadOptions& options) {
    shoal::detail::InputFile in(path);
    std::string head;
    const bool whole = in.append(head, std::size_t{1} << 20) < (std::size_t{1} << 20);
    return detail::read_csv_stream(in, std::move(head), whole, options);
}

TrackFile read_csv(const std::string& path, const ReadOptions& options) { return unpack(read_csv_packed(path, options)); }

}  // namespace shoal::track
