// libFuzzer target: the GPX track reader (OGR's GPX driver behind track::detail::read_gpx_at). Built by scripts/fuzz.sh; the entry point is shared with
// tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::gpx_tracks(data, size);
    return 0;
}
