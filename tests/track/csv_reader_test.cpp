// Tests of track::read_csv on real cuts and hand-made files in tests/data/tracks.
//
// Expected counts come from tools independent of shoal, run on the same files:
//   /usr/bin/python3 with csv.DictReader: rows, distinct ids in first-appearance order, fixes
//     per id = distinct (id, timestamp) pairs, duplicates = rows - fixes, rows whose time is
//     earlier than an earlier row of the same id (reordered);
//   awk -F, for columns (dimensions, headings); GNU date -u -d ... +%s for epoch seconds.
// Hand-made files were written so that every row's fate is visible in the file itself.

#include <shoal/track/csv_reader.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <tuple>
#include <cstdio>
#include <string>
#include <vector>

#include "util/parse_util.hpp"
#include "test_support.hpp"
#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::test::data_path;
using namespace shoal::track;
using testing::AllOf;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::ThrowsMessage;

std::size_t fix_count(const TrackFile& f) {
    std::size_t n = 0;
    for (const auto& t : f.tracks) n += t.fixes.size();
    return n;
}

const Track* find(const TrackFile& f, const std::string& id) {
    for (const auto& t : f.tracks)
        if (t.id == id) return &t;
    return nullptr;
}

bool sorted_by_time(const Track& t) {
    return std::is_sorted(t.fixes.begin(), t.fixes.end(), [](const Fix& a, const Fix& b) { return a.time_s < b.time_s; });
}

// ---------------------------------------------------------------------------------------------
// Real files

TEST(CsvReader, DecodedFixesLayoutSplitsVesselsInFirstAppearanceOrder) {
    // python3 csv: 299 rows, 54 ids, first ids OWN:aava-n2k.data (85 rows), 230035780 (44), 258858000 (5);
    // no repeated (id, timestamp); no heading_deg values, 213 cog_deg values.
    const auto f = read_csv(data_path("tracks/aava_n2k_fixes_head300.csv"));
    EXPECT_EQ(f.format, "csv");
    EXPECT_EQ(f.report.rows, 299u);
    EXPECT_EQ(f.report.skipped, 0u);
    EXPECT_EQ(f.report.duplicates, 0u);
    ASSERT_EQ(f.tracks.size(), 54u);
    EXPECT_EQ(fix_count(f), 299u);
    EXPECT_EQ(f.tracks[0].id, "OWN:aava-n2k.data");
    EXPECT_EQ(f.tracks[1].id, "230035780");
    EXPECT_EQ(f.tracks[2].id, "258858000");
    EXPECT_EQ(f.tracks[0].fixes.size(), 85u);
    EXPECT_EQ(f.tracks[1].fixes.size(), 44u);
    EXPECT_EQ(f.tracks[2].fixes.size(), 5u);
    const Fix& first = f.tracks[0].fixes.front();  // 2014-08-15T19:00:00.042Z,59.7250108,24.7366770
    EXPECT_DOUBLE_EQ(first.time_s, 1408129200.042);
    EXPECT_DOUBLE_EQ(first.position.lat, 59.7250108);
    EXPECT_DOUBLE_EQ(first.position.lon, 24.7366770);
    EXPECT_EQ(first.line, 2u);
    const Fix& other = f.tracks[1].fixes.front();  // ...,230035780,59.7249883,24.7366450,6.18,199.0,,PGN129039
    EXPECT_DOUBLE_EQ(other.sog_kn, 6.18);
    EXPECT_DOUBLE_EQ(other.cog_deg, 199.0);
    EXPECT_TRUE(std::isnan(other.heading_deg));
    for (const auto& t : f.tracks) {
        EXPECT_TRUE(sorted_by_time(t)) << t.id;
        EXPECT_EQ(t.file, data_path("tracks/aava_n2k_fixes_head300.csv"));
    }
}

/// Vessel ids are looked up by number when they are MMSIs (digits, no leading zero, up to 18)
/// and as text otherwise: rows interleaved across thousands of vessels, with ids that read as
/// the same number but are different text, must still make one track per distinct id text, in
/// order of first appearance (the answer here is a map of strings).
TEST(CsvReader, PlainDecimalsReadAsFromCharsReadsThem) {
    // detail::plain_decimal's digits over a power of ten against std::from_chars, bit for bit,
    // on random decimals of 1 to 18 digits with 0 to 17 after the point (the fast path takes
    // up to 15 in all), signs and leading zeros; and texts it must leave to from_chars.
    std::mt19937_64 rng(15);
    std::size_t fast = 0;
    for (int k = 0; k < 400000; ++k) {
        std::string s = rng() % 4 == 0 ? "-" : "";
        const std::size_t before = 1 + rng() % 9, after = rng() % 10;
        for (std::size_t i = 0; i < before; ++i) s += static_cast<char>('0' + (i == 0 && rng() % 3 ? 1 + rng() % 9 : rng() % 10));
        if (after || rng() % 2) {
            s += '.';
            for (std::size_t i = 0; i < after; ++i) s += static_cast<char>('0' + rng() % 10);
        }
        double want = 0;
        const auto r = std::from_chars(s.data(), s.data() + s.size(), want);
        double got = 12345;
        const bool taken = shoal::track::detail::plain_decimal(s, got);
        fast += taken;
        if (taken) {
            ASSERT_TRUE(r.ec == std::errc{} && r.ptr == s.data() + s.size()) << s;
            ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0) << s << ": " << got << " against " << want;
        }
        double parsed = 12345;
        const bool ok = shoal::track::detail::parse_double(s, parsed);
        ASSERT_EQ(ok, r.ec == std::errc{} && r.ptr == s.data() + s.size()) << s;
        if (ok) {
            ASSERT_EQ(std::memcmp(&parsed, &want, sizeof parsed), 0) << s;
        }
    }
    EXPECT_GT(fast, 200000u);
    for (const char* s : {"", "-", ".5", "5.", "1e5", "+1", "0x10", "1234567890123456", "1.234567890123456", "inf", "nan", "1 ", "--1", "1.2.3"}) {
        double v = 12345;
        EXPECT_FALSE(shoal::track::detail::plain_decimal(s, v)) << s;
        EXPECT_EQ(v, 12345) << s;
    }
    double v = 0;
    ASSERT_TRUE(shoal::track::detail::plain_decimal("-0.0", v));
    EXPECT_TRUE(std::signbit(v));
    ASSERT_TRUE(shoal::track::detail::plain_decimal("123456789012345", v));
    EXPECT_EQ(v, 123456789012345.0);
}

