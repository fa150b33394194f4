// Tests of track::read_gpx and track::read_geojson on hand-made files in tests/data/tracks.
//
// The GPX files were checked independently with GDAL's own tool: `ogrinfo -q FILE track_points`
// (and route_points) lists each point with its time (one track point without a time, one with
// +02 offset; GPX 1.0 course 80.5 and speed 2.572 m/s). Every GeoJSON value asserted below can
// be read in the file itself. Epoch seconds: date -u -d '2014-08-15T19:00:00Z' +%s -> 1408129200.

#include <shoal/track/ogr_reader.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::test::data_path;
using namespace shoal::track;
using testing::AllOf;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::ThrowsMessage;

constexpr double t0 = 1408129200.0;  // 2014-08-15T19:00:00Z

std::vector<double> times(const Track& t) {
    std::vector<double> out;
    for (const auto& f : t.fixes) out.push_back(f.time_s - t0);
    return out;
}

TEST(GpxReader, ReadsTracksAndRoutesWithTheirNames) {
    const std::string path = data_path("tracks/track_and_route.gpx");
    const auto f = read_gpx(path);
    EXPECT_EQ(f.format, "gpx");
    EXPECT_EQ(f.report.rows, 8u);  // 5 track points + 3 route points
    EXPECT_EQ(f.report.skipped, 1u);
    ASSERT_EQ(f.tracks.size(), 2u);
    const Track& trk = f.tracks[0];
    EXPECT_EQ(trk.id, "Trainee A");
    // Two segments joined; the +02:00 point is 19:00:20 UTC; the untimed 4th point is skipped.
    EXPECT_THAT(times(trk), ElementsAre(0.0, 10.5, 20.0, 40.0));
    EXPECT_DOUBLE_EQ(trk.fixes[3].position.lon, 24.904);
    EXPECT_DOUBLE_EQ(trk.fixes[3].position.lat, 60.15);
    EXPECT_EQ(trk.fixes[3].line, 12u);  // the file's lines (expat's), not the points' numbers
    const Track& rte = f.tracks[1];
    EXPECT_EQ(rte.id, "Plan B");
    EXPECT_THAT(times(rte), ElementsAre(-3600.0, -3000.0, -2400.0));
    EXPECT_EQ(rte.fixes[0].line, 17u);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_EQ(f.report.messages[0], path + " line 11 (track 'Trainee A'): no time; point skipped");
}

TEST(GpxReader, UnnamedSingleTrackTakesTheStemAndGpx10CourseAndSpeed) {
    const auto f = read_gpx(data_path("tracks/unnamed_track.gpx"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "unnamed_track");
    ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].cog_deg, 80.5);
    EXPECT_NEAR(f.tracks[0].fixes[0].sog_kn, 2.572 * 3600.0 / 1852.0, 1e-12);  // m/s -> knots
    EXPECT_TRUE(std::isnan(f.tracks[0].fixes[1].sog_kn));
}

TEST(GpxReader, RouteWithoutTimesIsAnErrorNamingFileAndRoute) {
    EXPECT_THAT([] { read_gpx(data_path("tracks/route_without_times.gpx")); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("route_without_times.gpx: route 'Planned passage' (route 1)"),
                                                HasSubstr("has no times"))));
}

TEST(GpxReader, NotGpxIsAnInputError) {
    EXPECT_THAT([] { read_gpx(data_path("tracks/unknown_format.txt")); },
                ThrowsMessage<InputError>(HasSubstr("unknown_format.txt: not a GPX file")));
}

