// The broad phase of an exercise (see broad_phase.hpp): every pair, and the hash grid.
#include "exercise/broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace shoal::audit::detail {

using geo::XY;

namespace {

double dist2(XY a, XY b) { return geo::norm2(b - a); }

class AllPairs final : public BroadPhase {
public:
    explicit AllPairs(PairThresholds t) : m_thresholds(std::move(t)) {}

    void near_pairs(const std::vector<std::uint32_t>& present, const std::vector<XY>& position, bool /*joined*/, PairIndex& index,
                    std::vector<std::uint32_t>& out) override {
        out.clear();
        m_order.assign(present.begin(), present.end());
        std::sort(m_order.begin(), m_order.end());
        for (std::size_t x = 0; x < m_order.size(); ++x)
            for (std::size_t y = x + 1; y < m_order.size(); ++y) {
                const std::uint32_t a = m_order[x], b = m_order[y];
                if (dist2(position[a], position[b]) <= m_thresholds.squared(a, b)) out.push_back(index.id(a, b));
            }
    }

private:
    PairThresholds m_thresholds;
    std::vector<std::uint32_t> m_order;
};

class HashGrid final : public BroadPhase {
public:
    HashGrid(PairThresholds t, double skin_m) : m_thresholds(std::move(t)), m_skin(skin_m), m_cell(m_thresholds.largest_m() + skin_m) {}

    void near_pairs(const std::vector<std::uint32_t>& present, const std::vector<XY>& position, bool joined, PairIndex& index,
                    std::vector<std::uint32_t>& out) override {
        out.clear();
        ++m_call;
        if (m_built_pos.size() < position.size()) {
            m_built_pos.resize(position.size());
            m_seen.resize(position.size(), 0);
        }
        double moved2 = 0;
        for (const std::uint32_t k : present) {
            m_seen[k] = m_call;
            moved2 = std::max(moved2, dist2(position[k], m_built_pos[k]));
        }
        if (joined || !m_built || moved2 > (m_skin / 2) * (m_skin / 2)) build(present, position, index);
        for (const Candidate& c : m_candidates) {
            if (m_seen[c.a] != m_call || m_seen[c.b] != m_call) continue;  // one has left since the build
            if (dist2(position[c.a], position[c.b]) <= c.threshold2) out.push_back(c.id);
        }
    }

    std::size_t rebuilds() const noexcept override { return m_rebuilds; }

private:
    struct Candidate {
        std::uint32_t a = 0, b = 0, id = 0;
        double threshold2 = 0;
    };

    /// Candidate pairs: within threshold + skin now.
    void build(const std::vector<std::uint32_t>& present, const std::vector<XY>& position, PairIndex& index) {
        ++m_rebuilds;
        m_built = true;
        m_candidates.clear();
        const std::size_t n = present.size();
        std::size_t buckets = 1;
        while (buckets < 2 * n) buckets *= 2;
        struct Entry {
            std::int64_t cx, cy;
            std::uint32_t ship;
        };
        auto bucket_of = [&](std::int64_t cx, std::int64_t cy) {
            const std::uint64_t h = static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(cy) * 0xC2B2AE3D27D4EB4Full;
            return static_cast<std::size_t>((h ^ (h >> 29)) & (buckets - 1));
        };
        std::vector<Entry> entries(n);
        std::vector<std::size_t> start(buckets + 1, 0);
        std::vector<std::size_t> bucket(n);
        for (std::size_t k = 0; k < n; ++k) {
            const XY p = position[present[k]];
            m_built_pos[present[k]] = p;
            const Entry e{static_cast<std::int64_t>(std::floor(p.x / m_cell)), static_cast<std::int64_t>(std::floor(p.y / m_cell)), present[k]};
            bucket[k] = bucket_of(e.cx, e.cy);
            ++start[bucket[k] + 1];
            entries[k] = e;
        }
        for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
        std::vector<Entry> sorted(n);
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (std::size_t k = 0; k < n; ++k) sorted[fill[bucket[k]]++] = entries[k];
        for (const Entry& e : sorted) {
            const XY p = position[e.ship];
            for (std::int64_t dx = -1; dx <= 1; ++dx)
                for (std::int64_t dy = -1; dy <= 1; ++dy) {
                    const std::int64_t cx = e.cx + dx, cy = e.cy + dy;
                    const std::size_t b = bucket_of(cx, cy);
                    for (std::size_t q = start[b]; q < start[b + 1]; ++q) {
                        const Entry& o = sorted[q];
                        if (o.ship <= e.ship || o.cx != cx || o.cy != cy) continue;
                        const double t2 = m_thresholds.squared(e.ship, o.ship);
                        const double t = std::sqrt(t2) + m_skin;
                        if (dist2(p, position[o.ship]) <= t * t) m_candidates.push_back({e.ship, o.ship, 0, t2});
                    }
                }
        }
        std::sort(m_candidates.begin(), m_candidates.end(),
                  [](const Candidate& x, const Candidate& y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
        for (Candidate& c : m_candidates) c.id = index.id(c.a, c.b);
    }

    PairThresholds m_thresholds;
    double m_skin = 0, m_cell = 0;
    bool m_built = false;
    std::size_t m_rebuilds = 0;
    std::uint64_t m_call = 0;
    std::vector<XY> m_built_pos;        ///< per ship: its position at the last build
    std::vector<std::uint64_t> m_seen;  ///< per ship: the last call it was present at
    std::vector<Candidate> m_candidates;
};

}  // namespace

double PairThresholds::largest_m() const noexcept {
    if (!automatic) return fixed_m;
    double r = 0;
    for (const double x : radius) r = std::max(r, x);
    return base_m + 2 * r;
}

std::uint32_t PairIndex::id(std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = (std::uint64_t{a} << 32) | b;
    auto [it, fresh] = m_ids.try_emplace(key, static_cast<std::uint32_t>(m_pairs.size()));
    if (fresh) m_pairs.emplace_back(a, b);
    return it->second;
}

std::unique_ptr<BroadPhase> all_pairs(PairThresholds thresholds) { return std::make_unique<AllPairs>(std::move(thresholds)); }

std::unique_ptr<BroadPhase> hash_grid(PairThresholds thresholds, double skin_m) {
    return std::make_unique<HashGrid>(std::move(thresholds), skin_m);
}

}  // namespace shoal::audit::detail