TEST(CsvReader, InterleavedIdsOfEveryKindMakeOneTrackPerIdText) {
    std::mt19937_64 rng(15);
    std::vector<std::string> ids;
    for (int k = 0; k < 2500; ++k) ids.push_back(std::to_string(200000000 + k * 7));
    for (const char* odd : {"0", "00", "0123", "123", "123 ", "999999999999999999", "1000000000000000000", "18446744073709551616",
                            "18446744073709551617", "abc", "-5", "+5", "5", "1e3", "1000"})
        ids.push_back(odd);
    std::string text = "mmsi,time,lat,lon\n";
    std::vector<std::string> first_seen;
    std::map<std::string, std::size_t> count;
    for (int k = 0; k < 30000; ++k) {
        const std::string& id = ids[rng() % ids.size()];
        // Times unique per row: no fix is a duplicate of another.
        text += id + "," + std::to_string(1700000000 + k) + ",60.0,24.0\n";
        const std::string key(shoal::track::detail::trim(id));
        if (count[key]++ == 0) first_seen.push_back(key);
    }
    const TrackFile f = read_csv_text(text, "ids.csv");
    ASSERT_EQ(f.tracks.size(), first_seen.size());
    for (std::size_t i = 0; i < f.tracks.size(); ++i) {
        EXPECT_EQ(f.tracks[i].id, first_seen[i]);
        EXPECT_EQ(f.tracks[i].fixes.size(), count[first_seen[i]]) << first_seen[i];
    }
}

TEST(CsvReader, MarineCadastreLayoutTreats511AsUnknownHeading) {
    // python3 csv: 144 rows, 3 MMSIs with 48 rows each; awk: Heading is 511 on all 144 rows.
    const auto f = read_csv(data_path("tracks/depons_marinecadastre.csv"));
    ASSERT_EQ(f.tracks.size(), 3u);
    EXPECT_EQ(f.tracks[0].id, "209715000");
    EXPECT_EQ(f.tracks[1].id, "636091769");
    EXPECT_EQ(f.tracks[2].id, "212396000");
    for (const auto& t : f.tracks) {
        EXPECT_EQ(t.fixes.size(), 48u);
        for (const auto& x : t.fixes) EXPECT_TRUE(std::isnan(x.heading_deg));
    }
    // First row: 209715000,2015-12-20T00:00:00,55.842890,15.857993,12.5,238.9,511 ; date -u -> 1450569600
    const Fix& x = f.tracks[0].fixes.front();
    EXPECT_EQ(x.time_s, 1450569600.0);
    EXPECT_DOUBLE_EQ(x.position.lat, 55.842890);
    EXPECT_DOUBLE_EQ(x.position.lon, 15.857993);
    EXPECT_DOUBLE_EQ(x.sog_kn, 12.5);
    EXPECT_DOUBLE_EQ(x.cog_deg, 238.9);
}

TEST(CsvReader, DanishMaritimeAuthorityExportWithDayFirstTimesAndDimensions) {
    // python3 csv: 199 rows, 166 MMSIs, 198 distinct (MMSI, time), 1 repeat (309186000 at
    // 11/06/2010 11:46:12, lines 48 and 50), 9 rows earlier than an earlier row of their vessel.
    // awk: 23 MMSIs have A,B,C,D all > 0; 219127000 MAERSK BARRY 155,20,11,18, draught 8.8.
    const auto f = read_csv(data_path("tracks/dma_export_dk_head200.csv"));
    EXPECT_EQ(f.report.rows, 199u);
    EXPECT_EQ(f.report.skipped, 0u);
    EXPECT_EQ(f.tracks.size(), 166u);
    EXPECT_EQ(fix_count(f), 198u);
    EXPECT_EQ(f.report.duplicates, 1u);
    EXPECT_EQ(f.report.reordered, 9u);
    EXPECT_EQ(std::count_if(f.tracks.begin(), f.tracks.end(), [](const Track& t) { return t.dims.has_value(); }), 23);

    const Track* barry = find(f, "219127000");
    ASSERT_NE(barry, nullptr);
    EXPECT_EQ(barry->name, "MAERSK BARRY");
    ASSERT_TRUE(barry->dims);
    EXPECT_EQ(*barry->dims, (shoal::hull::Dimensions{155, 20, 11, 18}));
    EXPECT_DOUBLE_EQ(barry->draught_m, 8.8);
    ASSERT_EQ(barry->fixes.size(), 1u);
    EXPECT_EQ(barry->fixes[0].time_s, 1276256778.0);  // 11/06/2010 11:46:18; date -u -> 1276256778
    EXPECT_DOUBLE_EQ(barry->fixes[0].heading_deg, 337.0);

    const Track* repeated = find(f, "309186000");
    ASSERT_NE(repeated, nullptr);
    ASSERT_EQ(repeated->fixes.size(), 1u);
    EXPECT_EQ(repeated->fixes[0].line, 48u);  // the first of the two rows is kept
    EXPECT_DOUBLE_EQ(repeated->fixes[0].heading_deg, 326.0);
}

TEST(CsvReader, TimesOfDayTakeTheDateOfTheVesselsLaterRows) {
    // gpsd_nl_fixes_head60.csv: 59 rows of one vessel; the first two are T09:47:36 (no date), the
    // rest 2018-08-20T09:47:37..55 as RMC, GGA, GLL triples: 20 distinct times (sort -u), so 39 repeats.
    const auto f = read_csv(data_path("tracks/gpsd_nl_fixes_head60.csv"));
    ASSERT_EQ(f.tracks.size(), 1u);
    const Track& t = f.tracks[0];
    EXPECT_EQ(t.id, "OWN:bundg_zeus_9.log");
    EXPECT_EQ(t.fixes.size(), 20u);
    EXPECT_EQ(f.report.duplicates, 39u);
    EXPECT_EQ(t.fixes.front().time_s, 1534758456.0);  // 2018-08-20T09:47:36Z ; date -u -> 1534758456
    EXPECT_EQ(t.fixes.back().time_s, 1534758456.0 + 19);
    // 09:47:37: the RMC row comes first and gives SOG 5.6, COG 230.5.
    EXPECT_DOUBLE_EQ(t.fixes[1].sog_kn, 5.6);
    EXPECT_DOUBLE_EQ(t.fixes[1].cog_deg, 230.5);
    EXPECT_TRUE(f.report.messages.empty());
}

