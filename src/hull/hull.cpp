#include <shoal/hull/hull.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <optional>
#include <ostream>
#include <sstream>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include <shoal/util/error.hpp>
#include "util/json_message.hpp"

namespace shoal::hull {

namespace {

using geo::XY;
using nlohmann::json;

/// Shortest text that reads back as the same double ("-3.5", "100", "1e+20").
std::string fmt(double v) {
    std::array<char, 32> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    return {buf.data(), res.ptr};
}

std::string fmt(XY p) { return "(" + fmt(p.x) + ", " + fmt(p.y) + ")"; }

bool is_valid_extent(double v) noexcept { return std::isfinite(v) && v > 0.0; }

/// What makes a hull of these dimensions larger than any ship, or smaller than any vessel ("" when
/// nothing does).
std::string size_problem(const Dimensions& dims) {
    if (dims.a + dims.b > Hull::max_length_m)
        return "a length (a + b) of " + fmt(dims.a + dims.b) + " m is more than the " + fmt(Hull::max_length_m) +
               " m of any ship (a wrong unit?)";
    if (dims.c + dims.d > Hull::max_beam_m)
        return "a beam (c + d) of " + fmt(dims.c + dims.d) + " m is more than the " + fmt(Hull::max_beam_m) +
               " m of any ship (a wrong unit?)";
    if (dims.a + dims.b < Hull::min_extent_m)
        return "a length (a + b) of " + fmt(dims.a + dims.b) + " m is less than the " + fmt(Hull::min_extent_m) + " m a hull needs (a wrong unit?)";
    if (dims.c + dims.d < Hull::min_extent_m)
        return "a beam (c + d) of " + fmt(dims.c + dims.d) + " m is less than the " + fmt(Hull::min_extent_m) + " m a hull needs (a wrong unit?)";
    return {};
}

void check_dimensions(const Dimensions& dims) {
    const std::array<std::pair<const char*, double>, 4> parts{
        {{"a", dims.a}, {"b", dims.b}, {"c", dims.c}, {"d", dims.d}}};
    for (const auto& [key, value] : parts)
        if (!is_valid_extent(value))
            throw InputError{std::string{"AIS dimension '"} + key + "' must be a finite number > 0 (got " +
                             fmt(value) + ")"};
    if (const std::string problem = size_problem(dims); !problem.empty()) throw InputError{"AIS dimensions: " + problem};
}

// ---------------------------------------------------------------------------------------------
// Generated outline

/// One side of the generated outline, from just aft of the bow tip to the stern, at the
/// full-beam line y = edge (d for starboard, -c for port); `centre` is the centreline y.
struct SidePlan {
    std::size_t bow = 0;      ///< bow points incl. the shoulder, excl. the tip
    std::size_t middle = 0;   ///< points strictly inside the parallel midbody
    std::size_t quarter = 0;  ///< 1: sharp stern corner; >= 2: arc of radius r
};

SidePlan plan_side(std::size_t k) {
    if (k == 1) return {0, 0, 1};
    if (k == 2) return {1, 0, 1};
    SidePlan p;
    p.quarter = std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(0.22 * static_cast<double>(k))), 1, 4);
    p.middle = static_cast<std::size_t>(0.18 * static_cast<double>(k));
    p.bow = k - p.quarter - p.middle;
    return p;
}

