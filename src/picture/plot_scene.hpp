#pragma once
/// The picture's scene: the page's geometry (rectangles, panels and their views, north and
/// scale) and the audit projected into the grid's local metres (tracks, events, areas, manoeuvres,
/// closest approaches).
/// Private to src/picture (plot.cpp puts the parts on the page); namespace plot_parts.

#include <optional>
#include <utility>
#include <vector>
#include <shoal/geo/local_frame.hpp>
#include <shoal/audit/audit.hpp>

#include "picture/plot_style.hpp"

namespace shoal::report::plot_parts {

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

/// Where true north points and how long a true metre is, at one place of the frame.
struct Bearing {
    double north_deg = 0;  ///< true north, clockwise from the page's up (grid north)
    double k = 1;          ///< local metres per true metre (the frame's scale there)
    bool known = false;
};

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

struct Scene {
    std::vector<TrackDraw> tracks;
    std::vector<EventDraw> events;
    std::vector<AreaDraw> areas;
    std::vector<ManoeuvreDraw> manoeuvres;
    std::vector<CpaDraw> cpas;
    Box data;  ///< tracks and events, local metres
};

/// The view of `want` (grown in one direction to the panel's shape, centred) in `px`.
View fit(Box want, Rect px);
Box intersection(const Box& a, const Box& b);
Bearing bearing_at(const geo::LocalFrame& frame, XY p);
/// Largest 1, 2 or 5 x 10^n not above `m` (m > 0).
double round_length(double m);
std::optional<XY> project(const geo::LocalFrame& frame, LonLat p);
std::vector<XY> project_line(const geo::LocalFrame& frame, const std::vector<LonLat>& line);
/// Where the track was at `t` (linear between fixes, local metres) and its course over ground
/// there (degrees clockwise from the frame's +y; NaN when not moving); nothing when `t` is
/// outside its pieces.
std::optional<std::pair<XY, double>> track_at(const TrackDraw& d, double t);
/// The track's hull at `t`: the outline of its kept pose nearest in time, moved from where the
/// ship was at that pose to where it was at `t` and turned by the change of course over ground
/// between the two (a rigid move: the hull's shape and its angle to the course are kept).
/// Empty when no pose has an outline or `t` is outside the track.
std::vector<XY> hull_at(const TrackDraw& d, const geo::LocalFrame& frame, double t);
double longest_chord(const std::vector<XY>& pts);
/// The tracks `only` names (indices in result.tracks; empty: every track) and their events.
Scene project_scene(const audit::AuditResult& result, const geo::LocalFrame& frame, const std::vector<std::size_t>& only = {});

}  // namespace shoal::report::plot_parts
