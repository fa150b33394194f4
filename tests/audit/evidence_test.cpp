// The real world's traffic model (audit/evidence.hpp): which stays are evidence of a berth, and
// the places it learns, against answers worked out by hand; and a brute-force count of the
// evidence on many random stays.
#include <gtest/gtest.h>

#include <random>

#include <shoal/audit/evidence.hpp>

namespace shoal::audit {
namespace {

Stay stay_at(double x, double y, double start_s, double end_s, std::size_t visit = 0) {
    Stay s;
    s.local = {x, y};
    s.start_s = start_s;
    s.end_s = end_s;
    s.visit = visit;
    return s;
}

geo::LocalFrame frame() { return geo::LocalFrame::transverse_mercator({10.0, 55.0}); }

TEST(Traffic, ResponderArrivingDuringAStayIsNoBerthButEarlierAndLaterStaysAre) {
    // A vessel lies at (0, 0) from t = 1000 to 5000. A tug comes alongside at 2000 (during:
    // a responder, no evidence); another vessel lay 150 m off before it (500-900: evidence);
    // one more comes after it left (6000-7000: evidence); one 400 m off is beyond the 300 m radius.
    TrackResult a, tug, before, after, far;
    a.stays = {stay_at(0, 0, 1000, 5000)};
    tug.stays = {stay_at(30, 20, 2000, 4000)};
    before.stays = {stay_at(150, 0, 500, 900)};
    after.stays = {stay_at(0, 100, 6000, 7000)};
    far.stays = {stay_at(400, 0, 0, 9000)};
    const Traffic t = learn_traffic({&a, &tug, &before, &after, &far}, {"A", "TUG", "B", "C", "FAR"}, frame(), {});
    EXPECT_EQ(t.berth_stays[0][0], 2u) << "before and after count, the tug does not";
    EXPECT_EQ(t.own_visits[0][0], 0u);
    // The tug's own stay: A began before it (and lies within 300 m), B and C too (B ended
    // before; C began after the tug left): three.
    EXPECT_EQ(t.berth_stays[1][0], 3u);
    // One learned berth: A, the tug, B and C within the radius of one another (single
    // linkage), four visits of four vessels; FAR is 400 m from A but 250 m from B: joined too.
    ASSERT_EQ(t.places.size(), 1u);
    EXPECT_EQ(t.places[0].kind, LearnedPlace::Kind::berth);
    EXPECT_EQ(t.places[0].vessels, 5u);
    EXPECT_EQ(t.places[0].count, 5u);
    EXPECT_DOUBLE_EQ(t.places[0].first_s, 0);
    EXPECT_DOUBLE_EQ(t.places[0].last_s, 9000);
}

TEST(Traffic, AStayBrokenByJitterIsOneVisitAndNoEvidenceForItself) {
    // One vessel, aground: its stay broken in three by GPS jitter, one visit. No berth.
    TrackResult a;
    a.stays = {stay_at(0, 0, 0, 600, 0), stay_at(5, 5, 620, 1800, 0), stay_at(2, 1, 1810, 9000, 0)};
    const Traffic t = learn_traffic({&a}, {"A"}, frame(), {});
    EXPECT_EQ(t.berth_stays[0], (std::vector<std::size_t>{0, 0, 0}));
    EXPECT_TRUE(t.places.empty()) << "one visit is no place vessels come to";
    // A ferry: the same pier on three visits (it went away between). Each call is evidence for the others.
    TrackResult ferry;
    ferry.stays = {stay_at(0, 0, 0, 900, 0), stay_at(10, 0, 3600, 4500, 1), stay_at(0, 10, 7200, 8100, 2)};
    const Traffic f = learn_traffic({&ferry}, {"FERRY"}, frame(), {});
    EXPECT_EQ(f.berth_stays[0], (std::vector<std::size_t>{2, 2, 2}));
    EXPECT_EQ(f.own_visits[0], (std::vector<std::size_t>{2, 2, 2})) << "all its own";
    ASSERT_EQ(f.places.size(), 1u);
    EXPECT_EQ(f.places[0].vessels, 1u);
    EXPECT_EQ(f.places[0].count, 3u);
    EXPECT_NEAR(f.places[0].hours, 0.75, 1e-12);
}

TEST(Traffic, WaterTheChartLacksIsCountedPerCellAndVessel) {
    TrackResult a, b;
    a.over_land = {{10, 10}, {20, 20}, {260, 10}};
    b.over_land = {{30, 30}};
    const Traffic t = learn_traffic({&a, &b}, {"A", "B"}, frame(), {});
    ASSERT_EQ(t.places.size(), 2u);
    EXPECT_EQ(t.places[0].kind, LearnedPlace::Kind::water);
    EXPECT_EQ(t.places[0].count, 3u) << "cell [0, 250) x [0, 250): two fixes of A, one of B";
    EXPECT_EQ(t.places[0].vessels, 2u);
    EXPECT_DOUBLE_EQ(t.places[0].local.x, 125);
    EXPECT_EQ(t.places[1].count, 1u);
    EXPECT_DOUBLE_EQ(t.places[1].local.x, 375);
}

TEST(Traffic, BerthEvidenceEqualsABruteForceCountOnRandomStays) {
    std::mt19937 rng(20261205);
    std::uniform_real_distribution<double> pos(-2000, 2000), t0(0, 86400), len(60, 20000);
    std::uniform_int_distribution<int> n_stays(0, 6);
    for (int round = 0; round < 20; ++round) {
        std::vector<TrackResult> tracks(30);
        std::vector<std::string> ids;
        for (std::size_t k = 0; k < tracks.size(); ++k) {
            ids.push_back("V" + std::to_string(k % 25));  // some ids twice: one vessel in two tracks counts as two here
            const int n = n_stays(rng);
            double t = t0(rng);
            for (int i = 0; i < n; ++i) {
                const double l = len(rng);
                tracks[k].stays.push_back(stay_at(pos(rng), pos(rng), t, t + l, static_cast<std::size_t>(i / 2)));
                t += l + len(rng);
            }
        }
        std::vector<const TrackResult*> ptr;
        for (const auto& r : tracks) ptr.push_back(&r);
        const Traffic got = learn_traffic(ptr, ids, frame(), {});
        for (std::size_t k = 0; k < tracks.size(); ++k)
            for (std::size_t i = 0; i < tracks[k].stays.size(); ++i) {
                const Stay& s = tracks[k].stays[i];
                std::size_t want = 0, own = 0;
                for (std::size_t j = 0; j < tracks.size(); ++j)
                    for (std::size_t m = 0; m < tracks[j].stays.size(); ++m) {
                        const Stay& o = tracks[j].stays[m];
                        if (j == k && m == i) continue;
                        if (j == k && o.visit == s.visit) continue;
                        if (std::hypot(o.local.x - s.local.x, o.local.y - s.local.y) > 300) continue;
                        if (o.start_s > s.start_s && o.start_s <= s.end_s) continue;
                        ++want;
                        own += j == k;
                    }
                EXPECT_EQ(got.berth_stays[k][i], want) << "round " << round << " track " << k << " stay " << i;
                EXPECT_EQ(got.own_visits[k][i], own) << "round " << round << " track " << k << " stay " << i;
            }
    }
}

}  // namespace
}  // namespace shoal::audit
