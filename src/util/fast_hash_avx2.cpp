// XXH3_64bits compiled for AVX2 (this file only: -mavx2), called by util::xxh3_64 only when
// the CPU has AVX2. Nothing else is compiled here: no template or inline function of a
// library header that another file could share (an AVX2 copy of it could be the one linked).
#include <cstddef>
#include <cstdint>

#define XXH_INLINE_ALL
#define XXH_VECTOR XXH_AVX2
#include <xxhash.h>

namespace shoal::util::detail {

std::uint64_t xxh3_64_avx2(const void* data, std::size_t size) noexcept { return XXH3_64bits(data, size); }

}  // namespace shoal::util::detail