TEST(GpxReader, APointWithoutANumberForLatOrLonCostsThatPointNamedByItsLine) {
    // GDAL's driver reads lat="abc" as latitude 0 and drops a point without lat silently; its
    // features carry no line. Each such point is a bad row named by the line of its tag, and
    // every fix keeps its line (the wild-fix messages and the report's fix_line name it).
    shoal::test::TempDir dir;
    const std::string path = dir.file("hostile.gpx");
    std::ofstream(path) << "<?xml version=\"1.0\"?>\n"                                                              // 1
                           "<gpx version=\"1.1\" creator=\"t\" xmlns=\"http://www.topografix.com/GPX/1/1\">\n"   // 2
                           "<trk><name>T</name><trkseg>\n"                                                       // 3
                           "<trkpt lat=\"60.10\" lon=\"24.90\"><time>2024-05-01T10:00:00Z</time></trkpt>\n"      // 4
                           "<trkpt lat=\"abc\" lon=\"24.902\"><time>2024-05-01T10:00:20Z</time></trkpt>\n"       // 5
                           "<trkpt lon=\"24.903\"><time>2024-05-01T10:00:30Z</time></trkpt>\n"                   // 6
                           "<trkpt lat=\"60.104\"\n"                                                             // 7
                           "  lon=\"24,904\"><time>2024-05-01T10:00:40Z</time></trkpt>\n"                        // 8
                           "<trkpt lat=\"1e999\" lon=\"24.905\"><time>2024-05-01T10:00:50Z</time></trkpt>\n"     // 9
                           "<trkpt lon=\"24.906\" lat=\"60.106\"><time>2024-05-01T10:01:00Z</time></trkpt>\n"    // 10
                           "</trkseg></trk></gpx>\n";
    const TrackFile f = read_gpx(path);
    ASSERT_EQ(f.tracks.size(), 1u);
    ASSERT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_EQ(f.tracks[0].fixes[0].line, 4u);
    EXPECT_EQ(f.tracks[0].fixes[1].line, 10u);
    EXPECT_EQ(f.tracks[0].fixes[1].position.lat, 60.106);
    EXPECT_EQ(f.report.rows, 6u);
    EXPECT_EQ(f.report.skipped, 4u);
    EXPECT_THAT(f.report.messages, ElementsAre(path + " line 5 (track 'T'): latitude 'abc' is not a number; point skipped",
                                               path + " line 6 (track 'T'): no lat attribute; point skipped",
                                               path + " line 7 (track 'T'): longitude '24,904' is not a number; point skipped",
                                               path + " line 9 (track 'T'): latitude '1e999' is not a number; point skipped"));
}

