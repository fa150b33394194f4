// Tests of audit.hpp: tracks audited in memory (audit_tracks) give what the same tracks give
// read from their file (run_audit), and the batch keeps going past a bad file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/sweep/evidence.hpp>
#include "track/merge.hpp"
#include <shoal/track/packed_track.hpp>
#include <shoal/track/reader.hpp>

#include "audit/solent_grid.hpp"
#include "test_support.hpp"

namespace {

using namespace shoal;
using namespace shoal::test;

/// Vessel 1 sails south across the Isle of Wight (it grounds); vessel 2 stays in open water
/// east of it (the Solent, from tests/data/coast/uk_solent_land.geojson).
std::string solent_csv() {
    std::string s = "mmsi,timestamp,lat,lon,sog,cog,heading\n";
    char buf[160];
    for (int i = 0; i <= 20; ++i) {
        std::snprintf(buf, sizeof buf, "111111111,2024-05-01T10:%02d:00Z,%.4f,-1.3000,11.9,180,511\n", i, 50.78 - 0.01 * i);
        s += buf;
    }
    for (int i = 0; i <= 10; ++i) {
        std::snprintf(buf, sizeof buf, "222222222,2024-05-01T10:%02d:00Z,50.7400,%.4f,11.9,90,511\n", i, -1.05 + 0.002 * i);
        s += buf;
    }
    return s;
}

class Audit : public ::testing::Test {
protected:
    static void SetUpTestSuite() { s_grid = &test::solent_grid(); }
    static const grid::CoastGrid* s_grid;
    TempDir m_dir;
    const hull::Hull m_hull = hull::Hull::from_dimensions({50, 10, 5, 5});
};
const grid::CoastGrid* Audit::s_grid = nullptr;

TEST_F(Audit, TracksInMemoryAuditAsTheirFile) {
    const std::string csv = m_dir.file("solent.csv");
    write_bytes(csv, [] { const std::string s = solent_csv(); return std::vector<char>(s.begin(), s.end()); }());
    audit::AuditOptions options;
    options.jobs = 2;
    const audit::AuditResult from_file = audit::run_audit({csv}, *s_grid, m_hull, "test hull", options);
    const audit::AuditResult in_memory =
        audit::audit_tracks(track::read_tracks(csv).tracks, *s_grid, m_hull, "test hull", options);

    ASSERT_EQ(from_file.tracks.size(), 2u);
    ASSERT_EQ(in_memory.tracks.size(), 2u);
    EXPECT_EQ(from_file.groundings, 1u);
    EXPECT_EQ(in_memory.groundings, from_file.groundings);
    EXPECT_EQ(in_memory.fixes, from_file.fixes);
    EXPECT_EQ(in_memory.poses, from_file.poses);
    for (std::size_t k = 0; k < 2; ++k) {
        const auto& a = from_file.tracks[k];
        const auto& b = in_memory.tracks[k];
        EXPECT_EQ(a.summary.id, b.summary.id);
        ASSERT_EQ(a.events.size(), b.events.size());
        for (std::size_t e = 0; e < a.events.size(); ++e) {
            EXPECT_EQ(a.events[e].kind, b.events[e].kind);
            EXPECT_EQ(a.events[e].start_s, b.events[e].start_s);
            EXPECT_EQ(a.events[e].end_s, b.events[e].end_s);
        }
    }
    EXPECT_TRUE(in_memory.files.empty());  // nothing was read
    ASSERT_EQ(from_file.files.size(), 1u);
    EXPECT_EQ(from_file.files[0].tracks, 2u);
}

TEST_F(Audit, ABadFileCostsThatFileOnly) {
    const std::string good = m_dir.file("good.csv"), bad = m_dir.file("bad.csv");
    const std::string text = solent_csv();
    write_bytes(good, std::vector<char>(text.begin(), text.end()));
    write_bytes(bad, {'x', '\n'});
    const audit::AuditResult r = audit::run_audit({bad, good}, *s_grid, m_hull, "test hull", {});
    ASSERT_EQ(r.files.size(), 2u);
    EXPECT_THAT(r.files[0].error, ::testing::HasSubstr("bad.csv"));
    EXPECT_TRUE(r.files[1].error.empty());
    EXPECT_EQ(r.tracks.size(), 2u);
    EXPECT_EQ(r.groundings, 1u);
}

/// A random track over the Solent: legs under way (some over the Isle of Wight's land), stays
/// (moored, aground or not said), GPS jitter, gaps, wild fixes, fixes with and without SOG,
/// COG and heading.
track::Track random_solent_track(std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> u(0, 1);
    track::Track t;
    t.id = std::to_string(230000000 + static_cast<int>(u(rng) * 1e5));
    double lat = 50.62 + 0.25 * u(rng), lon = -1.55 + 0.6 * u(rng), time = 1714550400;
    double course = 360 * u(rng), speed_kn = 12;
    int stay_left = 0;
    std::uint8_t status = track::nav_status_unknown;
    for (int i = 0; i < n; ++i) {
        const double r = u(rng);
        time += r < 0.01 ? 1200 + 3600 * u(rng) : 5 + 25 * u(rng);  // now and then a gap
        if (stay_left == 0 && u(rng) < 0.01) {
            stay_left = 20 + static_cast<int>(200 * u(rng));
            const double s = u(rng);
            status = s < 0.3 ? track::nav_status_moored : s < 0.4 ? track::nav_status_aground : track::nav_status_unknown;
        }
        track::Fix f;
        f.time_s = time;
        f.line = static_cast<std::size_t>(i + 2);
        if (stay_left > 0) {
            --stay_left;
            f.position = {lon + 2e-5 * (u(rng) - 0.5), lat + 2e-5 * (u(rng) - 0.5)};  // jitter of a metre or two
            f.nav_status = status;
            if (u(rng) < 0.5) f.sog_kn = 0.1 * u(rng);
        } else {
            if (u(rng) < 0.02) course = 360 * u(rng);
            speed_kn = std::clamp(speed_kn + u(rng) - 0.5, 0.0, 25.0);
            const double dt = 10, d_m = speed_kn * 1852.0 / 3600.0 * dt;
            lat += d_m * std::cos(course * M_PI / 180) / 111320.0;
            lon += d_m * std::sin(course * M_PI / 180) / (111320.0 * std::cos(lat * M_PI / 180));
            f.position = {lon, lat};
            if (u(rng) < 0.7) f.sog_kn = speed_kn;
            if (u(rng) < 0.6) f.cog_deg = course;
        }
        if (u(rng) < 0.4) f.heading_deg = course;
        if (u(rng) < 0.005) f.position = {f.position.lon + 0.3 * (u(rng) - 0.5), f.position.lat + 0.3 * (u(rng) - 0.5)};  // a wild fix
        t.fixes.push_back(f);
    }
    if (u(rng) < 0.5) t.dims = hull::Dimensions{100 * u(rng) + 10, 50 * u(rng) + 5, 8, 8};
    return t;
}

TEST_F(Audit, TrafficFromTheLightPreparationIsTheFullPreparations) {
    // prepare_traffic (no headings) must give every track the traffic prepare_track gives it:
    // the stays, the fixes over land, the cadence, read by the traffic of other partitions.
    std::mt19937 rng(39);
    const geo::LocalFrame frame(s_grid->frame());
    std::size_t stays = 0, over_land = 0, headings_differ = 0, wild = 0;
    for (audit::World world : {audit::World::real, audit::World::simulated})
        for (int k = 0; k < 60; ++k) {
            track::Track full = random_solent_track(rng, 200 + static_cast<int>(rng() % 3000));
            track::Track light = full;
            audit::AuditOptions options;
            options.world = world;
            wild += audit::prepare_track(full, options).size();
            audit::prepare_traffic(light, options);
            ASSERT_EQ(full.fixes.size(), light.fixes.size());
            for (std::size_t i = 0; i < full.fixes.size(); ++i)
                headings_differ += !(full.fixes[i].heading_used_deg == light.fixes[i].heading_used_deg);
            const double length = full.dims ? full.dims->a + full.dims->b : 60;
            const audit::TrackResult a = audit::traffic_of(full, length, frame, *s_grid, options.sweep, options.evidence);
            const audit::TrackResult b = audit::traffic_of(light, length, frame, *s_grid, options.sweep, options.evidence);
            ASSERT_EQ(a.stays.size(), b.stays.size()) << "track " << k;
            for (std::size_t s = 0; s < a.stays.size(); ++s) {
                EXPECT_EQ(a.stays[s].first, b.stays[s].first);
                EXPECT_EQ(a.stays[s].last, b.stays[s].last);
                EXPECT_EQ(a.stays[s].start_s, b.stays[s].start_s);
                EXPECT_EQ(a.stays[s].end_s, b.stays[s].end_s);
                EXPECT_EQ(a.stays[s].local.x, b.stays[s].local.x);
                EXPECT_EQ(a.stays[s].local.y, b.stays[s].local.y);
                EXPECT_EQ(a.stays[s].moored, b.stays[s].moored);
                EXPECT_EQ(a.stays[s].aground, b.stays[s].aground);
                EXPECT_EQ(a.stays[s].visit, b.stays[s].visit);
            }
            ASSERT_EQ(a.over_land.size(), b.over_land.size()) << "track " << k;
            for (std::size_t i = 0; i < a.over_land.size(); ++i) {
                EXPECT_EQ(a.over_land[i].x, b.over_land[i].x);
                EXPECT_EQ(a.over_land[i].y, b.over_land[i].y);
            }
            EXPECT_EQ(a.summary.cadence_s, b.summary.cadence_s);
            EXPECT_EQ(a.summary.hull_length_m, b.summary.hull_length_m);
            stays += a.stays.size();
            over_land += a.over_land.size();
        }
    // The tracks hold what the traffic is made of, and what the light preparation leaves out.
    EXPECT_GT(stays, 100u);
    EXPECT_GT(over_land, 1000u);
    EXPECT_GT(wild, 10u);
    EXPECT_GT(headings_differ, 10000u) << "the light preparation resolves no heading";
}

TEST(MergeSameVessels, PackedMergeIsTheTracksConcatenatedAndNormalised) {
    // One vessel in several files: merged packed, in place, it must be the unpacked tracks
    // concatenated and normalised (sorted by time, repeated times kept once, filled from the
    // repeats), the answer computed here from the unpacked fixes.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int round = 0; round < 40; ++round) {
        std::vector<track::PackedTrack> tracks;
        std::vector<track::Track> plain;
        const int files = 2 + static_cast<int>(rng() % 5);
        double time = 1714550400;
        for (int f = 0; f < files; ++f)
            for (const char* id : {"230000001", "230000002", "BUOY"}) {
                track::Track t;
                t.id = id;
                t.file = "day" + std::to_string(f) + ".csv";
                if (f == 1 && std::string(id) == "230000001") t.name = "SECOND";
                const int n = static_cast<int>(rng() % 400);
                for (int i = 0; i < n; ++i) {
                    track::Fix x;
                    // Mostly in order; now and then back in time, or a time given twice.
                    time += u(rng) < 0.05 ? -100 * u(rng) : u(rng) < 0.05 ? 0 : 10;
                    x.time_s = time;
                    x.position = {-1.2 + 0.001 * i, u(rng) < 0.1 ? 50.7 + 1e-9 * i : 50.7 + 1e-4 * (i % 7)};  // some beyond 7 decimals
                    if (u(rng) < 0.7) x.sog_kn = std::round(100 * 12 * u(rng)) / 100;
                    if (u(rng) < 0.5) x.heading_deg = u(rng) < 0.1 ? 123.456789 : 90;
                    if (u(rng) < 0.5) x.cog_deg = 91;
                    x.line = static_cast<std::size_t>(i + 2);
                    t.fixes.push_back(x);
                }
                plain.push_back(t);
                tracks.push_back(track::PackedTrack::pack(std::move(t)));
            }
        std::vector<track::PackedTrack> merged_tracks;
        for (const auto& t : tracks) {
            merged_tracks.push_back(track::PackedTrack::pack(t.unpack()));
            merged_tracks.back().file = t.file;
        }
        const std::vector<std::string> messages = track::merge_same_vessels(merged_tracks, {});
        ASSERT_EQ(merged_tracks.size(), 2u + static_cast<std::size_t>(files)) << "two vessels merged, the non-MMSI id kept per file";
        EXPECT_EQ(messages.size(), 2u);
        for (const char* id : {"230000001", "230000002"}) {
            track::Track answer;
            answer.file = "x";
            for (const auto& t : plain)
                if (t.id == id) answer.fixes.insert(answer.fixes.end(), t.fixes.begin(), t.fixes.end());
            track::ReadReport report;
            track::normalise(answer, report);
            const auto it = std::find_if(merged_tracks.begin(), merged_tracks.end(), [&](const auto& t) { return t.id == id; });
            ASSERT_NE(it, merged_tracks.end());
            const track::Track got = it->unpack();
            std::string files_named = "day0.csv";
            for (int f = 1; f < files; ++f) files_named += " + day" + std::to_string(f) + ".csv";
            EXPECT_EQ(got.file, files_named);
            if (std::string(id) == "230000001") {
                EXPECT_EQ(got.name, "SECOND") << "the name from the first file that has one";
            }
            ASSERT_EQ(got.fixes.size(), answer.fixes.size()) << id << " round " << round;
            for (std::size_t i = 0; i < got.fixes.size(); ++i) {
                const track::Fix &g = got.fixes[i], &a = answer.fixes[i];
                ASSERT_EQ(g.time_s, a.time_s) << i;
                EXPECT_EQ(g.position, a.position) << i;
                EXPECT_EQ(g.line, a.line) << i;
                EXPECT_TRUE(g.sog_kn == a.sog_kn || (std::isnan(g.sog_kn) && std::isnan(a.sog_kn))) << i;
                EXPECT_TRUE(g.heading_deg == a.heading_deg || (std::isnan(g.heading_deg) && std::isnan(a.heading_deg))) << i;
                EXPECT_TRUE(g.cog_deg == a.cog_deg || (std::isnan(g.cog_deg) && std::isnan(a.cog_deg))) << i;
            }
        }
    }
}

}  // namespace
