#include <shoal/track/columns.hpp>

#include <algorithm>
#include <cctype>
#include <iterator>
#include <stdexcept>

#include "util/parse_util.hpp"

namespace shoal::track {

using detail::trim;

namespace {

// Each field's names, the usual first: "mmsi" before a possible row id; a file with both
// "time" and "timestamp" keeps its "time".
constexpr std::string_view id[] = {"track_id", "mmsi", "id", "vessel", "vessel_id"};
constexpr std::string_view name[] = {"vesselname", "vessel_name", "name", "shipname", "ship_name"};
constexpr std::string_view time[] = {"time", "timestamp", "basedatetime", "time_utc", "datetime", "date_time", "utc"};
constexpr std::string_view lat[] = {"lat", "latitude"};
constexpr std::string_view lon[] = {"lon", "lng", "long", "longitude"};
constexpr std::string_view heading[] = {"heading", "hdg", "heading_deg", "true_heading", "trueheading"};
constexpr std::string_view cog[] = {"cog", "course", "cog_deg"};
constexpr std::string_view sog[] = {"sog", "speed", "sog_kn", "sog_knots"};
constexpr std::string_view to_bow[] = {"a", "to_bow_m", "to_bow"};
constexpr std::string_view to_stern[] = {"b", "to_stern_m", "to_stern"};
constexpr std::string_view to_port[] = {"c", "to_port_m", "to_port"};
constexpr std::string_view to_stbd[] = {"d", "to_stbd_m", "to_stbd", "to_starboard_m"};
constexpr std::string_view draught[] = {"draught", "draught_m", "draft", "draft_m"};
constexpr std::string_view length[] = {"length", "length_m"};
constexpr std::string_view width[] = {"width", "width_m", "beam", "beam_m"};
constexpr std::string_view mobile_type[] = {"type of mobile"};
constexpr std::string_view ship_type[] = {"vesseltype", "shiptype", "ship_type", "ship type", "vessel_type"};
constexpr std::string_view nav_status[] = {"navigational status", "navigational_status", "nav_status", "navstatus", "status"};

constexpr ColumnNames table[] = {
    {"id", id},           {"name", name},       {"time", time},       {"lat", lat},           {"lon", lon},
    {"heading", heading}, {"cog", cog},         {"sog", sog},         {"a", to_bow},          {"b", to_stern},
    {"c", to_port},       {"d", to_stbd},       {"draught", draught}, {"length", length},     {"width", width},
    {"mobile_type", mobile_type}, {"ship_type", ship_type}, {"nav_status", nav_status},
};

}  // namespace

std::span<const ColumnNames> column_table() noexcept { return table; }

std::span<const std::string_view> column_names(std::string_view field) {
    for (const ColumnNames& c : table)
        if (c.field == field) return c.names;
    throw std::logic_error("column_names: no field '" + std::string(field) + "'");
}

std::string normalise_column_name(std::string_view name) {
    name = trim(name);
    while (!name.empty() && (name.front() == '#' || name.front() == ' ')) name.remove_prefix(1);
    std::string out(name);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

bool is_time_column_name(std::string_view name) {
    const std::string n = normalise_column_name(name);
    static constexpr std::string_view qualifiers[] = {"utc", "gmt", "z", "iso", "iso8601", "epoch", "unix"};
    static constexpr std::string_view bases[] = {"time", "timestamp", "datetime", "basedatetime"};
    const auto is_qualifier = [](std::string_view w) { return std::find(std::begin(qualifiers), std::end(qualifiers), w) != std::end(qualifiers); };
    // The words (letters and digits between any other characters), the qualifiers left out.
    std::string joined;
    bool qualified = false;
    for (std::size_t at = 0; at < n.size();) {
        std::size_t end = at;
        while (end < n.size() && std::isalnum(static_cast<unsigned char>(n[end]))) ++end;
        const std::string_view word = std::string_view(n).substr(at, end - at);
        if (!word.empty()) {
            if (is_qualifier(word)) qualified = true;
            else joined += word;
        }
        at = end == at ? at + 1 : end;
    }
    if (joined.empty()) return qualified && n.find("utc") != std::string::npos;  // "UTC" alone
    const auto is_base = [](std::string_view w) { return std::find(std::begin(bases), std::end(bases), w) != std::end(bases); };
    if (is_base(joined)) return true;
    // A qualifier joined on either end: "timeutc", "datetimeutc", "utctime", "epochtime".
    for (const std::string_view q : qualifiers) {
        if (q.size() < 3) continue;  // "z" joined on would take "timez"-like names too lightly
        if (joined.size() > q.size() && joined.compare(joined.size() - q.size(), q.size(), q) == 0 && is_base(std::string_view(joined).substr(0, joined.size() - q.size())))
            return true;
        if (joined.size() > q.size() && joined.compare(0, q.size(), q) == 0 && is_base(std::string_view(joined).substr(q.size()))) return true;
    }
    return false;
}

}  // namespace shoal::track
