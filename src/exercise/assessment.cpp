// Scored criteria: a run's trainees scored against an assessment (see include/shoal/exercise/assessment.hpp; the file is read by assessment_file.cpp).
#include <shoal/exercise/assessment.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <tuple>

#include <shoal/geo/local_frame.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/track/time.hpp>
#include <shoal/track/track.hpp>
#include <shoal/util/error.hpp>

#include "geo/geos_context.hpp"
#include "sweep/local_track.hpp"

namespace shoal::audit {

using geo::LonLat;
using geo::XY;

double Assessment::watch_clearance_m() const noexcept {
    double w = 0;
    for (const Criterion& c : criteria)
        if (c.kind == CriterionKind::land_clearance) w = std::max(w, c.limit);
    return w;
}

namespace {

/// One interval over a limit: [start, end], its worst moment and value.
struct Run {
    double start = 0, end = 0, worst_t = 0, worst_v = NAN;
    XY at;  ///< local position of the trainee at the worst moment
};

/// A value along a track: `joined` when the change from the point before is linear in time.
struct ValuePoint {
    double t = 0, v = NAN;
    XY at;
    bool joined = false;
};

/// The runs of `pts` where v is over `limit` (`above`: v > limit; else v < limit), each
/// crossing interpolated linearly between joined points.
std::vector<Run> runs_over(const std::vector<ValuePoint>& pts, double limit, bool above) {
    const auto bad = [&](double v) { return above ? v > limit : v < limit; };
    const auto cross = [&](const ValuePoint& a, const ValuePoint& b) {
        if (!std::isfinite(a.v) || !std::isfinite(b.v) || a.v == b.v) return bad(a.v) ? a.t : b.t;
        const double f = std::clamp((limit - a.v) / (b.v - a.v), 0.0, 1.0);
        return a.t + f * (b.t - a.t);
    };
    std::vector<Run> out;
    std::optional<Run> cur;
    for (std::size_t k = 0; k < pts.size(); ++k) {
        const ValuePoint& p = pts[k];
        const ValuePoint* prev = k > 0 && p.joined ? &pts[k - 1] : nullptr;
        if (cur && !p.joined) {
            out.push_back(*cur);
            cur.reset();
        }
        if (bad(p.v)) {
            if (!cur) {
                cur = Run{prev ? cross(*prev, p) : p.t, p.t, p.t, p.v, p.at};
            } else if (above ? p.v > cur->worst_v : p.v < cur->worst_v) {
                cur->worst_t = p.t;
                cur->worst_v = p.v;
                cur->at = p.at;
            }
            cur->end = p.t;
        } else if (cur) {
            cur->end = prev ? cross(*prev, p) : cur->end;
            out.push_back(*cur);
            cur.reset();
        }
    }
    if (cur) out.push_back(*cur);
    return out;
}

/// A track for the criteria: the local track, broken at gaps over max_gap_s (not at jumps),
/// with its fixes' speeds; a moment is placed on the fix at or before it (LocalTrack::at).
struct Sailing {
    LocalTrack track;
    std::vector<double> speed_kn;  ///< per fix: track::Fix::speed_used_kn

