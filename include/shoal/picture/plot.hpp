#pragma once
/// A picture of an audit (`shoal check --plot FILE.svg`): an SVG 1.1 file with an overview
/// panel (coastline, land as the grid sees it, the tracks coloured by what happened on them,
/// hull footprints and markers at the events with their times) and zoomed panels (the hull at
/// the event, the track and its fixes, the coastline, the contact point): every grounding
/// first, in time order; then the other contacts, most severe first (alongside, then in
/// contact at the first fix, then contacts in expected-contact areas; within a kind, deepest
/// penetration first); then close passes, least clearance first; up to
/// PlotOptions::max_zoom_panels, with what is left out counted by kind. Each section has a
/// heading ("Groundings", "Other contacts (not groundings)", "Close passes"); each zoomed
/// panel's title gives the track and vessel name, the kind in words, the speed at contact and
/// where it came from, penetration or clearance, start (UTC) and duration, and the heading,
/// which is printed only when it was known: with no heading the hull drawn is the hull's
/// circle, dashed, labelled "heading unknown (hull circle)". Every panel has a scale bar in
/// true metres and an arrow to true north; both come from the frame's Jacobian at the panel's
/// centre, so they stay right in a user CRS whose grid north or scale differs from the ground's.
///
/// Colours: groundings red (a track is red only when it has one), close passes amber, the
/// contacts that are not groundings muted: alongside steel blue, in contact at the first fix
/// grey, expected contact green (and a track with such contacts and no grounding violet).
/// The headline counts every kind of event; the legend lists what is drawn.
///
/// Drawing is in the grid's local metres (a conformal frame), y up on the ground, y down on
/// the page. Land is the grid's own land test (`CoastGrid::is_land`) sampled about once per
/// pixel, with the clipped coastline segments drawn on top; outside the grid's extent is
/// shaded as "no chart".
///
/// Exercise mode (the result has encounters): a trainee's track is drawn on top in its own
/// blue (class `track trainee`), whatever happened on it (its events keep their markers), with
/// direction arrows (class `direction`, one every 110 px) and time ticks across it (class
/// `time-tick`, attribute `data-minutes`) every 1, 2, 5, 10, 15, 20, 30 min or 1, 2, 4, 8 h from
/// the first fix of its exercise (at most 12 over the exercise), labelled "T+10 min 10:12:30Z"
/// (class `label time-tick`) where they fit; targets keep the colours below. The assessment's
/// no-entry and speed-limit areas are drawn (classes `area no-entry`, `area speed-limit`) and
/// named ("Mother Bank (no entry)", class `label area-name`); each encounter's closest approach
/// (AuditResult::situations) is drawn in the overview (class `cpa`: both hulls then, the line
/// between the ships, the label "CPA 420 m 10:12:30Z") and, in plot_svg, as a zoomed panel of
/// its own (section "Closest approaches", ids `cpa-1`, `cpa-2`, ... in time order, at most
/// max_zoom_panels; see cpa_svg); the manoeuvres the COLREG reading found
/// (ColregEncounter::action_a/b) are rings on the track (class `manoeuvre`, attribute
/// `data-track`) labelled "alters course 10:05:00Z" (class `label manoeuvre-label`).
///
/// Classes a reader (or a test) can rely on: `panel overview`, `panel zoom` (ids `overview`,
/// `zoom-1`, `zoom-2`, ..., in the order above; the panel's title is inside its group, the
/// first line of class `zoom-title`), `section` (the headings), `note` (what was not drawn),
/// `event <kind>` (one marker per event, in the overview; <kind> as audit::to_string:
/// `grounding`, `alongside`, `in_contact_at_start`, `expected_contact`, `close_pass`),
/// `contact <kind>` (markers in zoomed panels), `hull <kind>` (dashed, `stroke-dasharray`,
/// when the heading was unknown), `label heading-unknown`, `track`, `coastline`, `land`,
/// `scale-bar` (its `bar` and `caption`), `north-arrow` (rotated clockwise from the page's up
/// by the angle of true north), `legend`, `summary`. Labels that would overlap others are left
/// out; every marker carries the event's full description and its evidence (speed and its
/// source, stop, reference point inside land, AIS status, structure, area) as a `<title>` (a
/// tooltip in browsers).

#include <cstddef>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/picture/wording.hpp>  // the events and times in words the picture uses
#include <shoal/report/markup.hpp>     // markup_text