TEST(GpxReader, EachPointsTimeIsItsOwnTimeAsWrittenAndOneThatIsNoTimeIsNamedByItsLine) {
    // GDAL's driver reads "2024-05-01 10:01:00Z" (a space for the T) as midnight, so a track
    // written so was one fix and the rest "repeats"; it reads a date alone as midnight and an
    // impossible time as none ("no time"). Each point's own <time> is read as a CSV's time is;
    // where GDAL's agrees (to the millisecond) GDAL's is kept; GDAL's is the one of a point
    // whose only <time> is deeper down (an extension's, line 11). Epoch seconds from GNU date:
    // date -u -d 2024-05-01T10:00:00Z +%s -> 1714557600.
    shoal::test::TempDir dir;
    const std::string path = dir.file("times.gpx");
    std::ofstream(path) << "<?xml version=\"1.0\"?>\n"                                                                       // 1
                           "<gpx version=\"1.1\" creator=\"t\" xmlns=\"http://www.topografix.com/GPX/1/1\">\n"            // 2
                           "<trk><name>T</name><trkseg>\n"                                                                // 3
                           "<trkpt lat=\"60.100\" lon=\"24.90\"><time>2024-05-01T10:00:00Z</time></trkpt>\n"              // 4
                           "<trkpt lat=\"60.101\" lon=\"24.90\"><time>2024-05-01 10:01:00Z</time></trkpt>\n"              // 5
                           "<trkpt lat=\"60.102\" lon=\"24.90\"><time>2024-05-01T12:01:30+02:00</time></trkpt>\n"         // 6
                           "<trkpt lat=\"60.103\" lon=\"24.90\"><time>2024-05-01T10:02:00.5Z</time></trkpt>\n"            // 7
                           "<trkpt lat=\"60.104\" lon=\"24.90\"><time>2024-05-01T10:02:30</time></trkpt>\n"               // 8
                           "<trkpt lat=\"60.105\" lon=\"24.90\"><time>2024-05-01</time></trkpt>\n"                        // 9
                           "<trkpt lat=\"60.106\" lon=\"24.90\"><time>2024-02-30T10:00:00Z</time></trkpt>\n"              // 10
                           "<trkpt lat=\"60.107\" lon=\"24.90\"><extensions><time>2024-05-01T10:03:00Z</time></extensions></trkpt>\n"  // 11
                           "<trkpt lat=\"60.108\" lon=\"24.90\"><time>\n  2024-05-01 10:03:30Z\n</time></trkpt>\n"        // 12-14
                           "<trkpt lat=\"abc\" lon=\"24.90\"><time>yesterday</time></trkpt>\n"                           // 15
                           "<trkpt lat=\"60.109\" lon=\"24.90\"><time>2024-05-01T10:04:00Z</time><time>2024-05-01T10:04:30Z</time></trkpt>\n"  // 16
                           "<trkpt lat=\"60.110\" lon=\"24.90\"><time></time></trkpt>\n"                                      // 17
                           "<trkpt lat=\"60.111\" lon=\"24.90\"><time>2024-05-01T10:05:00Z\xc2\xa0</time></trkpt>\n"        // 18
                           "<trkpt lat=\"60.112\" lon=\"24.90\"><time>2024-05-01T10:05:60Z</time></trkpt>\n"                 // 19
                           "</trkseg></trk></gpx>\n";
    const TrackFile f = read_gpx(path);
    ASSERT_EQ(f.tracks.size(), 1u);
    std::vector<double> times, lines;
    for (const auto& x : f.tracks[0].fixes) {
        times.push_back(x.time_s - 1714557600.0);
        lines.push_back(static_cast<double>(x.line));
    }
    // (Line 16: the last of two <time>s, as GDAL takes it; 17: an empty one is none; 18 and
    // 19, a trailing no-break space and a leap second, shoal's parser refuses and GDAL reads:
    // GDAL's, as before, its 60th second taken as 59.999.)
    EXPECT_THAT(times, ElementsAre(0, 60, 90, 120.5, 150, 180, 210, 270, 300, testing::DoubleNear(359.999, 1e-6)));
    EXPECT_THAT(lines, ElementsAre(4, 5, 6, 7, 8, 11, 12, 16, 18, 19));
    EXPECT_EQ(f.report.skipped, 4u);
    EXPECT_THAT(f.report.messages, ElementsAre(path + " line 9 (track 'T'): time '2024-05-01' is a date without a time of day; point skipped",
                                               path + " line 10 (track 'T'): time '2024-02-30T10:00:00Z' is not a valid time; point skipped",
                                               path + " line 15 (track 'T'): latitude 'abc' is not a number; point skipped",
                                               path + " line 17 (track 'T'): no time; point skipped"));
}

