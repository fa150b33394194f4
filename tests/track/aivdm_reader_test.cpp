// Raw AIS logs (AIVDM/AIVDO) through the public track reader: tracks per MMSI next to the own
// ship's, their times (own clock, $PGHP, tag blocks, receive times), static data joining its
// track, and bad input contained. Expected values come from gpsdecode (gpsd-clients) and
// `date -u -d ... +%s`, as each test says.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "test_support.hpp"
#include <shoal/track/ais.hpp>
#include <shoal/track/nmea_reader.hpp>
#include <shoal/track/reader.hpp>
#include <shoal/util/error.hpp>

namespace {

using namespace shoal;
using namespace shoal::track;
using test::data_path;
using test::TempDir;
using testing::AllOf;
using testing::Contains;
using testing::HasSubstr;
using testing::ThrowsMessage;

const Track* find(const TrackFile& f, const std::string& id) {
    const auto it = std::find_if(f.tracks.begin(), f.tracks.end(), [&](const Track& t) { return t.id == id; });
    return it == f.tracks.end() ? nullptr : &*it;
}

TEST(AivdmReader, MixedLogGivesTheOwnShipAndEveryAisVesselDatedByTheLogsClock) {
    // gpsd_ait250.log: 34 RMC with status A (grep -c); gpsdecode -j: 61 position reports with a
    // position of 20 MMSIs, 33 of them own ship !AIVDO of MMSI 244630386. Line 16 holds
    // !AIVDM 13njCt031t0DA=lN2:jKmad60l1p: MMSI 258774000, lon 4.427830, lat 52.488015, speed
    // 12.4, course 303.0, heading 310 (gpsdecode -u: lon 2656698, lat 31492809), after RMC
    // 194907.00 of 010809: date -u -d '2009-08-01T19:49:07Z' +%s -> 1249156147.
    const std::string path = data_path("tracks/ais_raw/gpsd_ait250.log");
    // One vessel, one track (issue 42): the RMC fixes and the own !AIVDO reports are one track
    // of the AIVDO's MMSI. Each of the 33 AIVDO follows an RMC of its own (awk: no RMC second
    // twice before an AIVDO), so it is dated by it: 33 times held by both, kept once.
    const TrackFile f = read_tracks(path);
    EXPECT_EQ(f.format, "nmea");
    ASSERT_EQ(f.tracks.size(), 20u);
    EXPECT_EQ(find(f, "gpsd_ait250"), nullptr);
    const Track* own = find(f, "244630386");
    ASSERT_NE(own, nullptr);
    EXPECT_EQ(own->fixes.size(), 34u);
    EXPECT_THAT(f.report.messages, Contains(path + ": the own ship's GPS fixes (RMC, GGA, GLL: 34) and its own AIS reports (!AIVDO of "
                                                   "MMSI 244630386: 33) are one vessel: one track '244630386' of 34 fixes, 33 times "
                                                   "held by both kept once (the GPS fix)"));
    std::size_t ais_fixes = 0;
    for (const Track& tr : f.tracks)
        if (&tr != own) ais_fixes += tr.fixes.size();
    EXPECT_EQ(ais_fixes + 33 + f.report.duplicates, 61u);  // reports of one vessel within one RMC second are one time
    // Its static data (gpsdecode -j): type 5 of MMSI 305235000 "MEDUM", shiptype 70; type 24 of
    // 244050308 "TYPHOON", shiptype 37 (part B).
    const Track* medum = find(f, "305235000");
    ASSERT_NE(medum, nullptr);
    EXPECT_EQ(medum->name, "MEDUM");
    EXPECT_EQ(medum->ship_type, 70);
    EXPECT_EQ(medum->ship_type_source, "AIS static data (message 5)");
    const Track* typhoon = find(f, "244050308");
    ASSERT_NE(typhoon, nullptr);
    EXPECT_EQ(typhoon->ship_type, 37);
    EXPECT_EQ(typhoon->ship_type_source, "AIS static data (message 24)");
    const Track* t = find(f, "258774000");
    ASSERT_NE(t, nullptr);
    const Fix& x = t->fixes.at(0);
    EXPECT_EQ(x.line, 16u);
    EXPECT_EQ(x.time_s, 1249156147.0);
    EXPECT_DOUBLE_EQ(x.position.lon, 2656698 / 600000.0);
    EXPECT_DOUBLE_EQ(x.position.lat, 31492809 / 600000.0);
    EXPECT_DOUBLE_EQ(x.sog_kn, 12.4);
    EXPECT_DOUBLE_EQ(x.cog_deg, 303.0);
    EXPECT_DOUBLE_EQ(x.heading_deg, 310.0);
    EXPECT_EQ(x.nav_status, 0);
    for (const Track& tr : f.tracks)
        for (const Fix& fx : tr.fixes) {
            EXPECT_GE(fx.time_s, 1249156147.0 - 1) << tr.id;  // 2009-08-01T19:49:07Z .. the last RMC
            EXPECT_LE(fx.time_s, 1249156147.0 + 60) << tr.id;
        }
}

TEST(AivdmReader, DmaLogIsDatedByItsPghpHeadersAndStaticDataJoinsItsTrack) {
    // dma_replay_dump.txt: line 1 $PGHP,1,2013,3,18,9,19,9,499,... then line 2 !BSVDM of MMSI
    // 309146000 at lon 12.459748, lat 56.216012 (gpsdecode); date -u -d '2013-03-18T09:19:09Z'
    // +%s -> 1363598349, + 0.499 s.
    const TrackFile f = read_tracks(data_path("tracks/ais_raw/dma_replay_dump.txt"));
    const Track* t = find(f, "309146000");
    ASSERT_NE(t, nullptr);
    EXPECT_DOUBLE_EQ(t->fixes.at(0).time_s, 1363598349.499);
    EXPECT_NEAR(t->fixes[0].position.lon, 12.459748, 1e-6);
    EXPECT_NEAR(t->fixes[0].position.lat, 56.216012, 1e-6);
    EXPECT_EQ(find(f, "dma_replay_dump"), nullptr);  // no own-ship sentence: no track of the file's own
}

TEST(AivdmReader, StaticDataGivesTheTrackItsNameDimensionsAndDraught) {
    // The first lines of gpsd's ais-nmea.log: a type 5 in two sentences (here with NMEA 4.10
    // tag-block groups), per gpsdecode -j MMSI 371255000, shipname "SEA ENTERPRISE", shiptype 90,
    // to_bow 13, to_stern 15, to_port 1, to_starboard 6, draught 1.4; its line 936, a type 3 of the same
    // MMSI: status 5 (moored), lon 3427638, lat 31705155 (gpsdecode -u), heading 249. The report
    // repeated with a tag-block time in milliseconds, an epoch receive time and an ISO 8601 one:
    // date -u -d @1586295591 -> 2020-04-07T21:39:51Z.
    TempDir dir;
    std::ofstream(dir.file("tagged.nmea"))
        << "\\g:1-2-77,c:1586295590*23\\!AIVDM,2,1,9,B,55R3Vn82=ILTQ3KKS>1<D60Dq@E918U<F222221J1`?164vc03S1CCAD,0*2A\n"
        << "\\g:2-2-77*5D\\!AIVDM,2,2,9,B,`88888888888880,2*76\n"
        << "\\c:1586295591500*65\\!AIVDM,1,1,,A,35R3Vn50000J9adN?8@siGjp0E1r,0*42\n"
        << "1586295592 !AIVDM,1,1,,A,35R3Vn50000J9adN?8@siGjp0E1r,0*42\n"
        << "2020-04-07T21:39:53Z !AIVDM,1,1,,A,35R3Vn50000J9adN?8@siGjp0E1r,0*42\n";
    const TrackFile f = read_tracks(dir.file("tagged.nmea"));
    EXPECT_THAT(f.report.messages, testing::IsEmpty());
    ASSERT_EQ(f.tracks.size(), 1u);
    const Track& t = f.tracks[0];
    EXPECT_EQ(t.id, "371255000");
    EXPECT_EQ(t.name, "SEA ENTERPRISE");
    EXPECT_EQ(t.dims, (hull::Dimensions{13, 15, 1, 6}));
    EXPECT_DOUBLE_EQ(t.draught_m, 1.4);
    EXPECT_EQ(t.ship_type, 90);
    EXPECT_EQ(t.ship_type_source, "AIS static data (message 5)");
    ASSERT_EQ(t.fixes.size(), 3u);
    EXPECT_DOUBLE_EQ(t.fixes[0].time_s, 1586295591.5);
    EXPECT_DOUBLE_EQ(t.fixes[1].time_s, 1586295592.0);
    EXPECT_DOUBLE_EQ(t.fixes[2].time_s, 1586295593.0);
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lon, 3427638 / 600000.0);
    EXPECT_DOUBLE_EQ(t.fixes[0].position.lat, 31705155 / 600000.0);
    EXPECT_DOUBLE_EQ(t.fixes[0].heading_deg, 249.0);
    EXPECT_EQ(t.fixes[0].nav_status, nav_status_moored);
}

