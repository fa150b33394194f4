#include <shoal/picture/plot.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <shoal/report/report.hpp>
#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>
#include "picture/event_phrases.hpp"

namespace shoal::report {

using namespace detail;  // the event phrases (picture/event_phrases.hpp)

namespace {

using audit::Event;
using audit::EventKind;
using geo::Box;
using geo::LonLat;
using geo::XY;

constexpr double pi = 3.14159265358979323846;

// Colours: pale water, sand land, grey "no chart"; red for groundings, amber for close passes,
// muted blue, grey and green for the contacts that are not groundings (alongside, in contact
// at the first fix, in an expected-contact area).
constexpr const char* water_fill = "#f3f8fc";
constexpr const char* land_fill = "#e8dec3";
constexpr const char* outside_fill = "#d4d4d4";
constexpr const char* coast_stroke = "#3b3b3b";
constexpr const char* red = "#d62728";
constexpr const char* red_dark = "#9e0e12";
constexpr const char* amber = "#f0a000";
constexpr const char* amber_dark = "#8f5600";
constexpr const char* steel = "#4a7fa8";
constexpr const char* steel_dark = "#2b5478";
constexpr const char* slate = "#6a7f95";
constexpr const char* slate_dark = "#3e4f60";
constexpr const char* green = "#33a02c";
constexpr const char* green_dark = "#1d6419";
constexpr const char* teal = "#17becf";       ///< the chart disagrees with the traffic
constexpr const char* teal_dark = "#0b6f7a";
constexpr const char* contact_violet = "#8a76b8";  ///< a track with contacts, none of them a grounding
constexpr const char* clear_grey = "#7f8b96";
constexpr const char* trainee_blue = "#0a58ca";  ///< exercise mode: a trainee's track
constexpr const char* trainee_dark = "#063a87";
constexpr const char* no_entry_stroke = "#b42318";
constexpr const char* speed_area_stroke = "#8f5600";
constexpr const char* cpa_ink = "#111111";
constexpr const char* ink = "#222222";
constexpr const char* font_family = "DejaVu Sans, Verdana, Arial, Helvetica, sans-serif";

// ---------------------------------------------------------------- text and numbers

/// Appends `v` with one decimal ("12.3", "12", "0"): a tenth of a pixel is plenty.
void put(std::string& out, double v) {
    if (!std::isfinite(v)) v = 0;
    char b[40];
    int n = std::snprintf(b, sizeof b, "%.1f", v);
    if (n >= 2 && b[n - 2] == '.' && b[n - 1] == '0') n -= 2;
    if (n == 2 && b[0] == '-' && b[1] == '0') {
        b[0] = '0';
        n = 1;
    }
    out.append(b, static_cast<std::size_t>(n));
}

std::string num(double v) {
    std::string s;
    put(s, v);
    return s;
}


/// Characters (code points) in UTF-8 text, for estimating its width.
std::size_t glyphs(std::string_view s) {
    return static_cast<std::size_t>(
        std::count_if(s.begin(), s.end(), [](char ch) { return (static_cast<unsigned char>(ch) & 0xC0) != 0x80; }));
}

/// Rough width in px of `s` at `size` px in a sans-serif font (DejaVu Sans is among the widest).
double text_width(std::string_view s, double size) { return static_cast<double>(glyphs(s)) * 0.6 * size; }

/// `s` cut (with an ellipsis) to about `max_px` at `size` px.
std::string fit_text(const std::string& s, double size, double max_px) {
    const auto max_glyphs = static_cast<std::size_t>(std::max(4.0, std::floor(max_px / (0.6 * size))));
    if (glyphs(s) <= max_glyphs) return s;
    std::string cut;
    std::size_t count = 0;
    for (char ch : s) {
        if ((static_cast<unsigned char>(ch) & 0xC0) != 0x80 && ++count > max_glyphs - 1) break;
        cut += ch;
    }
    return cut + "\xE2\x80\xA6";
}


std::string metres_text(double m) {
    char b[40];
    if (m >= 1000) std::snprintf(b, sizeof b, "%g km", m / 1000);
    else std::snprintf(b, sizeof b, "%g m", m);
    return b;
}

// ---------------------------------------------------------------- the kinds' colours and order
// (what an event is, in words: wording.cpp)

/// Fill and dark (stroke, text) colours of an event kind.
struct KindStyle {
    const char* fill;
    const char* dark;
};

KindStyle kind_style(EventKind k) noexcept {
    switch (k) {
    case EventKind::grounding: return {red, red_dark};
    case EventKind::alongside: return {steel, steel_dark};
    case EventKind::contact_at_start: return {slate, slate_dark};
    case EventKind::expected_contact: return {green, green_dark};
    case EventKind::close_pass: return {amber, amber_dark};
    case EventKind::chart_disagrees: return {teal, teal_dark};
    }
    return {red, red_dark};
}

/// Every kind, most severe first: the order of the zoomed panels.
constexpr EventKind kinds_by_severity[] = {EventKind::grounding, EventKind::alongside, EventKind::contact_at_start,
                                           EventKind::expected_contact, EventKind::close_pass, EventKind::chart_disagrees};

/// The place of `k` in kinds_by_severity (0 to 5).
std::size_t severity(EventKind k) noexcept {
    switch (k) {
    case EventKind::grounding: return 0;
    case EventKind::alongside: return 1;
    case EventKind::contact_at_start: return 2;
    case EventKind::expected_contact: return 3;
    case EventKind::close_pass: return 4;
    case EventKind::chart_disagrees: return 5;
    }
    return 0;
}

// ---------------------------------------------------------------- geometry of the page

/// A rectangle on the page, px, y down.
struct Rect {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    double w() const noexcept { return x1 - x0; }
    double h() const noexcept { return y1 - y0; }
    bool overlaps(const Rect& o) const noexcept { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
    bool within(const Rect& o) const noexcept { return x0 >= o.x0 && y0 >= o.y0 && x1 <= o.x1 && y1 <= o.y1; }
    Rect grown(double d) const noexcept { return {x0 - d, y0 - d, x1 + d, y1 + d}; }
};

/// A panel: the ground it shows (local metres) and where it sits on the page.
struct View {
    Box world;
    Rect px;
    double scale = 1;  ///< px per local metre
    XY to_px(XY p) const noexcept { return {px.x0 + (p.x - world.minx) * scale, px.y0 + (world.maxy - p.y) * scale}; }
    XY to_world(XY q) const noexcept { return {world.minx + (q.x - px.x0) / scale, world.maxy - (q.y - px.y0) / scale}; }
};

/// The view of `want` (grown in one direction to the panel's shape, centred) in `px`.
View fit(Box want, Rect px) {
    if (want.empty()) want = {-1000, -1000, 1000, 1000};
    const double cx = (want.minx + want.maxx) / 2, cy = (want.miny + want.maxy) / 2;
    const double ww = std::max(want.maxx - want.minx, 1.0), wh = std::max(want.maxy - want.miny, 1.0);
    const double s = std::min(px.w() / ww, px.h() / wh);
    const double hw = px.w() / s / 2, hh = px.h() / s / 2;
    return {{cx - hw, cy - hh, cx + hw, cy + hh}, px, s};
}

Box intersection(const Box& a, const Box& b) {
    return {std::max(a.minx, b.minx), std::max(a.miny, b.miny), std::min(a.maxx, b.maxx), std::min(a.maxy, b.maxy)};
}

/// Where true north points and how long a true metre is, at one place of the frame.
struct Bearing {
    double north_deg = 0;  ///< true north, clockwise from the page's up (grid north)
    double k = 1;          ///< local metres per true metre (the frame's scale there)
    bool known = false;
};

Bearing bearing_at(const geo::LocalFrame& frame, XY p) {
    Bearing b;
    try {
        const LonLat ll = frame.inverse(p);
        if (!std::isfinite(ll.lon) || !std::isfinite(ll.lat)) return b;
        const Eigen::Matrix2d j = frame.jacobian(ll);
        const double nx = j(0, 1), ny = j(1, 1);  // one metre north, in local metres
        const double k = std::sqrt(std::fabs(j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0)));
        if (!std::isfinite(nx) || !std::isfinite(ny) || !(k > 0) || !std::isfinite(k)) return b;
        b.north_deg = std::atan2(nx, ny) * 180 / pi;
        b.k = k;
        b.known = true;
    } catch (const InputError&) {  // a point the frame cannot take: left out
    }
    return b;
}

/// Largest 1, 2 or 5 x 10^n not above `m` (m > 0).
double round_length(double m) {
    const double p = std::pow(10.0, std::floor(std::log10(m)));
    for (double f : {5.0, 2.0, 1.0})
        if (f * p <= m * (1 + 1e-9)) return f * p;
    return p;
}

// ---------------------------------------------------------------- the data, projected

/// What happened on a track, least to most severe: nothing, close passes, contacts that are not
/// groundings (alongside, in contact at the first fix, expected contact), groundings.
enum class Status { clear, close, contact, aground };

struct TrackDraw {
    const audit::TrackResult* result = nullptr;
    std::size_t index = 0;  ///< in AuditResult::tracks
    const audit::TrackSummary* summary = nullptr;
    std::vector<std::vector<XY>> lines;
    std::vector<std::vector<double>> times;  ///< the fix times of `lines`, aligned (empty: not known)
    Box box;
    Status status = Status::clear;
    bool trainee = false;                ///< exercise mode: a trainee's track (its own colour, arrows, time ticks)
    double exercise_start_s = NAN;       ///< the first fix of its exercise (exercise time is counted from it)
};

/// An assessment area (no-entry, speed limit), drawn and named.
struct AreaDraw {
    std::vector<XY> ring;
    std::string name;
    bool no_entry = false;
    double limit_kn = NAN;
};

/// A manoeuvre the COLREG reading found (ColregEncounter::action_a/b): where the ship was then.
struct ManoeuvreDraw {
    const TrackDraw* track = nullptr;
    double time_s = NAN;
    XY at;
    bool course = false, speed = false;
};

/// An encounter's closest approach: both reference points, both hulls then, the distance.
struct CpaDraw {
    const audit::ColregEncounter* situation = nullptr;
    const TrackDraw* a = nullptr;
    const TrackDraw* b = nullptr;
    XY pa, pb;
    std::vector<XY> hull_a, hull_b;  ///< empty when the track kept no pose to shape it
    double hull_length_m = 0;
};

struct EventDraw {
    const audit::TrackSummary* track = nullptr;
    const TrackDraw* drawn_track = nullptr;
    const Event* event = nullptr;
    XY point;
    bool point_ok = false;
    std::vector<XY> hull;
    Box box;
    double hull_length_m = 0;
    std::size_t zoom = 0;  ///< number of its zoomed panel (1-based), 0 = none
};

std::optional<XY> project(const geo::LocalFrame& frame, LonLat p) {
    if (!std::isfinite(p.lon) || !std::isfinite(p.lat)) return std::nullopt;
    try {
        const XY q = frame.forward(p);
        if (std::isfinite(q.x) && std::isfinite(q.y)) return q;
    } catch (const InputError&) {  // a point the frame cannot take: left out
    }
    return std::nullopt;
}

std::vector<XY> project_line(const geo::LocalFrame& frame, const std::vector<LonLat>& line) {
    std::vector<double> xs, ys;
    xs.reserve(line.size());
    ys.reserve(line.size());
    for (const LonLat& p : line) {
        xs.push_back(p.lon);
        ys.push_back(p.lat);
    }
    std::vector<XY> out;
    std::size_t failed = 0;
    if (!line.empty() && frame.forward(xs, ys, &failed)) {
        out.reserve(line.size());
        for (std::size_t k = 0; k < xs.size(); ++k)
            if (std::isfinite(xs[k]) && std::isfinite(ys[k])) out.push_back({xs[k], ys[k]});
        return out;
    }
    for (const LonLat& p : line)  // some point failed: keep the others
        if (auto q = project(frame, p)) out.push_back(*q);
    return out;
}

struct Scene {
    std::vector<TrackDraw> tracks;
    std::vector<EventDraw> events;
    std::vector<AreaDraw> areas;
    std::vector<ManoeuvreDraw> manoeuvres;
    std::vector<CpaDraw> cpas;
    Box data;  ///< tracks and events, local metres
};

/// Where the track was at `t` (linear between fixes, local metres) and its course over ground
/// there (degrees clockwise from the frame's +y; NaN when not moving); nothing when `t` is
/// outside its pieces.
std::optional<std::pair<XY, double>> track_at(const TrackDraw& d, double t) {
    if (!std::isfinite(t)) return std::nullopt;
    for (std::size_t l = 0; l < d.lines.size() && l < d.times.size(); ++l) {
        const auto& pts = d.lines[l];
        const auto& ts = d.times[l];
        if (ts.empty() || ts.size() != pts.size() || t < ts.front() || t > ts.back()) continue;
        if (pts.size() == 1) return std::make_pair(pts[0], NAN);
        std::size_t k = static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin());
        k = std::clamp<std::size_t>(k, 1, ts.size() - 1);
        const double span = ts[k] - ts[k - 1];
        const double f = span > 0 ? std::clamp((t - ts[k - 1]) / span, 0.0, 1.0) : 0.0;
        const XY a = pts[k - 1], b = pts[k];
        const double dx = b.x - a.x, dy = b.y - a.y;
        const double course = std::hypot(dx, dy) > 1e-6 ? std::atan2(dx, dy) * 180 / pi : NAN;
        return std::make_pair(XY{a.x + f * dx, a.y + f * dy}, course);
    }
    return std::nullopt;
}

/// The track's hull at `t`: the outline of its kept pose nearest in time, moved from where the
/// ship was at that pose to where it was at `t` and turned by the change of course over ground
/// between the two (a rigid move: the hull's shape and its angle to the course are kept).
/// Empty when no pose has an outline or `t` is outside the track.
std::vector<XY> hull_at(const TrackDraw& d, const geo::LocalFrame& frame, double t) {
    const auto now = track_at(d, t);
    if (!now) return {};
    const audit::Pose* best = nullptr;
    for (const audit::Pose& p : d.result->poses)
        if (p.hull.size() >= 4 && (!best || std::fabs(p.time_s - t) < std::fabs(best->time_s - t))) best = &p;
    if (!best) return {};
    const auto then = track_at(d, best->time_s);
    if (!then) return {};
    const double turn = std::isfinite(now->second) && std::isfinite(then->second) ? (now->second - then->second) * pi / 180 : 0.0;
    const double c = std::cos(turn), s = std::sin(turn);
    std::vector<XY> out;
    for (const LonLat& q : best->hull)
        if (auto p = project(frame, q)) {
            const double x = p->x - then->first.x, y = p->y - then->first.y;
            out.push_back({now->first.x + x * c + y * s, now->first.y - x * s + y * c});  // clockwise by `turn`
        }
    return out.size() >= 3 ? out : std::vector<XY>{};
}

double longest_chord(const std::vector<XY>& pts) {
    double m = 0;
    for (std::size_t a = 0; a < pts.size(); ++a)
        for (std::size_t b = a + 1; b < pts.size(); ++b) m = std::max(m, geo::distance(pts[a], pts[b]));
    return m;
}

/// The tracks `only` names (indices in result.tracks; empty: every track) and their events.
Scene project_scene(const audit::AuditResult& result, const geo::LocalFrame& frame, const std::vector<std::size_t>& only = {}) {
    std::vector<std::size_t> chosen = only;
    if (chosen.empty())
        for (std::size_t ti = 0; ti < result.tracks.size(); ++ti) chosen.push_back(ti);
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    if (!chosen.empty() && chosen.back() >= result.tracks.size())
        throw UsageError("PlotOptions::tracks names track " + std::to_string(chosen.back()) + " of a result with " +
                         std::to_string(result.tracks.size()));
    Scene s;
    s.tracks.reserve(chosen.size());  // events point into it: never reallocated after
    for (const std::size_t ti : chosen) {
        const auto& t = result.tracks[ti];
        TrackDraw& d = s.tracks.emplace_back();
        d.result = &t;
        d.index = ti;
        d.summary = &t.summary;
        const std::size_t contacts = t.summary.alongside + t.summary.contacts_at_start + t.summary.expected_contacts;
        d.status = t.summary.groundings > 0 ? Status::aground
                   : contacts > 0           ? Status::contact
                   : t.summary.close_passes > 0 ? Status::close
                                                : Status::clear;
        d.trainee = result.has_encounters && t.summary.role == audit::Role::trainee;
        for (std::size_t l = 0; l < t.summary.lines.size(); ++l) {
            const auto& line = t.summary.lines[l];
            const bool timed = l < t.summary.line_times.size() && t.summary.line_times[l].size() == line.size();
            std::vector<XY> pts = project_line(frame, line);
            std::vector<double> times;
            if (timed && pts.size() == line.size()) times = t.summary.line_times[l];
            else if (timed) {  // some point failed: keep the others with their times
                pts.clear();
                for (std::size_t k = 0; k < line.size(); ++k)
                    if (auto q = project(frame, line[k])) {
                        pts.push_back(*q);
                        times.push_back(t.summary.line_times[l][k]);
                    }
            }
            for (const XY& p : pts) d.box.extend(p);
            if (!pts.empty()) {
                d.lines.push_back(std::move(pts));
                d.times.push_back(std::move(times));
            }
        }
        s.data.extend(d.box);
    }
    // Exercise time: from the first fix of each exercise (of the whole result).
    std::unordered_map<std::string, double> first_fix;
    for (const auto& t : result.tracks)
        if (std::isfinite(t.summary.start_s)) {
            auto [it, fresh] = first_fix.emplace(t.summary.exercise, t.summary.start_s);
            if (!fresh) it->second = std::min(it->second, t.summary.start_s);
        }
    for (TrackDraw& d : s.tracks)
        if (auto it = first_fix.find(d.summary->exercise); it != first_fix.end()) d.exercise_start_s = it->second;
    // The assessment's areas, each once.
    if (result.has_assessment)
        for (const audit::Criterion& c : result.assessment.criteria) {
            if (c.kind != audit::CriterionKind::no_entry && c.kind != audit::CriterionKind::speed_limit) continue;
            AreaDraw a;
            a.ring = project_line(frame, c.area);
            if (a.ring.size() < 3) continue;
            a.name = c.area_name.empty() ? c.id : c.area_name;
            a.no_entry = c.kind == audit::CriterionKind::no_entry;
            a.limit_kn = a.no_entry ? NAN : c.limit;
            const bool seen = std::any_of(s.areas.begin(), s.areas.end(), [&](const AreaDraw& o) {
                return o.name == a.name && o.no_entry == a.no_entry && o.ring.size() == a.ring.size() &&
                       (a.no_entry || o.limit_kn == a.limit_kn);
            });
            if (!seen) s.areas.push_back(std::move(a));
        }
    // The encounters of the tracks drawn: the closest approaches and the manoeuvres found.
    auto drawn = [&](std::size_t ti) -> const TrackDraw* {
        auto it = std::lower_bound(s.tracks.begin(), s.tracks.end(), ti, [](const TrackDraw& d, std::size_t i) { return d.index < i; });
        return it != s.tracks.end() && it->index == ti ? &*it : nullptr;
    };
    for (const audit::ColregEncounter& c : result.situations) {
        const TrackDraw* a = drawn(c.a);
        const TrackDraw* b = drawn(c.b);
        if (!a || !b) continue;
        CpaDraw& cp = s.cpas.emplace_back();
        cp.situation = &c;
        cp.a = a;
        cp.b = b;
        const auto pa = project(frame, c.a_closest), pb = project(frame, c.b_closest);
        const auto ta = track_at(*a, c.closest_s), tb = track_at(*b, c.closest_s);
        cp.pa = pa ? *pa : ta ? ta->first : XY{NAN, NAN};
        cp.pb = pb ? *pb : tb ? tb->first : XY{NAN, NAN};
        cp.hull_a = hull_at(*a, frame, c.closest_s);
        cp.hull_b = hull_at(*b, frame, c.closest_s);
        cp.hull_length_m = std::max(longest_chord(cp.hull_a), longest_chord(cp.hull_b));
        if (!std::isfinite(cp.pa.x) || !std::isfinite(cp.pb.x)) s.cpas.pop_back();
        for (const auto& who : {std::pair{a, &c.action_a}, std::pair{b, &c.action_b}}) {
            const TrackDraw* track = who.first;  // named, not bound: a lambda below takes them (clang 14)
            const audit::Manoeuvre* m = who.second;
            if (!std::isfinite(m->time_s)) continue;
            const auto at = track_at(*track, m->time_s);
            if (!at) continue;
            const bool seen = std::any_of(s.manoeuvres.begin(), s.manoeuvres.end(),
                                          [&](const ManoeuvreDraw& o) { return o.track == track && o.time_s == m->time_s; });
            if (!seen) s.manoeuvres.push_back({track, m->time_s, at->first, m->course, m->speed});
        }
    }
    for (const TrackDraw& td : s.tracks) {
        for (const auto& e : td.result->events) {
            EventDraw& d = s.events.emplace_back();
            d.track = td.summary;
            d.drawn_track = &td;
            d.event = &e;
            if (auto p = project(frame, e.point)) {
                d.point = *p;
                d.point_ok = true;
                d.box.extend(*p);
            }
            for (const LonLat& h : e.hull)
                if (auto q = project(frame, h)) {
                    d.hull.push_back(*q);
                    d.box.extend(*q);
                }
            for (std::size_t a = 0; a < d.hull.size(); ++a)
                for (std::size_t b = a + 1; b < d.hull.size(); ++b)
                    d.hull_length_m = std::max(d.hull_length_m, geo::distance(d.hull[a], d.hull[b]));
            if (!d.point_ok && !d.hull.empty()) {  // fall back to the middle of the hull
                d.point = {(d.box.minx + d.box.maxx) / 2, (d.box.miny + d.box.maxy) / 2};
                d.point_ok = true;
            }
            if (!d.box.empty()) s.data.extend(d.box);
        }
    }
    return s;
}

// ---------------------------------------------------------------- paths

/// Appends the polyline (page px) to a path in relative moves, dropping points closer than
/// `min_px` to the last one kept (the last point is always kept). Nothing for a polyline that
/// stays within 0.1 px.
void append_simplified(std::string& d, const std::vector<XY>& px, double min_px) {
    if (px.size() < 2) return;
    auto tenth = [](double v) { return std::round(v * 10) / 10; };
    std::string part = "M";
    XY last{tenth(px[0].x), tenth(px[0].y)};
    put(part, last.x);
    part += ',';
    put(part, last.y);
    XY kept = px[0];
    bool any = false;
    for (std::size_t k = 1; k < px.size(); ++k) {
        const double dist = geo::distance(px[k], kept);
        const bool end = k + 1 == px.size();
        if (dist >= min_px || (end && dist >= 0.1)) {
            const XY q{tenth(px[k].x), tenth(px[k].y)};
            part += any ? ' ' : 'l';
            put(part, q.x - last.x);
            part += ',';
            put(part, q.y - last.y);
            last = q;
            kept = px[k];
            any = true;
        }
    }
    if (any) d += part;
}

/// The parts of a polyline (local metres) that come near the view, as a path in page px.
std::string line_path(const std::vector<XY>& pts, const View& v, double min_px) {
    std::string d;
    const Rect near = v.px.grown(20);
    std::vector<XY> run;
    auto flush = [&] {
        append_simplified(d, run, min_px);
        run.clear();
    };
    for (std::size_t k = 1; k < pts.size(); ++k) {
        const XY a = v.to_px(pts[k - 1]), b = v.to_px(pts[k]);
        const Rect seg{std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x) + 1e-9, std::max(a.y, b.y) + 1e-9};
        if (!seg.overlaps(near)) {
            flush();
            continue;
        }
        if (run.empty()) run.push_back(a);
        run.push_back(b);
    }
    flush();
    return d;
}

