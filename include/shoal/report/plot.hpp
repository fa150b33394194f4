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
#include <string>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/coast_grid.hpp>

namespace shoal::report {

struct PlotOptions {
    /// Zoomed panels drawn at most (groundings first, then the other contacts, then close
    /// passes; see above); the rest are counted by kind.
    std::size_t max_zoom_panels = 12;
    /// Width of the picture in CSS pixels (>= 400); the height follows from the content.
    double width_px = 1200;
};

/// The picture of `result` (audited against `grid`) as SVG text. Throws UsageError for a
/// width under 400 px or not finite.
std::string plot_svg(const audit::AuditResult& result, const grid::CoastGrid& grid, const PlotOptions& options = {});

/// Writes `plot_svg(...)` to `path` atomically ("-" or "" writes to stdout). Throws InputError
/// naming the path when it cannot be written.
void write_plot_svg(const std::string& path, const audit::AuditResult& result, const grid::CoastGrid& grid,
                    const PlotOptions& options = {});

}  // namespace shoal::report
