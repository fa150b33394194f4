#pragma once
/// The pieces a panel is drawn of: paths, the chart, tracks, hulls, markers, scale bar and north
/// arrow, and exercise mode's areas, trainees' arrows and ticks, manoeuvres and closest approaches.
/// Private to src/picture (plot.cpp puts the parts on the page); namespace plot_parts.

#include <string>
#include <vector>
#include <shoal/grid/coast_grid.hpp>

#include "picture/plot_labels.hpp"

namespace shoal::report::plot_parts {

/// A trainee's direction arrows (one every 110 px of track on the page, class `direction`) and
/// time ticks (class `time-tick`, at whole multiples of tick_minutes from the exercise start;
/// their labels placed later from `ticks`).
struct Tick {
    XY at;
    std::string text;
};

/// Appends the polyline (page px) to a path in relative moves, dropping points closer than
/// `min_px` to the last one kept (the last point is always kept). Nothing for a polyline that
/// stays within 0.1 px.
void append_simplified(std::string& d, const std::vector<XY>& px, double min_px);
/// The parts of a polyline (local metres) that come near the view, as a path in page px.
std::string line_path(const std::vector<XY>& pts, const View& v, double min_px);
/// The coastline segments of the coast cells under the view as one path in page px: the
/// pieces of each cell chained, the chains of neighbouring cells joined where one ends at the
/// start of another, then simplified.
std::string coast_path(const grid::CoastGrid& g, const View& v, double min_px);
/// Land as the grid sees it (`is_land` at the centre of each sample square of `cell_px`),
/// as rectangles: runs along a row, merged with equal runs of the rows below.
std::string land_path(const grid::CoastGrid& g, const View& v, double cell_px);
std::string points_attr(const std::vector<XY>& pts, const View& v);
void text(std::string& out, double x, double y, const std::string& s, double size, const char* colour, const char* extra = "");
/// Background (grey where there is no chart), water over the grid's extent, land, coastline.
void draw_chart(std::string& out, const grid::CoastGrid& g, const View& v, double land_px, double coast_width);
const char* status_colour(Status s);
void draw_track(std::string& out, const TrackDraw& t, const View& v, const char* colour, double width, double opacity, const char* cls = "track");
/// Single-fix pieces have no line to draw: a dot shows them.
void draw_lonely_fixes(std::string& out, const TrackDraw& t, const View& v, const char* colour);
std::string event_title(const EventDraw& e);
/// The hull footprint; dashed when the heading was unknown (the hull's circle is drawn then).
void draw_hull(std::string& out, const EventDraw& e, const View& v, bool focus);
/// `pts` (page px) as an SVG points list.
std::string page_points(const std::vector<XY>& pts);
/// The marker shape of a kind at `p` (page px), `size` its radius: a circle (grounding,
/// larger; alongside), a square (in contact at the first fix), a diamond (expected contact),
/// a triangle (close pass). Returns the element's start up to its attributes' end, without
/// the closing of the tag; sets `tag` to the element's name.
std::string marker_shape(EventKind k, XY p, double size, std::string* tag);
/// Marker radius (px) of a kind in the overview: groundings and close passes large, the other
/// contacts small.
double marker_size(EventKind k) noexcept;
/// A marker in the overview (class `event <kind>`, one per event), the shape and colour of
/// its kind, with the event's full description as its tooltip.
Rect draw_marker(std::string& out, const EventDraw& e, const View& v, const char* cls, double size);
/// A contact point in a zoomed panel: a ring, so that the hull under it stays visible.
Rect draw_contact(std::string& out, const EventDraw& e, const View& v, double r);
/// Page box of an event's hull footprint (empty far away when it has none).
Rect hull_rect(const EventDraw& e, const View& v);
/// Scale bar (true metres) in the panel's lower left corner; returns the page area it takes.
Rect draw_scale_bar(std::string& out, const View& v, const Bearing& b);
/// Arrow to true north in the panel's upper right corner; returns the page area it takes.
Rect draw_north_arrow(std::string& out, const View& v, const Bearing& b);
void open_panel(std::string& out, const View& v, const std::string& cls, const std::string& id);
void close_panel(std::string& out, const View& v);
/// "no entry" or "speed limit 8.0 kn".
std::string area_rule(const AreaDraw& a);
/// The assessment's areas: a pale fill and a dashed outline (red: no entry; brown: speed limit).
void draw_areas(std::string& out, const Scene& scene, const View& v);
/// The areas' names ("Mother Bank (no entry)") inside them where they fit, else beside them.
void name_areas(std::string& out, const Scene& scene, const View& v, Labels& labels);
/// The minutes between time ticks: the smallest of 1, 2, 5, 10, 15, 20, 30 min, 1, 2, 4, 8 h
/// that gives at most 12 over `span_s`.
double tick_minutes(double span_s);
/// Exercise time with UTC beside it, for a time tick `minutes` after the start, at `t`:
/// "T+10:00 10:12:30Z", as the debrief's events give it (exercise_time_text).
std::string tick_text(double minutes, double t);
void draw_direction_and_ticks(std::string& out, const TrackDraw& t, const View& v, std::vector<Tick>& ticks);
/// "course", "speed", "course and speed".
const char* manoeuvre_words(const ManoeuvreDraw& m);
/// A manoeuvre on its track: a ring in the track's colour (class `manoeuvre`) with what was
/// altered and when as its tooltip; returns its page box.
Rect draw_manoeuvre(std::string& out, const ManoeuvreDraw& m, const View& v, const char* colour);
/// "alters course 10:05:00Z".
std::string manoeuvre_label(const ManoeuvreDraw& m);
/// "CPA 420 m 10:12:30Z".
std::string cpa_label(const CpaDraw& c);
/// The closest approach: both hulls at that moment (in the colours given), the line between
/// the reference points (dashed, class `cpa-line`); returns the page box of the line.
Rect draw_cpa(std::string& out, const CpaDraw& c, const View& v, const char* colour_a, const char* colour_b, double width);

}  // namespace shoal::report::plot_parts
