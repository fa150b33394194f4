#include <shoal/sweep/sweep.hpp>

#include <algorithm>
#include <optional>
#include <numbers>

#include <Eigen/LU>

#include <shoal/coast/expected_areas.hpp>
#include <shoal/util/error.hpp>
#include "sweep/interval_events.hpp"
#include "sweep/local_track.hpp"
#include "sweep/pose_outline.hpp"
#include "util/parse_util.hpp"

namespace shoal::audit {

using geo::XY;

const char* to_string(EventKind k) noexcept {
    switch (k) {
        case EventKind::grounding: return "grounding";
        case EventKind::alongside: return "alongside";
        case EventKind::contact_at_start: return "in_contact_at_start";
        case EventKind::expected_contact: return "expected_contact";
        case EventKind::close_pass: return "close_pass";
        case EventKind::chart_disagrees: return "chart_disagrees";
    }
    return "grounding";
}

void count_contact(TrackSummary& sum, EventKind k) noexcept {
    switch (k) {
        case EventKind::grounding: ++sum.groundings; break;
        case EventKind::alongside: ++sum.alongside; break;
        case EventKind::contact_at_start: ++sum.contacts_at_start; break;
        case EventKind::expected_contact: ++sum.expected_contacts; break;
        case EventKind::chart_disagrees: ++sum.chart_disagreements; break;
        case EventKind::close_pass: break;
    }
}

hull::Hull circle_hull(const hull::Hull& h) {
    constexpr int n = 36;
    const double r = h.radius() / std::cos(std::numbers::pi / n);
    std::vector<XY> pts;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n;
        pts.push_back({r * std::cos(a), r * std::sin(a)});
    }
    hull::Hull c = hull::Hull::from_contour(std::move(pts), h.name().empty() ? "hull circle" : h.name() + " (circle: heading unknown)");
    return c;
}

namespace {

constexpr double deg = std::numbers::pi / 180.0;
/// A vessel whose AIS status says moored or at anchor is alongside under this speed, whatever
/// the berthing speed (SOG noise of a moored vessel reaches 1-2 kn).
constexpr double moored_speed_kn = 3.0;

/// One checked moment: fix interval i, fraction f.
struct Sample {
    std::size_t i = 0;
    double f = 0;
    check::Contact contact;
};

class EventBuilder {
public:
    EventBuilder(const track::Track& t, const geo::LocalFrame& frame, const LocalTrack& local, const PoseChecker& checker,
                 const PoseChecker* unknown_heading, const SweepOptions& options, const SweepContext& context, TrackResult& out)
        : m_track(t), m_frame(frame), m_local(local), m_checker(checker), m_circle(unknown_heading), m_opt(options),
          m_ctx(context), m_out(out), m_corners(drawn_corners(checker.hull())),
          m_circle_corners(unknown_heading ? drawn_corners(unknown_heading->hull()) : std::vector<std::size_t>{}) {}

    /// The checker for poses between fix i and i+1 (f > 0) or at fix i: the hull's circle while
    /// the heading is unknown at either end.
    const PoseChecker& checker_at(std::size_t i, double f) const {
        if (!m_circle) return m_checker;
        const auto& fx = m_track.fixes;
        const bool unknown = fx[i].heading_source == track::HeadingSource::none ||
                             (f > 0 && i + 1 < fx.size() && fx[i + 1].heading_source == track::HeadingSource::none);
        return unknown ? *m_circle : m_checker;
    }

    /// The pose check at fix interval i, fraction f. The polyline of a hull wholly inside land
    /// (a search of the grid's rings) is left out: only an event's first sample needs it, and
    /// make_event asks for it then.
    /// `where`: the contact point matters (CheckOptions::want_contact_point): only at a sample
    /// that may be an event's first contact, i.e. unless the sample before was in contact.
    check::Contact check(std::size_t i, double f, bool penetration, bool where = true) const {
        return check(i, f, m_local.pose({i, f}), penetration, where);
    }
    /// The same, `pose` being m_local.pose({i, f}) (placed once by the caller).
    /// `hint`: CheckOptions::clearance_hint_m. `extra_m`: the clearance searched that much
    /// further than search_m() (check_further).
    check::Contact check(std::size_t i, double f, const check::LocalPose& pose, bool penetration, bool where, double hint = INFINITY,
                         double extra_m = 0) const {
        return checker_at(i, f).check(pose, {.max_clearance_m = search_m() + extra_m, .want_penetration = penetration, .want_polyline = false,
                                             .want_contact_point = where, .clearance_hint_m = hint});
    }