    Sailing(const track::Track& t, const geo::LocalFrame& frame, double max_gap_s) : track(t, frame, Breaks{.max_gap_s = max_gap_s}, Placing::positions) {
        for (const track::Fix& f : t.fixes) speed_kn.push_back(f.speed_used_kn);
    }
    std::size_t size() const { return track.size(); }
    double t(std::size_t k) const { return track.time(k); }
    XY p(std::size_t k) const { return track.position(k); }
    /// Segment k to k + 1 is sailed (no gap).
    bool sailed(std::size_t k) const { return track.sailed(k); }
    /// Fix k starts a new piece (the first fix, or a gap before it).
    bool gap_before(std::size_t k) const { return k == 0 || !track.sailed(k - 1); }
    XY position(double time) const { return track.position(track.at(time)); }
    double speed(double time) const { return track.interpolate(speed_kn, track.at(time)); }
};

/// The times a track spends inside a polygon (local metres), by GEOS: each sailed segment
/// intersected with it, the parts' ends mapped back to times; parts that meet are joined.
std::vector<std::pair<double, double>> inside_intervals(const Sailing& lt, const geo::GeosContext& ctx, const GEOSGeometry* area,
                                                        const GEOSPreparedGeometry* prepared) {
    std::vector<std::pair<double, double>> out;
    const auto add = [&](double a, double b) {
        if (!out.empty() && std::fabs(out.back().second - a) <= 1e-9) out.back().second = std::max(out.back().second, b);
        else out.emplace_back(a, b);
    };
    const auto point_inside = [&](XY q) {
        const geo::GeomPtr pt = geo::own(ctx, GEOSGeom_createPointFromXY_r(ctx, q.x, q.y), "making a point");
        return GEOSPreparedIntersects_r(ctx, prepared, pt.get()) == 1;
    };
    for (std::size_t k = 0; k < lt.size(); ++k) {
        if (!lt.sailed(k)) {
            // A lone fix (a piece of one fix, or the last of a piece): inside or not, no duration.
            if (lt.gap_before(k) && point_inside(lt.p(k))) add(lt.t(k), lt.t(k));
            continue;
        }
        const XY a = lt.p(k), b = lt.p(k + 1);
        const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
        if (len2 == 0) {
            if (point_inside(a)) add(lt.t(k), lt.t(k + 1));
            continue;
        }
        const XY seg[2] = {a, b};
        const geo::GeomPtr line = geo::make_linestring(ctx, seg, 2);
        if (GEOSPreparedIntersects_r(ctx, prepared, line.get()) != 1) continue;
        const geo::GeomPtr part = geo::own(ctx, GEOSIntersection_r(ctx, line.get(), area), "intersecting a track segment with an area");
        std::vector<std::vector<XY>> lines;
        geo::collect_lines(ctx, part.get(), lines);
        std::vector<std::pair<double, double>> fr;
        for (const auto& l : lines) {
            if (l.size() < 2) continue;
            double f0 = INFINITY, f1 = -INFINITY;
            for (const XY& q : l) {
                const double f = std::clamp(((q.x - a.x) * dx + (q.y - a.y) * dy) / len2, 0.0, 1.0);
                f0 = std::min(f0, f);
                f1 = std::max(f1, f);
            }
            fr.emplace_back(f0, f1);
        }
        std::sort(fr.begin(), fr.end());
        const double dt = lt.t(k + 1) - lt.t(k);
        for (const auto& [f0, f1] : fr) add(f0 <= 1e-12 ? lt.t(k) : lt.t(k) + f0 * dt, f1 >= 1 - 1e-12 ? lt.t(k + 1) : lt.t(k) + f1 * dt);
    }
    return out;
}

/// The least charted depth of the grid's depth areas and dangers that hold p (metres): 0 on
/// land, NaN for an area of unknown depth, INFINITY where none does.
double charted_depth_at(const grid::CoastGrid& grid, XY p) {
    if (grid.for_depth(std::nullopt).is_land(p)) return 0.0;
    for (const double d : grid.charted_depths()) {
        const double limit = std::isnan(d) ? std::numeric_limits<double>::lowest() : std::nextafter(d, INFINITY);
        if (grid.for_depth(limit).is_land(p)) return d;
    }
    return INFINITY;
}

/// "10:03:30Z".
std::string clock(double t) { return track::format_iso8601(t, 0).substr(11); }

std::string number(double v, int decimals) {
    if (!std::isfinite(v)) return "unknown";
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return b;
}

class Assessor {
public:
    Assessor(const Assessment& a, const AssessInput& in) : m_a(a), m_in(in) {}