/// The coastline segments of the coast cells under the view as one path in page px: the
/// pieces of each cell chained, the chains of neighbouring cells joined where one ends at the
/// start of another, then simplified.
std::string coast_path(const grid::CoastGrid& g, const View& v, double min_px) {
    std::string d;
    const Box w = intersection(v.world, g.extent());
    if (w.empty() || g.nx() <= 0 || g.ny() <= 0) return d;
    const int i0 = std::clamp(g.col_of(w.minx), 0, g.nx() - 1), i1 = std::clamp(g.col_of(w.maxx), 0, g.nx() - 1);
    const int j0 = std::clamp(g.row_of(w.miny), 0, g.ny() - 1), j1 = std::clamp(g.row_of(w.maxy), 0, g.ny() - 1);
    const double join_m = std::max(1e-6, 1e-9 * g.cell_size());
    std::vector<std::vector<XY>> chains;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            if (g.state(i, j) != grid::CellState::coast) continue;
            XY last_b{NAN, NAN};
            bool open = false;
            for (const grid::Segment& s : g.segments(i, j)) {
                if (!open || !(geo::distance(s.a, last_b) <= join_m)) {
                    chains.emplace_back().push_back(v.to_px(s.a));
                    open = true;
                }
                chains.back().push_back(v.to_px(s.b));
                last_b = s.b;
            }
        }
    // Join chains end to start (points equal to a twentieth of a pixel).
    auto key = [](XY p) {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::llround(p.x * 20))) << 32) |
               static_cast<std::uint32_t>(std::llround(p.y * 20));
    };
    std::unordered_multimap<std::uint64_t, std::size_t> starts;
    std::unordered_set<std::uint64_t> ends;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        starts.emplace(key(chains[c].front()), c);
        ends.insert(key(chains[c].back()));
    }
    std::vector<bool> used(chains.size(), false);
    std::vector<XY> line;
    auto follow = [&](std::size_t c) {
        line = chains[c];
        used[c] = true;
        for (;;) {
            auto [a, b] = starts.equal_range(key(line.back()));
            auto next = std::find_if(a, b, [&](const auto& kv) { return !used[kv.second]; });
            if (next == b) break;
            used[next->second] = true;
            const auto& more = chains[next->second];
            line.insert(line.end(), more.begin() + 1, more.end());
        }
        append_simplified(d, line, min_px);
    };
    for (std::size_t c = 0; c < chains.size(); ++c)  // first the chains nothing leads into
        if (!used[c] && !ends.count(key(chains[c].front()))) follow(c);
    for (std::size_t c = 0; c < chains.size(); ++c)  // then the loops
        if (!used[c]) follow(c);
    return d;
}

