#pragma once
/// A picture of an audit (`shoal check --plot FILE.svg`): an SVG 1.1 file with an overview
/// panel (coastline, land as the grid sees it, the tracks coloured by what happened on them,
/// hull footprints and markers at the events with their times) and one zoomed panel per
/// grounding (the hull at first contact, the track and its fixes, the coastline, the contact
/// point). Every panel has a scale bar in true metres and an arrow to true north; both come
/// from the frame's Jacobian at the panel's centre, so they stay right in a user CRS whose
/// grid north or scale differs from the ground's.
///
/// Drawing is in the grid's local metres (a conformal frame), y up on the ground, y down on
/// the page. Land is the grid's own land test (`CoastGrid::is_land`) sampled about once per
/// pixel, with the clipped coastline segments drawn on top; outside the grid's extent is
/// shaded as "no chart".
///
/// Classes a reader (or a test) can rely on: `panel overview`, `panel zoom` (ids `overview`,
/// `zoom-1`, `zoom-2`, ...), `event grounding` and `event close_pass` (one marker per event,
/// in the overview), `contact grounding` / `contact close_pass` (markers in zoomed panels),
/// `hull grounding` / `hull close_pass`, `track`, `coastline`, `land`, `scale-bar` (its `bar`
/// and `caption`), `north-arrow` (rotated clockwise from the page's up by the angle of true
/// north), `legend`. Labels that would overlap others are left out; every marker carries the
/// event's full description as a `<title>` (a tooltip in browsers).

#include <cstddef>
#include <string>

#include "audit/audit.hpp"
#include "grid/coast_grid.hpp"

namespace shoal::report {

struct PlotOptions {
    /// Zoomed panels drawn at most (one per grounding, in report order); the rest are counted.
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
