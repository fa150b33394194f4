// libFuzzer target: the files of check --partitions and --traffic-only (audit::read_partition, read_traffic). Built by scripts/fuzz.sh; the entry point
// is shared with tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::partitions(data, size);
    return 0;
}
