// A raw AIS log audits like the equivalent CSV (issue 19): three vessels of different size
// sail in the Solent; their voyages are written (a) as an !AIVDM log with NMEA 4.10 tag-block
// times, type 1 position reports and one type 5 (two sentences, a sequence id and a tag-block
// group) per vessel giving its A,B,C,D and draught, bit-packed by the tests' own encoder
// (track/ais_encoder.hpp), and (b) as a CSV of the same fixes (the AIS-quantised values) with
// A,B,C,D and draught columns. `shoal check` with a small default --dims must give the same
// events and the same hulls for both: the AIS log's hulls can only come from its type 5.
//
// The routes were laid out on tests/data/coast/uk_solent_land.geojson (GSHHG) with a script
// outside shoal (point in polygon, distance to the polygons' edges):
//  - the ferry sails due south along 1.30 W from mid-Solent (1.4 km from land) onto the Isle
//    of Wight at Cowes: its path crosses land, so it grounds whatever its hull;
//  - the coaster and the small boat head straight (bearing 218) for the island's north shore
//    west of Cowes, a straight shore there, arrive 30 m from it at 8 kn and turn away north-west
//    at 4 kn: the coaster's bow (45 m ahead of its reference point) reaches 15 m over the shore,
//    the boat's (9 m) stays 21 m off. With one hull for all (the default --dims), the events
//    differ: the test can tell a wrong hull.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "test_support.hpp"
#include "track/ais_encoder.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using shoal::test::data_path;
using shoal::test::Encoder;
using shoal::test::TempDir;
using shoal::test::with_checksum;

// ---------------------------------------------------------------------------------------------
// Running shoal

