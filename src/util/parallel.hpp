#pragma once
/// Work spread over threads: the audit's tracks, probe's blocks of poses.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace shoal::detail {

/// Threads for `jobs` (0: every core): never more than 4 per core (each holds a PROJ context
/// and buffers: -j 100000 would start 100,000 threads).
inline unsigned thread_count(unsigned jobs) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    return std::clamp(jobs ? jobs : cores, 1u, 4 * cores);
}

/// Runs `work(k, worker)` for k in [0, n) on `jobs` threads, never more than there is work
/// (work must not throw); `worker` is the thread's number, 0 .. threads - 1 (fewer when no
/// more threads can be started: this one then works too). Calls `tick` on
/// this thread about ten times a second meanwhile, and once at the end.
template <typename Work>
void parallel_for(std::size_t n, unsigned jobs, Work work, const std::function<void()>& tick = {}) {
    std::atomic<std::size_t> next{0};
    std::mutex mutex;
    std::condition_variable all_done;
    unsigned finished = 0;  // under mutex
    const auto threads = static_cast<unsigned>(std::clamp<std::size_t>(n, 1, std::max(1u, jobs)));
    auto finish = [&](unsigned count) {
        {
            const std::lock_guard<std::mutex> lock(mutex);
            finished += count;
        }
        all_done.notify_one();
    };
    auto worker = [&](unsigned w) {
        for (std::size_t k; (k = next.fetch_add(1)) < n;) work(k, w);
        finish(1);
    };
    std::vector<std::thread> pool;
    pool.reserve(threads);
    unsigned started = 0;
    try {
        for (; started < threads; ++started) pool.emplace_back(worker, started);
    } catch (const std::system_error&) {  // no thread to be had (nested in other threads' work): fewer do it
    }
    if (started < threads) {  // this thread as the next worker; the ones not started never finish
        worker(started);
        finish(threads - started - 1);
    }
    if (tick) {  // every tenth of a second until the work is done, woken as soon as it is
        std::unique_lock<std::mutex> lock(mutex);
        while (finished < threads) {
            lock.unlock();
            tick();
            lock.lock();
            all_done.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished >= threads; });
        }
    }
    for (auto& t : pool) t.join();
    if (tick) tick();
}

/// Items [0, weights.size()) cut into `runs` (at least 1) runs of neighbouring items of about
/// equal weight: the first item of each run, then the number of items (runs + 1 numbers, never
/// decreasing; a run may be empty). Each run a block of parallel_blocks, for work whose items
/// differ in size (tracks of a few fixes and of thousands).
inline std::vector<std::size_t> weighted_runs(const std::vector<std::size_t>& weights, std::size_t runs) {
    std::vector<std::size_t> before{0};  // the weight of the items before item k
    for (const std::size_t w : weights) before.push_back(before.back() + w);
    std::vector<std::size_t> starts;
    for (std::size_t b = 0; b < runs; ++b)
        starts.push_back(static_cast<std::size_t>(std::lower_bound(before.begin(), before.end() - 1, before.back() * b / runs) - before.begin()));
    starts.push_back(weights.size());
    return starts;
}

/// Runs `block(b, worker)` for the blocks b in [0, blocks) on `jobs` threads, as parallel_for;
/// `block` may throw. Once one throws, the blocks after the first that threw (in block order)
/// are not started, those before it still are (one of them may throw first); at the end the
/// exception of the first block that threw is thrown again, so a failure is the one a run on
/// one thread would meet.
template <typename Block>
void parallel_blocks(std::size_t blocks, unsigned jobs, Block block) {
    std::atomic<std::size_t> first_failed{blocks};
    std::vector<std::exception_ptr> failures(blocks);
    parallel_for(blocks, jobs, [&](std::size_t b, unsigned worker) {
        if (b > first_failed.load()) return;
        try {
            block(b, worker);
        } catch (...) {
            failures[b] = std::current_exception();
            for (std::size_t seen = first_failed.load(); b < seen && !first_failed.compare_exchange_weak(seen, b);) {
            }
        }
    });
    if (first_failed.load() < blocks) std::rethrow_exception(failures[first_failed.load()]);
}

}  // namespace shoal::detail