namespace shoal::report {

struct PlotOptions {
    /// Zoomed panels drawn at most (groundings first, then the other contacts, then close
    /// passes; see above); the rest are counted by kind.
    std::size_t max_zoom_panels = 12;
    /// Width of the picture in CSS pixels (>= 400); the height follows from the content.
    double width_px = 1200;
    /// The tracks drawn (indices in AuditResult::tracks), with their events: one exercise's,
    /// say. Empty: every track. The headline of plot_svg still counts the whole result.
    std::vector<std::size_t> tracks{};
};

/// The picture of `result` (audited against `grid`) as SVG text. Throws UsageError for a
/// width under 400 px or not finite, or a track index out of range.
std::string plot_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const PlotOptions& options = {});

/// The legend and the overview panel of plot_svg alone (no headline, no zoomed panels), as an
/// `<svg>` element without an XML declaration: to put inline in an HTML page. Its panel has
/// id `overview` (clip path `clip-overview`).
std::string overview_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const PlotOptions& options = {});

/// One zoomed panel, around a track event or around a moment of some tracks (a ship-to-ship
/// encounter, an assessment breach).
struct ZoomSpec {
    std::string id = "zoom";  ///< the panel's id (unique within a page); its clip path is `clip-<id>`
    geo::LonLat centre;       ///< the panel's centre, and where scale bar and north arrow are measured
    /// Ground across the panel's shorter side, metres; 0: 8 times the longest hull drawn, at
    /// least 100 m (800 m when no hull is known), as plot_svg's panels.
    double size_m = 0;
    /// The tracks drawn in colour with their fixes (indices in AuditResult::tracks); the other
    /// tracks of PlotOptions::tracks are grey. The first has the kind's colour, the next ones
    /// teal, purple, brown, grey (blue is a trainee's in exercise mode).
    std::vector<std::size_t> tracks;
    /// A track event of `tracks[0]` (an element of its TrackResult::events): drawn as plot_svg
    /// draws it (its hull, the contact ring, "first contact HH:MM:SSZ"); `kind` is then its own.
    const audit::Event* event = nullptr;
    /// Hull outlines at the moment (closed rings, lon/lat), in the order of `tracks`, each
    /// labelled with its track id (an encounter's two ships).
    std::vector<std::vector<geo::LonLat>> hulls;
    /// A time window (epoch seconds; NaN: none): the hulls of `tracks` at their kept poses
    /// (TrackResult::poses) inside it are outlined faintly, showing how the ships moved.
    double start_s = NAN, end_s = NAN;
    /// Class and colour of the marker at `centre` (`contact <kind>`, `hull <kind>`):
    /// "collision" (red), "close_quarters" (amber), "breach" (violet).
    std::string kind = "breach";
    std::string time_label;  ///< beside the marker ("" none)
    std::string tooltip;     ///< the marker's <title>
};

/// The panel as an `<svg>` element (no XML declaration, no title above it: the page around it
/// says what it is), `width_px` wide (>= 150) and 3/4 as high. Throws UsageError for a bad
/// width, a track index out of range, or an event that is not one of tracks[0]'s.
std::string zoom_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const ZoomSpec& spec, double width_px = 360,
                     const PlotOptions& options = {});

/// An encounter's closest approach (AuditResult::situations[situation]) as a panel like
/// zoom_svg's: both ships' tracks (a trainee first, in the trainee's blue), both hulls at that
/// moment (class `hull cpa`; each the outline of the track's nearest kept pose, moved rigidly to
/// where the ship was then and turned by the change of course over ground), the line between
/// the reference points (class `cpa-line`) and its label "CPA 420 m 10:12:30Z" (class
/// `cpa-distance`), the manoeuvres found on either track (class `manoeuvre`) and the
/// assessment's areas. "" when the closest approach cannot be placed. Throws UsageError for a
/// bad width or situation index.
std::string cpa_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, std::size_t situation, double width_px = 360,
                    const PlotOptions& options = {});

/// The colour (#rrggbb) the picture gives a kind: an audit::EventKind name (audit::to_string),
/// "collision", "close_quarters" or "breach"; grey for anything else.
const char* kind_colour(const std::string& kind) noexcept;

/// Writes `plot_svg(...)` to `path` atomically ("-" or "" writes to stdout). Throws InputError
/// naming the path when it cannot be written.
/// The start of the picture's <title> ("shoal audit: 3 tracks, ..."): how shoal tells a picture
/// it wrote, which --plot may replace (is_shoal_picture: the root <svg> element's first child,
/// within the file's first 4 KiB; a <title> further in, a group's, is not shoal's mark).
inline constexpr std::string_view picture_title = "shoal audit";
bool is_shoal_picture(const std::string& path);

void write_plot_svg(const std::string& path, const audit::AuditResult& result, const grid::CoastGrid& grid,
                    const PlotOptions& options = {});

}  // namespace shoal::report
