// The AIS decoder (shoal/track/ais.hpp) against two independent decoders from Debian:
// gpsd's `gpsdecode -u -j` (package gpsd-clients) and libais (python3-ais, under
// /usr/bin/python3), run as subprocesses, on the committed raw logs (tests/data/tracks/ais_raw/)
// and on messages bit-packed here from random fields by the tests' own encoder (ais_encoder.hpp).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "track/ais_encoder.hpp"
#include "track/decoders.hpp"
#include <shoal/track/ais.hpp>

namespace {

using namespace shoal;
using namespace shoal::track;
using json = nlohmann::json;
using test::data_path;
using test::TempDir;
using test::Encoder;
using test::with_checksum;

using test::gpsdecode_path;
using test::json_lines;
using test::python_path;
using test::run;

std::string file_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// Each AIS sentence of `text` from its `!` to the line's end: no receive times, no tag blocks
/// (what gpsdecode and the libais script read).
std::string sentences_only(const std::string& text) {
    std::string out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        for (std::size_t i = line.find('!'); i != std::string::npos; i = line.find('!', i + 1))
            if (line.compare(i + 3, 3, "VDM") == 0 || line.compare(i + 3, 3, "VDO") == 0) {
                out += line.substr(i) + "\n";
                break;
            }
    }
    return out;
}

/// gpsd's records, unscaled (the fields as sent), in the order the messages completed. gpsd
/// reads only the talkers of IEC 61162-1 (AI, AB, BS, ...), not DMA's `!BYVDM`: every talker is
/// written AI for it (the checksum computed anew where it was right).
std::vector<json> gpsdecode(const TempDir& dir, const std::string& sentences) {
    std::string in;
    std::istringstream lines(sentences);
    for (std::string s; std::getline(lines, s);) {
        const std::size_t star = s.find('*');
        std::string_view body;
        std::string problem;
        if (star != std::string::npos && s.size() > 3 && ais::checksum_ok(std::string_view(s).substr(1), body, problem)) {
            s = "!" + with_checksum("AI" + s.substr(3, star - 3));
        }
        in += s + "\n";
    }
    write_text(dir.file("gpsd.in"), in);
    return json_lines(run(std::string(gpsdecode_path) + " -u -j < " + dir.file("gpsd.in")));
}

/// libais on messages joined by a reassembly of its own (consecutive fragments of one sequence
/// id and channel, checksums verified), one record per complete message, normalised to
/// shoal's names; {"error": ..., "type": t} where libais refuses a message.
constexpr const char* libais_script = R"PY(
import sys, json, ais
pending = {}
for line in open(sys.argv[1]):
    s = line.strip(); body = s[1:].split('*')[0]; f = body.split(',')
    if len(f) != 7: continue
    if '*' in s:
        x = 0
        for c in body: x ^= ord(c)
        try:
            if int(s.split('*')[1][:2], 16) != x: continue
        except ValueError: continue
    n, k, key = int(f[1]), int(f[2]), (f[3], f[4], f[0][2:])
    if n == 1: payload = f[5]
    else:
        if k == 1: pending[key] = [f[5], 2, n]; continue
        p = pending.pop(key, None)
        if not p or p[1] != k or p[2] != n: continue
        p[0] += f[5]; p[1] += 1
        if k < n: pending[key] = p; continue
        payload = p[0]
    t = ord(payload[0]) - 48
    if t > 40: t -= 8
    try: d = ais.decode(payload, int(f[6]))
    except Exception as e:
        print(json.dumps({'error': str(e), 'type': t})); continue
    r = {'type': d['id'], 'mmsi': d['mmsi']}
    names = {'x': 'lon', 'y': 'lat', 'sog': 'sog', 'cog': 'cog', 'true_heading': 'heading', 'nav_status': 'status',
             'timestamp': 'second', 'type_and_cargo': 'shiptype', 'dim_a': 'a', 'dim_b': 'b', 'dim_c': 'c',
             'dim_d': 'd', 'draught': 'draught', 'part_num': 'part'}
    for k2, v in names.items():
        if k2 in d: r[v] = d[k2]
    if 'name' in d: r['name'] = d['name'].split('@')[0].rstrip(' ')
    print(json.dumps(r))
)PY";

