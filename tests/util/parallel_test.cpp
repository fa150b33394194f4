// detail::parallel_for and parallel_blocks: every item done once, on as many threads as asked
// (never more than there is work), the progress tick called meanwhile and once at the end, and
// the failure of the first failing block thrown again whatever the threads.
#include "util/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

TEST(ParallelFor, DoesEachItemOnceOnAtMostTheThreadsAsked) {
    for (const std::size_t n : {0u, 1u, 2u, 7u, 1000u})
        for (const unsigned jobs : {1u, 2u, 3u, 16u}) {
            std::vector<std::atomic<int>> done(n);
            std::vector<std::atomic<int>> by_worker(jobs + 1);
            std::atomic<int> ticks{0};
            shoal::detail::parallel_for(
                n, jobs,
                [&](std::size_t k, unsigned w) {
                    done[k].fetch_add(1);
                    by_worker.at(w).fetch_add(1);
                },
                [&] { ticks.fetch_add(1); });
            for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(done[k].load(), 1) << n << " items, " << jobs << " jobs, item " << k;
            unsigned workers = 0;
            for (unsigned w = 0; w <= jobs; ++w) workers += by_worker[w].load() > 0;
            EXPECT_LE(workers, std::min<std::size_t>(std::max<std::size_t>(n, 1), jobs));
            EXPECT_EQ(by_worker[jobs].load(), 0);  // worker numbers are 0 .. threads - 1
            EXPECT_GE(ticks.load(), 1);            // at least the one at the end
        }
}

TEST(ParallelFor, TicksWhileWorkIsUnderWayAndOnceAfter) {
    // The work waits until it has seen two ticks: the tick must come while it runs (a loop that
    // only ticked at the end would never let it finish, and the test would hang, not pass).
    std::atomic<int> ticks{0};
    shoal::detail::parallel_for(
        1, 1,
        [&](std::size_t, unsigned) {
            while (ticks.load() < 2) std::this_thread::yield();
        },
        [&] { ticks.fetch_add(1); });
    EXPECT_GE(ticks.load(), 3);
}

TEST(ParallelBlocks, ThrowsTheFirstFailingBlocksErrorOnAnyThreads) {
    for (const unsigned jobs : {1u, 2u, 4u}) {
        std::atomic<int> ran{0};
        try {
            shoal::detail::parallel_blocks(50, jobs, [&](std::size_t b, unsigned) {
                ran.fetch_add(1);
                if (b == 17 || b == 30 || b == 44) throw std::runtime_error("block " + std::to_string(b));
            });
            ADD_FAILURE() << "nothing thrown";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "block 17") << jobs << " jobs";
        }
        EXPECT_GE(ran.load(), 18);  // every block up to the first failure ran
    }
}

}  // namespace