TEST(GpxReader, EveryPointsLineAndEveryBadPointAgreeWithTheFileAsWrittenOnRandomFiles) {
    // Random GPX files (tracks, segments, routes, waypoints, points outside a segment, tags over
    // several lines, attributes in either order, lat or lon missing, empty, not numbers): what
    // the reader gives is what was written, known as each file was made: every good point a fix
    // of its track with the line of its tag, every other one a bad row.
    std::mt19937_64 rng(40);
    auto chance = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; };
    auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
    shoal::test::TempDir dir;
    std::size_t files_with_bad = 0, points_read = 0;
    for (int k = 0; k < 60; ++k) {
        std::string text = "<?xml version=\"1.0\"?>\n<gpx version=\"1.1\" creator=\"t\" xmlns=\"http://www.topografix.com/GPX/1/1\">\n";
        std::size_t line = 3;
        auto put = [&](const std::string& s) {
            text += s;
            for (char c : s) line += c == '\n';
        };
        struct Want {
            std::string track;
            std::size_t line;
            double lat, lon;
        };
        std::vector<Want> good;
        std::size_t bad = 0, second = 0;
        auto point = [&](const char* tag, const std::string& track) {
            const std::size_t at = line;
            const double lat = 60 + static_cast<double>(pick(100000)) * 1e-6, lon = 24 + static_cast<double>(pick(100000)) * 1e-6;
            char la[32], lo[32];
            std::snprintf(la, sizeof la, "%.6f", lat);
            std::snprintf(lo, sizeof lo, "%.6f", lon);
            std::string lat_attr = std::string(" lat=\"") + la + "\"", lon_attr = std::string(" lon=\"") + lo + "\"";
            bool ok = true;
            switch (chance(0.3) ? pick(6) : 6) {
                case 0: lat_attr.clear(); ok = false; break;
                case 1: lon_attr.clear(); ok = false; break;
                case 2: lat_attr = " lat=\"abc\""; ok = false; break;
                case 3: lon_attr = " lon=\"\""; ok = false; break;
                case 4: lat_attr = std::string(" lat=\"") + la + "x\""; ok = false; break;
                case 5: lon_attr = " lon=\"24,5\""; ok = false; break;
                default: break;
            }
            std::string attrs = chance(0.5) ? lat_attr + (chance(0.2) ? "\n  " : "") + lon_attr : lon_attr + " ele=\"1\"" + lat_attr;
            char when[64];
            ++second;
            std::snprintf(when, sizeof when, "<time>2024-05-01T10:%02zu:%02zuZ</time>", second / 60 % 60, second % 60);
            put(std::string("<") + tag + attrs + ">" + (chance(0.3) ? "\n" : "") + when + "</" + tag + ">" + (chance(0.7) ? "\n" : ""));
            if (ok) good.push_back({track, at, std::strtod(la, nullptr), std::strtod(lo, nullptr)});
            else ++bad;
        };
        const std::size_t tracks = 1 + pick(3), routes = pick(2);
        for (std::size_t t = 0; t < tracks; ++t) {
            if (chance(0.3)) put("<wpt lat=\"1\" lon=\"2\"><name>w</name></wpt>\n");
            const std::string name = "T" + std::to_string(t);
            put("<trk><name>" + name + "</name>\n");
            if (chance(0.1)) point("trkpt", name);  // outside any segment (GDAL reads it too)
            for (std::size_t g = 0, segs = 1 + pick(3); g < segs; ++g) {
                put("<trkseg>\n");
                for (std::size_t n = 0, pts = pick(6); n < pts; ++n) point("trkpt", name);
                put("</trkseg>\n");
            }
            put("</trk>\n");
        }
        for (std::size_t r = 0; r < routes; ++r) {
            const std::string name = "R" + std::to_string(r);
            put("<rte><name>" + name + "</name>\n");
            for (std::size_t n = 0, pts = 1 + pick(4); n < pts; ++n) point("rtept", name);
            put("</rte>\n");
        }
        put("</gpx>\n");
        const std::string path = dir.file("random" + std::to_string(k) + ".gpx");
        std::ofstream(path) << text;
        const TrackFile f = read_gpx(path);  // every point has a time: a track of bad points costs its points only
        std::vector<Want> got;
        for (const Track& t : f.tracks)
            for (const Fix& x : t.fixes) got.push_back({t.id, x.line, x.position.lat, x.position.lon});
        auto by_line = [](const Want& a, const Want& b) { return a.line < b.line || (a.line == b.line && a.lat < b.lat); };
        std::sort(got.begin(), got.end(), by_line);
        std::sort(good.begin(), good.end(), by_line);
        ASSERT_EQ(got.size(), good.size()) << text;
        for (std::size_t i = 0; i < got.size(); ++i) {
            EXPECT_EQ(got[i].track, good[i].track) << text;
            EXPECT_EQ(got[i].line, good[i].line) << text;
            EXPECT_EQ(got[i].lat, good[i].lat) << text;
            EXPECT_EQ(got[i].lon, good[i].lon) << text;
        }
        EXPECT_EQ(f.report.skipped, bad) << text;
        EXPECT_EQ(f.report.rows, good.size() + bad) << text;
        for (const std::string& m : f.report.messages) EXPECT_THAT(m, HasSubstr(" line ")) << m;
        files_with_bad += bad > 0;
        points_read += good.size();
        if (HasFailure()) return;
    }
    EXPECT_GT(files_with_bad, 20u) << "too few bad points to mean anything";
    EXPECT_GT(points_read, 300u);
}