std::vector<json> libais(const TempDir& dir, const std::string& sentences) {
    write_text(dir.file("libais.py"), libais_script);
    write_text(dir.file("libais.in"), sentences);
    return json_lines(run(std::string(python_path) + " " + dir.file("libais.py") + " " + dir.file("libais.in")));
}

bool read_type(int t) { return t == 1 || t == 2 || t == 3 || t == 5 || t == 18 || t == 19 || t == 24 || t == 27; }

/// NAN when the raw value means "not available" (or is out of range), else raw / scale.
double scaled(std::int64_t raw, std::int64_t first_invalid, double scale) { return raw >= first_invalid ? NAN : raw / scale; }

/// libais holds SOG, COG and draught as float.
#define EXPECT_NEAR_OR_NAN(a, b) EXPECT_TRUE((std::isnan(a) && std::isnan(b)) || std::fabs((a) - (b)) < 1e-4) << #a " = " << (a) << ", " #b " = " << (b)
#define EXPECT_SAME(a, b) EXPECT_TRUE((std::isnan(a) && std::isnan(b)) || (a) == (b)) << #a " = " << (a) << ", " #b " = " << (b)

/// One message against gpsd's unscaled record of it.
void expect_as_gpsd(const ais::Decoded& d, const json& g) {
    const ais::Message& m = d.message;
    SCOPED_TRACE("line " + std::to_string(d.line) + ", gpsd " + g.dump());
    ASSERT_EQ(m.type, g.at("type").get<int>());
    EXPECT_EQ(m.mmsi, g.at("mmsi").get<std::uint32_t>());
    if (m.is_position_report()) {
        const bool long_range = m.type == 27;
        const double per_degree = long_range ? 600.0 : 600000.0;
        const double lon = g.at("lon").get<std::int64_t>() / per_degree, lat = g.at("lat").get<std::int64_t>() / per_degree;
        if (std::fabs(lon) > 180.0 || std::fabs(lat) > 90.0) {  // 181, 91: not available
            EXPECT_FALSE(m.position);
        } else {
            EXPECT_TRUE(m.position);
            if (m.position) {
                EXPECT_EQ(*m.position, (geo::LonLat{lon, lat}));
            }
        }
        const std::int64_t speed = g.at("speed"), course = g.at("course");
        EXPECT_SAME(m.sog_kn, long_range ? scaled(speed, 63, 1.0) : scaled(speed, 1023, 10.0));
        EXPECT_SAME(m.cog_deg, long_range ? scaled(course, 360, 1.0) : scaled(course, 3600, 10.0));
        if (!long_range) {
            EXPECT_SAME(m.heading_deg, scaled(g.at("heading").get<std::int64_t>(), 360, 1.0));
            EXPECT_EQ(m.second, g.at("second").get<int>());
        }
        const int status = m.type <= 3 || long_range ? g.at("status").get<int>() : nav_status_unknown;
        EXPECT_EQ(m.nav_status, status);
    }
    if (m.type == 5 || m.type == 19) {
        EXPECT_EQ(m.name, g.at("shipname").get<std::string>());
        EXPECT_EQ(m.ship_type, g.at("shiptype").get<int>());
        const hull::Dimensions dims{g.at("to_bow"), g.at("to_stern"), g.at("to_port"), g.at("to_starboard")};
        if (dims.a > 0 && dims.b > 0 && dims.c > 0 && dims.d > 0) {
            EXPECT_EQ(m.dims, dims);
        } else {
            EXPECT_FALSE(m.dims);
        }
    }
    if (m.type == 5) {
        const std::int64_t draught = g.at("draught");
        EXPECT_SAME(m.draught_m, draught > 0 ? draught / 10.0 : NAN);
    }
}

