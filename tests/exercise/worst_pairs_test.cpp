// Listing the worst pairs per ship (worst_pairs.hpp): the pairs kept against a brute force
// (every ship's pairs sorted), and an audit of a crowd with a cap against the same audit with
// none: the same counts, the listed pairs those the brute force picks, their events, closest
// approaches and situations exactly the uncapped ones, and the output bounded by the ships.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <shoal/audit/audit.hpp>
#include "exercise/worst_pairs.hpp"
#include <shoal/grid/grid_cache.hpp>

#include "audit/solent_grid.hpp"
#include "test_support.hpp"

namespace shoal::audit {
namespace {

using Pair = WorstPairs::Pair;

/// A pair as the brute force ranks it (worst_pairs.hpp: approached first, then clearance,
/// then distance, then the tracks).
struct Ranked {
    Pair pair;
    double clearance_m, distance_m;
    auto key() const { return std::make_tuple(!std::isfinite(clearance_m), std::isfinite(clearance_m) ? clearance_m : 0.0, distance_m, pair); }
};

/// The pairs in the `per_ship` worst of either of their ships: every ship's pairs sorted.
std::set<Pair> brute_force(const std::vector<Ranked>& pairs, std::size_t per_ship) {
    std::map<std::size_t, std::vector<Ranked>> by_ship;
    for (const Ranked& r : pairs) {
        by_ship[r.pair.first].push_back(r);
        by_ship[r.pair.second].push_back(r);
    }
    std::set<Pair> out;
    for (auto& [ship, list] : by_ship) {
        std::sort(list.begin(), list.end(), [](const Ranked& x, const Ranked& y) { return x.key() < y.key(); });
        for (std::size_t k = 0; k < list.size() && k < per_ship; ++k) out.insert(list[k].pair);
    }
    return out;
}

TEST(WorstPairs, EachShipKeepsItsWorstPairsAsSortingEveryShipsPairsWould) {
    std::mt19937 rng(14);
    for (const std::size_t ships : {2u, 7u, 40u}) {
        std::vector<Ranked> pairs;
        for (std::size_t a = 0; a < ships; ++a)
            for (std::size_t b = a + 1; b < ships; ++b) {
                if (rng() % 5 == 0) continue;  // not every pair meets
                const unsigned kind = rng() % 3;  // a collision, within the threshold, or a situation only
                const double clearance = kind == 0 ? 0.0 : kind == 1 ? static_cast<double>(rng() % 40) : NAN;
                pairs.push_back({{a, b}, clearance, static_cast<double>(rng() % 500)});  // ties, on purpose
            }
        std::shuffle(pairs.begin(), pairs.end(), rng);
        for (const std::size_t per_ship : {1u, 3u, 10u, 100u}) {
            WorstPairs worst(per_ship);
            for (const Ranked& r : pairs) worst.offer(r.pair.first, r.pair.second, r.clearance_m, r.distance_m);
            const std::set<Pair> expected = brute_force(pairs, per_ship);
            std::set<Pair> listed;
            for (const Ranked& r : pairs)
                if (worst.listed(r.pair.first, r.pair.second)) listed.insert(r.pair);
            EXPECT_EQ(listed, expected) << ships << " ships, " << per_ship << " per ship";
            EXPECT_EQ(worst.size(), expected.size());
            EXPECT_LE(worst.size(), per_ship * ships);
            EXPECT_EQ(worst.offered(), pairs.size());
        }
        WorstPairs all(0);
        for (const Ranked& r : pairs) all.offer(r.pair.first, r.pair.second, r.clearance_m, r.distance_m);
        for (const Ranked& r : pairs) EXPECT_TRUE(all.listed(r.pair.first, r.pair.second)) << "0: no limit";
    }
}

constexpr double t0 = 1714557600;  // 2024-05-01T10:00:00Z
constexpr double lat0 = 50.70, lon0 = -0.98;  // open water east of the Isle of Wight
constexpr double m_per_deg_lat = 111195.0;

/// `ships` vessels at random in a `side_m` square, 2-8 kn on random courses, 7 fixes 10 s
/// apart (as scripts/make-crowd.py, without the bouncing).
std::vector<track::Track> crowd(std::size_t ships, double side_m) {
    std::mt19937 rng(2000);
    std::uniform_real_distribution<double> u(0, 1);
    const double m_per_deg_lon = m_per_deg_lat * std::cos(lat0 * M_PI / 180);
    std::vector<track::Track> out;
    for (std::size_t k = 0; k < ships; ++k) {
        track::Track t;
        t.id = std::to_string(200000000 + k);
        t.file = "crowd.csv";
        double x = (u(rng) - 0.5) * side_m, y = (u(rng) - 0.5) * side_m;
        const double course = 360 * u(rng), kn = 2 + 6 * u(rng);
        for (int i = 0; i < 7; ++i) {
            track::Fix f;
            f.time_s = t0 + 10 * i;
            f.position = {lon0 + x / m_per_deg_lon, lat0 + y / m_per_deg_lat};
            f.heading_deg = f.cog_deg = course;
            f.sog_kn = kn;
            f.line = k * 7 + static_cast<std::size_t>(i) + 2;
            t.fixes.push_back(f);
            x += kn * 0.514444 * 10 * std::sin(course * M_PI / 180);
            y += kn * 0.514444 * 10 * std::cos(course * M_PI / 180);
        }
        out.push_back(std::move(t));
    }
    return out;
}

class CrowdAudit : public ::testing::Test {
protected:
    static void SetUpTestSuite() { s_grid = &test::solent_grid(); }
    static AuditResult run(std::size_t per_ship) {
        AuditOptions o;
        o.jobs = 2;
        o.encounters = true;
        o.max_encounters_per_ship = per_ship;
        return audit_tracks(crowd(ships, 300), *s_grid, hull::Hull::from_dimensions({15, 5, 3, 3}), "test hull", o);
    }
    static constexpr std::size_t ships = 40;
    static const grid::CoastGrid* s_grid;
};
const grid::CoastGrid* CrowdAudit::s_grid = nullptr;

TEST_F(CrowdAudit, ACapListsEachShipsWorstPairsWithTheirEventsAndCountsEveryOne) {
    const AuditResult all = run(0), capped = run(3);
    ASSERT_EQ(all.tracks.size(), ships);
    // The crowd is one: every ship meets more than 3 others, with collisions, close quarters
    // and pairs only within the COLREG range.
    ASSERT_GT(all.encounters.approaches.size(), 3 * ships);
    ASSERT_GT(all.collisions, 3u);
    ASSERT_GT(all.close_quarters, 3u);
    ASSERT_TRUE(std::any_of(all.encounters.approaches.begin(), all.encounters.approaches.end(),
                            [](const ClosestApproach& a) { return std::isnan(a.clearance_m); }));
    EXPECT_EQ(all.unlisted.pairs, 0u);
    EXPECT_EQ(all.unlisted.collisions + all.unlisted.close_quarters + all.unlisted.situations, 0u);
    EXPECT_EQ(all.encounters.events.size(), all.collisions + all.close_quarters);

    // The independent answer: every ship's pairs of the uncapped run, sorted.
    std::vector<Ranked> ranked;
    for (const ClosestApproach& a : all.encounters.approaches) ranked.push_back({{a.a, a.b}, a.clearance_m, a.distance_m});
    const std::set<Pair> expected = brute_force(ranked, 3);
    ASSERT_LT(expected.size(), all.encounters.approaches.size()) << "the cap must leave some out";
    const auto is_expected = [&](std::size_t a, std::size_t b) { return expected.count({a, b}) > 0; };

    // Approaches, situations and events: exactly the uncapped ones of the listed pairs, in order.
    std::vector<Pair> got, want;
    for (const ClosestApproach& a : capped.encounters.approaches) got.push_back({a.a, a.b});
    for (const ClosestApproach& a : all.encounters.approaches)
        if (is_expected(a.a, a.b)) want.push_back({a.a, a.b});
    EXPECT_EQ(got, want);
    for (std::size_t k = 0, j = 0; k < all.encounters.approaches.size() && j < capped.encounters.approaches.size(); ++k) {
        const ClosestApproach& a = all.encounters.approaches[k];
        if (!is_expected(a.a, a.b)) continue;
        const ClosestApproach& c = capped.encounters.approaches[j++];
        EXPECT_EQ(c.time_s, a.time_s);
        EXPECT_TRUE(c.clearance_m == a.clearance_m || (std::isnan(c.clearance_m) && std::isnan(a.clearance_m)));
        EXPECT_EQ(c.distance_m, a.distance_m);
    }
    std::vector<std::tuple<Pair, double, double>> got_s, want_s;
    for (const ColregEncounter& c : capped.situations) got_s.emplace_back(Pair{c.a, c.b}, c.start_s, c.closest_m);
    for (const ColregEncounter& c : all.situations)
        if (is_expected(c.a, c.b)) want_s.emplace_back(Pair{c.a, c.b}, c.start_s, c.closest_m);
    EXPECT_EQ(got_s, want_s);
    std::vector<std::tuple<double, double, std::size_t, std::size_t, EncounterKind>> got_e, want_e;
    for (const Encounter& e : capped.encounters.events) got_e.emplace_back(e.start_s, e.end_s, e.a.track, e.b.track, e.kind);
    std::size_t unlisted_collisions = 0, unlisted_close_quarters = 0;
    for (const Encounter& e : all.encounters.events) {
        if (is_expected(e.a.track, e.b.track)) want_e.emplace_back(e.start_s, e.end_s, e.a.track, e.b.track, e.kind);
        else ++(e.kind == EncounterKind::collision ? unlisted_collisions : unlisted_close_quarters);
    }
    EXPECT_EQ(got_e, want_e);

    // Every one is counted: the totals are the uncapped run's, and what is left out is said.
    EXPECT_EQ(capped.collisions, all.collisions);
    EXPECT_EQ(capped.close_quarters, all.close_quarters);
    EXPECT_EQ(capped.situations_found(), all.situations.size());
    EXPECT_EQ(capped.unlisted.pairs, all.encounters.approaches.size() - expected.size());
    EXPECT_EQ(capped.unlisted.collisions, unlisted_collisions);
    EXPECT_EQ(capped.unlisted.close_quarters, unlisted_close_quarters);
    EXPECT_EQ(capped.unlisted.situations, all.situations.size() - capped.situations.size());
    EXPECT_GT(capped.unlisted.pairs, 0u);
    const auto warned = std::find_if(capped.warnings.begin(), capped.warnings.end(),
                                     [](const std::string& w) { return w.find("AuditOptions::max_encounters_per_ship") != std::string::npos; });
    ASSERT_NE(warned, capped.warnings.end());
    EXPECT_NE(warned->find(std::to_string(capped.unlisted.pairs) + " of " + std::to_string(all.encounters.approaches.size()) + " pairs"),
              std::string::npos)
        << *warned;

    // Bounded by the ships: at most 3 pairs per ship, and a ship's events only those of its pairs.
    EXPECT_LE(capped.encounters.approaches.size(), 3 * ships);
    EXPECT_LE(capped.situations.size(), 3 * ships);
}


TEST_F(CrowdAudit, AnAssessmentOfCloseQuartersTimeSaysWhenTheCapLeftEncountersUnscored) {
    const Assessment a = Assessment::parse(
        R"({"criteria": [{"id": "cq", "kind": "close_quarters_time", "limit": 0, "penalty": 1, "per": "second"}]})", "cq.json");
    AuditOptions o;
    o.jobs = 2;
    o.encounters = true;
    o.assessment = &a;
    const auto unscored = [](const AuditResult& r) {
        return std::count_if(r.warnings.begin(), r.warnings.end(),
                             [](const std::string& w) { return w.find("was not scored") != std::string::npos; });
    };
    o.max_encounters_per_ship = 3;
    const AuditResult capped = audit_tracks(crowd(ships, 300), *s_grid, hull::Hull::from_dimensions({15, 5, 3, 3}), "test hull", o);
    ASSERT_GT(capped.unlisted.close_quarters, 0u);
    EXPECT_EQ(unscored(capped), 1) << "the capped run says its scores leave close quarters out";
    o.max_encounters_per_ship = 0;
    const AuditResult all = audit_tracks(crowd(ships, 300), *s_grid, hull::Hull::from_dimensions({15, 5, 3, 3}), "test hull", o);
    EXPECT_EQ(unscored(all), 0);
    // Every close-quarters encounter over the limit of 0 s is a breach of each trainee in it.
    std::size_t breaches = 0;
    for (const Encounter& e : all.encounters.events) breaches += e.kind == EncounterKind::close_quarters && e.end_s > e.start_s ? 2 : 0;
    EXPECT_EQ(all.assessment.breaches.size(), breaches);
}

}  // namespace
}  // namespace shoal::audit