/// Land as the grid sees it (`is_land` at the centre of each sample square of `cell_px`),
/// as rectangles: runs along a row, merged with equal runs of the rows below.
std::string land_path(const grid::CoastGrid& g, const View& v, double cell_px) {
    struct Run {
        int c0, c1, r0, r1;  // columns [c0, c1), rows [r0, r1)
    };
    std::string d;
    if (intersection(v.world, g.extent()).empty()) return d;
    const int cols = static_cast<int>(std::ceil(v.px.w() / cell_px));
    const int rows = static_cast<int>(std::ceil(v.px.h() / cell_px));
    auto emit = [&](const Run& r) {
        d += 'M';
        put(d, v.px.x0 + r.c0 * cell_px);
        d += ',';
        put(d, v.px.y0 + r.r0 * cell_px);
        d += 'h';
        put(d, (r.c1 - r.c0) * cell_px);
        d += 'v';
        put(d, (r.r1 - r.r0) * cell_px);
        d += 'h';
        put(d, -(r.c1 - r.c0) * cell_px);
        d += 'z';
    };
    std::vector<Run> open, row, next;
    for (int r = 0; r < rows; ++r) {
        row.clear();
        const double y = v.px.y0 + (r + 0.5) * cell_px;
        int start = -1;
        for (int c = 0; c <= cols; ++c) {
            const bool land = c < cols && g.is_land(v.to_world({v.px.x0 + (c + 0.5) * cell_px, y}));
            if (land && start < 0) start = c;
            if (!land && start >= 0) {
                row.push_back({start, c, r, r + 1});
                start = -1;
            }
        }
        next.clear();
        std::size_t k = 0;
        for (Run n : row) {
            while (k < open.size() && open[k].c0 < n.c0) emit(open[k++]);
            if (k < open.size() && open[k].c0 == n.c0 && open[k].c1 == n.c1) {
                n.r0 = open[k++].r0;
            }
            next.push_back(n);
        }
        while (k < open.size()) emit(open[k++]);
        open.swap(next);
    }
    for (const Run& r : open) emit(r);
    return d;
}

std::string points_attr(const std::vector<XY>& pts, const View& v) {
    std::string s;
    for (const XY& p : pts) {
        const XY q = v.to_px(p);
        if (!s.empty()) s += ' ';
        put(s, q.x);
        s += ',';
        put(s, q.y);
    }
    return s;
}

// ---------------------------------------------------------------- labels

/// Places labels where they overlap nothing placed or blocked before, inside the panel. The
/// rectangles taken are kept in buckets of a coarse grid over the panel, so that a try looks
/// only at the rectangles near it: placing a label costs the same with 100 vessels or 100,000
/// (before, every try was tested against every rectangle taken: quadratic in vessels).
class Labels {
public:
    explicit Labels(Rect bounds) : m_bounds(bounds) {
        m_cols = std::max(1, static_cast<int>(std::ceil(bounds.w() / bucket_px)));
        m_rows = std::max(1, static_cast<int>(std::ceil(bounds.h() / bucket_px)));
        m_buckets.resize(static_cast<std::size_t>(m_cols) * static_cast<std::size_t>(m_rows));
    }
    void block(const Rect& r) {
        const Span s = span(r);
        if (s.empty()) return;  // outside the panel: no label there can overlap it
        const auto id = static_cast<std::uint32_t>(m_used.size());
        m_used.push_back(r);
        for (int j = s.j0; j <= s.j1; ++j)
            for (int i = s.i0; i <= s.i1; ++i) m_buckets[static_cast<std::size_t>(j) * m_cols + i].push_back(id);
    }
    /// Tries the four corners around `anchor` (px) at `gap`, then above and below, then the
    /// same further out up to `reach` px; the box of the label, or nothing.
    std::optional<Rect> place(XY anchor, double w, double h, double gap, double reach = 0) {
        // A step of at least 2 px: with no gap (an area's name, placed on its centre first) the
        // step d / 2 from d = 0 was 0, and a name whose first tries were all taken never left the loop.
        for (double d = gap; d <= std::max(gap, reach); d += std::max(d < 2 * gap ? gap : d / 2, 2.0)) {
            const Rect tries[] = {
                {anchor.x + d, anchor.y - d - h, anchor.x + d + w, anchor.y - d},
                {anchor.x + d, anchor.y + d, anchor.x + d + w, anchor.y + d + h},
                {anchor.x - d - w, anchor.y - d - h, anchor.x - d, anchor.y - d},
                {anchor.x - d - w, anchor.y + d, anchor.x - d, anchor.y + d + h},
                {anchor.x - w / 2, anchor.y - 2 * d - h, anchor.x + w / 2, anchor.y - 2 * d},
                {anchor.x - w / 2, anchor.y + 2 * d, anchor.x + w / 2, anchor.y + 2 * d + h},
                {anchor.x + 2 * d, anchor.y - h / 2, anchor.x + 2 * d + w, anchor.y + h / 2},
                {anchor.x - 2 * d - w, anchor.y - h / 2, anchor.x - 2 * d, anchor.y + h / 2},
            };
            for (const Rect& r : tries) {
                if (!r.within(m_bounds) || taken(r)) continue;
                block(r);
                return r;
            }
        }
        return std::nullopt;
    }

private:
    static constexpr double bucket_px = 48;
    struct Span {
        int i0 = 0, j0 = 0, i1 = -1, j1 = -1;
        bool empty() const noexcept { return i1 < i0 || j1 < j0; }
    };
    /// The buckets `r` touches (clamped to the panel).
    Span span(const Rect& r) const noexcept {
        if (!r.overlaps(m_bounds)) return {};  // then it overlaps no label (labels lie within the panel)
        auto at = [&](double v, double v0, int n) {
            return static_cast<int>(std::clamp(std::floor((v - v0) / bucket_px), 0.0, static_cast<double>(n - 1)));
        };
        return {at(r.x0, m_bounds.x0, m_cols), at(r.y0, m_bounds.y0, m_rows), at(r.x1, m_bounds.x0, m_cols), at(r.y1, m_bounds.y0, m_rows)};
    }
    bool taken(const Rect& r) const {
        const Span s = span(r);
        for (int j = s.j0; j <= s.j1; ++j)
            for (int i = s.i0; i <= s.i1; ++i)
                for (const std::uint32_t id : m_buckets[static_cast<std::size_t>(j) * m_cols + i])
                    if (m_used[id].overlaps(r)) return true;
        return false;
    }

    Rect m_bounds;
    int m_cols = 1, m_rows = 1;
    std::vector<Rect> m_used;
    std::vector<std::vector<std::uint32_t>> m_buckets;  ///< per bucket (row-major): ids in m_used
};

/// A thin line from `anchor` to the nearest point of a label placed away from it.
void leader(std::string& out, XY anchor, const Rect& box, double min_px, const char* colour) {
    const XY near{std::clamp(anchor.x, box.x0, box.x1), std::clamp(anchor.y, box.y0, box.y1)};
    if (geo::distance(anchor, near) < min_px) return;
    out += "<line class=\"leader\" x1=\"" + num(anchor.x) + "\" y1=\"" + num(anchor.y) + "\" x2=\"" + num(near.x) + "\" y2=\"" +
           num(near.y) + "\" stroke=\"" + colour + "\" stroke-width=\"0.8\"/>\n";
}

/// A label on a pale box (readable over lines), text left-aligned in `box`.
void label(std::string& out, const Rect& box, const std::string& text, double size, const char* colour,
           const char* cls = "label", bool bold = false) {
    out += "<g class=\"" + std::string(cls) + "\"><rect x=\"" + num(box.x0) + "\" y=\"" + num(box.y0) + "\" width=\"" +
           num(box.w()) + "\" height=\"" + num(box.h()) +
           "\" rx=\"2\" fill=\"#ffffff\" fill-opacity=\"0.8\"/><text x=\"" + num(box.x0 + 2) + "\" y=\"" +
           num(box.y0 + size * 0.95 + 1) + "\" font-size=\"" + num(size) + "\" fill=\"" + colour + "\"" +
           (bold ? " font-weight=\"bold\"" : "") + ">" + markup_text(text) + "</text></g>\n";
}

// ---------------------------------------------------------------- pieces of a panel

void text(std::string& out, double x, double y, const std::string& s, double size, const char* colour,
          const char* extra = "") {
    out += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) + "\" fill=\"" + colour + "\"" + extra +
           ">" + markup_text(s) + "</text>\n";
}

/// Background (grey where there is no chart), water over the grid's extent, land, coastline.
void draw_chart(std::string& out, const grid::CoastGrid& g, const View& v, double land_px, double coast_width) {
    out += "<rect class=\"outside\" x=\"" + num(v.px.x0) + "\" y=\"" + num(v.px.y0) + "\" width=\"" + num(v.px.w()) +
           "\" height=\"" + num(v.px.h()) + "\" fill=\"" + outside_fill + "\"/>\n";
    const Box covered = intersection(v.world, g.extent());
    if (!covered.empty()) {
        const XY a = v.to_px({covered.minx, covered.maxy}), b = v.to_px({covered.maxx, covered.miny});
        out += "<rect class=\"water\" x=\"" + num(a.x) + "\" y=\"" + num(a.y) + "\" width=\"" + num(b.x - a.x) +
               "\" height=\"" + num(b.y - a.y) + "\" fill=\"" + water_fill + "\"/>\n";
    }
    if (g.has_land_side()) {
        const std::string land = land_path(g, v, land_px);
        if (!land.empty()) out += "<path class=\"land\" fill=\"" + std::string(land_fill) + "\" d=\"" + land + "\"/>\n";
    }
    const std::string coast = coast_path(g, v, coast_width < 1 ? 0.75 : 0.4);
    if (!coast.empty())
        out += "<path class=\"coastline\" fill=\"none\" stroke=\"" + std::string(coast_stroke) + "\" stroke-width=\"" +
               num(coast_width) + "\" stroke-linejoin=\"round\" stroke-linecap=\"round\" d=\"" + coast + "\"/>\n";
}

const char* status_colour(Status s) {
    switch (s) {
    case Status::aground: return red;
    case Status::contact: return contact_violet;
    case Status::close: return amber;
    case Status::clear: return clear_grey;
    }
    return clear_grey;
}

void draw_track(std::string& out, const TrackDraw& t, const View& v, const char* colour, double width, double opacity,
                const char* cls = "track") {
    if (t.box.empty() || v.world.distance_to(t.box) > 0) return;
    std::string d;
    for (const auto& line : t.lines) d += line_path(line, v, 0.6);
    if (d.empty()) return;
    out += "<path class=\"" + std::string(cls) + "\" fill=\"none\" stroke=\"" + std::string(colour) + "\" stroke-width=\"" + num(width) +
           "\" stroke-opacity=\"" + num(opacity) + "\" stroke-linejoin=\"round\" stroke-linecap=\"round\" d=\"" + d +
           "\"><title>" + markup_text("track " + t.summary->id + (t.summary->name.empty() ? "" : " (" + t.summary->name + ")")) +
           "</title></path>\n";
}

/// Single-fix pieces have no line to draw: a dot shows them.
void draw_lonely_fixes(std::string& out, const TrackDraw& t, const View& v, const char* colour) {
    for (const auto& line : t.lines) {
        if (line.size() != 1) continue;
        const XY p = v.to_px(line[0]);
        if (!Rect{p.x, p.y, p.x, p.y}.overlaps(v.px.grown(5))) continue;
        out += "<circle class=\"track fix\" cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"1.8\" fill=\"" + colour + "\"/>\n";
    }
}