    AssessmentResult run() {
        const std::vector<TrackResult>& swept = m_in.swept;
        m_out.criteria = m_a.criteria;
        m_out.pass_mark = m_a.pass_mark;
        m_out.source = m_a.source;
        for (const Criterion& c : m_a.criteria)
            if (c.kind == CriterionKind::under_keel_clearance && m_in.grid.charted_depths().empty())
                m_out.warnings.push_back("assessment: the grid holds no depth areas or dangers, so " + c.id +
                                         " (under-keel clearance) is breached only where a ship's reference point lies on land");
        for (std::size_t k = 0; k < swept.size(); ++k) {
            const TrackSummary& s = swept[k].summary;
            if (s.role != Role::trainee) continue;
            const track::Track* t = k < m_in.tracks.size() ? m_in.tracks[k] : nullptr;
            const Sailing* lt = t && !t->fixes.empty() ? &local(k) : nullptr;
            for (std::size_t c = 0; c < m_a.criteria.size(); ++c) {
                const Criterion& cr = m_a.criteria[c];
                m_crit = c;
                switch (cr.kind) {
                    case CriterionKind::land_clearance: land_clearance(k, cr); break;
                    case CriterionKind::under_keel_clearance:
                        if (lt) under_keel(k, cr, *lt);
                        break;
                    case CriterionKind::cpa:
                        if (lt) cpa(k, cr, *lt);
                        break;
                    case CriterionKind::speed_limit:
                    case CriterionKind::no_entry:
                        if (lt) in_area(k, cr, *lt);
                        break;
                    case CriterionKind::close_quarters_time: close_quarters(k, cr); break;
                    case CriterionKind::colreg:
                        if (t) colreg(k, cr, *t);
                        break;
                }
            }
            std::stable_sort(m_track.begin(), m_track.end(), [](const Pending& x, const Pending& y) {
                return std::tie(x.breach.start_s, x.criterion, x.other) < std::tie(y.breach.start_s, y.criterion, y.other);
            });
            Score score;
            score.exercise = s.exercise;
            score.track = s.id;
            score.breaches = m_track.size();
            score.track_index = k;
            score.by_criterion.assign(m_a.criteria.size(), 0.0);
            for (Pending& b : m_track) {
                score.penalty += b.breach.penalty;
                score.by_criterion[b.criterion] += b.breach.penalty;
                if (b.listed) m_out.breaches.push_back(std::move(b.breach));
                else ++m_unlisted;
            }
            m_track.clear();
            // At most the pass mark, within the rounding of the sum (0.1 + 0.2 is 0.30000000000000004:
            // a trainee charged 0.1 and 0.2 against a pass mark of 0.3 failed): n terms round by at
            // most n ulps of their total. False without a pass mark (NaN).
            const double rounding = 4.0 * static_cast<double>(score.breaches + 1) * std::numeric_limits<double>::epsilon() *
                                    std::max(score.penalty, m_a.pass_mark);
            score.passed = score.penalty <= m_a.pass_mark + rounding;
            m_out.scores.push_back(score);
        }
        if (m_unlisted > 0)
            m_out.warnings.push_back("assessment: " + std::to_string(m_unlisted) + " CPA breaches not listed, each trainee's listed against the " +
                                     std::to_string(m_in.max_others_per_trainee) +
                                     " ships it came closest to (AuditOptions::max_encounters_per_ship); the scores count every one");
        return std::move(m_out);
    }

private:
    const TrackSummary& summary(std::size_t k) const { return m_in.swept[k].summary; }

    /// Track k in local metres (projected once).
    const Sailing& local(std::size_t k) {
        if (m_local.size() < m_in.swept.size()) m_local.resize(m_in.swept.size());
        if (!m_local[k]) m_local[k].emplace(*m_in.tracks[k], m_in.frame, m_in.max_gap_s);
        return *m_local[k];
    }

    /// A breach of criterion cr by track k: whose it is and of what; the caller says when, where and how much.
    Breach breach_of(std::size_t k, const Criterion& cr) {
        Breach b;
        const TrackSummary& s = summary(k);
        b.exercise = s.exercise;
        b.track = s.id;
        b.track_index = k;
        b.criterion = cr.id;
        b.kind = cr.kind;
        return b;
    }

