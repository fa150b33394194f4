#include "util/lazy_libraries.hpp"

#include <dlfcn.h>

#include <atomic>
#include <mutex>
#include <string>

#include <shoal/util/error.hpp>

// The libraries this build was made against (src/CMakeLists.txt): their sonames, loaded as the
// dynamic linker would load a library named in DT_NEEDED, and their folders, tried when the
// soname alone is not found there (a GDAL installed under its own prefix).
#ifndef SHOAL_GDAL_SONAME
#error "SHOAL_GDAL_SONAME, SHOAL_GEOS_SONAME and SHOAL_PROJ_SONAME come from src/CMakeLists.txt"
#endif

namespace shoal::detail {
namespace {

struct Library {
    const char* name;    ///< for messages
    const char* probe;   ///< a function it exports: found already, the library is there
    const char* soname;
    const char* folder;
    std::once_flag once;
};

Library gdal{"GDAL", "GDALAllRegister", SHOAL_GDAL_SONAME, SHOAL_GDAL_FOLDER, {}};
Library geos{"GEOS", "GEOS_init_r", SHOAL_GEOS_SONAME, SHOAL_GEOS_FOLDER, {}};
Library proj{"PROJ", "proj_context_create", SHOAL_PROJ_SONAME, SHOAL_PROJ_FOLDER, {}};

std::atomic<void (*)()> gdal_setup{nullptr};
std::atomic<bool> gdal_ready{false};

/// Loads `lib` into the global scope unless its functions are already found from here; nullptr
/// when done, else the loader's message.
const char* load(const Library& lib) {
    if (::dlsym(RTLD_DEFAULT, lib.probe)) return nullptr;
    if (::dlopen(lib.soname, RTLD_NOW | RTLD_GLOBAL)) return nullptr;
    const char* first = ::dlerror();
    static thread_local std::string message;
    message = first ? first : "no reason given";
    const std::string path = std::string(lib.folder) + "/" + lib.soname;
    if (*lib.folder && ::dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL)) return nullptr;
    return message.c_str();
}

void need(Library& lib) {
    std::call_once(lib.once, [&lib] {
        if (const char* why = load(lib))
            throw LibraryError(std::string("cannot load ") + lib.name + " (" + lib.soname + "), which this run needs: " + why);
    });
}

}  // namespace

void need_gdal() {
    if (gdal_ready.load(std::memory_order_acquire)) return;
    need(gdal);
    static std::once_flag setup_once;
    std::call_once(setup_once, [] {
        if (auto* setup = gdal_setup.load()) setup();
    });
    gdal_ready.store(true, std::memory_order_release);
}

void need_geos() { need(geos); }

void need_proj() { need(proj); }

void on_gdal_loaded(void (*setup)()) {
    gdal_setup.store(setup);
    if (gdal_ready.load(std::memory_order_acquire)) setup();
}

bool load_all_now(const char** failure) {
    for (const Library* lib : {&gdal, &geos, &proj})
        if (const char* why = load(*lib)) {
            if (failure) *failure = why;
            return false;
        }
    return true;
}

}  // namespace shoal::detail
