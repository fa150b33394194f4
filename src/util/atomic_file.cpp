#include "util/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "util/error.hpp"

namespace shoal {

namespace fs = std::filesystem;

void write_file_atomically(const std::string& path, std::string_view bytes) {
    if (path.empty() || path == "-") {
        if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
            throw InputError(std::string("cannot write to stdout: ") + std::strerror(errno));
        return;
    }
    const fs::path target(path);
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + path + "': folder '" + dir.string() + "' does not exist");
    if (fs::is_directory(target, ec)) throw InputError("cannot write '" + path + "': it is a directory");
    std::random_device rd;
    char suffix[40];
    std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%08x", static_cast<long>(::getpid()), rd());
    const fs::path tmp = dir / ("." + target.filename().string() + suffix);
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError("cannot write '" + path + "': " + std::strerror(errno));
    bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() && std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
    int err = ok ? 0 : errno;
    if (std::fclose(f) != 0 && ok) {
        ok = false;
        err = errno;
    }
    if (!ok) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + path + "': " + std::strerror(err));
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw InputError("cannot write '" + path + "': " + ec.message());
    }
}

}  // namespace shoal
