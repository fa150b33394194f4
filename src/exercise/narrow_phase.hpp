#pragma once
/// The narrow phase of an exercise (internal to src/exercise): hull to hull for a pair of ships
/// the broad phase found near, in local metres. Two implementations of one interface: every
/// edge pair at every check (find_encounters_brute, the reference), and the bounded one
/// (find_encounters), which skips a check when bounds prove the clearance over the margin and
/// not under the pair's closest approach so far, and otherwise tests only the edge pairs that
/// capsule bounds cannot rule out: the results are those of computing it.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>

#include <shoal/check/hull_contact.hpp>
#include "exercise/exercise_ship.hpp"
#include "check/hull_shape.hpp"

namespace shoal::audit::detail {

/// What one check of a pair found.
struct PairSample {
    double t = 0;
    bool far = false;  ///< proved clearance > margin (and no better than the closest approach so far) without computing it
    check::HullContact contact;
    geo::XY pos_a, pos_b;
    bool touching() const noexcept { return !far && contact.collision; }
};

/// What the bounded narrow phase remembers of a pair between instants.
struct PairMemo {
    check::detail::EdgePair hint;  ///< the nearest (or touching) edge pair at the last exact check
    /// Clearance at the last exact check, the pair checked at every instant since, and both
    /// ships' odometers then: the clearance can have shrunk by at most what they moved since.
    bool clear_known = false;
    double last_clear = 0;
    double odometer_a = 0, odometer_b = 0;
};

/// What the narrow phase is asked of a pair at the current instant.
struct PairQuery {
    std::uint64_t instant = 0;
    bool contiguous = false;  ///< the pair was checked at the instant before, both ships present
    bool touch_only = false;  ///< a collision goes on: only "still touching?" matters
    double margin_m = 0;      ///< close quarters under this
    double best_m = INFINITY;  ///< the pair's closest approach so far
};

/// Hull to hull for a pair of ships: the contact (s.contact) or a proof that it is over the
/// margin and no closer than the best so far (s.far). Each returns its exact hull computations.
class NarrowPhase {
public:
    virtual ~NarrowPhase() = default;
    /// At the current instant.
    virtual std::size_t now(ExerciseShip& a, ExerciseShip& b, PairMemo& memo, const PairQuery& q, PairSample& s) const = 0;
    /// At another moment (bisection): the hulls placed in pa and pb; only touching matters.
    virtual std::size_t at(const ExerciseShip& a, const check::detail::Placed& pa, const ExerciseShip& b,
                           const check::detail::Placed& pb, PairSample& s) const = 0;
};

/// Every edge pair at every check: the reference.
std::unique_ptr<NarrowPhase> all_edges();
/// Bounds first, then the pruned search.
std::unique_ptr<NarrowPhase> bounded();

}  // namespace shoal::audit::detail
