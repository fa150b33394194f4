// Tables of AIS static data, "vessels tables" (track/vessels_table.hpp).
#include <shoal/track/vessels_table.hpp>

#include <algorithm>
#include <set>
#include <sstream>

#include <shoal/track/columns.hpp>
#include <shoal/track/csv_reader.hpp>
#include <shoal/track/csv_splitter.hpp>
#include "util/input_file.hpp"
#include "util/parse_util.hpp"
#include <shoal/util/error.hpp>

namespace shoal::track {

bool is_vessels_table(const std::string& path) {
    // The first line, of at most 64 KiB (a header longer than that is no vessels table's).
    std::string head = shoal::detail::read_head(path, 64 * 1024);
    if (head.starts_with("\xEF\xBB\xBF")) head.erase(0, 3);
    const std::size_t nl = head.find('\n');
    if (nl == std::string::npos && head.size() == 64 * 1024) return false;
    head.resize(std::min(nl, head.size()));
    if (!head.empty() && head.back() == '\r') head.pop_back();
    CsvSplitter split(head);
    std::vector<std::string_view> f_names;
    if (split.separator() == '\0' || !split.next(f_names)) return false;
    std::set<std::string> names;
    for (const auto h : f_names) names.insert(normalise_column_name(h));
    const auto any = [&](std::initializer_list<std::string_view> fields) {
        return std::any_of(fields.begin(), fields.end(), [&](std::string_view field) {
            const auto known = column_names(field);
            return std::any_of(known.begin(), known.end(), [&](std::string_view c) { return names.contains(std::string(c)); });
        });
    };
    // A position makes it a track file; an MMSI and what a vessels table gives, a vessels table.
    if (any({"lat", "lon"})) return false;
    return names.contains("mmsi") && any({"name", "ship_type", "draught", "a", "b", "c", "d"});
}

namespace {

/// "a=88 b=12 c=10 d=6"
std::string dims_text(const hull::Dimensions& d) {
    std::ostringstream os;
    os << d;
    return os.str();
}

/// Up to 40 bytes of a field, for messages.
std::string quoted(std::string_view v) {
    const std::string s = to_utf8(v.substr(0, 40));
    return "'" + s + (v.size() > 40 ? "...'" : "'");
}

}  // namespace

std::string integral_id(std::string_view id) {
    const auto digit = [](char c) { return c >= '0' && c <= '9'; };
    std::size_t i = 0;
    while (i < id.size() && digit(id[i])) ++i;
    const std::string_view whole = id.substr(0, i);
    if (whole.empty() || i == id.size()) return std::string(id);
    std::string_view rest = id.substr(i);
    std::string fraction;
    if (rest.front() == '.') {
        rest.remove_prefix(1);
        std::size_t k = 0;
        while (k < rest.size() && digit(rest[k])) ++k;
        fraction = rest.substr(0, k);
        rest.remove_prefix(k);
    }
    long exponent = 0;
    if (!rest.empty()) {
        if (rest.front() != 'e' && rest.front() != 'E') return std::string(id);
        rest.remove_prefix(1);
        bool negative = false;
        if (!rest.empty() && (rest.front() == '+' || rest.front() == '-')) {
            negative = rest.front() == '-';
            rest.remove_prefix(1);
        }
        if (rest.empty() || rest.size() > 3 || !std::all_of(rest.begin(), rest.end(), digit)) return std::string(id);
        exponent = std::stol(std::string(rest));
        if (negative) exponent = -exponent;
    }
    // The digits, the point moved by the exponent: integral when every digit after it is 0, and
    // exact only when no digit is missing (2.30036E+08 is a rounded MMSI: not one).
    std::string digits = std::string(whole) + fraction;
    const long point = static_cast<long>(whole.size()) + exponent;
    if (point < 1 || point > static_cast<long>(digits.size()) || point > 18) return std::string(id);
    for (std::size_t k = static_cast<std::size_t>(point); k < digits.size(); ++k)
        if (digits[k] != '0') return std::string(id);
    digits.resize(static_cast<std::size_t>(point));
    return digits;
}

std::vector<std::string> unmatched_vessels_tables(const std::map<std::string, VesselInfo>& vessels, const std::vector<std::string>& track_ids) {
    std::set<std::string> ids;
    for (const std::string& id : track_ids) {
        ids.insert(id);
        ids.insert(integral_id(id));
    }
    std::map<std::string, std::pair<std::size_t, std::size_t>> by_table;  // table: (vessels, of them tracks)
    std::map<std::string, std::string> example;
    for (const auto& [id, v] : vessels)
        for (const std::string& s : v.sources) {
            auto& [n, matched] = by_table[s];
            ++n;
            if (ids.contains(id)) ++matched;
            else example.try_emplace(s, id);
        }
    std::vector<std::string> out;
    for (const auto& [table, count] : by_table) {
        if (count.second > 0) continue;
        std::string seen;
        std::size_t k = 0;
        for (const std::string& id : ids)
            if (id == integral_id(id) && k++ < 3) seen += (seen.empty() ? "" : ", ") + quoted(std::string_view(id));
        out.push_back(table + ": none of its " + std::to_string(count.first) + " vessels is a track read (its ids such as " + quoted(std::string_view(example[table])) +
                      ", the tracks' such as " + (seen.empty() ? std::string("none") : seen) +
                      "): its names, dimensions and draughts are not used (the default hull and draught serve)");
    }
    return out;
}

std::map<std::string, VesselInfo> read_vessels(const std::string& path, std::vector<std::string>* warnings) {
    std::string text;
    try {
        text = shoal::detail::read_input(path, max_vessels_bytes, "a vessels file");
    } catch (const shoal::detail::InputOpenError& e) {
        throw InputError(path + ": cannot read (" + e.reason + ")");
    }
    // One row a line: a quote never closed costs its line, not the rest of the file. The
    // header is split once for the separator and columns, then each line after it with it.
    const std::size_t header_end = std::min(text.find('\n'), text.size());
    const std::string header(text, 0, header_end);
    std::vector<std::string_view> f;
    char sep = '\0';
    std::vector<std::string> names;
    {
        CsvSplitter split(header);
        sep = split.separator();
        if (sep == '\0' || !split.next(f)) throw InputError(path + ": not a vessels CSV file (no header)");
        for (const auto h : f) names.push_back(normalise_column_name(h));
    }
    constexpr std::size_t absent = static_cast<std::size_t>(-1);
    // The columns by the track files' names (columns.hpp), the MMSI by its own.
    auto col = [&](std::span<const std::string_view> candidates) {
        for (const auto c : candidates)
            for (std::size_t i = 0; i < names.size(); ++i)
                if (names[i] == c) return i;
        return absent;
    };
    constexpr std::string_view mmsi_name[] = {"mmsi"};
    const std::size_t mmsi = col(mmsi_name);
    if (mmsi == absent) throw InputError(path + ": vessels file without an 'mmsi' column");
    const std::size_t name = col(column_names("name"));
    const std::size_t type = col(column_names("ship_type"));
    const std::size_t draught = col(column_names("draught"));
    const std::array<std::size_t, 4> dims{col(column_names("a")), col(column_names("b")), col(column_names("c")), col(column_names("d"))};
    const bool decimal_comma = sep != ',';
    std::size_t said = 0, bad = 0;
    std::string row_text;
    std::map<std::string, VesselInfo> out;
    std::size_t line = 1;
    for (std::size_t at = header_end; at < text.size();) {
        ++at;  // past the '\n'
        const std::size_t nl = std::min(text.find('\n', at), text.size());
        std::string_view raw(text.data() + at, nl - at);
        at = nl;
        ++line;
        if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
        if (detail::trim(raw).empty()) continue;
        auto skip = [&](const std::string& why) {
            ++bad;
            if (warnings && said++ < 10) warnings->push_back(path + " line " + std::to_string(line) + ": " + why + "; row skipped");
        };
        if (std::count(raw.begin(), raw.end(), '"') % 2 != 0) {
            skip("a quote is not closed on its line");
            continue;
        }
        row_text.assign(header).append("\n").append(raw);
        CsvSplitter split(row_text);
        if (!split.next(f) || !split.next(f)) continue;
        if (f.size() != names.size()) {
            skip("has " + std::to_string(f.size()) + " fields, the header " + std::to_string(names.size()) +
                 (decimal_comma ? std::string() : std::string(" (a decimal comma in a comma-separated file?)")));
            continue;
        }
        const std::string id = integral_id(detail::trim(f[mmsi]));  // 230035780.0, as a spreadsheet writes it: 230035780
        if (id.empty()) {
            skip("no mmsi");
            continue;
        }
        // A value given must be a number; empty (and AIS 0: not available) is unknown.
        std::string problem;
        auto number = [&](std::size_t c) -> double {
            double v = NAN;
            if (c == absent || detail::trim(f[c]).empty()) return NAN;
            if (!detail::parse_double(f[c], v, decimal_comma) || !std::isfinite(v)) {
                if (problem.empty()) problem = names[c] + " " + quoted(f[c]) + " is not a number";
                return NAN;
            }
            if (v < 0 && problem.empty()) problem = names[c] + " " + quoted(f[c]) + " is negative";
            return v;
        };
        std::array<double, 4> d{};
        bool all_given = true;
        for (std::size_t k = 0; k < 4; ++k) {
            d[k] = number(dims[k]);
            all_given = all_given && std::isfinite(d[k]) && d[k] > 0.0;
        }
        const double dr = number(draught);
        const double t = type == absent ? NAN : [&] {
            double v = NAN;
            return detail::parse_double(f[type], v) ? v : NAN;  // a ship type may be text (DMA): not a number is unknown
        }();
        std::optional<hull::Dimensions> given;
        if (all_given) given = hull::Dimensions{d[0], d[1], d[2], d[3]};
        if (problem.empty() && given && !hull::Hull::plausible(*given))
            problem = "dimensions " + dims_text(*given) + " are larger than any ship (length A+B over " + detail::fmt(hull::Hull::max_length_m) +
                      " m or beam C+D over " + detail::fmt(hull::Hull::max_beam_m) + " m) or under a hull's " +
                      detail::fmt(hull::Hull::min_extent_m) + " m: a wrong unit?";
        if (problem.empty() && std::isfinite(dr) && dr > max_draught_m)
            problem = "draught " + detail::fmt(dr) + " m is deeper than any ship draws (" + detail::fmt(max_draught_m) + " m)";
        if (!problem.empty()) {
            skip(problem);
            continue;
        }
        VesselInfo& v = out[id];
        if (v.name.empty() && name != absent) v.name = to_utf8(detail::trim(f[name]));
        if (!v.dims) v.dims = given;
        if (std::isnan(v.draught_m) && std::isfinite(dr) && dr > 0.0) v.draught_m = dr;
        // AIS ship types are 1-255 (0: not available); anything else is not one: unknown.
        if (v.ship_type < 0 && t >= 1.0 && t <= 255.0 && t == std::floor(t)) v.ship_type = static_cast<int>(t);
    }
    if (warnings && bad > said) warnings->push_back(path + ": " + std::to_string(bad - said) + " more bad rows skipped");
    return out;
}

std::map<std::string, VesselInfo> read_vessels_files(const std::vector<std::string>& paths, std::vector<std::string>* warnings) {
    std::map<std::string, VesselInfo> all;
    for (const std::string& f : paths) merge_vessels(all, read_vessels(f, warnings), "vessels file " + f, warnings);
    return all;
}

void merge_vessels(std::map<std::string, VesselInfo>& into, std::map<std::string, VesselInfo>&& from, const std::string& source,
                   std::vector<std::string>* warnings) {
    for (auto& [id, v] : from) {
        v.source = source;
        v.sources = {source};
        auto [it, fresh] = into.try_emplace(id, std::move(v));
        if (fresh) continue;
        VesselInfo& kept = it->second;
        kept.sources.push_back(source);
        const VesselInfo& other = v;
        std::string differ;
        if (kept.dims && other.dims && !(*kept.dims == *other.dims))
            differ = "dimensions " + dims_text(*kept.dims) + " and " + dims_text(*other.dims);
        if (!std::isnan(kept.draught_m) && !std::isnan(other.draught_m) && kept.draught_m != other.draught_m)
            differ += (differ.empty() ? "draught " : ", draught ") + detail::fmt(kept.draught_m) + " m and " + detail::fmt(other.draught_m) + " m";
        if (!differ.empty() && warnings)
            warnings->push_back("vessel " + id + ": " + kept.source + " and " + source + " disagree (" + differ + "): those of " +
                                kept.source + " (given first) are used");
        // What the first source lacks, a later one gives.
        if (kept.name.empty()) kept.name = other.name;
        if (!kept.dims && other.dims) {
            kept.dims = other.dims;
            kept.dims_source = source;
        }
        if (std::isnan(kept.draught_m) && !std::isnan(other.draught_m)) {
            kept.draught_m = other.draught_m;
            kept.draught_source = source;
        }
        if (kept.ship_type < 0 && other.ship_type >= 0) {
            kept.ship_type = other.ship_type;
            kept.ship_type_source = source;
        }
    }
}

}  // namespace shoal::track
