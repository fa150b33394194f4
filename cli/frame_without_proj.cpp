// The `shoal` executable's frames: shoal's own transverse Mercator only. This definition of
// geo::detail::make_crs_projection is linked into the executable ahead of the core's archive,
// so the core's own (geo/crs_projection.cpp, PROJ) is never taken from it, and the executable
// loads no PROJ (its tree of shared libraries is most of what a probe of a grid would load).
// grid_probe.cpp asks a grid file's frame first (grid::GridFile::frame_definition) and leaves
// any other frame to the full front end, which has PROJ: this refusal is only a safeguard.
#include "geo/crs_projection.hpp"

#include <shoal/util/error.hpp>

namespace shoal::geo::detail {

std::unique_ptr<CrsProjection> make_crs_projection(const std::string& definition) {
    throw LibraryError("the frame '" + definition + "' needs PROJ, which this part of shoal does not load");
}

}  // namespace shoal::geo::detail
