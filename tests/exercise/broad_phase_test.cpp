// The broad phase: the hash grid (with its Verlet list) and every pair, against a direct
// O(n^2) scan in the test, on many random fleets that move, jump, join and leave.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "exercise/broad_phase.hpp"

namespace shoal::audit::detail {
namespace {

using geo::XY;
using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// The pairs the broad phase reported, by ship.
Pairs named(const std::vector<std::uint32_t>& ids, const PairIndex& index) {
    Pairs out;
    for (const std::uint32_t id : ids) out.push_back(index.pair(id));
    return out;
}

/// Every pair of present ships within its threshold, by (a, b): the answer.
Pairs direct(const std::vector<std::uint32_t>& present, const std::vector<XY>& pos, const PairThresholds& th) {
    Pairs out;
    for (const std::uint32_t a : present)
        for (const std::uint32_t b : present) {
            if (a >= b) continue;
            const double t = th.automatic ? th.base_m + th.radius[a] + th.radius[b] : th.fixed_m;
            const double dx = pos[a].x - pos[b].x, dy = pos[a].y - pos[b].y;
            if (dx * dx + dy * dy <= t * t) out.emplace_back(a, b);
        }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(BroadPhase, HashGridAndAllPairsGiveTheDirectAnswerOnRandomFleets) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t instants = 0, found = 0, rebuilds = 0;
    for (int fleet = 0; fleet < 60; ++fleet) {
        const std::size_t n = 2 + rng() % 80;
        const double side = 300 + 3000 * u(rng);
        PairThresholds th;
        th.automatic = fleet % 3 != 0;
        th.fixed_m = 50 + 200 * u(rng);
        th.base_m = 25;
        for (std::size_t k = 0; k < n; ++k) th.radius.push_back(5 + 100 * u(rng));
        const double skin = std::max(10.0, 0.5 * th.largest_m());
        const auto grid = hash_grid(th, skin);
        const auto all = all_pairs(th);
        PairIndex grid_index, all_index;
        std::vector<XY> pos(n);
        std::vector<bool> present(n, false);
        for (std::size_t k = 0; k < n; ++k) pos[k] = {side * u(rng), side * u(rng)};
        std::vector<std::uint32_t> ids;
        for (int step = 0; step < 80; ++step) {
            bool joined = step == 0;
            for (std::size_t k = 0; k < n; ++k) {
                if (step == 0) present[k] = u(rng) < 0.8;
                else if (u(rng) < 0.02) {
                    joined |= !present[k];
                    present[k] = !present[k];
                }
                // Mostly small moves; now and then a jump larger than the skin.
                const double reach = u(rng) < 0.01 ? 2 * skin : 0.1 * skin;
                pos[k] = pos[k] + XY{reach * (u(rng) - 0.5), reach * (u(rng) - 0.5)};
            }
            std::vector<std::uint32_t> active;
            for (std::uint32_t k = 0; k < n; ++k)
                if (present[k]) active.push_back(k);
            std::shuffle(active.begin(), active.end(), rng);
            const Pairs want = direct(active, pos, th);
            grid->near_pairs(active, pos, joined, grid_index, ids);
            ASSERT_EQ(named(ids, grid_index), want) << "hash grid, fleet " << fleet << " step " << step;
            all->near_pairs(active, pos, joined, all_index, ids);
            ASSERT_EQ(named(ids, all_index), want) << "all pairs, fleet " << fleet << " step " << step;
            ++instants;
            found += want.size();
        }
        rebuilds += grid->rebuilds();
        EXPECT_EQ(all->rebuilds(), 0u);
    }
    EXPECT_GT(found, 1000u);
    // The Verlet list is reused between builds (not rebuilt every instant).
    EXPECT_LT(rebuilds, instants / 2);
    EXPECT_GT(rebuilds, 60u);
}

TEST(BroadPhase, PairIdsAreDenseAndStable) {
    PairIndex index;
    EXPECT_EQ(index.id(3, 9), 0u);
    EXPECT_EQ(index.id(1, 2), 1u);
    EXPECT_EQ(index.id(3, 9), 0u);
    EXPECT_EQ(index.size(), 2u);
    EXPECT_EQ(index.pair(1), (std::pair<std::uint32_t, std::uint32_t>{1, 2}));
}

}  // namespace
}  // namespace shoal::audit::detail
