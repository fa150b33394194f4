#pragma once
/// The transformation between WGS84 and a user's CRS, by PROJ (crs_projection.cpp): the part of
/// `LocalFrame` that needs PROJ. shoal's own transverse Mercator needs none
/// (transverse_mercator.hpp), so a program that only ever loads grids in that frame may link a
/// definition of `make_crs_projection` of its own that refuses (the `shoal` executable's probe
/// of a grid: cli/frame_without_proj.cpp) and so load no PROJ.

#include <memory>
#include <string>

namespace shoal::geo::detail {

class CrsProjection {
public:
    virtual ~CrsProjection() = default;
    /// The CRS's name, or "".
    virtual const std::string& name() const = 0;
    /// lon, lat (degrees) -> x, y (metres) in place, on the calling thread; non-finite or huge
    /// values where PROJ cannot.
    virtual void forward(double* xs, double* ys, std::size_t n) const = 0;
    /// x, y -> lon, lat in place.
    virtual void inverse(double& x, double& y) const = 0;
};

/// Throws UsageError naming `definition` when PROJ cannot read it as a projected CRS or has no
/// transformation to it from WGS84.
std::unique_ptr<CrsProjection> make_crs_projection(const std::string& definition);

}  // namespace shoal::geo::detail
