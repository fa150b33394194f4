#pragma once
/// The independent AIS decoders from Debian the tests compare shoal's with: gpsd's
/// `gpsdecode -j` (gpsd-clients) and libais (python3-ais, under Debian's python), and how to
/// run them and read their JSON lines.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace shoal::test {

inline const char* const gpsdecode_path = "/usr/bin/gpsdecode";
inline const char* const python_path = "/usr/bin/python3";

/// The standard output of `cmd` (a shell command line); a failure if it exits non-zero.
inline std::string run(const std::string& cmd) {
    std::string out;
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return out;
    char buf[1 << 14];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    const int status = ::pclose(p);
    if (status != 0) ADD_FAILURE() << cmd << " exited with status " << status;
    return out;
}

/// One JSON document per non-empty line (gpsdecode -j's and our libais script's output).
inline std::vector<nlohmann::json> json_lines(const std::string& text) {
    std::vector<nlohmann::json> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) out.push_back(nlohmann::json::parse(line));
    return out;
}

inline bool have_gpsdecode() { return std::filesystem::exists(gpsdecode_path); }
inline bool have_libais() {
    return std::filesystem::exists(python_path) && std::system("/usr/bin/python3 -c 'import ais' >/dev/null 2>&1") == 0;
}

}  // namespace shoal::test

/// Skips the test, saying what to install, when either decoder is missing.
#define REQUIRE_DECODERS()                                                                                                  \
    do {                                                                                                                    \
        if (!::shoal::test::have_gpsdecode())                                                                               \
            GTEST_SKIP() << ::shoal::test::gpsdecode_path << " is missing: install gpsd-clients (scripts/install-deps.sh)"; \
        if (!::shoal::test::have_libais()) GTEST_SKIP() << "libais is missing: install python3-ais (scripts/install-deps.sh)"; \
    } while (0)