// ---------------------------------------------------------------------------------------------
// Hand-made failure modes

TEST(CsvReader, TimesOfDayWithoutAnyDateAreDated1970AndSaySo) {
    // time_of_day.csv: T23:59:58, T23:59:59, T00:00:01 (past midnight).
    const auto f = read_csv(data_path("tracks/time_of_day.csv"));
    ASSERT_EQ(f.tracks.size(), 1u);
    const auto& x = f.tracks[0].fixes;
    ASSERT_EQ(x.size(), 3u);
    EXPECT_EQ(x[0].time_s, 86398.0);
    EXPECT_EQ(x[1].time_s, 86399.0);
    EXPECT_EQ(x[2].time_s, 86401.0);  // rollover to 1970-01-02
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_THAT(f.report.messages[0], HasSubstr("time_of_day.csv: times are times of day only"));
    EXPECT_THAT(f.report.messages[0], HasSubstr("1970-01-01"));
    EXPECT_EQ(f.report.skipped, 0u);
}

TEST(CsvReader, TimesOfDayTakeTheCallersDate) {
    ReadOptions options;
    options.date_s = 1408129200.0 + 1234.5;  // any time on 2014-08-15
    const auto f = read_csv(data_path("tracks/time_of_day.csv"), options);
    const auto& x = f.tracks.at(0).fixes;
    const double midnight = 1408129200.0 - 19 * 3600.0;
    EXPECT_EQ(x.at(0).time_s, midnight + 86398.0);
    EXPECT_EQ(x.at(2).time_s, midnight + 86401.0);
    EXPECT_TRUE(f.report.messages.empty());
}

TEST(CsvReader, SkipsImpossibleCoordinatesWithAMessagePerRow) {
    // bad_coordinates.csv: lines 2 and 11 are good; lines 3-10: NaN, inf, 91, 181, -90.5, -180.2, empty, "sixty".
    const std::string path = data_path("tracks/bad_coordinates.csv");
    const auto f = read_csv(path);
    EXPECT_EQ(f.report.rows, 10u);
    EXPECT_EQ(f.report.skipped, 8u);
    EXPECT_EQ(fix_count(f), 2u);
    ASSERT_EQ(f.report.messages.size(), 8u);
    EXPECT_EQ(f.report.messages[0], path + " line 3: latitude nan is not a number; row skipped");
    EXPECT_EQ(f.report.messages[1], path + " line 4: longitude inf is not a number; row skipped");
    EXPECT_EQ(f.report.messages[2], path + " line 5: latitude 91 (AIS: not available); row skipped");
    EXPECT_EQ(f.report.messages[3], path + " line 6: longitude 181 (AIS: not available); row skipped");
    EXPECT_THAT(f.report.messages[4], HasSubstr("line 7: latitude -90.5 is outside [-90, 90]"));
    EXPECT_THAT(f.report.messages[5], HasSubstr("line 8: longitude -180.2 is outside [-180, 180]"));
    EXPECT_THAT(f.report.messages[6], HasSubstr("line 9: no latitude; row skipped"));
    EXPECT_THAT(f.report.messages[7], HasSubstr("line 10: latitude 'sixty' is not a number; row skipped"));
    EXPECT_EQ(f.tracks[0].fixes[0].line, 2u);
    EXPECT_EQ(f.tracks[0].fixes[1].line, 11u);
}

TEST(CsvReader, SkipsImpossibleTimesAndReadsEveryTimeForm) {
    // bad_times.csv lines 2-8: month 13, hour 25, 30 February, date only, "yesterday", empty, minute 60;
    // lines 9-12: epoch s, epoch ms, day-first, +02:00 offset: 19:00:00, :10.5, :20, :30 on 2014-08-15.
    const auto f = read_csv(data_path("tracks/bad_times.csv"));
    EXPECT_EQ(f.report.rows, 11u);
    EXPECT_EQ(f.report.skipped, 7u);
    ASSERT_EQ(f.tracks.size(), 1u);
    std::vector<double> times;
    for (const auto& x : f.tracks[0].fixes) times.push_back(x.time_s - 1408129200.0);
    EXPECT_THAT(times, ElementsAre(0.0, 10.5, 20.0, 30.0));
    ASSERT_GE(f.report.messages.size(), 6u);
    EXPECT_THAT(f.report.messages[0], HasSubstr("line 2: time '2014-13-15T19:00:00Z' is not a valid time"));
    EXPECT_THAT(f.report.messages[3], HasSubstr("line 5: time '2014-08-15' is not a valid time"));
    EXPECT_THAT(f.report.messages[5], HasSubstr("line 7: no time; row skipped"));
}

TEST(CsvReader, SortsRowsThatGoBackInTime) {
    // backwards.csv: 19:00:00, :30, :10, :40, :20 -> two rows earlier than an earlier row.
    const auto f = read_csv(data_path("tracks/backwards.csv"));
    EXPECT_EQ(f.report.reordered, 2u);
    std::vector<double> lons;
    for (const auto& x : f.tracks.at(0).fixes) lons.push_back(x.position.lon);
    EXPECT_THAT(lons, ElementsAre(24.90, 24.91, 24.92, 24.93, 24.94));
    std::vector<std::size_t> lines;
    for (const auto& x : f.tracks.at(0).fixes) lines.push_back(x.line);
    EXPECT_THAT(lines, ElementsAre(2u, 4u, 6u, 3u, 5u));
}

TEST(CsvReader, DropsRepeatedTimesKeepingTheFirstRowAndItsMissingValuesFilled) {
    // repeated.csv: 6 rows at 19:00:00 (x2), :10 (x3), :20 -> 3 fixes, 3 repeats; the second
    // 19:00:00 row alone has a heading (93).
    const auto f = read_csv(data_path("tracks/repeated.csv"));
    EXPECT_EQ(f.report.rows, 6u);
    EXPECT_EQ(f.report.duplicates, 3u);
    const auto& x = f.tracks.at(0).fixes;
    ASSERT_EQ(x.size(), 3u);
    EXPECT_EQ(x[0].line, 2u);
    EXPECT_DOUBLE_EQ(x[0].heading_deg, 93.0);
    EXPECT_TRUE(std::isnan(x[1].heading_deg));
}