    /// check() at fix i, the clearance searched `extra_m` further: the same answer (a
    /// clearance beyond search_m() is none, CheckOptions::max_clearance_m), and in `clear_m`
    /// how far the pose is proved clear of every segment (0 when a contact or a clearance
    /// within search_m() was found): beyond that answer, what the next fixes need to be
    /// carried (beyond()).
    check::Contact check_further(std::size_t i, const check::LocalPose& pose, bool where, double hint, double extra_m, double& clear_m) const {
        const double limit = search_m();
        const check::Contact c = check(i, 0.0, pose, true, where, hint, extra_m);
        clear_m = 0;
        if (c.collision || c.clearance_m <= limit) return c;
        clear_m = std::isfinite(c.clearance_m) ? c.clearance_m : limit + extra_m;
        return beyond(c.covered);
    }

    /// The answer of check() for a pose with nothing within search_m(): no contact, no
    /// clearance, `covered` the pose's.
    static check::Contact beyond(bool covered) {
        check::Contact c;
        c.covered = covered;
        return c;
    }

    /// An open contact goes on: the next sample in contact is not its first.
    bool in_contact() const noexcept { return m_intervals.in_contact(); }

    /// The answer at fix interval i, fraction f, when what matters of it is known
    /// (SweepOptions::carry_over): in contact (`clearance_m` 0), or clear by at least
    /// `clearance_m`, under the margin and over the least clearance of the pass so far. Where
    /// the contact is, only an event's first sample reports (always checked); the clearance of
    /// such a clear pose no one reads (it is not the pass's nearest, and no clearance is
    /// watched), only that it is near. `pose` is m_local.pose({i, f}).
    check::Contact carried(std::size_t i, double f, const check::LocalPose& pose, double clearance_m) const {
        check::Contact c;
        c.collision = clearance_m == 0;
        c.clearance_m = clearance_m;
        c.covered = checker_at(i, f).covered(pose);
        c.hull_point = c.coast_point = pose.position;
        return c;
    }

    /// The least clearance of the open pass (IntervalEvents::near_min).
    double near_min() const noexcept { return m_intervals.near_min(); }

    /// The deepest penetration of the open contact so far; -infinity when none is open.
    double contact_depth() const noexcept { return m_intervals.in_contact() ? m_ground.penetration_m : -INFINITY; }

    /// How far clearance is searched: the lookahead beyond the margin (or the watch, when larger).
    double search_m() const { return std::max(m_opt.margin_m, m_opt.watch_clearance_m) + m_opt.lookahead_m; }

    /// SweepOptions::watch_clearance_m: keeps `s` in TrackResult::clearance when under the
    /// watch, with the sample before it (pending) and the one after. `piece_start`: the first
    /// sample of a piece of track.
    void watch(const Sample& s, bool piece_start) {
        if (!(m_opt.watch_clearance_m > 0)) return;
        ClearanceSample c;
        c.time_s = m_local.time({s.i, s.f});
        c.clearance_m = s.contact.collision ? 0.0 : s.contact.clearance_m;
        c.ship = m_frame.inverse(m_local.pose({s.i, s.f}).position);
        c.covered = s.contact.covered;
        if (piece_start) {
            m_watch_pending.reset();
            m_watch_last_kept = false;
        }
        const bool under = c.covered && c.clearance_m < m_opt.watch_clearance_m;
        if (under) {
            if (m_watch_pending) {
                m_watch_pending->after_break = true;
                m_out.clearance.push_back(*m_watch_pending);
                m_watch_pending.reset();
            } else {
                c.after_break = !m_watch_last_kept;
            }
            m_out.clearance.push_back(c);
            m_watch_last_kept = true;
        } else if (m_watch_last_kept) {
            m_out.clearance.push_back(c);
            m_watch_last_kept = false;
        } else {
            m_watch_pending = c;
        }
    }

    /// A new piece of track starts at fix i; `after` is "track start", "gap" or "jump".
    void start_piece(std::size_t i, const char* after) {
        m_piece_first = i;
        m_piece_after = after;
    }

    /// The next checked sample of the current piece.
    void add(const Sample& s) { m_intervals.add(s, *this); }

    /// Closes open intervals at the end of a piece of track.
    void end_piece() { m_intervals.end(*this); }

private:
    friend class detail::IntervalEvents<Sample, true>;

    // The interval events' handler (interval_events.hpp): contacts are groundings (of some
    // kind), near intervals that never reach contact close passes.
    double time(const Sample& s) const { return m_local.time({s.i, s.f}); }
    static bool contact(const Sample& s) { return s.contact.collision; }
    bool near(const Sample& s) const { return s.contact.collision || s.contact.clearance_m < m_opt.margin_m; }
    static double clearance(const Sample& s) { return s.contact.clearance_m; }

