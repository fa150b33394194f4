// Ship-to-ship encounters (see include/shoal/exercise/encounters.hpp): each pair's events and
// closest approach over the instants it is checked, and the exercise put together from its
// parts: the ships (exercise_ship), the clock (exercise_clock), the broad phase, the narrow
// phase, the interval events, and the hull-to-hull contact (check/hull_contact).
#include <shoal/exercise/encounters.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include <shoal/util/error.hpp>
#include "exercise/broad_phase.hpp"
#include "exercise/exercise_clock.hpp"
#include "exercise/exercise_ship.hpp"
#include "sweep/interval_events.hpp"
#include "sweep/local_track.hpp"
#include "exercise/narrow_phase.hpp"

namespace shoal::audit {

using geo::XY;
using check::detail::Placed;
using detail::PairSample;

const char* to_string(EncounterKind k) noexcept { return k == EncounterKind::collision ? "collision" : "close_quarters"; }

namespace {

/// Verlet skin of the broad phase as a fraction of the largest threshold (and at least two
/// steps): candidates are pairs within threshold + skin at the last build, rebuilt when some
/// ship has moved half a skin.
constexpr double skin_fraction = 0.5;

struct PairState {
    std::uint32_t a = 0, b = 0;
    std::uint64_t last_instant = 0;
    bool checked = false, listed = false;
    detail::IntervalEvents<PairSample> intervals;  ///< collisions (contact) and close quarters (near)
    std::size_t collision_event = 0;  ///< index in the result's events of the open collision
    double best = INFINITY, best_t = 0;  ///< closest approach so far
    XY best_pos_a, best_pos_b;
    detail::PairMemo memo;
    bool open() const noexcept { return intervals.open(); }
};

enum class Method { fast, reference };

class Exercise {
public:
    Exercise(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
             const geo::LocalFrame& frame, const EncounterOptions& options, Method method)
        : m_frame(frame), m_opt(options), m_ships(tracks.size()) {
        validate(tracks, hulls);
        detail::PairThresholds thresholds;
        thresholds.automatic = !(m_opt.threshold_m > 0);
        thresholds.fixed_m = m_opt.threshold_m;
        thresholds.base_m = m_opt.ship_margin_m + m_opt.step_m;
        std::vector<detail::ExerciseClock::Ship> timing;
        for (std::size_t k = 0; k < tracks.size(); ++k) {
            detail::prepare_ship(m_ships[k], *tracks[k], hulls[k], m_frame, m_opt.max_gap_s);
            thresholds.radius.push_back(m_ships[k].shape.radius);
            timing.push_back({&*m_ships[k].local, &m_ships[k].speed});
        }
        m_pos.resize(m_ships.size());
        m_clock.emplace(std::move(timing), m_opt.step_m);
        m_result.threshold_m = thresholds.largest_m();
        const double skin = std::max(2 * m_opt.step_m, skin_fraction * m_result.threshold_m);
        if (method == Method::fast) {
            m_broad = detail::hash_grid(std::move(thresholds), skin);
            m_narrow = detail::bounded();
        } else {
            m_broad = detail::all_pairs(std::move(thresholds));
            m_narrow = detail::all_edges();
        }
    }

    EncounterResult run() {
        m_clock->run([this](double t) { instant(t); });
        close_open(true);
        return finish();
    }

private:
    void validate(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls) const {
        if (hulls.size() != tracks.size())
            throw UsageError("find_encounters: " + std::to_string(tracks.size()) + " tracks but " + std::to_string(hulls.size()) +
                             " hulls (one hull per track)");
        if (!(m_opt.step_m > 0) || !std::isfinite(m_opt.step_m)) throw UsageError("EncounterOptions::step_m must be > 0 metres");
        if (!(m_opt.ship_margin_m >= 0) || !std::isfinite(m_opt.ship_margin_m)) throw UsageError("EncounterOptions::ship_margin_m must be >= 0 metres");
        if (!(m_opt.threshold_m >= 0) || !std::isfinite(m_opt.threshold_m)) throw UsageError("the encounter threshold must be >= 0 metres (0 = automatic)");
        if (!(m_opt.max_gap_s > 0)) throw UsageError("EncounterOptions::max_gap_s must be > 0 seconds");
        if (!(m_opt.time_tolerance_s > 0)) throw UsageError("the time tolerance must be > 0 seconds");
        for (const track::Track* t : tracks) {
            if (!t) throw UsageError("find_encounters: null track");
            for (std::size_t i = 0; i < t->fixes.size(); ++i) {
                const track::Fix& f = t->fixes[i];
                auto fail = [&](const char* what) {
                    throw InputError("track '" + t->id + "' in '" + t->file + "', fix at line " + std::to_string(f.line) + ": " + what);
                };
                if (!std::isfinite(f.time_s)) fail("no time");
                if (!std::isfinite(f.heading_used_deg)) fail("no heading (headings not resolved)");
                if (i > 0 && !(f.time_s > t->fixes[i - 1].time_s)) fail("fix times not strictly increasing");
            }
        }
    }