TEST(CsvReader, KeepsTheFirstTenMessagesAndCountsTheRest) {
    // many_bad_rows.csv: 15 rows with latitudes 95..109, then one good row.
    const auto f = read_csv(data_path("tracks/many_bad_rows.csv"));
    EXPECT_EQ(f.report.skipped, 15u);
    EXPECT_EQ(f.report.messages.size(), 10u);
    EXPECT_THAT(f.report.messages.back(), HasSubstr("line 11: latitude 104"));
    EXPECT_EQ(fix_count(f), 1u);

    ReadOptions three;
    three.max_messages = 3;
    const auto g = read_csv(data_path("tracks/many_bad_rows.csv"), three);
    EXPECT_EQ(g.report.skipped, 15u);
    EXPECT_EQ(g.report.messages.size(), 3u);
}

TEST(CsvReader, ReadsBomCrlfSemicolonsQuotesAndDecimalCommas) {
    // crlf_bom_semicolon.csv: UTF-8 BOM, CRLF, ';', "Sea; Star", 60,10 / 24,90, heading 511,
    // third row COG 360 (AIS: not available) and heading 92.
    const auto f = read_csv(data_path("tracks/crlf_bom_semicolon.csv"));
    ASSERT_EQ(f.tracks.size(), 1u);
    const Track& t = f.tracks[0];
    EXPECT_EQ(t.id, "230000001");
    EXPECT_EQ(t.name, "Sea; Star");
    ASSERT_EQ(t.fixes.size(), 3u);
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lat, 60.10);
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lon, 24.90);
    EXPECT_DOUBLE_EQ(t.fixes[0].sog_kn, 5.5);
    EXPECT_TRUE(std::isnan(t.fixes[0].heading_deg));
    EXPECT_TRUE(std::isnan(t.fixes[2].cog_deg));
    EXPECT_DOUBLE_EQ(t.fixes[2].heading_deg, 92.0);
    EXPECT_EQ(t.fixes[0].time_s, 1408129200.0);
}

TEST(CsvReader, ReadsTabSeparatedFiles) {
    const auto f = read_csv(data_path("tracks/tab_separated.txt"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "x1");
    ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[1].heading_deg, 11.0);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[1].position.lon, 24.91);
}

TEST(CsvReader, QuotedFieldsMayHoldSeparatorsQuotesAndLineBreaks) {
    // quoted.csv: line 4 opens a quoted name that ends on line 5, so the last row is on line 6.
    const auto f = read_csv(data_path("tracks/quoted.csv"));
    ASSERT_EQ(f.tracks.size(), 3u);
    EXPECT_EQ(f.tracks[0].id, "111");
    EXPECT_EQ(f.tracks[0].name, "Smith, John");
    EXPECT_EQ(f.tracks[1].name, "The \"Quote\"");
    EXPECT_EQ(f.tracks[2].name, "Two\nLines");
    ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_EQ(f.tracks[0].fixes[1].line, 6u);
}

TEST(CsvReader, Latin1NamesBecomeUtf8AndDimensionsAreRead) {
    const auto f = read_csv(data_path("tracks/latin1_name.csv"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].name, "SK\xC3\x85NE");  // SKÅNE in UTF-8
    ASSERT_TRUE(f.tracks[0].dims);
    EXPECT_EQ(*f.tracks[0].dims, (shoal::hull::Dimensions{100, 20, 8, 10}));
}

TEST(CsvReader, HeaderOnlyGivesNoTrack) {
    const auto f = read_csv(data_path("tracks/header_only.csv"));
    EXPECT_EQ(f.report.rows, 0u);
    EXPECT_TRUE(f.tracks.empty());
}

TEST(CsvReader, HeaderWithoutPositionColumnsIsNotATrackFormat) {
    EXPECT_THAT([] { read_csv_text("mmsi,time,x,y\n1,2014-08-15T19:00:00Z,1,2\n", "xy.csv"); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("xy.csv: not a track format shoal reads"),
                                                HasSubstr("no latitude"))));
    EXPECT_THAT([] { read_csv_text("mmsi,lat,lon\n1,60,24\n", "notime.csv"); },
                ThrowsMessage<InputError>(HasSubstr("no time")));
}

// Issue 39: TIMESTAMP_UTC was no time column though time_utc was. Every spelling of a time
// column (a base name with words that say only how it is written) is taken; a local time, an ETA
// or a date alone is not. Each header is read with the same two rows, and the fixes' times are
// the independent answer (19:00:00 and 19:00:30 UTC of 2014-08-15 = 1408129200 s, + 30 s).
TEST(CsvReader, AnySpellingOfATimeColumnIsTheTimeColumn) {
    for (const char* time : {"TIMESTAMP_UTC", "Time (UTC)", "utc-time", "DateTimeUTC", "TimeUTC", "epoch_time", "Date Time", "timestamp.utc",
                             "BaseDateTime", "# Timestamp", "UTC", "time_gmt", "Time [UTC]", "datetime_iso8601"}) {
        SCOPED_TRACE(time);
        EXPECT_TRUE(is_time_column_name(time));
        const auto f = read_csv_text(std::string("mmsi,") + time + ",lat,lon\n1,2014-08-15T19:00:00Z,60,24\n1,2014-08-15T19:00:30Z,60,24.001\n", "t.csv");
        ASSERT_EQ(f.tracks.size(), 1u);
        ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
        EXPECT_EQ(f.tracks[0].fixes[0].time_s, 1408129200.0);
        EXPECT_EQ(f.tracks[0].fixes[1].time_s, 1408129230.0);
    }
    for (const char* other : {"local_time", "time_local", "eta", "date", "timezone", "z", "epoch", "times", "runtime", "time_s"}) {
        SCOPED_TRACE(other);
        EXPECT_FALSE(is_time_column_name(other));
        EXPECT_THAT([&] { read_csv_text(std::string("mmsi,") + other + ",lat,lon\n1,2014-08-15T19:00:00Z,60,24\n", "t.csv"); },
                    ThrowsMessage<InputError>(AllOf(HasSubstr("t.csv: not a track format shoal reads"), HasSubstr("the header has no time ("))));
    }
    // The usual name wins over a spelling further left (the order the names were matched in before).
    const auto f = read_csv_text("mmsi,time_utc_received,TIMESTAMP_UTC,time,lat,lon\n1,x,x,2014-08-15T19:00:00Z,60,24\n", "t.csv");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].fixes[0].time_s, 1408129200.0);
}

TEST(CsvReader, WithoutAnIdColumnTheFileIsOneTrackNamedAfterItsStem) {
    const auto f = read_csv_text("time,lat,lon\n2014-08-15T19:00:00Z,60,24\n2014-08-15T19:00:01Z,60,24.001\n",
                                 "/some/where/exercise-3.csv");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "exercise-3");
    EXPECT_EQ(f.tracks[0].fixes.size(), 2u);
}

