// Tests of track.hpp (normalise, resolve_headings) and reader.hpp (read_tracks, expand_inputs,
// read_vessels).
//
// Expected bearings come from an independent computation in /usr/bin/python3: the chord from
// A to B (unit vectors on the sphere) projected on the east and north unit vectors at A,
// bearing = atan2(chord.east, chord.north) (shoal uses the trigonometric initial-bearing formula).
// Speeds: 0.001 deg of latitude = 6371008.8 m * pi/180 * 0.001 = 111.195 m; in 10 s = 21.6 kn.
// Vessel counts: awk -F, on gpsd_nl_vessels.csv (19 distinct MMSIs, 16 with A,B,C,D all > 0).

#include <shoal/track/reader.hpp>
#include <shoal/track/vessels_table.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.hpp"
#include <shoal/track/columns.hpp>
#include <shoal/track/packed_track.hpp>
#include <shoal/track/track.hpp>
#include <shoal/track/wild_fixes.hpp>
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::test::data_path;
using shoal::test::TempDir;
using namespace shoal::track;
using testing::AllOf;
using testing::ElementsAre;
using testing::EndsWith;
using testing::HasSubstr;
using testing::ThrowsMessage;

Fix fix(double t, double lat, double lon, double heading = NAN, double cog = NAN, double sog = NAN) {
    Fix f;
    f.time_s = t;
    f.position = {lon, lat};
    f.heading_deg = heading;
    f.cog_deg = cog;
    f.sog_kn = sog;
    return f;
}

std::vector<HeadingSource> sources(const Track& t) {
    std::vector<HeadingSource> out;
    for (const auto& f : t.fixes) out.push_back(f.heading_source);
    return out;
}