    /// The pair at an arbitrary moment (both ships present there), for bisection: whether
    /// the hulls touch, and where. The fast way may answer "far" (not touching) early.
    PairSample sample_at(std::uint32_t a, std::uint32_t b, double t) {
        const detail::ExerciseShip& sa = m_ships[a];
        const detail::ExerciseShip& sb = m_ships[b];
        check::detail::place(sa.shape, sa.local->pose(sa.local->at(t)), m_scratch_a);
        check::detail::place(sb.shape, sb.local->pose(sb.local->at(t)), m_scratch_b);
        PairSample s;
        s.t = t;
        s.pos_a = m_scratch_a.position;
        s.pos_b = m_scratch_b.position;
        m_result.hull_checks += m_narrow->at(sa, m_scratch_a, sb, m_scratch_b, s);
        return s;
    }

    void instant(double t) {
        ++m_result.instants;
        m_instant = m_clock->instant();
        for (const std::uint32_t k : m_clock->present()) {
            detail::ExerciseShip& s = m_ships[k];
            s.at = m_clock->where(k);
            s.pos = m_pos[k] = s.local->position(s.at);
        }
        m_broad->near_pairs(m_clock->present(), m_pos, m_clock->joined(), m_index, m_near);
        while (m_states.size() < m_index.size()) {
            PairState& p = m_states.emplace_back();
            std::tie(p.a, p.b) = m_index.pair(static_cast<std::uint32_t>(m_states.size() - 1));
        }
        for (const std::uint32_t id : m_near) check(id, t);
        close_open(false);
    }

    /// The interval events' handler for one pair (interval_events.hpp): contacts are
    /// collisions, near intervals that never reach contact close quarters.
    struct PairEvents {
        Exercise& x;
        PairState& p;
        static double time(const PairSample& s) { return s.t; }
        static bool contact(const PairSample& s) { return s.touching(); }
        bool near(const PairSample& s) const { return s.touching() || (!s.far && s.contact.clearance_m < x.m_opt.ship_margin_m); }
        static double clearance(const PairSample& s) { return s.contact.clearance_m; }
        /// Between a moment without contact and one with, the moment of change, to the
        /// tolerance; the sample on the contact side.
        PairSample bisect(const PairSample& clear, const PairSample& hit, bool /*forward: either way in time*/) {
            PairSample found = hit;
            detail::bisect_change(clear.t, hit.t, 1.0, x.m_opt.time_tolerance_s, 60, [&](double mid) {
                PairSample m = x.sample_at(p.a, p.b, mid);
                if (!m.touching()) return false;
                found = m;
                return true;
            });
            return found;
        }
        void contact_opened(const PairSample& first, const PairSample& /*s*/, bool /*seen_clear*/) {
            p.collision_event = x.m_result.events.size();
            x.m_result.events.push_back(x.make_event(EncounterKind::collision, p, first.t, first.contact));
            x.offer(p, first);
        }
        void contact_continues(const PairSample&) {}
        void contact_closed(double /*start_s*/, double end_s) { x.m_result.events[p.collision_event].end_s = end_s; }
        void near_closed(double start_s, double end_s, const PairSample& nearest) {
            HullContact c;
            c.clearance_m = nearest.contact.clearance_m;
            c.on_a = c.on_b = 0.5 * (nearest.contact.on_a + nearest.contact.on_b);
            Encounter e = x.make_event(EncounterKind::close_quarters, p, nearest.t, c);
            e.start_s = start_s;
            e.end_s = end_s;
            e.min_clearance_m = c.clearance_m;
            x.m_result.events.push_back(std::move(e));
        }
    };

    /// One check of pair `index` at the current instant, time t: narrow phase and events.
    void check(std::uint32_t index, double t) {
        ++m_result.pairs_checked;
        PairState& p = m_states[index];
        detail::ExerciseShip& sa = m_ships[p.a];
        detail::ExerciseShip& sb = m_ships[p.b];
        PairEvents events{*this, p};
        detail::PairQuery q;
        q.instant = m_instant;
        q.contiguous = p.checked && p.last_instant + 1 == m_instant && m_clock->entered(p.a) < m_instant && m_clock->entered(p.b) < m_instant;
        if (!q.contiguous) p.intervals.end(events);
        q.touch_only = p.intervals.in_contact();
        q.margin_m = m_opt.ship_margin_m;
        q.best_m = p.best;

        PairSample s;
        s.t = t;
        s.pos_a = sa.pos;
        s.pos_b = sb.pos;
        m_result.hull_checks += m_narrow->now(sa, sb, p.memo, q, s);
        p.intervals.add(s, events);
        if (!s.far && !s.touching()) offer(p, s);

        p.last_instant = m_instant;
        p.checked = true;
        if (p.open() && !p.listed) {
            p.listed = true;
            m_open.push_back(index);
        }
    }

