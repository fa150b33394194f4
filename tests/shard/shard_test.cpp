// Shards of a run: the key, the hash (XXH3, checked against its published value), the "I/N" text.
#include <gtest/gtest.h>

#include <unistd.h>

#include <random>
#include <string>

#include <shoal/shard/shard.hpp>
#include <shoal/util/error.hpp>

namespace shoal::audit {

TEST(Shard, HashIsXxh3OfTheKeyBytes) {
    // XXH3_64bits of no bytes is 0x2D06800538D394C2 (the xxHash reference): 3244421341483603138, mod 7 = 4, mod 5 = 3.
    EXPECT_EQ(0x2D06800538D394C2ull % 5, 3u);
    EXPECT_EQ(shard_of("", 7), 4u);
    EXPECT_EQ(shard_of("", 5), 3u);
    EXPECT_EQ(shard_of("anything", 1), 0u);
}

TEST(Shard, TracksSpreadEvenlyAndStayPut) {
    std::mt19937 rng(16);
    std::uniform_int_distribution<int> mmsi(200000000, 799999999);
    for (unsigned n : {2u, 3u, 8u}) {
        std::vector<int> per(n, 0);
        for (int i = 0; i < 8000; ++i) {
            const std::string id = std::to_string(mmsi(rng));
            const unsigned s = shard_of(shard_key(id, std::nullopt), n);
            ASSERT_LT(s, n);
            EXPECT_EQ(s, shard_of(id, n)) << "the same id, the same shard";
            ++per[s];
        }
        for (unsigned s = 0; s < n; ++s) {
            EXPECT_GT(per[s], 8000 / static_cast<int>(n) * 8 / 10) << "shard " << s << " of " << n;
            EXPECT_LT(per[s], 8000 / static_cast<int>(n) * 12 / 10) << "shard " << s << " of " << n;
        }
    }
}

TEST(Shard, AnExerciseIsOneShard) {
    EXPECT_EQ(shard_key("230990001", std::string("day1/ex1.csv")), shard_key("230990002", std::string("day1/ex1.csv")));
    EXPECT_EQ(shard_key("230990001", std::nullopt), "230990001");
}

TEST(Shard, TextIsParsedAndBadTextIsNamed) {
    const Shard s = parse_shard("2/5");
    EXPECT_EQ(s.index, 2u);
    EXPECT_EQ(s.count, 5u);
    EXPECT_EQ(s.text(), "2/5");
    EXPECT_EQ(Shard{}.text(), "");
    for (const char* bad : {"3/3", "1", "a/2", "-1/2", "0/0", "1/", "/2", "1/2/3", " 1/2", "0x1/2", "99999999/100000000"}) {
        try {
            parse_shard(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("AuditOptions::shard '" + std::string(bad) + "'"), std::string::npos) << e.what();
        }
    }
}

}  // namespace shoal::audit

// Partitions (audit/partition.hpp): every partition read back, together, is what one run reads.
#include <filesystem>
#include <fstream>

#include <shoal/audit/partition.hpp>

