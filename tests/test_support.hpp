#pragma once
/// Helpers shared by the geo, coast and grid tests: where the test data lives, a temporary
/// folder, and GEOS shapes built *independently* of the code under test (land polygons read
/// straight from OGR and projected vertex by vertex with the same LocalFrame), so that tests
/// compare shoal's answers with GEOS's.

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <stdlib.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geo/geos_context.hpp"
#include "temp_dir.hpp"
#include <shoal/geo/local_frame.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::test {

/// Absolute path of a file under tests/data/ (`rel` like "coast/uk_solent_land.geojson").
inline std::string data_path(const std::string& rel) { return std::string(SHOAL_TEST_DATA) + rel; }


inline std::vector<char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("test cannot read " + path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A file's bytes as a string.
inline std::string read_text(const std::string& path) {
    const std::vector<char> b = read_bytes(path);
    return {b.begin(), b.end()};
}

inline void write_bytes(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("test cannot write " + path);
}

/// A polygon in WGS84 lon/lat as OGR reads it: rings[0] the shell, then the holes.
struct LonLatPolygon {
    std::vector<std::vector<geo::LonLat>> rings;
    std::int64_t fid = -1;
};

/// Every polygon part of layer `layer` ("" = the first layer) of `path`, read with OGR alone
/// and transformed to WGS84 lon/lat when the layer has another CRS. Throws on trouble.
inline std::vector<LonLatPolygon> read_polygons_with_ogr(const std::string& path, const std::string& layer = "") {
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) throw std::runtime_error("OGR cannot open " + path);
    OGRLayer* l = layer.empty() ? ds->GetLayer(0) : ds->GetLayerByName(layer.c_str());
    if (!l) throw std::runtime_error("no layer '" + layer + "' in " + path);
    std::unique_ptr<OGRCoordinateTransformation> ct;
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (const OGRSpatialReference* srs = l->GetSpatialRef(); srs && !(srs->IsGeographic() && srs->IsSame(&wgs84))) {
        OGRSpatialReference src(*srs);
        src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        ct.reset(OGRCreateCoordinateTransformation(&src, &wgs84));
    }
    std::vector<LonLatPolygon> out;
    auto add = [&](const OGRPolygon& poly, std::int64_t fid) {
        LonLatPolygon p;
        p.fid = fid;
        for (const OGRLinearRing* ring : poly) {
            auto& r = p.rings.emplace_back();
            for (const OGRPoint& pt : *ring) {
                double x = pt.getX(), y = pt.getY();
                if (ct && !ct->Transform(1, &x, &y)) throw std::runtime_error("cannot transform a vertex of " + path);
                r.push_back({x, y});
            }
        }
        out.push_back(std::move(p));
    };
    for (auto& f : *l) {
        const OGRGeometry* g = f->GetGeometryRef();
        if (!g) continue;
        const auto type = wkbFlatten(g->getGeometryType());
        if (type == wkbPolygon) add(*g->toPolygon(), f->GetFID());
        if (type == wkbMultiPolygon)
            for (const OGRPolygon* part : *g->toMultiPolygon()) add(*part, f->GetFID());
    }
    return out;
}

/// Geometry owner bound to a context (tests only: GEOS errors become std::runtime_error).
inline geo::GeomPtr check(const geo::GeosContext& ctx, GEOSGeometry* g, const char* what) {
    if (!g) throw std::runtime_error(std::string("GEOS ") + what + " failed: " + ctx.last_message());
    return geo::GeomPtr(g, geo::GeomDeleter{ctx.get()});
}

inline GEOSCoordSequence* sequence(const geo::GeosContext& ctx, const std::vector<geo::XY>& pts) {
    GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx, static_cast<unsigned>(pts.size()), 2);
    for (unsigned i = 0; i < pts.size(); ++i) GEOSCoordSeq_setXY_r(ctx, seq, i, pts[i].x, pts[i].y);
    return seq;
}

inline geo::GeomPtr point(const geo::GeosContext& ctx, geo::XY p) {
    return check(ctx, GEOSGeom_createPointFromXY_r(ctx, p.x, p.y), "point");
}

/// A LineString; a degenerate one (a == b) becomes a Point so that GEOS treats it sanely.
inline geo::GeomPtr segment(const geo::GeosContext& ctx, geo::XY a, geo::XY b) {
    if (a == b) return point(ctx, a);
    return check(ctx, GEOSGeom_createLineString_r(ctx, sequence(ctx, {a, b})), "line");
}

