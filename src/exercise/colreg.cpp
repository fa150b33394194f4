// COLREG situations (see include/shoal/exercise/colreg.hpp): the classification at the moment a
// pair comes within range, CPA/TCPA then, the actual closest approach and each ship's action.
#include <shoal/exercise/colreg.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <shoal/util/error.hpp>
#include "sweep/local_track.hpp"

namespace shoal::audit {

using geo::XY;

const char* to_string(Situation s) noexcept {
    switch (s) {
        case Situation::head_on: return "head-on";
        case Situation::overtaking: return "overtaking";
        case Situation::crossing: break;
    }
    return "crossing";
}

namespace {

constexpr double deg = 180.0 / std::numbers::pi;
constexpr double abaft_from_deg = 112.5;  // 22.5 degrees abaft the beam
constexpr double slowest_reference_ms = 1852.0 / 3600.0;  // speed changes are judged against at least 1 knot

/// |a - b| on the circle, in [0, 180].
double angle_between(double a, double b) { return std::fabs(turn(b, a)); }
bool abaft_the_beam(double bearing) { return bearing > abaft_from_deg && bearing < 360.0 - abaft_from_deg; }
bool right_ahead(double bearing, double tol) { return bearing <= tol || bearing >= 360.0 - tol; }
bool on_starboard(double bearing) { return bearing > 0 && bearing < 180; }

/// One track for the rules: the local track (broken at gaps and at jumps), per fix a heading
/// (an unknown one from the motion) and a velocity, per fix interval the velocity.
struct Local {
    LocalTrack track;
    std::vector<double> heading;  ///< per fix, [0, 360)
    std::vector<XY> velocity;     ///< per fix interval (m/s)
    std::vector<XY> fix_velocity;  ///< per fix: from its speed and course over ground when given, else from positions

