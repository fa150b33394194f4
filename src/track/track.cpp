#include <shoal/track/track.hpp>

#include <algorithm>
#include <cctype>
#include <string>
#include <numbers>

namespace shoal::track {

namespace {

constexpr double earth_radius_m = 6371008.8;  // mean radius (IUGG)
constexpr double metres_per_nm = 1852.0;
constexpr double deg = std::numbers::pi / 180.0;

double wrap_360(double a) noexcept {
    a = std::fmod(a, 360.0);
    if (a < 0.0) a += 360.0;
    if (a >= 360.0) a = 0.0;  // -1e-17 + 360 rounds to 360
    return a;
}

}  // namespace

double distance_m(geo::LonLat a, geo::LonLat b) noexcept {
    const double dlat = (b.lat - a.lat) * deg;
    const double dlon = (b.lon - a.lon) * deg;
    const double h = std::sin(dlat / 2) * std::sin(dlat / 2) +
                     std::cos(a.lat * deg) * std::cos(b.lat * deg) * std::sin(dlon / 2) * std::sin(dlon / 2);
    return 2.0 * earth_radius_m * std::asin(std::min(1.0, std::sqrt(h)));
}

DistanceBounds distance_bounds_m(geo::LonLat a, geo::LonLat b) noexcept {
    const double pa = std::fabs(a.lat), pb = std::fabs(b.lat);
    // Longitudes more than a turn apart: the reduction below would round (readers refuse them).
    if (!(pa <= 90 && pb <= 90) || !(std::fabs(b.lon - a.lon) <= 360)) return {};
    const double dlat = std::fabs(b.lat - a.lat) * deg;
    double dlon = std::fmod(std::fabs(b.lon - a.lon) * deg, 2 * std::numbers::pi);
    if (dlon > std::numbers::pi) dlon = 2 * std::numbers::pi - dlon;
    const double x = std::max(pa, pb) * deg;
    const double x2 = x * x;
    const double cos_up = 1 - x2 / 2 + x2 * x2 / 24;  // >= cos x for every x (Taylor, alternating); > 0 up to the pole
    const double lower = earth_radius_m * dlat;
    const double upper = earth_radius_m * (dlat + cos_up * dlon);
    // Near the antipode the haversine's asin(sqrt(h)) turns one rounding of h into decimetres:
    // nothing proved beyond 0.9 of half the circumference (18,000 km; no fix to fix test comes
    // near it).
    if (!(upper <= 0.9 * std::numbers::pi * earth_radius_m)) return {};
    constexpr double rel = 1e-9, abs_m = 1e-6;
    return {std::max(0.0, lower * (1 - rel) - abs_m), upper * (1 + rel) + abs_m};
}

namespace {

/// Initial great-circle bearing from a to b, degrees clockwise from true north in [0, 360).
double initial_bearing_deg(geo::LonLat a, geo::LonLat b) noexcept {
    const double p1 = a.lat * deg, p2 = b.lat * deg, dl = (b.lon - a.lon) * deg;
    const double y = std::sin(dl) * std::cos(p2);
    const double x = std::cos(p1) * std::sin(p2) - std::sin(p1) * std::cos(p2) * std::cos(dl);
    return wrap_360(std::atan2(y, x) / deg);
}

/// Speed in knots between two fixes; NAN when the times do not increase.
double speed_kn(const Fix& a, const Fix& b) noexcept {
    const double dt = b.time_s - a.time_s;
    if (!(dt > 0.0)) return NAN;
    return distance_m(a.position, b.position) / dt * 3600.0 / metres_per_nm;
}

/// Heading from positions: a baseline long enough that 5 m of jitter turns it by 6 degrees at most.
constexpr double baseline_m = 50.0;
/// ... looked for among this many fixes (a vessel crawling at 0.5 kn with a fix a second).
constexpr std::size_t baseline_max_fixes = 256;

/// The nearest fix before (`dir` -1) or after (+1) fix i, within its piece of track (no jump
/// between), at least baseline_m from it, among the next baseline_max_fixes; null if none.
const Fix* baseline_fix(const std::vector<Fix>& fx, std::size_t i, int dir) noexcept {
    const Fix& f = fx[i];
    for (std::size_t k = i, seen = 0; seen < baseline_max_fixes; ++seen) {
        if (dir < 0) {
            if (k == 0 || fx[k].jump_before) return nullptr;
            --k;
        } else {
            if (k + 1 >= fx.size() || fx[k + 1].jump_before) return nullptr;
            ++k;
        }
        // distance_m's answer, asked only when its bounds leave it open (most fixes of a slow or
        // moored vessel lie well within the baseline).
        const DistanceBounds d = distance_bounds_m(fx[k].position, f.position);
        if (d.upper < baseline_m) continue;
        if (d.lower >= baseline_m || distance_m(fx[k].position, f.position) >= baseline_m) return &fx[k];
    }
    return nullptr;
}

}  // namespace

const char* to_string(HeadingSource s) noexcept {
    switch (s) {
        case HeadingSource::heading: return "heading";
        case HeadingSource::cog: return "cog";
        case HeadingSource::positions: return "positions";
        case HeadingSource::previous: return "previous";
        case HeadingSource::none: return "none";
    }
    return "none";
}

const char* to_string(SpeedSource s) noexcept {
    switch (s) {
        case SpeedSource::sog: return "sog";
        case SpeedSource::positions: return "positions";
        case SpeedSource::positions_over_sog: return "positions (SOG disagrees)";
        case SpeedSource::none: return "none";
    }
    return "none";
}

namespace {
constexpr const char* nav_status_names[16] = {
    "under way using engine", "at anchor", "not under command", "restricted manoeuvrability",
    "constrained by her draught", "moored", "aground", "engaged in fishing",
    "under way sailing", "reserved (HSC)", "reserved (WIG)", "towing astern",
    "pushing ahead or towing alongside", "reserved", "AIS-SART active", "not defined"};
}  // namespace

const char* nav_status_text(std::uint8_t status) noexcept { return status < 16 ? nav_status_names[status] : ""; }

const char* role_value(std::string_view text) noexcept {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
    char buf[16];
    if (text.size() > sizeof buf) return nullptr;
    for (std::size_t i = 0; i < text.size(); ++i) buf[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
    const std::string_view v(buf, text.size());
    if (v == "trainee" || v == "own" || v == "own ship" || v == "own_ship") return "trainee";
    if (v == "target") return "target";
    return nullptr;
}

std::uint8_t parse_nav_status(std::string_view text) noexcept {
    while (!text.empty() && (text.front() == ' ' || text.front() == '"')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '"' || text.back() == '\r')) text.remove_suffix(1);
    if (text.empty()) return nav_status_unknown;
    if (text.size() <= 2 && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        const int v = text.size() == 1 ? text[0] - '0' : (text[0] - '0') * 10 + (text[1] - '0');
        return v < 16 ? static_cast<std::uint8_t>(v) : nav_status_unknown;
    }
    std::string t(text.substr(0, 64));
    for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    auto has = [&](const char* s) { return t.find(s) != std::string::npos; };
    // DMA's export: "Under way using engine", "At anchor", "Not under command", "Restricted
    // maneuverability", "Constrained by her draught", "Moored", "Aground", "Engaged in fishing",
    // "Under way sailing", "Reserved for future amendment [HSC]", "... [WIG]",
    // "Power-driven vessel towing astern", "Power-driven vessel pushing ahead or towing
    // alongside", "AIS-SART is active", "Unknown value" / "Undefined".
    if (has("aground")) return 6;
    if (has("moored")) return 5;
    if (has("anchor")) return 1;
    if (has("not under command")) return 2;
    if (has("restricted")) return 3;
    if (has("draught") || has("draft")) return 4;
    if (has("fishing")) return 7;
    if (has("sailing")) return 8;
    if (has("using engine")) return 0;
    if (has("hsc")) return 9;
    if (has("wig")) return 10;
    if (has("towing astern")) return 11;
    if (has("pushing") || has("towing alongside")) return 12;
    if (has("sart")) return 14;
    if (has("undefined") || has("not defined") || has("unknown")) return 15;
    return nav_status_unknown;
}

void ReadReport::skip(const std::string& message) {
    ++skipped;
    if (messages.size() < max_messages) {
        messages.push_back(message);
        ++skips_said;
    }
}

void ReadReport::skip_all(std::size_t count, const std::string& message) {
    skipped += count;
    skips_said += count;
    messages.push_back(message);
}

void normalise(Track& track, ReadReport& report) {
    auto& fixes = track.fixes;
    // Readers never make a fix without a time; a caller building tracks by hand might.
    const auto no_time = std::stable_partition(fixes.begin(), fixes.end(),
                                               [](const Fix& f) { return std::isfinite(f.time_s); });
    for (auto it = no_time; it != fixes.end(); ++it)
        report.skip(track.file + " line " + std::to_string(it->line) + ": fix without a time; dropped");
    fixes.erase(no_time, fixes.end());

    double latest = -INFINITY;
    for (const Fix& f : fixes) {
        if (f.time_s < latest) ++report.reordered;
        latest = std::max(latest, f.time_s);
    }
    std::stable_sort(fixes.begin(), fixes.end(), [](const Fix& a, const Fix& b) { return a.time_s < b.time_s; });

    // Equal times: keep the first fix, and take from the repeats only what it lacks.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < fixes.size(); ++i) {
        if (kept > 0 && fixes[i].time_s == fixes[kept - 1].time_s) {
            Fix& k = fixes[kept - 1];
            if (std::isnan(k.heading_deg)) k.heading_deg = fixes[i].heading_deg;
            if (std::isnan(k.cog_deg)) k.cog_deg = fixes[i].cog_deg;
            if (std::isnan(k.sog_kn)) k.sog_kn = fixes[i].sog_kn;
            ++report.duplicates;
            continue;
        }
        if (kept != i) fixes[kept] = fixes[i];
        ++kept;
    }
    fixes.resize(kept);
}

