// The ship type's meaning (shoal/track/ship_type.hpp) against two independent decoders from
// Debian: gpsd's `gpsdecode -j` (gpsd-clients: its "shiptype_text") and libais (python3-ais:
// ais.lut.TYPE_AND_CARGO), on one type 5 message for every ship type 0-255 built by the tests'
// own encoder (ais_encoder.hpp). The three must read the same number from each message, and
// give it the same meaning, word for word after a normalisation of spelling only
// (normalised()); the few places where they differ from each other or from ITU-R M.1371 are
// listed, with the reason, in the test.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "track/ais_encoder.hpp"
#include "track/decoders.hpp"
#include <shoal/track/ais.hpp>
#include "track/ship_type.hpp"

namespace {

using namespace shoal;
using json = nlohmann::json;
using test::Encoder;
using test::TempDir;
using test::with_checksum;

using test::gpsdecode_path;
using test::json_lines;
using test::python_path;
using test::run;

/// Type 5 (ITU-R M.1371 table 72) of MMSI 200000000 + `ship_type` with that ship type, as two
/// sentences.
std::string type5(int ship_type) {
    Encoder e;
    e.put(5, 6);
    e.put(0, 2);
    e.put(200000000 + ship_type, 30);
    e.put(0, 2);        // AIS version
    e.put(1234567, 30);  // IMO number
    e.text("CALL", 7);
    e.text("SHIP " + std::to_string(ship_type), 20);
    e.put(ship_type, 8);
    e.put(50, 9);  // A, B, C, D
    e.put(10, 9);
    e.put(5, 6);
    e.put(5, 6);
    e.put(1, 4);  // EPFD: GPS
    e.put(1, 4);  // ETA: January 1st, 00:00
    e.put(1, 5);
    e.put(0, 5);
    e.put(0, 6);
    e.put(42, 8);  // draught 4.2 m
    e.text("ROTTERDAM", 20);
    e.put(0, 2);  // DTE, spare
    const auto [payload, fill] = e.armour();
    const std::string seq = std::to_string(ship_type % 10);
    return "!" + with_checksum("AIVDM,2,1," + seq + ",A," + payload.substr(0, 60) + ",0") + "\n" + "!" +
           with_checksum("AIVDM,2,2," + seq + ",A," + payload.substr(60) + "," + std::to_string(fill)) + "\n";
}

/// The words of a meaning, in lower case, spelt one way: "ops" operations, "cat" category,
/// "polution" pollution, "200m" 200 m, "no info" no additional information, and "reserved
/// for future use" reserved (the decoders shorten it at 38 and 39, and libais everywhere).
std::string normalised(const std::string& text) {
    std::string s;
    for (const char c : text) s += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : ' ';
    std::istringstream in(s);
    std::string out;
    for (std::string w; in >> w;) {
        if (w == "ops") w = "operations";
        else if (w == "cat") w = "category";
        else if (w == "polution") w = "pollution";
        else if (w == "info") w = "additional information";  // libais's "No info"
        else if (w.size() > 1 && w.back() == 'm' && std::isdigit(static_cast<unsigned char>(w[0]))) w = w.substr(0, w.size() - 1) + " m";
        out += (out.empty() ? "" : " ") + w;
    }
    const std::string future = "reserved for future use";
    for (std::size_t at = out.find(future); at != std::string::npos; at = out.find(future, at)) out.replace(at, future.size(), "reserved");
    return out;
}

TEST(ShipType, NormalisingChangesSpellingNotMeaning) {
    EXPECT_EQ(normalised("Dredging or underwater ops"), normalised("Dredging or underwater operations"));
    EXPECT_EQ(normalised("Towing: length exceeds 200m or breadth exceeds 25m"), "towing length exceeds 200 m or breadth exceeds 25 m");
    EXPECT_EQ(normalised("Wing in ground (WIG), No info"), "wing in ground wig no additional information");
    EXPECT_NE(normalised("Cargo, Hazardous cat A"), normalised("Cargo, hazardous category B"));
    EXPECT_NE(normalised("Tanker, all ships of this type"), normalised("Cargo, all ships of this type"));
    EXPECT_NE(normalised("Reserved for regional use"), normalised("Reserved for future use"));
}

TEST(ShipType, TheTableNamesEveryNumberAndOnlyThose) {
    EXPECT_EQ(track::ship_type_text(-1), "");
    EXPECT_EQ(track::ship_type_text(256), "");
    for (int t = 0; t <= 255; ++t) EXPECT_FALSE(track::ship_type_text(t).empty()) << t;
    // ITU-R M.1371-5 table 53, read there: 100-199 regional, 200-255 future use.
    EXPECT_EQ(track::ship_type_text(100), "Reserved for regional use");
    EXPECT_EQ(track::ship_type_text(199), "Reserved for regional use");
    EXPECT_EQ(track::ship_type_text(200), "Reserved for future use");
    EXPECT_EQ(track::ship_type_text(255), "Reserved for future use");
    EXPECT_EQ(track::ship_type_text(52), "Tug");
    EXPECT_EQ(track::ship_type_text(70), "Cargo, all ships of this type");
}

TEST(ShipType, EveryShipTypeMeansWhatGpsdAndLibaisSayItMeans) {
    if (!std::filesystem::exists(gpsdecode_path)) GTEST_SKIP() << gpsdecode_path << " is missing: install gpsd-clients";
    if (std::system("/usr/bin/python3 -c 'import ais.lut' >/dev/null 2>&1") != 0) GTEST_SKIP() << "libais is missing: install python3-ais";
    TempDir dir;
    std::string log;
    for (int t = 0; t <= 255; ++t) log += type5(t);
    const std::string in = dir.file("type5.nmea");
    std::ofstream(in, std::ios::binary) << log;

    // Ours: the number decoded, and its meaning.
    const std::vector<track::ais::Decoded> ours = track::ais::decode_lines(log);
    ASSERT_EQ(ours.size(), 256u);
    // gpsd: its record of each message, with its own text.
    const std::vector<json> gpsd = json_lines(run(std::string(gpsdecode_path) + " -j < " + in));
    ASSERT_EQ(gpsd.size(), 256u);
    // libais: the number it decodes and its look-up table's text (none outside 20-99).
    const std::string script = dir.file("libais.py");
    std::ofstream(script) << "import sys, json, ais, ais.lut\n"
                             "lines = [l.strip() for l in open(sys.argv[1]) if l.strip()]\n"
                             "for a, b in zip(lines[0::2], lines[1::2]):\n"
                             "    p = a.split(',')[5] + b.split(',')[5]\n"
                             "    d = ais.decode(p, int(b.split(',')[6].split('*')[0]))\n"
                             "    t = d['type_and_cargo']\n"
                             "    print(json.dumps({'shiptype': t, 'text': ais.lut.TYPE_AND_CARGO.get(t)}))\n";
    const std::vector<json> lib = json_lines(run(std::string(python_path) + " " + script + " " + in));
    ASSERT_EQ(lib.size(), 256u);

    for (int t = 0; t <= 255; ++t) {
        const std::size_t k = static_cast<std::size_t>(t);
        SCOPED_TRACE("ship type " + std::to_string(t) + ": gpsd " + gpsd[k].dump() + ", libais " + lib[k].dump());
        ASSERT_EQ(ours[k].message.type, 5);
        ASSERT_EQ(ours[k].message.ship_type, t);
        ASSERT_EQ(gpsd[k].at("shiptype").get<int>(), t);
        ASSERT_EQ(lib[k].at("shiptype").get<int>(), t);
        const std::string mine = normalised(track::ship_type_text(t));
        const std::string g = normalised(gpsd[k].at("shiptype_text").get<std::string>());
        if (t >= 100) {
            // gpsd calls 100-255 invalid; M.1371-5 reserves them (regional use, future use).
            EXPECT_EQ(g, "invalid ship type");
        } else if (t == 29) {
            // gpsd: "reserved"; M.1371 (second digit 9) and libais: no additional information.
            EXPECT_EQ(g, normalised("Wing in ground (WIG) - Reserved"));
            EXPECT_EQ(mine, normalised("Wing in ground (WIG), no additional information"));
        } else if (t == 59) {
            // Both decoders leave out M.1371-5's first word, "Noncombatant".
            EXPECT_EQ(g, "ship according to rr resolution no 18");
            EXPECT_EQ(mine, "noncombatant " + g);
        } else {
            EXPECT_EQ(mine, g);
        }
        if (lib[k].at("text").is_null()) {
            EXPECT_TRUE(t < 20 || t >= 100);
        } else {
            const std::string l = normalised(lib[k].at("text").get<std::string>());
            EXPECT_EQ(mine, t == 59 ? "noncombatant " + l : l);
        }
    }
}

}  // namespace