struct Outcome {
    int status = -1;
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Runs shoal with `args` (no shell), stdout and stderr into files in `dir`, the grid cache in `dir`.
Outcome shoal(const std::vector<std::string>& args, const fs::path& dir) {
    std::vector<std::string> argv{SHOAL_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, (dir / "stdout.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&files, 2, (dir / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> env_strings;
    for (char** e = environ; *e; ++e)
        if (std::string(*e).rfind("SHOAL_CACHE_DIR=", 0) != 0) env_strings.emplace_back(*e);
    env_strings.push_back("SHOAL_CACHE_DIR=" + (dir / "cache").string());
    std::vector<char*> cargs, env;
    for (auto& a : argv) cargs.push_back(a.data());
    cargs.push_back(nullptr);
    for (auto& e : env_strings) env.push_back(e.data());
    env.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv[0].c_str(), &files, nullptr, cargs.data(), env.data());
    posix_spawn_file_actions_destroy(&files);
    Outcome r;
    int st = 0;
    if (rc == 0 && ::waitpid(pid, &st, 0) == pid) r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    r.out = slurp(dir / "stdout.txt");
    r.err = slurp(dir / "stderr.txt");
    return r;
}

// ---------------------------------------------------------------------------------------------
// The voyages

/// 2024-05-01T10:00:00Z.
const std::int64_t t0 = [] {
    std::tm tm{};
    tm.tm_year = 2024 - 1900;
    tm.tm_mon = 4;
    tm.tm_mday = 1;
    tm.tm_hour = 10;
    return static_cast<std::int64_t>(::timegm(&tm));
}();

struct Waypoint {
    double lon, lat;
    double sog_kn;  ///< on the leg from here to the next waypoint
};

struct Vessel {
    std::uint32_t mmsi;
    std::string name;
    int a, b, c, d;
    int draught_dm;     ///< AIS draught, 1/10 m
    int ship_type;      ///< AIS ship and cargo type
    std::int64_t start;  ///< seconds after t0
    std::vector<Waypoint> route;
};

/// One position report as AIS carries it: the raw (quantised) fields.
struct Report {
    std::int64_t time;
    std::int64_t lon, lat;  ///< 1/10000 minute
    int sog;                ///< 1/10 kn
    int cog;                ///< 1/10 degree
    int heading;            ///< degrees
};

constexpr double per_degree = 600000.0;
constexpr double m_per_deg_lat = 111200.0;  // near 50.77 N (the fixes' speeds need only be about right)
const double m_per_deg_lon = 111320.0 * std::cos(50.77 * M_PI / 180.0);

std::vector<Vessel> vessels() {
    // P: 30 m off the Isle of Wight's north shore west of Cowes, on the bearing 218 from W.
    const Waypoint w{-1.26, 50.775, 8.0}, p{-1.2727674, 50.7646374, 4.0}, away{-1.2850, 50.7780, 0.0};
    return {
        {235100001, "SMALL ONE", 9, 3, 2, 2, 12, 37, 120, {w, p, away}},
        {235100002, "COASTER", 45, 15, 5, 5, 38, 70, 0, {w, p, away}},
        {235100003, "SOLENT FERRY", 150, 30, 14, 14, 65, 60, 60, {{-1.30, 50.795, 12.0}, {-1.30, 50.750, 0.0}}},
    };
}

/// The vessel's reports along its route, every 10-60 s (from `rng`), the last at its end.
std::vector<Report> sail(const Vessel& v, std::mt19937& rng) {
    std::vector<Report> out;
    std::uniform_int_distribution<int> interval(10, 60);
    std::int64_t t = t0 + v.start;
    double arrival_bearing = 0;
    for (std::size_t leg = 0; leg + 1 < v.route.size(); ++leg) {
        const Waypoint& from = v.route[leg];
        const Waypoint& to = v.route[leg + 1];
        const double dx = (to.lon - from.lon) * m_per_deg_lon, dy = (to.lat - from.lat) * m_per_deg_lat;
        const double length = std::hypot(dx, dy), speed = from.sog_kn * 1852.0 / 3600.0;
        double bearing = std::atan2(dx, dy) * 180.0 / M_PI;
        if (bearing < 0) bearing += 360.0;
        const bool last_leg = leg + 2 == v.route.size();
        for (double s = 0;;) {
            const double f = std::min(s / length, 1.0);
            Report r;
            r.time = t;
            r.lon = std::llround((from.lon + f * (to.lon - from.lon)) * per_degree);
            r.lat = std::llround((from.lat + f * (to.lat - from.lat)) * per_degree);
            // At a waypoint the vessel arrives bow first: the course, heading and speed it came with.
            const bool arriving = s == 0 && leg > 0;
            const double sog = arriving ? v.route[leg - 1].sog_kn : from.sog_kn, course = arriving ? arrival_bearing : bearing;
            r.sog = static_cast<int>(std::lround(sog * 10));
            r.cog = static_cast<int>(std::lround(course * 10)) % 3600;
            r.heading = static_cast<int>(std::lround(course + 3)) % 360;  // a little leeway
            out.push_back(r);
            if (f >= 1.0) break;
            const int dt = interval(rng);
            if (s + speed * dt >= length && !last_leg) {  // the next leg starts with a fix at its waypoint
                t += std::max<std::int64_t>(10, static_cast<std::int64_t>(std::ceil((length - s) / speed)));
                break;
            }
            s += speed * dt;
            t += dt;
        }
        arrival_bearing = bearing;
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// (a) the AIVDM log

/// Type 1 position report (ITU-R M.1371 table 45), status 0 (under way using engine).
std::string type1(std::uint32_t mmsi, const Report& r) {
    Encoder e;
    e.put(1, 6);
    e.put(0, 2);  // repeat
    e.put(mmsi, 30);
    e.put(0, 4);     // navigational status
    e.put(-128, 8);  // rate of turn: not available
    e.put(r.sog, 10);
    e.put(1, 1);  // position accuracy
    e.put(r.lon, 28);
    e.put(r.lat, 27);
    e.put(r.cog, 12);
    e.put(r.heading, 9);
    e.put(r.time % 60, 6);
    e.put(0, 2 + 3 + 1 + 19);  // manoeuvre, spare, RAIM, radio status
    EXPECT_EQ(e.size(), 168u);
    return e.armour().first;
}

/// Type 5 static and voyage data (table 72): 424 bits, two sentences.
std::pair<std::string, int> type5(const Vessel& v) {
    Encoder e;
    e.put(5, 6);
    e.put(0, 2);
    e.put(v.mmsi, 30);
    e.put(0, 2);        // AIS version
    e.put(9000000 + v.mmsi % 1000, 30);  // IMO number
    e.text("MCALL", 7);
    e.text(v.name, 20);
    e.put(v.ship_type, 8);
    e.put(v.a, 9);
    e.put(v.b, 9);
    e.put(v.c, 6);
    e.put(v.d, 6);
    e.put(1, 4);  // EPFD: GPS
    e.put(5, 4);  // ETA: May 1st, 18:00
    e.put(1, 5);
    e.put(18, 5);
    e.put(0, 6);
    e.put(v.draught_dm, 8);
    e.text("SOUTHAMPTON", 20);
    e.put(0, 2);  // DTE, spare
    EXPECT_EQ(e.size(), 424u);
    return e.armour();
}

std::string tag_block(const std::string& fields) { return "\\" + with_checksum(fields) + "\\"; }

std::string sentence(int count, int number, const std::string& seq, char channel, const std::string& payload, int fill) {
    return "!" + with_checksum("AIVDM," + std::to_string(count) + "," + std::to_string(number) + "," + seq + "," + channel + "," +
                               payload + "," + std::to_string(fill));
}

struct Line {
    std::int64_t time;
    int order;  ///< among lines of one time: the order written
    std::string text;
};

/// The log: every vessel's reports in time order, its type 5 before its first report or, when
/// `static_after` > 0, between its report `static_after` and the next.
std::string aivdm_log(const std::vector<Vessel>& fleet, const std::vector<std::vector<Report>>& reports, std::size_t static_after) {
    std::vector<Line> lines;
    int order = 0, seq = 0, group = 4100;
    for (std::size_t k = 0; k < fleet.size(); ++k) {
        const Vessel& v = fleet[k];
        const std::vector<Report>& rs = reports[k];
        const char channel = k % 2 ? 'B' : 'A';
        for (const Report& r : rs)
            lines.push_back({r.time, order++, tag_block("c:" + std::to_string(r.time)) + sentence(1, 1, "", channel, type1(v.mmsi, r), 0)});
        const std::int64_t at = static_after == 0 ? rs.front().time - 5 : rs.at(static_after - 1).time + 1;
        const auto [payload, fill] = type5(v);
        const std::string s = std::to_string(seq++ % 10), g = std::to_string(group++);
        lines.push_back({at, order++, tag_block("g:1-2-" + g + ",c:" + std::to_string(at)) + sentence(2, 1, s, channel, payload.substr(0, 60), 0)});
        lines.push_back({at, order++, tag_block("g:2-2-" + g) + sentence(2, 2, s, channel, payload.substr(60), fill)});
    }
    std::sort(lines.begin(), lines.end(), [](const Line& x, const Line& y) { return std::tie(x.time, x.order) < std::tie(y.time, y.order); });
    std::string out;
    for (const Line& l : lines) out += l.text + "\r\n";
    return out;
}

// ---------------------------------------------------------------------------------------------
// (b) the CSV

std::string iso(std::int64_t t) {
    const std::time_t tt = static_cast<std::time_t>(t);
    std::tm tm{};
    ::gmtime_r(&tt, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

/// The same fixes, each value the double the AIS decoding gives (raw / scale, printed to round
/// trip), with the vessel's name, status 0 and, when `with_dims`, its A,B,C,D, draught and ship type.
std::string csv(const std::vector<Vessel>& fleet, const std::vector<std::vector<Report>>& reports, bool with_dims) {
    struct Row {
        std::int64_t time;
        std::string text;
    };
    std::vector<Row> rows;
    for (std::size_t k = 0; k < fleet.size(); ++k) {
        const Vessel& v = fleet[k];
        for (const Report& r : reports[k]) {
            char buf[256];
            std::snprintf(buf, sizeof buf, "%u,%s,%s,%.17g,%.17g,%.17g,%.17g,%d,0", v.mmsi, v.name.c_str(), iso(r.time).c_str(),
                          r.lat / per_degree, r.lon / per_degree, r.sog / 10.0, r.cog / 10.0, r.heading);
            std::string row = buf;
            if (with_dims) {
                std::snprintf(buf, sizeof buf, ",%d,%d,%d,%d,%.17g,%d", v.a, v.b, v.c, v.d, v.draught_dm / 10.0, v.ship_type);
                row += buf;
            }
            rows.push_back({r.time, row + "\n"});
        }
    }
    std::stable_sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) { return x.time < y.time; });
    std::string out = "mmsi,name,timestamp,lat,lon,sog,cog,heading,nav_status";
    out += with_dims ? ",A,B,C,D,draught,shiptype\n" : "\n";
    for (const Row& r : rows) out += r.text;
    return out;
}

// ---------------------------------------------------------------------------------------------
// Comparing reports

/// "AIS dimensions 9,3,2,2 (A,B,C,D columns)" -> "AIS dimensions 9,3,2,2": the hull, not where it came from.
std::string hull_dims(const json& hull) {
    const std::string s = hull.get<std::string>();
    return s.substr(0, s.find(" ("));
}

/// The report's events, ordered by track, start and kind.
std::vector<json> events(const json& report) {
    std::vector<json> out(report.at("features").begin(), report.at("features").end());
    std::sort(out.begin(), out.end(), [](const json& x, const json& y) {
        const json& a = x.at("properties");
        const json& b = y.at("properties");
        return std::tie(a.at("track"), a.at("start"), a.at("kind")) < std::tie(b.at("track"), b.at("start"), b.at("kind"));
    });
    return out;
}

/// Same value: numbers to `tolerance`, anything else exactly.
void expect_same(const json& a, const json& b, double tolerance, const std::string& what) {
    if (a.is_number() && b.is_number()) {
        EXPECT_NEAR(a.get<double>(), b.get<double>(), tolerance) << what;
    } else {
        EXPECT_EQ(a, b) << what;
    }
}

/// Properties that name the input (its file, its line) or the hull's origin: compared apart.
bool about_the_input(const std::string& key) {
    return key == "file" || key == "fix_line" || key == "hull" || key == "draught_source" || key == "ship_type_source";
}

/// Every event of the AIS run is the CSV run's: kind, track, start, end, position (to 2e-7
/// degrees: the report has 7 decimals), every other field, and the hull's dimensions.
void expect_same_events(const json& ais, const json& csv) {
    const std::vector<json> x = events(ais), y = events(csv);
    ASSERT_EQ(x.size(), y.size()) << "events of the AIS run and of the CSV run";
    for (std::size_t i = 0; i < x.size(); ++i) {
        const json& p = x[i].at("properties");
        const json& q = y[i].at("properties");
        const std::string what = "event " + std::to_string(i) + ": " + p.dump() + "\nCSV: " + q.dump();
        EXPECT_EQ(p.at("kind"), q.at("kind")) << what;
        EXPECT_EQ(p.at("track"), q.at("track")) << what;
        EXPECT_EQ(p.at("start"), q.at("start")) << what;
        EXPECT_EQ(p.at("end"), q.at("end")) << what;
        const json& c = x[i].at("geometry").at("coordinates");
        const json& d = y[i].at("geometry").at("coordinates");
        EXPECT_NEAR(c.at(0).get<double>(), d.at(0).get<double>(), 2e-7) << what;  // one unit of the report's 7 decimals
        EXPECT_NEAR(c.at(1).get<double>(), d.at(1).get<double>(), 2e-7) << what;  // one unit of the report's 7 decimals
        EXPECT_NEAR(p.at("ship_lat").get<double>(), q.at("ship_lat").get<double>(), 2e-7) << what;  // one unit of the report's 7 decimals
        EXPECT_NEAR(p.at("ship_lon").get<double>(), q.at("ship_lon").get<double>(), 2e-7) << what;  // one unit of the report's 7 decimals
        EXPECT_EQ(hull_dims(p.at("hull")), hull_dims(q.at("hull"))) << what;
        for (const auto& [key, value] : p.items()) {
            if (about_the_input(key)) continue;
            ASSERT_TRUE(q.contains(key)) << key << ", " << what;
            expect_same(value, q.at(key), 1e-6, key + ", " + what);
        }
        EXPECT_EQ(p.size(), q.size()) << what;
    }
}

/// The report's tracks with fixes, by id.
std::map<std::string, json> tracks(const json& report) {
    std::map<std::string, json> out;
    for (const json& t : report.at("shoal").at("tracks"))
        if (t.at("fixes").get<int>() > 0) out[t.at("track").get<std::string>()] = t;
    return out;
}

void expect_same_tracks(const json& ais, const json& csv) {
    const auto x = tracks(ais), y = tracks(csv);
    ASSERT_EQ(x.size(), y.size());
    for (const auto& [id, t] : x) {
        ASSERT_TRUE(y.count(id)) << id;
        const json& u = y.at(id);
        EXPECT_EQ(hull_dims(t.at("hull")), hull_dims(u.at("hull"))) << id;
        for (const auto& [key, value] : t.items())
            if (!about_the_input(key)) expect_same(value, u.at(key), 1e-9, id + " " + key);
    }
}

/// Each event's track, kind, start and end.
std::vector<std::string> outline(const json& report) {
    std::vector<std::string> out;
    for (const json& e : events(report)) {
        const json& p = e.at("properties");
        out.push_back(p.at("track").get<std::string>() + " " + p.at("kind").get<std::string>() + " " + p.at("start").get<std::string>() +
                      " " + p.at("end").get<std::string>());
    }
    return out;
}

const Vessel& by_name(const std::vector<Vessel>& fleet, const std::string& name) {
    return *std::find_if(fleet.begin(), fleet.end(), [&](const Vessel& v) { return v.name == name; });
}

std::size_t count_kind(const json& report, const std::string& track, const std::string& kind) {
    std::size_t n = 0;
    for (const json& f : report.at("features"))
        if (f.at("properties").at("track") == track && f.at("properties").at("kind") == kind) ++n;
    return n;
}

// ---------------------------------------------------------------------------------------------

class AivdmAudit : public testing::Test {
protected:
    static void SetUpTestSuite() {
        s_dir = new TempDir;
        s_grid = s_dir->file("solent.shoalgrid");
        const Outcome o = shoal({"import", data_path("coast/uk_solent_land.geojson"), "--cell", "1000", "-o", s_grid}, s_dir->path());
        ASSERT_EQ(o.status, 0) << o.err;
    }
    static void TearDownTestSuite() {
        delete s_dir;
        s_dir = nullptr;
    }

    void SetUp() override {
        std::mt19937 rng(20240501);
        for (const Vessel& v : m_fleet) m_reports.push_back(sail(v, rng));
    }

    std::string file(const std::string& name, const std::string& text) const {
        const std::string p = m_dir.file(name);
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }

    /// `shoal check --dims 2,2,1,1` of `track`; the report.
    json check(const std::string& track, const std::string& name) const {
        const std::string report = m_dir.file(name + ".geojson");
        const Outcome o = shoal({"check", "--world", "simulated", "--coast", s_grid, "--dims", "2,2,1,1", "--jobs", "2", track, "-o", report}, m_dir.path());
        EXPECT_EQ(o.status, 1) << "a grounding found: exit status 1\n" << o.err;  // the ferry's, at least
        std::ifstream in(report);
        if (!in) {
            ADD_FAILURE() << "no report " << report << "\n" << o.err;
            return json::object({{"features", json::array()}, {"shoal", {{"tracks", json::array()}}}});
        }
        return json::parse(in);
    }

    /// The AIS log with its type 5 messages where `static_after` says, against the CSV.
    void expect_log_audits_as_csv(std::size_t static_after) {
        const json ais = check(file("voyages.nmea", aivdm_log(m_fleet, m_reports, static_after)), "ais");
        const json with_dims = check(file("voyages.csv", csv(m_fleet, m_reports, true)), "csv");
        expect_same_events(ais, with_dims);
        expect_same_tracks(ais, with_dims);

        // The hulls are each vessel's own, taken from its type 5 for the whole track.
        for (const Vessel& v : m_fleet) {
            const std::string id = std::to_string(v.mmsi);
            const auto t = tracks(ais);
            ASSERT_TRUE(t.count(id)) << id;
            const std::string dims =
                std::to_string(v.a) + "," + std::to_string(v.b) + "," + std::to_string(v.c) + "," + std::to_string(v.d);
            EXPECT_NE(t.at(id).at("hull").get<std::string>().find(dims), std::string::npos) << t.at(id).dump();
            EXPECT_NE(t.at(id).at("hull").get<std::string>().find("message 5"), std::string::npos) << t.at(id).dump();
            EXPECT_EQ(t.at(id).at("draught_m"), v.draught_dm / 10.0) << t.at(id).dump();
            EXPECT_EQ(t.at(id).at("fixes").get<std::size_t>(), m_reports[static_cast<std::size_t>(&v - m_fleet.data())].size());
            for (const json& f : ais.at("features"))
                if (f.at("properties").at("track") == id) {
                    EXPECT_EQ(f.at("properties").at("hull"), t.at(id).at("hull")) << f.dump();
                }
        }

        // What the geometry makes certain: the ferry's path crosses the Isle of Wight.
        EXPECT_GE(count_kind(ais, std::to_string(by_name(m_fleet, "SOLENT FERRY").mmsi), "grounding"), 1u);
        // And the comparison can tell hulls apart: the coaster's bow over the shore, the boat
        // 21 m off; with the small default hull for every vessel, the coaster stays clear.
        EXPECT_GE(count_kind(ais, std::to_string(by_name(m_fleet, "COASTER").mmsi), "grounding"), 1u);
        EXPECT_EQ(count_kind(ais, std::to_string(by_name(m_fleet, "SMALL ONE").mmsi), "grounding"), 0u);
        const json one_hull = check(file("voyages_no_dims.csv", csv(m_fleet, m_reports, false)), "one_hull");
        EXPECT_EQ(count_kind(one_hull, std::to_string(by_name(m_fleet, "COASTER").mmsi), "grounding"), 0u);
        EXPECT_NE(outline(one_hull), outline(with_dims));
    }

    static TempDir* s_dir;
    static std::string s_grid;
    TempDir m_dir;
    std::vector<Vessel> m_fleet = vessels();
    std::vector<std::vector<Report>> m_reports;
};

TempDir* AivdmAudit::s_dir = nullptr;
std::string AivdmAudit::s_grid;

TEST_F(AivdmAudit, TheVoyagesAsAisWithTheirStaticDataFirstAuditAsTheCsvWithEachHull) {
    for (const auto& r : m_reports) {  // every 10-60 s
        ASSERT_GE(r.size(), 10u);
        for (std::size_t i = 1; i < r.size(); ++i) {
            EXPECT_GE(r[i].time - r[i - 1].time, 10);
            EXPECT_LE(r[i].time - r[i - 1].time, 60);
        }
    }
    expect_log_audits_as_csv(0);
}

TEST_F(AivdmAudit, TheTypeFiveArrivingAfterSomeReportsStillGivesTheWholeTrackItsHull) {
    expect_log_audits_as_csv(4);
}

/// The tracks layer of a GeoPackage report: ship_type (null: -1), ship_type_text, ship_type_source by track.
std::map<std::string, std::tuple<int, std::string, std::string>> gpkg_ship_types(const std::string& path) {
    GDALAllRegister();
    std::map<std::string, std::tuple<int, std::string, std::string>> out;
    const GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    if (!ds) {
        ADD_FAILURE() << "cannot open " << path;
        return out;
    }
    OGRLayer* tracks = ds->GetLayerByName("tracks");
    if (!tracks) {
        ADD_FAILURE() << path << " has no tracks layer";
        return out;
    }
    for (const auto& f : *tracks) {
        const int type = f->GetFieldIndex("ship_type");
        EXPECT_GE(type, 0);
        EXPECT_EQ(f->GetDefnRef()->GetFieldDefn(type)->GetType(), OFTInteger64);
        const bool null_text = f->IsFieldNull(f->GetFieldIndex("ship_type_text"));
        out[f->GetFieldAsString("track")] = {f->IsFieldNull(type) ? -1 : f->GetFieldAsInteger(type),
                                             null_text ? "(null)" : f->GetFieldAsString("ship_type_text"),
                                             f->GetFieldAsString("ship_type_source")};
    }
    return out;
}

TEST_F(AivdmAudit, EachVesselsShipTypeFromItsTypeFiveIsReportedWithItsMeaningAndSourceInGeoJsonAndGeoPackage) {
    // The meanings after ITU-R M.1371 table 53, written out here.
    const std::map<int, std::string> meaning = {
        {37, "Pleasure craft"}, {70, "Cargo, all ships of this type"}, {60, "Passenger, all ships of this type"}};
    const std::string log = file("voyages.nmea", aivdm_log(m_fleet, m_reports, 0));
    const json ais = check(log, "ais");
    const std::string gpkg = m_dir.file("ais.gpkg");
    const Outcome o = shoal({"check", "--world", "simulated", "--coast", s_grid, "--dims", "2,2,1,1", log, "-o", gpkg}, m_dir.path());
    ASSERT_EQ(o.status, 1) << o.err;
    const auto in_gpkg = gpkg_ship_types(gpkg);
    const auto t = tracks(ais);
    for (const Vessel& v : m_fleet) {
        const std::string id = std::to_string(v.mmsi);
        ASSERT_TRUE(t.count(id)) << id;
        const json& j = t.at(id);
        EXPECT_EQ(j.at("ship_type"), v.ship_type) << j.dump();
        EXPECT_EQ(j.at("ship_type_text"), meaning.at(v.ship_type)) << j.dump();
        EXPECT_EQ(j.at("ship_type_source"), "AIS static data (message 5)") << j.dump();
        ASSERT_TRUE(in_gpkg.count(id)) << id;
        EXPECT_EQ(in_gpkg.at(id), std::make_tuple(v.ship_type, meaning.at(v.ship_type), std::string("AIS static data (message 5)")));
    }
    EXPECT_EQ(by_name(m_fleet, "COASTER").ship_type, 70);

    // The same from a CSV's ship type column; a CSV without one: not known (null, null, "").
    const auto with_type = tracks(check(file("voyages.csv", csv(m_fleet, m_reports, true)), "csv"));
    const auto without = tracks(check(file("voyages_no_dims.csv", csv(m_fleet, m_reports, false)), "no_dims"));
    for (const Vessel& v : m_fleet) {
        const std::string id = std::to_string(v.mmsi);
        EXPECT_EQ(with_type.at(id).at("ship_type"), v.ship_type);
        EXPECT_EQ(with_type.at(id).at("ship_type_source"), "ship type column");
        EXPECT_TRUE(without.at(id).at("ship_type").is_null()) << without.at(id).dump();
        EXPECT_TRUE(without.at(id).at("ship_type_text").is_null()) << without.at(id).dump();
        EXPECT_EQ(without.at(id).at("ship_type_source"), "");
    }
}

}  // namespace