TEST(CsvReader, MmsiNamesTheVesselBeforeARowId) {
    const auto f = read_csv_text("id,mmsi,time,lat,lon\n1,230000001,2014-08-15T19:00:00Z,60,24\n"
                                 "2,230000001,2014-08-15T19:00:10Z,60,24.001\n",
                                 "db_dump.csv");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "230000001");
}

TEST(CsvReader, RowsWithTooFewFieldsOrNoIdAreSkipped) {
    const auto f = read_csv_text("id,time,lat,lon\na,2014-08-15T19:00:00Z,60\n,2014-08-15T19:00:00Z,60,24\n", "x.csv");
    EXPECT_EQ(f.report.skipped, 2u);
    EXPECT_THAT(f.report.messages.at(0), HasSubstr("x.csv line 2: has 3 fields, the header needs 4; row skipped"));
    EXPECT_THAT(f.report.messages.at(1), HasSubstr("x.csv line 3: no vessel id; row skipped"));
}

TEST(CsvReader, RowsWithMoreFieldsThanTheHeaderNamesAreSkippedUnlessTheRestAreBlank) {
    // Before: read as if the extra fields were not there. "60,24" of a decimal comma put the
    // vessel at 60, 24; a name with a comma shifted the length, width and draught after it.
    const auto f = read_csv_text(
        "mmsi,time,lat,lon,sog,name,length\n"
        "1,2014-08-15T19:00:00Z,60.1,24.9,10,A,100\n"
        "1,2014-08-15T19:00:10Z,60,1,24,9,10,A,100\n"
        "1,2014-08-15T19:00:20Z,60.1,24.902,10,SHIP, THE,100\n"
        "1,2014-08-15T19:00:30Z,60.1,24.903,10,A,100,\n"
        "1,2014-08-15T19:00:40Z,60.1,24.904,10,A,100, ,\t\n",
        "x.csv");
    EXPECT_EQ(f.report.skipped, 2u);
    ASSERT_EQ(f.report.messages.size(), 2u);
    EXPECT_EQ(f.report.messages[0],
              "x.csv line 3: has 9 fields, the header 7 (a decimal comma in a comma-separated file, or a comma inside an unquoted field?); row skipped");
    EXPECT_THAT(f.report.messages[1], HasSubstr("x.csv line 4: has 8 fields, the header 7 ("));
    ASSERT_EQ(f.tracks.size(), 1u);
    ASSERT_EQ(f.tracks[0].fixes.size(), 3u);
    EXPECT_EQ(f.tracks[0].fixes[1].line, 5u);
    EXPECT_EQ(f.tracks[0].fixes[2].line, 6u);
    const auto g = read_csv_text("mmsi;time;lat;lon\n1;2014-08-15T19:00:00Z;60,1;24,9;x\n1;2014-08-15T19:00:10Z;60,1;24,9\n", "g.csv");
    ASSERT_EQ(g.report.messages.size(), 1u);
    EXPECT_EQ(g.report.messages[0], "g.csv line 2: has 5 fields, the header 4 (a separator inside an unquoted field?); row skipped");
}

// ---------------------------------------------------------------------------------------------
// Pieces

TEST(CsvSplitter, DetectsTheSeparatorAndSplitsQuotedFields) {
    std::vector<std::string_view> f;
    CsvSplitter a("a;b,c;d\n1;\"2;3\";4\n");
    EXPECT_EQ(a.separator(), ';');
    ASSERT_TRUE(a.next(f));
    EXPECT_THAT(f, ElementsAre("a", "b,c", "d"));
    ASSERT_TRUE(a.next(f));
    EXPECT_THAT(f, ElementsAre("1", "2;3", "4"));
    EXPECT_FALSE(a.next(f));

    CsvSplitter b("x\ty\r\n\r\n 1 \t 2 \r\n,\t\n");
    EXPECT_EQ(b.separator(), '\t');
    ASSERT_TRUE(b.next(f));
    ASSERT_TRUE(b.next(f));  // the blank line is skipped
    EXPECT_THAT(f, ElementsAre("1", "2"));
    EXPECT_EQ(b.line(), 3u);
    ASSERT_TRUE(b.next(f));
    EXPECT_THAT(f, ElementsAre(",", ""));

    CsvSplitter none("just words\n");
    EXPECT_EQ(none.separator(), '\0');
}

TEST(CsvSplitter, RecordsWithoutQuotesSplitAsANaiveSplitDoes) {
    // The splitter's bit-mask path (records without a quote) against a split of each line at
    // every separator, fields trimmed, blank lines dropped: random fields of 0 to 150 bytes (so
    // records cross the 64-byte windows anywhere) with blanks, tabs and CRs, in text given whole
    // and in blocks that end anywhere, with the record cut there read again in the next block.
    std::mt19937_64 rng(15);
    const std::string alphabet = "abc019.- \t\r_/:";
    for (int round = 0; round < 300; ++round) {
        const char sep = round % 3 == 0 ? ',' : round % 3 == 1 ? ';' : '\t';
        std::string text = std::string("h1") + sep + "h2" + sep + "h3\n";
        const std::size_t records = 1 + rng() % 60;
        for (std::size_t r = 0; r < records; ++r) {
            const std::size_t fields = rng() % 8;
            for (std::size_t k = 0; k <= fields; ++k) {
                if (k) text += sep;
                const std::size_t len = rng() % 4 == 0 ? rng() % 150 : rng() % 8;
                for (std::size_t i = 0; i < len; ++i) {
                    char c = alphabet[rng() % alphabet.size()];
                    if (c == sep) c = 'x';
                    text += c;
                }
            }
            if (r + 1 < records || rng() % 2) text += '\n';
        }
        // The independent answer: line by line.
        std::vector<std::pair<std::size_t, std::vector<std::string>>> want;
        std::size_t line = 1, start = 0;
        while (start < text.size()) {
            const std::size_t end = std::min(text.find('\n', start), text.size());
            std::vector<std::string> f;
            std::size_t from = start;
            for (;;) {
                const std::size_t at = std::min(text.find(sep, from), end);
                f.emplace_back(shoal::track::detail::trim(std::string_view(text).substr(from, at - from)));
                if (at >= end) break;
                from = at + 1;
            }
            if (!(f.size() == 1 && f[0].empty())) want.emplace_back(line, f);
            ++line;
            start = end + 1;
        }
        auto same = [&](const std::vector<std::string_view>& got, std::size_t k) {
            return std::vector<std::string>(got.begin(), got.end()) == want[k].second;
        };
        {  // whole
            CsvSplitter sp(text);
            ASSERT_EQ(sp.separator(), sep);
            std::vector<std::string_view> f;
            std::size_t k = 0;
            for (; sp.next(f); ++k) {
                ASSERT_LT(k, want.size());
                ASSERT_TRUE(same(f, k)) << "round " << round << " record " << k;
                ASSERT_EQ(sp.line(), want[k].first);
            }
            ASSERT_EQ(k, want.size());
        }
        {  // in blocks
            const std::size_t block = 1 + rng() % 200;
            std::size_t taken = 0, have = std::min(text.size(), std::max<std::size_t>(block, text.find('\n') + 1));
            CsvSplitter sp(std::string_view(text).substr(0, have), have == text.size());
            std::vector<std::string_view> f;
            std::size_t k = 0;
            for (;;) {
                while (sp.next(f)) {
                    ASSERT_LT(k, want.size());
                    ASSERT_TRUE(same(f, k)) << "round " << round << " record " << k << " in blocks of " << block;
                    ASSERT_EQ(sp.line(), want[k].first);
                    ++k;
                }
                taken += sp.consumed();
                if (have == text.size()) break;
                have = std::min(text.size(), have + block);
                sp.more(std::string_view(text).substr(taken, have - taken), have == text.size());
            }
            ASSERT_EQ(k, want.size()) << "round " << round << " in blocks of " << block;
        }
    }
}

