// Tests of track::read_nmea on real log cuts and hand-made logs in tests/data/tracks.
//
// Expected values come from tools independent of shoal, run on the same files:
//   grep -c '[$!]' FILE                       -> sentences (rows)
//   grep GLL FILE | awk -F, '$7=="A"' | wc -l -> valid GLL fixes
//   awk over GGA/GLL/RMC time fields | sort -u | wc -l -> distinct fix times
//   /usr/bin/python3: for each GLL with status A, the first VTG after it (its COG/SOG)
//   GNU date -u -d ... +%s for epoch seconds.
// The hand-made logs were written by /usr/bin/python3 with checksums computed there (XOR of the
// characters between '$' and '*'); what each line should do is visible in the file.

#include <shoal/track/nmea_reader.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::test::data_path;
using namespace shoal::track;
using testing::ElementsAre;
using testing::HasSubstr;

std::vector<double> times_since(const Track& t, double origin) {
    std::vector<double> out;
    for (const auto& f : t.fixes) out.push_back(f.time_s - origin);
    return out;
}

TEST(NmeaReader, PlakaLogHasGllPositionsVtgCoursesAndNoDate) {
    // plaka_head400.log: 400 sentences (grep -c '[$!]'), 25 GLL with status A, no RMC and ZDA
    // without date fields. python3: the VTG after the first GLL (09:55:59) says 225.18 T, 5.80 N;
    // 24 of the 25 fixes have a VTG after them (the last GLL is the file's 395th line).
    const auto f = read_nmea(data_path("tracks/plaka_head400.log"));
    EXPECT_EQ(f.format, "nmea");
    EXPECT_EQ(f.report.rows, 400u);
    EXPECT_EQ(f.report.skipped, 0u);
    ASSERT_EQ(f.tracks.size(), 1u);
    const Track& t = f.tracks[0];
    EXPECT_EQ(t.id, "plaka_head400");
    ASSERT_EQ(t.fixes.size(), 25u);
    const Fix& first = t.fixes[0];  // $GPGLL,6005.071,N,02332.346,E,095559,A,D*43
    EXPECT_DOUBLE_EQ(first.position.lat, 60.0 + 5.071 / 60.0);
    EXPECT_DOUBLE_EQ(first.position.lon, 23.0 + 32.346 / 60.0);
    EXPECT_EQ(first.time_s, 9 * 3600.0 + 55 * 60 + 59);  // 1970-01-01, no date in the log
    EXPECT_DOUBLE_EQ(first.cog_deg, 225.18);
    EXPECT_DOUBLE_EQ(first.sog_kn, 5.80);
    EXPECT_TRUE(std::isnan(first.heading_deg));  // every HDT in the log is empty
    EXPECT_EQ(first.line, 11u);
    EXPECT_DOUBLE_EQ(t.fixes[1].cog_deg, 226.95);
    EXPECT_TRUE(std::isnan(t.fixes.back().cog_deg));
    EXPECT_EQ(t.fixes.back().time_s, 9 * 3600.0 + 56 * 60 + 48);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_THAT(f.report.messages[0], HasSubstr("no date in the log"));
}

TEST(NmeaReader, DateFromTheFirstRmcDatesTheGgaBeforeIt) {
    // bundg_zeus_9_head300.log: 290 sentences; GGA/GLL/RMC at 9 distinct times 09:47:36..44;
    // the first RMC (094737) gives 200818. The first fix is the GGA at 094736 (5251.0094 N, 00518.8172 E).
    // date -u -d '2018-08-20T09:47:36Z' +%s -> 1534758456.
    const auto f = read_nmea(data_path("tracks/bundg_zeus_9_head300.log"));
    EXPECT_EQ(f.report.rows, 290u);
    EXPECT_EQ(f.report.skipped, 0u);
    const Track& t = f.tracks.at(0);
    EXPECT_EQ(t.id, "bundg_zeus_9_head300");
    EXPECT_THAT(times_since(t, 1534758456.0), ElementsAre(0, 1, 2, 3, 4, 5, 6, 7, 8));
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lat, 52.0 + 51.0094 / 60.0);
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lon, 5.0 + 18.8172 / 60.0);
    EXPECT_TRUE(std::isnan(t.fixes[0].sog_kn));
    // 094737: $GPRMC,094737,A,5251.0093,N,00518.8170,E,5.6,230.5,200818,...
    EXPECT_DOUBLE_EQ(t.fixes[1].sog_kn, 5.6);
    EXPECT_DOUBLE_EQ(t.fixes[1].cog_deg, 230.5);
    EXPECT_DOUBLE_EQ(t.fixes[1].position.lat, 52.0 + 51.0093 / 60.0);
    EXPECT_TRUE(f.report.messages.empty());
}

