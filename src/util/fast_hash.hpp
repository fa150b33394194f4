#pragma once
// XXH3 (64 bits) with the widest vector instructions this CPU has: AVX2 where the CPU has it
// (chosen once, at the first call), else SSE2 (x86-64's baseline) or the scalar code. The
// numbers are XXH3_64bits' whatever the instructions: the hash is defined apart from its
// implementation (tests/util/fast_hash_test.cpp compares them). Used for the grid file's
// checksum (an 11.8 MB grid: 11.6 M instructions with SSE2, 3.7 M with AVX2).
// (Debian's libxxhash.so has such a dispatch, XXH3_64bits_dispatch, but its static archive
// has not; shoal takes xxHash header-only, so that no program linking it loads one library
// more.)

#include <cstddef>
#include <cstdint>

namespace shoal::util {

/// XXH3_64bits(data, size), with the CPU's widest vectors.
std::uint64_t xxh3_64(const void* data, std::size_t size) noexcept;

namespace detail {
/// XXH3_64bits with the baseline's vectors (what the build targets by default).
std::uint64_t xxh3_64_baseline(const void* data, std::size_t size) noexcept;
/// Whether xxh3_64 uses AVX2 here (this build has it and the CPU has AVX2).
bool xxh3_uses_avx2() noexcept;
}  // namespace detail

}  // namespace shoal::util