TEST(GpxReader, AFileCutShortSaysWhereItBreaksAndEveryPointBeforeItKeepsItsLine) {
    // GDAL's parser stops at the break without a word (and drops the features of the block it
    // fails in); expat's scan says where, and names every point written before it that was not
    // read. A Windows-1252 file (which GDAL's parser reads) keeps its lines too, and points on
    // one line are told apart by their column.
    shoal::test::TempDir dir;
    std::string text = "<?xml version=\"1.0\" encoding=\"windows-1252\"?>\n<gpx version=\"1.1\" creator=\"t\">\n<trk><name>S\xE9</name><trkseg>\n";
    for (int i = 0; i < 400; ++i) {
        char row[160];
        std::snprintf(row, sizeof row, "<trkpt lat=\"%.5f\" lon=\"24.9\"><time>2024-05-01T10:%02d:%02dZ</time></trkpt>\n", 60.1 + i * 1e-5, i / 60,
                      i % 60);
        text += row;
    }
    const std::string whole = dir.file("whole.gpx");
    std::ofstream(whole) << text << "</trkseg></trk></gpx>\n";
    const TrackFile w = read_gpx(whole);
    ASSERT_EQ(w.tracks.size(), 1u);
    ASSERT_EQ(w.tracks[0].fixes.size(), 400u);
    for (std::size_t i = 0; i < 400; ++i) ASSERT_EQ(w.tracks[0].fixes[i].line, i + 4);
    EXPECT_TRUE(w.report.messages.empty());

    const std::string cut = dir.file("cut.gpx");
    std::ofstream(cut) << text.substr(0, text.size() - 30);  // inside the last point's <time>
    const TrackFile c = read_gpx(cut);
    ASSERT_EQ(c.tracks.size(), 1u);
    const std::size_t read = c.tracks[0].fixes.size();
    ASSERT_GT(read, 300u);
    for (std::size_t i = 0; i < read; ++i) ASSERT_EQ(c.tracks[0].fixes[i].line, i + 4);
    // The 400th point's tag is on line 403; every one from the first lost to it is named.
    EXPECT_EQ(c.report.skipped, 400 - read);
    ASSERT_FALSE(c.report.messages.empty());
    EXPECT_THAT(c.report.messages.back(), AllOf(HasSubstr(cut + " line 403 column "), HasSubstr("the XML is not well-formed"),
                                                HasSubstr("no point after it is read")));
    if (read < 400) {
        // (its track unnamed: GDAL's tracks layer holds no track whose end tag it did not read)
        EXPECT_EQ(c.report.messages.front(), cut + " line " + std::to_string(read + 4) +
                                                  " (track 'cut:track1'): not read: the XML is not well-formed further on, at line 403; point skipped");
    }

    const std::string one = dir.file("one.gpx");  // the second <trkpt starts after 128 characters
    std::ofstream(one) << "<gpx version=\"1.1\" creator=\"t\"><trk><name>A</name><trkseg>"
                          "<trkpt lat=\"60.1\" lon=\"24.9\"><time>2024-05-01T10:00:00Z</time></trkpt>"
                          "<trkpt lat=\"abc\" lon=\"24.9\"><time>2024-05-01T10:00:10Z</time></trkpt>"
                          "</trkseg></trk></gpx>";
    const TrackFile o = read_gpx(one);
    ASSERT_EQ(o.report.messages.size(), 1u);
    EXPECT_EQ(o.report.messages[0], one + " line 1 column 129 (track 'A'): latitude 'abc' is not a number; point skipped");
}

