// The real world's traffic model (audit/evidence.hpp): which stays are evidence of a berth, and
// the places it learns, against answers worked out by hand; and a brute-force count of the
// evidence on many random stays.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>

#include <shoal/sweep/evidence.hpp>

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

/// Water the chart lacks against a brute force: each cell of fixes on land holds every such
/// fix in it and the vessels (ids, one vessel in two tracks once) that made them; random fixes
/// either side of zero, ids repeated.
TEST(Traffic, WaterCellsEqualABruteForceCountOnRandomFixes) {
    std::mt19937 rng(20261207);
    std::uniform_real_distribution<double> pos(-1500, 1500);
    for (int round = 0; round < 20; ++round) {
        std::vector<TrackResult> tracks(1 + rng() % 20);
        std::vector<std::string> ids;
        for (std::size_t k = 0; k < tracks.size(); ++k) {
            ids.push_back("V" + std::to_string(k % 7));
            const std::size_t n = rng() % 200;
            for (std::size_t i = 0; i < n; ++i) tracks[k].over_land.push_back({pos(rng), pos(rng)});
        }
        std::vector<const TrackResult*> ptr;
        for (const auto& r : tracks) ptr.push_back(&r);
        const Traffic got = learn_traffic(ptr, ids, frame(), {});
        const double W = EvidenceOptions{}.water_cell_m;
        std::size_t cells = 0;
        for (const LearnedPlace& pl : got.places) {
            if (pl.kind != LearnedPlace::Kind::water) continue;
            ++cells;
            std::size_t fixes = 0;
            std::set<std::string> vessels;
            for (std::size_t k = 0; k < tracks.size(); ++k)
                for (const auto& q : tracks[k].over_land)
                    if (std::fabs(q.x - pl.local.x) < W / 2 && std::fabs(q.y - pl.local.y) < W / 2) {
                        ++fixes;
                        vessels.insert(ids[k]);
                    }
            EXPECT_EQ(pl.count, fixes) << "round " << round << " cell at " << pl.local.x << ", " << pl.local.y;
            EXPECT_EQ(pl.vessels, vessels.size()) << "round " << round;
        }
        std::set<std::pair<long long, long long>> expected_cells;
        for (const auto& t : tracks)
            for (const auto& q : t.over_land) expected_cells.insert({static_cast<long long>(std::floor(q.x / W)), static_cast<long long>(std::floor(q.y / W))});
        EXPECT_EQ(cells, expected_cells.size()) << "round " << round;
    }
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

// The simulated world's one event per stay (merge_stays, issue 39: one moored ship gave dozens of
// `alongside` events, each touch of its jittering hull a new one). Hand-made tracks at 36 N,
// 5 W: a fix a minute; 1e-5 degrees of latitude is 1.109 m there, of longitude 0.900 m.
track::Fix still_fix(double t, double dlat_m = 0, double dlon_m = 0, double speed_kn = 0.2, bool stopped = true) {
    track::Fix f;
    f.time_s = t;
    f.position = {-5.0 + dlon_m / 90163.0, 36.0 + dlat_m / 110938.0};
    f.speed_used_kn = speed_kn;
    f.stopped = stopped;
    return f;
}

Event contact(EventKind kind, double start_s, double end_s, double penetration_m = 1.0) {
    Event e;
    e.kind = kind;
    e.start_s = start_s;
    e.end_s = end_s;
    e.penetration_m = penetration_m;
    e.ship = {-5.0, 36.0};
    return e;
}

std::vector<EventKind> kinds(const TrackResult& r) {
    std::vector<EventKind> k;
    for (const Event& e : r.events) k.push_back(e.kind);
    return k;
}

TEST(OneEventPerStay, ContactsOfOneStayAtOnePlaceAreOneEventAndAClosePassStays) {
    // Moored an hour, jittering within 6 m, at 0.2 kn (one fix's SOG noise at 1.8 kn, not
    // stopped: still under the 3 kn of a vessel under way): three touches, a gap-restart in
    // contact, a close pass between. One alongside from the first touch's start to the last
    // one's end, the deepest penetration (3 m), pieces 1 + 1 + 1 + 1; the close pass is kept.
    track::Track t;
    for (int i = 0; i <= 60; ++i) t.fixes.push_back(still_fix(60.0 * i, (i % 3) * 2.0, (i % 2) * 3.0, i == 20 ? 1.8 : 0.2, i != 20));
    TrackResult r;
    r.events = {contact(EventKind::alongside, 100, 400), contact(EventKind::alongside, 700, 900, 3.0),
                contact(EventKind::contact_at_start, 1500, 1800), contact(EventKind::close_pass, 2000, 2100, 0),
                contact(EventKind::alongside, 2500, 3000, 2.0)};
    merge_stays(r, t, SweepOptions{});
    ASSERT_EQ(kinds(r), (std::vector<EventKind>{EventKind::alongside, EventKind::close_pass}));
    EXPECT_DOUBLE_EQ(r.events[0].start_s, 100);
    EXPECT_DOUBLE_EQ(r.events[0].end_s, 3000);
    EXPECT_DOUBLE_EQ(r.events[0].penetration_m, 3.0);
    EXPECT_EQ(r.events[0].evidence.pieces, 4u);
    EXPECT_EQ(r.summary.alongside, 1u);
    EXPECT_EQ(r.summary.contacts_at_start, 0u);
}

TEST(OneEventPerStay, AShipThatLeavesAndComesBackHasTwoStays) {
    // At the berth 0-1200 s, away 1260-2400 s at 4 kn (600 m out and back), at the berth again
    // 2460-3600 s: two stays, two alongside events.
    track::Track t;
    for (int i = 0; i <= 20; ++i) t.fixes.push_back(still_fix(60.0 * i));
    for (int i = 21; i <= 40; ++i) t.fixes.push_back(still_fix(60.0 * i, 600.0 - std::abs(30 - i) * 60.0, 0, 4.0, false));
    for (int i = 41; i <= 60; ++i) t.fixes.push_back(still_fix(60.0 * i));
    TrackResult r;
    r.events = {contact(EventKind::alongside, 100, 500), contact(EventKind::alongside, 2600, 3000)};
    merge_stays(r, t, SweepOptions{});
    EXPECT_EQ(kinds(r), (std::vector<EventKind>{EventKind::alongside, EventKind::alongside}));
    EXPECT_EQ(r.summary.alongside, 2u);
    // Stopped all along but shifted 80 m along the quay between the touches (under the berthing
    // speed): another place, beyond the 50 m stop diameter: two events too.
    track::Track shifted;
    for (int i = 0; i <= 60; ++i) shifted.fixes.push_back(still_fix(60.0 * i, 0, i < 30 ? 0.0 : 80.0, 0.5, i < 25 || i > 35));
    TrackResult s;
    s.events = {contact(EventKind::alongside, 100, 500), contact(EventKind::alongside, 2600, 3000)};
    merge_stays(s, shifted, SweepOptions{});
    EXPECT_EQ(s.summary.alongside, 2u);
    // The same still track with a jump between the touches: the positions say nothing, two events.
    track::Track jumped;
    for (int i = 0; i <= 60; ++i) jumped.fixes.push_back(still_fix(60.0 * i));
    jumped.fixes[20].jump_before = true;
    TrackResult j;
    j.events = {contact(EventKind::alongside, 100, 500), contact(EventKind::alongside, 2600, 3000)};
    merge_stays(j, jumped, SweepOptions{});
    EXPECT_EQ(j.summary.alongside, 2u);
}

TEST(OneEventPerStay, BerthingContactsSecondsApartThatComeToRestInOneStayAreOneArrival) {
    // A vessel creeping in across a coastline drawn a few metres off: jitter takes it in and out
    // of contact (before, an alongside event for each). All come to rest in stay 0 (from
    // t = 1000); the first two 20 s apart are one arrival, the third 230 s later another; two
    // groundings that come to rest there stay two (never merged); an alongside contact that
    // comes to rest in another stay stays its own.
    TrackResult r;
    r.stays = {Stay{}, Stay{}};
    r.stays[0].start_s = 1000, r.stays[0].end_s = 5000;
    r.stays[1].start_s = 9000, r.stays[1].end_s = 12000;
    auto arriving = [](EventKind k, double start_s, double end_s, std::size_t stay, double penetration_m) {
        Event e = contact(k, start_s, end_s, penetration_m);
        e.stopped_before = k == EventKind::alongside;  // decided alongside, "stopped before the contact"
        e.reported_aground = k == EventKind::grounding;  // decided a grounding, "AIS status aground"
        e.evidence.stay = stay;
        e.evidence.stay_s = 4000;
        e.evidence.pieces = 1;
        return e;
    };
    r.events = {arriving(EventKind::alongside, 100, 130, 0, 1.0), arriving(EventKind::alongside, 150, 170, 0, 4.0),
                arriving(EventKind::alongside, 400, 420, 0, 2.0), arriving(EventKind::grounding, 500, 520, 0, 1.0),
                arriving(EventKind::grounding, 530, 560, 0, 1.0), arriving(EventKind::alongside, 8000, 8010, 1, 1.0)};
    decide_kinds(r, {0, 0}, {0, 0}, EvidenceOptions{});
    ASSERT_EQ(kinds(r), (std::vector<EventKind>{EventKind::alongside, EventKind::alongside, EventKind::grounding, EventKind::grounding,
                                                EventKind::alongside}));
    EXPECT_DOUBLE_EQ(r.events[0].start_s, 100);
    EXPECT_DOUBLE_EQ(r.events[0].end_s, 170);
    EXPECT_DOUBLE_EQ(r.events[0].penetration_m, 4.0);
    EXPECT_EQ(r.events[0].evidence.pieces, 2u);
    EXPECT_DOUBLE_EQ(r.events[1].start_s, 400);
    EXPECT_EQ(r.summary.alongside, 3u);
    EXPECT_EQ(r.summary.groundings, 2u);
    // Jitter contacts just before the stay, the last running into it, then touches inside it:
    // one event (the merged one ends in the stay, so later ones there are part of it).
    TrackResult j;
    j.stays = {Stay{}};
    j.stays[0].start_s = 1000, j.stays[0].end_s = 5000;
    j.events = {arriving(EventKind::alongside, 900, 930, 0, 1.0), arriving(EventKind::alongside, 950, 1100, 0, 1.0),
                arriving(EventKind::alongside, 2000, 2100, 0, 1.0), arriving(EventKind::alongside, 3000, 3100, 0, 1.0)};
    decide_kinds(j, {0}, {0}, EvidenceOptions{});
    ASSERT_EQ(j.events.size(), 1u);
    EXPECT_DOUBLE_EQ(j.events[0].start_s, 900);
    EXPECT_DOUBLE_EQ(j.events[0].end_s, 3100);
}

TEST(RealWorld, ASlowContactWithAChartedDepthWhereNoVesselBerthsIsAground) {
    // Drifting (or dragging its anchor) at 1.5 kn onto a 3.6 m shoal of an S-57 chart and lying
    // there 4 h: before, "alongside ... berthing". A depth area is no berth's face: aground,
    // unless vessels berth there (other stays, a berth or harbour area, a structure). Land
    // (a port the coarse chart lacks) keeps its rules.
    auto decided = [](coast::HazardKind hit, std::size_t berth_stays, const std::string& area) {
        TrackResult r;
        Event e = contact(EventKind::alongside, 1000, 15400, 20.0);
        e.hit = hit;
        e.charted_depth_m = hit == coast::HazardKind::shallow ? 3.6 : NAN;
        e.speed_kn = 1.5;
        e.area_kind = area;
        e.evidence.stay = 0;
        e.evidence.stay_s = 4 * 3600.0;
        e.evidence.rests_in_contact = true;
        e.evidence.prompt_stop = true;
        e.evidence.stop_distance_m = 70.0;
        e.evidence.seen_clear_before = true;
        e.evidence.speed_before_kn = 1.5;
        r.events.push_back(e);
        r.summary.hull_length_m = 120.0;
        decide_kinds(r, {berth_stays}, {0}, EvidenceOptions{});
        return r.events.at(0);
    };
    const Event shoal = decided(coast::HazardKind::shallow, 0, "");
    EXPECT_EQ(shoal.kind, EventKind::grounding);
    EXPECT_EQ(shoal.evidence.reason,
              "came onto charted shallow water (3.6 m charted) at 1.5 kn and lay there 240 min, where no vessel berths: a charted depth is no berth, aground");
    EXPECT_EQ(decided(coast::HazardKind::danger, 0, "").kind, EventKind::grounding);
    EXPECT_EQ(decided(coast::HazardKind::shallow, 2, "").kind, EventKind::alongside) << "vessels berth there";
    EXPECT_NE(decided(coast::HazardKind::shallow, 0, "harbour").kind, EventKind::grounding) << "in a harbour area";
    EXPECT_EQ(decided(coast::HazardKind::land, 0, "").kind, EventKind::alongside) << "a port the coarse chart lacks";
}

TEST(SimulatedWorld, AContactFirstSeenAfterAGapUnderWayBeforeItIsAGroundingInsideTheGap) {
    // Seen clear at 10 kn (5.14 m/s) every minute northwards, then nothing for 30 min, then in
    // contact at rest 3 km further on (within 1.5 x 10 kn x 30 min = 13.9 km): aground inside
    // the gap, the fix before it the start's bound.
    auto run = [](double gap_s, double speed_kn, bool stopped, double lying_m, bool jump, bool contact_before) {
        track::Track t;
        for (int i = 0; i <= 10; ++i) t.fixes.push_back(still_fix(60.0 * i, 308.6 * i, 0, speed_kn, stopped));
        const double t1 = 600.0 + gap_s;
        for (int i = 0; i <= 5; ++i) t.fixes.push_back(still_fix(t1 + 60.0 * i, 3086.0 + lying_m, 0, 0.0, true));
        t.fixes[11].jump_before = jump;
        TrackResult r;
        if (contact_before) r.events.push_back(contact(EventKind::alongside, 500, 600));
        Event e = contact(EventKind::contact_at_start, t1, t1 + 300);
        e.unseen_after = "gap";
        r.events.push_back(e);
        ground_inside_gaps(r, t, SweepOptions{}, EvidenceOptions{}, 100.0);
        return r;
    };
    const TrackResult g = run(1800, 10, false, 3000, false, false);
    ASSERT_EQ(g.events.size(), 1u);
    EXPECT_EQ(g.events[0].kind, EventKind::grounding);
    EXPECT_DOUBLE_EQ(g.events[0].evidence.start_not_before_s, 600);
    EXPECT_DOUBLE_EQ(g.events[0].evidence.speed_before_kn, 10);
    EXPECT_DOUBLE_EQ(g.events[0].evidence.speed_before_age_s, 1800);
    EXPECT_EQ(g.summary.groundings, 1u);
    EXPECT_EQ(g.summary.contacts_at_start, 0u);
    // Not when: the gap is over the hour; the vessel was stopped or under the berthing speed
    // before it; it lies further than it could have gone; the fixes jump; it was in contact
    // before the gap.
    EXPECT_EQ(run(3700, 10, false, 3000, false, false).events[0].kind, EventKind::contact_at_start);
    EXPECT_EQ(run(1800, 10, true, 3000, false, false).events[0].kind, EventKind::contact_at_start);
    EXPECT_EQ(run(1800, 0.5, false, 3000, false, false).events[0].kind, EventKind::contact_at_start);
    EXPECT_EQ(run(1800, 10, false, 20000, false, false).events[0].kind, EventKind::contact_at_start);
    EXPECT_EQ(run(1800, 10, false, 3000, true, false).events[0].kind, EventKind::contact_at_start);
    EXPECT_EQ(run(1800, 10, false, 3000, false, true).events[1].kind, EventKind::contact_at_start);
    // Its reason, graded by the simulated world.
    TrackResult graded = g;
    grade_simulated(graded);
    EXPECT_EQ(graded.events[0].evidence.grade, 3) << "its speed at the contact was not seen";
    EXPECT_EQ(graded.events[0].evidence.reason,
              "seen clear under way at 10 kn, in contact after a gap of 1800 s: aground inside the gap (its speed at the contact not seen); the chart is the world");
}

TEST(OneEventPerStay, GroundingsAndExpectedContactsAreNeverMergedNorMergedInto) {
    track::Track t;
    for (int i = 0; i <= 60; ++i) t.fixes.push_back(still_fix(60.0 * i));
    TrackResult r;
    r.events = {contact(EventKind::alongside, 100, 400), contact(EventKind::grounding, 500, 600), contact(EventKind::alongside, 700, 900),
                contact(EventKind::expected_contact, 1000, 1100), contact(EventKind::expected_contact, 1200, 1300),
                contact(EventKind::grounding, 1400, 1500), contact(EventKind::grounding, 1600, 1700)};
    merge_stays(r, t, SweepOptions{});
    EXPECT_EQ(kinds(r), (std::vector<EventKind>{EventKind::alongside, EventKind::grounding, EventKind::alongside, EventKind::expected_contact,
                                                EventKind::expected_contact, EventKind::grounding, EventKind::grounding}));
    EXPECT_EQ(r.summary.groundings, 3u);
    EXPECT_EQ(r.summary.alongside, 2u);
    EXPECT_EQ(r.summary.expected_contacts, 2u);
}

}  // namespace
}  // namespace shoal::audit