/// Points of one side in order bow -> stern. `sign` is +1 for starboard, -1 for port.
std::vector<XY> side_points(const Dimensions& dims, const SidePlan& plan, double sign) {
    const double length = dims.a + dims.b;
    const double half_beam = 0.5 * (dims.c + dims.d);
    const double centre = 0.5 * (dims.d - dims.c);
    const double edge = sign > 0 ? dims.d : -dims.c;
    // The bow and the rounded quarter stay clear of x = 0, so the reference point lies in the
    // parallel midbody, between the full-beam lines: strictly inside.
    const double bow_len = std::min(0.25 * length, 0.9 * dims.a);
    const double radius = plan.quarter >= 2 ? std::min({0.3 * half_beam, 0.08 * length, 0.9 * dims.b}) : 0.0;
    const double shoulder_x = dims.a - bow_len;
    const double quarter_x = -dims.b + radius;

    std::vector<XY> pts;
    // Parabolic bow y = edge + (centre - edge) t^2, t = 1 at the tip: pointed, and tangent to
    // the midbody at the shoulder (t = 0). Listed from the tip aft, so t decreases.
    for (std::size_t j = plan.bow; j-- > 0;) {
        const double t = static_cast<double>(j) / static_cast<double>(plan.bow);
        pts.push_back({shoulder_x + t * bow_len, edge + (centre - edge) * t * t});
    }
    const double mid_from = plan.bow > 0 ? shoulder_x : dims.a;
    for (std::size_t i = 1; i <= plan.middle; ++i) {
        const double f = static_cast<double>(i) / static_cast<double>(plan.middle + 1);
        pts.push_back({mid_from + (quarter_x - mid_from) * f, edge});
    }
    if (plan.quarter == 1) {
        pts.push_back({-dims.b, edge});
    } else {
        for (std::size_t j = 0; j < plan.quarter; ++j) {
            const double phi = 0.5 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(plan.quarter - 1);
            pts.push_back({-dims.b + radius * (1.0 - std::sin(phi)), edge - sign * radius * (1.0 - std::cos(phi))});
        }
    }
    return pts;
}

std::vector<XY> generate_outline(const Dimensions& dims, std::size_t n) {
    const bool stern_point = n % 2 == 0;
    const std::size_t per_side = (n - 1 - (stern_point ? 1 : 0)) / 2;
    const SidePlan plan = plan_side(per_side);
    const double centre = 0.5 * (dims.d - dims.c);

    std::vector<XY> out;
    out.reserve(n);
    out.push_back({dims.a, centre});  // bow tip
    const auto starboard = side_points(dims, plan, +1.0);
    out.insert(out.end(), starboard.begin(), starboard.end());
    if (stern_point) out.push_back({-dims.b, centre});
    const auto port = side_points(dims, plan, -1.0);
    out.insert(out.end(), port.rbegin(), port.rend());
    return out;
}

// ---------------------------------------------------------------------------------------------
// Contour validation

double twice_signed_area(const std::vector<XY>& ring) noexcept {
    double s = 0.0;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) s += cross(ring[j], ring[i]);
    return s;
}

/// Crossing-number test; the caller has already excluded points on the boundary.
bool contains(const std::vector<XY>& ring, XY p) noexcept {
    bool inside = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const XY a = ring[j], b = ring[i];
        if ((a.y > p.y) != (b.y > p.y)) {
            const double x_cross = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < x_cross) inside = !inside;
        }
    }
    return inside;
}

std::string edge_name(std::size_t i, std::size_t n) {
    return std::to_string(i) + "-" + std::to_string((i + 1) % n);
}

/// Throws InputError unless `ring` (open, >= 3 points) is a simple polygon holding (0,0) strictly
/// inside. Point numbers in the messages are 0-based indices into the caller's list.
void validate_contour(const std::vector<XY>& ring) {
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(ring[i].x) || !std::isfinite(ring[i].y))
            throw InputError{"contour point " + std::to_string(i) + " " + fmt(ring[i]) + " is not finite"};
    for (std::size_t i = 0; i < n; ++i)
        if (ring[i] == ring[(i + 1) % n])
            throw InputError{"contour points " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                             " are the same point " + fmt(ring[i]) + "; remove the repeat"};
    const std::string not_simple = "contour is not a simple polygon: ";
    for (std::size_t i = 0; i < n; ++i) {
        const XY a = ring[i], b = ring[(i + 1) % n];
        // An edge that doubles back along its predecessor overlaps it.
        const XY prev = ring[(i + n - 1) % n];
        if (orient(prev, a, b) == 0.0 && dot(a - prev, b - a) < 0.0)
            throw InputError{not_simple + "edge " + edge_name(i, n) + " doubles back along edge " +
                             edge_name((i + n - 1) % n, n)};
        for (std::size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
            if (geo::segments_intersect(a, b, ring[j], ring[(j + 1) % n]))
                throw InputError{not_simple + "edge " + edge_name(i, n) + " crosses or touches edge " +
                                 edge_name(j, n)};
        }
    }
    if (twice_signed_area(ring) == 0.0) throw InputError{"contour encloses no area"};
    const XY ref{0.0, 0.0};
    for (std::size_t i = 0; i < n; ++i)
        if (geo::point_segment_dist2(ref, ring[i], ring[(i + 1) % n]) == 0.0)
            throw InputError{"the reference point (0,0) lies on contour edge " + edge_name(i, n) +
                             "; it must be strictly inside"};
    if (!contains(ring, ref))
        throw InputError{"the reference point (0,0) is outside the contour; points are metres from the "
                         "position reference point, x forward and y to starboard"};
}