TEST(CsvReader, AQuoteThatDoesNotCloseCostsItsOwnRowOnly) {
    // An AIS name with a stray quote ("ALPHA): before, its field took in every row after it
    // up to the end of the file, and they were lost without a word.
    std::string text = "mmsi,time,lat,lon,name\n";
    for (int i = 0; i < 200; ++i) {
        char row[96];
        std::snprintf(row, sizeof row, "230000001,2014-08-15T19:%02d:%02dZ,60,%.4f,%s\n", i / 60, i % 60, 24 + i * 1e-4, i == 100 ? "\"ALPHA" : "ALPHA");
        text += row;
    }
    const auto f = read_csv_text(text, "stray.csv");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].fixes.size(), 199u);
    EXPECT_EQ(f.report.skipped, 1u);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_THAT(f.report.messages[0], HasSubstr("stray.csv line 102: a quote (\") opens a field that does not close"));
    EXPECT_THAT(f.report.messages[0], HasSubstr("row skipped"));
    // A quoted name over two lines, closed as a field's quotes close, is one row as before.
    const auto g = read_csv_text("mmsi,time,lat,lon,name\n230000001,2014-08-15T19:00:00Z,60,24,\"TWO\nLINES\"\n"
                                 "230000001,2014-08-15T19:00:10Z,60,24.001,B\n",
                                 "two.csv");
    EXPECT_EQ(g.report.skipped, 0u);
    ASSERT_EQ(g.tracks.size(), 1u);
    EXPECT_EQ(g.tracks[0].fixes.size(), 2u);
    // Said, though: a stray quote closed by another a few lines on, before a separator, joins
    // the rows between into one as RFC 4180 reads it (rows 3-5 here), and only this says so.
    EXPECT_THAT(g.report.messages, ElementsAre("two.csv: 1 row holds line ends inside quotes, each read as one row (the first on line 2, "
                                               "over 2 lines); a stray quote (\") closed by another on a later line joins the rows between so"));
    const auto m = read_csv_text("mmsi,time,lat,lon,name\n230000001,2014-08-15T19:00:00Z,60,24,A\n230000001,2014-08-15T19:00:10Z,60,24.001,\"SEA STAR\n"
                                 "230000001,2014-08-15T19:00:20Z,60,24.002,A\n230000001,2014-08-15T19:00:30Z,60,24.003,OCEAN\"\n"
                                 "230000001,2014-08-15T19:00:40Z,60,24.004,A\n",
                                 "merged.csv");
    ASSERT_EQ(m.tracks.size(), 1u);
    EXPECT_EQ(m.tracks[0].fixes.size(), 3u);
    EXPECT_THAT(m.report.messages, ElementsAre(HasSubstr("merged.csv: 1 row holds line ends inside quotes, each read as one row (the first on line 3, over 3 lines)")));
}

TEST(CsvReader, AStrayQuoteBesideARecordOverTheLineLimitCostsTheSameRowsReadWholeOrStreamed) {
    // A record over 1 MiB is read without being held (read_long_record); a stray quote there, or
    // on the row before it, used to take in every row after it when the file was streamed (50
    // fixes of 200), while the same text read whole cost two rows.
    const std::string big(3 << 20, 'x');
    for (const bool quote_in_long : {true, false}) {
        std::string text = "mmsi,time,lat,lon,name\n";
        for (int i = 0; i < 200; ++i) {
            char row[96];
            std::snprintf(row, sizeof row, "230000001,2014-08-15T19:%02d:%02dZ,60,%.4f,", i / 60, i % 60, 24 + i * 1e-4);
            text += row;
            if (i == 50) text += quote_in_long ? "\"" + big : "\"ALPHA";
            else if (i == 51 && !quote_in_long) text += big;
            else text += "ALPHA";
            text += '\n';
        }
        shoal::test::TempDir dir;
        const std::string path = dir.file("long.csv");
        {
            std::ofstream out(path, std::ios::binary);
            out << text;
        }
        const auto whole = read_csv_text(text, path);
        const auto streamed = read_csv(path);
        ASSERT_EQ(whole.tracks.size(), 1u);
        ASSERT_EQ(streamed.tracks.size(), 1u);
        const std::size_t lost = quote_in_long ? 1 : 2;  // the stray quote's row (and the long one)
        EXPECT_EQ(whole.tracks[0].fixes.size(), 200 - lost) << quote_in_long;
        EXPECT_EQ(streamed.tracks[0].fixes.size(), 200 - lost) << quote_in_long;
        EXPECT_EQ(streamed.report.skipped, whole.report.skipped) << quote_in_long;
        EXPECT_EQ(streamed.report.messages, whole.report.messages) << quote_in_long;
        EXPECT_THAT(streamed.report.messages.at(0), HasSubstr("long.csv line 52: a quote (\") opens a field that does not close"));
    }
}