/// A name as libais writes it: 6-bit characters 31 `_` and 39 `'` (ITU-R M.1371 table 47) as
/// `-` and `` ` `` (gpsd and shoal keep the table's; real names have them: "X_PRESS MATTERHORN").
std::string libais_spelling(std::string name) {
    for (char& c : name) c = c == '_' ? '-' : c == '\'' ? '`' : c;
    return name;
}

/// One message against libais's scaled record.
void expect_as_libais(const ais::Decoded& d, const json& l) {
    const ais::Message& m = d.message;
    SCOPED_TRACE("line " + std::to_string(d.line) + ", libais " + l.dump());
    ASSERT_EQ(m.type, l.at("type").get<int>());
    EXPECT_EQ(m.mmsi, l.at("mmsi").get<std::uint32_t>());
    if (m.is_position_report()) {
        const double lon = l.at("lon"), lat = l.at("lat");
        if (std::fabs(lon) > 180.0 || std::fabs(lat) > 90.0) {
            EXPECT_FALSE(m.position);
        } else {
            EXPECT_TRUE(m.position);
            if (m.position) {
                EXPECT_NEAR(m.position->lon, lon, 1e-9);  // libais divides in float steps of its own
                EXPECT_NEAR(m.position->lat, lat, 1e-9);
            }
        }
        const bool long_range = m.type == 27;
        const double sog = l.at("sog"), cog = l.at("cog");
        EXPECT_NEAR_OR_NAN(m.sog_kn, sog >= (long_range ? 63.0 : 102.3) - 1e-4 ? NAN : sog);
        EXPECT_NEAR_OR_NAN(m.cog_deg, cog >= 360.0 - 1e-4 ? NAN : cog);
        if (!long_range) {
            EXPECT_SAME(m.heading_deg, scaled(l.at("heading").get<std::int64_t>(), 360, 1.0));
            EXPECT_EQ(m.second, l.at("second").get<int>());
        }
        if (m.type <= 3 || long_range) {
            EXPECT_EQ(m.nav_status, l.at("status").get<int>());
        }
    }
    if (l.contains("name")) {
        EXPECT_EQ(libais_spelling(m.name), l.at("name").get<std::string>());
    }
    if (l.contains("shiptype")) {
        EXPECT_EQ(m.ship_type, l.at("shiptype").get<int>());
    }
    if (l.contains("a") && m.mmsi / 10000000 != 98) {
        const hull::Dimensions dims{l.at("a"), l.at("b"), l.at("c"), l.at("d")};
        if (dims.a > 0 && dims.b > 0 && dims.c > 0 && dims.d > 0) {
            EXPECT_EQ(m.dims, dims);
        } else {
            EXPECT_FALSE(m.dims);
        }
    }
    if (l.contains("draught")) {
        const double draught = l.at("draught");
        EXPECT_NEAR_OR_NAN(m.draught_m, draught > 0 ? draught : NAN);
    }
    if (m.type == 24) {
        EXPECT_EQ(m.part, l.at("part").get<int>());
    }
}

struct Comparison {
    std::size_t messages = 0, libais_refused = 0;
};