Dimensions extent(const std::vector<XY>& ring) noexcept {
    geo::Box box;
    for (const XY p : ring) box.extend(p);
    return {box.maxx, -box.minx, -box.miny, box.maxy};
}

// ---------------------------------------------------------------------------------------------
// --dims

std::string_view trim(std::string_view s) noexcept {
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t");
    return s.substr(first, last - first + 1);
}

// ---------------------------------------------------------------------------------------------
// Ship file

constexpr std::array<std::string_view, 10> known_fields{"$schema", "name", "length", "beam", "a",
                                                       "b",       "c",    "d",      "draught", "contour"};

std::size_t edit_distance(std::string_view s, std::string_view t) {
    std::vector<std::size_t> row(t.size() + 1);
    for (std::size_t j = 0; j <= t.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= s.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= t.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (s[i - 1] == t[j - 1] ? 0u : 1u)});
            diag = up;
        }
    }
    return row[t.size()];
}

/// Short JSON text of a value for messages.
std::string brief(const json& v) {
    std::string text = v.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

struct ShipSpec {
    std::string name;
    Dimensions dims;
    double draught_m = 0.0;
    std::optional<std::vector<XY>> contour;
};

class ShipFileReader {
public:
    ShipFileReader(std::string path, std::string_view text) : m_path{std::move(path)}, m_text{text} {}

    /// The file's content, checked field by field; the contour is not yet checked as a polygon.
    ShipSpec read() const {
        const json doc = parse();
        if (!doc.is_object()) fail("the top level must be a JSON object (got " + std::string{doc.type_name()} + ")");
        check_unknown_fields(doc);

        ShipSpec spec;
        spec.name = read_name(doc);
        spec.dims = {required_extent(doc, "a", "to the bow"), required_extent(doc, "b", "to the stern"),
                     required_extent(doc, "c", "to port"), required_extent(doc, "d", "to starboard")};
        check_total(doc, "length", "a", "b", spec.dims.a, spec.dims.b);
        check_total(doc, "beam", "c", "d", spec.dims.c, spec.dims.d);
        if (const auto v = optional_number(doc, "draught")) {
            if (*v < 0.0) fail("'draught' must be >= 0 (got " + fmt(*v) + ")");
            spec.draught_m = *v;
        }
        if (doc.contains("contour")) spec.contour = read_contour(doc.at("contour"), spec.dims);
        return spec;
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError{"In ship file '" + m_path + "': " + what};
    }

private:
    json parse() const {
        try {
            return json::parse(m_text);
        } catch (const json::parse_error& e) {
            fail("not valid JSON at byte " + std::to_string(e.byte) + ": " + shoal::detail::json_error_text(e.what()));
        } catch (const json::exception& e) {  // e.g. a number too large for a double
            fail("not valid JSON: " + shoal::detail::json_error_text(e.what()));
        }
    }

    void check_unknown_fields(const json& doc) const {
        std::string unknown;
        std::size_t count = 0;
        for (const auto& [key, value] : doc.items()) {
            if (std::find(known_fields.begin(), known_fields.end(), key) != known_fields.end()) continue;
            if (count == 5) {  // the message stays one short line, whatever the file holds
                unknown += ", ...";
                ++count;
            }
            if (count > 5) continue;
            unknown += (count++ ? ", '" : "'") + (key.size() > 40 ? key.substr(0, 40) + "..." : key) + "'";
            for (const auto known : known_fields)
                if (edit_distance(key, known) <= (known.size() <= 2 ? 0u : 2u)) {
                    unknown += " (did you mean '" + std::string{known} + "'?)";
                    break;
                }
        }
        if (count == 0) return;
        std::string allowed;
        for (const auto known : known_fields) allowed += (allowed.empty() ? "" : ", ") + std::string{known};
        fail((count == 1 ? "unknown field " : "unknown fields ") + unknown + "; allowed fields: " + allowed);
    }

    std::string read_name(const json& doc) const {
        if (!doc.contains("name")) fail("'name' is required (the ship's name, a string)");
        const json& v = doc.at("name");
        if (!v.is_string()) fail("'name' must be a string (got " + brief(v) + ")");
        std::string name = v.get<std::string>();
        if (name.empty()) fail("'name' must not be empty");
        return name;
    }

    std::optional<double> optional_number(const json& doc, const char* key) const {
        if (!doc.contains(key)) return std::nullopt;
        const json& v = doc.at(key);
        if (!v.is_number()) fail(std::string{"'"} + key + "' must be a number (got " + brief(v) + ")");
        const double value = v.get<double>();
        if (!std::isfinite(value)) fail(std::string{"'"} + key + "' must be finite (got " + fmt(value) + ")");
        return value;
    }

    double required_extent(const json& doc, const char* key, const char* meaning) const {
        const auto v = optional_number(doc, key);
        if (!v)
            fail(std::string{"'"} + key + "' is required (AIS dimension: metres from the position reference point " +
                 meaning + ", > 0)");
        if (*v <= 0.0) fail(std::string{"'"} + key + "' must be > 0 (got " + fmt(*v) + ")");
        return *v;
    }

    /// `length` must agree with a + b, `beam` with c + d, within 0.5 m or 1 %.
    void check_total(const json& doc, const char* key, const char* k1, const char* k2, double v1, double v2) const {
        const auto v = optional_number(doc, key);
        if (!v) return;
        if (*v <= 0.0) fail(std::string{"'"} + key + "' must be > 0 (got " + fmt(*v) + ")");
        const double sum = v1 + v2;
        if (std::abs(*v - sum) > std::max(0.5, 0.01 * sum))
            fail(std::string{"'"} + key + "' (" + fmt(*v) + ") disagrees with '" + k1 + "' + '" + k2 + "' (" +
                 fmt(v1) + " + " + fmt(v2) + " = " + fmt(sum) + "); they must agree within 0.5 m or 1%");
    }

    std::vector<XY> read_contour(const json& v, const Dimensions& dims) const {
        if (!v.is_array()) fail("'contour' must be an array of [x_forward, y_starboard] pairs (got " + brief(v) + ")");
        if (v.size() < 3) fail("'contour' needs at least 3 points (got " + std::to_string(v.size()) + ")");
        constexpr double tolerance_m = 0.01;
        std::vector<XY> pts;
        pts.reserve(v.size());
        for (std::size_t i = 0; i < v.size(); ++i) {
            const json& p = v[i];
            const std::string field = "'contour[" + std::to_string(i) + "]'";
            if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
                fail(field + " must be a pair [x_forward, y_starboard] of numbers in metres (got " + brief(p) + ")");
            const XY q{p[0].get<double>(), p[1].get<double>()};
            if (!std::isfinite(q.x) || !std::isfinite(q.y)) fail(field + " must be finite (got " + brief(p) + ")");
            if (q.x > dims.a + tolerance_m || q.x < -dims.b - tolerance_m || q.y > dims.d + tolerance_m ||
                q.y < -dims.c - tolerance_m)
                fail(field + " = " + brief(p) + " lies outside the box given by 'a', 'b', 'c', 'd': x must be in [" +
                     fmt(-dims.b) + ", " + fmt(dims.a) + "] and y in [" + fmt(-dims.c) + ", " + fmt(dims.d) +
                     "] (tolerance 0.01 m)");
            pts.push_back(q);
        }
        return pts;
    }

    std::string m_path;
    std::string_view m_text;
};

}  // namespace

