// Shards of a run: the key, the hash (XXH3, checked against its published value), the "I/N" text.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include <shoal/audit/shard.hpp>
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
