#include "audit/sweep.hpp"

#include <algorithm>
#include <numbers>

#include "audit/motion.hpp"
#include "util/error.hpp"

namespace shoal::audit {

using geo::XY;

const char* to_string(EventKind k) noexcept { return k == EventKind::grounding ? "grounding" : "close_pass"; }

namespace {

constexpr double deg = std::numbers::pi / 180.0;

/// One checked moment: fix interval i, fraction f.
struct Sample {
    std::size_t i = 0;
    double f = 0;
    check::Contact contact;
};

class EventBuilder {
public:
    EventBuilder(const track::Track& t, const geo::LocalFrame& frame, const Motion& motion, const PoseChecker& checker,
                 const SweepOptions& options, TrackResult& out)
        : m_track(t), m_frame(frame), m_motion(motion), m_checker(checker), m_opt(options), m_out(out) {}

    check::Contact check(std::size_t i, double f, bool penetration) const {
        return m_checker.check(m_motion.pose(i, f), {m_opt.margin_m + m_opt.lookahead_m, penetration});
    }

    void add(const Sample& s, const Sample* prev) {
        const check::Contact& c = s.contact;
        // Groundings: intervals of contact, first and last contact refined by bisection.
        if (c.collision && !m_in_ground) {
            m_in_ground = true;
            Sample first = s;
            if (prev && !prev->contact.collision) first = bisect(*prev, s, true);
            m_ground = make_event(EventKind::grounding, first);
            m_ground.start_s = m_motion.time(first.i, first.f);
            m_ground.end_s = m_ground.start_s;
            m_ground.penetration_m = std::max(first.contact.penetration_m, c.penetration_m);
        } else if (c.collision) {
            m_ground.end_s = m_motion.time(s.i, s.f);
            m_ground.penetration_m = std::max(m_ground.penetration_m, c.penetration_m);
        } else if (m_in_ground) {
            const Sample last = prev ? bisect(s, *prev, false) : s;
            m_ground.end_s = m_motion.time(last.i, last.f);
            finish_ground();
        }
        // Close passes: intervals under the margin that never reach contact.
        const bool near = c.collision || c.clearance_m < m_opt.margin_m;
        if (near) {
            if (!m_in_near) {
                m_in_near = true;
                m_near_contact = false;
                m_near_min = INFINITY;
                m_near_start = m_motion.time(s.i, s.f);
            }
            m_near_end = m_motion.time(s.i, s.f);
            if (c.collision) {
                m_near_contact = true;
            } else if (c.clearance_m < m_near_min) {
                m_near_min = c.clearance_m;
                m_near = make_event(EventKind::close_pass, s);
                m_near.min_clearance_m = c.clearance_m;
            }
        } else if (m_in_near) {
            finish_near();
        }
    }

    /// Closes open intervals at the end of a piece of track.
    void end_piece() {
        if (m_in_ground) finish_ground();
        if (m_in_near) finish_near();
    }

private:
    /// Between a sample without contact (`clear`) and one with (`hit`), the moment of change.
    /// Returns the sample on the contact side. `forward`: clear is earlier than hit.
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
        for (int it = 0; it < 50 && duration * std::fabs(f_hit - f_clear) > m_opt.time_tolerance_s; ++it) {
            const double mid = (f_clear + f_hit) / 2;
            const check::Contact c = check(i, mid, false);
            if (c.collision) {
                f_hit = mid;
                hit.contact = c;
            } else {
                f_clear = mid;
            }
        }
        if (f_hit >= 1.0) return Sample{i + 1, 0.0, hit.contact};
        hit.i = i;
        hit.f = f_hit;
        return hit;
    }

    Event make_event(EventKind kind, const Sample& s) const {
        Event e;
        e.kind = kind;
        e.start_s = e.end_s = m_motion.time(s.i, s.f);
        const check::LocalPose pose = m_motion.pose(s.i, s.f);
        e.point = m_frame.inverse(s.contact.coast_point);
        if (const grid::CoastGrid* g = m_checker.grid(); g && s.contact.polyline < g->polyline_count()) {
            const coast::Hazard& hit = g->hazard(s.contact.polyline);
            e.hit = hit.kind;
            e.charted_depth_m = hit.depth_m;
            e.danger = hit.danger;
        }
        e.ship = m_frame.inverse(pose.position);
        e.heading_deg = m_motion.heading(s.i, s.f);
        const std::size_t fix = s.f >= 1.0 ? s.i + 1 : s.i;
        e.fix_index = fix;
        e.fix_line = m_track.fixes[fix].line;
        e.heading_source = m_track.fixes[fix].heading_source;
        for (const XY& p : check::hull_outline(m_checker.hull(), pose)) e.hull.push_back(m_frame.inverse(p));
        if (!e.hull.empty()) e.hull.push_back(e.hull.front());
        return e;
    }