    std::size_t size() const { return track.size(); }
    double t(std::size_t j) const { return track.time(j); }
    /// Position at tt on fix interval i (tt may be its end).
    XY at(std::size_t i, double tt) const { return track.position({i, track.fraction(i, tt)}); }
    double speed_at_fix(std::size_t j) const { return std::sqrt(geo::norm2(fix_velocity[j])); }
    VesselAt state(std::size_t i, double tt) const {
        const Where w{i, track.fraction(i, tt)};
        return {track.position(w), wrap_360(track.interpolate_heading(heading, w)), track.interpolate(fix_velocity, w)};
    }
    /// The first fix after tt.
    std::size_t first_after(double tt) const {
        const auto& fx = track.track().fixes;
        return static_cast<std::size_t>(std::upper_bound(fx.begin(), fx.end(), tt, [](double v, const track::Fix& x) { return v < x.time_s; }) - fx.begin());
    }
};

Local prepare(const track::Track& tr, const geo::LocalFrame& frame, double max_gap_s) {
    const std::size_t n = tr.fixes.size();
    for (const track::Fix& f : tr.fixes)
        if (!std::isfinite(f.time_s)) throw InputError("track '" + tr.id + "' in '" + tr.file + "', fix at line " + std::to_string(f.line) + ": no time");
    for (std::size_t i = 0; i + 1 < n; ++i)
        if (!(tr.fixes[i + 1].time_s > tr.fixes[i].time_s))
            throw InputError("track '" + tr.id + "' in '" + tr.file + "', fix at line " + std::to_string(tr.fixes[i + 1].line) +
                             ": fix times not strictly increasing");
    Local l{LocalTrack(tr, frame, Breaks{.max_gap_s = max_gap_s, .at_jumps = true}, Placing::positions), {}, {}, {}};
    for (std::size_t i = 0; i + 1 < n; ++i)
        l.velocity.push_back((1.0 / (l.t(i + 1) - l.t(i))) * (l.track.position(i + 1) - l.track.position(i)));
    for (std::size_t j = 0; j < n; ++j) {
        const track::Fix& f = tr.fixes[j];
        double h = f.heading_used_deg;
        if (f.heading_source == track::HeadingSource::none || !std::isfinite(h)) {
            const XY v = l.velocity.empty() ? XY{} : l.velocity[std::min(j, l.velocity.size() - 1)];
            h = geo::norm2(v) > 0 ? std::atan2(v.x, v.y) * deg : (j > 0 ? l.heading[j - 1] : 0.0);
        }
        l.heading.push_back(wrap_360(h));
    }
    // Velocity at each fix: the speed and course over ground the source gives (smoother than
    // positions a few seconds apart), else the motion between fixes around it.
    for (std::size_t j = 0; j < n; ++j) {
        const track::Fix& f = tr.fixes[j];
        const double kn = std::isfinite(f.speed_used_kn) ? f.speed_used_kn : f.sog_kn;
        if (std::isfinite(kn) && std::isfinite(f.cog_deg) && f.speed_source != track::SpeedSource::positions &&
            f.speed_source != track::SpeedSource::positions_over_sog) {
            const double a = f.cog_deg / deg;
            l.fix_velocity.push_back((kn * 1852.0 / 3600.0) * XY{std::sin(a), std::cos(a)});
        } else if (l.velocity.empty()) {
            l.fix_velocity.push_back({});
        } else if (j == 0 || j == n - 1) {
            l.fix_velocity.push_back(l.velocity[std::min(j, l.velocity.size() - 1)]);
        } else {
            l.fix_velocity.push_back(0.5 * (l.velocity[j - 1] + l.velocity[j]));
        }
    }
    return l;
}

/// The first fix after `from_s` and up to `until_s` from which the ship's heading or speed
/// differs from those at the start, and keeps differing for `sustain_s`.
Manoeuvre action(const Local& s, double from_s, double until_s, const VesselAt& start, const ColregOptions& o) {
    const double v0 = std::sqrt(geo::norm2(start.velocity));
    const double ref = std::max(v0, slowest_reference_ms);
    auto course = [&](std::size_t j) { return angle_between(s.heading[j], start.heading_deg) >= o.course_change_deg; };
    auto speed = [&](std::size_t j) { return std::abs(s.speed_at_fix(j) - v0) >= o.speed_change * ref; };
    const std::size_t n = s.size();
    for (std::size_t j = s.first_after(from_s); j < n && s.t(j) <= until_s; ++j) {
        if (!course(j) && !speed(j)) continue;
        bool kept = true, long_enough = false;
        for (std::size_t k = j; k < n; ++k) {
            if (!course(k) && !speed(k)) {
                kept = false;
                break;
            }
            if (s.t(k) >= s.t(j) + o.sustain_s) {
                long_enough = true;
                break;
            }
        }
        if (!kept || !long_enough) continue;
        Manoeuvre m;
        m.course = course(j);
        m.speed = speed(j);
        m.time_s = s.t(j);
        return m;
    }
    return {};
}

}  // namespace

double relative_bearing_deg(const VesselAt& from, XY to) {
    const XY d = to - from.position;
    return wrap_360(std::atan2(d.x, d.y) * deg - from.heading_deg);
}

Classification classify(const VesselAt& a, const VesselAt& b, double head_on_tolerance_deg) {
    Classification c;
    c.bearing_of_b_deg = relative_bearing_deg(a, b.position);
    c.bearing_of_a_deg = relative_bearing_deg(b, a.position);
    const bool b_abaft = abaft_the_beam(c.bearing_of_b_deg), a_abaft = abaft_the_beam(c.bearing_of_a_deg);
    if (b_abaft || a_abaft) {
        c.situation = Situation::overtaking;
        // The ship abaft the other's beam is the overtaking one; both: the faster.
        const bool b_overtakes = b_abaft && a_abaft ? geo::norm2(b.velocity) > geo::norm2(a.velocity) : b_abaft;
        c.give_way = b_overtakes ? Party::b : Party::a;
        c.stand_on = b_overtakes ? Party::a : Party::b;
        return c;
    }
    if (angle_between(a.heading_deg, b.heading_deg + 180.0) <= head_on_tolerance_deg && right_ahead(c.bearing_of_b_deg, head_on_tolerance_deg) &&
        right_ahead(c.bearing_of_a_deg, head_on_tolerance_deg)) {
        c.situation = Situation::head_on;
        c.give_way = Party::both;
        c.stand_on = Party::neither;
        return c;
    }
    c.situation = Situation::crossing;
    const bool a_gives = on_starboard(c.bearing_of_b_deg), b_gives = on_starboard(c.bearing_of_a_deg);
    if (a_gives && b_gives) {
        c.give_way = Party::both;
    } else if (a_gives) {
        c.give_way = Party::a;
        c.stand_on = Party::b;
    } else if (b_gives) {
        c.give_way = Party::b;
        c.stand_on = Party::a;
    }
    return c;
}

Cpa cpa(const VesselAt& a, const VesselAt& b) {
    const XY r = b.position - a.position;
    const XY v = b.velocity - a.velocity;
    const double vv = geo::norm2(v);
    Cpa c;
    if (!(vv > 1e-12)) {
        c.distance_m = std::sqrt(geo::norm2(r));
        return c;
    }
    c.time_s = -geo::dot(r, v) / vv;
    c.distance_m = std::sqrt(geo::norm2(r + c.time_s * v));
    return c;
}

std::vector<ColregEncounter> find_situations(const std::vector<const track::Track*>& tracks, const geo::LocalFrame& frame,
                                             const ColregOptions& o, double max_gap_s,
                                             const std::function<bool(std::size_t, std::size_t)>& wanted) {
    std::vector<ColregEncounter> out;
    for_each_situation(tracks, frame, o, max_gap_s, wanted, [&](ColregEncounter& e) { out.push_back(e); });
    return out;
}

void for_each_situation(const std::vector<const track::Track*>& tracks, const geo::LocalFrame& frame, const ColregOptions& o,
                        double max_gap_s, const std::function<bool(std::size_t, std::size_t)>& wanted,
                        const std::function<void(ColregEncounter&)>& found) {
    if (!(o.range_m > 0) || !std::isfinite(o.range_m)) throw UsageError("ColregOptions::range_m must be > 0 metres");
    if (!(o.head_on_tolerance_deg >= 0 && o.head_on_tolerance_deg < 22.5))
        throw UsageError("ColregOptions::head_on_tolerance_deg must be in [0, 22.5) degrees");
    if (!(o.course_change_deg > 0 && o.course_change_deg <= 180)) throw UsageError("ColregOptions::course_change_deg must be in (0, 180] degrees");
    if (!(o.speed_change > 0) || !std::isfinite(o.speed_change)) throw UsageError("ColregOptions::speed_change must be > 0");
    if (!(o.sustain_s >= 0) || !std::isfinite(o.sustain_s)) throw UsageError("ColregOptions::sustain_s must be >= 0 seconds");
    std::vector<Local> ships;
    ships.reserve(tracks.size());
    for (const track::Track* t : tracks) {
        if (!t) throw UsageError("find_situations: null track");
        ships.push_back(prepare(*t, frame, max_gap_s));
    }
    const double R = o.range_m, R2 = R * R;
    std::vector<double> times;
    for (std::size_t ia = 0; ia < ships.size(); ++ia) {
        for (std::size_t ib = ia + 1; ib < ships.size(); ++ib) {
            const Local& A = ships[ia];
            const Local& B = ships[ib];
            if (A.size() < 2 || B.size() < 2) continue;
            const XY a0 = A.track.lo(), a1 = A.track.hi(), b0 = B.track.lo(), b1 = B.track.hi();
            if (a0.x - b1.x > R || b0.x - a1.x > R || a0.y - b1.y > R || b0.y - a1.y > R) continue;
            const double lo = std::max(A.t(0), B.t(0)), hi = std::min(A.t(A.size() - 1), B.t(B.size() - 1));
            if (!(lo < hi)) continue;
            if (wanted && !wanted(ia, ib)) continue;
            times.clear();
            times.push_back(lo);
            for (const Local* s : {&A, &B})
                for (std::size_t j = 0; j < s->size(); ++j)
                    if (s->t(j) > lo && s->t(j) < hi) times.push_back(s->t(j));
            times.push_back(hi);
            std::sort(times.begin(), times.end());
            times.erase(std::unique(times.begin(), times.end()), times.end());

            bool started = false, ended = false;
            ColregEncounter e;
            e.a = ia;
            e.b = ib;
            double best = std::numeric_limits<double>::infinity();
            double last_present = lo;
            for (std::size_t k = 0; k + 1 < times.size(); ++k) {
                const double u0 = times[k], u1 = times[k + 1];
                const double mid = 0.5 * (u0 + u1);
                const std::size_t i = A.track.interval(mid), j = B.track.interval(mid);
                if (!A.track.sailed(i) || !B.track.sailed(j)) {
                    if (started && !ended) {
                        ended = true;
                        e.end_s = u0;
                    }
                    continue;
                }
                last_present = u1;
                const double dt = u1 - u0;
                const XY r0 = B.at(j, u0) - A.at(i, u0);
                const XY w = B.velocity[j] - A.velocity[i];
                const double ww = geo::norm2(w), rw = geo::dot(r0, w), rr = geo::norm2(r0);
                // Closest approach in the interval.
                const double tau = ww > 0 ? std::clamp(-rw / ww, 0.0, dt) : 0.0;
                const double d = std::sqrt(geo::norm2(r0 + tau * w));
                if (d < best) {
                    best = d;
                    e.closest_m = d;
                    e.closest_s = u0 + tau;
                    e.a_closest = frame.inverse(A.at(i, u0 + tau));
                    e.b_closest = frame.inverse(B.at(j, u0 + tau));
                }
                // Entry into and exit from the range circle: |r0 + w s| = R.
                const double disc = rw * rw - ww * (rr - R2);
                double from = 0;
                if (!started) {
                    double enter = NAN;
                    if (rr <= R2) {
                        enter = 0;
                    } else if (ww > 0 && disc >= 0) {
                        const double s1 = (-rw - std::sqrt(disc)) / ww;
                        if (s1 >= 0 && s1 <= dt) enter = s1;
                    }
                    if (std::isnan(enter)) continue;
                    started = true;
                    from = enter;
                    e.start_s = u0 + enter;
                    e.a_start = A.state(i, e.start_s);
                    e.b_start = B.state(j, e.start_s);
                }
                if (started && !ended && ww > 0 && disc >= 0) {
                    const double s2 = (-rw + std::sqrt(disc)) / ww;
                    if (s2 >= from && s2 < dt) {
                        ended = true;
                        e.end_s = u0 + s2;
                    }
                }
            }
            if (!started) continue;
            if (!ended) e.end_s = last_present;
            e.at_start = classify(e.a_start, e.b_start, o.head_on_tolerance_deg);
            const double slow_ms = o.under_way_kn * 1852.0 / 3600.0;
            e.a_stopped = geo::norm2(e.a_start.velocity) < slow_ms * slow_ms;
            e.b_stopped = geo::norm2(e.b_start.velocity) < slow_ms * slow_ms;
            if (e.a_stopped || e.b_stopped) e.at_start.give_way = e.at_start.stand_on = Party::neither;
            e.cpa_start = cpa(e.a_start, e.b_start);
            e.action_a = action(A, e.start_s, e.end_s, e.a_start, o);
            e.action_b = action(B, e.start_s, e.end_s, e.b_start, o);
            found(e);
        }
    }
}

}  // namespace shoal::audit
