// libFuzzer target: shards' reports merged (report::merge_geojson, shoal merge). Built by scripts/fuzz.sh; the entry point
// is shared with tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::merge_parts(data, size);
    return 0;
}