void write(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

// ---------------------------------------------------------------------------------------------
// normalise

TEST(Normalise, SortsCountsReorderedAndMergesRepeatedTimes) {
    Track t;
    t.file = "x.csv";
    t.fixes = {fix(30, 60, 24.3), fix(10, 60, 24.1), fix(10, 60, 24.15, 5.0), fix(20, 60, 24.2, NAN, 7.0),
               fix(NAN, 60, 24.9), fix(0, 60, 24.0)};
    t.fixes[4].line = 99;
    ReadReport r;
    normalise(t, r);
    std::vector<double> times, lons;
    for (const auto& f : t.fixes) {
        times.push_back(f.time_s);
        lons.push_back(f.position.lon);
    }
    EXPECT_THAT(times, ElementsAre(0, 10, 20, 30));
    EXPECT_THAT(lons, ElementsAre(24.0, 24.1, 24.2, 24.3));  // the first of the two at t=10 kept
    EXPECT_DOUBLE_EQ(t.fixes[1].heading_deg, 5.0);           // ... with the repeat's heading
    EXPECT_EQ(r.duplicates, 1u);
    EXPECT_EQ(r.reordered, 4u);  // 10, 10, 20 and 0 come after 30
    EXPECT_EQ(r.skipped, 1u);
    EXPECT_THAT(r.messages, ElementsAre("x.csv line 99: fix without a time; dropped"));
}

TEST(ReadReport, KeepsMessagesUpToItsLimit) {
    ReadReport r;
    r.max_messages = 2;
    for (int i = 0; i < 5; ++i) r.skip("m" + std::to_string(i));
    EXPECT_EQ(r.skipped, 5u);
    EXPECT_THAT(r.messages, ElementsAre("m0", "m1"));
}

// ---------------------------------------------------------------------------------------------
// resolve_headings

TEST(ResolveHeadings, PrefersHeadingThenCogWhenMovingThenPrevious) {
    Track t;
    t.fixes = {fix(0, 60, 24, NAN, 100.0, 0.1),    // stopped, COG ignored, nothing known yet
               fix(10, 60, 24, 80.0, 100.0, 0.1),  // true heading
               fix(20, 60, 24, NAN, 100.0, 6.0),   // moving: COG
               fix(30, 60, 24, NAN, 120.0, 0.2),   // stopped: previous (100)
               fix(40, 60, 24, NAN, NAN, 6.0)};    // moving, no COG, positions equal: previous
    resolve_headings(t);
    EXPECT_THAT(sources(t), ElementsAre(HeadingSource::none, HeadingSource::heading, HeadingSource::cog,
                                        HeadingSource::previous, HeadingSource::previous));
    std::vector<double> used;
    for (const auto& f : t.fixes) used.push_back(f.heading_used_deg);
    EXPECT_THAT(used, ElementsAre(0.0, 80.0, 100.0, 100.0, 100.0));
}

TEST(ResolveHeadings, UnknownSogUsesMotionBetweenPositions) {
    Track t;
    t.fixes = {fix(0, 60.0, 24.0, NAN, 30.0),     // 0.001 deg north in 10 s to the next: 21.6 kn, moving: COG
               fix(10, 60.001, 24.0, NAN, 31.0),  // next is 0.00001 deg away: 0.2 kn, stopped: previous
               fix(20, 60.00101, 24.0),           // next is 1 deg away: moving, no COG: bearing to it
               fix(30, 61.0, 25.0),               // next is due north
               fix(40, 62.0, 25.0)};              // last: speed and bearing from the previous fix
    resolve_headings(t, 0.5);
    EXPECT_THAT(sources(t), ElementsAre(HeadingSource::cog, HeadingSource::previous, HeadingSource::positions,
                                        HeadingSource::positions, HeadingSource::positions));
    EXPECT_DOUBLE_EQ(t.fixes[0].heading_used_deg, 30.0);
    EXPECT_DOUBLE_EQ(t.fixes[1].heading_used_deg, 30.0);
    EXPECT_NEAR(t.fixes[3].heading_used_deg, 0.0, 1e-9);
    EXPECT_NEAR(t.fixes[4].heading_used_deg, 0.0, 1e-9);

    Track stop;  // the last fix crawls 0.11 m in 10 s (0.02 kn): stopped, heading held
    stop.fixes = {fix(0, 60, 24, 45.0), fix(10, 60.000001, 24)};
    resolve_headings(stop, 0.5);
    EXPECT_THAT(sources(stop), ElementsAre(HeadingSource::heading, HeadingSource::previous));
    EXPECT_DOUBLE_EQ(stop.fixes[1].heading_used_deg, 45.0);
}

TEST(ResolveHeadings, BearingBetweenPositionsIsTheInitialGreatCircleBearing) {
    // python3 (chord projection): 60N 24E -> 61N 25E: 25.782388958202198;
    // 60N 24E -> 59.99N 23.98E: 225.01298983573034.
    Track t;
    t.fixes = {fix(0, 60, 24), fix(3600, 61, 25)};
    resolve_headings(t);
    EXPECT_EQ(t.fixes[0].heading_source, HeadingSource::positions);
    EXPECT_NEAR(t.fixes[0].heading_used_deg, 25.782388958202198, 1e-9);
    Track u;
    u.fixes = {fix(0, 60, 24), fix(60, 59.99, 23.98)};
    resolve_headings(u);
    EXPECT_NEAR(u.fixes[0].heading_used_deg, 225.01298983573034, 1e-9);
    EXPECT_NEAR(u.fixes[1].heading_used_deg, 225.01298983573034, 1e-9);  // from the previous fix
}

TEST(ResolveHeadings, NormalisesToZeroTo360) {
    Track t;
    t.fixes = {fix(0, 60, 24, -10.0), fix(10, 60, 24, 370.0), fix(20, 60, 24, 360.0)};
    resolve_headings(t);
    EXPECT_DOUBLE_EQ(t.fixes[0].heading_used_deg, 350.0);
    EXPECT_DOUBLE_EQ(t.fixes[1].heading_used_deg, 10.0);
    EXPECT_DOUBLE_EQ(t.fixes[2].heading_used_deg, 0.0);
}

TEST(HeadingSourceNames, AreTheReportWords) {
    EXPECT_STREQ(to_string(HeadingSource::heading), "heading");
    EXPECT_STREQ(to_string(HeadingSource::cog), "cog");
    EXPECT_STREQ(to_string(HeadingSource::positions), "positions");
    EXPECT_STREQ(to_string(HeadingSource::previous), "previous");
    EXPECT_STREQ(to_string(HeadingSource::none), "none");
}

// ---------------------------------------------------------------------------------------------
// read_tracks

TEST(ReadTracks, DispatchesOnContent) {
    EXPECT_EQ(read_tracks(data_path("tracks/depons_marinecadastre.csv")).format, "csv");
    EXPECT_EQ(read_tracks(data_path("tracks/plaka_head400.log")).format, "nmea");
    EXPECT_EQ(read_tracks(data_path("tracks/bundg_zeus_9_head300.log")).format, "nmea");  // '#' comments first
    EXPECT_EQ(read_tracks(data_path("tracks/dma_export_dk_head200.csv")).format, "csv");  // '# Timestamp' header
    EXPECT_EQ(read_tracks(data_path("tracks/track_and_route.gpx")).format, "gpx");
    EXPECT_EQ(read_tracks(data_path("tracks/line_times.geojson")).format, "geojson");
    EXPECT_EQ(read_tracks(data_path("tracks/tab_separated.txt")).format, "csv");
}

TEST(ReadTracks, ARenamedFileIsReadByItsContent) {
    TempDir dir;
    const std::string copy = dir.file("log.csv");
    shoal::test::write_bytes(copy, shoal::test::read_bytes(data_path("tracks/mixed_talkers.nmea")));
    const auto f = read_tracks(copy);
    EXPECT_EQ(f.format, "nmea");
    EXPECT_EQ(f.tracks.at(0).id, "log");
    EXPECT_EQ(f.tracks.at(0).fixes.size(), 4u);
}

TEST(ReadTracks, EmptyHeaderOnlyUnknownAndMissingFilesAreInputErrors) {
    EXPECT_THAT([] { read_tracks(data_path("tracks/empty.csv")); },
                ThrowsMessage<InputError>(EndsWith("empty.csv: empty file")));
    EXPECT_THAT([] { read_tracks(data_path("tracks/header_only.csv")); },
                ThrowsMessage<InputError>(EndsWith("header_only.csv: no usable fix (0 rows read, 0 skipped)")));
    EXPECT_THAT([] { read_tracks(data_path("tracks/unknown_format.txt")); },
                ThrowsMessage<InputError>(EndsWith(
                    "unknown_format.txt: not a track format shoal reads (CSV with a header, GPX, GeoJSON, NMEA 0183): its first line "
                    "('Voyage notes') holds no ',', ';' or tab")));
    TempDir dir;
    // Where the beginning says why: comment lines before a CSV header; NUL bytes as a binary
    // file has them (before, the whole file refused without a line named).
    write(dir.file("comments.csv"), "# exported by tool\nmmsi,time,lat,lon\n1,2014-08-15T19:00:00Z,60,24\n");
    EXPECT_THAT([&] { read_tracks(dir.file("comments.csv")); },
                ThrowsMessage<InputError>(HasSubstr("its first line ('# exported by tool') holds no ',', ';' or tab (a CSV file's header must be its first line")));
    std::string nul = "mmsi,time,lat,lon\n";
    for (int i = 0; i < 100; ++i) nul += "1,2014-08-15T19:00:" + std::to_string(10 + i % 50) + "Z,60,24\n";
    // One NUL in the first 4 KB (a line damaged there): that row alone, named (before: the
    // whole file refused as binary). NULs on the first line, or more than a few: binary.
    const std::size_t at = nul.find('\n', 200) + 3;
    std::string damaged = nul;
    damaged[at] = '\0';
    write(dir.file("nul.csv"), damaged);
    const TrackFile got = read_tracks(dir.file("nul.csv"));
    EXPECT_EQ(got.report.skipped, 1u);
    ASSERT_EQ(got.report.messages.size(), 1u);
    EXPECT_EQ(got.report.messages[0], dir.file("nul.csv") + " line 9: a NUL byte at its byte 3: a damaged line; row skipped");
    std::string id = nul;
    id[nul.find('\n', 300) + 1] = '\0';  // in a row's id: no vessel "\0" of its own
    write(dir.file("nul_id.csv"), id);
    const TrackFile got_id = read_tracks(dir.file("nul_id.csv"));
    EXPECT_EQ(got_id.tracks.size(), 1u);
    EXPECT_EQ(got_id.report.skipped, 1u);
    std::string first = nul;
    first[2] = '\0';
    write(dir.file("nul_first.csv"), first);
    EXPECT_THAT([&] { read_tracks(dir.file("nul_first.csv")); }, ThrowsMessage<InputError>(HasSubstr("a NUL byte on line 1 (byte 3)")));
    // In a GPX or GeoJSON file (a whole document, whose parser would stop at it): binary, as
    // before (a second FeatureCollection after a NUL was lost without a word).
    std::string doc = "{\"type\": \"FeatureCollection\",\n\"features\": []}\n";
    doc += '\0';
    doc += "\n{\"type\": \"FeatureCollection\"}\n";
    write(dir.file("nul.geojson"), doc);
    EXPECT_THAT([&] { read_tracks(dir.file("nul.geojson")); }, ThrowsMessage<InputError>(HasSubstr("a NUL byte on line 3")));
    std::string many = nul;
    for (const std::size_t k : {200, 260, 320, 380, 440}) many[k] = '\0';
    write(dir.file("nul_many.csv"), many);
    EXPECT_THAT([&] { read_tracks(dir.file("nul_many.csv")); }, ThrowsMessage<InputError>(HasSubstr("a NUL byte on line ")));
    write(dir.file("bom.csv"), "\xEF\xBB\xBF\r\n");
    EXPECT_THAT([&] { read_tracks(dir.file("bom.csv")); }, ThrowsMessage<InputError>(EndsWith("bom.csv: empty file")));
    EXPECT_THAT([] { read_tracks(data_path("tracks/no_such_file.csv")); },
                ThrowsMessage<InputError>(HasSubstr("no_such_file.csv: no such file")));
    EXPECT_THAT([] { read_tracks(data_path("tracks")); }, ThrowsMessage<InputError>(HasSubstr("is a folder")));
}

TEST(ReadTracks, AFileWithoutAnyGoodRowSaysWhy) {
    TempDir dir;
    write(dir.file("bad.csv"), "id,time,lat,lon\na,2014-08-15T19:00:00Z,91,181\n");
    EXPECT_THAT([&] { read_tracks(dir.file("bad.csv")); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("bad.csv: no usable fix (1 rows read, 1 skipped)"),
                                                HasSubstr("first problem: "), HasSubstr("latitude 91"))));
    write(dir.file("ais.nmea"), "!AIVDM,1,1,,B,13u?etPv2;0n:dDPwUM1U1Cb069D,0*27\n");
    EXPECT_THAT([&] { read_tracks(dir.file("ais.nmea")); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("ais.nmea: AIS position reports without any time source"),
                                                HasSubstr("the AIS second field alone cannot date a fix"))));
}

