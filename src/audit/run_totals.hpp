#pragma once
/// A run's totals (AuditResult's counts and first and last fix) from its tracks' summaries:
/// the audit adds each track as it is swept, a merge of shards' debrief records adds them
/// again. Internal.

#include <algorithm>
#include <cmath>

#include <shoal/audit/audit.hpp>

namespace shoal::audit {

/// Adds the counts and times of `s` to `run`'s totals.
inline void add_to_totals(AuditResult& run, const TrackSummary& s) noexcept {
    run.fixes += s.fixes;
    run.poses += s.poses;
    run.uncovered_fixes += s.uncovered_fixes;
    run.groundings += s.groundings;
    run.close_passes += s.close_passes;
    run.alongside += s.alongside;
    run.contacts_at_start += s.contacts_at_start;
    run.expected_contacts += s.expected_contacts;
    run.chart_disagreements += s.chart_disagreements;
    run.wild_fixes += s.wild_fixes.size();
    run.jumps += s.jumps;
    run.unknown_heading_fixes += s.unknown_heading_fixes;
    if (s.fixes) {
        run.first_fix_s = std::isnan(run.first_fix_s) ? s.start_s : std::min(run.first_fix_s, s.start_s);
        run.last_fix_s = std::isnan(run.last_fix_s) ? s.end_s : std::max(run.last_fix_s, s.end_s);
    }
}

}  // namespace shoal::audit
