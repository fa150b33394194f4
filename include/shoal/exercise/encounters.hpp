#pragma once
/// Ship-to-ship encounters in an exercise: several ships on one clock, each hull moved along
/// its track, every pair that comes near checked hull to hull. The paper (section 3.1) checks
/// own ship against every other ship within a threshold equal to the cell size; here every
/// pair of a whole exercise is followed through time:
///
/// - *Instants*: every fix time of every ship, and between them as many evenly spaced
///   instants as needed so that no hull point moves more than `step_m` relative to any other
///   ship from one instant to the next (the bound is the sum of the two fastest ships'
///   motions, rotation included, over the ships present in that interval).
/// - *Presence*: a ship is present from its first to its last fix, except inside a gap
///   (fixes more than `max_gap_s` apart). Ships whose spans do not overlap are never paired.
/// - *Broad phase*: a pair is *checked* at an instant when its reference points are within
///   the threshold. Candidates (pairs within threshold + a skin) come from a uniform hash grid
///   of cell threshold + skin, rebuilt only when some ship has moved half a skin since the last
///   build (a Verlet list), so most instants cost one distance per candidate pair.
/// - *Narrow phase*: exact hull-to-hull contact and clearance in local metres: segment-segment
///   distances and intersections of the edges that capsule bounds (around chunks of edges, then
///   single edges) cannot rule out, plus containment of one hull in the other. A check is
///   skipped when bounds (circles around the hulls, chunk capsules, or the last exact clearance
///   minus how far both hulls can have moved since) prove the clearance is over the margin and
///   not under the pair's closest approach so far: the results are those of computing it.
///
/// Events per pair: a *collision* is an interval of contact, its first and last contact refined
/// by bisection; *close quarters* is an interval with clearance under `ship_margin_m` that
/// never reaches contact (one that does is told by its collision). Every checked pair also gets
/// its closest approach. `find_encounters_brute` pairs every ship with every other at every
/// instant and checks every edge pair: the reference the fast path must match exactly.

#include <cstddef>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/check/hull_contact.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/track/track.hpp>

namespace shoal::audit {

struct EncounterOptions {
    double step_m = 5.0;          ///< no hull point moves more than this relative to another ship between instants
    double ship_margin_m = 20.0;  ///< close quarters: hull-to-hull clearance under this (metres, >= 0)
    /// Broad phase: pairs whose reference points are within this (metres) are checked and get a
    /// closest approach. 0 = automatic, per pair: ship_margin_m + both hull radii + step_m, so
    /// that no close quarters can be missed. A smaller value (the paper's cell size) may miss some.
    double threshold_m = 0;
    double max_gap_s = 600.0;        ///< a longer gap between two fixes of a ship: it is absent in between
    double time_tolerance_s = 0.01;  ///< first and last contact are refined by bisection to this
};

enum class EncounterKind { collision, close_quarters };
const char* to_string(EncounterKind k) noexcept;  ///< "collision", "close_quarters"

/// One ship at one moment.
struct ShipAt {
    std::size_t track = 0;          ///< index in the `tracks` given to find_encounters
    geo::LonLat position;           ///< reference point, WGS84
    double heading_deg = 0;         ///< true heading used at that moment, [0, 360)
    std::size_t fix_index = 0;      ///< index (0-based) of the last fix at or before that moment
    std::vector<geo::LonLat> hull;  ///< hull outline at that moment (closed ring)
};

struct Encounter {
    EncounterKind kind = EncounterKind::collision;
    double start_s = 0, end_s = 0;  ///< epoch seconds; a collision's are the refined first and last contact
    double min_clearance_m = 0;     ///< least hull-to-hull clearance (0 for a collision)
    double distance_m = 0;          ///< between the two reference points at that moment
    /// Collision: contact point at the first contact. Close quarters: midpoint of the two
    /// closest hull points at the least clearance.
    geo::LonLat point;
    ShipAt a, b;  ///< the two ships at that moment; a.track < b.track
};

/// The moment of least hull-to-hull clearance of a pair over the instants it was checked
/// (the earliest such moment; for a pair that collided, the refined first contact).
struct ClosestApproach {
    std::size_t a = 0, b = 0;  ///< track indices, a < b
    double time_s = 0;         ///< epoch seconds
    double clearance_m = 0;    ///< hull to hull (0: contact)
    double distance_m = 0;     ///< between the reference points at that moment
    geo::LonLat a_position, b_position;
};

struct EncounterResult {
    std::vector<Encounter> events;             ///< by (start, a, b)
    std::vector<ClosestApproach> approaches;   ///< by (a, b)
    std::size_t instants = 0;       ///< instants processed (fix times and the instants between them)
    std::size_t pairs_checked = 0;  ///< (pair, instant) within the threshold
    std::size_t hull_checks = 0;    ///< exact hull-to-hull computations (bisection included)
    std::size_t rebuilds = 0;       ///< broad-phase grid builds (0 for the brute force)
    double threshold_m = 0;         ///< the threshold used (the largest over pairs when automatic)
    double setup_s = 0;             ///< wall-clock seconds projecting the tracks and preparing the hulls
    double sweep_s = 0;             ///< wall-clock seconds of the instants, events and approaches
};

/// Finds the encounters between the ships of one exercise. `tracks` have resolved headings
/// (track::resolve_headings) and strictly increasing fix times; `hulls[k]` is track k's hull.
/// Deterministic: events by (start, a, b), approaches by (a, b). Throws UsageError on bad
/// options or mismatched sizes, InputError on a fix that cannot be projected or is unusable.
EncounterResult find_encounters(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                                const geo::LocalFrame& frame, const EncounterOptions& options);

/// The reference: the same instants and the same events, but every ship paired with every
/// other at every instant and every hull edge tested against every other. Quadratic; for
/// tests and benchmarks.
EncounterResult find_encounters_brute(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                                      const geo::LocalFrame& frame, const EncounterOptions& options);

/// Hull-to-hull contact, in check/ since it is geometry; here too for callers of old.
using check::HullContact;
using check::hull_contact;

}  // namespace shoal::audit