    void add(std::size_t k, const Criterion& cr, const Run& run, double value, std::size_t other = SIZE_MAX) {
        Breach b = breach_of(k, cr);
        b.start_s = run.start;
        b.end_s = run.end;
        b.worst_s = run.worst_t;
        const LonLat at = m_in.frame.inverse(run.at);
        b.lon = at.lon;
        b.lat = at.lat;
        b.value = value;
        b.limit = cr.limit;
        if (other != SIZE_MAX) b.other = summary(other).id;
        const double duration = b.end_s - b.start_s;
        switch (cr.per) {
            case PenaltyPer::breach: b.penalty = cr.penalty; break;
            case PenaltyPer::second:
                b.penalty = cr.penalty * (cr.kind == CriterionKind::close_quarters_time ? value - cr.limit : duration);
                break;
            case PenaltyPer::metre: {
                // How far beyond the limit the worst moment was; a depth not known counts as no clearance left.
                const double beyond = cr.kind == CriterionKind::speed_limit ? value - cr.limit : cr.limit - (std::isfinite(value) ? value : 0.0);
                b.penalty = cr.penalty * std::max(0.0, beyond);
                break;
            }
        }
        const int dec = cr.kind == CriterionKind::speed_limit || cr.kind == CriterionKind::under_keel_clearance ? 2 : 1;
        std::string what;
        switch (cr.kind) {
            case CriterionKind::land_clearance: what = "clearance to land " + number(value, dec) + " m, under " + number(cr.limit, dec) + " m"; break;
            case CriterionKind::under_keel_clearance:
                what = "under-keel clearance " + number(value, dec) + " m, under " + number(cr.limit, dec) + " m";
                break;
            case CriterionKind::cpa: what = "CPA to " + b.other + " " + number(value, dec) + " m, under " + number(cr.limit, dec) + " m"; break;
            case CriterionKind::speed_limit:
                what = "speed " + number(value, dec) + " kn over the limit of " + number(cr.limit, dec) + " kn" +
                       (cr.area_name.empty() ? std::string() : " in " + cr.area_name);
                break;
            case CriterionKind::no_entry: what = "inside " + (cr.area_name.empty() ? std::string("a no-entry area") : cr.area_name); break;
            case CriterionKind::close_quarters_time:
                what = "close quarters with " + b.other + " for " + number(value, 0) + " s, over " + number(cr.limit, 0) + " s";
                break;
            case CriterionKind::colreg: break;  // colreg() words its own
        }
        const std::string area = cr.area_name.empty() ? std::string("the area") : cr.area_name;
        switch (cr.kind) {
            case CriterionKind::land_clearance: b.asked = "a clearance to land or hazards of at least " + number(cr.limit, dec) + " m"; break;
            case CriterionKind::under_keel_clearance: b.asked = "an under-keel clearance of at least " + number(cr.limit, dec) + " m"; break;
            case CriterionKind::cpa: b.asked = "a closest approach to every other ship of at least " + number(cr.limit, dec) + " m"; break;
            case CriterionKind::speed_limit: b.asked = "at most " + number(cr.limit, dec) + " kn in " + area; break;
            case CriterionKind::no_entry: b.asked = "no entry into " + area; break;
            case CriterionKind::close_quarters_time: b.asked = "at most " + number(cr.limit, 0) + " s in close quarters with another ship"; break;
            case CriterionKind::colreg: break;
        }
        b.did = what + ", " + clock(b.start_s) + "-" + clock(b.end_s) + " (" + number(duration, 0) + " s)";
        b.detail = cr.id + ": " + what + ", " + clock(b.start_s) + "-" + clock(b.end_s) + " (" + number(duration, 0) + " s); penalty " +
                   number(b.penalty, 2);
        m_track.push_back({std::move(b), m_crit, other, true});
    }

