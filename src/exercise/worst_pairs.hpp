#pragma once
/// Which pairs of an exercise a report lists when each ship lists at most `per_ship` others:
/// the pairs a ship came closest to. A crowd (2,000 ships in 1 km²: two million pairs within
/// the COLREG range, 13,000 collisions) is counted whole but listed like this, so the report
/// grows with the ships, not with the square of them.
///
/// - *Rank* of a pair (the smaller, the worse): pairs that came within the hull-to-hull
///   threshold (a finite clearance) before those that did not; then the least hull-to-hull
///   clearance (0: a collision); then the distance between the reference points at that
///   moment (for a collision the nearer, the deeper; for a pair that never came within the
///   threshold, its closest distance); then the track indices.
/// - A pair is *listed* when it is among the `per_ship` worst of either of its ships. So every
///   ship's `per_ship` worst pairs are listed, and at most `per_ship` x ships pairs are.
/// - `per_ship` 0: every pair is listed.
///
/// Pairs are offered one at a time; memory holds the listed pairs so far only (a pair pushed
/// out of both its ships' lists is forgotten), whatever the number offered.

#include <cstddef>
#include <map>
#include <utility>
#include <vector>

namespace shoal::audit {

class WorstPairs {
public:
    using Pair = std::pair<std::size_t, std::size_t>;  ///< track indices (a, b), a < b

    explicit WorstPairs(std::size_t per_ship) : m_per_ship(per_ship) {}

    /// Offers pair (a, b), a < b, once: its least hull-to-hull clearance (NaN: it never came
    /// within the threshold) and the distance between the reference points then (metres).
    void offer(std::size_t a, std::size_t b, double clearance_m, double distance_m);

    /// Whether pair (a, b) is listed so far (with per_ship 0: always).
    bool listed(std::size_t a, std::size_t b) const { return m_per_ship == 0 || m_held.count({a, b}) > 0; }
    /// Pairs listed so far (only for per_ship > 0).
    std::size_t size() const noexcept { return m_held.size(); }
    std::size_t offered() const noexcept { return m_offered; }

private:
    struct Entry {
        bool unapproached = false;  ///< never within the threshold: ranks after every pair that was
        double clearance_m = 0, distance_m = 0;
        Pair pair;
        bool operator<(const Entry& o) const noexcept;
    };
    void add(std::size_t ship, const Entry& e);
    void release(const Pair& p);

    std::size_t m_per_ship;
    std::size_t m_offered = 0;
    std::map<std::size_t, std::vector<Entry>> m_worst;  ///< per ship: a max-heap of its worst pairs (the top: the least bad)
    std::map<Pair, int> m_held;  ///< listed pairs: in how many ships' lists (1 or 2)
};

}  // namespace shoal::audit
