#include <shoal/grid/grid_cache.hpp>

#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <shoal/util/error.hpp>

namespace shoal::grid {

namespace fs = std::filesystem;

namespace {

fs::path cache_folder(const std::string& requested) {
    if (!requested.empty()) return requested;
    if (const char* d = std::getenv("SHOAL_CACHE_DIR"); d && *d) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return fs::path(d) / "shoal";
    if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "shoal";
    // No HOME (cron, services): the user's home from the password database, never a shared
    // predictable folder; failing that, a folder of this user's own in the temporary directory
    // (created 0700 and owner-checked like any other).
    struct passwd pw{};
    struct passwd* found = nullptr;
    char buf[4096];
    if (getpwuid_r(::geteuid(), &pw, buf, sizeof buf, &found) == 0 && found && found->pw_dir && *found->pw_dir)
        return fs::path(found->pw_dir) / ".cache" / "shoal";
    return fs::temp_directory_path() / ("shoal-cache-" + std::to_string(::geteuid()));
}

/// Whether `p` (a folder or a file) is this user's own and nobody else may write it; else why not.
bool private_to_user(const fs::path& p, std::string& why) {
    // Appended to, not prepended ("'" + string trips GCC 12's -Wrestrict at -O3, bug 105329).
    auto quoted = [&] {
        std::string q(1, '\'');
        q += p.string();
        q += '\'';
        return q;
    };
    struct stat st{};
    if (::lstat(p.c_str(), &st) != 0) return true;  // not there (yet): nothing to distrust
    if (S_ISLNK(st.st_mode)) {
        why = quoted() + " is a symbolic link";
        return false;
    }
    if (st.st_uid != ::geteuid()) {
        why = quoted() + " belongs to user " + std::to_string(st.st_uid) + ", not to you (" + std::to_string(::geteuid()) + ")";
        return false;
    }
    if (st.st_mode & (S_IWGRP | S_IWOTH)) {
        why = quoted() + " may be written by other users";
        return false;
    }
    return true;
}

/// What `p` is when it is there and is not a regular file (lstat: a link is itself); else null.
const char* not_a_regular_file(const fs::path& p) {
    struct stat st{};
    if (::lstat(p.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return nullptr;
    if (S_ISFIFO(st.st_mode)) return "a FIFO (a named pipe)";
    if (S_ISDIR(st.st_mode)) return "a directory";
    if (S_ISSOCK(st.st_mode)) return "a socket";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
    if (S_ISLNK(st.st_mode)) return "a symbolic link";
    return "an entry of another kind";
}

}  // namespace

CoastGrid load_or_build(const std::vector<std::string>& paths, const BuildRequest& request, LoadReport* report) {
    const auto t0 = std::chrono::steady_clock::now();
    LoadReport local;
    LoadReport& rep = report ? *report : local;
    auto done = [&](CoastGrid g) {
        rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return g;
    };
    if (paths.size() == 1 && looks_like_grid(paths[0])) {
        rep.how = "loaded grid";
        return done(GridFile::load(paths[0]));
    }
    // A file named as a grid that is none (empty, another file renamed): said as a grid's
    // problem, not as a coastline OGR cannot read.
    if (std::error_code ec; paths.size() == 1 && fs::path(paths[0]).extension() == ".shoalgrid" && fs::is_regular_file(paths[0], ec))
        GridFile::load(paths[0]);  // throws: it is no grid
    for (const auto& p : paths)
        if (paths.size() > 1 && looks_like_grid(p))
            throw UsageError("'" + p + "' is a grid file: give either one grid or coastline sources, not both");
    const double cell_key = request.cell_m > 0 ? request.cell_m : 2.5 * request.ship_length_m;
    const std::uint64_t fp = fingerprint_sources(paths, request.import, request.crs, cell_key);
    const fs::path dir = cache_folder(request.cache_dir);
    const fs::path cache = dir / (fs::path(paths[0]).stem().string() + "-" + fingerprint_hex(fp) + ".shoalgrid");
    rep.cache_path = cache.string();
    std::error_code ec;
    // A cache is trusted only when it is the user's own: a grid planted by another user (its
    // fingerprint and checksum are plain hashes anyone can recompute) could hide land.
    std::string why;
    if (!private_to_user(dir, why) || !private_to_user(cache, why)) {
        rep.warnings.push_back("the grid cache is not private (" + why + "): not used; the grid is built for this run only "
                               "(give BuildRequest::cache_dir a folder of your own)");
        CoastGrid g = build_grid(paths, request, &rep.warnings, &rep.build);
        rep.how = "built (cache not private, not used)";
        return done(std::move(g));
    }
    // Only a regular file is a cached grid: a FIFO there would hold the run for ever (reading
    // it, or writing the new grid into it), a device or a folder is not ours to replace. Told
    // apart by lstat alone, never opened.
    if (const char* kind = not_a_regular_file(cache)) {
        rep.warnings.push_back("the cached grid's path '" + cache.string() + "' is " + kind +
                               ", not a regular file: not read or written; the grid is built for this run only (remove it to cache the grid)");
        CoastGrid g = build_grid(paths, request, &rep.warnings, &rep.build);
        rep.how = "built (cache path not a regular file, not used)";
        return done(std::move(g));
    }
    if (fs::exists(cache, ec)) {
        try {
            CoastGrid g = GridFile::load(cache.string());
            if (g.source().fingerprint == fp) {
                // One cached grid serves every limiting depth: the default is this request's.
                g.source().limiting_depth_m = request.import.limiting_depth_m.value_or(NAN);
                rep.how = "reused cached grid";
                return done(std::move(g));
            }
        } catch (const InputError& e) {
            rep.warnings.push_back(std::string("cached grid unusable, rebuilding: ") + e.what());
        }
    }
    CoastGrid g = build_grid(paths, request, &rep.warnings, &rep.build);
    if (!fs::exists(dir, ec)) {
        fs::create_directories(dir, ec);
        ::chmod(dir.c_str(), 0700);  // the cache folder is private to its user
    }
    try {
        GridFile::save(g, cache.string());
        rep.how = "built and cached";
    } catch (const InputError& e) {
        rep.how = "built (not cached)";
        rep.warnings.push_back(std::string("could not cache the grid: ") + e.what());
    }
    return done(std::move(g));
}

}  // namespace shoal::grid
