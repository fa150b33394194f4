// libFuzzer target: AIS sentences (AIVDM/AIVDO), the line decoder and the tracks the NMEA
// reader makes of them. Built by scripts/fuzz.sh; the entry point is shared with
// tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::aivdm(data, size);
    return 0;
}