TEST(NmeaReader, MergesTalkersSkipsVoidFixesAndAttachesHeadingAndCourse) {
    // mixed_talkers.nmea (15 sentences, each behind a receive-time prefix):
    //   GNGGA 09:59:59 before any date; ZDA 2014-08-15; GPRMC+GNRMC+GPGGA at 10:00:00 -> one fix,
    //   then HDT 47.5; void RMC, GGA quality 0; !AIVDM with a bad checksum (python3: *27, not *24)
    //   skipped, DBT ignored; RMC 10:00:02 COG 46 then a
    //   VTG 46.5 (the RMC's COG stays); INGLL 10:00:03 then VTG 47.0/6.2; INGLL status V.
    // date -u -d '2014-08-15T09:59:59Z' +%s -> 1408096799.
    const std::string path = data_path("tracks/mixed_talkers.nmea");
    const auto f = read_nmea(path);
    EXPECT_EQ(f.report.rows, 15u);
    EXPECT_EQ(f.report.skipped, 4u);
    const Track& t = f.tracks.at(0);
    EXPECT_THAT(times_since(t, 1408096799.0), ElementsAre(0, 1, 3, 4));
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lon, 18.0);
    EXPECT_EQ(t.fixes[1].line, 4u);
    EXPECT_DOUBLE_EQ(t.fixes[1].cog_deg, 45.0);
    EXPECT_DOUBLE_EQ(t.fixes[1].sog_kn, 6.0);
    EXPECT_DOUBLE_EQ(t.fixes[1].heading_deg, 47.5);
    EXPECT_DOUBLE_EQ(t.fixes[2].cog_deg, 46.0);
    EXPECT_DOUBLE_EQ(t.fixes[3].position.lon, 18.0 + 0.030 / 60.0);
    EXPECT_DOUBLE_EQ(t.fixes[3].cog_deg, 47.0);
    EXPECT_DOUBLE_EQ(t.fixes[3].sog_kn, 6.2);
    ASSERT_EQ(f.report.messages.size(), 4u);
    EXPECT_EQ(f.report.messages[0], path + " line 8: RMC status 'V' (no valid fix); sentence skipped");
    EXPECT_EQ(f.report.messages[1], path + " line 9: GGA fix quality '0' (no fix); sentence skipped");
    EXPECT_EQ(f.report.messages[2], path + " line 10: bad checksum '*24' (computed *27); sentence skipped");
    EXPECT_EQ(f.report.messages[3], path + " line 16: GLL status V (no valid fix); sentence skipped");
}

TEST(NmeaReader, BadChecksumSkipsTheLineAndNoChecksumIsAccepted) {
    // bad_checksum.nmea: 5 RMC 12:00:00..04; line 3 has *00 instead of its checksum, line 4 none.
    const std::string path = data_path("tracks/bad_checksum.nmea");
    const auto f = read_nmea(path);
    EXPECT_EQ(f.report.skipped, 1u);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_THAT(f.report.messages[0], HasSubstr(path + " line 3: bad checksum '*00' (computed *"));
    EXPECT_THAT(f.report.messages[0], HasSubstr("; sentence skipped"));
    // date -u -d '2014-08-15T12:00:00Z' +%s -> 1408104000
    EXPECT_THAT(times_since(f.tracks.at(0), 1408104000.0), ElementsAre(0, 1, 3, 4));
}

TEST(NmeaReader, MidnightRolloverWithoutANewDate) {
    // midnight.nmea: RMC 23:59:58 15/08/14, GGA 23:59:59, 00:00:00, 00:00:01, RMC 00:00:02 16/08/14.
    // date -u -d '2014-08-15T23:59:58Z' +%s -> 1408147198
    const auto f = read_nmea(data_path("tracks/midnight.nmea"));
    EXPECT_THAT(times_since(f.tracks.at(0), 1408147198.0), ElementsAre(0, 1, 2, 3, 4));
    EXPECT_EQ(f.report.reordered, 0u);
}