std::string event_title(const EventDraw& e) { return event_description(*e.track, *e.event); }

/// The hull footprint; dashed when the heading was unknown (the hull's circle is drawn then).
void draw_hull(std::string& out, const EventDraw& e, const View& v, bool focus) {
    if (e.hull.size() < 3) return;
    const KindStyle k = kind_style(e.event->kind);
    const char* stroke = e.event->kind == EventKind::grounding && !focus ? red : k.dark;
    out += std::string("<polygon class=\"hull ") + audit::to_string(e.event->kind) + "\" points=\"" + points_attr(e.hull, v) +
           "\" fill=\"" + k.fill + "\" fill-opacity=\"" + (focus ? "0.35" : "0.2") + "\" stroke=\"" + stroke +
           "\" stroke-width=\"" + (focus ? "1.6" : "1") + "\" stroke-linejoin=\"round\"" +
           (e.event->orientation_unknown ? (focus ? " stroke-dasharray=\"5,3\"" : " stroke-dasharray=\"3,2\"") : "") + ">";
    if (e.event->orientation_unknown) out += "<title>hull circle: heading unknown, the hull at any heading</title>";
    out += "</polygon>\n";
}

/// `pts` (page px) as an SVG points list.
std::string page_points(const std::vector<XY>& pts) {
    std::string s;
    for (const XY& q : pts) {
        if (!s.empty()) s += ' ';
        put(s, q.x);
        s += ',';
        put(s, q.y);
    }
    return s;
}

/// The marker shape of a kind at `p` (page px), `size` its radius: a circle (grounding,
/// larger; alongside), a square (in contact at the first fix), a diamond (expected contact),
/// a triangle (close pass). Returns the element's start up to its attributes' end, without
/// the closing of the tag; sets `tag` to the element's name.
std::string marker_shape(EventKind k, XY p, double size, std::string* tag) {
    switch (k) {
    case EventKind::grounding:
    case EventKind::alongside:
        *tag = "circle";
        return "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"" + num(size) + "\"";
    case EventKind::contact_at_start:
        *tag = "rect";
        return "<rect x=\"" + num(p.x - size * 0.85) + "\" y=\"" + num(p.y - size * 0.85) + "\" width=\"" + num(size * 1.7) +
               "\" height=\"" + num(size * 1.7) + "\"";
    case EventKind::expected_contact: {
        const double s = size * 1.15;
        *tag = "polygon";
        return "<polygon points=\"" + page_points({{p.x, p.y - s}, {p.x + s, p.y}, {p.x, p.y + s}, {p.x - s, p.y}}) + "\"";
    }
    case EventKind::close_pass:
    case EventKind::chart_disagrees: {
        const double s = size * 1.25;
        *tag = "polygon";
        return "<polygon points=\"" + page_points({{p.x, p.y - s}, {p.x + s * 0.9, p.y + s * 0.6}, {p.x - s * 0.9, p.y + s * 0.6}}) +
               "\"";
    }
    }
    *tag = "circle";
    return "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"" + num(size) + "\"";
}

/// Marker radius (px) of a kind in the overview: groundings and close passes large, the other
/// contacts small.
double marker_size(EventKind k) noexcept {
    return k == EventKind::grounding || k == EventKind::close_pass ? 5 : k == EventKind::alongside ? 3.5 : 3.2;
}

/// A marker in the overview (class `event <kind>`, one per event), the shape and colour of
/// its kind, with the event's full description as its tooltip.
Rect draw_marker(std::string& out, const EventDraw& e, const View& v, const char* cls, double size) {
    const XY p = v.to_px(e.point);
    const EventKind kind = e.event->kind;
    std::string tag;
    std::string shape = marker_shape(kind, p, size, &tag);
    shape.insert(tag.size() + 1, " class=\"" + std::string(cls) + " " + audit::to_string(kind) + "\"");
    const bool big = kind == EventKind::grounding || kind == EventKind::close_pass;
    out += shape + " fill=\"" + kind_style(kind).fill + "\" stroke=\"#ffffff\" stroke-width=\"" + (big ? "1.5" : "1") +
           "\" stroke-linejoin=\"round\"><title>" + markup_text(event_title(e)) + "</title></" + tag + ">\n";
    const double r = size * 1.25;
    return {p.x - r - 1, p.y - r - 1, p.x + r + 1, p.y + r + 1};
}

/// A contact point in a zoomed panel: a ring, so that the hull under it stays visible.
Rect draw_contact(std::string& out, const EventDraw& e, const View& v, double r) {
    const XY p = v.to_px(e.point);
    const char* dark = kind_style(e.event->kind).dark;
    out += std::string("<g class=\"contact ") + audit::to_string(e.event->kind) + "\"><title>" + markup_text(event_title(e)) +
           "</title><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"" + num(r) +
           "\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"3.5\"/><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) +
           "\" r=\"" + num(r) + "\" fill=\"none\" stroke=\"" + dark + "\" stroke-width=\"1.8\"/><circle cx=\"" + num(p.x) +
           "\" cy=\"" + num(p.y) + "\" r=\"1.2\" fill=\"" + dark + "\"/></g>\n";
    return {p.x - r - 2, p.y - r - 2, p.x + r + 2, p.y + r + 2};
}

/// Page box of an event's hull footprint (empty far away when it has none).
Rect hull_rect(const EventDraw& e, const View& v) {
    if (e.hull.empty()) return {-1e9, -1e9, -1e9, -1e9};
    Rect r{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const XY& p : e.hull) {
        const XY q = v.to_px(p);
        r = {std::min(r.x0, q.x), std::min(r.y0, q.y), std::max(r.x1, q.x), std::max(r.y1, q.y)};
    }
    return r.grown(1);
}

/// Scale bar (true metres) in the panel's lower left corner; returns the page area it takes.
Rect draw_scale_bar(std::string& out, const View& v, const Bearing& b) {
    const double px_per_true_m = v.scale * b.k;
    const double length_m = round_length(std::max(v.px.w() * 0.22, 40.0) / px_per_true_m);
    const double bar = length_m * px_per_true_m;
    const std::string caption = metres_text(length_m);
    const double w = std::max(bar, text_width(caption, 11)) + 16, h = 34;
    const Rect box{v.px.x0 + 8, v.px.y1 - 8 - h, v.px.x0 + 8 + w, v.px.y1 - 8};
    const double x = box.x0 + 8, y = box.y0 + 21;
    out += "<g class=\"scale-bar\"><title>" + markup_text("scale bar: " + caption + " on the ground" +
                                                    (b.known ? "" : " (frame scale unknown here: local metres)")) +
           "</title>\n<rect x=\"" + num(box.x0) + "\" y=\"" + num(box.y0) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
           "\" rx=\"3\" fill=\"#ffffff\" fill-opacity=\"0.85\"/>\n<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" +
           num(bar / 2) + "\" height=\"5\" fill=\"" + ink + "\"/>\n<rect x=\"" + num(x + bar / 2) + "\" y=\"" + num(y) +
           "\" width=\"" + num(bar / 2) + "\" height=\"5\" fill=\"#ffffff\"/>\n<rect class=\"bar\" x=\"" + num(x) + "\" y=\"" + num(y) +
           "\" width=\"" + num(bar) + "\" height=\"5\" fill=\"none\" stroke=\"" + ink + "\" stroke-width=\"1\"/>\n";
    text(out, x, y - 5, caption, 11, ink, " class=\"caption\"");
    out += "</g>\n";
    return box;
}

/// Arrow to true north in the panel's upper right corner; returns the page area it takes.
Rect draw_north_arrow(std::string& out, const View& v, const Bearing& b) {
    const double r = 22;
    const XY c{v.px.x1 - 8 - r, v.px.y0 + 8 + r};
    char title[160];
    if (b.known)
        std::snprintf(title, sizeof title, "true north (%.2f\xC2\xB0 %s of grid north, the page's up)", std::fabs(b.north_deg),
                      b.north_deg >= 0 ? "east" : "west");
    else
        std::snprintf(title, sizeof title, "grid north (true north unknown here)");
    out += "<g class=\"north-arrow\" transform=\"translate(" + num(c.x) + "," + num(c.y) + ") rotate(";
    char angle[32];
    std::snprintf(angle, sizeof angle, "%.3f", b.north_deg);
    out += std::string(angle) + ")\"><title>" + markup_text(title) + "</title>\n<circle r=\"" + num(r) +
           "\" fill=\"#ffffff\" fill-opacity=\"0.85\"/>\n<polygon points=\"0,-8 -6,16 0,11\" fill=\"" + ink +
           "\"/>\n<polygon points=\"0,-8 6,16 0,11\" fill=\"#ffffff\" stroke=\"" + ink +
           "\" stroke-width=\"1\" stroke-linejoin=\"round\"/>\n<polygon points=\"0,-8 -6,16 0,11\" fill=\"none\" stroke=\"" + ink +
           "\" stroke-width=\"1\" stroke-linejoin=\"round\"/>\n";
    text(out, 0, -10.5, "N", 11, ink, " font-weight=\"bold\" text-anchor=\"middle\"");
    out += "</g>\n";
    return {c.x - r, c.y - r, c.x + r, c.y + r};
}

void open_panel(std::string& out, const View& v, const std::string& cls, const std::string& id) {
    out += "<g class=\"panel " + cls + "\" id=\"" + id + "\">\n<defs><clipPath id=\"clip-" + id + "\"><rect x=\"" + num(v.px.x0) +
           "\" y=\"" + num(v.px.y0) + "\" width=\"" + num(v.px.w()) + "\" height=\"" + num(v.px.h()) +
           "\"/></clipPath></defs>\n<g clip-path=\"url(#clip-" + id + ")\">\n";
}

void close_panel(std::string& out, const View& v) {
    out += "<rect class=\"frame\" x=\"" + num(v.px.x0) + "\" y=\"" + num(v.px.y0) + "\" width=\"" + num(v.px.w()) + "\" height=\"" +
           num(v.px.h()) + "\" fill=\"none\" stroke=\"#555555\" stroke-width=\"1\"/>\n</g>\n";
}

// ---------------------------------------------------------------- exercise mode: areas, trainees, encounters

/// "no entry" or "speed limit 8.0 kn".
std::string area_rule(const AreaDraw& a) { return a.no_entry ? "no entry" : "speed limit " + fixed_text(a.limit_kn, 1) + " kn"; }

/// The assessment's areas: a pale fill and a dashed outline (red: no entry; brown: speed limit).
void draw_areas(std::string& out, const Scene& scene, const View& v) {
    for (const AreaDraw& a : scene.areas) {
        const char* stroke = a.no_entry ? no_entry_stroke : speed_area_stroke;
        out += std::string("<polygon class=\"area ") + (a.no_entry ? "no-entry" : "speed-limit") + "\" points=\"" + points_attr(a.ring, v) +
               "\" fill=\"" + (a.no_entry ? red : amber) + "\" fill-opacity=\"0.12\" stroke=\"" + stroke + "\" stroke-width=\"1.6\" stroke-dasharray=\"" +
               (a.no_entry ? "7,3" : "2,3") + "\"><title>" + markup_text(a.name + ": " + area_rule(a)) + "</title></polygon>\n";
    }
}

/// The areas' names ("Mother Bank (no entry)") inside them where they fit, else beside them.
void name_areas(std::string& out, const Scene& scene, const View& v, Labels& labels) {
    for (const AreaDraw& a : scene.areas) {
        Box b;
        for (const XY& p : a.ring) b.extend(p);
        XY c = v.to_px({(b.minx + b.maxx) / 2, (b.miny + b.maxy) / 2});
        c.x = std::clamp(c.x, v.px.x0 + 4, v.px.x1 - 4);
        c.y = std::clamp(c.y, v.px.y0 + 4, v.px.y1 - 4);
        const std::string s = a.name + " (" + area_rule(a) + ")";
        if (auto r = labels.place(c, text_width(s, 10) + 4, 14, 0, 60))
            label(out, *r, s, 10, a.no_entry ? no_entry_stroke : speed_area_stroke, "label area-name", true);
    }
}

/// The minutes between time ticks: the smallest of 1, 2, 5, 10, 15, 20, 30 min, 1, 2, 4, 8 h
/// that gives at most 12 over `span_s`.
double tick_minutes(double span_s) {
    for (const double m : {1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0, 60.0, 120.0, 240.0})
        if (span_s / (60 * m) <= 12) return m;
    return 480;
}