TEST(AivdmReader, BadSentencesAreSkippedWithTheirLinesAndNeverFatal) {
    TempDir dir;
    const std::string path = dir.file("bad.nmea");
    std::ofstream(path) << "1586295590 !AIVDM,1,1,,B,13aDp<PP000IwSlN?Wm@0?wN2<1T,0*28\n"                   // 1: bad checksum
                        << "1586295591 !AIVDM,2,2,9,B,`88888888888880,2*76\n"                              // 2: fragment 2 alone
                        << "1586295592 !AIVDM,2,1,9,B,55R3Vn82=ILTQ3KKS>1<D60Dq@E918U<F222221J1`?164vc03S1CCAD,0*2A\n"  // 3: never completed
                        << "1586295593 !AIVDM,1,1,,A,402B4L0000Htt1Lg@6FV5vG01d7N,0*06\n"                  // 4: type 4, not read
                        << "1586295594 !AIVDM,1,1,,B,13aDp<PP000IwSlN?Wm@0?wN2<1T,0*29\n"                  // 5: good
                        << "1586295595 !AIVDM,1,1,,B,13aDp<PP000IwSlN?Wm@0?wN2<1T\n"                         // 6: too few fields
                        << "1586295596 !AIVDM,1,1,,B,13aDp<PP000IwSlN?Wm@0?wN2<1T,7*2E\n";                 // 7: fill 7
    const TrackFile f = read_tracks(path);
    ASSERT_EQ(f.tracks.size(), 1u);
    EXPECT_EQ(f.tracks[0].id, "244660274");
    EXPECT_EQ(f.tracks[0].fixes.size(), 1u);
    EXPECT_EQ(f.report.rows, 7u);
    EXPECT_EQ(f.report.skipped, 5u);
    EXPECT_THAT(f.report.messages, Contains(path + " line 1: bad checksum '*28' (computed *29); sentence skipped"));
    EXPECT_THAT(f.report.messages, Contains(AllOf(HasSubstr("line 2: AIS fragment 2 of 2 without the fragments before it"), HasSubstr("half message"))));
    EXPECT_THAT(f.report.messages, Contains(HasSubstr("line 3: AIS message of 2 fragments without fragment 2 (half message)")));
    EXPECT_THAT(f.report.messages, Contains(HasSubstr("line 6: AIVDM with 6 fields")));
    EXPECT_THAT(f.report.messages, Contains(HasSubstr("line 7: AIVDM fill bits '7' (0-5)")));
    EXPECT_THAT(f.report.messages, Contains(path + ": 1 AIS messages of types shoal does not read ignored (1 of type 4)"));
}

