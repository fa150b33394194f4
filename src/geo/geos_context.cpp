#include "geo/geos_context.hpp"

#include <shoal/util/error.hpp>

#include "util/lazy_libraries.hpp"

namespace shoal::geo {

// GEOS loaded first when this program was linked without it (util/lazy_libraries.hpp): every
// GEOS call goes through a context.
GeosContext::GeosContext() : m_handle((detail::need_geos(), GEOS_init_r())) {
    GEOSContext_setErrorMessageHandler_r(m_handle, &GeosContext::on_message, this);
}

GeosContext::~GeosContext() { GEOS_finish_r(m_handle); }

void GeosContext::on_message(const char* message, void* userdata) {
    static_cast<GeosContext*>(userdata)->m_last_message = message ? message : "";
}

GeomPtr own(const GeosContext& ctx, GEOSGeometry* g, const char* what) {
    if (!g) throw LibraryError(std::string(what) + " failed in GEOS: " + ctx.last_message());
    return GeomPtr(g, GeomDeleter{ctx.get()});
}

namespace {

GEOSCoordSequence* make_seq(const GeosContext& ctx, const XY* pts, std::size_t n) {
    static_assert(sizeof(XY) == 2 * sizeof(double));
    GEOSCoordSequence* seq =
        GEOSCoordSeq_copyFromBuffer_r(ctx, reinterpret_cast<const double*>(pts), static_cast<unsigned>(n), 0, 0);
    if (!seq) throw LibraryError("creating a GEOS coordinate sequence failed: " + ctx.last_message());
    return seq;
}

void read_seq(const GeosContext& ctx, const GEOSGeometry* line, std::vector<XY>& out) {
    const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(ctx, line);
    unsigned n = 0;
    GEOSCoordSeq_getSize_r(ctx, seq, &n);
    out.resize(n);
    if (n) GEOSCoordSeq_copyToBuffer_r(ctx, seq, reinterpret_cast<double*>(out.data()), 0, 0);
}

}  // namespace

GeomPtr make_linestring(const GeosContext& ctx, const XY* pts, std::size_t n) {
    return own(ctx, GEOSGeom_createLineString_r(ctx, make_seq(ctx, pts, n)), "creating a line");
}

GeomPtr make_polygon(const GeosContext& ctx, const std::vector<std::vector<XY>>& rings) {
    if (rings.empty()) return own(ctx, GEOSGeom_createEmptyPolygon_r(ctx), "creating an empty polygon");
    // Rings are owned here until the polygon takes them.
    std::vector<GeomPtr> owned;
    for (const auto& ring : rings)
        owned.push_back(own(ctx, GEOSGeom_createLinearRing_r(ctx, make_seq(ctx, ring.data(), ring.size())), "creating a ring"));
    std::vector<GEOSGeometry*> holes;
    for (std::size_t i = 1; i < owned.size(); ++i) holes.push_back(owned[i].get());
    GEOSGeometry* poly = GEOSGeom_createPolygon_r(ctx, owned[0].get(), holes.data(), static_cast<unsigned>(holes.size()));
    if (poly)
        for (auto& r : owned) static_cast<void>(r.release());  // now owned by the polygon
    return own(ctx, poly, "creating a polygon");
}

void collect_lines(const GeosContext& ctx, const GEOSGeometry* g, std::vector<std::vector<XY>>& out) {
    if (!g || GEOSisEmpty_r(ctx, g)) return;
    const int type = GEOSGeomTypeId_r(ctx, g);
    if (type == GEOS_LINESTRING || type == GEOS_LINEARRING) {
        out.emplace_back();
        read_seq(ctx, g, out.back());
    } else if (type == GEOS_MULTILINESTRING || type == GEOS_GEOMETRYCOLLECTION) {
        const int n = GEOSGetNumGeometries_r(ctx, g);
        for (int i = 0; i < n; ++i) collect_lines(ctx, GEOSGetGeometryN_r(ctx, g, i), out);
    }
}

void collect_polygons(const GeosContext& ctx, const GEOSGeometry* g, std::vector<std::vector<std::vector<XY>>>& out) {
    if (!g || GEOSisEmpty_r(ctx, g)) return;
    const int type = GEOSGeomTypeId_r(ctx, g);
    if (type == GEOS_POLYGON) {
        auto& rings = out.emplace_back();
        rings.emplace_back();
        read_seq(ctx, GEOSGetExteriorRing_r(ctx, g), rings.back());
        const int nh = GEOSGetNumInteriorRings_r(ctx, g);
        for (int i = 0; i < nh; ++i) {
            rings.emplace_back();
            read_seq(ctx, GEOSGetInteriorRingN_r(ctx, g, i), rings.back());
        }
    } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
        const int n = GEOSGetNumGeometries_r(ctx, g);
        for (int i = 0; i < n; ++i) collect_polygons(ctx, GEOSGetGeometryN_r(ctx, g, i), out);
    }
}

}  // namespace shoal::geo
