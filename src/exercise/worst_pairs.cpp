#include "exercise/worst_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace shoal::audit {

bool WorstPairs::Entry::operator<(const Entry& o) const noexcept {
    return std::tie(unapproached, clearance_m, distance_m, pair) < std::tie(o.unapproached, o.clearance_m, o.distance_m, o.pair);
}

void WorstPairs::offer(std::size_t a, std::size_t b, double clearance_m, double distance_m) {
    ++m_offered;
    if (m_per_ship == 0) return;
    Entry e;
    e.unapproached = !std::isfinite(clearance_m);
    e.clearance_m = e.unapproached ? 0 : clearance_m;
    e.distance_m = std::isfinite(distance_m) ? distance_m : INFINITY;
    e.pair = {a, b};
    add(a, e);
    add(b, e);
}

void WorstPairs::add(std::size_t ship, const Entry& e) {
    std::vector<Entry>& heap = m_worst[ship];
    if (heap.size() == m_per_ship) {
        if (!(e < heap.front())) return;  // no worse than the least bad it holds
        std::pop_heap(heap.begin(), heap.end());
        release(heap.back().pair);
        heap.pop_back();
    }
    heap.push_back(e);
    std::push_heap(heap.begin(), heap.end());
    ++m_held[e.pair];
}

void WorstPairs::release(const Pair& p) {
    const auto it = m_held.find(p);
    if (it != m_held.end() && --it->second == 0) m_held.erase(it);
}

}  // namespace shoal::audit
