#pragma once
/// The instructor's debrief sheet (`shoal check --debrief FOLDER`): one self-contained HTML page
/// per exercise, written into FOLDER as `<exercise>.html` (nothing else is written there). A
/// page needs nothing at view time (no network: styles inline, pictures inline SVG, no script,
/// no font to fetch) and prints on A4 (`@page`, print rules, no section split across pages
/// where it can be helped). It holds, in this order:
///
/// - a header (`header`): the exercise, its time span (first to last fix of its tracks), the
///   chart and grid (sources, frame, cell size, fingerprint), the hull and the rules of the run
///   (margin, step, ship margin, encounter range, limiting depth, under-keel clearance);
/// - the picture of the run (`section#picture`): plot.hpp's overview of the exercise's tracks;
/// - the trainees' scores (`section#scores`, a `table.scores` with one `tr.score` per trainee)
///   when the run was assessed (AuditResult::has_assessment), else a line saying it was not;
/// - the ships (`table.ships`, one `tr.ship` per track: id, name, role, fixes, times, events);
/// - the events in time order (`section#events`, one `article.event` each, `data-kind` its kind,
///   `data-time` its start as ISO 8601 UTC): groundings and the other contacts, close passes,
///   collisions, close quarters, and assessment breaches, each with a zoomed panel (plot.hpp's
///   zoom_svg) up to DebriefOptions::max_zoom_panels;
/// - the encounter table (`table.encounters`, one `tr.encounter` per COLREG situation:
///   situation, start, the two ships, give-way, stand-on, relative bearings, CPA and TCPA at
///   the start, the actual closest approach, least hull-to-hull clearance, each ship's action).
///
/// Every text that comes from input (track ids and names, file and exercise names, criteria)
/// is escaped. A page carries `<meta name="generator" content="shoal debrief">`: an existing
/// `<exercise>.html` is replaced only when it carries that mark (a warning otherwise, and that
/// page is not written).
///
/// File names: the exercise name's last path components, as few as keep the names of the run
/// apart (compared ignoring case), with every character but ASCII letters, digits, `.`, `-`
/// and `_` made `_`, no leading dot, at most 100 bytes, then `.html`; "exercise" when nothing
/// is left; `-2`, `-3`, ... added to names still equal. Outside exercise mode the run is one
/// page, `run.html`.

#include <cstddef>
#include <string>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::report {

struct DebriefOptions {
    double picture_width_px = 1000;    ///< the overview (scaled to the page's width)
    double zoom_width_px = 340;        ///< each zoomed panel
    std::size_t max_zoom_panels = 60;  ///< events with a panel at most (the first in time); the rest are listed without
};

/// One page: an exercise, its file name in the folder and its tracks (indices in AuditResult::tracks).
struct DebriefPage {
    std::string exercise;
    std::string file;
    std::vector<std::size_t> tracks;
    /// What of the run's lists belongs to the page, found once for every page by debrief_pages
    /// (so that writing n pages costs linear time, not n passes over the run's lists): the
    /// indices of its encounters (AuditResult::encounters.events), closest approaches
    /// (encounters.approaches), COLREG situations, breaches and scores. Without `indexed` (a
    /// page made by hand), debrief_html finds them itself.
    bool indexed = false;
    std::vector<std::size_t> encounters, approaches, situations, breaches, scores;
};

/// The pages of `result`: one per exercise (TrackSummary::exercise; the whole run when not in
/// exercise mode), in the order of their first track, with their file names (see above).
std::vector<DebriefPage> debrief_pages(const audit::AuditResult& result);

/// The page of `page` as HTML text. `info` says what the run was (report::run_info).
std::string debrief_html(const audit::AuditResult& result, const grid::CoastGrid& grid, const RunInfo& info, const DebriefPage& page,
                         const DebriefOptions& options = {});

/// Before any work: `folder` can receive the pages: it is a folder, or does not exist yet and
/// its parent folder does (it is created when the pages are staged). Throws UsageError for a
/// path that names a page rather than a folder (ends in .html or .htm) or standard output,
/// InputError otherwise.
void check_debrief_folder(const std::string& folder);

/// The pages' paths in `folder`, as outputs for check_outputs (option "--debrief").
std::vector<OutputSpec> debrief_outputs(const std::string& folder, const std::vector<DebriefPage>& pages);

/// Every page of `result` staged in `folder` (created if it does not exist), for commit_all
/// with the report, once check_outputs has passed for the pages (debrief_outputs) with
/// `others` (the run's other outputs) against `inputs`: the page names come from the
/// exercises, so they can be checked only now. A page whose file exists without shoal's mark
/// is not staged: `refused` says so, a message each (the CLI's exit 2). Throws UsageError
/// when a page would be an input or another output, InputError naming the file when one
/// cannot be written.
std::vector<StagedOutput> stage_debrief(const std::string& folder, const audit::AuditResult& result, const grid::CoastGrid& grid,
                                        const RunInfo& info, const std::vector<std::string>& inputs,
                                        const std::vector<OutputSpec>& others, const DebriefOptions& options = {},
                                        std::vector<std::string>* refused = nullptr);

}  // namespace shoal::report
