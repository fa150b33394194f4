// Every input the fuzzers were seeded with (fuzz/corpus/) and every input that once broke a
// parser (fuzz/regressions/), run through the fuzz targets' own entry points in the normal
// build, so each regression stays a test without clang or libFuzzer. A target must return
// normally: InputError is the expected answer to bad input; a crash, an abort from a broken
// invariant or another exception fails here.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;

using Entry = void (*)(const std::uint8_t*, std::size_t);

struct Target {
    const char* name;
    Entry entry;
};

const Target targets[] = {
    {"csv_tracks", shoal::fuzz::csv_tracks},
    {"nmea", shoal::fuzz::nmea},
    {"aivdm", shoal::fuzz::aivdm},
    {"geojson_tracks", shoal::fuzz::geojson_tracks},
    {"gpx_tracks", shoal::fuzz::gpx_tracks},
    {"vessels", shoal::fuzz::vessels},
    {"ship", shoal::fuzz::ship},
    {"grid_cache", shoal::fuzz::grid_cache},
    {"roles", shoal::fuzz::roles},
    {"assessment", shoal::fuzz::assessment},
    {"poses", shoal::fuzz::poses},
    {"merge_parts", shoal::fuzz::merge_parts},
    {"zip_members", shoal::fuzz::zip_members},
    {"debrief_record", shoal::fuzz::debrief_record},
    {"partitions", shoal::fuzz::partitions},
};

std::vector<fs::path> inputs(const std::string& target, const char* kind) {
    std::vector<fs::path> out;
    const fs::path dir = fs::path(SHOAL_FUZZ_DIR) / kind / target;
    if (!fs::is_directory(dir)) return out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().filename().string().front() != '.') out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::uint8_t> bytes_of(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public testing::TestWithParam<Target> {};

TEST_P(FuzzReplay, EveryRegressionInputReturnsNormally) {
    const Target& t = GetParam();
    const auto regressions = inputs(t.name, "regressions");
    // Skipped, not passed, for a target that never broke (ctest lists it as skipped).
    if (regressions.empty()) GTEST_SKIP() << "fuzz/regressions/" << t.name << " holds no input";
    for (const fs::path& p : regressions) {
        SCOPED_TRACE(p.string());
        const auto b = bytes_of(p);
        EXPECT_NO_THROW(t.entry(b.data(), b.size()));
    }
}

TEST_P(FuzzReplay, EverySeedInputReturnsNormally) {
    const Target& t = GetParam();
    const auto seeds = inputs(t.name, "corpus");
    EXPECT_FALSE(seeds.empty()) << "fuzz/corpus/" << t.name << " has no seeds";
    for (const fs::path& p : seeds) {
        SCOPED_TRACE(p.string());
        const auto b = bytes_of(p);
        EXPECT_NO_THROW(t.entry(b.data(), b.size()));
    }
}

TEST_P(FuzzReplay, EmptyAndOneByteInputsReturnNormally) {
    const Target& t = GetParam();
    const std::uint8_t one[1] = {0xFF};
    EXPECT_NO_THROW(t.entry(one, 0));
    EXPECT_NO_THROW(t.entry(one, 1));
}

TEST(FuzzInputs, EveryFolderOfSavedInputsNamesATarget) {
    // An input saved under a misspelt or removed target's name would be replayed by nobody.
    std::size_t folders = 0;
    for (const char* kind : {"corpus", "regressions"})
        for (const auto& e : fs::directory_iterator(fs::path(SHOAL_FUZZ_DIR) / kind)) {
            if (!e.is_directory()) continue;
            ++folders;
            const std::string name = e.path().filename().string();
            const bool known = std::any_of(std::begin(targets), std::end(targets), [&](const Target& t) { return name == t.name; });
            EXPECT_TRUE(known) << "fuzz/" << kind << "/" << name << " is not a fuzz target's name";
        }
    EXPECT_GE(folders, std::size(targets)) << "every target has its seeds";
}

INSTANTIATE_TEST_SUITE_P(Fuzz, FuzzReplay, testing::ValuesIn(targets),
                         [](const testing::TestParamInfo<Target>& p) { return std::string(p.param.name); });

}  // namespace