    void land_clearance(std::size_t k, const Criterion& cr) {
        const auto& samples = m_in.swept[k].clearance;
        // A contact the audit does not call a grounding (alongside a quay, in contact from the
        // first fix, in a berth or harbour area) is no breach of clearance: its samples are
        // left out, and the samples on either side of it are not joined across it.
        const auto& events = m_in.swept[k].events;
        const auto excused = [&](double t) {
            return std::any_of(events.begin(), events.end(), [t](const Event& e) {
                return (e.kind == EventKind::alongside || e.kind == EventKind::contact_at_start ||
                        e.kind == EventKind::expected_contact) &&
                       t >= e.start_s && t <= e.end_s;
            });
        };
        std::vector<ValuePoint> pts;
        bool broken = false;
        for (const ClearanceSample& c : samples) {
            if (excused(c.time_s)) {
                broken = true;
                continue;
            }
            pts.push_back({c.time_s, c.covered ? c.clearance_m : INFINITY, m_in.frame.forward(c.ship), !c.after_break && !broken});
            broken = false;
        }
        for (const Run& run : runs_over(pts, cr.limit, false)) add(k, cr, run, run.worst_v);
    }

    void under_keel(std::size_t k, const Criterion& cr, const Sailing& lt) {
        const TrackSummary& sum = summary(k);
        const double draught = std::isfinite(sum.draught_m) && sum.draught_m > 0 ? sum.draught_m : m_in.default_draught_m;
        if (!(draught > 0)) {
            m_out.warnings.push_back("assessment: track '" + sum.id + "' has no draught (its own or the ship file's): " + cr.id + " not assessed for it");
            return;
        }
        const grid::CoastGrid& hazards = m_in.grid.for_depth(draught + cr.limit);
        const double step = std::max(m_in.step_m, 0.01);
        struct S {
            double t = 0;
            XY p;
            bool in = false;
        };
        std::optional<Run> cur;
        double worst_depth = INFINITY;
        bool worst_known = false;
        // The worst moment: the least known depth (an area of unknown depth only when no depth is known).
        const auto note_worst = [&](const S& s) {
            const double d = charted_depth_at(m_in.grid, s.p);
            if (!worst_known || (std::isnan(worst_depth) && !std::isnan(d)) || (!std::isnan(d) && d < worst_depth)) {
                worst_depth = d;
                cur->worst_t = s.t;
                cur->at = s.p;
                worst_known = true;
            }
        };
        const auto close = [&]() {
            add(k, cr, *cur, worst_depth - draught);
            cur.reset();
        };
        // The moment between a sample outside and one inside (same segment), bisected.
        const auto boundary = [&](const S& out, const S& in) {
            double lo = out.t, hi = in.t;
            for (int it = 0; it < 60 && hi - lo > m_in.time_tolerance_s; ++it) {
                const double mid = 0.5 * (lo + hi);
                (hazards.is_land(lt.position(mid)) ? hi : lo) = mid;
            }
            return hi;
        };
        S prev;
        bool have_prev = false;  // prev is the sample before, in this piece
        for (std::size_t i = 0; i < lt.size(); ++i) {
            if (lt.gap_before(i)) {
                if (cur) close();
                have_prev = false;
            }
            std::vector<S> here;
            here.push_back({lt.t(i), lt.p(i), hazards.is_land(lt.p(i))});
            if (lt.sailed(i)) {
                const double len = std::hypot(lt.p(i + 1).x - lt.p(i).x, lt.p(i + 1).y - lt.p(i).y);
                const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(len / step)));
                for (std::size_t j = 1; j < n; ++j) {
                    const double t = lt.t(i) + (lt.t(i + 1) - lt.t(i)) * static_cast<double>(j) / static_cast<double>(n);
                    const XY p = lt.position(t);
                    here.push_back({t, p, hazards.is_land(p)});
                }
            }
            for (const S& s : here) {
                if (s.in) {
                    if (!cur) {
                        cur = Run{have_prev && !prev.in ? boundary(prev, s) : s.t, s.t, s.t, NAN, s.p};
                        worst_known = false;
                        worst_depth = INFINITY;
                    }
                    cur->end = s.t;
                    note_worst(s);
                } else if (cur) {
                    if (have_prev && prev.in) {
                        // The last moment inside: bisected from the inside.
                        double lo = prev.t, hi = s.t;
                        for (int it = 0; it < 60 && hi - lo > m_in.time_tolerance_s; ++it) {
                            const double mid = 0.5 * (lo + hi);
                            (hazards.is_land(lt.position(mid)) ? lo : hi) = mid;
                        }
                        cur->end = lo;
                    }
                    close();
                }
                prev = s;
                have_prev = true;
            }
        }
        if (cur) close();
    }

