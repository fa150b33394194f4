#pragma once
/// RAII owners for the GEOS C API (reentrant `_r` functions only). A `GeosContext` keeps the
/// last GEOS error message so that callers can throw with it; one context per thread.

#define GEOS_USE_ONLY_R_API
#include <geos_c.h>

#include <memory>
#include <string>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::geo {

class GeosContext {
public:
    GeosContext();
    ~GeosContext();
    GeosContext(const GeosContext&) = delete;
    GeosContext& operator=(const GeosContext&) = delete;

    GEOSContextHandle_t get() const noexcept { return m_handle; }
    operator GEOSContextHandle_t() const noexcept { return m_handle; }
    /// The last error or notice GEOS reported on this context ("" when none).
    const std::string& last_message() const noexcept { return m_last_message; }

private:
    static void on_message(const char* message, void* userdata);
    GEOSContextHandle_t m_handle;
    std::string m_last_message;
};

struct GeomDeleter {
    GEOSContextHandle_t ctx = nullptr;
    void operator()(GEOSGeometry* g) const noexcept { GEOSGeom_destroy_r(ctx, g); }
};
using GeomPtr = std::unique_ptr<GEOSGeometry, GeomDeleter>;

struct PreparedDeleter {
    GEOSContextHandle_t ctx = nullptr;
    void operator()(const GEOSPreparedGeometry* p) const noexcept { GEOSPreparedGeom_destroy_r(ctx, p); }
};
using PreparedPtr = std::unique_ptr<const GEOSPreparedGeometry, PreparedDeleter>;

struct TreeDeleter {
    GEOSContextHandle_t ctx = nullptr;
    void operator()(GEOSSTRtree* t) const noexcept { GEOSSTRtree_destroy_r(ctx, t); }
};
using TreePtr = std::unique_ptr<GEOSSTRtree, TreeDeleter>;

/// Takes ownership of `g`; throws LibraryError with `what` and GEOS's message when null.
GeomPtr own(const GeosContext& ctx, GEOSGeometry* g, const char* what);

GeomPtr make_linestring(const GeosContext& ctx, const XY* pts, std::size_t n);
/// A polygon from rings (each closed: first == last); the first is the shell.
GeomPtr make_polygon(const GeosContext& ctx, const std::vector<std::vector<XY>>& rings);
/// Appends every LineString reachable in `g` (multi and collections walked) as point lists.
void collect_lines(const GeosContext& ctx, const GEOSGeometry* g, std::vector<std::vector<XY>>& out);
/// Appends every Polygon's rings in `g` as closed point lists: out[i][0] is a shell.
void collect_polygons(const GeosContext& ctx, const GEOSGeometry* g, std::vector<std::vector<std::vector<XY>>>& out);

}  // namespace shoal::geo