// ---------------------------------------------------------------------------------------------

std::ostream& operator<<(std::ostream& os, const Dimensions& dims) {
    return os << "a=" << fmt(dims.a) << " b=" << fmt(dims.b) << " c=" << fmt(dims.c) << " d=" << fmt(dims.d);
}

Hull::Hull(std::string name, std::vector<XY> contour, Dimensions dims, double draught_m)
    : m_name{std::move(name)}, m_contour{std::move(contour)}, m_dims{dims}, m_draught_m{draught_m} {
    for (const XY p : m_contour) m_radius_m = std::max(m_radius_m, std::hypot(p.x, p.y));
}

Hull Hull::from_dimensions(const Dimensions& dims, std::string name) {
    return from_dimensions_n(dims, default_points, std::move(name));
}

Hull Hull::from_dimensions_n(const Dimensions& dims, std::size_t n, std::string name) {
    if (n < 3) throw UsageError{"a hull outline needs at least 3 points (got " + std::to_string(n) + ")"};
    check_dimensions(dims);
    return Hull{std::move(name), generate_outline(dims, n), dims, 0.0};
}

Hull Hull::from_contour(std::vector<XY> contour, std::string name) {
    if (contour.size() > 1 && contour.front() == contour.back()) contour.pop_back();
    if (contour.size() < 3)
        throw InputError{"a contour needs at least 3 points (got " + std::to_string(contour.size()) + ")"};
    if (contour.size() > max_points)
        throw InputError{"a contour of " + std::to_string(contour.size()) + " points is more than the " +
                         std::to_string(max_points) + " supported; simplify the outline"};
    validate_contour(contour);
    if (twice_signed_area(contour) < 0.0) std::reverse(std::next(contour.begin()), contour.end());
    const Dimensions dims = extent(contour);
    return Hull{std::move(name), std::move(contour), dims, 0.0};
}