    void cpa(std::size_t k, const Criterion& cr, const Sailing& a) {
        // The breaches against each other ship (its closest approach among them, the ship, where
        // they start in m_track): listed for the max_others_per_trainee ships it came closest to.
        std::vector<std::tuple<double, std::size_t, std::size_t, std::size_t>> by_other;
        cpa_each(k, cr, a, by_other);
        const std::size_t cap = m_in.max_others_per_trainee;
        if (cap == 0 || by_other.size() <= cap) return;
        std::sort(by_other.begin(), by_other.end());
        for (std::size_t i = cap; i < by_other.size(); ++i)
            for (std::size_t j = std::get<2>(by_other[i]); j < std::get<3>(by_other[i]); ++j) m_track[j].listed = false;
    }

    void cpa_each(std::size_t k, const Criterion& cr, const Sailing& a, std::vector<std::tuple<double, std::size_t, std::size_t, std::size_t>>& by_other) {
        const std::vector<TrackResult>& swept = m_in.swept;
        const double L = cr.limit;
        for (std::size_t m = 0; m < swept.size(); ++m) {
            const std::size_t from = m_track.size();
            const auto note = [&] {
                double closest = INFINITY;
                for (std::size_t j = from; j < m_track.size(); ++j) closest = std::min(closest, m_track[j].breach.value);
                if (m_track.size() > from) by_other.emplace_back(closest, m, from, m_track.size());
            };
            if (m == k || swept[m].summary.exercise != summary(k).exercise) continue;
            const track::Track* tb = m < m_in.tracks.size() ? m_in.tracks[m] : nullptr;
            if (!tb || tb->fixes.empty()) continue;
            // Never at the same time, or never within the limit of each other's box: no breach.
            const double t0 = std::max(a.t(0), tb->fixes.front().time_s), t1 = std::min(a.t(a.size() - 1), tb->fixes.back().time_s);
            if (!(t0 <= t1)) continue;
            const Sailing& b = local(m);
            const XY alo = a.track.lo(), ahi = a.track.hi(), blo = b.track.lo(), bhi = b.track.hi();
            if (std::max({blo.x - ahi.x, alo.x - bhi.x, blo.y - ahi.y, alo.y - bhi.y}) >= L) continue;
            std::vector<double> cuts{t0, t1};
            for (const Sailing* sp : {&a, &b})
                for (std::size_t j = 0; j < sp->size(); ++j)
                    if (const double t = sp->t(j); t > t0 && t < t1) cuts.push_back(t);
            std::sort(cuts.begin(), cuts.end());
            cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
            std::optional<Run> cur;
            const auto flush = [&]() {
                if (cur) add(k, cr, *cur, cur->worst_v, m);
                cur.reset();
            };
            const auto consider = [&](double ta, double tb2) {
                // Relative position r(s) = r0 + w s, s in [0, 1]: where |r| < L, and its least.
                const XY pa0 = a.position(ta), pa1 = a.position(tb2), pb0 = b.position(ta), pb1 = b.position(tb2);
                const XY r0{pb0.x - pa0.x, pb0.y - pa0.y}, r1{pb1.x - pa1.x, pb1.y - pa1.y};
                const XY w{r1.x - r0.x, r1.y - r0.y};
                const double A = w.x * w.x + w.y * w.y, B = 2 * (r0.x * w.x + r0.y * w.y), C = r0.x * r0.x + r0.y * r0.y - L * L;
                double s0 = 1, s1 = 0;  // empty
                if (A == 0) {
                    if (C < 0) s0 = 0, s1 = 1;
                } else {
                    const double disc = B * B - 4 * A * C;
                    if (disc > 0) {
                        const double q = std::sqrt(disc);
                        s0 = std::max(0.0, (-B - q) / (2 * A));
                        s1 = std::min(1.0, (-B + q) / (2 * A));
                    }
                }
                if (!(s0 < s1) && !(s0 == s1 && C < 0)) {
                    flush();
                    return;
                }
                const double smin = A == 0 ? 0.0 : std::clamp(-B / (2 * A), s0, s1);
                const double dmin = std::sqrt(std::max(0.0, (r0.x + w.x * smin) * (r0.x + w.x * smin) + (r0.y + w.y * smin) * (r0.y + w.y * smin)));
                const double dt = tb2 - ta;
                const double start = s0 <= 0 ? ta : ta + s0 * dt, end = s1 >= 1 ? tb2 : ta + s1 * dt, tmin = ta + smin * dt;
                if (cur && std::fabs(cur->end - start) > 1e-9) flush();
                if (!cur) cur = Run{start, end, tmin, dmin, a.position(tmin)};
                cur->end = end;
                if (dmin < cur->worst_v) {
                    cur->worst_v = dmin;
                    cur->worst_t = tmin;
                    cur->at = a.position(tmin);
                }
                if (s1 < 1) flush();
            };
            for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
                const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
                if (!a.track.present(mid) || !b.track.present(mid)) {
                    flush();
                    continue;
                }
                consider(cuts[i], cuts[i + 1]);
            }
            if (cuts.size() == 1 && a.track.present(t0) && b.track.present(t0)) consider(t0, t0);
            flush();
            note();
        }
    }

    void in_area(std::size_t k, const Criterion& cr, const Sailing& lt) {
        const geo::GeosContext ctx;
        std::vector<XY> ring;
        for (const LonLat& p : cr.area) ring.push_back(m_in.frame.forward(p));
        const bool finite = std::all_of(ring.begin(), ring.end(), [](const XY& q) { return std::isfinite(q.x) && std::isfinite(q.y); });
        const geo::GeomPtr area = finite ? geo::make_polygon(ctx, {ring}) : nullptr;
        // An area spanning much of the globe does not survive the run's local frame (points on
        // its far side fold back): said, never a silent "no breach".
        if (!area || GEOSisValid_r(ctx, area.get()) != 1)
            throw InputError("assessment: the area of " + cr.id + (cr.area_name.empty() ? "" : " (" + cr.area_name + ")") +
                             " is too large for the run's local frame (its outline, projected, is not a simple polygon): "
                             "draw it around the waters of the exercise");
        const geo::PreparedPtr prepared(GEOSPrepare_r(ctx, area.get()), geo::PreparedDeleter{ctx});
        if (!prepared) throw LibraryError("preparing the area of " + cr.id + ": " + ctx.last_message());
        for (const auto& [t0, t1] : inside_intervals(lt, ctx, area.get(), prepared.get())) {
            if (cr.kind == CriterionKind::no_entry) {
                add(k, cr, Run{t0, t1, t0, t1 - t0, lt.position(t0)}, t1 - t0);
                continue;
            }
            std::vector<ValuePoint> pts;
            pts.push_back({t0, lt.speed(t0), lt.position(t0), false});
            for (std::size_t i = 0; i < lt.size(); ++i)
                if (lt.t(i) > t0 && lt.t(i) < t1) pts.push_back({lt.t(i), lt.speed_kn[i], lt.p(i), true});
            if (t1 > t0) pts.push_back({t1, lt.speed(t1), lt.position(t1), true});
            for (const Run& run : runs_over(pts, cr.limit, true)) add(k, cr, run, run.worst_v);
        }
    }

    /// The trainee's conduct under the rules in each situation with another ship of its exercise.
    void colreg(std::size_t k, const Criterion& cr, const track::Track& own) {
        const std::vector<TrackResult>& swept = m_in.swept;
        std::vector<const track::Track*> others;
        std::vector<std::size_t> index;
        for (std::size_t m = 0; m < swept.size(); ++m) {
            if (m == k || swept[m].summary.exercise != summary(k).exercise) continue;
            const track::Track* t = m < m_in.tracks.size() ? m_in.tracks[m] : nullptr;
            if (!t || t->fixes.size() < 2) continue;
            others.push_back(t);
            index.push_back(m);
        }
        if (others.empty()) return;
        std::vector<ConductRecord> records;
        for (const Conduct& c : judge_conduct(own, others, m_in.frame, cr.colreg, m_in.max_gap_s)) {
            ConductRecord& rec = records.emplace_back();
            rec.exercise = summary(k).exercise;
            rec.track = summary(k).id;
            rec.criterion = cr.id;
            rec.track_index = k;
            rec.other = summary(index[c.other]).id;
            rec.other_index = index[c.other];
            rec.situation = to_string(c.situation.at_start.situation);
            rec.role = c.role;
            rec.start_s = c.situation.start_s;
            rec.closest_m = c.situation.closest_m;
            rec.rules = c.rules;
            rec.did = c.did;
            for (const ConductBreach& cb : c.breaches) rec.breached.push_back(cb.rule);
            for (const ConductBreach& cb : c.breaches) {
                Breach b = breach_of(k, cr);
                b.start_s = c.situation.start_s;
                b.end_s = std::max(c.situation.start_s, cb.time_s);
                b.worst_s = cb.time_s;
                b.lon = cb.at.lon;
                b.lat = cb.at.lat;
                b.value = c.situation.closest_m;
                b.limit = cr.colreg.cpa_m;
                b.penalty = cr.penalty;
                b.other = summary(index[c.other]).id;
                b.rule = cb.rule;
                b.asked = cb.asked;
                b.did = cb.did;
                b.detail = cr.id + ": rule " + cb.rule + ", " + to_string(c.situation.at_start.situation) + " with " + b.other + " (" + c.role +
                           "), " + clock(cb.time_s) + ": " + cb.asked + "; " + cb.did + "; penalty " + number(b.penalty, 2);
                m_track.push_back({std::move(b), m_crit, index[c.other], true});
            }
        }
        std::stable_sort(records.begin(), records.end(), [](const ConductRecord& x, const ConductRecord& y) {
            return std::tie(x.start_s, x.other_index) < std::tie(y.start_s, y.other_index);
        });
        for (ConductRecord& rec : records) m_out.conduct.push_back(std::move(rec));
    }

    void close_quarters(std::size_t k, const Criterion& cr) {
        for (const Encounter& e : m_in.encounters.events) {
            if (e.kind != EncounterKind::close_quarters || (e.a.track != k && e.b.track != k)) continue;
            const double duration = e.end_s - e.start_s;
            if (!(duration > cr.limit)) continue;
            const ShipAt& me = e.a.track == k ? e.a : e.b;
            const ShipAt& other = e.a.track == k ? e.b : e.a;
            add(k, cr, Run{e.start_s, e.end_s, e.end_s, duration, m_in.frame.forward(me.position)}, duration, other.track);
        }
    }

    const Assessment& m_a;
    const AssessInput& m_in;
    AssessmentResult m_out;
    std::size_t m_crit = 0;  ///< the criterion being assessed (its index)
    /// The breaches of the track being assessed, with what orders them after the start.
    struct Pending {
        Breach breach;
        std::size_t criterion = 0, other = 0;
        bool listed = true;  ///< false: a cpa breach against a ship beyond the trainee's closest (AssessInput::max_others_per_trainee)
    };
    std::vector<Pending> m_track;
    std::size_t m_unlisted = 0;  ///< breaches scored but not listed
    std::vector<std::optional<Sailing>> m_local;  ///< by index in AuditResult::tracks
};

}  // namespace

AssessmentResult assess(const Assessment& assessment, const AssessInput& in) { return Assessor(assessment, in).run(); }

}  // namespace shoal::audit
