// util::xxh3_64 (AVX2 when the CPU has it) against xxHash's own XXH3_64bits compiled here (the
// build's baseline): the same numbers on buffers of every size up to 4 KiB and beyond its
// stripes and blocks, at five alignments, of random bytes.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "util/fast_hash.hpp"

namespace {

TEST(FastHash, EqualsXxh3OnEverySizeAndAlignment) {
    std::mt19937_64 rng(7);
    std::vector<unsigned char> buf((1u << 20) + 64);
    for (unsigned char& c : buf) c = static_cast<unsigned char>(rng());
    std::vector<std::size_t> sizes;
    for (std::size_t n = 0; n <= 4096; ++n) sizes.push_back(n);
    for (std::size_t n : {8191u, 8192u, 8193u, 65535u, 100003u, 1u << 20}) sizes.push_back(n);
    int checked = 0;
    for (std::size_t n : sizes)
        for (std::size_t off : {0u, 1u, 3u, 8u, 13u}) {
            const void* p = buf.data() + off;
            const std::uint64_t want = XXH3_64bits(p, n);
            ASSERT_EQ(shoal::util::xxh3_64(p, n), want) << n << " bytes at offset " << off;
            ASSERT_EQ(shoal::util::detail::xxh3_64_baseline(p, n), want) << n << " bytes at offset " << off;
            ++checked;
        }
    // xxHash's own test vector: the empty input.
    EXPECT_EQ(shoal::util::xxh3_64("", 0), 0x2D06800538D394C2ULL);
    std::printf("%d buffers; AVX2 %s\n", checked, shoal::util::detail::xxh3_uses_avx2() ? "used" : "not used (the CPU or the build has none)");
}

}  // namespace