TEST(CsvSplitter, AQuoteThatDoesNotCloseIsItsOwnLineSplitAsItStands) {
    std::vector<std::string_view> f;
    auto records = [&](std::string_view text) {
        std::vector<std::tuple<std::size_t, bool, std::vector<std::string>>> out;
        CsvSplitter sp(text);
        EXPECT_TRUE(sp.next(f));  // the header
        while (sp.next(f)) out.emplace_back(sp.line(), sp.quote_not_closed(), std::vector<std::string>(f.begin(), f.end()));
        return out;
    };
    using R = std::tuple<std::size_t, bool, std::vector<std::string>>;
    using V = std::vector<std::string>;
    // Not closed by the end of the file.
    EXPECT_THAT(records("h,n\n1,\"ALPHA\n2,b\n3,c\n"), ElementsAre(R{2, true, V{"1", "\"ALPHA"}}, R{3, false, V{"2", "b"}}, R{4, false, V{"3", "c"}}));
    // Closed by a later field's opening quote, text after it.
    EXPECT_THAT(records("h,n\n1,\"ALPHA\n2,\"B, C\"\n3,x\n"),
                ElementsAre(R{2, true, V{"1", "\"ALPHA"}}, R{3, false, V{"2", "B, C"}}, R{4, false, V{"3", "x"}}));
    // A field over two lines that closes as a field does: one record, as RFC 4180 reads it.
    EXPECT_THAT(records("h,n\n1,\"two\nlines\" \r\n2,x\n"), ElementsAre(R{2, false, V{"1", "two\nlines"}}, R{4, false, V{"2", "x"}}));
    // Not closed on the last line, no line after it: the field runs to the end, as before.
    EXPECT_THAT(records("h,n\n1,\"ALPHA"), ElementsAre(R{2, false, V{"1", "ALPHA"}}));
    // At most max_quoted_lines line ends in a field.
    const std::size_t cap = CsvSplitter::max_quoted_lines;
    auto lines = [](std::size_t k) {
        std::string s = "h,n\n1,\"";
        for (std::size_t i = 0; i < k; ++i) s += "x\n";
        return s + "end\"\n2,b\n";
    };
    const auto under = records(lines(cap - 1));
    ASSERT_EQ(under.size(), 2u);
    EXPECT_FALSE(std::get<1>(under[0]));
    EXPECT_EQ(std::get<0>(under[1]), cap + 2);
    const auto over = records(lines(cap));
    ASSERT_GE(over.size(), 2u);
    EXPECT_EQ(over[0], (R{2, true, V{"1", "\"x"}}));
    EXPECT_EQ(std::get<0>(over[1]), 3u);
}

TEST(CsvSplitter, QuotesLeftOpenGiveTheSameRecordsInBlocksAsWhole) {
    // Random lines of plain fields, quoted fields (separators, doubled quotes, line ends inside)
    // and stray quotes: the records, their lines and quote_not_closed() the same whether the
    // text comes whole or in blocks ending anywhere; a line whose quote did not close is its
    // line split at each separator.
    std::mt19937_64 rng(40);
    std::vector<std::string_view> f;
    for (int round = 0; round < 3000; ++round) {
        std::string text = "a,b,c\n";
        const std::size_t lines = 1 + rng() % 30;
        for (std::size_t r = 0; r < lines; ++r) {
            const std::size_t fields = 1 + rng() % 4;
            for (std::size_t k = 0; k < fields; ++k) {
                if (k) text += ',';
                switch (rng() % 8) {
                case 0: text += "\"ALPHA"; break;                         // stray
                case 1: text += "\"q, \"\"x\"\"\""; break;                  // quoted, doubled quotes
                case 2: text += "\"two\nlines\""; break;                   // over a line end
                case 3: text += "\"shut\" tail"; break;                     // text after the quote
                case 4: text += std::string(rng() % 3, ' ') + "v" + std::to_string(rng() % 100); break;
                default: text += "w" + std::to_string(rng() % 1000);
                }
            }
            if (r + 1 < lines || rng() % 2) text += rng() % 4 ? "\n" : "\r\n";
        }
        std::vector<std::tuple<std::size_t, bool, std::vector<std::string>>> whole;
        {
            CsvSplitter sp(text);
            while (sp.next(f)) {
                whole.emplace_back(sp.line(), sp.quote_not_closed(), std::vector<std::string>(f.begin(), f.end()));
                if (sp.quote_not_closed()) {  // its own line, split at each separator
                    std::size_t at = 0;
                    for (std::size_t l = 1; l < sp.line(); ++l) at = text.find('\n', at) + 1;
                    const std::string line = text.substr(at, text.find('\n', at) - at);
                    std::vector<std::string> naive;
                    for (std::size_t from = 0;;) {
                        const std::size_t to = std::min(line.find(',', from), line.size());
                        naive.emplace_back(shoal::track::detail::trim(std::string_view(line).substr(from, to - from)));
                        if (to == line.size()) break;
                        from = to + 1;
                    }
                    ASSERT_EQ(std::get<2>(whole.back()), naive) << "round " << round << " line " << sp.line();
                }
            }
        }
        const std::size_t block = 1 + rng() % 64;
        std::size_t taken = 0, have = std::min(text.size(), std::max<std::size_t>(block, text.find('\n') + 1));
        CsvSplitter sp(std::string_view(text).substr(0, have), have == text.size());
        std::size_t k = 0;
        for (;;) {
            while (sp.next(f)) {
                ASSERT_LT(k, whole.size()) << "round " << round;
                ASSERT_EQ((std::tuple<std::size_t, bool, std::vector<std::string>>(sp.line(), sp.quote_not_closed(),
                                                                                  std::vector<std::string>(f.begin(), f.end()))),
                          whole[k])
                    << "round " << round << " record " << k << " in blocks of " << block;
                ++k;
            }
            taken += sp.consumed();
            if (have == text.size()) break;
            have = std::min(text.size(), have + block);
            sp.more(std::string_view(text).substr(taken, have - taken), have == text.size());
        }
        ASSERT_EQ(k, whole.size()) << "round " << round << " in blocks of " << block;
    }
}