    void contact_opened(const Sample& first, const Sample& s, bool seen_clear) {
        m_ground = make_event(EventKind::grounding, first);
        m_ground.penetration_m = std::max(first.contact.penetration_m, s.contact.penetration_m);
        classify(m_ground, first, seen_clear);
        note_status(s);
    }
    void contact_continues(const Sample& s) {
        note_status(s);
        m_ground.penetration_m = std::max(m_ground.penetration_m, s.contact.penetration_m);
    }
    void contact_closed(double start_s, double end_s) {
        m_ground.start_s = start_s;
        m_ground.end_s = end_s;
        m_ground.min_clearance_m = 0;
        m_out.events.push_back(m_ground);
        count_contact(m_out.summary, m_ground.kind);
    }
    void near_closed(double start_s, double end_s, const Sample& nearest) {
        Event e = make_event(EventKind::close_pass, nearest);
        e.min_clearance_m = nearest.contact.clearance_m;
        const track::Fix& fx = m_track.fixes[nearest.i];
        e.speed_kn = fx.speed_used_kn;
        e.speed_source = fx.speed_source;
        e.nav_status = fx.nav_status;
        e.start_s = start_s;
        e.end_s = end_s;
        m_out.events.push_back(std::move(e));
        ++m_out.summary.close_passes;
    }

    /// The kind of a contact that begins at `first`, from what was observed, and its evidence.
    void classify(Event& e, const Sample& first, bool seen_clear) const {
        const auto& fx = m_track.fixes;
        // The fixes around the first contact: `before` the last one at or before it where the
        // vessel was seen (clear), `after` the first one at or after it.
        const std::size_t after = first.f > 0 ? first.i + 1 : first.i;
        const std::size_t before = first.f > 0 ? first.i : (first.i > m_piece_first ? first.i - 1 : first.i);
        const track::Fix& b = fx[before];
        const track::Fix& a = fx[std::min(after, fx.size() - 1)];
        // The approach speed from positions: the displacement over the window that ends at the
        // first fix at or after the contact, from no earlier than the piece's first fix (never
        // reaching forward into what came after the contact).
        double approach_kn = NAN;
        if (after < fx.size() && after > m_piece_first) {
            std::size_t j = after;
            while (j > m_piece_first && a.time_s - fx[j].time_s < m_opt.speed_window_s) --j;
            if (a.time_s > fx[j].time_s)
                approach_kn = track::distance_m(fx[j].position, a.position) / (a.time_s - fx[j].time_s) * 3600.0 / 1852.0;
        }
        double sog = std::isfinite(b.sog_kn) ? b.sog_kn : a.sog_kn;
        // Sparse fixes: the SOG of a fix minutes before the contact says little of the speed at
        // it when a fix after it lies nearer; the SOG is then taken between the two, by time
        // (21.5 kn 187 s before and 5.2 kn 3 s after: 5.5 kn, not 21.5).
        if (std::isfinite(b.sog_kn) && std::isfinite(a.sog_kn) && &a != &b && e.start_s - b.time_s > m_opt.speed_window_s &&
            a.time_s - e.start_s < e.start_s - b.time_s && a.time_s > b.time_s)
            sog = b.sog_kn + (a.sog_kn - b.sog_kn) * (e.start_s - b.time_s) / (a.time_s - b.time_s);
        if (std::isfinite(sog) && !(approach_kn >= 2.0 && approach_kn > 2 * sog + 1)) {
            e.speed_kn = sog;
            e.speed_source = track::SpeedSource::sog;
        } else if (std::isfinite(approach_kn)) {
            // No SOG, or a SOG the positions belie (class B units that always send 0).
            e.speed_kn = approach_kn;
            e.speed_source = std::isfinite(sog) ? track::SpeedSource::positions_over_sog : track::SpeedSource::positions;
        } else if (std::isfinite(b.speed_used_kn)) {
            e.speed_kn = b.speed_used_kn;
            e.speed_source = b.speed_source;
        }
        const check::LocalPose pose = m_local.pose({first.i, first.f});
        // A stopped fix vouches for the contact while it is recent (within the speed window: a
        // jitter burst, a tug's push) or the vessel is still within the stop diameter of it;
        // not when the vessel has since gone on at twice the speed of one under way or more,
        // which no berthing averages over minutes (it left its anchorage and ran 735 m onto
        // the shore at 7.9 kn in the 3 minutes to the next fix; one that leaves its anchorage
        // and berths 530 m on in 5 minutes, 3.5 kn, or one GPS fix 150 m off at a berth, is
        // still "stopped before").
        const XY moved = pose.position - m_local.position(before);
        const double moved_m = std::hypot(moved.x, moved.y), since_s = e.start_s - b.time_s;
        const bool left_stop = since_s > m_opt.speed_window_s && moved_m > m_opt.stop_diameter_m &&
                               moved_m / since_s * 3600.0 / 1852.0 >= 2 * moored_speed_kn;
        e.stopped_before = b.stopped && !left_stop;
        e.nav_status = b.nav_status;
        const double t0 = e.start_s;
        if (const auto stop = track::stopped_after(m_track, after < fx.size() ? after : before, t0, m_opt.motion()))
            e.stopped_after_s = *stop - t0;
        e.reference_inside_m = m_checker.inside_depth(pose.position, 2 * m_checker.hull().radius() + m_opt.margin_m);
        if (std::isinf(e.reference_inside_m)) e.reference_inside_m = NAN;
        e.orientation_unknown = &checker_at(first.i, first.f) != &m_checker;
        if (m_ctx.areas) {
            const coast::ExpectedArea* area = m_ctx.areas->find(pose.position, coast::AreaRole::expected);
            if (!area) area = m_ctx.areas->find(first.contact.coast_point, coast::AreaRole::expected);
            if (area) {
                e.area_kind = area->kind;
                e.area_name = area->name;
            }
            if (e.structure.empty())  // what was hit, when it is a structure, else the area the contact point lies on
                if (const coast::ExpectedArea* st = m_ctx.areas->find(first.contact.coast_point, coast::AreaRole::structure))
                    e.structure = st->kind;
        }
        // The rules: a contact not seen begin; a vessel stopped, under the berthing speed, or
        // moored / at anchor by its AIS status and slow; else a grounding. Inside an area
        // where contact is expected, the first two are expected contacts; a contact under way
        // stays a grounding there (an allision with a quay at speed is no berthing), the area
        // said as evidence.
        const bool moored_status = b.nav_status == track::nav_status_moored || b.nav_status == track::nav_status_at_anchor;
        const bool slow = e.stopped_before || !(e.speed_kn >= m_opt.berthing_speed_kn) || (moored_status && e.speed_kn < moored_speed_kn);
        if (!seen_clear) {
            e.kind = e.area_kind.empty() ? EventKind::contact_at_start : EventKind::expected_contact;
            e.unseen_after = m_piece_after;
        } else if (slow) {
            e.kind = e.area_kind.empty() ? EventKind::alongside : EventKind::expected_contact;
        } else {
            e.kind = EventKind::grounding;
        }
    }

