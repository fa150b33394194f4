// XXH3 with the CPU's widest vectors (util/fast_hash.hpp): the baseline here, AVX2 in
// fast_hash_avx2.cpp (compiled with -mavx2, called only when the CPU has it).
#include "util/fast_hash.hpp"

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace shoal::util {

#if defined(SHOAL_HAVE_AVX2_XXH3)
namespace detail {
std::uint64_t xxh3_64_avx2(const void* data, std::size_t size) noexcept;  // fast_hash_avx2.cpp
}
#endif

std::uint64_t detail::xxh3_64_baseline(const void* data, std::size_t size) noexcept { return XXH3_64bits(data, size); }

bool detail::xxh3_uses_avx2() noexcept {
#if defined(SHOAL_HAVE_AVX2_XXH3)
    static const bool avx2 = [] {
        __builtin_cpu_init();  // (needed when first asked before main, from a static initialiser)
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return avx2;
#else
    return false;
#endif
}

std::uint64_t xxh3_64(const void* data, std::size_t size) noexcept {
#if defined(SHOAL_HAVE_AVX2_XXH3)
    if (detail::xxh3_uses_avx2()) return detail::xxh3_64_avx2(data, size);
#endif
    return XXH3_64bits(data, size);
}

}  // namespace shoal::util