TEST(GpxReader, PointsAfterATrackAndBytesWindows1252LeavesUndefinedAreTakenAsGdalTakesThem) {
    shoal::test::TempDir dir;
    // GDAL's driver gives a point after </trk> to the last track begun: so does its message.
    const std::string after = dir.file("after.gpx");
    std::ofstream(after) << "<gpx version=\"1.1\" creator=\"t\">\n"                                                   // 1
                            "<trk><name>T</name><trkseg>\n"                                                            // 2
                            "<trkpt lat=\"60.1\" lon=\"24.9\"><time>2024-05-01T10:00:00Z</time></trkpt>\n"           // 3
                            "</trkseg></trk>\n"                                                                        // 4
                            "<trkpt lat=\"abc\" lon=\"24.9\"><time>2024-05-01T10:00:10Z</time></trkpt>\n"            // 5
                            "<trkpt lon=\"24.9\"><time>2024-05-01T10:00:20Z</time></trkpt>\n"                        // 6
                            "</gpx>\n";
    const TrackFile a = read_gpx(after);
    EXPECT_THAT(a.report.messages, ElementsAre(after + " line 5 (track 'T'): latitude 'abc' is not a number; point skipped",
                                               after + " line 6 (track 'T'): no lat attribute; point skipped"));
    // 0x81 is no character in Windows-1252: GDAL's parser stops there, and the scan says so.
    std::string text = "<?xml version=\"1.0\" encoding=\"windows-1252\"?>\n<gpx version=\"1.1\" creator=\"t\">\n<trk><name>W</name><trkseg>\n";
    for (int i = 0; i < 300; ++i) {
        char row[160];
        std::snprintf(row, sizeof row, "<trkpt lat=\"60.1\" lon=\"%.5f\"><time>2024-05-01T10:%02d:%02dZ</time>%s</trkpt>\n", 24.9 + i * 1e-5, i / 60,
                      i % 60, i == 200 ? "<desc>\x81</desc>" : "");
        text += row;
    }
    const std::string undefined = dir.file("undefined.gpx");
    std::ofstream(undefined) << text << "</trkseg></trk></gpx>\n";
    const TrackFile u = read_gpx(undefined);
    ASSERT_FALSE(u.report.messages.empty());
    EXPECT_THAT(u.report.messages.back(), AllOf(HasSubstr(undefined + " line 204 column "), HasSubstr("the XML is not well-formed")));
}

TEST(GeoJsonReader, LineStringWithTimesArray) {
    const std::string path = data_path("tracks/line_times.geojson");
    const auto f = read_geojson(path);
    EXPECT_EQ(f.format, "geojson");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "Aava");
    EXPECT_EQ(f.tracks[0].name, "Aava");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0, 20.25, 40.0));
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[3].position.lon, 24.94);
    EXPECT_EQ(f.report.rows, 5u);
    EXPECT_EQ(f.report.skipped, 1u);
    ASSERT_EQ(f.report.messages.size(), 1u);
    EXPECT_EQ(f.report.messages[0], path + " feature 1 vertex 4: times \"not a time\" is not a valid time; point skipped");
}

TEST(GeoJsonReader, MultiLineStringWithCoordinatePropertiesAndMillisecondCoordTimes) {
    const auto f = read_geojson(data_path("tracks/line_coordinate_properties.geojson"));
    ASSERT_EQ(f.tracks.size(), 2u);
    EXPECT_EQ(f.tracks[0].id, "244000001");  // the feature's id
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0, 20.0, 30.0));
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[2].position.lon, 5.32);
    EXPECT_EQ(f.tracks[1].id, "244000002");  // the mmsi property, a number
    EXPECT_THAT(times(f.tracks[1]), ElementsAre(0.0, 10.0));
}

TEST(GeoJsonReader, LineStringWithMeasureCoordinates) {
    const auto f = read_geojson(data_path("tracks/line_m.geojson"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "M-ship");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0, 20.5));
}

TEST(GeoJsonReader, PointsAreSplitByMmsiInFirstAppearanceOrder) {
    // points.geojson: 230000002 at 19:00:00 (sog 6.5, cog 45, heading 511) and 19:00:10;
    // 230000001 at 19:00:05 (heading 270), one point without time, a numeric timestamp
    // 1408129215, and a Polygon feature.
    const auto f = read_geojson(data_path("tracks/points.geojson"));
    EXPECT_EQ(f.report.rows, 6u);
    EXPECT_EQ(f.report.skipped, 2u);
    ASSERT_EQ(f.tracks.size(), 2u);
    EXPECT_EQ(f.tracks[0].id, "230000002");
    EXPECT_EQ(f.tracks[1].id, "230000001");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0));
    EXPECT_THAT(times(f.tracks[1]), ElementsAre(5.0, 15.0));
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].sog_kn, 6.5);
    EXPECT_DOUBLE_EQ(f.tracks[0].fixes[0].cog_deg, 45.0);
    EXPECT_TRUE(std::isnan(f.tracks[0].fixes[0].heading_deg));
    EXPECT_DOUBLE_EQ(f.tracks[1].fixes[0].heading_deg, 270.0);
    EXPECT_THAT(f.report.messages.at(0), HasSubstr("feature 4: Point without a 'time' or 'timestamp' property"));
    EXPECT_THAT(f.report.messages.at(1), HasSubstr("feature 6: a Polygon is not a track"));
}

