#pragma once
/// Running the `shoal` executable (SHOAL_BINARY) from a test through the shell: the caller
/// quotes `args`; the grid cache goes to `cache_dir`, standard error through `err_file`; the
/// command runs in folder `cwd` when one is given.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace shoal::test {

struct Outcome {
    int status = -1;  ///< the exit status; -1 when the process did not exit (a signal)
    std::string out, err;
};

inline Outcome run_shoal(const std::string& args, const std::filesystem::path& cache_dir, const std::filesystem::path& err_file,
                         const std::filesystem::path& cwd = {}) {
    const std::string cmd = (cwd.empty() ? std::string() : "cd '" + cwd.string() + "' && ") + "SHOAL_CACHE_DIR='" + cache_dir.string() + "' '" + SHOAL_BINARY + "' " + args + " 2>'" + err_file.string() + "'";
    Outcome r;
    FILE* p = ::popen(cmd.c_str(), "r");
    std::array<char, 4096> buf;
    for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) r.out.append(buf.data(), n);
    const int st = ::pclose(p);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    std::ifstream in(err_file, std::ios::binary);
    r.err.assign(std::istreambuf_iterator<char>(in), {});
    return r;
}

}  // namespace shoal::test