void resolve_headings(Track& track, double moving_kn, double max_gap_s, bool hold_at_rest) {
    auto& fx = track.fixes;
    const std::size_t n = fx.size();
    double previous = NAN;
    for (std::size_t i = 0; i < n; ++i) {
        Fix& f = fx[i];
        if (i > 0 && (f.jump_before || f.time_s - fx[i - 1].time_s > max_gap_s)) previous = NAN;  // a new piece
        const bool has_next = i + 1 < n;
        const bool has_prev = i > 0;
        double used = NAN;
        HeadingSource source = HeadingSource::none;
        bool moving = false;
        if (std::isfinite(f.heading_deg)) {
            used = f.heading_deg;
            source = HeadingSource::heading;
        } else {
            if (std::isfinite(f.speed_used_kn)) {
                moving = f.speed_used_kn >= moving_kn;
            } else if (std::isfinite(f.sog_kn)) {
                moving = f.sog_kn >= moving_kn;
            } else {
                double v = has_next && !fx[i + 1].jump_before ? speed_kn(f, fx[i + 1]) : NAN;
                if (std::isnan(v) && has_prev && !f.jump_before) v = speed_kn(fx[i - 1], f);
                moving = v >= moving_kn;
            }
            if (moving && std::isfinite(f.cog_deg)) {
                used = f.cog_deg;
                source = HeadingSource::cog;
            } else if (moving) {
                // The course made good: the bearing towards the first later fix at least
                // `baseline_m` away (within the piece), else from the latest earlier one. Not
                // fix to fix: between fixes a few metres apart, GPS jitter turns the bearing
                // anywhere (a vessel that has just run aground would swing about).
                if (const Fix* to = baseline_fix(fx, i, +1)) {
                    used = initial_bearing_deg(f.position, to->position);
                    source = HeadingSource::positions;
                } else if (const Fix* from = baseline_fix(fx, i, -1)) {
                    used = initial_bearing_deg(from->position, f.position);
                    source = HeadingSource::positions;
                }
            }
        }
        if (std::isnan(used) && std::isfinite(previous) && (hold_at_rest || moving || std::isfinite(f.cog_deg))) {
            used = previous;
            source = HeadingSource::previous;
        }
        if (std::isnan(used)) {
            used = 0.0;
            source = HeadingSource::none;
        }
        f.heading_used_deg = wrap_360(used);
        f.heading_source = source;
        if (source != HeadingSource::none) previous = f.heading_used_deg;
    }
}

}  // namespace shoal::track