/// `!AIVDM,...` with its checksum.
std::string aivdm(const std::string& body) {
    unsigned sum = 0;
    for (const char c : body) sum ^= static_cast<unsigned char>(c);
    char buf[4];
    std::snprintf(buf, sizeof buf, "%02X", sum);
    return "!" + body + "*" + buf;
}

TEST(AivdmReader, MessagesWaitingForFragmentsAreBoundedWhateverTheLines) {
    // Issue 42 (the class of "bad lines cost memory per line"): every first fragment with an id
    // of its own was held until the end (2 M of them: 806 MB). Now at most max_pending wait;
    // one more is the half message of the oldest, said at once. An id longer than a message
    // id and a first fragment longer than any message are refused at their line.
    std::vector<std::string> problems;
    ais::LineDecoder decoder([&](std::size_t line, const std::string& what) { problems.push_back(std::to_string(line) + ": " + what); });
    const std::string payload = "53brRt4000010SG;700iE@LE8@Tp4000000000153P615t0Ht0SCkjH4jC1C";
    ais::Decoded d;
    const std::size_t n = ais::LineDecoder::max_pending;
    for (std::size_t i = 1; i <= n; ++i) EXPECT_FALSE(decoder.line(aivdm("AIVDM,2,1," + std::to_string(i) + ",A," + payload + ",0"), i, d));
    EXPECT_THAT(problems, testing::IsEmpty());
    EXPECT_FALSE(decoder.line(aivdm("AIVDM,2,1,x,A," + payload + ",0"), n + 1, d));
    EXPECT_THAT(problems, testing::ElementsAre("1: AIS message of 2 fragments without fragment 2 (half message)"));
    // The newest still complete (type 5 of MMSI 244670316 in two sentences: gpsdecode).
    EXPECT_TRUE(decoder.line(aivdm("AIVDM,2,2,x,A,`0000000001,2"), n + 2, d));
    EXPECT_EQ(d.message.type, 5);
    EXPECT_EQ(d.line, n + 1);
    problems.clear();
    EXPECT_FALSE(decoder.line(aivdm("AIVDM,2,1," + std::string(40, '7') + ",A," + payload + ",0"), n + 3, d));
    EXPECT_FALSE(decoder.line(aivdm("AIVDM,2,1,y,A," + std::string(3000, '0') + ",0"), n + 4, d));
    EXPECT_THAT(problems, testing::ElementsAre(HasSubstr(std::to_string(n + 3) + ": AIVDM sequence id and channel '7777"),
                                               std::to_string(n + 4) + ": AIS message of more than 2048 payload characters"));
    problems.clear();
    decoder.finish();
    EXPECT_EQ(problems.size(), n - 1);  // the rest of the first ones, oldest first
    EXPECT_EQ(problems.front(), "2: AIS message of 2 fragments without fragment 2 (half message)");
}

