#include <shoal/track/wild_fixes.hpp>

#include <cmath>
#include <algorithm>
#include <cstdio>

namespace shoal::track {

namespace {

constexpr double metres_per_nm = 1852.0;

double implied_kn(const Fix& a, const Fix& b) noexcept {
    const double dt = b.time_s - a.time_s;
    const double d = distance_m(a.position, b.position);
    return dt > 0 ? d / dt * 3600.0 / metres_per_nm : INFINITY;
}

std::string describe_jump(const Fix& from, const Fix& to, const char* tail) {
    char buf[160];
    const double d = distance_m(from.position, to.position);
    const double dt = to.time_s - from.time_s;
    if (d >= 1000)
        std::snprintf(buf, sizeof buf, "jump of %.1f km in %.0f s (%.0f kn) from the fix at line %zu%s", d / 1000, dt,
                      implied_kn(from, to), from.line, tail);
    else
        std::snprintf(buf, sizeof buf, "jump of %.0f m in %.1f s (%.0f kn) from the fix at line %zu%s", d, dt, implied_kn(from, to),
                      from.line, tail);
    return buf;
}

bool null_island(const Fix& f) noexcept { return std::fabs(f.position.lat) < 1e-7 && std::fabs(f.position.lon) < 1e-7; }

}  // namespace

bool plausible(const Fix& a, const Fix& b, const WildFixOptions& o) noexcept {
    const double dt = std::fabs(b.time_s - a.time_s);
    return distance_m(a.position, b.position) <= o.tolerance_m + o.max_speed_kn * metres_per_nm / 3600.0 * dt;
}

std::vector<WildFix> drop_wild_fixes(Track& track, const WildFixOptions& o) {
    std::vector<Fix>& fx = track.fixes;
    const std::size_t n = fx.size();
    std::vector<WildFix> wild;
    std::vector<char> drop(n, 0);
    auto mark = [&](std::size_t i, double kn, std::string why) {
        drop[i] = 1;
        wild.push_back({fx[i].line, fx[i].time_s, fx[i].position, kn, std::move(why)});
    };
    for (std::size_t i = 0; i < n; ++i) {
        fx[i].jump_before = false;
        if (null_island(fx[i])) mark(i, INFINITY, "position 0,0 (no fix)");
    }
    // Walk the good fixes; `last` is the last good one. Pieces are runs between persistent jumps.
    std::vector<std::vector<std::size_t>> pieces;
    std::size_t last = n;
    for (std::size_t i = 0; i < n; ++i) {
        if (drop[i]) continue;
        if (last == n) {
            pieces.push_back({i});
            last = i;
            continue;
        }
        if (plausible(fx[last], fx[i], o)) {
            pieces.back().push_back(i);
            last = i;
            continue;
        }
        // Does the track come back within the next fixes?
        std::size_t back = n;
        for (std::size_t j = i + 1, seen = 0; j < n && seen < o.lookahead; ++j) {
            if (drop[j]) continue;
            ++seen;
            if (plausible(fx[last], fx[j], o)) {
                back = j;
                break;
            }
        }
        if (back != n) {
            for (std::size_t k = i; k < back; ++k)
                if (!drop[k]) mark(k, implied_kn(fx[last], fx[k]), describe_jump(fx[last], fx[k], " and back"));
            pieces.back().push_back(back);
            last = back;
            i = back;
            continue;
        }
        // The jump persists: a new piece starts here.
        pieces.push_back({i});
        last = i;
    }
    // A piece of one fix between jumps, or between a jump and the track's start or end,
    // agrees with nothing on either side.
    // (Only when some piece holds fixes that agree with each other: of two lone fixes, neither
    // can be told wild; they stay, as pieces of their own, never swept between.)
    const bool some_run = std::any_of(pieces.begin(), pieces.end(), [](const auto& p) { return p.size() > 1; });
    if (pieces.size() > 1 && some_run)
        for (std::size_t p = 0; p < pieces.size(); ++p)
            if (pieces[p].size() == 1) mark(pieces[p][0], NAN, "lone fix between jumps: no fix before or after it is within reach");
    for (std::size_t p = 1; p < pieces.size(); ++p) fx[pieces[p][0]].jump_before = true;
    // Remove, keeping a jump mark on the next good fix when the fix carrying it was dropped.
    std::vector<Fix> kept;
    kept.reserve(n);
    bool carry = false;
    for (std::size_t i = 0; i < n; ++i) {
        if (drop[i]) {
            carry = carry || fx[i].jump_before;
            continue;
        }
        kept.push_back(fx[i]);
        if (carry && kept.size() > 1) kept.back().jump_before = true;
        carry = false;
    }
    if (!kept.empty()) kept.front().jump_before = false;
    fx = std::move(kept);
    std::sort(wild.begin(), wild.end(), [](const WildFix& a, const WildFix& b) { return a.time_s < b.time_s; });
    return wild;
}

}  // namespace shoal::track