    /// AIS status 6 "aground" at a fix of the open contact is evidence for it.
    void note_status(const Sample& s) {
        const auto& fx = m_track.fixes;
        const std::size_t i = s.f > 0 && s.i + 1 < fx.size() ? s.i + 1 : s.i;
        if (fx[s.i].nav_status == track::nav_status_aground || fx[i].nav_status == track::nav_status_aground)
            m_ground.reported_aground = true;
    }

    /// Between a sample without contact (`clear`) and one with (`hit`), the moment of change.
    /// Returns the sample on the contact side: going forward (clear is earlier than hit), with
    /// its contact as check() gives it; going back, only its moment is meant (the contact is
    /// `hit`'s).
    Sample bisect(Sample clear, Sample hit, bool forward) const {
        // Both lie in one fix interval (consecutive samples), or hit is the next fix (f = 0).
        std::size_t i = clear.i;
        double f_clear = clear.f, f_hit = hit.f;
        if (forward && hit.i != clear.i) f_hit = 1.0;  // hit is fix i+1
        if (!forward && hit.i != clear.i) {             // clear is fix i+1 (f = 0), hit in interval hit.i
            i = hit.i;
            f_clear = 1.0;
        }
        const double duration = m_track.fixes[i + 1].time_s - m_track.fixes[i].time_s;
        // The steps ask only whether the hull touches: no clearance searched, no contact point
        // (collision is the same whatever else is asked: CheckOptions). The contact at the
        // moment found, when it is an event's first, is then checked as other samples are.
        const double f_start = f_hit;
        f_hit = detail::bisect_change(f_clear, f_hit, duration, m_opt.time_tolerance_s, 50, [&](double mid) {
            return checker_at(i, mid)
                .check(m_local.pose({i, mid}), {.max_clearance_m = 0, .want_penetration = false, .want_polyline = false, .want_contact_point = false})
                .collision;
        });
        if (forward && f_hit != f_start) hit.contact = check(i, f_hit, false);
        if (f_hit >= 1.0) return Sample{i + 1, 0.0, hit.contact};
        hit.i = i;
        hit.f = f_hit;
        return hit;
    }

