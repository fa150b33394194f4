#pragma once
// The GEOS-only pose checker of the benchmarks: what a careful engineer would write with GEOS
// alone. Every coastline polyline cut into pieces of at most `chunk_segments` segments in an
// STRtree, every land ring as a prepared polygon in a second STRtree. Per pose: the hull
// polygon from its outline, the piece tree queried with the hull's envelope grown by the margin
// (grown 250 m, 1 km, 4 km, ... when the clearance is unlimited), GEOSDistance on the
// candidates nearest envelope first with early exit, and, when no piece meets the hull, one
// hull vertex located in the ring tree (wholly on land or wholly in water). Answers follow the
// detector's conventions: clearance 0 on collision, INFINITY beyond max_clearance.
// Used by bench_detector (in process, per pose) and bench_geos_probe (a whole process, run as
// `shoal probe` is).

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "geo/geos_context.hpp"
#include <shoal/coast/coastline.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::bench {

using shoal::geo::GeomPtr;
using shoal::geo::PreparedPtr;
using shoal::geo::TreePtr;
using shoal::geo::XY;

struct Answer {
    bool collision = false;
    double clearance = INFINITY;
};

/// Builds a GEOS polygon from an open ring without a vector copy per call.
class HullPolygon {
public:
    explicit HullPolygon(GEOSContextHandle_t ctx) : m_ctx(ctx) {}
    GEOSGeometry* make(const std::vector<XY>& outline) {
        m_buf.resize(2 * (outline.size() + 1));
        for (std::size_t i = 0; i <= outline.size(); ++i) {
            const XY p = outline[i % outline.size()];
            m_buf[2 * i] = p.x;
            m_buf[2 * i + 1] = p.y;
        }
        GEOSCoordSequence* seq =
            GEOSCoordSeq_copyFromBuffer_r(m_ctx, m_buf.data(), static_cast<unsigned>(outline.size() + 1), 0, 0);
        GEOSGeometry* ring = GEOSGeom_createLinearRing_r(m_ctx, seq);
        return GEOSGeom_createPolygon_r(m_ctx, ring, nullptr, 0);
    }

private:
    GEOSContextHandle_t m_ctx;
    std::vector<double> m_buf;
};

inline shoal::geo::Box box_of(const std::vector<XY>& pts) {
    shoal::geo::Box b;
    for (const XY& p : pts) b.extend(p);
    return b;
}

inline double signed_area2(const std::vector<XY>& ring) {
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) a += shoal::geo::cross(ring[i] - ring[0], ring[i + 1] - ring[0]);
    return a;
}

/// STRtree of coastline pieces + STRtree of prepared land rings.
class GeosTree {
public:
    GeosTree(const std::vector<shoal::coast::LocalPolyline>& lines, std::size_t chunk_segments) : m_hull(m_ctx.get()) {
        for (const auto& l : lines) {
            const std::size_t nseg = l.points.size() - 1;
            for (std::size_t s = 0; s < nseg; s += chunk_segments) {
                const std::size_t e = std::min(nseg, s + chunk_segments);
                Piece p;
                p.geom = shoal::geo::make_linestring(m_ctx, l.points.data() + s, e - s + 1);
                for (std::size_t k = s; k <= e; ++k) p.box.extend(l.points[k]);
                m_pieces.push_back(std::move(p));
            }
            if (l.land_left && l.points.size() >= 4 && l.points.front() == l.points.back()) {
                Ring r;
                r.geom = shoal::geo::make_polygon(m_ctx, {l.points});
                r.prepared = PreparedPtr(GEOSPrepare_r(m_ctx, r.geom.get()), {m_ctx.get()});
                r.sign = signed_area2(l.points) > 0 ? 1 : -1;  // shells counter-clockwise, holes clockwise
                m_rings.push_back(std::move(r));
            }
        }
        shoal::geo::Box all;
        for (const Piece& p : m_pieces) all.extend(p.box);
        m_span = std::hypot(all.maxx - all.minx, all.maxy - all.miny);
        // The trees' items point into m_pieces and m_rings (not resized from here on), which
        // own the geometries and outlive the trees (declared before them).
        m_piece_tree = TreePtr(GEOSSTRtree_create_r(m_ctx, 10), {m_ctx.get()});
        for (Piece& p : m_pieces) GEOSSTRtree_insert_r(m_ctx, m_piece_tree.get(), p.geom.get(), &p);
        m_ring_tree = TreePtr(GEOSSTRtree_create_r(m_ctx, 10), {m_ctx.get()});
        for (Ring& r : m_rings) GEOSSTRtree_insert_r(m_ctx, m_ring_tree.get(), r.geom.get(), &r);
        // Build the trees now, not in the first query (the rings' point-in-area indexes are
        // built on first use: the untimed warm-up pass does that).
        const GeomPtr probe(GEOSGeom_createPointFromXY_r(m_ctx, 0, 0), {m_ctx.get()});
        GEOSSTRtree_query_r(m_ctx, m_piece_tree.get(), probe.get(), [](void*, void*) {}, nullptr);
        GEOSSTRtree_query_r(m_ctx, m_ring_tree.get(), probe.get(), [](void*, void*) {}, nullptr);
    }
    GeosTree(const GeosTree&) = delete;
    GeosTree& operator=(const GeosTree&) = delete;

