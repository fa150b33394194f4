// The narrow phase of an exercise (see narrow_phase.hpp): every edge pair, and bounded.
#include "exercise/narrow_phase.hpp"

#include <algorithm>

namespace shoal::audit::detail {

using check::detail::bound_slack_m;
using check::detail::Placed;

namespace {

double dist2(geo::XY a, geo::XY b) { return geo::norm2(b - a); }

class AllEdges final : public NarrowPhase {
public:
    std::size_t now(ExerciseShip& a, ExerciseShip& b, PairMemo&, const PairQuery& q, PairSample& s) const override {
        s.contact = check::detail::contact_all(a.outlined(q.instant).pts, b.outlined(q.instant).pts);
        return 1;
    }
    std::size_t at(const ExerciseShip&, const Placed& pa, const ExerciseShip&, const Placed& pb, PairSample& s) const override {
        s.contact = check::detail::contact_all(pa.pts, pb.pts);
        return 1;
    }
};

/// A check is skipped when bounds (circles around the hulls, the last exact clearance minus
/// how far both hulls can have moved since, chunk capsules) prove the clearance is over the
/// margin and not under the best so far; else only the edge pairs capsules cannot rule out.
class Bounded final : public NarrowPhase {
public:
    std::size_t now(ExerciseShip& a, ExerciseShip& b, PairMemo& m, const PairQuery& q, PairSample& s) const override {
        if (!q.contiguous) m.clear_known = false;
        double lb = std::sqrt(dist2(a.pos, b.pos)) - a.reach - b.reach;
        if (m.clear_known) {
            const double moved = (a.odometer_now() - m.odometer_a) + (b.odometer_now() - m.odometer_b);
            lb = std::max(lb, m.last_clear - moved * (1 + 1e-9) - bound_slack_m);
        }
        s.far = lb > q.margin_m && lb >= q.best_m;
        std::size_t computed = 0;
        // In a collision that goes on, only "still touching?" matters: the event has its
        // first contact and the closest approach is 0 already.
        if (!s.far && q.touch_only &&
            check::detail::touching_pruned(a.shape, a.outlined(q.instant), b.shape, b.outlined(q.instant), &m.hint)) {
            computed = 1;
            s.contact.collision = true;
            s.contact.clearance_m = 0;
        } else if (!s.far) {
            s.far = check::detail::chunks_apart(a.posed(q.instant), b.posed(q.instant), q.margin_m, q.best_m);
            if (!s.far) {
                check::detail::contact_pruned(a.shape, a.outlined(q.instant), b.shape, b.outlined(q.instant), INFINITY, INFINITY, s.contact,
                                              &m.hint);
                computed = 1;
            }
        }
        if (!s.far) {
            m.clear_known = true;
            m.last_clear = s.contact.clearance_m;
            m.odometer_a = a.odometer_now();
            m.odometer_b = b.odometer_now();
        }
        return computed;
    }
    std::size_t at(const ExerciseShip& a, const Placed& pa, const ExerciseShip& b, const Placed& pb, PairSample& s) const override {
        s.far = !check::detail::contact_pruned(a.shape, pa, b.shape, pb, 0, 0, s.contact);
        return !s.far;
    }
};

}  // namespace

std::unique_ptr<NarrowPhase> all_edges() { return std::make_unique<AllEdges>(); }
std::unique_ptr<NarrowPhase> bounded() { return std::make_unique<Bounded>(); }

}  // namespace shoal::audit::detail
