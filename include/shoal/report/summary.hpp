#pragma once
/// The summary table of a run, for stdout.

#include <string>

#include <shoal/audit/audit.hpp>

namespace shoal::report {

/// How much of a run the summary shows: `normal` the counts of each kind of event first, then
/// one line per track with events; `verbose` one line per track (every track read).
enum class SummaryDetail { normal, verbose };

/// The human summary: the world, the totals and the counts of each kind of event first; then
/// the table of tracks (those with events, or every track: `detail`), every grounding, the
/// encounters and scores (exercise mode), and the problems met.
std::string summary_table(const audit::AuditResult& result, SummaryDetail detail = SummaryDetail::normal);

}  // namespace shoal::report
