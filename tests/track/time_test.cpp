// Tests of the time parsing and formatting in track/time.hpp.
//
// Expected epoch seconds come from GNU date, independently of shoal:
//   date -u -d '2014-08-15T19:00:00Z' +%s   -> 1408129200
//   date -u -d '2016-02-29T12:00:00Z' +%s   -> 1456747200
//   date -u -d '2000-03-01T00:00:00Z' +%s   -> 951868800
//   date -u -d '1969-12-31T23:59:59Z' +%s   -> -1
//   date -u -d '2038-01-19T03:14:08Z' +%s   -> 2147483648
//   date -u -d '1900-01-01T00:00:00Z' +%s   -> -2208988800
//   date -u -d '2400-02-29T00:00:00Z' +%s   -> 13574563200

#include <shoal/track/time.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <random>
#include <string>

namespace {

using namespace shoal::track;

constexpr double t_2014_08_15_19 = 1408129200.0;  // 2014-08-15T19:00:00Z

TEST(ParseIso8601, ReadsUtcWithAndWithoutZoneAndFraction) {
    EXPECT_EQ(parse_iso8601("2014-08-15T19:00:00Z"), t_2014_08_15_19);
    EXPECT_EQ(parse_iso8601("2014-08-15T19:00:00"), t_2014_08_15_19);  // MarineCadastre: no zone = UTC
    EXPECT_EQ(parse_iso8601("2014-08-15 19:00:00"), t_2014_08_15_19);  // space for T
    EXPECT_EQ(parse_iso8601("2014-08-15T19:00Z"), t_2014_08_15_19);    // no seconds
    EXPECT_EQ(parse_iso8601("  2014-08-15T19:00:00Z\r"), t_2014_08_15_19);
    EXPECT_EQ(parse_iso8601("2014-08-15 19:00:00 UTC"), t_2014_08_15_19);
    EXPECT_DOUBLE_EQ(*parse_iso8601("2014-08-15T19:00:00.042Z"), t_2014_08_15_19 + 0.042);
    EXPECT_DOUBLE_EQ(*parse_iso8601("2014-08-15T19:00:00,5Z"), t_2014_08_15_19 + 0.5);
}

TEST(ParseIso8601, AppliesZoneOffsets) {
    EXPECT_EQ(parse_iso8601("2014-08-15T21:00:00+02:00"), t_2014_08_15_19);
    EXPECT_EQ(parse_iso8601("2014-08-15T21:00:00+0200"), t_2014_08_15_19);
    EXPECT_EQ(parse_iso8601("2014-08-15T21:00:00+02"), t_2014_08_15_19);
    EXPECT_EQ(parse_iso8601("2014-08-15T14:30:00-04:30"), t_2014_08_15_19);
}

TEST(ParseIso8601, HandlesCalendarEdges) {
    EXPECT_EQ(parse_iso8601("2016-02-29T12:00:00Z"), 1456747200.0);  // leap day
    EXPECT_EQ(parse_iso8601("2000-03-01T00:00:00Z"), 951868800.0);   // after the 400-year leap day
    EXPECT_EQ(parse_iso8601("1969-12-31T23:59:59Z"), -1.0);
    EXPECT_EQ(parse_iso8601("2038-01-19T03:14:08Z"), 2147483648.0);
    EXPECT_EQ(parse_iso8601("1900-01-01T00:00:00Z"), -2208988800.0);
    EXPECT_EQ(parse_iso8601("2400-02-29T00:00:00Z"), 13574563200.0);
}

TEST(ParseIso8601, RejectsImpossibleTimesAndDateOnly) {
    for (const char* bad : {"2014-13-15T19:00:00Z", "2014-00-15T19:00:00Z", "2014-02-30T19:00:00Z",
                            "2015-02-29T00:00:00Z", "1900-02-29T00:00:00Z", "2014-04-31T00:00:00Z",
                            "2014-08-15T25:00:00Z", "2014-08-15T24:00:00Z", "2014-08-15T19:60:00Z",
                            "2014-08-15T19:00:60Z", "2014-08-15", "2014-08-15T", "2014-08-15T19",
                            "2014-08-15T19:00:00+25:00", "2014-08-15T19:00:00X", "2014-8-15T19:00:00Z",
                            "2014-08-15T19:00:00.Z", ""})
        EXPECT_EQ(parse_iso8601(bad), std::nullopt) << bad;
}

TEST(ParseDayFirst, ReadsDanishMaritimeAuthorityTimestamps) {
    // date -u -d '2013-03-18T09:19:09Z' +%s -> 1363598349
    EXPECT_EQ(parse_day_first("18/03/2013 09:19:09"), 1363598349.0);
    EXPECT_EQ(parse_day_first("18/3/2013 09:19:09"), 1363598349.0);
    EXPECT_DOUBLE_EQ(*parse_day_first("18/03/2013 09:19:09.25"), 1363598349.25);
    EXPECT_EQ(parse_day_first("15/08/2014 19:00"), t_2014_08_15_19);
    EXPECT_EQ(parse_day_first("30/02/2013 09:19:09"), std::nullopt);
    EXPECT_EQ(parse_day_first("18/13/2013 09:19:09"), std::nullopt);
    EXPECT_EQ(parse_day_first("18/03/2013"), std::nullopt);
    EXPECT_EQ(parse_day_first("18/03/2013 25:19:09"), std::nullopt);
}

TEST(ParseEpoch, SecondsAboveOneHundredMillionAndMillisecondsAboveOneHundredBillion) {
    EXPECT_EQ(parse_epoch("1408129200"), t_2014_08_15_19);
    EXPECT_DOUBLE_EQ(*parse_epoch("1408129200.25"), t_2014_08_15_19 + 0.25);
    EXPECT_DOUBLE_EQ(*parse_epoch("1408129200250"), t_2014_08_15_19 + 0.25);  // milliseconds
    EXPECT_EQ(parse_epoch("100000001"), 100000001.0);
    EXPECT_EQ(parse_epoch("99999999"), std::nullopt);  // too small to be sure it is a time
    EXPECT_EQ(parse_epoch("-1408129200"), std::nullopt);
    EXPECT_EQ(parse_epoch("nan"), std::nullopt);
    EXPECT_EQ(parse_epoch("inf"), std::nullopt);
    EXPECT_EQ(parse_epoch("14081292OO"), std::nullopt);
}

TEST(ParseTimeOfDay, ReadsWithOrWithoutT) {
    EXPECT_EQ(parse_time_of_day("T09:47:36"), 9 * 3600.0 + 47 * 60 + 36);
    EXPECT_EQ(parse_time_of_day("09:47:36"), 9 * 3600.0 + 47 * 60 + 36);
    EXPECT_DOUBLE_EQ(*parse_time_of_day("T20:02:54.00"), 20 * 3600.0 + 2 * 60 + 54);
    EXPECT_DOUBLE_EQ(*parse_time_of_day("23:59:59.5Z"), 86399.5);
    EXPECT_EQ(parse_time_of_day("T24:00:00"), std::nullopt);
    EXPECT_EQ(parse_time_of_day("T09:61:00"), std::nullopt);
    EXPECT_EQ(parse_time_of_day("T09:47:36 tomorrow"), std::nullopt);
}

TEST(ParseTime, TellsEveryFormApartAndFlagsAMissingDate) {
    auto iso = parse_time("2014-08-15T19:00:00Z");
    ASSERT_TRUE(iso);
    EXPECT_EQ(iso->seconds, t_2014_08_15_19);
    EXPECT_FALSE(iso->date_missing);

    auto dmy = parse_time("15/08/2014 19:00:00");
    ASSERT_TRUE(dmy);
    EXPECT_EQ(dmy->seconds, t_2014_08_15_19);

    auto epoch = parse_time("1408129200");
    ASSERT_TRUE(epoch);
    EXPECT_EQ(epoch->seconds, t_2014_08_15_19);

    auto tod = parse_time("T19:00:00");
    ASSERT_TRUE(tod);
    EXPECT_TRUE(tod->date_missing);
    EXPECT_EQ(tod->seconds, 19 * 3600.0);

    for (const char* bad : {"", "T", "2014-08-15", "yesterday", "12345", "2014-13-01T00:00:00Z", "31/04/2014 10:00:00"})
        EXPECT_EQ(parse_time(bad), std::nullopt) << bad;
}

TEST(FormatIso8601, WholeSecondsWithoutFractionAndFractionWithFixedDigits) {
    EXPECT_EQ(format_iso8601(t_2014_08_15_19, 3), "2014-08-15T19:00:00Z");
    EXPECT_EQ(format_iso8601(t_2014_08_15_19 + 0.042, 3), "2014-08-15T19:00:00.042Z");
    EXPECT_EQ(format_iso8601(t_2014_08_15_19 + 0.5, 3), "2014-08-15T19:00:00.500Z");
    EXPECT_EQ(format_iso8601(t_2014_08_15_19 + 0.5, 0), "2014-08-15T19:00:01Z");  // rounded half away
    EXPECT_EQ(format_iso8601(t_2014_08_15_19 + 0.0004, 3), "2014-08-15T19:00:00Z");
    EXPECT_EQ(format_iso8601(t_2014_08_15_19 - 0.0004, 3), "2014-08-15T19:00:00Z");  // carries into the minute
    EXPECT_EQ(format_iso8601(1456747200.0, 3), "2016-02-29T12:00:00Z");
    EXPECT_EQ(format_iso8601(-1.0, 3), "1969-12-31T23:59:59Z");
    EXPECT_EQ(format_iso8601(-0.25, 2), "1969-12-31T23:59:59.75Z");
    EXPECT_EQ(format_iso8601(0.0, 3), "1970-01-01T00:00:00Z");
    EXPECT_EQ(format_iso8601(NAN, 3), "");
}

TEST(FormatIso8601, RoundTripsThroughTheParser) {
    for (double t = -2208988800.0; t < 13574563200.0; t += 86400.0 * 97.3 + 0.125) {
        const std::string s = format_iso8601(t, 3);
        ASSERT_EQ(parse_iso8601(s), t) << s;
    }
}

/// Against glibc's gmtime_r and snprintf (an independent calendar and formatter), on random
/// times from year 1 to 9999 at every number of decimals, and years past 9999.
TEST(FormatIso8601, WritesWhatGmtimeAndPrintfWrite) {
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<long long> seconds(-62135596800LL, 253402300799LL);  // 0001-01-01 .. 9999-12-31
    std::uniform_int_distribution<long long> ticks(0, 999999999);
    auto expected = [](long long secs, long long frac, int decimals) {
        const std::time_t t = static_cast<std::time_t>(secs);
        std::tm tm{};
        gmtime_r(&t, &tm);
        char buf[96];
        int n = std::snprintf(buf, sizeof buf, "%04lld-%02d-%02dT%02d:%02d:%02d", tm.tm_year + 1900LL, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour,
                              tm.tm_min, tm.tm_sec);
        if (frac != 0) n += std::snprintf(buf + n, sizeof buf - static_cast<std::size_t>(n), ".%0*lld", decimals, frac);
        return std::string(buf, static_cast<std::size_t>(n)) + "Z";
    };
    int checked = 0;
    for (int i = 0; i < 200000; ++i) {
        const int decimals = i % 10;
        const long long scale = static_cast<long long>(std::pow(10.0, decimals));
        const long long secs = i % 7 == 0 ? seconds(rng) % 100000 : seconds(rng);  // some near the epoch, on both sides
        const long long frac = i % 3 == 0 ? 0 : ticks(rng) % scale;
        // A time whose ticks at `decimals` are exact: decimals where a double holds them.
        if (std::fabs(static_cast<double>(secs)) * static_cast<double>(scale) > 1e14) continue;
        const double t = static_cast<double>(secs * scale + frac) / static_cast<double>(scale);
        ASSERT_EQ(format_iso8601(t, decimals), expected(secs, frac, decimals)) << secs << " + " << frac << " at " << decimals;
        ++checked;
    }
    EXPECT_GT(checked, 80000);
    EXPECT_EQ(format_iso8601(253402300800.0, 0), expected(253402300800LL, 0, 0));  // 10000-01-01: five digits
    EXPECT_EQ(format_iso8601(253402300800.0, 0), "10000-01-01T00:00:00Z");
    EXPECT_EQ(format_iso8601(-62135596801.0, 0), expected(-62135596801LL, 0, 0));  // year 0
    EXPECT_EQ(format_iso8601(-62198755200.0, 0), expected(-62198755200LL, 0, 0));  // year -1 ("-001")
}

TEST(DayClock, NumbersDaysAcrossMidnightAndDatesEarlierTimes) {
    DayClock clock;
    EXPECT_EQ(clock.day_of(86398.0), 0);  // 23:59:58
    EXPECT_FALSE(clock.has_date());
    EXPECT_EQ(clock.day_of(1.0), 1);      // 00:00:01: rollover
    EXPECT_EQ(clock.day_of(86399.0), 0);  // a late sentence from before midnight
    EXPECT_EQ(clock.day_of(2.0), 1);
    // 2014-08-16T00:00:03Z is day 1: so day 0 is 2014-08-15.
    EXPECT_EQ(clock.date_seen(t_2014_08_15_19 + 5 * 3600.0 + 3.0), 1);
    EXPECT_TRUE(clock.has_date());
    const double midnight_15 = t_2014_08_15_19 - 19 * 3600.0;
    EXPECT_EQ(clock.resolve(0, 86398.0), midnight_15 + 86398.0);
    EXPECT_EQ(clock.resolve_early(1, 1.0, 0.0), midnight_15 + 86400.0 + 1.0);
    DayClock none;
    EXPECT_EQ(none.resolve_early(0, 36900.0, 0.0), 36900.0);
}

TEST(ValidDate, KnowsLeapYears) {
    EXPECT_TRUE(valid_date(2016, 2, 29));
    EXPECT_TRUE(valid_date(2000, 2, 29));
    EXPECT_FALSE(valid_date(1900, 2, 29));
    EXPECT_FALSE(valid_date(2015, 2, 29));
    EXPECT_FALSE(valid_date(2015, 6, 31));
    EXPECT_FALSE(valid_date(2015, 0, 1));
    EXPECT_EQ(utc_seconds(2014, 8, 15, 19, 0, 0.0), t_2014_08_15_19);
    EXPECT_EQ(utc_seconds(2014, 8, 15, 19, 0, 60.0), std::nullopt);
}

}  // namespace

// Midnights from `date -u -d 2024-05-01 +%s` (1714521600) and `date -u -d 2000-02-29 +%s`.
TEST(ParseDate, ReadsADayAsItsMidnightUtc) {
    EXPECT_EQ(shoal::track::parse_date("2024-05-01"), 1714521600.0);
    EXPECT_EQ(shoal::track::parse_date(" 2000-02-29 "), 951782400.0);
    for (const char* bad : {"2023-02-29", "2024-13-01", "2024-5-1", "2024-05-01T00:00", "2024-05-01x", "", "yesterday"})
        EXPECT_EQ(shoal::track::parse_date(bad), std::nullopt) << bad;
}

TEST(PlausibleFixTime, SpansTheYears1980To2099) {
    using shoal::track::plausible_fix_time;
    EXPECT_TRUE(plausible_fix_time(315532800.0));    // date -u -d 1980-01-01 +%s
    EXPECT_FALSE(plausible_fix_time(315532799.0));
    EXPECT_TRUE(plausible_fix_time(4102444799.0));
    EXPECT_FALSE(plausible_fix_time(4102444800.0));  // date -u -d 2100-01-01 +%s
    EXPECT_FALSE(plausible_fix_time(NAN));
}