TEST(NmeaReader, NoDateAtAllUsesTheCallersDateOr1970WithAWarning) {
    // missing_date.nmea: GGA 10:15:00, :01, :02 only.
    const auto plain = read_nmea(data_path("tracks/missing_date.nmea"));
    EXPECT_THAT(times_since(plain.tracks.at(0), 36900.0), ElementsAre(0, 1, 2));  // 1970-01-01T10:15:00Z
    ASSERT_EQ(plain.report.messages.size(), 1u);
    EXPECT_THAT(plain.report.messages[0], HasSubstr("times are times of day only, dated 1970-01-01"));
    EXPECT_EQ(plain.report.skipped, 0u);

    ReadOptions options;
    options.date_s = 1408129200.0;  // 2014-08-15T19:00:00Z: only its date counts
    const auto dated = read_nmea(data_path("tracks/missing_date.nmea"), options);
    // date -u -d '2014-08-15T10:15:00Z' +%s -> 1408097700
    EXPECT_THAT(times_since(dated.tracks.at(0), 1408097700.0), ElementsAre(0, 1, 2));
    EXPECT_TRUE(dated.report.messages.empty());
}

TEST(NmeaReader, OldVtgAndTwoDigitZdaYears) {
    const std::string log =
        "$GPZDA,195719,16,04,14,-02,00*63\n"  // a real gofree-merrimac.log line: 2-digit year
        "$GPGGA,195720,5310.8115,N,00525.7025,E,1,08,0.9,1.0,M,17.0,M,,\n"
        "$GPVTG,054.7,034.4,005.5,010.2\n";  // NMEA 1.5 VTG: true, magnetic, knots, km/h
    const auto f = read_nmea_text(log, "x.nmea");
    ASSERT_EQ(f.tracks.at(0).fixes.size(), 1u);
    const Fix& x = f.tracks[0].fixes[0];
    // date -u -d '2014-04-16T19:57:20Z' +%s -> 1397678240
    EXPECT_EQ(x.time_s, 1397678240.0);
    EXPECT_DOUBLE_EQ(x.cog_deg, 54.7);
    EXPECT_DOUBLE_EQ(x.sog_kn, 5.5);
    EXPECT_DOUBLE_EQ(x.position.lat, 53.0 + 10.8115 / 60.0);
}

TEST(NmeaReader, SouthernAndWesternHemispheresAndBadFields) {
    const std::string log =
        "$GPRMC,120000,A,3345.000,S,07030.000,W,1.0,10.0,010120,,,A\n"
        "$GPRMC,120001,A,3345.000,X,07030.000,W,1.0,10.0,010120,,,A\n"  // bad hemisphere
        "$GPRMC,126101,A,3345.000,S,07030.000,W,1.0,10.0,010120,,,A\n"  // minute 61
        "$GPRMC,120002,A,3361.000,S,07030.000,W,1.0,10.0,010120,,,A\n"  // 61 minutes of latitude
        "$GPGLL,3345.000,S,07030.000,W,,A,A\n";                        // GLL without a time
    const auto f = read_nmea_text(log, "south.nmea");
    ASSERT_EQ(f.tracks.at(0).fixes.size(), 1u);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].position.lat, -33.75);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].position.lon, -70.5);
    EXPECT_EQ(f.report.skipped, 4u);
    EXPECT_THAT(f.report.messages.at(1), HasSubstr("RMC time '126101' is not hhmmss"));
    EXPECT_THAT(f.report.messages.at(3), HasSubstr("GLL without a time"));
}

TEST(NmeaSniff, FindsSentencesBehindPrefixes) {
    EXPECT_TRUE(holds_nmea_sentence("$GPRMC,120000,A"));
    EXPECT_TRUE(holds_nmea_sentence("1234.5 $GPGGA,1"));
    EXPECT_TRUE(holds_nmea_sentence("\\s:r003669,c:1241544035*4A\\!AIVDM,1,1,,B,15N4cJ"));
    EXPECT_FALSE(holds_nmea_sentence("price $5, cheap"));
    EXPECT_FALSE(holds_nmea_sentence("mmsi,lat,lon"));
}

}  // namespace