    Event make_event(EventKind kind, const Sample& s) const {
        Event e;
        e.kind = kind;
        e.start_s = e.end_s = m_local.time({s.i, s.f});
        const check::LocalPose pose = m_local.pose({s.i, s.f});
        e.point = m_frame.inverse(s.contact.coast_point);
        const PoseChecker& used = checker_at(s.i, s.f);
        if (const grid::CoastGrid* g = m_checker.grid()) {
            std::uint32_t polyline = s.contact.polyline;
            // Not searched by check(): asked again as the sample was checked (penetration at
            // fixes), so that the same pose at the next fixes is answered from the last check.
            if (s.contact.collision && polyline == grid::CoastGrid::no_polyline)
                polyline = used.check(pose, {.max_clearance_m = search_m(), .want_penetration = s.f == 0.0, .want_polyline = true}).polyline;
            if (polyline < g->polyline_count()) {
                const coast::Hazard& hit = g->hazard(polyline);
                e.hit = hit.kind;
                e.charted_depth_m = hit.depth_m;
                e.danger = hit.danger;
                e.hit_name = hit.name;
                if (hit.kind == coast::HazardKind::structure) e.structure = coast::to_string(hit.structure);
            }
        }
        e.ship = m_frame.inverse(pose.position);
        const std::size_t fix = s.f >= 1.0 ? s.i + 1 : s.i;
        e.fix_index = fix;
        e.fix_line = m_track.fixes[fix].line;
        e.orientation_unknown = &used != &m_checker;
        e.heading_source = e.orientation_unknown ? track::HeadingSource::none : m_track.fixes[fix].heading_source;
        e.heading_deg = e.orientation_unknown ? NAN : wrap_360(m_local.heading({s.i, s.f}));
        for (const XY& p : check::hull_outline(used.hull(), pose)) e.hull.push_back(m_frame.inverse(p));
        if (!e.hull.empty()) e.hull.push_back(e.hull.front());
        return e;
    }

public:
    /// The hull at fix i, with what the check there found.
    Pose pose_at(std::size_t i, const check::Contact& c) const {
        Pose p;
        const track::Fix& fix = m_track.fixes[i];
        p.time_s = p.until_s = fix.time_s;
        p.speed_kn = fix.speed_used_kn;
        const PoseChecker& used = checker_at(i, 0.0);
        p.heading_deg = &used != &m_checker ? NAN : wrap_360(m_local.heading({i, 0.0}));
        p.contact = c.collision;
        p.clearance_m = c.collision ? 0.0 : c.clearance_m;
        p.covered = c.covered;
        p.fix_index = i;
        p.fix_line = fix.line;
        // The corners the drawn outline keeps (pose_outline.hpp), placed at the pose.
        const std::vector<XY> outline = check::hull_outline(used.hull(), m_local.pose({i, 0.0}));
        for (const std::size_t k : &used != &m_checker ? m_circle_corners : m_corners) p.hull.push_back(m_frame.inverse(outline[k]));
        if (!p.hull.empty()) p.hull.push_back(p.hull.front());
        return p;
    }

private:
    /// The corners of `h`'s outline the poses layer draws (pose_outline_corners, in the hull's metres).
    static std::vector<std::size_t> drawn_corners(const hull::Hull& h) {
        std::vector<XY> ring = h.contour();
        if (!ring.empty()) ring.push_back(ring.front());
        return pose_outline_corners(ring);
    }

    const track::Track& m_track;
    const geo::LocalFrame& m_frame;
    const LocalTrack& m_local;
    const PoseChecker& m_checker;
    const PoseChecker* m_circle;
    const SweepOptions& m_opt;
    const SweepContext& m_ctx;
    TrackResult& m_out;
    std::size_t m_piece_first = 0;
    const char* m_piece_after = "track start";
    detail::IntervalEvents<Sample, true> m_intervals;
    Event m_ground;  ///< the open contact, from its first contact
    std::vector<std::size_t> m_corners, m_circle_corners;  ///< drawn corners of the hull's outline, of its circle's
    std::optional<ClearanceSample> m_watch_pending;  ///< the last sample over the watch, not kept (yet)
    bool m_watch_last_kept = false;                  ///< the last sample was kept
};

/// The largest singular value of `m`: how far it stretches a unit vector at most.
double largest_stretch(const Eigen::Matrix2d& m) {
    const double s = m.squaredNorm(), det = m.determinant();
    return std::sqrt((s + std::sqrt(std::max(0.0, s * s - 4 * det * det))) / 2);
}

/// Gives the last answer again for the same pose and options (a pure function of them): a
/// vessel standing still, a fix a second for a day at anchor or aground, costs one check per
/// change of pose rather than one per fix (a hull deep in land costs a long penetration search).
class RepeatingChecker final : public PoseChecker {
public:
    explicit RepeatingChecker(const PoseChecker& inner) : m_inner(inner) {}
    check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const override {
        // An answer with the polyline (or the contact point) also serves a question without it
        // (make_event asks for the polyline of an event's first sample; the same pose at the
        // next fixes costs nothing), and a contact one with any clearance limit (contact does
        // not depend on it: CheckOptions::max_clearance_m; a fix's check searches further).
        if (!(m_have && pose.position == m_pose.position && pose.ship_to_local == m_pose.ship_to_local &&
              (options.max_clearance_m == m_options.max_clearance_m || m_contact.collision) &&
              options.want_penetration == m_options.want_penetration &&
              (m_options.want_polyline || !options.want_polyline) && (m_options.want_contact_point || !options.want_contact_point))) {
            m_contact = m_inner.check(pose, options);
            m_pose = pose;
            m_options = options;
            m_have = true;
        }
        return m_contact;
    }
    const hull::Hull& hull() const override { return m_inner.hull(); }
    const grid::CoastGrid* grid() const override { return m_inner.grid(); }
    double inside_depth(geo::XY p, double max_m) const override { return m_inner.inside_depth(p, max_m); }
    bool covered(const check::LocalPose& pose) const override { return m_inner.covered(pose); }

private:
    const PoseChecker& m_inner;
    mutable bool m_have = false;
    mutable check::LocalPose m_pose;
    mutable check::CheckOptions m_options;
    mutable check::Contact m_contact;
};

}  // namespace