TEST(GeoJsonReader, PointFeatureIdsDoNotSplitTracks) {
    const auto f = read_geojson_text(R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": 1, "properties": {"time": "2014-08-15T19:00:00Z"}, "geometry": {"type": "Point", "coordinates": [24.9, 60.1]}},
        {"type": "Feature", "id": 2, "properties": {"time": "2014-08-15T19:00:10Z"}, "geometry": {"type": "Point", "coordinates": [24.91, 60.1]}}]})",
                                     "/x/trainee-7.geojson");
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "trainee-7");
    EXPECT_THAT(times(f.tracks[0]), ElementsAre(0.0, 10.0));
}

TEST(GeoJsonReader, ALineThatCannotBeReadCostsThatFeatureNamedAndNotTheFile) {
    const auto a = read_geojson(data_path("tracks/line_without_times.geojson"));
    EXPECT_TRUE(a.tracks.empty());
    EXPECT_EQ(a.report.skipped, 1u);
    EXPECT_THAT(a.report.messages, ElementsAre(AllOf(HasSubstr("line_without_times.geojson feature 1 ('no clock')"),
                                                     HasSubstr("line without times"), HasSubstr("feature skipped"))));
    const auto b = read_geojson(data_path("tracks/line_times_mismatch.geojson"));
    EXPECT_THAT(b.report.messages, ElementsAre(HasSubstr("feature 1: 'times' has 1 times for 2 vertices; feature skipped")));
    // Before, one such line cost every track of its file.
    const auto c = read_geojson_text(R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"id": "ok", "times": ["2014-08-15T19:00:00Z", "2014-08-15T19:00:10Z"]}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.1], [24.91, 60.1]]}},
        {"type": "Feature", "properties": {"id": "short", "times": ["2014-08-15T19:00:00Z"]}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.1], [24.91, 60.1]]}},
        {"type": "Feature", "properties": {"id": "none"}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.1], [24.91, 60.1]]}},
        {"type": "Feature", "properties": {"id": "ok2", "times": ["2014-08-15T19:00:00Z", "2014-08-15T19:00:10Z"]}, "geometry": {"type": "LineString", "coordinates": [[24.9, 60.2], [24.91, 60.2]]}}]})",
                                     "three.geojson");
    ASSERT_EQ(c.tracks.size(), 2u);
    EXPECT_EQ(c.tracks[0].id, "ok");
    EXPECT_EQ(c.tracks[1].id, "ok2");
    EXPECT_EQ(c.tracks[1].fixes.size(), 2u);
    EXPECT_EQ(c.report.skipped, 2u);
    EXPECT_THAT(c.report.messages, ElementsAre(HasSubstr("three.geojson feature 2: 'times' has 1 times for 2 vertices; feature skipped"),
                                               HasSubstr("three.geojson feature 3 ('none'): line without times")));
}

TEST(GeoJsonReader, RejectsBrokenJsonOtherJsonAndOtherCrs) {
    EXPECT_THAT([] { read_geojson_text("{\"type\": \"FeatureCollection\", ", "cut.geojson"); },
                ThrowsMessage<InputError>(HasSubstr("cut.geojson: not valid JSON")));
    // A number too large for a double (nlohmann's out_of_range, not a parse_error) is bad input too.
    EXPECT_THAT([] { read_geojson_text(R"({"type": "FeatureCollection", "features": [], "x": 1e999})", "huge.geojson"); },
                ThrowsMessage<InputError>(HasSubstr("huge.geojson: not valid JSON")));
    EXPECT_THAT([] { read_geojson_text(R"({"name": "tanker", "a": 100})", "ship.json"); },
                ThrowsMessage<InputError>(HasSubstr("ship.json: not a track format shoal reads")));
    EXPECT_THAT(
        [] {
            read_geojson_text(R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:3067"}},
                                  "features": []})",
                              "tm35.geojson");
        },
        ThrowsMessage<InputError>(HasSubstr("tm35.geojson: crs 'EPSG:3067' is not WGS84")));
    EXPECT_THAT([] { read_geojson_text(R"({"type": "LineString", "coordinates": [[0, 0], [1, 1]]})", "bare.geojson"); },
                ThrowsMessage<InputError>(HasSubstr("bare.geojson: a bare LineString geometry has no times")));
}

}  // namespace