/// Exercise time with UTC beside it, for a time tick `minutes` after the start, at `t`:
/// "T+10:00 10:12:30Z", as the debrief's events give it (exercise_time_text).
std::string tick_text(double minutes, double t) { return exercise_time_text(t, t - 60 * minutes) + " " + clock_text(t); }

/// A trainee's direction arrows (one every 110 px of track on the page, class `direction`) and
/// time ticks (class `time-tick`, at whole multiples of tick_minutes from the exercise start;
/// their labels placed later from `ticks`).
struct Tick {
    XY at;
    std::string text;
};
void draw_direction_and_ticks(std::string& out, const TrackDraw& t, const View& v, std::vector<Tick>& ticks) {
    if (t.box.empty() || v.world.distance_to(t.box) > 0) return;
    std::string arrows;
    for (const auto& line : t.lines) {
        double walked = 55;  // the first arrow half a spacing in
        for (std::size_t k = 1; k < line.size(); ++k) {
            const XY a = v.to_px(line[k - 1]), b = v.to_px(line[k]);
            const double len = geo::distance(a, b);
            if (len <= 0) continue;
            const XY u{(b.x - a.x) / len, (b.y - a.y) / len};
            for (double at = 110 - walked; at <= len; at += 110) {
                const XY p{a.x + u.x * at, a.y + u.y * at};
                if (!Rect{p.x, p.y, p.x, p.y}.overlaps(v.px)) continue;
                const XY tip{p.x + u.x * 5, p.y + u.y * 5}, back{p.x - u.x * 5, p.y - u.y * 5};
                arrows += "<polygon class=\"direction\" points=\"" + page_points({tip, {back.x - u.y * 4.5, back.y + u.x * 4.5}, {back.x + u.y * 4.5, back.y - u.x * 4.5}}) +
                          "\"/>";
            }
            walked = std::fmod(walked + len, 110.0);
        }
    }
    if (!arrows.empty())
        out += "<g class=\"directions\" fill=\"" + std::string(trainee_dark) + "\" stroke=\"#ffffff\" stroke-width=\"0.8\" stroke-linejoin=\"round\">" + arrows + "</g>\n";
    if (!std::isfinite(t.exercise_start_s) || !std::isfinite(t.summary->start_s) || !std::isfinite(t.summary->end_s)) return;  // NaN: no end to the ticks
    const double minutes = tick_minutes(t.summary->end_s - t.exercise_start_s);
    std::string marks;
    std::optional<XY> last;
    for (double n = std::ceil((t.summary->start_s - t.exercise_start_s) / (60 * minutes) - 1e-9); ; ++n) {
        if (n < 1) continue;
        const double time = t.exercise_start_s + n * minutes * 60;
        if (time > t.summary->end_s + 1e-6) break;
        const auto at = track_at(t, time);
        if (!at) continue;
        const XY p = v.to_px(at->first);
        if (!Rect{p.x, p.y, p.x, p.y}.overlaps(v.px) || (last && geo::distance(*last, p) < 24)) continue;
        last = p;
        // Across the track: perpendicular to the course (page y is down).
        const double c = std::isfinite(at->second) ? at->second * pi / 180 : 0;
        const XY across{std::cos(c), std::sin(c)};
        marks += "<line class=\"time-tick\" data-minutes=\"" + num(n * minutes) + "\" x1=\"" + num(p.x - across.x * 6) + "\" y1=\"" +
                 num(p.y - across.y * 6) + "\" x2=\"" + num(p.x + across.x * 6) + "\" y2=\"" + num(p.y + across.y * 6) + "\"><title>" +
                 markup_text(t.summary->id + ": " + tick_text(n * minutes, time) + " UTC") + "</title></line>";
        ticks.push_back({p, tick_text(n * minutes, time)});
    }
    if (!marks.empty())
        out += "<g class=\"time-ticks\" stroke=\"" + std::string(trainee_dark) + "\" stroke-width=\"2\" stroke-linecap=\"round\">" + marks + "</g>\n";
}

/// "course", "speed", "course and speed".
const char* manoeuvre_words(const ManoeuvreDraw& m) { return m.course && m.speed ? "course and speed" : m.course ? "course" : "speed"; }

/// A manoeuvre on its track: a ring in the track's colour (class `manoeuvre`) with what was
/// altered and when as its tooltip; returns its page box.
Rect draw_manoeuvre(std::string& out, const ManoeuvreDraw& m, const View& v, const char* colour) {
    const XY p = v.to_px(m.at);
    out += "<g class=\"manoeuvre\" data-track=\"" + markup_text(m.track->summary->id) + "\"><title>" +
           markup_text(m.track->summary->id + " altered " + manoeuvre_words(m) + " at " + clock_text(m.time_s) + " UTC (" +
                       exercise_time_text(m.time_s, m.track->exercise_start_s) + ")") +
           "</title><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"6\" fill=\"#ffffff\" stroke=\"" + colour +
           "\" stroke-width=\"2.2\"/><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"2\" fill=\"" + colour + "\"/></g>\n";
    return {p.x - 7, p.y - 7, p.x + 7, p.y + 7};
}

/// "alters course 10:05:00Z".
std::string manoeuvre_label(const ManoeuvreDraw& m) { return std::string("alters ") + manoeuvre_words(m) + " " + clock_text(m.time_s); }

/// "CPA 420 m 10:12:30Z".
std::string cpa_label(const CpaDraw& c) {
    return "CPA " + fixed_text(c.situation->closest_m, 0) + " m " + clock_text(c.situation->closest_s);
}

/// The closest approach: both hulls at that moment (in the colours given), the line between
/// the reference points (dashed, class `cpa-line`); returns the page box of the line.
Rect draw_cpa(std::string& out, const CpaDraw& c, const View& v, const char* colour_a, const char* colour_b, double width) {
    const XY a = v.to_px(c.pa), b = v.to_px(c.pb);
    out += "<g class=\"cpa\" data-ships=\"" + markup_text(c.a->summary->id + " x " + c.b->summary->id) + "\"><title>" +
           markup_text(c.a->summary->id + " and " + c.b->summary->id + ": closest approach " + fixed_text(c.situation->closest_m, 0) + " m at " +
                       date_clock_text(c.situation->closest_s) + " UTC (" + exercise_time_text(c.situation->closest_s, c.a->exercise_start_s) + ")") +
           "</title>";
    for (const auto& [hull, colour] : {std::pair{&c.hull_a, colour_a}, std::pair{&c.hull_b, colour_b}})
        if (hull->size() >= 3)
            out += "<polygon class=\"hull cpa-hull\" points=\"" + points_attr(*hull, v) + "\" fill=\"" + colour + "\" fill-opacity=\"0.35\" stroke=\"" +
                   colour + "\" stroke-width=\"1.4\" stroke-linejoin=\"round\"/>";
    out += "<line class=\"cpa-line\" x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) + "\" y2=\"" + num(b.y) + "\" stroke=\"" +
           cpa_ink + "\" stroke-width=\"" + num(width) + "\" stroke-dasharray=\"4,3\"/>";
    for (const XY& p : {a, b})
        out += "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"1.8\" fill=\"" + cpa_ink + "\"/>";
    out += "</g>\n";
    return {std::min(a.x, b.x) - 3, std::min(a.y, b.y) - 3, std::max(a.x, b.x) + 3, std::max(a.y, b.y) + 3};
}

// ---------------------------------------------------------------- the panels

/// The time label of an event in the overview: "10:03:12Z", "(n)" added when it has a panel.
std::string time_label(const EventDraw& e) {
    return clock_text(e.event->start_s) + (e.zoom ? " (" + std::to_string(e.zoom) + ")" : "");
}

/// `order`: the events most severe first (see order_events).
void draw_overview(std::string& out, const Scene& scene, const grid::CoastGrid& g, const View& v,
                   const std::vector<EventDraw*>& order) {
    open_panel(out, v, "overview", "overview");
    draw_chart(out, g, v, 2, 0.8);
    draw_areas(out, scene, v);
    for (Status s : {Status::clear, Status::close, Status::contact, Status::aground})
        for (const TrackDraw& t : scene.tracks)
            if (t.status == s && !t.trainee) {
                draw_track(out, t, v, status_colour(s), s == Status::clear ? 1.0 : 1.6, s == Status::clear ? 0.75 : 0.95);
                draw_lonely_fixes(out, t, v, status_colour(s));
            }
    // Trainees on top, in their own colour, with direction arrows and time ticks.
    std::vector<Tick> ticks;
    for (const TrackDraw& t : scene.tracks)
        if (t.trainee) {
            draw_track(out, t, v, trainee_blue, 2.4, 1.0, "track trainee");
            draw_lonely_fixes(out, t, v, trainee_blue);
        }
    for (const TrackDraw& t : scene.tracks)
        if (t.trainee) draw_direction_and_ticks(out, t, v, ticks);
    for (auto it = order.rbegin(); it != order.rend(); ++it) draw_hull(out, **it, v, false);

    // Markers (the most severe drawn last, on top), then labels where they fit: event times
    // most severe first, then the ids of tracks with events, then the rest.
    Labels labels(v.px.grown(-2));
    std::string marks, texts;
    for (const EventDraw& e : scene.events) labels.block(hull_rect(e, v));
    for (auto it = order.rbegin(); it != order.rend(); ++it)
        if ((*it)->point_ok) labels.block(draw_marker(marks, **it, v, "event", marker_size((*it)->event->kind)));
    std::vector<Rect> cpa_boxes;
    for (const CpaDraw& c : scene.cpas) cpa_boxes.push_back(draw_cpa(marks, c, v, c.a->trainee ? trainee_blue : clear_grey,
                                                                        c.b->trainee ? trainee_blue : clear_grey, 1.3));
    for (const Rect& r : cpa_boxes) labels.block(r);
    for (const ManoeuvreDraw& m : scene.manoeuvres)
        labels.block(draw_manoeuvre(marks, m, v, m.track->trainee ? trainee_dark : slate_dark));
    out += marks;
    out += "</g>\n";  // end of the clipped group: labels, scale bar and arrow are placed inside the panel
    const Bearing b = bearing_at(g.frame(), v.to_world({(v.px.x0 + v.px.x1) / 2, (v.px.y0 + v.px.y1) / 2}));
    labels.block(draw_scale_bar(texts, v, b));
    labels.block(draw_north_arrow(texts, v, b));
    for (const EventDraw* e : order) {
        if (!e->point_ok) continue;
        const std::string s = time_label(*e);
        const XY at = v.to_px(e->point);
        const char* colour = kind_style(e->event->kind).dark;
        // Numbered events (they have a panel) may move off a crowded spot on a leader line.
        if (auto r = labels.place(at, text_width(s, 10.5) + 4, 14, 5, e->zoom ? 40 : 10)) {
            leader(texts, at, *r, 12, colour);
            label(texts, *r, s, 10.5, colour, "label event-time", e->event->kind == EventKind::grounding || e->zoom);
        }
    }
    // The closest approaches ("CPA 420 m 10:12:30Z"), the manoeuvres, the areas' names, the time ticks.
    for (const CpaDraw& c : scene.cpas) {
        const XY pa = v.to_px(c.pa), pb = v.to_px(c.pb);
        const XY mid{(pa.x + pb.x) / 2, (pa.y + pb.y) / 2};
        const std::string s = cpa_label(c);
        if (auto r = labels.place(mid, text_width(s, 10.5) + 4, 14, 6, 60)) {
            leader(texts, mid, *r, 10, cpa_ink);
            label(texts, *r, s, 10.5, cpa_ink, "label cpa-distance", true);
        }
    }
    for (const ManoeuvreDraw& m : scene.manoeuvres) {
        const XY p = v.to_px(m.at);
        const std::string s = manoeuvre_label(m);
        const char* colour = m.track->trainee ? trainee_dark : slate_dark;
        if (auto r = labels.place(p, text_width(s, 9.5) + 4, 13, 6, 40)) {
            leader(texts, p, *r, 10, colour);
            label(texts, *r, s, 9.5, colour, "label manoeuvre-label");
        }
    }
    name_areas(texts, scene, v, labels);
    for (const Tick& t : ticks)
        if (auto r = labels.place(t.at, text_width(t.text, 9) + 4, 12, 5, 14)) label(texts, *r, t.text, 9, trainee_dark, "label time-tick");
    for (Status s : {Status::aground, Status::contact, Status::close, Status::clear})
        for (const TrackDraw& t : scene.tracks) {
            if (t.status != s || t.lines.empty()) continue;
            const XY start = v.to_px(t.lines.front().front());
            if (!Rect{start.x, start.y, start.x, start.y}.overlaps(v.px)) continue;
            if (auto r = labels.place(start, text_width(t.summary->id, 9.5) + 4, 13, 3))
                label(texts, *r, t.summary->id, 9.5, "#333333", "label track-id");
        }
    out += texts;
    close_panel(out, v);
}

