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
    const double limit = o.tolerance_m + o.max_speed_kn * metres_per_nm / 3600.0 * dt;
    // distance_m's answer, its sines asked only when its bounds leave the comparison open.
    const DistanceBounds d = distance_bounds_m(a.position, b.position);
    if (d.upper <= limit) return true;
    if (d.lower > limit) return false;
    return distance_m(a.position, b.position) <= limit;
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
    // Walk the good fixes; `last` is the last good one. Pieces are runs between persistent
    // jumps and time gaps; `opened_by_jump[p]` says what began piece p.
    std::vector<std::vector<std::size_t>> pieces;
    std::vector<char> opened_by_jump;
    std::size_t last = n;
    auto open_piece = [&](std::size_t i, bool by_jump) {
        pieces.push_back({i});
        opened_by_jump.push_back(by_jump ? 1 : 0);
        last = i;
    };
    for (std::size_t i = 0; i < n; ++i) {
        if (drop[i]) continue;
        if (last == n) {
            open_piece(i, false);
            continue;
        }
        // After a gap the clock allows almost anything: the fix starts afresh (a wild fix
        // there is caught below as a lone fix, when the fixes after it disagree with it).
        if (fx[i].time_s - fx[last].time_s > o.max_gap_s) {
            open_piece(i, false);
            continue;
        }
        if (plausible(fx[last], fx[i], o)) {
            pieces.back().push_back(i);
            last = i;
            continue;
        }
        // Does the track come back within the next few minutes? A later fix is "back" when it
        // is within reach of the last good fix and disagrees with the jumped one (or lies
        // nearer the good one): time alone must not make a jump that persists look like a
        // return.
        std::size_t back = n;
        for (std::size_t j = i + 1, seen = 0; j < n && seen < o.lookahead && fx[j].time_s - fx[i].time_s <= o.lookahead_s; ++j) {
            if (drop[j]) continue;
            ++seen;
            if (plausible(fx[last], fx[j], o) &&
                (!plausible(fx[i], fx[j], o) || distance_m(fx[last].position, fx[j].position) < distance_m(fx[i].position, fx[j].position))) {
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
        open_piece(i, true);
    }
    // A piece of one fix with a jump on one side agrees with nothing: the jump is its own.
    // (Only when some piece holds fixes that agree with each other: of two lone fixes, neither
    // can be told wild; they stay, as pieces of their own, never swept between.)
    const bool some_run = std::any_of(pieces.begin(), pieces.end(), [](const auto& p) { return p.size() > 1; });
    if (pieces.size() > 1 && some_run)
        for (std::size_t p = 0; p < pieces.size(); ++p) {
            const bool jump_side = opened_by_jump[p] || (p + 1 < pieces.size() && opened_by_jump[p + 1]);
            if (pieces[p].size() == 1 && jump_side)
                mark(pieces[p][0], NAN, "lone fix between jumps: no fix before or after it is within reach");
        }
    for (std::size_t p = 1; p < pieces.size(); ++p)
        if (opened_by_jump[p]) fx[pieces[p][0]].jump_before = true;
    // A spike against the vessel's own SOG: out to the fix and back far faster than the
    // vessel says it sails, while the fixes either side agree with that SOG. (Within reach of
    // --max-speed, a 700 m sideways fix at a 60 s cadence passes the first test.)
    for (const auto& piece : pieces)
        for (std::size_t k = 1; k + 1 < piece.size(); ++k) {
            const Fix& a = fx[piece[k - 1]];
            const Fix& f = fx[piece[k]];
            const Fix& b = fx[piece[k + 1]];
            if (drop[piece[k]] || drop[piece[k - 1]] || drop[piece[k + 1]] || !std::isfinite(a.sog_kn) || !std::isfinite(b.sog_kn)) continue;
            const double dt = b.time_s - a.time_s, dt1 = f.time_s - a.time_s, dt2 = b.time_s - f.time_s;
            if (!(dt > 0 && dt1 > 0 && dt2 > 0)) continue;
            const double sog = std::max(a.sog_kn, b.sog_kn);
            const double allowed_kn = std::max(2 * sog, sog + 10);
            // Marked only when both legs are faster than allowed: a leg whose distance's upper
            // bound already keeps it within (the same expression, and rounding is monotone) rules
            // the fix out, as the full test below would, without its sines.
            auto leg_bound_kn = [&](const Fix& x, const Fix& y, double t) {
                return std::max(0.0, distance_bounds_m(x.position, y.position).upper - o.tolerance_m) / t * 3600.0 / metres_per_nm;
            };
            if (leg_bound_kn(a, f, dt1) <= allowed_kn || leg_bound_kn(f, b, dt2) <= allowed_kn) continue;
            const double direct_kn = distance_m(a.position, b.position) / dt * 3600.0 / metres_per_nm;
            if (std::fabs(direct_kn - (a.sog_kn + b.sog_kn) / 2) > 0.5 * sog + 2) continue;  // SOG not borne out here
            auto leg_kn = [&](const Fix& x, const Fix& y, double t) {
                return std::max(0.0, distance_m(x.position, y.position) - o.tolerance_m) / t * 3600.0 / metres_per_nm;
            };
            if (leg_kn(a, f, dt1) > allowed_kn && leg_kn(f, b, dt2) > allowed_kn) {
                char why[200];
                std::snprintf(why, sizeof why, "out %.0f m and back in %.0f s against a SOG of %.1f kn (from the fix at line %zu)",
                              distance_m(a.position, f.position), dt, sog, a.line);
                mark(piece[k], leg_kn(a, f, dt1), why);
            }
        }
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