/// The lines of a committed log, its `#` note dropped.
std::vector<std::string> log_lines(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line.front() != '#') out.push_back(line);
    return out;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
}

// ---------------------------------------------------------------------------------------------
// One vessel, one track (issue 42)

TEST(AivdmReader, OwnShipGpsFixesAndItsAivdoReportsAreOneTrackOfItsMmsi) {
    // own_ship_rmc_and_aivdo.nmea (make_logs.py): RMC each minute 10:00-10:20; after each an
    // !AIVDO of MMSI 235000001 dated by it (the same time), and between them 20 !AIVDO with
    // tag-block times at the half minute; a target 235000002. Before: a track of the file's
    // stem (21 fixes) and one of 235000001 (41): one ship, two tracks.
    const std::string path = data_path("tracks/ais_identity/own_ship_rmc_and_aivdo.nmea");
    const TrackFile f = read_tracks(path);
    ASSERT_EQ(f.tracks.size(), 2u);
    EXPECT_EQ(find(f, "own_ship_rmc_and_aivdo"), nullptr);
    const Track* own = find(f, "235000001");
    ASSERT_NE(own, nullptr);
    ASSERT_EQ(own->fixes.size(), 41u);
    // date -u -d 2024-05-01T10:00:00Z +%s -> 1714557600; one fix each half minute, in order,
    // the whole minutes the RMC's (line 2, 6, ...: 4 lines a minute), the half minutes the AIVDO's.
    for (std::size_t k = 0; k < own->fixes.size(); ++k) {
        EXPECT_DOUBLE_EQ(own->fixes[k].time_s, 1714557600.0 + 30.0 * static_cast<double>(k)) << k;
        EXPECT_EQ(own->fixes[k].line, k % 2 == 0 ? 2 + 4 * (k / 2) : 4 + 4 * (k / 2)) << k;
        EXPECT_NEAR(own->fixes[k].position.lat, 50.78 - 0.005 * static_cast<double>(k), 1e-6) << k;
    }
    EXPECT_DOUBLE_EQ(own->fixes[0].heading_deg, 180.0);  // the RMC has none: the AIVDO of its time gives it
    EXPECT_EQ(f.report.duplicates, 0u);
    EXPECT_THAT(f.report.messages, testing::ElementsAre(path + ": the own ship's GPS fixes (RMC, GGA, GLL: 21) and its own AIS reports "
                                                               "(!AIVDO of MMSI 235000001: 41) are one vessel: one track '235000001' "
                                                               "of 41 fixes, 21 times held by both kept once (the GPS fix)"));
}

