#pragma once
/// What kind of build the tests run in.

namespace shoal::test {

/// True in a build under AddressSanitizer or ThreadSanitizer (GCC and Clang define these). The
/// few tests that run `shoal` hundreds of times, one code path per option or case with several
/// values on each, keep every path there but fewer values on each: a sanitizer finds a fault on
/// a path's first run, and the plain build still runs every value.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool under_sanitizer = true;
#else
inline constexpr bool under_sanitizer = false;
#endif

}  // namespace shoal::test