TEST(ReadTracks, DropsVesselsLeftWithoutFixes) {
    TempDir dir;
    write(dir.file("two.csv"), "id,time,lat,lon\na,2014-08-15T19:00:00Z,91,24\nb,2014-08-15T19:00:00Z,60,24\n");
    const auto f = read_tracks(dir.file("two.csv"));
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "b");
    EXPECT_EQ(f.report.skipped, 1u);
}

TEST(SniffFormat, LooksAtContentFirst) {
    EXPECT_EQ(sniff_format("\xEF\xBB\xBF<?xml version=\"1.0\"?>\n<gpx version=\"1.1\">"), "gpx");
    EXPECT_EQ(sniff_format("<kml></kml>"), "");
    EXPECT_EQ(sniff_format("<?xml version=\"1.0\"?>\n<trk/>", "x.gpx"), "gpx");  // the extension breaks the tie
    EXPECT_EQ(sniff_format("  {\"type\": \"FeatureCollection\"}"), "geojson");
    EXPECT_EQ(sniff_format("# comment\n$GPGGA,1\n$GPRMC,2\n"), "nmea");
    EXPECT_EQ(sniff_format("# Timestamp,MMSI\n18/03/2013 09:19:09,1\n"), "csv");
    EXPECT_EQ(sniff_format("plain words\n"), "");
    EXPECT_EQ(sniff_format(std::string_view("a,b\0c", 5)), "");  // binary
}