TEST(AivdmReader, OwnShipIsOneTrackWhateverTheLogHoldsOfIt) {
    // Held-out variants of the log above: its AIVDO before any RMC, RMC only, AIVDO only, GGA
    // instead of RMC, and own reports of two MMSIs (said, joined to neither).
    TempDir dir;
    const std::vector<std::string> lines = log_lines(data_path("tracks/ais_identity/own_ship_rmc_and_aivdo.nmea"));
    auto read = [&](const std::vector<std::string>& l) {
        std::ofstream(dir.file("v.nmea")) << joined(l);
        return read_tracks(dir.file("v.nmea"));
    };
    auto only = [&](auto keep) {
        std::vector<std::string> out;
        for (const auto& l : lines)
            if (keep(l)) out.push_back(l);
        return out;
    };
    auto own_fixes = [](const TrackFile& f) {
        const Track* t = find(f, "235000001");
        return t ? t->fixes.size() : 0u;
    };
    {  // The tagged AIVDO first, then the rest: one track, as before.
        std::vector<std::string> l = only([](const std::string& x) { return x.front() == '\\'; });
        const std::vector<std::string> rest = only([](const std::string& x) { return x.front() != '\\'; });
        l.insert(l.end(), rest.begin(), rest.end());
        const TrackFile f = read(l);
        EXPECT_EQ(f.tracks.size(), 2u);
        EXPECT_EQ(own_fixes(f), 41u);
    }
    {  // RMC only: the file's track, as before.
        const TrackFile f = read(only([](const std::string& x) { return x.find("!AIVDO") == std::string::npos; }));
        ASSERT_EQ(f.tracks.size(), 2u);
        EXPECT_NE(find(f, "v"), nullptr);
        EXPECT_EQ(find(f, "v")->fixes.size(), 21u);
        EXPECT_EQ(own_fixes(f), 0u);
    }
    {  // AIVDO only: the MMSI's track of its 20 tagged reports; its 21 others and the target's 21 have no time, said once.
        const TrackFile f = read(only([](const std::string& x) { return x.find("$GPRMC") == std::string::npos; }));
        EXPECT_EQ(own_fixes(f), 20u);
        EXPECT_EQ(find(f, "v"), nullptr);
        EXPECT_THAT(f.report.messages, Contains(HasSubstr("v.nmea: 42 AIS position reports without a time dropped (lines 1-62; the first: before the log's first time)")));
    }
    {  // GGA for every RMC but the first (a GGA has no date: the first RMC dates them)
        std::vector<std::string> l;
        bool first = true;
        for (const auto& x : lines) {
            if (x.rfind("$GPRMC", 0) == 0 && !first) {
                // $GPRMC,hhmmss,A,lat,N,lon,W,... -> $GPGGA,hhmmss,lat,N,lon,W,1,08,1.0,0.0,M,0.0,M,,
                std::vector<std::string> f;
                std::string body = x.substr(1, x.find('*') - 1);
                for (std::size_t p = 0, c; ; p = c + 1) {
                    c = body.find(',', p);
                    f.push_back(body.substr(p, c == std::string::npos ? std::string::npos : c - p));
                    if (c == std::string::npos) break;
                }
                const std::string gga = "GPGGA," + f[1] + "," + f[3] + "," + f[4] + "," + f[5] + "," + f[6] + ",1,08,1.0,0.0,M,0.0,M,,";
                unsigned sum = 0;
                for (const char c : gga) sum ^= static_cast<unsigned char>(c);
                char buf[4];
                std::snprintf(buf, sizeof buf, "%02X", sum);
                l.push_back("$" + gga + "*" + buf);
            } else {
                l.push_back(x);
            }
            if (x.rfind("$GPRMC", 0) == 0) first = false;
        }
        const TrackFile f = read(l);
        EXPECT_EQ(f.tracks.size(), 2u);
        EXPECT_EQ(own_fixes(f), 41u);
    }
    {  // Own reports of two MMSIs: the GPS fixes stay the file's track, said.
        std::vector<std::string> l = lines;
        l.push_back("!AIVDO,1,1,,,13P7@hh01@wr390M3W`725`00000,0*17");  // MMSI 235000003 (gpsdecode), 50.78 N 1.30 W
        const TrackFile f = read(l);
        EXPECT_NE(find(f, "v"), nullptr);
        EXPECT_THAT(f.report.messages, Contains(HasSubstr("its own AIS reports (!AIVDO) give 2 MMSIs (235000001, 235000003): its GPS "
                                                          "fixes (RMC, GGA, GLL) stay the track 'v', joined to none of them")));
    }
}

TEST(AivdmReader, ALogWithoutATimeSourceIsRefusedNamingTheFile) {
    // gpsd's ais-raw-messages.log: bare !AIVDM lines, nothing to date them with.
    const std::string path = data_path("tracks/ais_raw/gpsd_ais_raw_messages.log");
    EXPECT_THAT([&] { read_tracks(path); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path + ": AIS position reports without any time source"),
                                                HasSubstr("the AIS second field alone cannot date a fix"))));
}

}  // namespace
