// libshoal_c.so.1's user CRS: PROJ loaded only when a grid in such a frame is loaded, from the
// module libshoal_crs.so (geo/crs_module.cpp) beside libshoal_c.so.1 (the build tree) or in
// shoal/ below it (an install: ${libdir}/shoal/). A grid in shoal's own transverse Mercator
// (transverse_mercator.hpp) never comes here, so a simulator's process loads no PROJ.
#include <dlfcn.h>
#include <sys/stat.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "geo/crs_projection.hpp"
#include <shoal/util/error.hpp>

namespace shoal::geo::detail {

namespace {

using Make = CrsProjection* (*)(const char*, char*, std::size_t);

/// The folder this library was loaded from (symbolic links and a relative path resolved), or "".
std::string own_folder() {
    Dl_info info{};
    if (::dladdr(reinterpret_cast<void*>(&own_folder), &info) == 0 || !info.dli_fname) return "";
    char* real = ::realpath(info.dli_fname, nullptr);
    const std::string path = real ? real : info.dli_fname;
    std::free(real);
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

/// Told when the library is loaded: a path relative to the working folder then (a relative
/// LD_LIBRARY_PATH entry) would be wrong after the program changes folder.
const std::string loaded_from = own_folder();

/// The module's entry point, loaded once a process; throws UsageError saying why it cannot be.
Make entry() {
    static std::once_flag once;
    static Make make = nullptr;
    static std::string why;
    std::call_once(once, [] {
        const std::string& dir = loaded_from;
        std::string path = dir + "/" SHOAL_CRS_MODULE_FILE;
        struct stat st{};
        if (dir.empty() || ::stat(path.c_str(), &st) != 0) path = (dir.empty() ? std::string(".") : dir) + "/shoal/" SHOAL_CRS_MODULE_FILE;
        void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: its projections live on
        make = module ? reinterpret_cast<Make>(::dlsym(module, "shoal_crs_projection_make")) : nullptr;
        if (!make) {
            const char* reason = ::dlerror();
            why = "shoal's PROJ module '" + path + "' cannot be loaded (" + (reason ? reason : "no reason given") +
                  "): the installation is incomplete";
        }
    });
    if (!make) throw UsageError(why);
    return make;
}

}  // namespace

std::unique_ptr<CrsProjection> make_crs_projection(const std::string& definition) {
    const Make make = entry();
    char error[8192] = "";  // room for a message that quotes a long WKT
    CrsProjection* p = make(definition.c_str(), error, sizeof error);
    if (!p) throw UsageError(error[0] ? error : "CRS '" + definition + "' cannot be used");
    return std::unique_ptr<CrsProjection>(p);
}

}  // namespace shoal::geo::detail