// ---------------------------------------------------------------------------------------------
// expand_inputs, read_vessels

TEST(ExpandInputs, FoldersBecomeTheirTrackFilesSorted) {
    TempDir dir;
    for (const char* name : {"b.GPX", "a.csv", "notes.md", "z.log", "m.geojson"})
        write(dir.file(name), "x");
    // A vessels table by its header, whatever its name; a track file named like one is a track file.
    write(dir.file("c_vessels.csv"), "mmsi,name,draught_m\n111,A,3\n");
    write(dir.file("fleet.csv"), "MMSI;Ship type;to_bow\n111;70;10\n");
    write(dir.file("d_vessels.csv"), "mmsi,name,lat,lon,time\n111,A,50,1,2024-05-01T10:00:00Z\n");
    std::filesystem::create_directory(dir.path() / "sub.csv");
    std::vector<std::string> tables;
    const auto files = expand_inputs({dir.path().string(), data_path("tracks/plaka_head400.log")}, nullptr, &tables);
    EXPECT_THAT(files, ElementsAre(dir.file("a.csv"), dir.file("b.GPX"), dir.file("d_vessels.csv"), dir.file("m.geojson"), dir.file("z.log"),
                                   data_path("tracks/plaka_head400.log")));
    std::sort(tables.begin(), tables.end());
    EXPECT_THAT(tables, ElementsAre(dir.file("c_vessels.csv"), dir.file("fleet.csv")));
}

TEST(ExpandInputs, StandardInputByAnyOfItsNamesIsReadOnce) {
    std::vector<std::string> warnings;
    const auto files = expand_inputs({"-", "/dev/stdin", "-", "/vsistdin/"}, &warnings);
    EXPECT_EQ(files, std::vector<std::string>{"-"});
    EXPECT_EQ(warnings.size(), 3u);
}

TEST(ExpandInputs, MissingPathsAndFoldersWithoutTracksAreInputErrors) {
    TempDir dir;
    write(dir.file("readme.md"), "x");
    EXPECT_THAT([&] { expand_inputs({dir.file("gone.csv")}); },
                ThrowsMessage<InputError>(EndsWith("gone.csv: no such file or folder")));
    EXPECT_THAT([&] { expand_inputs({dir.path().string()}); }, ThrowsMessage<InputError>(HasSubstr("holds no track files")));
}

TEST(ReadVessels, ReadsStaticDataByMmsi) {
    // gpsd_nl_vessels.csv rows: 244050308 TYPHOON 37,10,3,2,2,(no draught); 305235000 MEDUM 70,88,12,10,6,6.3;
    // 211524940 TUI MAYA 69,0,0,0,0,1.7; 244820267 PLEIADE with no values.
    const auto v = read_vessels(data_path("tracks/gpsd_nl_vessels.csv"));
    EXPECT_EQ(v.size(), 19u);
    EXPECT_EQ(std::count_if(v.begin(), v.end(), [](const auto& kv) { return kv.second.dims.has_value(); }), 16);
    const VesselInfo& medum = v.at("305235000");
    EXPECT_EQ(medum.name, "MEDUM");
    EXPECT_EQ(*medum.dims, (shoal::hull::Dimensions{88, 12, 10, 6}));
    EXPECT_DOUBLE_EQ(medum.draught_m, 6.3);
    EXPECT_EQ(medum.ship_type, 70);
    EXPECT_TRUE(std::isnan(v.at("244050308").draught_m));
    EXPECT_FALSE(v.at("211524940").dims.has_value());
    EXPECT_DOUBLE_EQ(v.at("211524940").draught_m, 1.7);
    EXPECT_EQ(v.at("244820267").ship_type, -1);
    EXPECT_THAT([] { read_vessels(data_path("tracks/backwards.csv")); },
                ThrowsMessage<InputError>(HasSubstr("without an 'mmsi' column")));
}