    void offer(PairState& p, const PairSample& s) {
        if (!(s.contact.clearance_m < p.best)) return;
        p.best = s.contact.clearance_m;
        p.best_t = s.t;
        p.best_pos_a = s.pos_a;
        p.best_pos_b = s.pos_b;
    }

    /// After an instant (or at the end): ends the intervals of pairs not checked at it (they
    /// end at their last check).
    void close_open(bool all) {
        std::size_t kept = 0;
        for (const std::uint32_t index : m_open) {
            PairState& p = m_states[index];
            if (p.open() && (all || p.last_instant != m_instant)) {
                PairEvents events{*this, p};
                p.intervals.end(events);
            }
            if (p.open()) {
                m_open[kept++] = index;
            } else {
                p.listed = false;
            }
        }
        m_open.resize(kept);
    }

    ShipAt ship_at(std::uint32_t k, double t, XY* position) const {
        const detail::ExerciseShip& s = m_ships[k];
        const Where w = s.local->at(t);
        const check::LocalPose pose = s.local->pose(w);
        ShipAt out;
        out.track = k;
        out.position = m_frame.inverse(pose.position);
        out.heading_deg = wrap_360(s.local->heading(w));
        out.fix_index = w.i;
        for (const XY& q : check::hull_outline(*s.hull, pose)) out.hull.push_back(m_frame.inverse(q));
        if (!out.hull.empty()) out.hull.push_back(out.hull.front());
        *position = pose.position;
        return out;
    }

    Encounter make_event(EncounterKind kind, const PairState& p, double t, const HullContact& c) const {
        Encounter e;
        e.kind = kind;
        e.start_s = e.end_s = t;
        e.min_clearance_m = kind == EncounterKind::collision ? 0 : c.clearance_m;
        e.point = m_frame.inverse(c.on_a);
        XY pa, pb;
        e.a = ship_at(p.a, t, &pa);
        e.b = ship_at(p.b, t, &pb);
        e.distance_m = geo::distance(pa, pb);
        return e;
    }

    EncounterResult finish() {
        for (const PairState& p : m_states) {
            if (!p.checked || !std::isfinite(p.best)) continue;
            ClosestApproach c;
            c.a = p.a;
            c.b = p.b;
            c.time_s = p.best_t;
            c.clearance_m = p.best;
            c.distance_m = geo::distance(p.best_pos_a, p.best_pos_b);
            c.a_position = m_frame.inverse(p.best_pos_a);
            c.b_position = m_frame.inverse(p.best_pos_b);
            m_result.approaches.push_back(c);
        }
        std::sort(m_result.approaches.begin(), m_result.approaches.end(), [](const ClosestApproach& x, const ClosestApproach& y) {
            return x.a < y.a || (x.a == y.a && x.b < y.b);
        });
        std::sort(m_result.events.begin(), m_result.events.end(), [](const Encounter& x, const Encounter& y) {
            if (x.start_s != y.start_s) return x.start_s < y.start_s;
            if (x.a.track != y.a.track) return x.a.track < y.a.track;
            if (x.b.track != y.b.track) return x.b.track < y.b.track;
            return x.kind < y.kind;
        });
        m_result.rebuilds = m_broad->rebuilds();
        return std::move(m_result);
    }

    const geo::LocalFrame& m_frame;
    EncounterOptions m_opt;
    std::vector<detail::ExerciseShip> m_ships;
    std::optional<detail::ExerciseClock> m_clock;
    std::unique_ptr<detail::BroadPhase> m_broad;
    std::unique_ptr<detail::NarrowPhase> m_narrow;
    EncounterResult m_result;

    std::uint64_t m_instant = 0;
    std::vector<XY> m_pos;  ///< per ship: reference point at the current instant (while present)
    detail::PairIndex m_index;
    std::vector<PairState> m_states;  ///< by pair id in m_index
    std::vector<std::uint32_t> m_near;  ///< pairs within the threshold at the current instant
    std::vector<std::uint32_t> m_open;  ///< pairs with open intervals
    Placed m_scratch_a, m_scratch_b;
};

EncounterResult run_exercise(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                             const geo::LocalFrame& frame, const EncounterOptions& options, Method method) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    Exercise exercise(tracks, hulls, frame, options, method);
    const auto ready = Clock::now();
    EncounterResult r = exercise.run();
    r.setup_s = std::chrono::duration<double>(ready - start).count();
    r.sweep_s = std::chrono::duration<double>(Clock::now() - ready).count();
    return r;
}

}  // namespace

EncounterResult find_encounters(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                                const geo::LocalFrame& frame, const EncounterOptions& options) {
    return run_exercise(tracks, hulls, frame, options, Method::fast);
}

EncounterResult find_encounters_brute(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                                      const geo::LocalFrame& frame, const EncounterOptions& options) {
    return run_exercise(tracks, hulls, frame, options, Method::reference);
}

}  // namespace shoal::audit