inline geo::GeomPtr line(const geo::GeosContext& ctx, const std::vector<geo::XY>& pts) {
    return check(ctx, GEOSGeom_createLineString_r(ctx, sequence(ctx, pts)), "line");
}

/// A polygon from closed rings (first the shell).
inline geo::GeomPtr polygon(const geo::GeosContext& ctx, const std::vector<std::vector<geo::XY>>& rings) {
    GEOSGeometry* shell = GEOSGeom_createLinearRing_r(ctx, sequence(ctx, rings.at(0)));
    std::vector<GEOSGeometry*> holes;
    for (std::size_t i = 1; i < rings.size(); ++i) holes.push_back(GEOSGeom_createLinearRing_r(ctx, sequence(ctx, rings[i])));
    return check(ctx, GEOSGeom_createPolygon_r(ctx, shell, holes.data(), static_cast<unsigned>(holes.size())), "polygon");
}

inline geo::GeomPtr box_polygon(const geo::GeosContext& ctx, const geo::Box& b) {
    return polygon(ctx, {{{b.minx, b.miny}, {b.maxx, b.miny}, {b.maxx, b.maxy}, {b.minx, b.maxy}, {b.minx, b.miny}}});
}

/// A collection (MultiLineString, MultiPolygon, ...) taking ownership of `parts`.
inline geo::GeomPtr collection(const geo::GeosContext& ctx, int type, std::vector<geo::GeomPtr> parts) {
    std::vector<GEOSGeometry*> raw;
    for (auto& p : parts) raw.push_back(p.release());
    return check(ctx, GEOSGeom_createCollection_r(ctx, type, raw.data(), static_cast<unsigned>(raw.size())), "collection");
}

/// The polylines (each of >= 2 points) as one MultiLineString.
inline geo::GeomPtr multi_line(const geo::GeosContext& ctx, const std::vector<std::vector<geo::XY>>& lines) {
    std::vector<geo::GeomPtr> parts;
    for (const auto& l : lines)
        if (l.size() >= 2) parts.push_back(line(ctx, l));
    return collection(ctx, GEOS_MULTILINESTRING, std::move(parts));
}

/// Land polygons read by OGR, projected vertex by vertex with `frame`, as one valid GEOS
/// geometry (the union, so overlapping polygons are land once).
inline geo::GeomPtr projected_land(const geo::GeosContext& ctx, const std::vector<LonLatPolygon>& polys,
                                   const geo::LocalFrame& frame) {
    std::vector<geo::GeomPtr> parts;
    for (const auto& p : polys) {
        std::vector<std::vector<geo::XY>> rings;
        for (const auto& r : p.rings) {
            auto& xy = rings.emplace_back();
            for (const geo::LonLat& ll : r) xy.push_back(frame.forward(ll));
        }
        parts.push_back(polygon(ctx, rings));
    }
    geo::GeomPtr all = collection(ctx, GEOS_GEOMETRYCOLLECTION, std::move(parts));
    return check(ctx, GEOSUnaryUnion_r(ctx, all.get()), "union");
}

using geo::PreparedDeleter;
using geo::PreparedPtr;

/// A prepared view of `g` for fast repeated predicates (`g` must outlive it).
inline PreparedPtr prepare(const geo::GeosContext& ctx, const GEOSGeometry* g) {
    const GEOSPreparedGeometry* p = GEOSPrepare_r(ctx, g);
    if (!p) throw std::runtime_error("GEOSPrepare failed: " + ctx.last_message());
    return PreparedPtr(p, PreparedDeleter{ctx.get()});
}

inline double length(const geo::GeosContext& ctx, const GEOSGeometry* g) {
    double len = 0;
    if (!GEOSLength_r(ctx, g, &len)) throw std::runtime_error("GEOSLength failed");
    return len;
}

inline std::string wkt(const geo::GeosContext& ctx, const GEOSGeometry* g, std::size_t max_chars = 2000) {
    GEOSWKTWriter* w = GEOSWKTWriter_create_r(ctx);
    GEOSWKTWriter_setRoundingPrecision_r(ctx, w, 12);
    char* s = GEOSWKTWriter_write_r(ctx, w, g);
    std::string out = s ? s : "(null)";
    GEOSFree_r(ctx, s);
    GEOSWKTWriter_destroy_r(ctx, w);
    if (out.size() > max_chars) out = out.substr(0, max_chars) + "...";
    return out;
}

}  // namespace shoal::test