    void finish_ground() {
        m_in_ground = false;
        m_ground.min_clearance_m = 0;
        m_out.events.push_back(m_ground);
        ++m_out.summary.groundings;
    }

    void finish_near() {
        m_in_near = false;
        if (m_near_contact) return;  // it reached contact: the grounding tells it
        m_near.start_s = m_near_start;
        m_near.end_s = m_near_end;
        m_out.events.push_back(m_near);
        ++m_out.summary.close_passes;
    }

    const track::Track& m_track;
    const geo::LocalFrame& m_frame;
    const Motion& m_motion;
    const PoseChecker& m_checker;
    const SweepOptions& m_opt;
    TrackResult& m_out;
    bool m_in_ground = false, m_in_near = false, m_near_contact = false;
    Event m_ground, m_near;
    double m_near_min = INFINITY, m_near_start = 0, m_near_end = 0;
};

/// Gives the last answer again for the same pose and options (a pure function of them): a
/// vessel standing still, a fix a second for a day at anchor or aground, costs one check per
/// change of pose rather than one per fix (a hull deep in land costs a long penetration search).
class RepeatingChecker final : public PoseChecker {
public:
    explicit RepeatingChecker(const PoseChecker& inner) : m_inner(inner) {}
    check::Contact check(const check::LocalPose& pose, const check::CheckOptions& options) const override {
        if (!(m_have && pose.position == m_pose.position && pose.ship_to_local == m_pose.ship_to_local &&
              options.max_clearance_m == m_options.max_clearance_m && options.want_penetration == m_options.want_penetration)) {
            m_contact = m_inner.check(pose, options);
            m_pose = pose;
            m_options = options;
            m_have = true;
        }
        return m_contact;
    }
    const hull::Hull& hull() const override { return m_inner.hull(); }
    const grid::CoastGrid* grid() const override { return m_inner.grid(); }

private:
    const PoseChecker& m_inner;
    mutable bool m_have = false;
    mutable check::LocalPose m_pose;
    mutable check::CheckOptions m_options;
    mutable check::Contact m_contact;
};

}  // namespace

TrackResult sweep_track(const track::Track& t, const geo::LocalFrame& frame, const PoseChecker& inner,
                        const SweepOptions& opt) {
    if (!(opt.step_m > 0)) throw UsageError("--step must be > 0 metres");
    const RepeatingChecker checker(inner);
    TrackResult out;
    TrackSummary& sum = out.summary;
    sum.id = t.id;
    sum.name = t.name;
    sum.file = t.file;
    sum.fixes = t.fixes.size();
    if (t.fixes.empty()) return out;
    sum.start_s = t.fixes.front().time_s;
    sum.end_s = t.fixes.back().time_s;
    const std::vector<LocalFix> local = project_fixes(t, frame);
    const Motion motion(t, local);
    EventBuilder events(t, frame, motion, checker, opt, out);
    const double radius = checker.hull().radius();

    // Hull motion (metres) that may pass before the next check: what the last check proved clear.
    double budget_m = 0;
    auto note = [&](const check::Contact& c) {
        ++sum.poses;
        if (c.covered) sum.min_clearance_m = std::min(sum.min_clearance_m, c.clearance_m);
        const double clear = std::isinf(c.clearance_m) ? opt.margin_m + opt.lookahead_m : c.clearance_m;
        budget_m = c.collision ? 0 : std::max(0.0, clear - opt.margin_m);
    };
    Sample prev;
    bool have_prev = false;
    std::vector<geo::LonLat>* line = nullptr;
    for (std::size_t i = 0; i < t.fixes.size(); ++i) {
        const bool new_piece = !have_prev || t.fixes[i].time_s - t.fixes[i - 1].time_s > opt.max_gap_s;
        if (new_piece) {
            if (have_prev) {
                events.end_piece();
                ++sum.gaps;
            }
            ++sum.segments;
            line = &sum.lines.emplace_back();
            have_prev = false;
        } else {
            // Sweep from fix i-1 to fix i: no hull point moves more than step between checks.
            const XY d = local[i].position - local[i - 1].position;
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
                s.contact = events.check(s.i, s.f, false);
                note(s.contact);
                events.add(s, &prev);
                prev = s;
            }
        }
        Sample s{i, 0.0, {}};
        s.contact = events.check(i, 0.0, true);
        if (!s.contact.covered) ++sum.uncovered_fixes;
        note(s.contact);
        events.add(s, have_prev ? &prev : nullptr);
        prev = s;
        have_prev = true;
        line->push_back(t.fixes[i].position);
    }
    events.end_piece();
    std::stable_sort(out.events.begin(), out.events.end(), [](const Event& a, const Event& b) { return a.start_s < b.start_s; });
    return out;
}

}  // namespace shoal::audit
