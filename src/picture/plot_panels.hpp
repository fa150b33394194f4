#pragma once
/// The panels: the overview, a zoomed panel and what it is about (its focus), and the legend.
/// Private to src/picture (plot.cpp puts the parts on the page); namespace plot_parts.

#include <string>
#include <vector>
#include <shoal/grid/coast_grid.hpp>

#include "picture/plot_pieces.hpp"

namespace shoal::report::plot_parts {

/// One line of a zoomed panel's title.
struct TitleLine {
    std::string text;
    const char* colour;
    double size;
    bool bold;
};

/// Height (px) the title of a zoomed panel takes above it.
inline constexpr double zoom_title_px = 76;

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
inline constexpr const char* other_track_colours[] = {"#0f7d6b", "#7b3fa0", "#8c564b", "#4d4d4d"};

struct LegendItem {
    std::string symbol;  ///< SVG drawn in a 22 x 12 box at the origin
    std::string caption;
};

/// The time label of an event in the overview: "10:03:12Z", "(n)" added when it has a panel.
std::string time_label(const EventDraw& e);
/// `order`: the events most severe first (see order_events).
void draw_overview(std::string& out, const Scene& scene, const grid::CoastGrid& g, const View& v, const std::vector<EventDraw*>& order);
/// The title of a zoomed panel: track and name; the kind in words; speed at contact (or at
/// least clearance) and penetration (or clearance); start and duration; heading.
std::vector<TitleLine> zoom_title(const EventDraw& e);
const char* own_colour(const Focus& f, std::size_t k);
void draw_zoom(std::string& out, const Scene& scene, const grid::CoastGrid& g, const Focus& focus, const View& v);
/// The focus of a track event's panel, titled as plot_svg titles it.
Focus event_focus(const EventDraw& e);
/// The focus of an encounter's closest approach: both ships (a trainee first, in the
/// trainee's colour), their hulls at that moment, the CPA line and distance.
Focus cpa_focus(const CpaDraw& c, const std::string& id, std::size_t number);
/// The ground a closest approach's panel shows across its shorter side (metres).
double cpa_size_m(const CpaDraw& c);
double draw_legend(std::string& out, double x0, double y0, double width, const std::vector<LegendItem>& items);
/// What the picture draws: the chart, the kinds of track present, hulls, and a marker for
/// groundings and close passes (always, so that none drawn says none) and for each other kind
/// of contact present.
std::vector<LegendItem> legend_items(const grid::CoastGrid& g, const Scene& scene);

}  // namespace shoal::report::plot_parts
