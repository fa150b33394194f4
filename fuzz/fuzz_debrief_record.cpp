// libFuzzer target: a shard's debrief record (report::parse_debrief_record, shoal merge --debrief). Built by scripts/fuzz.sh; the entry point
// is shared with tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::debrief_record(data, size);
    return 0;
}
