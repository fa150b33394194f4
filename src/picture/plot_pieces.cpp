// The pieces a panel is drawn of: paths, the chart, tracks, hulls, markers, scale bar and north
// arrow, and exercise mode's areas, trainees' arrows and ticks, manoeuvres and closest approaches.
#include "picture/plot_pieces.hpp"

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

// ---------------------------------------------------------------- paths

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


// ---------------------------------------------------------------- pieces of a panel

void text(std::string& out, double x, double y, const std::string& s, double size, const char* colour,
          const char* extra) {
    out += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) + "\" fill=\"" + colour + "\"" + extra +
           ">" + markup_text(s) + "</text>\n";
}

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
                const char* cls) {
    if (t.box.empty() || v.world.distance_to(t.box) > 0) return;
    std::string d;
    for (const auto& line : t.lines) d += line_path(line, v, 0.6);
    if (d.empty()) return;
    out += "<path class=\"" + std::string(cls) + "\" fill=\"none\" stroke=\"" + std::string(colour) + "\" stroke-width=\"" + num(width) +
           "\" stroke-opacity=\"" + num(opacity) + "\" stroke-linejoin=\"round\" stroke-linecap=\"round\" d=\"" + d +
           "\"><title>" + markup_text("track " + t.summary->id + (t.summary->name.empty() ? "" : " (" + t.summary->name + ")")) +
           "</title></path>\n";
}

void draw_lonely_fixes(std::string& out, const TrackDraw& t, const View& v, const char* colour) {
    for (const auto& line : t.lines) {
        if (line.size() != 1) continue;
        const XY p = v.to_px(line[0]);
        if (!Rect{p.x, p.y, p.x, p.y}.overlaps(v.px.grown(5))) continue;
        out += "<circle class=\"track fix\" cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"1.8\" fill=\"" + colour + "\"/>\n";
    }
}

std::string event_title(const EventDraw& e) { return event_description(*e.track, *e.event); }

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

double marker_size(EventKind k) noexcept {
    return k == EventKind::grounding || k == EventKind::close_pass ? 5 : k == EventKind::alongside ? 3.5 : 3.2;
}

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

Rect hull_rect(const EventDraw& e, const View& v) {
    if (e.hull.empty()) return {-1e9, -1e9, -1e9, -1e9};
    Rect r{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const XY& p : e.hull) {
        const XY q = v.to_px(p);
        r = {std::min(r.x0, q.x), std::min(r.y0, q.y), std::max(r.x1, q.x), std::max(r.y1, q.y)};
    }
    return r.grown(1);
}

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

std::string area_rule(const AreaDraw& a) { return a.no_entry ? "no entry" : "speed limit " + fixed_text(a.limit_kn, 1) + " kn"; }

void draw_areas(std::string& out, const Scene& scene, const View& v) {
    for (const AreaDraw& a : scene.areas) {
        const char* stroke = a.no_entry ? no_entry_stroke : speed_area_stroke;
        out += std::string("<polygon class=\"area ") + (a.no_entry ? "no-entry" : "speed-limit") + "\" points=\"" + points_attr(a.ring, v) +
               "\" fill=\"" + (a.no_entry ? red : amber) + "\" fill-opacity=\"0.12\" stroke=\"" + stroke + "\" stroke-width=\"1.6\" stroke-dasharray=\"" +
               (a.no_entry ? "7,3" : "2,3") + "\"><title>" + markup_text(a.name + ": " + area_rule(a)) + "</title></polygon>\n";
    }
}

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

double tick_minutes(double span_s) {
    for (const double m : {1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0, 60.0, 120.0, 240.0})
        if (span_s / (60 * m) <= 12) return m;
    return 480;
}

std::string tick_text(double minutes, double t) { return exercise_time_text(t, t - 60 * minutes) + " " + clock_text(t); }

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

const char* manoeuvre_words(const ManoeuvreDraw& m) { return m.course && m.speed ? "course and speed" : m.course ? "course" : "speed"; }

Rect draw_manoeuvre(std::string& out, const ManoeuvreDraw& m, const View& v, const char* colour) {
    const XY p = v.to_px(m.at);
    out += "<g class=\"manoeuvre\" data-track=\"" + markup_text(m.track->summary->id) + "\"><title>" +
           markup_text(m.track->summary->id + " altered " + manoeuvre_words(m) + " at " + clock_text(m.time_s) + " UTC (" +
                       exercise_time_text(m.time_s, m.track->exercise_start_s) + ")") +
           "</title><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"6\" fill=\"#ffffff\" stroke=\"" + colour +
           "\" stroke-width=\"2.2\"/><circle cx=\"" + num(p.x) + "\" cy=\"" + num(p.y) + "\" r=\"2\" fill=\"" + colour + "\"/></g>\n";
    return {p.x - 7, p.y - 7, p.x + 7, p.y + 7};
}

std::string manoeuvre_label(const ManoeuvreDraw& m) { return std::string("alters ") + manoeuvre_words(m) + " " + clock_text(m.time_s); }

std::string cpa_label(const CpaDraw& c) {
    return "CPA " + fixed_text(c.situation->closest_m, 0) + " m " + clock_text(c.situation->closest_s);
}

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


}  // namespace shoal::report::plot_parts