Hull Hull::from_dims_string(const std::string& text) {
    static constexpr std::array<const char*, 4> letters{"A", "B", "C", "D"};
    const std::string usage = "Hull::dims expects A,B,C,D: metres from the position reference point to bow, stern, "
                              "port and starboard, e.g. 120,30,8,10";
    std::vector<std::string_view> parts;
    std::string_view rest{text};
    for (;;) {
        const auto comma = rest.find(',');
        parts.push_back(trim(rest.substr(0, comma)));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
    }
    if (parts.size() != 4)
        throw InputError{usage + "; got " + std::to_string(parts.size()) + (parts.size() == 1 ? " part" : " parts") +
                         " in '" + text + "'"};
    std::array<double, 4> v{};
    for (std::size_t i = 0; i < 4; ++i) {
        const std::string_view part = parts[i];
        const std::string which = std::string{"Hull::dims: "} + letters[i] + " ";
        if (part.empty()) throw InputError{which + "is empty in '" + text + "'; " + usage};
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v[i]);
        if (ec != std::errc{} || end != part.data() + part.size())
            throw InputError{which + "'" + std::string{part} + "' is not a number (in '" + text + "')"};
        if (!is_valid_extent(v[i]))
            throw InputError{which + "must be a finite number > 0 (got " + std::string{part} + " in '" + text + "')"};
    }
    return from_dimensions({v[0], v[1], v[2], v[3]});
}

bool Hull::plausible(const Dimensions& dims) noexcept {
    return dims.a + dims.b <= max_length_m && dims.c + dims.d <= max_beam_m && dims.a + dims.b >= min_extent_m && dims.c + dims.d >= min_extent_m;
}

Hull Hull::parse(std::string_view text, const std::string& name) {
    const ShipFileReader reader{name, text};
    ShipSpec spec = reader.read();
    if (const std::string problem = size_problem(spec.dims); !problem.empty()) reader.fail(problem);
    std::vector<XY> outline;
    if (spec.contour) {
        try {
            outline = from_contour(std::move(*spec.contour)).m_contour;
        } catch (const InputError& e) {
            reader.fail(std::string{"'contour': "} + e.what());
        }
    } else {
        outline = generate_outline(spec.dims, default_points);
    }
    // The dimensions are the file's, not the contour's extent (which may be a little smaller).
    return Hull{std::move(spec.name), std::move(outline), spec.dims, spec.draught_m};
}

void Hull::place(XY position, double heading_deg, std::vector<XY>& out) const {
    const double h = heading_deg * std::numbers::pi / 180.0;
    const XY forward{std::sin(h), std::cos(h)};
    const XY starboard{std::cos(h), -std::sin(h)};
    out.resize(m_contour.size());
    for (std::size_t i = 0; i < m_contour.size(); ++i)
        out[i] = position + m_contour[i].x * forward + m_contour[i].y * starboard;
}

std::vector<XY> Hull::placed(XY position, double heading_deg) const {
    std::vector<XY> out;
    place(position, heading_deg, out);
    return out;
}

}  // namespace shoal::hull
