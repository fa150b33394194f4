#include "util/lazy_libraries.hpp"

#include <dlfcn.h>

#include <atomic>
#include <mutex>
#include <string>

// The libraries this build was made against (src/CMakeLists.txt): their sonames, loaded as the
// dynamic linker would load a library named in DT_NEEDED, and their folders, tried when the
// soname alone is not found there (a GDAL installed under its own prefix). Empty when the
// program is linked with them (SHOAL_LAZY_LIBRARIES off): they are then always found already.
#ifndef SHOAL_GDAL_SONAME
#error "SHOAL_GDAL_SONAME, SHOAL_GEOS_SONAME and SHOAL_PROJ_SONAME come from src/CMakeLists.txt"
#endif

namespace shoal::detail {
namespace {

struct Library {
    const char* name;    ///< for messages
    const char* probe;   ///< a function it exports: found, the library is there
    const char* soname;
    const char* folder;
    std::mutex mutex;
    std::atomic<bool> ready{false};
};

Library gdal{"GDAL", "GDALAllRegister", SHOAL_GDAL_SONAME, SHOAL_GDAL_FOLDER, {}, {}};
Library geos{"GEOS", "GEOS_init_r", SHOAL_GEOS_SONAME, SHOAL_GEOS_FOLDER, {}, {}};
Library proj{"PROJ", "proj_context_create", SHOAL_PROJ_SONAME, SHOAL_PROJ_FOLDER, {}, {}};

std::atomic<void (*)()> gdal_setup{nullptr};

/// Loads `lib` into the global scope unless its functions are found from here already; "" when
/// they are found after, else why not (each place tried, with the loader's reason).
std::string load(const Library& lib) {
    // Without SHOAL_LAZY_LIBRARIES the program is linked with the library (shared or static:
    // a static one's functions are in no dynamic symbol table), and its calls are bound by then.
    if (!*lib.soname) return "";
    if (::dlsym(RTLD_DEFAULT, lib.probe)) return "";
    std::string why;
    auto attempt = [&](const std::string& file) {
        // Lazily bound, as a library named in DT_NEEDED would be (Debian's are built to bind
        // at once anyway); global, so that the module's calls find its functions.
        if (void* handle = ::dlopen(file.c_str(), RTLD_LAZY | RTLD_GLOBAL)) {
            if (::dlsym(RTLD_DEFAULT, lib.probe)) return true;
            ::dlclose(handle);  // not the library: its symbols leave the global scope again
            why += (why.empty() ? "" : "; ") + file + " has no " + lib.probe;
            return false;
        }
        const char* e = ::dlerror();
        why += (why.empty() ? "" : "; ") + std::string(e ? e : file + ": not loaded");
        return false;
    };
    if (attempt(lib.soname)) return "";
    if (*lib.folder && attempt(std::string(lib.folder) + "/" + lib.soname)) return "";
    return why;
}

void need(Library& lib) {
    if (lib.ready.load(std::memory_order_acquire)) return;
    const std::lock_guard<std::mutex> lock(lib.mutex);
    if (lib.ready.load(std::memory_order_relaxed)) return;
    if (const std::string why = load(lib); !why.empty())  // not ready: the next need tries again
        throw MissingLibrary(std::string("cannot load ") + lib.name + " (" + lib.soname + "), which this run needs: " + why);
    // Under the lock: a setup must not need GDAL itself (register_drivers, QuietErrors), which
    // would take this lock again. The CLI's sets GDAL's error handler, nothing more.
    if (&lib == &gdal)
        if (auto* setup = gdal_setup.load()) setup();
    lib.ready.store(true, std::memory_order_release);
}

}  // namespace

void need_gdal() { need(gdal); }

void need_geos() { need(geos); }

void need_proj() { need(proj); }

void on_gdal_loaded(void (*setup)()) {
    gdal_setup.store(setup);
    if (gdal.ready.load(std::memory_order_acquire)) setup();
}

bool load_all_now(std::string* failure) {
    for (const Library* lib : {&gdal, &geos, &proj})
        if (std::string why = load(*lib); !why.empty()) {
            if (failure) *failure = std::string("cannot load ") + lib->name + " (" + lib->soname + "): " + why;
            return false;
        }
    return true;
}

}  // namespace shoal::detail
