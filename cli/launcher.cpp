// shoal: the executable. It links no GDAL (GDAL's 114 shared libraries cost some 150 M
// instructions to load and initialise: docs/performance.md, "Start-up"), runs a probe of a grid
// file itself (grid_probe.cpp), and loads the full front end, every command, from the module
// libshoal_cli_full.so for anything else, handing it the command line unchanged: help,
// messages, exit statuses and Ctrl-C are the module's, as they were when it was all one program.
#include "launcher.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <string>
#include <sys/stat.h>

#include "commands.hpp"
#include "process.hpp"
#include "util/lazy_libraries.hpp"

#ifndef SHOAL_CLI_MODULE_DIR
#define SHOAL_CLI_MODULE_DIR "../lib/shoal"
#endif

namespace {

/// The folder of this executable (symbolic links resolved), or "" when it cannot be told.
std::string own_folder() {
    char buf[PATH_MAX];
    const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) return "";
    const std::string path(buf, static_cast<std::size_t>(n));
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

/// Where the module is: beside the executable (the build tree), else where the install puts it
/// (SHOAL_CLI_MODULE_DIR, relative to the executable's folder: ../lib/shoal).
std::string module_path() {
    const std::string dir = own_folder();
    const std::string beside = dir + "/" SHOAL_CLI_MODULE_FILE;
    struct stat st{};
    if (!dir.empty() && ::stat(beside.c_str(), &st) == 0) return beside;
    return (dir.empty() ? std::string(".") : dir) + "/" SHOAL_CLI_MODULE_DIR "/" SHOAL_CLI_MODULE_FILE;
}

int run_module(int argc, char** argv) {
    const std::string path = module_path();
    // Lazily bound: the module calls GDAL, GEOS and PROJ without naming them, and loads each when
    // a run first needs it (src/util/lazy_libraries.hpp). Where lazy binding is turned off
    // (LD_BIND_NOW, or a module linked with -z now), the module cannot be loaded before them:
    // then, and only then, they are loaded first, and it again.
    void* module = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    std::string failure;
    if (!module) {
        const char* e = ::dlerror();
        failure = e ? e : "no reason given";
        if (failure.find("undefined symbol") != std::string::npos || failure.find("symbol not found") != std::string::npos) {  // glibc's, musl's
            std::string why;
            if (!shoal::detail::load_all_now(&why)) failure += "; " + why;
            else if (!(module = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL))) {
                const char* again = ::dlerror();
                failure = again ? again : "no reason given";
            }
        }
    }
    using Entry = int (*)(int, char**);
    Entry entry = module ? reinterpret_cast<Entry>(::dlsym(module, SHOAL_CLI_ENTRY_NAME)) : nullptr;
    if (!entry) {
        if (module) {
            const char* e = ::dlerror();
            failure = e ? e : "no entry point";
        }
        std::fprintf(stderr,
                     "shoal: internal error: cannot load shoal's command module '%s' (%s): the installation is incomplete "
                     "(every command but a probe of a .shoalgrid needs it; reinstall shoal)\n",
                     path.c_str(), failure.c_str());
        return shoal::cli::exit_internal;
    }
    return entry(argc, argv);  // never closed: its static objects end with the process, as before
}

}  // namespace

int main(int argc, char** argv) {
    shoal::cli::keep_standard_streams();
    shoal::cli::fewer_malloc_arenas();
    // From the start, as before the split: Ctrl-C while the module loads is "interrupted" (130);
    // the module installs its own handler (for the files it writes) when it starts.
    shoal::cli::handle_interrupts();
    int rc = 0;
    if (shoal::cli::run_grid_probe(argc, argv, rc)) return rc;
    return run_module(argc, argv);
}