TEST(CsvNames, MatchesCaseAndHashInsensitively) {
    EXPECT_EQ(normalise_column_name("# Timestamp"), "timestamp");
    EXPECT_EQ(normalise_column_name(" BaseDateTime "), "basedatetime");
    EXPECT_EQ(to_utf8("plain"), "plain");
    EXPECT_EQ(to_utf8("\xC3\x85"), "\xC3\x85");      // valid UTF-8 stays
    EXPECT_EQ(to_utf8("\xC5"), "\xC3\x85");          // Latin-1 Å
    EXPECT_EQ(to_utf8("caf\xE9!"), "caf\xC3\xA9!");  // Latin-1 é
}

}  // namespace

// Exercise mode (issue 18): an exercise column and a role column.

namespace {

/// Two exercises in one file: vessel 235000001 sails in both (two tracks), 235000002 in A only.
/// Line 6 has no exercise, line 7 an unknown role: both bad rows. 235000004 (lines 8, 9) gives
/// both roles: a target, said. Columns are found in any case ("Exercise", "ROLE").
constexpr const char* two_exercises =
    "mmsi,Exercise,ROLE,timestamp,lat,lon\n"
    "235000001,A,own ship,2024-05-01T10:00:00Z,50.70,-1.00\n"  // line 2
    "235000001,B,Trainee,2024-05-01T10:00:00Z,50.71,-1.00\n"
    "235000002,A,target,2024-05-01T10:00:00Z,50.72,-1.00\n"
    "235000001,A,own,2024-05-01T10:01:00Z,50.70,-0.99\n"
    "235000001,,trainee,2024-05-01T10:02:00Z,50.70,-0.98\n"   // line 6: no exercise
    "235000002,A,pilot,2024-05-01T10:01:00Z,50.72,-0.99\n"     // line 7: not a role
    "235000004,B,trainee,2024-05-01T10:00:00Z,50.73,-1.00\n"
    "235000004,B,target,2024-05-01T10:01:00Z,50.73,-0.99\n";

ReadOptions columns() {
    ReadOptions o;
    o.exercise_column = "exercise";
    o.role_column = "role";
    return o;
}

TEST(CsvReader, AnExerciseColumnKeysTracksByExerciseAndIdWithTheirRoles) {
    const TrackFile f = read_csv_text(two_exercises, "two.csv", columns());
    ASSERT_EQ(f.tracks.size(), 4u);
    std::vector<std::string> keys;
    for (const auto& t : f.tracks) keys.push_back(t.exercise + "/" + t.id + "/" + t.role + "/" + std::to_string(t.fixes.size()));
    // In first-appearance order; the vessel of two exercises is two tracks.
    EXPECT_THAT(keys, ElementsAre("A/235000001/trainee/2", "B/235000001/trainee/1", "A/235000002/target/1", "B/235000004/target/2"));
    EXPECT_EQ(f.report.rows, 8u);
    EXPECT_EQ(f.report.skipped, 2u);
    const std::string said = [&] {
        std::string s;
        for (const auto& m : f.report.messages) s += m + "\n";
        return s;
    }();
    EXPECT_THAT(said, HasSubstr("two.csv line 6: no exercise (column 'exercise' is empty); row skipped"));
    EXPECT_THAT(said, HasSubstr("two.csv line 7: role 'pilot' (column 'role') is neither trainee (own, own ship) nor target; row skipped"));
    EXPECT_THAT(said, HasSubstr("two.csv: track '235000004' of exercise 'B': its rows disagree on the role (trainee on line 8, target on "
                                "line 9 of column 'role'): it is taken as a target"));
    // Without the columns asked for, the same file is three vessels, the rows merged by id.
    const TrackFile plain = read_csv_text(two_exercises, "two.csv");
    EXPECT_EQ(plain.tracks.size(), 3u);
    for (const auto& t : plain.tracks) EXPECT_EQ(t.exercise + t.role, "");
}

TEST(CsvReader, AFileWithoutTheExerciseOrRoleColumnIsAnErrorNamingFileAndColumn) {
    const std::string text = "mmsi,timestamp,lat,lon\n235000001,2024-05-01T10:00:00Z,50.70,-1.00\n";
    ReadOptions o;
    o.exercise_column = "Exercise";
    EXPECT_THAT([&] { read_csv_text(text, "plain.csv", o); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("plain.csv: the header has no column 'Exercise', the exercise column"),
                                                HasSubstr("header: mmsi,timestamp,lat,lon"))));
    ReadOptions r;
    r.role_column = "role";
    EXPECT_THAT([&] { read_csv_text(text, "plain.csv", r); },
                ThrowsMessage<InputError>(HasSubstr("plain.csv: the header has no column 'role', the role column")));
}

TEST(CsvReader, ARowShortOfTheExerciseColumnIsABadRow) {
    ReadOptions o;
    o.exercise_column = "exercise";
    const TrackFile f = read_csv_text("mmsi,timestamp,lat,lon,exercise\n235000001,2024-05-01T10:00:00Z,50.70,-1.00,A\n"
                                      "235000001,2024-05-01T10:01:00Z,50.70,-0.99\n",
                                      "short.csv", o);
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].fixes.size(), 1u);
    EXPECT_EQ(f.report.skipped, 1u);
    EXPECT_THAT(f.report.messages.at(0), HasSubstr("short.csv line 3: has 4 fields, the header needs 5"));
}

TEST(TrackReader, GpxAndNmeaHaveNoColumnsToReadTheExerciseFrom) {
    ReadOptions o;
    o.exercise_column = "exercise";
    EXPECT_THAT([&] { read_tracks(data_path("tracks/track_and_route.gpx"), o); },
                ThrowsMessage<InputError>(HasSubstr("track_and_route.gpx: a GPX file has no column 'exercise', the exercise column")));
    ReadOptions r;
    r.role_column = "role";
    EXPECT_THAT([&] { read_tracks_packed(data_path("tracks/midnight.nmea"), r); },
                ThrowsMessage<InputError>(HasSubstr("midnight.nmea: an NMEA log has no column 'role', the role column")));
}

TEST(TrackRoles, RoleValuesInAnyCase) {
    EXPECT_STREQ(role_value("Own Ship"), "trainee");
    EXPECT_STREQ(role_value(" own_ship "), "trainee");
    EXPECT_STREQ(role_value("OWN"), "trainee");
    EXPECT_STREQ(role_value("trainee"), "trainee");
    EXPECT_STREQ(role_value("TARGET"), "target");
    EXPECT_EQ(role_value("pilot"), nullptr);
    EXPECT_EQ(role_value(""), nullptr);
    EXPECT_EQ(role_value("target but much longer than any role"), nullptr);
}

}  // namespace
