#include "sweep/pose_outline.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geo/geos_context.hpp"

namespace shoal::audit {

std::vector<std::size_t> pose_outline_corners(const std::vector<geo::XY>& xy) {
    std::vector<std::size_t> all(xy.empty() ? 0 : xy.size() - 1);
    std::iota(all.begin(), all.end(), std::size_t{0});
    if (xy.size() < 4 || xy.size() <= pose_outline_min_corners + 1) return all;
    double length2 = 0;  // squared: one square root, not one per pair
    for (std::size_t i = 0; i + 1 < xy.size(); ++i)
        for (std::size_t j = i + 1; j + 1 < xy.size(); ++j) length2 = std::max(length2, geo::norm2(xy[i] - xy[j]));
    const double length = std::sqrt(length2);
    if (!(length > 0)) return all;

    thread_local geo::GeosContext ctx;
    // Douglas-Peucker (GEOSSimplify) on the outline as a closed line, a tenth of the cost of
    // the topology-preserving simplifier; kept when the ring it leaves is simple (valid) and
    // has enough corners, else the topology-preserving simplifier of the polygon. (As a line:
    // a polygon's simplification is "repaired" by GEOS, with new vertices.)
    const double tolerance = pose_outline_tolerance * length;
    std::vector<std::vector<std::vector<geo::XY>>> rings;
    {
        const geo::GeomPtr line = geo::make_linestring(ctx, xy.data(), xy.size());
        const geo::GeomPtr simple = geo::own(ctx, GEOSSimplify_r(ctx, line.get(), tolerance), "simplifying a hull outline");
        std::vector<std::vector<geo::XY>> lines;
        geo::collect_lines(ctx, simple.get(), lines);
        if (lines.size() == 1 && lines[0].size() >= pose_outline_min_corners + 1 && lines[0].front() == lines[0].back()) {
            const geo::GeomPtr simplified = geo::make_polygon(ctx, {lines[0]});
            if (GEOSisValid_r(ctx, simplified.get()) == 1) rings.push_back({lines[0]});
        }
    }
    if (rings.empty()) {
        const geo::GeomPtr poly = geo::make_polygon(ctx, {xy});
        const geo::GeomPtr simple = geo::own(ctx, GEOSTopologyPreserveSimplify_r(ctx, poly.get(), tolerance), "simplifying a hull outline");
        geo::collect_polygons(ctx, simple.get(), rings);
    }
    if (rings.size() != 1 || rings[0].empty()) return all;
    const std::vector<geo::XY>& kept = rings[0][0];
    if (kept.size() < pose_outline_min_corners + 1) return all;
    // The kept vertices are vertices of the outline, in its order (GEOS may start the ring
    // elsewhere or turn it): each is found again, so the drawn outline holds its own points.
    std::vector<bool> keep(xy.size(), false);
    for (const geo::XY& q : kept) {
        const auto at = std::find(xy.begin(), xy.end() - 1, q);
        if (at == xy.end() - 1) return all;  // not one of ours: keep the outline whole
        keep[static_cast<std::size_t>(at - xy.begin())] = true;
    }
    keep[0] = true;
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i + 1 < xy.size(); ++i)
        if (keep[i]) out.push_back(i);
    if (out.size() < pose_outline_min_corners) return all;
    return out;
}

}  // namespace shoal::audit