    std::size_t pieces() const noexcept { return m_pieces.size(); }
    std::size_t rings() const noexcept { return m_rings.size(); }

    Answer check(const std::vector<XY>& outline, double max_clearance) {
        // The owners in the timed calls hold the context handle beside the pointer: no
        // allocation, the same GEOS calls in the same order as destroying by hand.
        const GeomPtr hull(m_hull.make(outline), {m_ctx.get()});
        const shoal::geo::Box hb = box_of(outline);
        Answer a;
        double best = INFINITY;
        if (std::isfinite(max_clearance)) {
            best = nearest_within(hull.get(), hb, max_clearance);
        } else {
            // Unlimited: the same search in envelopes grown 250 m, 1 km, 4 km, ... until a
            // piece lies within the searched distance (GEOSSTRtree_nearest_generic with
            // GEOSDistance as the metric was 10-20x slower than this in this benchmark).
            for (double r = 250;; r *= 4) {
                best = nearest_within(hull.get(), hb, r);
                if (best <= r || r > m_span) break;
            }
        }
        if (best == 0) {
            a.collision = true;
            a.clearance = 0;
        } else if (on_land(outline.front())) {  // no coastline meets the hull: wholly land or water
            a.collision = true;
            a.clearance = 0;
        } else if (best <= max_clearance) {
            a.clearance = best;
        }
        return a;
    }

private:
    struct Piece {
        GeomPtr geom;
        shoal::geo::Box box;
    };
    struct Ring {
        GeomPtr geom;
        PreparedPtr prepared;  // of geom: declared after it, destroyed before it
        int sign = 1;
    };