/// One line of a zoomed panel's title.
struct TitleLine {
    std::string text;
    const char* colour;
    double size;
    bool bold;
};

/// The title of a zoomed panel: track and name; the kind in words; speed at contact (or at
/// least clearance) and penetration (or clearance); start and duration; heading.
std::vector<TitleLine> zoom_title(const EventDraw& e) {
    const Event& ev = *e.event;
    std::vector<TitleLine> lines;
    lines.push_back({"(" + std::to_string(e.zoom) + ") " + track_text(*e.track), ink, 12, true});
    std::string kind = kind_words(ev);
    const std::string hazard = audit::is_contact(ev.kind) ? hazard_text(ev) : "";
    if (!hazard.empty()) kind += ", " + hazard;
    if (ev.evidence.grade > 0) kind += ", grade " + std::to_string(ev.evidence.grade);
    lines.push_back({kind, kind_style(ev.kind).dark, 11, true});
    lines.push_back({speed_text(ev) + speed_when(ev) + ", " + depth_text(ev), ink, 11, false});
    lines.push_back({"from " + date_clock_text(ev.start_s) + " UTC for " + duration_words(ev.end_s - ev.start_s), ink, 11, false});
    lines.push_back({heading_text(ev, true), ev.orientation_unknown ? slate_dark : "#555555", 11, false});
    return lines;
}

/// Height (px) the title of a zoomed panel takes above it.
constexpr double zoom_title_px = 76;

/// What a zoomed panel is about: a track event (drawn as plot_svg draws it), or a moment of
/// one or more tracks (an encounter, a breach) with their hulls then and over a time window.
struct Focus {
    std::string id;                      ///< the panel's id
    XY point;                            ///< the marker, and where north and scale are measured
    bool point_ok = false;
    const EventDraw* event = nullptr;    ///< a track event, or null
    std::vector<const TrackDraw*> own;   ///< tracks drawn in colour, with their fixes
    std::vector<std::vector<XY>> hulls;  ///< hull outlines at the moment, one per track of `own` (or fewer)
    std::vector<std::vector<XY>> window_hulls;  ///< the hulls of `own` at their poses in the time window (faint)
    std::vector<std::size_t> window_owner;      ///< for each of window_hulls, its track's place in `own`
    std::string cls;                     ///< marker class: an EventKind name, "collision", "close_quarters", "breach"
    KindStyle style{red, red_dark};
    std::string time_text;               ///< the label at the marker
    std::string tooltip;                 ///< the marker's <title>
    std::vector<TitleLine> title;        ///< above the panel (none: the panel starts at its top)
    const CpaDraw* cpa = nullptr;        ///< an encounter's closest approach: its line and distance drawn
    std::vector<const char*> colours;    ///< the colours of `own` (empty: the kind's, then other_track_colours)
};

/// Colours of the second, third, ... track of a moment (the first has the kind's).
/// No blue: blue is the trainee's (exercise mode).
constexpr const char* other_track_colours[] = {"#0f7d6b", "#7b3fa0", "#8c564b", "#4d4d4d"};

const char* own_colour(const Focus& f, std::size_t k) {
    if (k < f.colours.size()) return f.colours[k];
    if (f.event) return status_colour(f.own[0]->status);
    return k == 0 ? f.style.dark : other_track_colours[(k - 1) % std::size(other_track_colours)];
}

void draw_zoom(std::string& out, const Scene& scene, const grid::CoastGrid& g, const Focus& focus, const View& v) {
    open_panel(out, v, "zoom", focus.id);
    draw_chart(out, g, v, 1, 1.3);
    draw_areas(out, scene, v);
    for (const TrackDraw& t : scene.tracks)
        if (std::find(focus.own.begin(), focus.own.end(), &t) == focus.own.end()) draw_track(out, t, v, clear_grey, 1.0, 0.8);
    for (std::size_t k = 0; k < focus.own.size(); ++k) {
        const TrackDraw& own = *focus.own[k];
        const char* colour = own_colour(focus, k);
        draw_track(out, own, v, colour, 2.0, 0.95);
        std::string dots;  // the track's fixes: how often the ship was seen
        for (const auto& line : own.lines)
            for (const XY& p : line) {
                const XY q = v.to_px(p);
                if (!Rect{q.x, q.y, q.x, q.y}.overlaps(v.px.grown(4))) continue;
                dots += "<circle cx=\"" + num(q.x) + "\" cy=\"" + num(q.y) + "\" r=\"2.2\"/>";
            }
        if (!dots.empty())
            out += "<g class=\"fixes\" fill=\"" + std::string(colour) + "\" stroke=\"#ffffff\" stroke-width=\"0.6\">" + dots + "</g>\n";
    }
    for (std::size_t k = 0; k < focus.window_hulls.size(); ++k)
        out += "<polygon class=\"hull window\" points=\"" + points_attr(focus.window_hulls[k], v) + "\" fill=\"none\" stroke=\"" +
               own_colour(focus, focus.window_owner[k]) + "\" stroke-width=\"0.8\" stroke-opacity=\"0.6\"/>\n";
    Labels labels(v.px.grown(-2));
    for (const EventDraw& e : scene.events)
        if (&e != focus.event && !e.box.empty() && v.world.distance_to(e.box) == 0) {
            draw_hull(out, e, v, false);
            labels.block(hull_rect(e, v));
        }
    if (focus.event) {
        draw_hull(out, *focus.event, v, true);
        labels.block(hull_rect(*focus.event, v));
    }
    for (std::size_t k = 0; k < focus.hulls.size(); ++k) {
        if (focus.hulls[k].size() < 3) continue;
        const char* colour = own_colour(focus, k);
        out += "<polygon class=\"hull " + focus.cls + "\" points=\"" + points_attr(focus.hulls[k], v) + "\" fill=\"" + colour +
               "\" fill-opacity=\"0.3\" stroke=\"" + colour + "\" stroke-width=\"1.6\" stroke-linejoin=\"round\"/>\n";
    }
    for (const EventDraw& e : scene.events)
        if (&e != focus.event && e.point_ok && v.world.distance_to(e.box) == 0) labels.block(draw_contact(out, e, v, 3));
    for (const ManoeuvreDraw& m : scene.manoeuvres)
        for (std::size_t k = 0; k < focus.own.size(); ++k)
            if (m.track == focus.own[k] && Rect{v.to_px(m.at).x, v.to_px(m.at).y, v.to_px(m.at).x, v.to_px(m.at).y}.overlaps(v.px))
                labels.block(draw_manoeuvre(out, m, v, own_colour(focus, k)));
    if (focus.cpa) {
        const XY a = v.to_px(focus.cpa->pa), b = v.to_px(focus.cpa->pb);
        out += "<g class=\"cpa\"><line class=\"cpa-line\" x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) + "\" y2=\"" +
               num(b.y) + "\" stroke=\"" + cpa_ink + "\" stroke-width=\"1.6\" stroke-dasharray=\"5,3\"/>";
        for (const XY& p : {a, b}) out += "<circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"2.4\" fill=\"" + cpa_ink + "\"/>";
        out += "</g>\n";
        labels.block({std::min(a.x, b.x) - 3, std::min(a.y, b.y) - 3, std::max(a.x, b.x) + 3, std::max(a.y, b.y) + 3});
    }
    if (focus.event) labels.block(draw_contact(out, *focus.event, v, 4.5));
    else if (focus.point_ok && !focus.cpa) {
        const XY p = v.to_px(focus.point);
        out += "<g class=\"contact " + focus.cls + "\"><title>" + markup_text(focus.tooltip) + "</title><circle cx=\"" + num(p.x) +
               "\" cy=\"" + num(p.y) + "\" r=\"4.5\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"3.5\"/><circle cx=\"" + num(p.x) +
               "\" cy=\"" + num(p.y) + "\" r=\"4.5\" fill=\"none\" stroke=\"" + focus.style.dark +
               "\" stroke-width=\"1.8\"/><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"1.2\" fill=\"" + focus.style.dark +
               "\"/></g>\n";
        labels.block({p.x - 7, p.y - 7, p.x + 7, p.y + 7});
    }
    out += "</g>\n";
    const Bearing b = bearing_at(g.frame(), focus.point);
    std::string texts;
    labels.block(draw_scale_bar(texts, v, b));
    labels.block(draw_north_arrow(texts, v, b));
    if (focus.event && focus.event->event->orientation_unknown) {  // said in the picture as well as in the title
        const std::string s = "heading unknown (hull circle)";
        const Rect r{v.px.x0 + 6, v.px.y0 + 6, v.px.x0 + 10 + text_width(s, 10.5), v.px.y0 + 21};
        labels.block(r);
        label(texts, r, s, 10.5, slate_dark, "label heading-unknown");
    }
    const XY at = v.to_px(focus.point);
    if (focus.cpa) {  // the distance, by the line's middle
        const std::string s = cpa_label(*focus.cpa);
        if (auto r = labels.place(at, text_width(s, 11) + 4, 15, 6, v.px.w() / 3)) {
            leader(texts, at, *r, 10, cpa_ink);
            label(texts, *r, s, 11, cpa_ink, "label cpa-distance", true);
        }
    }
    if (focus.point_ok && !focus.time_text.empty())
        if (auto r = labels.place(at, text_width(focus.time_text, 11) + 4, 15, 7, v.px.w() / 3)) {
            leader(texts, at, *r, 14, focus.style.dark);
            label(texts, *r, focus.time_text, 11, focus.style.dark, "label event-time", true);
        }
    // Which ship is which: the ids beside the hulls of a moment.
    for (std::size_t k = 0; k < focus.hulls.size() && k < focus.own.size(); ++k) {
        if (focus.hulls[k].empty()) continue;
        Box hb;
        for (const XY& p : focus.hulls[k]) hb.extend(p);
        const XY c = v.to_px({(hb.minx + hb.maxx) / 2, (hb.miny + hb.maxy) / 2});
        const std::string& id = focus.own[k]->summary->id;
        if (auto r = labels.place(c, text_width(id, 10) + 4, 14, 8, v.px.w() / 4)) {
            leader(texts, c, *r, 10, own_colour(focus, k));
            label(texts, *r, id, 10, own_colour(focus, k), "label track-id", true);
        }
    }
    out += texts;
    // The title above the panel (inside the panel's group, outside its clip).
    double ty = v.px.y0 - zoom_title_px;
    for (std::size_t k = 0; k < focus.title.size(); ++k) {
        const TitleLine& line = focus.title[k];
        ty += k == 0 ? 12 : 14.5;
        text(out, v.px.x0, ty, fit_text(line.text, line.size, v.px.w()), line.size, line.colour,
             k == 0 ? " class=\"zoom-title\" font-weight=\"bold\"" : line.bold ? " font-weight=\"bold\"" : "");
    }
    close_panel(out, v);
}

/// The focus of a track event's panel, titled as plot_svg titles it.
Focus event_focus(const EventDraw& e) {
    Focus f;
    f.id = "zoom-" + std::to_string(e.zoom);
    f.point = e.point;
    f.point_ok = e.point_ok;
    f.event = &e;
    f.own = {e.drawn_track};
    f.cls = audit::to_string(e.event->kind);
    f.style = kind_style(e.event->kind);
    const Event& ev = *e.event;
    f.time_text = (ev.kind == EventKind::contact_at_start ? "in contact at first fix "
                   : ev.kind == EventKind::close_pass     ? "close pass from "
                                                          : "first contact ") +
                  clock_text(ev.start_s);
    f.title = zoom_title(e);
    return f;
}