/// Everything shoal decodes from `text` equals gpsd's and libais's decoding, message by message.
Comparison compare_with_decoders(const std::string& text) {
    Comparison out;
    TempDir dir;
    const std::vector<ais::Decoded> ours = ais::decode_lines(text);
    const std::string sentences = sentences_only(text);
    out.messages = ours.size();

    // gpsd: the same messages in the same order; type 24 merged by gpsd (parts A and B of one
    // MMSI into one record), so compared per MMSI with the parts shoal decoded before it.
    std::vector<json> gpsd;
    for (json& g : gpsdecode(dir, sentences))
        if (read_type(g.at("type"))) gpsd.push_back(std::move(g));
    std::vector<const ais::Decoded*> ours_not24;
    std::map<std::uint32_t, std::pair<const ais::Message*, const ais::Message*>> parts;  // A, B
    std::size_t k24 = 0, gpsd24 = 0;
    std::vector<const ais::Decoded*> order24;
    for (const ais::Decoded& d : ours) (d.message.type == 24 ? order24 : ours_not24).push_back(&d);
    std::vector<json> gpsd_not24;
    for (json& g : gpsd) {
        if (g.at("type") != 24) {
            gpsd_not24.push_back(std::move(g));
            continue;
        }
        ++gpsd24;
        const std::uint32_t mmsi = g.at("mmsi");
        while (k24 < order24.size()) {  // shoal's parts up to the one gpsd completed this record with
            const ais::Message& m = order24[k24++]->message;
            (m.part == 0 ? parts[m.mmsi].first : parts[m.mmsi].second) = &m;
            if (m.mmsi == mmsi && parts[mmsi].first && parts[mmsi].second) break;
        }
        const auto [a, b] = parts[mmsi];
        if (!a || !b) {
            ADD_FAILURE() << "gpsd has type 24 of MMSI " << mmsi << " where shoal does not have both parts: " << g.dump();
            continue;
        }
        EXPECT_EQ(a->name, g.value("shipname", std::string())) << g.dump();
        EXPECT_EQ(b->ship_type, g.at("shiptype").get<int>()) << g.dump();
        if (g.contains("to_bow")) {
            const hull::Dimensions dims{g.at("to_bow"), g.at("to_stern"), g.at("to_port"), g.at("to_starboard")};
            EXPECT_EQ(b->dims, dims.a > 0 && dims.b > 0 && dims.c > 0 && dims.d > 0 ? std::optional(dims) : std::nullopt) << g.dump();
        } else {
            EXPECT_FALSE(b->dims) << g.dump();
        }
    }
    EXPECT_EQ(ours_not24.size(), gpsd_not24.size()) << "messages other than type 24, shoal and gpsd";
    for (std::size_t i = 0; i < std::min(ours_not24.size(), gpsd_not24.size()); ++i) expect_as_gpsd(*ours_not24[i], gpsd_not24[i]);
    std::printf("  type 24: %zu parts of shoal's, %zu records of gpsd's (the parts A and B of one vessel merged)\n", order24.size(), gpsd24);

    // libais: every message, in order; a message it refuses only for a bit count other than the
    // standard's (gpsd and shoal accept a longer one, and type 5 of 420-423 bits).
    std::vector<json> lib;
    for (json& l : libais(dir, sentences))
        if (read_type(l.at("type"))) lib.push_back(std::move(l));
    EXPECT_EQ(ours.size(), lib.size()) << "messages, shoal and libais";
    for (std::size_t i = 0; i < std::min(ours.size(), lib.size()); ++i) {
        if (lib[i].contains("error")) {
            EXPECT_THAT(lib[i].at("error").get<std::string>(), testing::HasSubstr("BAD_BIT_COUNT")) << "line " << ours[i].line;
            ++out.libais_refused;
            continue;
        }
        expect_as_libais(ours[i], lib[i]);
    }
    return out;
}

TEST(AisDecoder, RawLogsDecodeAsGpsdAndLibaisDecodeThem) {
    REQUIRE_DECODERS();
    for (const char* name : {"gpsd_ais_nmea_head400.log", "gpsd_ait250.log", "gpsd_ais_raw_messages.log",
                             "dma_stream_example_head400.txt", "dma_replay_dump.txt"}) {
        SCOPED_TRACE(name);
        const Comparison c = compare_with_decoders(file_text(data_path(std::string("tracks/ais_raw/") + name)));
        EXPECT_GT(c.messages, 10u);
        std::printf("%s: %zu messages compared (libais refused %zu for their bit count)\n", name, c.messages, c.libais_refused);
    }
}