void check_step(double step_m) {
    if (!(step_m >= min_step_m))
        throw UsageError("SweepOptions::step_m " + track::detail::fmt(step_m) + " is under the smallest step, " + track::detail::fmt(min_step_m) +
                         " m: a sweep that fine never ends");
}

TrackResult sweep_track(const track::Track& t, const geo::LocalFrame& frame, const PoseChecker& inner,
                        const SweepOptions& opt, const SweepContext& ctx) {
    if (!(opt.step_m > 0)) throw UsageError("SweepOptions::step_m must be > 0 metres");
    const RepeatingChecker checker(inner);
    std::optional<RepeatingChecker> circle;
    if (ctx.unknown_heading) circle.emplace(*ctx.unknown_heading);
    TrackResult out;
    TrackSummary& sum = out.summary;
    sum.id = t.id;
    sum.name = t.name;
    sum.file = t.file;
    sum.fixes = t.fixes.size();
    if (t.fixes.empty()) return out;
    sum.start_s = t.fixes.front().time_s;
    sum.end_s = t.fixes.back().time_s;
    const LocalTrack lt(t, frame);
    if (ctx.positions) *ctx.positions = lt.positions();
    EventBuilder events(t, frame, lt, checker, circle ? &*circle : nullptr, opt, ctx, out);
    const double radius = std::max(checker.hull().radius(), circle ? circle->hull().radius() : 0.0);

    // Hull motion (metres) that may pass before the next check: what the last check proved clear.
    double budget_m = 0;
    const double near_m = std::max(opt.margin_m, opt.watch_clearance_m);  // clearance followed up to this
    auto note = [&](const check::Contact& c) {
        ++sum.poses;
        if (c.covered) sum.min_clearance_m = std::min(sum.min_clearance_m, c.clearance_m);
        const double clear = std::isinf(c.clearance_m) ? near_m + opt.lookahead_m : c.clearance_m;
        budget_m = c.collision ? 0 : std::max(0.0, clear - near_m);
    };
    // SweepOptions::carry_over: the penetration found at the last fix checked in contact (0:
    // none), the checker and the pose that found it; the clearance of the last checked pose
    // clear (NaN: none), its checker and pose. How far a pose is from one of them bounds how
    // far any hull point is (local metres): the translation plus the change of the placement
    // (rotation and the frame's scale) on the hull's radius. Penetration and clearance move
    // no more than the hull's points, whatever the path between the two poses.
    double contact_depth_m = 0;
    const PoseChecker* contact_checker = nullptr;
    check::LocalPose contact_pose;
    double clear_ref_m = NAN;
    const PoseChecker* clear_checker = nullptr;
    check::LocalPose clear_pose;
    auto apart = [&](const check::LocalPose& a, const check::LocalPose& b) {
        const XY d = b.position - a.position;
        return std::hypot(d.x, d.y) + radius * largest_stretch(b.ship_to_local - a.ship_to_local);
    };
    // The bound with a 1 % and 1 cm allowance (rounding).
    auto slack = [](double motion_m) { return motion_m * 1.01 + 0.01; };
    auto still_in_contact = [&](const PoseChecker& c, const check::LocalPose& pose) {
        return opt.carry_over && &c == contact_checker && contact_depth_m > 0 && slack(apart(contact_pose, pose)) < contact_depth_m;
    };
    // The clearance a pose is known to have at least, when that is all that matters of it; NaN else.
    auto known_near = [&](const PoseChecker& c, const check::LocalPose& pose) -> double {
        if (!opt.carry_over || opt.watch_clearance_m > 0 || &c != clear_checker || !std::isfinite(clear_ref_m)) return NAN;
        const double moved = slack(apart(clear_pose, pose));
        const double lower = clear_ref_m - moved, upper = clear_ref_m + moved;
        const bool known = lower > 0 && upper < opt.margin_m && lower > events.near_min() && lower >= sum.min_clearance_m;
        return known ? lower : NAN;
    };
    // The clearance a pose has at most, from the last pose checked clear (CheckOptions::
    // clearance_hint_m: it only speeds the search); INFINITY when there is none.
    auto hint = [&](const PoseChecker& c, const check::LocalPose& pose) -> double {
        if (&c != clear_checker || !std::isfinite(clear_ref_m)) return INFINITY;
        return clear_ref_m + slack(apart(clear_pose, pose));
    };
    // The fix last checked with nothing found within the search (carry_over): how far it is
    // proved clear of every segment, its checker and pose. A later fix no nearer than that
    // distance less its motion, and that still beyond the search, has check()'s answer
    // without a check: nothing within the search (EventBuilder::beyond).
    double far_m = 0;
    const PoseChecker* far_checker = nullptr;
    check::LocalPose far_pose;
    auto proved_beyond = [&](const PoseChecker& c, const check::LocalPose& pose) {
        return opt.carry_over && &c == far_checker && far_m - slack(apart(far_pose, pose)) > events.search_m();
    };
    // How much further than the search a fix's check reaches: the hull's motion over the next
    // fixes of the piece (up to further_fixes of them, at most the lookahead), so that they
    // can be proved beyond it. Only the work depends on it, not an answer, but for one case
    // that CheckOptions::clearance_hint_m also has: of two hull and coast points exactly as
    // near, the search may report the other.
    constexpr std::size_t further_fixes = 8;
    auto further_m = [&](std::size_t i) {
        if (!opt.carry_over) return 0.0;
        double reach = 0;
        for (std::size_t k = i + 1; k < t.fixes.size() && k <= i + further_fixes; ++k) {
            if (t.fixes[k].time_s - t.fixes[k - 1].time_s > opt.max_gap_s || t.fixes[k].jump_before) break;
            const XY d = lt.position(k) - lt.position(i);
            reach = std::max(reach, std::hypot(d.x, d.y));
        }
        return std::max(0.0, std::min(opt.lookahead_m, reach * 1.25 + 0.25 * radius + 1.0));
    };
    auto checked = [&](const check::Contact& c, const PoseChecker& by, const check::LocalPose& pose) {  // a pose checked in full
        clear_ref_m = !c.collision && std::isfinite(c.clearance_m) ? c.clearance_m : NAN;
        clear_checker = &by;
        clear_pose = pose;
    };
    bool have_prev = false;
    // The fix before was in contact. While it was not, a contact between fixes has no fix to
    // measure its penetration at: the swept poses in contact measure it (all of them are
    // checked then, whether answers carry over or not, so the figure is the same either way).
    bool fix_in_contact = false;
    std::vector<geo::LonLat>* line = nullptr;
    std::vector<double>* times = nullptr;
    // Poses for the report (SweepOptions::pose_interval_s): the last kept one of this piece,
    // and the fix before (kept when the piece ends or the state changes).
    std::size_t piece_poses = 0;  ///< index in out.poses of this piece's first pose
    int last_state = -1;
    std::optional<std::pair<std::size_t, check::Contact>> pending;  ///< the previous fix, not kept (yet)
    auto state_of = [&](const check::Contact& c) { return c.collision ? 2 : c.clearance_m < opt.margin_m ? 1 : 0; };
    auto keep = [&](Pose p) {
        if (out.poses.size() > piece_poses) out.poses.back().until_s = p.time_s;
        out.poses.push_back(std::move(p));
    };
    auto end_poses = [&] {
        if (pending) keep(events.pose_at(pending->first, pending->second));
        pending.reset();
        piece_poses = out.poses.size();
    };
    for (std::size_t i = 0; i < t.fixes.size(); ++i) {
        const bool gap = have_prev && t.fixes[i].time_s - t.fixes[i - 1].time_s > opt.max_gap_s;
        const bool jump = have_prev && t.fixes[i].jump_before;
        const bool continues = have_prev && !gap && !jump;
        if (!continues) {
            if (have_prev) {
                end_poses();
                events.end_piece();
                ++(gap ? sum.gaps : sum.jumps);
            }
            events.start_piece(i, !have_prev ? "track start" : gap ? "gap" : "jump");
            ++sum.segments;
            line = &sum.lines.emplace_back();
            times = &sum.line_times.emplace_back();
            have_prev = false;
        } else {
            // Sweep from fix i-1 to fix i: no hull point moves more than step between checks.
            const XY d = lt.position(i) - lt.position(i - 1);
            sum.distance_m += std::hypot(d.x, d.y);
            const double rot = std::fabs(turn(t.fixes[i - 1].heading_used_deg, t.fixes[i].heading_used_deg)) * deg;
            const double motion_m = std::hypot(d.x, d.y) + radius * rot;
            const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(motion_m / opt.step_m)));
            const double per_step = motion_m / static_cast<double>(n);
            double moved = 0;
            for (std::size_t k = 1; k < n; ++k) {
                moved += per_step;
                if (moved < budget_m) continue;  // proved clear of the margin by the last check
                budget_m = 0;
                moved = 0;
                Sample s{i - 1, static_cast<double>(k) / static_cast<double>(n), {}};
                // Proved in contact by the last fix's penetration, or near and not the nearest by
                // the last clearance checked, or checked.
                const PoseChecker& by = events.checker_at(s.i, s.f);
                const check::LocalPose pose = lt.pose({s.i, s.f});
                if (still_in_contact(by, pose)) {
                    s.contact = events.carried(s.i, s.f, pose, 0);
                } else if (const double near = known_near(by, pose); !std::isnan(near)) {
                    s.contact = events.carried(s.i, s.f, pose, near);
                } else {
                    s.contact = events.check(s.i, s.f, pose, !fix_in_contact, !events.in_contact(), hint(by, pose));
                    checked(s.contact, by, pose);
                }
                note(s.contact);
                events.add(s);
                events.watch(s, false);
            }
        }
        Sample s{i, 0.0, {}};
        // A fix proved in contact by the last fix checked, and no deeper than the open
        // contact's deepest (penetration moves no more than the hull's points), adds nothing
        // to its event: it is not checked, and that last fix stays the reference.
        const PoseChecker& at_fix = events.checker_at(i, 0.0);
        const check::LocalPose pose = lt.pose({i, 0.0});
        if (continues && still_in_contact(at_fix, pose) && contact_depth_m + slack(apart(contact_pose, pose)) <= events.contact_depth()) {
            s.contact = events.carried(i, 0.0, pose, 0);
        } else {
            if (continues && proved_beyond(at_fix, pose)) {
                // Nothing within the search, as its check would say, and all below as after
                // that check; the last fix checked stays the proof's reference.
                s.contact = EventBuilder::beyond(at_fix.covered(pose));
            } else {
                double clear_m = 0;
                s.contact = events.check_further(i, pose, !continues || !events.in_contact(), continues ? hint(at_fix, pose) : INFINITY,
                                                 further_m(i), clear_m);
                far_m = clear_m;
                far_checker = &at_fix;
                far_pose = pose;
            }
            contact_depth_m = s.contact.collision ? s.contact.penetration_m : 0.0;
            contact_checker = &at_fix;
            contact_pose = pose;
            checked(s.contact, at_fix, pose);
        }
        if (t.fixes[i].heading_source == track::HeadingSource::none && circle) ++sum.unknown_heading_fixes;
        if (!s.contact.covered) ++sum.uncovered_fixes;
        note(s.contact);
        events.add(s);
        events.watch(s, !have_prev);
        if (opt.keep_poses) {
            const int state = state_of(s.contact);
            const bool first = out.poses.size() == piece_poses;
            bool take = first || state != last_state || !(opt.pose_interval_s > 0);
            if (!take) {
                const Pose& last = out.poses.back();
                const double dt = t.fixes[i].time_s - last.time_s;
                const XY d = lt.position(i) - lt.position(last.fix_index);
                take = (dt >= opt.pose_interval_s && std::hypot(d.x, d.y) >= opt.pose_distance_m) || dt >= opt.pose_max_interval_s;
            }
            if (state != last_state && !first && pending) keep(events.pose_at(pending->first, pending->second));  // the fix before the change
            pending.reset();
            if (take) keep(events.pose_at(i, s.contact));
            else pending.emplace(i, s.contact);
            last_state = state;
        }
        have_prev = true;
        fix_in_contact = s.contact.collision;
        line->push_back(t.fixes[i].position);
        times->push_back(t.fixes[i].time_s);
    }
    end_poses();
    events.end_piece();
    std::stable_sort(out.events.begin(), out.events.end(), [](const Event& a, const Event& b) { return a.start_s < b.start_s; });
    return out;
}

}  // namespace shoal::audit