/// The focus of an encounter's closest approach: both ships (a trainee first, in the
/// trainee's colour), their hulls at that moment, the CPA line and distance.
Focus cpa_focus(const CpaDraw& c, const std::string& id, std::size_t number) {
    Focus f;
    f.id = id;
    f.cpa = &c;
    f.point = {(c.pa.x + c.pb.x) / 2, (c.pa.y + c.pb.y) / 2};
    f.point_ok = true;
    const bool swap = c.b->trainee && !c.a->trainee;
    f.own = swap ? std::vector<const TrackDraw*>{c.b, c.a} : std::vector<const TrackDraw*>{c.a, c.b};
    f.hulls = swap ? std::vector<std::vector<XY>>{c.hull_b, c.hull_a} : std::vector<std::vector<XY>>{c.hull_a, c.hull_b};
    f.colours = {f.own[0]->trainee ? trainee_blue : other_track_colours[0], other_track_colours[1]};
    f.cls = "cpa";
    f.style = {clear_grey, cpa_ink};
    const audit::ColregEncounter& s = *c.situation;
    const std::string& a = c.a->summary->id;
    const std::string& b = c.b->summary->id;
    f.tooltip = a + " and " + b + " (" + audit::to_string(s.at_start.situation) + "): closest approach " + fixed_text(s.closest_m, 0) + " m at " +
                date_clock_text(s.closest_s) + " UTC";
    auto party = [&](audit::Party p) {
        return p == audit::Party::a ? a : p == audit::Party::b ? b : p == audit::Party::both ? "both" : std::string("neither");
    };
    auto action = [&](const std::string& who, const audit::Manoeuvre& m) {
        return who + ": " + (std::isnan(m.time_s) ? std::string("no alteration")
                                                  : std::string(m.course && m.speed ? "course and speed" : m.course ? "course" : "speed") +
                                                        " altered at " + clock_text(m.time_s));
    };
    f.title = {{"(" + std::to_string(number) + ") " + a + " \xC3\x97 " + b + ": " + audit::to_string(s.at_start.situation), ink, 12, true},
               {"closest approach " + fixed_text(s.closest_m, 0) + " m", cpa_ink, 11, true},
               {"at " + date_clock_text(s.closest_s) + " UTC (" + exercise_time_text(s.closest_s, c.a->exercise_start_s) + ")", ink, 11, false},
               {"give-way " + party(s.at_start.give_way) + ", stand-on " + party(s.at_start.stand_on), ink, 11, false},
               {action(a, s.action_a) + "; " + action(b, s.action_b), "#555555", 11, false}};
    return f;
}

/// The ground a closest approach's panel shows across its shorter side (metres).
double cpa_size_m(const CpaDraw& c) { return std::max({8 * c.hull_length_m, 1.8 * c.situation->closest_m, 100.0}); }

// ---------------------------------------------------------------- legend

struct LegendItem {
    std::string symbol;  ///< SVG drawn in a 22 x 12 box at the origin
    std::string caption;
};

double draw_legend(std::string& out, double x0, double y0, double width, const std::vector<LegendItem>& items) {
    out += "<g class=\"legend\">\n";
    double x = x0, y = y0;
    for (const auto& it : items) {
        const double w = 28 + text_width(it.caption, 11) + 14;
        if (x > x0 && x + w > x0 + width) {
            x = x0;
            y += 18;
        }
        out += "<g transform=\"translate(" + num(x) + "," + num(y) + ")\">" + it.symbol + "</g>\n";
        text(out, x + 28, y + 10.5, it.caption, 11, ink);
        x += w;
    }
    out += "</g>\n";
    return y + 18;
}

/// What the picture draws: the chart, the kinds of track present, hulls, and a marker for
/// groundings and close passes (always, so that none drawn says none) and for each other kind
/// of contact present.
std::vector<LegendItem> legend_items(const grid::CoastGrid& g, const Scene& scene) {
    auto line = [](const char* colour, double w) {
        return std::string("<line x1=\"0\" y1=\"6\" x2=\"22\" y2=\"6\" stroke=\"") + colour + "\" stroke-width=\"" + num(w) +
               "\" stroke-linecap=\"round\"/>";
    };
    auto swatch = [](const char* colour) {
        return std::string("<rect x=\"0\" y=\"0\" width=\"22\" height=\"12\" fill=\"") + colour +
               "\" stroke=\"#999999\" stroke-width=\"0.5\"/>";
    };
    auto marker = [](EventKind k) {
        std::string tag;
        const bool big = k == EventKind::grounding || k == EventKind::close_pass;
        return marker_shape(k, {11, 6}, big ? 5 : 4, &tag) + " fill=\"" + kind_style(k).fill + "\" stroke=\"#ffffff\" stroke-width=\"" +
               (big ? "1.5" : "1") + "\" stroke-linejoin=\"round\"/>";
    };
    bool kind_present[6] = {false, false, false, false, false, false};
    bool unknown_heading = false;
    for (const EventDraw& e : scene.events) {
        kind_present[severity(e.event->kind)] = true;
        unknown_heading = unknown_heading || (e.event->orientation_unknown && e.hull.size() >= 3);
    }
    bool contact_track = false;
    for (const TrackDraw& t : scene.tracks) contact_track = contact_track || t.status == Status::contact;

    std::vector<LegendItem> items;
    items.push_back({line(coast_stroke, 1.2), "coastline"});
    if (g.has_land_side()) items.push_back({swatch(land_fill), "land (as the grid sees it)"});
    else items.push_back({swatch(water_fill), "land side unknown: coastline only"});
    items.push_back({swatch(outside_fill), "no chart (outside the grid)"});
    bool trainees = false;
    for (const TrackDraw& t : scene.tracks) trainees = trainees || t.trainee;
    if (trainees)
        items.push_back({line(trainee_blue, 2.6) + "<polygon points=\"16,6 9,2 9,10\" fill=\"" + trainee_dark + "\"/>",
                         "trainee (arrows: direction; ticks: exercise time T+m:ss from its first fix, UTC)"});
    items.push_back({line(red, 2), trainees ? "target with grounding" : "track with grounding"});
    if (contact_track) items.push_back({line(contact_violet, 2), trainees ? "target with contacts, no grounding" : "track with contacts, no grounding"});
    items.push_back({line(amber, 2), trainees ? "target with close pass" : "track with close pass"});
    items.push_back({line(clear_grey, 1.5), trainees ? "other target" : "other track"});
    bool no_entry = false, speed_area = false;
    for (const AreaDraw& a : scene.areas) (a.no_entry ? no_entry : speed_area) = true;
    if (no_entry)
        items.push_back({std::string("<rect x=\"1\" y=\"1\" width=\"20\" height=\"10\" fill=\"") + red + "\" fill-opacity=\"0.12\" stroke=\"" +
                             no_entry_stroke + "\" stroke-width=\"1.4\" stroke-dasharray=\"5,2\"/>",
                         "no-entry area"});
    if (speed_area)
        items.push_back({std::string("<rect x=\"1\" y=\"1\" width=\"20\" height=\"10\" fill=\"") + amber + "\" fill-opacity=\"0.12\" stroke=\"" +
                             speed_area_stroke + "\" stroke-width=\"1.4\" stroke-dasharray=\"2,2\"/>",
                         "speed-limit area"});
    if (!scene.cpas.empty())
        items.push_back({std::string("<line x1=\"2\" y1=\"6\" x2=\"20\" y2=\"6\" stroke=\"") + cpa_ink +
                             "\" stroke-width=\"1.3\" stroke-dasharray=\"4,3\"/><circle cx=\"2\" cy=\"6\" r=\"1.8\"/><circle cx=\"20\" cy=\"6\" r=\"1.8\"/>",
                         "closest approach: both hulls then, distance (UTC)"});
    if (!scene.manoeuvres.empty())
        items.push_back({std::string("<circle cx=\"11\" cy=\"6\" r=\"5\" fill=\"#ffffff\" stroke=\"") + trainee_dark +
                             "\" stroke-width=\"2\"/><circle cx=\"11\" cy=\"6\" r=\"1.8\" fill=\"" + trainee_dark + "\"/>",
                         "manoeuvre: course or speed altered"});
    items.push_back({std::string("<polygon points=\"1,3 15,3 21,6 15,9 1,9\" fill=\"") + red +
                         "\" fill-opacity=\"0.3\" stroke=\"" + red_dark + "\" stroke-width=\"1\"/>",
                     "hull at event"});
    if (unknown_heading)
        items.push_back({std::string("<circle cx=\"11\" cy=\"6\" r=\"5.5\" fill=\"") + slate + "\" fill-opacity=\"0.2\" stroke=\"" +
                             slate_dark + "\" stroke-width=\"1\" stroke-dasharray=\"3,2\"/>",
                         "hull circle: heading unknown"});
    items.push_back({marker(EventKind::grounding), "grounding (first contact, time UTC)"});
    if (kind_present[severity(EventKind::alongside)])
        items.push_back({marker(EventKind::alongside), "alongside (not a grounding)"});
    if (kind_present[severity(EventKind::contact_at_start)])
        items.push_back({marker(EventKind::contact_at_start), "in contact at the first fix"});
    if (kind_present[severity(EventKind::expected_contact)])
        items.push_back({marker(EventKind::expected_contact), "contact in a berth or harbour area"});
    if (kind_present[severity(EventKind::chart_disagrees)])
        items.push_back({marker(EventKind::chart_disagrees), "the chart disagrees with the traffic (sailed through)"});
    items.push_back({marker(EventKind::close_pass), "close pass"});
    return items;
}

/// The events most severe first: groundings in time order, then alongside, in contact at the
/// first fix and expected contacts (each deepest penetration first), then close passes (least
/// clearance first); report order among equals.
std::vector<EventDraw*> order_events(Scene& scene) {
    std::vector<EventDraw*> order;
    order.reserve(scene.events.size());
    for (EventDraw& e : scene.events) order.push_back(&e);
    auto key = [](const Event& e) {
        if (e.kind == EventKind::grounding) return e.start_s;
        if (e.kind == EventKind::close_pass) return e.min_clearance_m;
        return -e.penetration_m;
    };
    std::stable_sort(order.begin(), order.end(), [&](const EventDraw* a, const EventDraw* b) {
        const std::size_t sa = severity(a->event->kind), sb = severity(b->event->kind);
        if (sa != sb) return sa < sb;
        const double ka = key(*a->event), kb = key(*b->event);
        if (ka != kb && !std::isnan(ka) && !std::isnan(kb)) return ka < kb;
        return std::isnan(kb) && !std::isnan(ka);  // unknown figures last
    });
    return order;
}

/// The legend and the overview panel from `y` (px) down, `inner` px wide at `x0`: the tracks
/// and events, padded by at least 2 km, kept within the chart (unless the data reach beyond
/// it). Returns the y below them.
double draw_overview_section(std::string& body, const Scene& scene, const grid::CoastGrid& grid, const std::vector<EventDraw*>& order,
                             double x0, double y, double inner) {
    y = draw_legend(body, x0, y, inner, legend_items(grid, scene)) + 8;
    Box want = scene.data;
    if (want.empty()) want = grid.extent();
    else {
        const double pad = std::max(2000.0, 0.05 * std::max(want.maxx - want.minx, want.maxy - want.miny));
        Box allowed = grid.extent();
        allowed.extend(want);
        want = intersection(want.grown(pad), allowed);
    }
    const double ww = std::max(want.maxx - want.minx, 1.0), wh = std::max(want.maxy - want.miny, 1.0);
    const double oh = std::clamp(inner * wh / ww, 0.4 * inner, 1.0 * inner);
    text(body, x0, y + 14, "Overview", 14, ink, " font-weight=\"bold\"");
    y += 22;
    const View overview = fit(want, {x0, y, x0 + inner, y + oh});
    draw_overview(body, scene, grid, overview, order);
    return y + oh + 12;
}

/// An <svg> element of `width` x `height` px around `body`, titled `title`.
std::string svg_element(const std::string& body, double width, double height, const std::string& title) {
    std::string out;
    out.reserve(body.size() + 600);
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + num(width) + "\" height=\"" + num(height) +
           "\" viewBox=\"0 0 " + num(width) + " " + num(height) + "\" font-family=\"" + font_family + "\">\n";
    out += "<title>" + markup_text(title) + "</title>\n";
    out += "<rect width=\"" + num(width) + "\" height=\"" + num(height) + "\" fill=\"#ffffff\"/>\n";
    out += body;
    out += "</svg>\n";
    return out;
}

void check_width(double width) {
    if (!std::isfinite(width) || width < 400 || width > 20000)
        throw UsageError("plot width must be between 400 and 20000 px (got " + num(width) + ")");
}

}  // namespace