TEST(ReadVessels, AnMmsiWrittenAsASpreadsheetsIntegralNumberIsTheMmsi) {
    EXPECT_EQ(integral_id("230035780.0"), "230035780");
    EXPECT_EQ(integral_id("230035780."), "230035780");
    EXPECT_EQ(integral_id("230035780.000"), "230035780");
    EXPECT_EQ(integral_id("2.30035780E+08"), "230035780");
    EXPECT_EQ(integral_id("2.30035781E+08"), "230035781");
    EXPECT_EQ(integral_id("2.30035780e8"), "230035780");
    EXPECT_EQ(integral_id("230035780"), "230035780");
    // Not integral, a rounded MMSI (digits missing), or not a number: as it is.
    EXPECT_EQ(integral_id("230035780.5"), "230035780.5");
    EXPECT_EQ(integral_id("2.30036E+08"), "2.30036E+08");
    EXPECT_EQ(integral_id("2.3003578E+08"), "2.3003578E+08") << "its ninth digit is not written: 230035780 or 230035781?";
    EXPECT_EQ(integral_id("OWN SHIP"), "OWN SHIP");
    EXPECT_EQ(integral_id("230035780.0x"), "230035780.0x");
    EXPECT_EQ(integral_id(".5"), ".5");
    EXPECT_EQ(integral_id("1e999999"), "1e999999");
    TempDir dir;
    const std::string path = dir.file("sheet_vessels.csv");
    std::ofstream(path) << "mmsi,name,to_bow_m,to_stern_m,to_port_m,to_stbd_m,draught_m\n230035780.0,SHEET,10,5,2,2,3\n";
    const auto v = read_vessels(path);
    ASSERT_EQ(v.count("230035780"), 1u);
    EXPECT_EQ(v.at("230035780").name, "SHEET");
}

// The vessels table knows its columns by the track files' names (one table, columns.hpp): names
// the CSV reader took and the table did not (ship_name, vessel_type, draft_m) are read too.
TEST(ReadVessels, ColumnsAreKnownByTheTrackFilesNames) {
    TempDir dir;
    const std::string path = dir.file("named_vessels.csv");
    std::ofstream(path) << "MMSI,Ship_Name,Vessel_Type,Draft_m,A,B,C,D\n230035780,SHEET,70,4.5,10,5,2,2\n";
    EXPECT_TRUE(is_vessels_table(path));
    const auto v = read_vessels(path);
    ASSERT_EQ(v.count("230035780"), 1u);
    const VesselInfo& s = v.at("230035780");
    EXPECT_EQ(s.name, "SHEET");
    EXPECT_EQ(s.draught_m, 4.5);
    ASSERT_TRUE(s.dims.has_value());
    EXPECT_EQ(s.dims->a, 10);
    EXPECT_EQ(s.dims->d, 2);
    // Every name of the table is written as a header is matched (normalised), and each field is
    // asked for by its own name.
    for (const ColumnNames& c : column_table()) {
        EXPECT_FALSE(c.names.empty()) << c.field;
        for (const std::string_view n : c.names) EXPECT_EQ(normalise_column_name(n), n) << c.field;
        EXPECT_EQ(column_names(c.field).data(), c.names.data());
    }
    EXPECT_THROW(column_names("latitude"), std::logic_error);
}

TEST(ReadVessels, ATableNoneOfWhoseVesselsIsATrackIsSaidNamingItAndItsCount) {
    std::map<std::string, VesselInfo> all;
    merge_vessels(all, {{"111", VesselInfo{}}, {"222", VesselInfo{}}}, "vessels file A");
    merge_vessels(all, {{"999", VesselInfo{}}, {"888", VesselInfo{}}}, "vessels file B");
    merge_vessels(all, {{"111", VesselInfo{}}}, "vessels file C");  // a vessel of A too: C matches
    const auto w = unmatched_vessels_tables(all, {"111", "333"});
    ASSERT_EQ(w.size(), 1u) << testing::PrintToString(w);
    EXPECT_THAT(w[0], HasSubstr("vessels file B: none of its 2 vessels is a track read (its ids such as '888', the tracks' such as '111', '333')"));
    EXPECT_TRUE(unmatched_vessels_tables(all, {"111", "888"}).empty());
    // A track whose id is written 230035780.0 matches the table's 230035780.
    std::map<std::string, VesselInfo> one;
    merge_vessels(one, {{"230035780", VesselInfo{}}}, "vessels file D");
    EXPECT_TRUE(unmatched_vessels_tables(one, {"230035780.0"}).empty());
}

