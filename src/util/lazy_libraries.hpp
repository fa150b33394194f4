#pragma once
/// GDAL, GEOS and PROJ loaded when first needed, for a program linked without them.
///
/// The CLI's command module (cli/CMakeLists.txt) is linked against none of the three: their
/// functions stay unresolved in it until first called (lazy binding), and loading GDAL's tree
/// of some hundred shared libraries cost 190 M instructions at every start, which a check of
/// plain track files against a grid file does not need (docs/performance.md, "GDAL, GEOS and
/// PROJ loaded when a run needs them"). Every part of the library that calls one of them first
/// calls its need_...(): GDAL's driver registration, its error scope and its virtual files
/// (util/gdal_support.hpp, util/gdal_input.cpp), a GEOS context (geo/geos_context.cpp), PROJ's
/// user CRSs (geo/crs_projection.cpp). In a program linked with the library (the tests, the
/// Python module, a user's program), each finds its library already there and does nothing else.
///
/// Each is thread-safe and cheap once done. A library that cannot be loaded is a MissingLibrary
/// naming it and the loader's reasons (tried again at the next need).

#include <string>

#include <shoal/util/error.hpp>

namespace shoal::detail {

/// GDAL, GEOS or PROJ could not be loaded when a run needed it: the installation is incomplete
/// (not the input's fault, nor a bug).
struct MissingLibrary : LibraryError {
    using LibraryError::LibraryError;
};

void need_gdal();
void need_geos();
void need_proj();

/// Runs `setup` once GDAL is loaded (now, when it already is): the CLI's own error handler.
/// Set it before any thread may need GDAL.
void on_gdal_loaded(void (*setup)());

/// Loads all three now, into the global scope (a program whose lazy binding is turned off, by
/// LD_BIND_NOW, must have them before it loads a module that calls them). False, with why,
/// when one cannot be loaded.
bool load_all_now(std::string* failure);

}  // namespace shoal::detail
