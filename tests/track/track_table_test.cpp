// Rows of fixes into tracks (track/track_table.hpp) and the row rules (track/row_rules.hpp),
// against answers worked out by hand and against a plain map of ids made here.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <shoal/track/row_rules.hpp>
#include <shoal/track/track_table.hpp>

namespace shoal::track {
namespace {

TEST(TrackTable, TracksStandInTheOrderTheirIdsFirstAppearAndMmsisWithALeadingZeroAreOtherVessels) {
    std::vector<PackedTrack> tracks;
    TrackTable table(tracks, "dir/day.csv", true, false);
    EXPECT_EQ(table.track_for("230035780"), 0u);
    EXPECT_EQ(table.track_for("0230035780"), 1u);  // not the same number: another vessel
    EXPECT_EQ(table.track_for("ferry"), 2u);
    EXPECT_EQ(table.track_for("230035780"), 0u);
    EXPECT_EQ(table.track_for("ferry"), 2u);
    EXPECT_EQ(table.track_for("0230035780"), 1u);
    ASSERT_EQ(tracks.size(), 3u);
    EXPECT_EQ(tracks[0].id, "230035780");
    EXPECT_EQ(tracks[1].id, "0230035780");
    EXPECT_EQ(tracks[2].id, "ferry");
    for (const PackedTrack& t : tracks) EXPECT_EQ(t.file, "dir/day.csv");
}

TEST(TrackTable, WithoutAnIdColumnEveryRowIsTheFilesOneTrack) {
    std::vector<PackedTrack> tracks;
    TrackTable table(tracks, "logs/plaka_first_hour.nmea", false, false);
    EXPECT_EQ(table.track_for({}), 0u);
    EXPECT_EQ(table.track_for({}), 0u);
    ASSERT_EQ(tracks.size(), 1u);
    EXPECT_EQ(tracks[0].id, "plaka_first_hour");
}

TEST(TrackTable, OneVesselInTwoExercisesIsTwoTracks) {
    std::vector<PackedTrack> tracks;
    TrackTable table(tracks, "runs.csv", true, true);
    EXPECT_EQ(table.track_for("211000001", "A"), 0u);
    EXPECT_EQ(table.track_for("211000001", "B"), 1u);
    EXPECT_EQ(table.track_for("211000001", "A"), 0u);
    EXPECT_EQ(tracks[0].exercise, "A");
    EXPECT_EQ(tracks[1].exercise, "B");
    EXPECT_EQ(tracks[1].id, "211000001");
    // Without the exercise column the exercise is not part of the key.
    std::vector<PackedTrack> one;
    TrackTable plain(one, "runs.csv", true, false);
    EXPECT_EQ(plain.track_for("211000001", "A"), plain.track_for("211000001", "B"));
    EXPECT_EQ(one.size(), 1u);
}

TEST(TrackTable, RandomRowsGiveTheTracksOfAPlainMapOfIds) {
    std::mt19937 rng(2026);
    for (int round = 0; round < 50; ++round) {
        std::vector<std::string> ids;
        for (int k = 0; k < 40; ++k) {
            switch (rng() % 4) {
            case 0: ids.push_back(std::to_string(200000000 + rng() % 1000)); break;  // MMSIs
            case 1: ids.push_back("0" + std::to_string(rng() % 1000)); break;      // leading zero: text
            case 2: ids.push_back("v" + std::to_string(rng() % 50)); break;
            default: ids.push_back(std::to_string(rng() % 100)); break;
            }
        }
        std::vector<PackedTrack> tracks;
        TrackTable table(tracks, "f.csv", true, false);
        std::map<std::string, std::size_t> expected;
        for (int row = 0; row < 2000; ++row) {
            const std::string& id = ids[rng() % ids.size()];
            const auto [it, fresh] = expected.try_emplace(id, expected.size());
            ASSERT_EQ(table.track_for(id), it->second) << id;
        }
        ASSERT_EQ(tracks.size(), expected.size());
        for (const auto& [id, k] : expected) EXPECT_EQ(tracks[k].id, id);
    }
}

TEST(RowRules, ATrackKeepsTheFirstUsableStaticValueOfEachKind) {
    PackedTrack t;
    offer_name(t, "");
    offer_name(t, "ARIADNE");
    offer_name(t, "OTHER");
    EXPECT_EQ(t.name, "ARIADNE");
    offer_dims(t, dims_from_abcd(100, 20, 8, 0), dims_from_abcd_source);  // D of 0: AIS's "not available"
    EXPECT_FALSE(t.dims);
    offer_dims(t, dims_from_abcd(100, 20, 8, NAN), dims_from_abcd_source);
    EXPECT_FALSE(t.dims);
    offer_dims(t, dims_from_length_width(120, 20), dims_from_length_width_source);
    ASSERT_TRUE(t.dims);
    EXPECT_EQ(*t.dims, (hull::Dimensions{60, 60, 10, 10}));
    EXPECT_EQ(t.dims_source, dims_from_length_width_source);
    offer_dims(t, dims_from_abcd(100, 20, 8, 8), dims_from_abcd_source);  // later: not taken
    EXPECT_EQ(*t.dims, (hull::Dimensions{60, 60, 10, 10}));
    offer_draught(t, 0);
    offer_draught(t, -3);
    EXPECT_TRUE(std::isnan(t.draught_m));
    offer_draught(t, 7.5);
    offer_draught(t, 9);
    EXPECT_EQ(t.draught_m, 7.5);
    EXPECT_EQ(t.draught_source, draught_source);
    offer_ship_type(t, 0);     // not available
    offer_ship_type(t, 70.5);  // not a whole number
    offer_ship_type(t, 256);
    EXPECT_EQ(t.ship_type, -1);
    offer_ship_type(t, 70);
    offer_ship_type(t, 60);
    EXPECT_EQ(t.ship_type, 70);
}

TEST(RowRules, PositionsRefusedAsAisAndTheirRangesSayAndTheFastTestAgreesWithTheFullOne) {
    std::string what;
    EXPECT_TRUE(position_problem(91, 10, what));
    EXPECT_EQ(what, "latitude 91 (AIS: not available)");
    EXPECT_TRUE(position_problem(10, 181, what));
    EXPECT_EQ(what, "longitude 181 (AIS: not available)");
    EXPECT_TRUE(position_problem(-90.5, 10, what));
    EXPECT_EQ(what, "latitude -90.5 is outside [-90, 90]");
    EXPECT_TRUE(position_problem(NAN, 10, what));
    EXPECT_EQ(what, "latitude nan is not a number");
    EXPECT_FALSE(position_problem(90, -180, what));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> lat(-95, 95), lon(-185, 185);
    for (int k = 0; k < 100000; ++k) {
        const double a = lat(rng), b = lon(rng);
        std::string w1, w2;
        EXPECT_EQ(position_problem(a, b, w1), position_problem_text(a, b, w2));
        EXPECT_EQ(w1, w2);
    }
    EXPECT_FALSE(is_vessel_row("AtoN"));
    EXPECT_FALSE(is_vessel_row("Base Station"));
    EXPECT_TRUE(is_vessel_row("Class A"));
    EXPECT_EQ(not_a_vessel_message("AtoN"), "not a vessel (Type of mobile 'AtoN')");
}

}  // namespace
}  // namespace shoal::track
