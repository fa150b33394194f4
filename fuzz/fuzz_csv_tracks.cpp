// libFuzzer target: the CSV track reader (every dialect: separators, layouts, quoting, BOM, CRLF, Latin-1).
// Built by scripts/fuzz.sh; the entry point is shared with tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::csv_tracks(data, size);
    return 0;
}
