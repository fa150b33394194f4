// The panels: the overview, a zoomed panel and what it is about (its focus), and the legend.
#include "picture/plot_panels.hpp"

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

// ---------------------------------------------------------------- the panels

std::string time_label(const EventDraw& e) {
    return clock_text(e.event->start_s) + (e.zoom ? " (" + std::to_string(e.zoom) + ")" : "");
}

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

double cpa_size_m(const CpaDraw& c) { return std::max({8 * c.hull_length_m, 1.8 * c.situation->closest_m, 100.0}); }

// ---------------------------------------------------------------- legend


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

}  // namespace shoal::report::plot_parts