namespace shoal::audit {

TEST(Partition, PartitionsTogetherAreWhatOneRunReads) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("shoal-partition-test-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    // Two "days": vessels 230000001..6 in both (one crossing midnight), a non-MMSI id in both
    // (two tracks, as one run keeps them), a bad row in day 2, line 4.
    const std::string header = "mmsi,time,lat,lon,sog,cog\n";
    std::vector<std::string> days = {(dir / "day1.csv").string(), (dir / "day2.csv").string()};
    {
        std::ofstream a(days[0]), b(days[1]);
        a << header;
        b << header;
        for (int k = 0; k < 20; ++k)
            for (int v = 1; v <= 6; ++v) {
                a << "23000000" << v << ",2024-05-01T23:" << 10 + k << ":00Z," << 60 + v * 0.01 << "," << 25 + k * 0.001 << ",5,90\n";
                b << "23000000" << v << ",2024-05-02T00:" << 10 + k << ":00Z," << 60 + v * 0.01 << "," << 25.5 + k * 0.001 << ",5,90\n";
                if (k == 0 && v == 1) b << "230000001,not a time,60,25,5,90\n";
            }
        a << "BUOY,2024-05-01T23:00:00Z,60.5,25.5,0,0\n";
        b << "BUOY,2024-05-02T00:00:00Z,60.5,25.5,0,0\n";
    }
    const auto fingerprint = [](const FileResult&) { return std::pair<long long, std::string>{42, "f"}; };
    const unsigned count = 3;
    std::vector<std::string> folders;
    for (std::size_t d = 0; d < days.size(); ++d) {
        folders.push_back((dir / ("in-" + std::to_string(d))).string());
        write_partitions(folders.back(), days[d], {}, count, 1, fingerprint);
    }
    EXPECT_THROW(write_partitions(folders[0], days[0], {}, count, 1, fingerprint), InputError) << "an existing folder is never replaced";
    const ReadResult one = read_inputs(days, {}, 1);  // one run's read: the answer
    ASSERT_EQ(one.tracks.size(), 8u) << "6 vessels merged across the days, BUOY twice";
    ASSERT_EQ(one.files.size(), 2u);
    ASSERT_EQ(one.files[1].read.skipped, 1u) << "the bad row of day 2";
    ASSERT_EQ(one.files[1].read.messages.size(), 1u);
    std::vector<int> seen(one.tracks.size(), 0);
    for (unsigned p = 0; p < count; ++p) {
        std::vector<std::size_t> positions;
        std::vector<std::string> ids;
        const ReadResult part = read_partition(folders, days, {}, Shard{p, count}, positions, &ids);
        EXPECT_EQ(ids.size(), 14u) << "every track of every file (7 per day)";
        ASSERT_EQ(part.files.size(), one.files.size());
        for (std::size_t f = 0; f < one.files.size(); ++f) {
            EXPECT_EQ(part.files[f].file, one.files[f].file);
            EXPECT_EQ(part.files[f].read.messages, one.files[f].read.messages) << "the bad row kept with its file and line";
            EXPECT_EQ(part.files[f].read.skipped, one.files[f].read.skipped);
            EXPECT_EQ(part.files[f].fingerprint, "f");
        }
        ASSERT_EQ(positions.size(), part.tracks.size());
        for (std::size_t k = 0; k < part.tracks.size(); ++k) {
            ASSERT_LT(positions[k], one.tracks.size());
            const track::PackedTrack& a = part.tracks[k];
            const track::PackedTrack& b = one.tracks[positions[k]];
            EXPECT_EQ(a.id, b.id);
            EXPECT_EQ(shard_of(a.id, count), p) << "a vessel in its own partition";
            EXPECT_EQ(a.file, b.file);
            ASSERT_EQ(a.size(), b.size()) << a.id;
            for (std::size_t i = 0; i < a.size(); ++i) {
                EXPECT_EQ(a.fix(i).time_s, b.fix(i).time_s);
                EXPECT_EQ(a.fix(i).line, b.fix(i).line);
                EXPECT_EQ(a.fix(i).position.lon, b.fix(i).position.lon);
            }
            ++seen[positions[k]];
        }
    }
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "track " << k << " in exactly one partition";
    std::vector<std::size_t> positions;
    EXPECT_THROW(read_partition({folders[1], folders[0]}, days, {}, Shard{0, count}, positions), InputError) << "inputs out of order";
    EXPECT_THROW(read_partition(folders, days, {}, Shard{0, 4}, positions), InputError) << "another count";
    {  // read with other options than the run's: the first that differs named
        track::ReadOptions dated;
        dated.date_s = 1714521600;  // 2024-05-01
        try {
            read_partition(folders, days, dated, Shard{0, count}, positions);
            ADD_FAILURE() << "partitions read without a date audited with one";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(": the partitions were read with ReadOptions::date_s none, this run asks ReadOptions::date_s 2024-05-01"),
                      std::string::npos)
                << e.what();
        }
        track::ReadOptions lw;
        lw.hull_from_length_width = true;
        EXPECT_THROW(read_partition(folders, days, lw, Shard{0, count}, positions), InputError);
    }
    {  // a partition file cut short
        const fs::path part = fs::path(folders[0]) / "part-00001.bin";
        fs::resize_file(part, fs::file_size(part) - 5);
        EXPECT_THROW(read_partition(folders, days, {}, Shard{1, count}, positions), InputError);
    }
    fs::remove_all(dir);
}

}  // namespace shoal::audit
