#pragma once
/// The broad phase of an exercise (internal to src/exercise): at each instant, the pairs of
/// present ships whose reference points are within the pair's threshold, the only pairs the
/// narrow phase (hull to hull) looks at. Two implementations of one interface: a uniform hash
/// grid with a Verlet list (find_encounters) and every pair (find_encounters_brute, the
/// reference). Both give the same pairs in the same order.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::audit::detail {

/// The threshold of each pair: a fixed one, or (automatic) base_m plus both hull radii.
struct PairThresholds {
    bool automatic = true;
    double fixed_m = 0;         ///< when not automatic
    double base_m = 0;          ///< when automatic: ship margin + step
    std::vector<double> radius;  ///< per ship: hull radius
    /// The pair's threshold, squared.
    double squared(std::uint32_t a, std::uint32_t b) const noexcept {
        const double t = automatic ? base_m + radius[a] + radius[b] : fixed_m;
        return t * t;
    }
    /// The largest threshold over all pairs.
    double largest_m() const noexcept;
};

/// The pairs of ships (a < b) met so far, numbered 0, 1, ... in the order first met.
class PairIndex {
public:
    std::uint32_t id(std::uint32_t a, std::uint32_t b);
    std::size_t size() const noexcept { return m_pairs.size(); }
    std::pair<std::uint32_t, std::uint32_t> pair(std::uint32_t id) const { return m_pairs[id]; }

private:
    std::unordered_map<std::uint64_t, std::uint32_t> m_ids;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> m_pairs;
};

class BroadPhase {
public:
    virtual ~BroadPhase() = default;
    /// The ids (in `index`) of the pairs of ships in `present` (any order) whose positions
    /// (`position[ship]`, local metres) are within the pair's threshold, by (a, b), into `out`.
    /// Called once an instant; `joined`: some ship became present since the last call.
    virtual void near_pairs(const std::vector<std::uint32_t>& present, const std::vector<geo::XY>& position, bool joined,
                            PairIndex& index, std::vector<std::uint32_t>& out) = 0;
    /// Candidate lists built so far (0 for every pair).
    virtual std::size_t rebuilds() const noexcept { return 0; }
};

/// Every pair of present ships at every instant: the reference.
std::unique_ptr<BroadPhase> all_pairs(PairThresholds thresholds);

/// Candidates (pairs within threshold + `skin_m`) from a uniform hash grid of cell the largest
/// threshold + skin, rebuilt only when a ship has joined or some ship has moved half a skin
/// since the last build (a Verlet list): most instants cost one distance per candidate.
std::unique_ptr<BroadPhase> hash_grid(PairThresholds thresholds, double skin_m);

}  // namespace shoal::audit::detail