/// The whole raw logs of the project's shared data (the committed ones are copies or their
/// first 400 lines), when they are there: $SHOAL_SHARED_DATA, or ../shared/data beside the
/// repository.
TEST(AisDecoder, WholeSharedRawLogsDecodeAsGpsdAndLibaisDecodeThem) {
    REQUIRE_DECODERS();
    const char* env = std::getenv("SHOAL_SHARED_DATA");
    const std::filesystem::path shared = env ? std::filesystem::path(env)
                                             : std::filesystem::path(SHOAL_TEST_DATA).parent_path().parent_path().parent_path().parent_path() /
                                                   "shared" / "data";
    const std::filesystem::path tracks = shared / "tracks";
    if (!std::filesystem::exists(tracks / "gpsd" / "raw")) GTEST_SKIP() << tracks << " not found (set SHOAL_SHARED_DATA)";
    for (const char* name : {"gpsd/raw/ais-nmea.log", "gpsd/raw/ait250.log", "gpsd/raw/ais-raw-messages.log", "dma/raw/stream_example.txt",
                             "dma/raw/replay_dump.txt"}) {
        SCOPED_TRACE(name);
        if (!std::filesystem::exists(tracks / name)) {
            ADD_FAILURE() << tracks / name << " is missing from the shared data";
            continue;
        }
        const Comparison c = compare_with_decoders(file_text((tracks / name).string()));
        EXPECT_GT(c.messages, 10u);
        std::printf("%s: %zu messages compared (libais refused %zu for their bit count)\n", name, c.messages, c.libais_refused);
    }
}

// ---------------------------------------------------------------------------------------------
// Messages built here

/// What the generator put in a message: shoal's values as ITU-R M.1371 defines them.
struct Truth {
    ais::Message message;
};

class Generator {
public:
    explicit Generator(std::uint32_t seed) : m_rng(seed) {}

