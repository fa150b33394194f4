// The picture's scene: the page's geometry (rectangles, panels and their views, north and
// scale) and the audit projected into the grid's local metres (tracks, events, areas, manoeuvres,
// closest approaches).
#include "picture/plot_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <iterator>
#include <unordered_map>
#include <unordered_set>

#include <shoal/picture/plot.hpp>
#include <shoal/picture/wording.hpp>
#include <shoal/report/markup.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/util/error.hpp>
#include "picture/event_phrases.hpp"

namespace shoal::report::plot_parts {

using namespace detail;  // the event phrases (picture/event_phrases.hpp)

// ---------------------------------------------------------------- geometry of the page



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

double round_length(double m) {
    const double p = std::pow(10.0, std::floor(std::log10(m)));
    for (double f : {5.0, 2.0, 1.0})
        if (f * p <= m * (1 + 1e-9)) return f * p;
    return p;
}

// ---------------------------------------------------------------- the data, projected







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

Scene project_scene(const audit::AuditResult& result, const geo::LocalFrame& frame, const std::vector<std::size_t>& only) {
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


}  // namespace shoal::report::plot_parts