TEST(ReadVessels, EveryBadRowCostsThatRowWithAWarningNamingItsLine) {
    TempDir dir;
    // The independent answer: the good rows, read from a file that holds only them.
    const std::string header = "mmsi,name,to_bow_m,to_stern_m,to_port_m,to_stbd_m,draught_m\n";
    const std::string good1 = "111,FIRST,10,5,2,2,3\n", good2 = "222,AFTER QUOTE,20,6,3,3,4\n", good3 = "888,LAST,30,7,4,4,5\n";
    write(dir.file("bad_vessels.csv"), header + good1 +
                                           "333,\"BROKEN,10,5,2,2,3\n"  // line 3: a quote never closed
                                           + good2 +                    // line 4: read (before: swallowed)
                                           "444,BIG,10000,10,5,5,3\n"   // line 5: a 10 km ship
                                           "555,COMMA,10,5,2,2,3,5\n"   // line 6: decimal comma
                                           "666,WORDS,ten,5,2,2,3\n"    // line 7: not a number
                                           ",NONAME,10,5,2,2,3\n"       // line 8
                                           "777,DEEP,10,5,2,2,80\n"     // line 9: draught in decimetres
                                           "999,NEG,10,-5,2,2,3\n"      // line 10
                                           + good3);
    write(dir.file("good_vessels.csv"), header + good1 + good2 + good3);
    std::vector<std::string> warnings;
    const auto got = read_vessels(dir.file("bad_vessels.csv"), &warnings);
    const auto want = read_vessels(dir.file("good_vessels.csv"));
    ASSERT_EQ(got.size(), want.size());
    for (const auto& [id, v] : want) {
        ASSERT_TRUE(got.count(id)) << id;
        EXPECT_EQ(got.at(id).name, v.name);
        EXPECT_EQ(got.at(id).dims, v.dims);
        EXPECT_EQ(got.at(id).draught_m, v.draught_m);
    }
    const std::string f = dir.file("bad_vessels.csv");
    EXPECT_THAT(warnings, ElementsAre(f + " line 3: a quote is not closed on its line; row skipped",
                                      HasSubstr(f + " line 5: dimensions a=10000 b=10 c=5 d=5 are larger than any ship"),
                                      f + " line 6: has 8 fields, the header 7 (a decimal comma in a comma-separated file?); row skipped",
                                      f + " line 7: to_bow_m 'ten' is not a number; row skipped", f + " line 8: no mmsi; row skipped",
                                      HasSubstr(f + " line 9: draught 80 m is deeper than any ship draws"),
                                      f + " line 10: to_stern_m '-5' is negative; row skipped"));
    // Semicolons: decimal commas are numbers; AIS 0 and empty values are "not known", silently.
    write(dir.file("semi_vessels.csv"), "mmsi;name;a;b;c;d;draught\n123;SEMI;12,5;4;2;2,5;3,2\n124;ZERO;0;0;0;0;0\n");
    warnings.clear();
    const auto semi = read_vessels(dir.file("semi_vessels.csv"), &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_EQ(*semi.at("123").dims, (shoal::hull::Dimensions{12.5, 4, 2, 2.5}));
    EXPECT_DOUBLE_EQ(semi.at("123").draught_m, 3.2);
    EXPECT_FALSE(semi.at("124").dims.has_value());
    // The real table has no bad row.
    warnings.clear();
    EXPECT_EQ(read_vessels(data_path("tracks/gpsd_nl_vessels.csv"), &warnings).size(), 19u);
    EXPECT_TRUE(warnings.empty());
}

TEST(ReadVessels, TwoTablesThatDisagreeAboutAVesselKeepTheFirstAndSaySoOnce) {
    TempDir dir;
    write(dir.file("a_vessels.csv"), "mmsi,name,a,b,c,d,draught\n111,ONE,10,5,2,2,\n222,TWO,20,5,3,3,4\n");
    write(dir.file("b_vessels.csv"), "mmsi,name,a,b,c,d,draught\n111,ONE,12,5,2,2,3.5\n111,ONE,12,5,2,2,3.5\n222,TWO,20,5,3,3,4\n333,,8,2,1,1,1\n");
    std::map<std::string, VesselInfo> all;
    std::vector<std::string> warnings;
    merge_vessels(all, read_vessels(dir.file("a_vessels.csv")), "vessels file A", &warnings);
    merge_vessels(all, read_vessels(dir.file("b_vessels.csv")), "vessels file B", &warnings);
    ASSERT_EQ(all.size(), 3u);
    EXPECT_THAT(warnings, ElementsAre("vessel 111: vessels file A and vessels file B disagree (dimensions a=10 b=5 c=2 d=2 and "
                                      "a=12 b=5 c=2 d=2): those of vessels file A (given first) are used"));
    EXPECT_EQ(*all.at("111").dims, (shoal::hull::Dimensions{10, 5, 2, 2}));
    EXPECT_EQ(all.at("111").source, "vessels file A");
    // What the first lacked (the draught), the second gives, and says where it came from.
    EXPECT_DOUBLE_EQ(all.at("111").draught_m, 3.5);
    EXPECT_EQ(all.at("111").draught_source, "vessels file B");
    EXPECT_EQ(all.at("333").source, "vessels file B");
}

}  // namespace