std::string plot_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const PlotOptions& options) {
    const double width = options.width_px;
    check_width(width);
    const double margin = 16;
    const double inner = width - 2 * margin;

    Scene scene = project_scene(result, grid.frame(), options.tracks);
    const std::vector<EventDraw*> order = order_events(scene);
    // Zoomed panels in that order, up to the limit; what is left out is counted by kind.
    std::size_t zoom_count = 0;
    std::size_t left_out[6] = {0, 0, 0, 0, 0, 0};
    for (EventDraw* e : order) {
        if (zoom_count < options.max_zoom_panels && e->point_ok) e->zoom = ++zoom_count;
        else ++left_out[severity(e->event->kind)];
    }

    std::string body;
    // Title and summary: every kind of event counted (the contacts that are not groundings when present).
    text(body, margin, margin + 18, "shoal audit", 20, ink, " font-weight=\"bold\"");
    std::string summary = plural(result.tracks.size(), "track", "tracks") + ", " + plural(result.fixes, "fix", "fixes") + ", " +
                          count_text(EventKind::grounding, result.groundings);
    if (result.contacts_at_start) summary += ", " + count_text(EventKind::contact_at_start, result.contacts_at_start);
    if (result.alongside) summary += ", " + count_text(EventKind::alongside, result.alongside);
    if (result.expected_contacts) summary += ", " + count_text(EventKind::expected_contact, result.expected_contacts);
    summary += ", " + count_text(EventKind::close_pass, result.close_passes);
    if (result.uncovered_fixes) summary += ", " + plural(result.uncovered_fixes, "uncovered fix", "uncovered fixes");
    std::size_t unreadable = result.errors.size();
    for (const auto& f : result.files) unreadable += f.error.empty() ? 0 : 1;
    if (unreadable) summary += ", " + plural(unreadable, "file or track not read", "files or tracks not read");
    text(body, margin, margin + 40, fit_text(summary, 13, inner), 13, ink, " class=\"summary\"");
    std::string when;
    if (std::isfinite(result.first_fix_s) && std::isfinite(result.last_fix_s))
        when = "fixes from " + date_clock_text(result.first_fix_s) + " to " + date_clock_text(result.last_fix_s);
    const std::string how = "drawn in " + grid.frame().description() + ", grid cells of " + num(grid.cell_size()) + " m";
    double y = margin + 58;
    if (!when.empty() && text_width(when + "; " + how, 11) > inner) {
        text(body, margin, y, when, 11, "#555555");
        y += 15;
        text(body, margin, y, fit_text(how, 11, inner), 11, "#555555");
    } else {
        text(body, margin, y, fit_text(when.empty() ? how : when + "; " + how, 11, inner), 11, "#555555");
    }
    y = draw_overview_section(body, scene, grid, order, margin, y + 10, inner);

    // Zoomed panels in three sections: groundings, the other contacts, close passes.
    struct Section {
        const char* heading;
        bool (*holds)(EventKind);
    };
    const Section sections[] = {
        {"Groundings", [](EventKind k) { return k == EventKind::grounding; }},
        {"Other contacts (not groundings)", [](EventKind k) { return k != EventKind::grounding && audit::is_contact(k); }},
        {"Close passes", [](EventKind k) { return k == EventKind::close_pass; }},
    };
    const int cols = width >= 900 ? 3 : 2;
    const double gap = 16;
    const double zw = (inner - (cols - 1) * gap) / cols, zh = zw * 0.75;
    for (const Section& sec : sections) {
        std::vector<const EventDraw*> drawn;
        std::size_t all = 0;
        for (const EventDraw* e : order) {
            if (!sec.holds(e->event->kind)) continue;
            ++all;
            if (e->zoom) drawn.push_back(e);
        }
        if (drawn.empty()) continue;
        y += 10;
        text(body, margin, y + 14,
             drawn.size() == all ? std::string(sec.heading)
                                 : std::string(sec.heading) + ": first " + std::to_string(drawn.size()) + " of " + std::to_string(all),
             14, ink, " class=\"section\" font-weight=\"bold\"");
        y += 24;
        for (std::size_t n = 0; n < drawn.size(); ++n) {
            const EventDraw& e = *drawn[n];
            const double x = margin + static_cast<double>(n % static_cast<std::size_t>(cols)) * (zw + gap);
            const double size_m = std::max(8 * (e.hull_length_m > 0 ? e.hull_length_m : 100.0), 100.0);
            const Rect px{x, y + zoom_title_px, x + zw, y + zoom_title_px + zh};
            const View v = fit({e.point.x - size_m / 2, e.point.y - size_m / 2, e.point.x + size_m / 2, e.point.y + size_m / 2}, px);
            draw_zoom(body, scene, grid, event_focus(e), v);
            if ((n + 1) % static_cast<std::size_t>(cols) == 0 || n + 1 == drawn.size()) y += zoom_title_px + zh + 16;
        }
    }
    // The encounters' closest approaches, in time order, numbered after the events' panels.
    std::vector<const CpaDraw*> cpas;
    for (const CpaDraw& c : scene.cpas) cpas.push_back(&c);
    std::stable_sort(cpas.begin(), cpas.end(), [](const CpaDraw* a, const CpaDraw* b) { return a->situation->closest_s < b->situation->closest_s; });
    const std::size_t cpa_drawn = std::min(cpas.size(), options.max_zoom_panels);
    if (cpa_drawn > 0) {
        y += 10;
        text(body, margin, y + 14,
             cpa_drawn == cpas.size() ? std::string("Closest approaches")
                                      : "Closest approaches: first " + std::to_string(cpa_drawn) + " of " + std::to_string(cpas.size()),
             14, ink, " class=\"section\" font-weight=\"bold\"");
        y += 24;
        for (std::size_t n = 0; n < cpa_drawn; ++n) {
            const CpaDraw& c = *cpas[n];
            const double x = margin + static_cast<double>(n % static_cast<std::size_t>(cols)) * (zw + gap);
            const Rect px{x, y + zoom_title_px, x + zw, y + zoom_title_px + zh};
            const Focus f = cpa_focus(c, "cpa-" + std::to_string(n + 1), zoom_count + n + 1);
            const double size_m = cpa_size_m(c);
            const View v = fit({f.point.x - size_m / 2, f.point.y - size_m / 2, f.point.x + size_m / 2, f.point.y + size_m / 2}, px);
            draw_zoom(body, scene, grid, f, v);
            if ((n + 1) % static_cast<std::size_t>(cols) == 0 || n + 1 == cpa_drawn) y += zoom_title_px + zh + 16;
        }
    }
    std::size_t more = 0;
    for (std::size_t n : left_out) more += n;
    if (more > 0) {
        std::string what;
        for (EventKind k : kinds_by_severity) {
            const std::size_t n = left_out[severity(k)];
            if (n) what += (what.empty() ? "" : ", ") + count_text(k, n);
        }
        const std::string note = std::to_string(more) + " more not drawn: " + what + " (at most " +
                                 std::to_string(options.max_zoom_panels) + " zoomed panels; see the report for all)";
        text(body, margin, y + 12, fit_text(note, 12, inner), 12, left_out[0] ? red_dark : ink, " class=\"note\"");
        y += 22;
    }
    const double height = std::ceil(y + margin);

    return "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n" +
           svg_element(body, width, height, std::string(picture_title) + ": " + summary);
}

std::string overview_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const PlotOptions& options) {
    const double width = options.width_px;
    check_width(width);
    const double margin = 8;
    Scene scene = project_scene(result, grid.frame(), options.tracks);
    const std::vector<EventDraw*> order = order_events(scene);
    std::string body;
    const double height = std::ceil(draw_overview_section(body, scene, grid, order, margin, margin, width - 2 * margin));
    return svg_element(body, width, height, "shoal: overview of " + plural(scene.tracks.size(), "track", "tracks"));
}

namespace {

KindStyle named_style(const std::string& kind) noexcept {
    for (EventKind k : kinds_by_severity)
        if (kind == audit::to_string(k)) return kind_style(k);
    if (kind == "collision") return {red, red_dark};
    if (kind == "close_quarters") return {amber, amber_dark};
    if (kind == "breach") return {contact_violet, "#5b3f8f"};
    return {clear_grey, slate_dark};
}

}  // namespace

const char* kind_colour(const std::string& kind) noexcept { return named_style(kind).dark; }

std::string cpa_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, std::size_t situation, double width_px,
                    const PlotOptions& options) {
    if (!std::isfinite(width_px) || width_px < 150 || width_px > 20000)
        throw UsageError("zoomed panel width must be between 150 and 20000 px (got " + num(width_px) + ")");
    if (situation >= result.situations.size())
        throw UsageError("cpa_svg: situation " + std::to_string(situation) + " of a result with " + std::to_string(result.situations.size()));
    const audit::ColregEncounter& s = result.situations[situation];
    std::vector<std::size_t> drawn = options.tracks;
    if (!drawn.empty()) drawn.insert(drawn.end(), {s.a, s.b});
    const Scene scene = project_scene(result, grid.frame(), drawn);
    const CpaDraw* c = nullptr;
    for (const CpaDraw& d : scene.cpas)
        if (d.situation == &s) c = &d;
    if (!c) return "";  // the closest approach cannot be placed
    Focus f = cpa_focus(*c, "cpa-" + std::to_string(situation + 1), situation + 1);
    f.title.clear();
    const double size_m = cpa_size_m(*c);
    const double h_px = std::round(width_px * 0.75);
    const View v = fit({f.point.x - size_m / 2, f.point.y - size_m / 2, f.point.x + size_m / 2, f.point.y + size_m / 2},
                       {0.5, 0.5, width_px - 0.5, h_px - 0.5});
    std::string body;
    draw_zoom(body, scene, grid, f, v);
    return svg_element(body, width_px, h_px, f.tooltip);
}

std::string zoom_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const ZoomSpec& spec, double width_px,
                     const PlotOptions& options) {
    if (!std::isfinite(width_px) || width_px < 150 || width_px > 20000)
        throw UsageError("zoomed panel width must be between 150 and 20000 px (got " + num(width_px) + ")");
    std::vector<std::size_t> drawn = options.tracks;
    if (!drawn.empty()) drawn.insert(drawn.end(), spec.tracks.begin(), spec.tracks.end());
    const Scene scene = project_scene(result, grid.frame(), drawn);
    const geo::LocalFrame& frame = grid.frame();
    Focus f;
    f.id = spec.id;
    f.cls = spec.kind;
    f.style = named_style(spec.kind);
    f.time_text = spec.time_label;
    f.tooltip = spec.tooltip;
    for (const std::size_t ti : spec.tracks) {
        auto it = std::find_if(scene.tracks.begin(), scene.tracks.end(), [&](const TrackDraw& t) { return t.index == ti; });
        if (it == scene.tracks.end()) throw UsageError("ZoomSpec::tracks names track " + std::to_string(ti) + " of a result with " +
                                                       std::to_string(result.tracks.size()));
        f.own.push_back(&*it);
    }
    double hull_m = 0;
    if (spec.event) {
        for (const EventDraw& e : scene.events)
            if (e.event == spec.event && !f.own.empty() && e.drawn_track == f.own[0]) f.event = &e;
        if (!f.event) throw UsageError("ZoomSpec::event is not an event of ZoomSpec::tracks[0]");
        f.cls = audit::to_string(spec.event->kind);
        f.style = kind_style(spec.event->kind);
        hull_m = f.event->hull_length_m;
    }
    for (const auto& ring : spec.hulls) {
        std::vector<XY>& h = f.hulls.emplace_back();
        for (const LonLat& p : ring)
            if (auto q = project(frame, p)) h.push_back(*q);
        for (std::size_t a = 0; a < h.size(); ++a)
            for (std::size_t b = a + 1; b < h.size(); ++b) hull_m = std::max(hull_m, geo::distance(h[a], h[b]));
    }
    if (std::isfinite(spec.start_s) && std::isfinite(spec.end_s))
        for (std::size_t k = 0; k < f.own.size(); ++k)
            for (const audit::Pose& pose : f.own[k]->result->poses) {
                if (pose.time_s < spec.start_s || pose.time_s > spec.end_s) continue;
                std::vector<XY> h;
                for (const LonLat& p : pose.hull)
                    if (auto q = project(frame, p)) h.push_back(*q);
                if (h.size() < 3) continue;
                f.window_hulls.push_back(std::move(h));
                f.window_owner.push_back(k);
            }
    if (auto c = project(frame, spec.centre)) {
        f.point = *c;
        f.point_ok = true;
    } else if (f.event) {
        f.point = f.event->point;
        f.point_ok = f.event->point_ok;
    }
    const double size_m = spec.size_m > 0 ? spec.size_m : hull_m > 0 ? std::max(8 * hull_m, 100.0) : 800.0;
    const double h_px = std::round(width_px * 0.75);
    const Rect px{0.5, 0.5, width_px - 0.5, h_px - 0.5};
    const View v = fit({f.point.x - size_m / 2, f.point.y - size_m / 2, f.point.x + size_m / 2, f.point.y + size_m / 2}, px);
    std::string body;
    draw_zoom(body, scene, grid, f, v);
    return svg_element(body, width_px, h_px, spec.tooltip.empty() ? "shoal: zoomed panel" : spec.tooltip);
}

void write_plot_svg(const std::string& path, const audit::AuditResult& result, const grid::CoastGrid& grid,
                    const PlotOptions& options) {
    write_file_atomically(path, plot_svg(result, grid, options));
}

bool is_shoal_picture(const std::string& path) {
    return file_head(path, 4096).find("<title>" + std::string(picture_title)) != std::string::npos;
}

}  // namespace shoal::report