    /// Smallest distance from the hull to a piece whose envelope lies within `r` of the
    /// hull's envelope (INFINITY if none): STRtree query, then exact distances, nearest
    /// envelope first, stopping as soon as no other piece can be nearer.
    double nearest_within(const GEOSGeometry* hull, const shoal::geo::Box& hb, double r) {
        const shoal::geo::Box q = hb.grown(r);
        GeomPtr rect(GEOSGeom_createRectangle_r(m_ctx, q.minx, q.miny, q.maxx, q.maxy), {m_ctx.get()});
        m_cand.clear();
        GEOSSTRtree_query_r(
            m_ctx, m_piece_tree.get(), rect.get(),
            [](void* item, void* self) { static_cast<GeosTree*>(self)->m_cand.push_back({0.0, static_cast<const Piece*>(item)}); },
            this);
        rect.reset();  // freed here, before the distances, as before
        for (auto& c : m_cand) c.first = hb.distance_to(c.second->box);
        std::sort(m_cand.begin(), m_cand.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        double best = INFINITY;
        for (const auto& [env_d, piece] : m_cand) {
            if (env_d > r || env_d >= best) break;
            double d = INFINITY;
            GEOSDistance_r(m_ctx, hull, piece->geom.get(), &d);
            best = std::min(best, d);
            if (best == 0) break;
        }
        return best;
    }

    bool on_land(XY p) {
        const GeomPtr pt(GEOSGeom_createPointFromXY_r(m_ctx, p.x, p.y), {m_ctx.get()});
        m_ring_cand.clear();
        GEOSSTRtree_query_r(
            m_ctx, m_ring_tree.get(), pt.get(), [](void* item, void* self) { static_cast<GeosTree*>(self)->m_ring_cand.push_back(static_cast<const Ring*>(item)); },
            this);
        int winding = 0;
        for (const Ring* r : m_ring_cand)
            if (GEOSPreparedIntersects_r(m_ctx, r->prepared.get(), pt.get()) == 1) winding += r->sign;
        return winding > 0;
    }

    shoal::geo::GeosContext m_ctx;
    HullPolygon m_hull;
    std::vector<Piece> m_pieces;  // own the trees' geometries: declared before the trees
    std::vector<Ring> m_rings;
    TreePtr m_piece_tree{nullptr, {m_ctx.get()}};
    TreePtr m_ring_tree{nullptr, {m_ctx.get()}};
    std::vector<std::pair<double, const Piece*>> m_cand;
    std::vector<const Ring*> m_ring_cand;
    double m_span = 0;  // diagonal of all pieces' envelope
};

/// The GEOS-only checker as the simplest careful design has it (issue 40): the land as prepared
/// polygons (each land shell with the holes it holds) in an STRtree. Per pose: the hull polygon;
/// the polygons whose envelopes meet the hull's, each asked GEOSPreparedIntersects (a
/// collision); else GEOSPreparedDistance to the polygons in the hull's envelope grown 250 m,
/// 1 km, 4 km, ... until one lies within the grown distance (or `max_clearance`). The same
/// answers as GeosTree.
class GeosPolygonTree {
public:
    explicit GeosPolygonTree(const std::vector<shoal::coast::LocalPolyline>& lines) : m_hull(m_ctx.get()) {
        std::vector<const std::vector<XY>*> shells, holes;
        for (const auto& l : lines) {
            if (!l.land_left || l.points.size() < 4 || l.points.front() != l.points.back()) continue;
            (signed_area2(l.points) > 0 ? shells : holes).push_back(&l.points);
        }
        // Each hole to the shell that holds its first point.
        std::vector<std::vector<std::vector<XY>>> rings(shells.size());
        std::vector<GeomPtr> plain;
        for (std::size_t i = 0; i < shells.size(); ++i) {
            rings[i].push_back(*shells[i]);
            plain.push_back(shoal::geo::make_polygon(m_ctx, {*shells[i]}));
        }
        for (const auto* h : holes) {
            const GeomPtr pt(GEOSGeom_createPointFromXY_r(m_ctx, h->front().x, h->front().y), {m_ctx.get()});
            for (std::size_t i = 0; i < shells.size(); ++i)
                if (GEOSContains_r(m_ctx, plain[i].get(), pt.get()) == 1) {
                    rings[i].push_back(*h);
                    break;
                }
        }
        shoal::geo::Box all;
        for (std::size_t i = 0; i < shells.size(); ++i) {
            Land land;
            land.geom = shoal::geo::make_polygon(m_ctx, rings[i]);
            land.prepared = PreparedPtr(GEOSPrepare_r(m_ctx, land.geom.get()), {m_ctx.get()});
            land.box = box_of(*shells[i]);
            all.extend(land.box);
            m_land.push_back(std::move(land));
        }
        m_span = std::hypot(all.maxx - all.minx, all.maxy - all.miny);
        m_tree = TreePtr(GEOSSTRtree_create_r(m_ctx, 10), {m_ctx.get()});
        for (Land& l : m_land) GEOSSTRtree_insert_r(m_ctx, m_tree.get(), l.geom.get(), &l);
        const GeomPtr probe(GEOSGeom_createPointFromXY_r(m_ctx, 0, 0), {m_ctx.get()});
        GEOSSTRtree_query_r(m_ctx, m_tree.get(), probe.get(), [](void*, void*) {}, nullptr);
    }
    GeosPolygonTree(const GeosPolygonTree&) = delete;
    GeosPolygonTree& operator=(const GeosPolygonTree&) = delete;

    Answer check(const std::vector<XY>& outline, double max_clearance) {
        const GeomPtr hull(m_hull.make(outline), {m_ctx.get()});
        const shoal::geo::Box hb = box_of(outline);
        Answer a;
        query(hb);
        for (const Land* l : m_cand)
            if (GEOSPreparedIntersects_r(m_ctx, l->prepared.get(), hull.get()) == 1) {
                a.collision = true;
                a.clearance = 0;
                return a;
            }
        double best = INFINITY;
        for (double r = std::isfinite(max_clearance) ? max_clearance : 250;; r *= 4) {
            query(hb.grown(r));
            for (const Land* l : m_cand) {
                double d = INFINITY;
                GEOSPreparedDistance_r(m_ctx, l->prepared.get(), hull.get(), &d);
                best = std::min(best, d);
            }
            if (std::isfinite(max_clearance) || best <= r || r > m_span) break;
        }
        if (best <= max_clearance) a.clearance = best;
        return a;
    }

private:
    struct Land {
        GeomPtr geom;
        PreparedPtr prepared;  // of geom: declared after it, destroyed before it
        shoal::geo::Box box;
    };
    void query(const shoal::geo::Box& q) {
        GeomPtr rect(GEOSGeom_createRectangle_r(m_ctx, q.minx, q.miny, q.maxx, q.maxy), {m_ctx.get()});
        m_cand.clear();
        GEOSSTRtree_query_r(
            m_ctx, m_tree.get(), rect.get(),
            [](void* item, void* self) { static_cast<GeosPolygonTree*>(self)->m_cand.push_back(static_cast<const Land*>(item)); }, this);
    }

    shoal::geo::GeosContext m_ctx;
    HullPolygon m_hull;
    std::vector<Land> m_land;  // owns the tree's geometries: declared before it
    TreePtr m_tree{nullptr, {m_ctx.get()}};
    std::vector<const Land*> m_cand;
    double m_span = 0;
};

}  // namespace shoal::bench