    /// A random message of a type shoal reads, its sentences (with a tag-block group when it
    /// takes several and `tag_groups`), and what it holds.
    Truth next(std::string& lines, std::string& plain) {
        static constexpr int types[] = {1, 2, 3, 18, 19, 27, 5, 24};
        const int type = types[pick(0, 7)];
        Encoder e;
        Truth t;
        ais::Message& m = t.message;
        m.type = type;
        m.mmsi = static_cast<std::uint32_t>(pick(0, 999999999));
        if (chance(0.05)) m.mmsi = 980000000 + static_cast<std::uint32_t>(pick(0, 9999999));  // auxiliary craft
        e.put(type, 6);
        e.put(pick(0, 3), 2);
        e.put(m.mmsi, 30);
        if (type == 27) {
            long_range(e, m);
        } else if (type == 5) {
            e.put(pick(0, 3), 2);
            e.put(pick(0, (1 << 30) - 1), 30);
            e.text(name(7), 7);
            m.name = trimmed(name(20));
            e.text(m.name, 20);
            ship_static(e, m);
            e.put(pick(0, 15), 4);  // EPFD
            e.put(pick(0, (1 << 20) - 1), 20);  // ETA
            const int draught = chance(0.2) ? 0 : pick(1, 255);
            e.put(draught, 8);
            if (draught > 0) m.draught_m = draught / 10.0;
            e.text(name(20), 20);
            e.put(0, 2);  // DTE, spare
        } else if (type == 24) {
            m.part = pick(0, 1);
            e.put(m.part, 2);
            if (m.part == 0) {
                m.name = trimmed(name(20));
                e.text(m.name, 20);
            } else {
                m.ship_type = pick(0, 255);
                e.put(m.ship_type, 8);
                e.text(name(7), 7);
                e.text(name(7), 7);
                dims(e, m);
                if (m.mmsi / 10000000 == 98) m.dims.reset();
                e.put(0, 6);
            }
        } else {
            position_report(e, m);
        }
        emit(e, lines, plain);
        return t;
    }

private:
    int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(m_rng); }
    bool chance(double p) { return std::bernoulli_distribution(p)(m_rng); }

    /// Up to `n` characters of 6-bit ASCII (no `@`: the text's end), perhaps with blanks. Not
    /// 31 `_` and 39 `'` (ITU-R M.1371 table 47), which libais writes `-` and `` ` ``.
    std::string name(std::size_t n) {
        static const std::string chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^ !\"#$%&()*+,-./0123456789:;<=>?";
        std::string s;
        const std::size_t len = static_cast<std::size_t>(pick(0, static_cast<int>(n)));
        for (std::size_t i = 0; i < len; ++i) s += chance(0.7) ? chars[static_cast<std::size_t>(pick(0, 25))] : chars[static_cast<std::size_t>(pick(0, static_cast<int>(chars.size()) - 1))];
        return s;
    }
    static std::string trimmed(std::string s) {
        while (!s.empty() && s.back() == ' ') s.pop_back();
        return s;
    }

    /// A coordinate in 1/`per_degree` degrees: mostly on the globe, sometimes "not available"
    /// (181 / 91) or off it.
    std::int64_t coordinate(double limit, double na, double per_degree, double& value) {
        const double r = std::uniform_real_distribution<double>(0, 1)(m_rng);
        std::int64_t raw;
        if (r < 0.1) raw = static_cast<std::int64_t>(na * per_degree);
        else if (r < 0.13) raw = static_cast<std::int64_t>((limit + 1 + pick(0, 5)) * per_degree) * (chance(0.5) ? 1 : -1);
        else raw = std::uniform_int_distribution<std::int64_t>(static_cast<std::int64_t>(-limit * per_degree),
                                                               static_cast<std::int64_t>(limit * per_degree))(m_rng);
        value = raw / per_degree;
        return raw;
    }

    void place(ais::Message& m, double lon, double lat) {
        if (std::fabs(lon) <= 180.0 && std::fabs(lat) <= 90.0) m.position = geo::LonLat{lon, lat};
    }

    void position_report(Encoder& e, ais::Message& m) {
        const bool class_a = m.type <= 3;
        if (class_a) {
            m.nav_status = static_cast<std::uint8_t>(pick(0, 15));
            e.put(m.nav_status, 4);
            e.put(pick(-128, 127), 8);  // rate of turn
        } else {
            e.put(pick(0, 255), 8);
        }
        const int sog = chance(0.1) ? 1023 : pick(0, 1022);
        m.sog_kn = sog == 1023 ? NAN : sog / 10.0;
        e.put(sog, 10);
        e.put(pick(0, 1), 1);
        double lon = 0, lat = 0;
        e.put(coordinate(180, 181, 600000.0, lon), 28);
        e.put(coordinate(90, 91, 600000.0, lat), 27);
        place(m, lon, lat);
        const int cog = chance(0.1) ? 3600 : chance(0.05) ? pick(3601, 4095) : pick(0, 3599);
        m.cog_deg = cog >= 3600 ? NAN : cog / 10.0;
        e.put(cog, 12);
        const int heading = chance(0.2) ? 511 : chance(0.05) ? pick(360, 510) : pick(0, 359);
        m.heading_deg = heading >= 360 ? NAN : heading;
        e.put(heading, 9);
        m.second = pick(0, 63);
        e.put(m.second, 6);
        if (m.type == 19) {
            e.put(pick(0, 15), 4);
            m.name = trimmed(name(20));
            e.text(m.name, 20);
            ship_static(e, m);
            e.put(pick(0, 15), 4);  // EPFD
            e.put(0, 7);            // RAIM, DTE, assigned, spare
        } else {
            while (e.size() < 168) e.put(pick(0, 1), 1);  // manoeuvre, RAIM, radio status, ...
        }
    }

    void long_range(Encoder& e, ais::Message& m) {
        e.put(pick(0, 1), 1);
        e.put(pick(0, 1), 1);
        m.nav_status = static_cast<std::uint8_t>(pick(0, 15));
        e.put(m.nav_status, 4);
        double lon = 0, lat = 0;
        e.put(coordinate(180, 181, 600.0, lon), 18);
        e.put(coordinate(90, 91, 600.0, lat), 17);
        place(m, lon, lat);
        const int sog = pick(0, 63), cog = chance(0.1) ? 511 : pick(0, 511);
        m.sog_kn = sog == 63 ? NAN : sog;
        m.cog_deg = cog >= 360 ? NAN : cog;
        e.put(sog, 6);
        e.put(cog, 9);
        e.put(pick(0, 1), 1);
        e.put(0, 1);
    }

    void dims(Encoder& e, ais::Message& m) {
        const int a = chance(0.15) ? 0 : pick(1, 511), b = chance(0.15) ? 0 : pick(1, 511);
        const int c = chance(0.15) ? 0 : pick(1, 63), d = chance(0.15) ? 0 : pick(1, 63);
        e.put(a, 9);
        e.put(b, 9);
        e.put(c, 6);
        e.put(d, 6);
        if (a > 0 && b > 0 && c > 0 && d > 0) m.dims = hull::Dimensions{double(a), double(b), double(c), double(d)};
    }

    void ship_static(Encoder& e, ais::Message& m) {
        m.ship_type = pick(0, 255);
        e.put(m.ship_type, 8);
        dims(e, m);
    }

    /// The sentences: one, or fragments of at most 60 characters with a sequence id (and, every
    /// other time, an NMEA 4.10 tag-block group in `lines` only: gpsdecode reads `plain`).
    void emit(const Encoder& e, std::string& lines, std::string& plain) {
        const auto [payload, fill] = e.armour();
        const std::size_t n = (payload.size() + 59) / 60;
        const int seq = m_seq++ % 10;
        const char channel = chance(0.5) ? 'A' : 'B';
        const bool group = chance(0.5);
        const int group_id = pick(1, 99999);
        for (std::size_t k = 0; k < n; ++k) {
            std::string body = "AIVDM," + std::to_string(n) + "," + std::to_string(k + 1) + "," + (n > 1 ? std::to_string(seq) : "") +
                               "," + channel + "," + payload.substr(k * 60, 60) + "," + std::to_string(k + 1 == n ? fill : 0);
            const std::string sentence = "!" + with_checksum(body);
            plain += sentence + "\n";
            if (n > 1 && group) {
                lines += "\\" + with_checksum("g:" + std::to_string(k + 1) + "-" + std::to_string(n) + "-" + std::to_string(group_id)) +
                         "\\" + sentence + "\n";
            } else {
                lines += sentence + "\n";
            }
        }
    }

    std::mt19937 m_rng;
    int m_seq = 0;
};

