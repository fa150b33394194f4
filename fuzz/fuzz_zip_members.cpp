// libFuzzer target: zip files read as folders (detail::zip_members, zip_entry_names reading the central directory). Built by
// scripts/fuzz.sh; the entry point is shared with tests/fuzz_replay_test.cpp.

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shoal::fuzz::zip_members(data, size);
    return 0;
}