namespace {

/// The same double, bit for bit (NaN and -0.0 included).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(PackedTrack, EveryFixComesBackBitForBit) {
    // Fixes packed as a reader packs them (AIS's 1e-7 degrees and hundredths, and values that
    // are not: any double, -0.0, NaN, halves of the last unit, lines over 2^32), across chunk
    // boundaries, after truncate() and in a moved track: each unpacks to the very fix packed.
    std::mt19937_64 rng(15);
    std::uniform_real_distribution<double> u(0, 1);
    auto value = [&](double lo, double hi, double scale) {
        switch (rng() % 8) {
            case 0: return lo + (hi - lo) * u(rng);                                      // any double
            case 1: return -0.0;
            case 2: return std::round((lo + (hi - lo) * u(rng)) * scale) / scale + 0.5 / scale;  // half a unit off
            case 3: return hi;
            default: return std::round((lo + (hi - lo) * u(rng)) * scale) / scale;         // as AIS writes it
        }
    };
    for (int round = 0; round < 20; ++round) {
        PackedTrack t;
        std::vector<Fix> want;
        const std::size_t n = 1 + rng() % 3000;
        for (std::size_t i = 0; i < n; ++i) {
            Fix f;
            f.time_s = 1.7e9 + static_cast<double>(i);
            f.position = {value(-180, 180, 1e7), value(-90, 90, 1e7)};
            f.heading_deg = rng() % 5 == 0 ? NAN : value(0, 359.99, 100);
            f.cog_deg = rng() % 5 == 0 ? NAN : value(0, 359.99, 100);
            f.sog_kn = rng() % 5 == 0 ? NAN : value(0, 102.2, 100);
            f.line = rng() % 50 == 0 ? (std::size_t{1} << 33) + i : i + 2;
            f.nav_status = static_cast<std::uint8_t>(rng() % 16);
            t.push_back(f);
            want.push_back(f);
            if (rng() % 500 == 0) {  // drop some, go on
                const std::size_t keep = want.size() / 2;
                t.fixes.truncate(keep);
                want.resize(keep);
            }
        }
        PackedTrack moved = std::move(t);
        Fix extra;
        extra.time_s = 1.8e9;
        extra.position = {24.5, 60.25};
        moved.push_back(extra);
        want.push_back(extra);
        ASSERT_EQ(moved.size(), want.size());
        for (std::size_t i = 0; i < want.size(); ++i) {
            const Fix g = moved.fix(i), &w = want[i];
            ASSERT_TRUE(same_bits(g.time_s, w.time_s) && same_bits(g.position.lat, w.position.lat) && same_bits(g.position.lon, w.position.lon) &&
                        same_bits(g.heading_deg, w.heading_deg) && same_bits(g.cog_deg, w.cog_deg) && same_bits(g.sog_kn, w.sog_kn) &&
                        g.line == w.line && g.nav_status == w.nav_status)
                << "round " << round << " fix " << i << ": lat " << w.position.lat << " lon " << w.position.lon;
        }
    }
}

/// The tracks of a file normalised on threads are those normalised one after another, and so
/// are the report's counts and messages (a fix without a time is said, within the report's
/// limit, in track order): tracks in order, out of order, with repeated times, without times.
TEST(PackedTrack, TracksNormalisedOnThreadsAreThoseNormalisedInTurn) {
    std::mt19937_64 rng(41);
    for (int round = 0; round < 6; ++round) {
        std::vector<PackedTrack> tracks(1 + rng() % 300);
        for (std::size_t k = 0; k < tracks.size(); ++k) {
            tracks[k].id = std::to_string(k);
            tracks[k].file = "day.csv";
            const std::size_t n = rng() % 20 == 0 ? 20000 + rng() % 40000 : rng() % 900;
            const int kind = static_cast<int>(rng() % 4);  // 0 in order, 1 repeats, 2 out of order, 3 times missing
            for (std::size_t i = 0; i < n; ++i) {
                Fix f;
                f.time_s = 1.7e9 + (kind == 2 ? static_cast<double>(rng() % n) : static_cast<double>(i / (kind == 1 ? 2 : 1)));
                if (kind == 3 && rng() % 50 == 0) f.time_s = NAN;
                f.position = {24 + 1e-5 * static_cast<double>(i), 60.0};
                f.heading_deg = rng() % 3 == 0 ? NAN : static_cast<double>(rng() % 360);
                f.line = i + 2;
                tracks[k].push_back(f);
            }
        }
        auto normalised = [&](unsigned threads, ReadReport& report) {
            std::vector<PackedTrack> copy;
            for (const PackedTrack& t : tracks) {
                PackedTrack& c = copy.emplace_back();
                c.id = t.id;
                c.file = t.file;
                for (std::size_t i = 0; i < t.size(); ++i) c.push_back(t.fix(i));
            }
            if (threads == 0)
                for (PackedTrack& t : copy) normalise(t, report);
            else
                normalise(copy, report, threads);
            return copy;
        };
        ReadReport want_report;
        want_report.max_messages = 1 + round;
        const std::vector<PackedTrack> want = normalised(0, want_report);
        for (const unsigned threads : {1u, 2u, 3u, 8u}) {
            ReadReport got_report;
            got_report.max_messages = want_report.max_messages;
            const std::vector<PackedTrack> got = normalised(threads, got_report);
            ASSERT_EQ(got.size(), want.size());
            for (std::size_t k = 0; k < want.size(); ++k) {
                ASSERT_EQ(got[k].size(), want[k].size()) << "track " << k;
                for (std::size_t i = 0; i < want[k].size(); ++i) {
                    const Fix g = got[k].fix(i), w = want[k].fix(i);
                    ASSERT_TRUE(same_bits(g.time_s, w.time_s) && same_bits(g.heading_deg, w.heading_deg) && g.line == w.line)
                        << "round " << round << ", " << threads << " threads, track " << k << " fix " << i;
                }
            }
            EXPECT_EQ(got_report.skipped, want_report.skipped);
            EXPECT_EQ(got_report.skips_said, want_report.skips_said);
            EXPECT_EQ(got_report.duplicates, want_report.duplicates);
            EXPECT_EQ(got_report.reordered, want_report.reordered);
            EXPECT_EQ(got_report.messages, want_report.messages) << threads << " threads";
        }
        EXPECT_GT(want_report.duplicates + want_report.reordered, 0u);
    }
}

}  // namespace

