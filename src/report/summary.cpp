#include <cstdio>

#include "report/report.hpp"

namespace shoal::report {

std::string summary_table(const audit::AuditResult& r) {
    std::string out;
    char line[512];
    std::snprintf(line, sizeof line, "%-24s %9s %9s %6s %6s %10s  %s\n", "track", "fixes", "uncovered", "aground", "close",
                  "least m", "file");
    out += line;
    std::size_t quiet = 0;
    for (const auto& t : r.tracks) {
        const auto& s = t.summary;
        if (s.groundings == 0 && s.close_passes == 0 && s.uncovered_fixes == 0) {
            ++quiet;
            continue;
        }
        char least[32];
        if (std::isfinite(s.min_clearance_m)) std::snprintf(least, sizeof least, "%.1f", s.min_clearance_m);
        else std::snprintf(least, sizeof least, "-");
        std::snprintf(line, sizeof line, "%-24.24s %9zu %9zu %6zu %6zu %10s  %s\n", s.id.c_str(), s.fixes, s.uncovered_fixes,
                      s.groundings, s.close_passes, least, s.file.c_str());
        out += line;
    }
    if (quiet) {
        std::snprintf(line, sizeof line, "(%zu more track%s: no event, all covered)\n", quiet, quiet == 1 ? "" : "s");
        out += line;
    }
    std::snprintf(line, sizeof line,
                  "total: %zu files, %zu tracks, %zu fixes (%zu poses checked), %zu groundings, %zu close passes, %zu uncovered fixes, %zu bad rows skipped\n",
                  r.files.size(), r.tracks.size(), r.fixes, r.poses, r.groundings, r.close_passes, r.uncovered_fixes, r.skipped_rows);
    out += line;
    if (r.has_encounters) {
        std::snprintf(line, sizeof line, "encounters: %zu collisions, %zu close quarters, %zu pairs came within the threshold (%.0f m)\n",
                      r.collisions, r.close_quarters, r.encounters.approaches.size(), r.encounters.threshold_m);
        out += line;
        for (const auto& e : r.encounters.events) {
            std::snprintf(line, sizeof line, "  %-14s %s - %s  %s x %s  least %.1f m\n", audit::to_string(e.kind),
                          iso_time(e.start_s).c_str(), iso_time(e.end_s).c_str(), r.tracks.at(e.a.track).summary.id.c_str(),
                          r.tracks.at(e.b.track).summary.id.c_str(), e.min_clearance_m);
            out += line;
        }
    }
    for (const auto& f : r.files)
        if (!f.error.empty()) out += "unreadable: " + f.error + "\n";
    for (const auto& e : r.errors) out += "track failed: " + e.track + " in " + e.file + ": " + e.message + "\n";
    return out;
}

}  // namespace shoal::report
