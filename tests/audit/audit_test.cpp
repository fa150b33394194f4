// Tests of audit.hpp: tracks audited in memory (audit_tracks) give what the same tracks give
// read from their file (run_audit), and the batch keeps going past a bad file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>

#include <shoal/audit/audit.hpp>
#include <shoal/grid/grid_cache.hpp>
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

}  // namespace
