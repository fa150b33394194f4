// The `shoal` executable's frames: shoal's own transverse Mercator only. The executable's
// definition of geo::detail::make_crs_projection (the full library's is geo/crs_projection.cpp,
// with PROJ): it refuses, so the executable loads no PROJ (its tree of shared libraries was most
// of what a probe of a grid loaded).
// grid_probe.cpp asks a grid file's frame first (grid::GridFile::frame_definition) and leaves
// any other frame to the full front end, which has PROJ: this refusal is only a safeguard.
#include "geo/crs_projection.hpp"

#include <shoal/util/error.hpp>

namespace shoal::geo::detail {

std::unique_ptr<CrsProjection> make_crs_projection(const std::string& definition) {
    throw LibraryError("the frame '" + definition + "' needs PROJ, which this part of shoal does not load");
}

}  // namespace shoal::geo::detail