namespace {

// Exercise mode (issue 18): the exercise and role columns are GeoJSON properties too.
TEST(GeoJsonReader, ExerciseAndRolePropertiesKeyTracksByExerciseAndId) {
    const std::string text = R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "A", "Role": "own ship", "time": "2024-05-01T10:00:00Z"},
         "geometry": {"type": "Point", "coordinates": [-1.0, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "B", "Role": "target", "time": "2024-05-01T10:00:00Z"},
         "geometry": {"type": "Point", "coordinates": [-1.0, 50.71]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": 7, "Role": "trainee", "times": ["2024-05-01T10:00:00Z", "2024-05-01T10:01:00Z"]},
         "geometry": {"type": "LineString", "coordinates": [[-1.0, 50.72], [-0.99, 50.72]]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "Role": "trainee", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "A", "Role": "pilot", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 235000001, "EXERCISE": "B", "Role": "trainee", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.71]}}]})";
    ReadOptions o;
    o.exercise_column = "exercise";
    o.role_column = "role";
    const TrackFile f = read_geojson_text(text, "ex.geojson", o);
    std::vector<std::string> keys;
    for (const auto& t : f.tracks) keys.push_back(t.exercise + "/" + t.id + "/" + t.role + "/" + std::to_string(t.fixes.size()));
    EXPECT_THAT(keys, ElementsAre("A/235000001/trainee/1", "B/235000001/target/2", "7/235000001/trainee/2"));
    EXPECT_EQ(f.report.skipped, 2u);
    std::string said;
    for (const auto& m : f.report.messages) said += m + "\n";
    EXPECT_THAT(said, HasSubstr("ex.geojson feature 4: no exercise (property 'exercise' is missing or empty); feature skipped"));
    EXPECT_THAT(said, HasSubstr("ex.geojson feature 5: role \"pilot\" (property 'role') is neither trainee (own, own ship) nor target; feature skipped"));
    EXPECT_THAT(said, HasSubstr("ex.geojson: track '235000001' of exercise 'B': its features disagree on the role (target in feature 2, trainee "
                                "in feature 6 of property 'role'): it is taken as a target"));
    // No feature has the property: the file is refused, naming it and the column.
    ReadOptions other;
    other.exercise_column = "drill";
    EXPECT_THAT([&] { read_geojson_text(text, "ex.geojson", other); },
                ThrowsMessage<InputError>(HasSubstr("ex.geojson: no feature has the property 'drill', the exercise column")));
}

TEST(GeoJsonReader, BlanksAroundAnExerciseAreIgnoredAsInACsvAndBlanksAloneAreNone) {
    const std::string text = R"({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"mmsi": 1, "exercise": "A", "time": "2024-05-01T10:00:00Z"},
         "geometry": {"type": "Point", "coordinates": [-1.0, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 1, "exercise": " A\t", "time": "2024-05-01T10:01:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.99, 50.7]}},
        {"type": "Feature", "properties": {"mmsi": 1, "exercise": "  ", "time": "2024-05-01T10:02:00Z"},
         "geometry": {"type": "Point", "coordinates": [-0.98, 50.7]}}]})";
    ReadOptions o;
    o.exercise_column = "exercise";
    const TrackFile f = read_geojson_text(text, "ex.geojson", o);
    ASSERT_EQ(f.tracks.size(), 1u) << "' A' is exercise A";
    EXPECT_EQ(f.tracks[0].exercise, "A");
    EXPECT_EQ(f.tracks[0].fixes.size(), 2u);
    EXPECT_EQ(f.report.skipped, 1u) << "blanks alone: no exercise";
}

}  // namespace