namespace {

using shoal::geo::LonLat;
using shoal::track::distance_bounds_m;
using shoal::track::distance_m;

/// A point `metres` from p in the direction `bearing` (radians), on the flat approximation: the
/// pairs need only be near each other, not at an exact distance.
LonLat offset(LonLat p, double metres, double bearing) {
    const double lat = p.lat + metres * std::cos(bearing) / 111195.0;
    const double lon = p.lon + metres * std::sin(bearing) / (111195.0 * std::max(1e-6, std::cos(p.lat * M_PI / 180)));
    return {lon, std::clamp(lat, -90.0, 90.0)};
}

}  // namespace

TEST(DistanceBounds, HoldDistanceMOnRandomAndAdversarialPairs) {
    std::mt19937_64 rng(20261206);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    long checked = 0, tight = 0, near_pairs = 0;
    auto check = [&](LonLat a, LonLat b) {
        const double d = distance_m(a, b);
        const auto bnd = distance_bounds_m(a, b);
        ASSERT_LE(bnd.lower, d) << a.lon << "," << a.lat << " " << b.lon << "," << b.lat;
        ASSERT_GE(bnd.upper, d) << a.lon << "," << a.lat << " " << b.lon << "," << b.lat;
        ++checked;
        // Near pairs off the polar caps: the upper bound within 3x of the distance (the shortcut
        // is only worth having when it decides), the lower one within it when north-south.
        if (d < 100e3 && std::max(std::fabs(a.lat), std::fabs(b.lat)) < 60) {
            ++near_pairs;
            if (bnd.upper <= 3 * d + 1e-5) ++tight;
        }
    };
    for (int i = 0; i < 400000; ++i) {
        const LonLat a{-180 + 360 * u(rng), -90 + 180 * u(rng)};
        switch (i % 8) {
        case 0: check(a, {-180 + 360 * u(rng), -90 + 180 * u(rng)}); break;                          // anywhere
        case 1: check(a, offset(a, std::pow(10, -3 + 8 * u(rng)), 2 * M_PI * u(rng))); break;       // 1 mm to 100 km
        case 2: check(a, a); break;                                                                    // the same point
        case 3: check(a, {a.lon + 180 - 1e-6 * u(rng), -a.lat}); break;                                // nearly antipodal
        case 4: check({a.lon, 90 - 1e-4 * u(rng)}, {a.lon + 360 * u(rng) - 180, 90 - 1e-3 * u(rng)}); break;  // at a pole
        case 5: check({180 - 1e-5 * u(rng), a.lat}, {-180 + 1e-5 * u(rng), a.lat + 1e-5 * (u(rng) - 0.5)}); break;  // across the date line
        case 6: check(a, {a.lon + 1e-9 * (u(rng) - 0.5), a.lat + 1e-9 * (u(rng) - 0.5)}); break;      // a micrometre apart
        default: check(a, offset(a, 10 + 300 * u(rng), 2 * M_PI * u(rng))); break;                    // AIS fix to fix
        }
    }
    EXPECT_EQ(checked, 400000);
    EXPECT_GT(tight, near_pairs * 99 / 100) << tight << " of " << near_pairs;
    // Exactly antipodal along the equator and pole to pole (the haversine rounds by decimetres
    // there), and longitudes more than a turn apart: nothing proved, the haversine decides.
    for (const double off : {0.0, 1.2e-6, 1e-4}) {
        check({0, 0}, {180 - off, 0});
        check({10, 90 - off}, {10, -90});
    }
    EXPECT_TRUE(std::isinf(distance_bounds_m({0, 0}, {179.9999988, 0}).upper));
    EXPECT_TRUE(std::isinf(distance_bounds_m({0, 10}, {1e12, 10}).upper));
    // Nothing proved beyond the poles or for a value that is not a number.
    const auto beyond = distance_bounds_m({0, 91}, {0, 89});
    EXPECT_EQ(beyond.lower, 0);
    EXPECT_TRUE(std::isinf(beyond.upper));
    EXPECT_TRUE(std::isinf(distance_bounds_m({NAN, 10}, {0, 10}).upper));
}

TEST(DistanceBounds, PlausibleDecidesAsTheDistanceItself) {
    // Pairs whose distance lies around the plausibility limit (tolerance + max speed x time):
    // plausible() answers as distance_m(a, b) <= limit does, on either side and on the edge.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const shoal::track::WildFixOptions o;
    int within = 0, beyond = 0;
    for (int i = 0; i < 200000; ++i) {
        shoal::track::Fix a, b;
        a.position = {-180 + 360 * u(rng), -89 + 178 * u(rng)};
        a.time_s = 1000;
        b.time_s = 1000 + std::floor(1 + 120 * u(rng));
        const double limit = o.tolerance_m + o.max_speed_kn * 1852.0 / 3600.0 * (b.time_s - a.time_s);
        b.position = offset(a.position, limit * (0.5 + u(rng)), 2 * M_PI * u(rng));
        const bool exact = distance_m(a.position, b.position) <= limit;
        ASSERT_EQ(shoal::track::plausible(a, b, o), exact) << i;
        ASSERT_EQ(shoal::track::plausible(b, a, o), exact) << i;
        (exact ? within : beyond)++;
    }
    EXPECT_GT(within, 50000);
    EXPECT_GT(beyond, 50000);
}