void expect_truth(const ais::Decoded& d, const Truth& t) {
    const ais::Message& m = d.message;
    const ais::Message& w = t.message;
    SCOPED_TRACE("line " + std::to_string(d.line) + " type " + std::to_string(w.type));
    ASSERT_EQ(m.type, w.type);
    EXPECT_EQ(m.mmsi, w.mmsi);
    EXPECT_EQ(m.part, w.part);
    EXPECT_EQ(m.position, w.position);
    EXPECT_SAME(m.sog_kn, w.sog_kn);
    EXPECT_SAME(m.cog_deg, w.cog_deg);
    EXPECT_SAME(m.heading_deg, w.heading_deg);
    EXPECT_EQ(m.nav_status, w.nav_status);
    if (w.type != 27 && w.is_position_report()) {
        EXPECT_EQ(m.second, w.second);
    }
    EXPECT_EQ(m.name, w.name);
    EXPECT_EQ(m.ship_type, w.ship_type);
    EXPECT_EQ(m.dims, w.dims);
    EXPECT_SAME(m.draught_m, w.draught_m);
}

TEST(AisDecoder, RandomMessagesDecodeAsBuiltAndAsGpsdAndLibaisDecodeThem) {
    REQUIRE_DECODERS();
    Generator gen(20240519);
    std::string lines, plain;
    std::vector<Truth> truth;
    for (int i = 0; i < 3000; ++i) truth.push_back(gen.next(lines, plain));
    std::vector<std::string> problems;
    const std::vector<ais::Decoded> ours = ais::decode_lines(lines, &problems);
    EXPECT_THAT(problems, testing::IsEmpty());
    ASSERT_EQ(ours.size(), truth.size());
    for (std::size_t i = 0; i < ours.size(); ++i) expect_truth(ours[i], truth[i]);
    // The same sentences without tag blocks, for gpsd and libais.
    const std::vector<ais::Decoded> untagged = ais::decode_lines(plain);
    ASSERT_EQ(untagged.size(), truth.size());
    const Comparison c = compare_with_decoders(plain);
    EXPECT_EQ(c.messages, truth.size());
    EXPECT_EQ(c.libais_refused, 0u);
}

}  // namespace
