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

#include <shoal/report/run_info.hpp>
#include <shoal/util/atomic_file.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>
#include "picture/event_phrases.hpp"

#include "picture/plot_panels.hpp"

namespace shoal::report {

using namespace detail;  // the event phrases (picture/event_phrases.hpp)
using namespace plot_parts;  // the picture's parts (picture/plot_*.hpp)

namespace {

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
    // The root element's first child, as svg_element writes it: not a <title> anywhere (a
    // user's drawing with a group titled "shoal audit area").
    const std::string head = file_head(path, 4096);
    std::size_t at = head.find("<svg");
    auto ends_name = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '>'; };
    while (at != std::string::npos && at + 4 < head.size() && !ends_name(head[at + 4])) at = head.find("<svg", at + 4);  // "<svgx": another element
    if (at == std::string::npos) return false;
    // The end of its start tag (a '>' inside a quoted attribute value passed over).
    char quote = 0;
    std::size_t i = at + 4;
    for (; i < head.size(); ++i) {
        if (quote) {
            if (head[i] == quote) quote = 0;
        } else if (head[i] == '"' || head[i] == '\'') {
            quote = head[i];
        } else if (head[i] == '>') {
            break;
        }
    }
    if (i >= head.size()) return false;
    const std::size_t child = head.find_first_not_of(" \t\r\n", i + 1);
    return child != std::string::npos && head.compare(child, 7 + picture_title.size(), "<title>" + std::string(picture_title)) == 0;
}

}  // namespace shoal::report