// coast::project (declared in <shoal/coast/coastline.hpp>): a coastline into the local frame.
// Apart from coastline.cpp (which reads charts with GDAL/OGR) so that the GDAL-free core the
// C API links (src/CMakeLists.txt: shoal_core) has CoastGrid::build without GDAL.

#include <shoal/coast/coastline.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <shoal/geo/local_frame.hpp>
#include <shoal/util/error.hpp>

namespace shoal::coast {

std::vector<LocalPolyline> project(const Coastline& coast, const geo::LocalFrame& frame) {
    std::vector<LocalPolyline> out;
    out.reserve(coast.polylines.size());
    std::vector<double> xs, ys;
    for (const Polyline& pl : coast.polylines) {
        xs.resize(pl.points.size());
        ys.resize(pl.points.size());
        for (std::size_t i = 0; i < pl.points.size(); ++i) { xs[i] = pl.points[i].lon; ys[i] = pl.points[i].lat; }
        std::size_t bad = 0;
        if (!frame.forward(xs, ys, &bad)) {
            const LayerStats& l = coast.layers.at(pl.layer);
            char buf[96];
            std::snprintf(buf, sizeof buf, " (lon %.6f, lat %.6f)", pl.points[bad].lon, pl.points[bad].lat);
            throw InputError("In '" + l.file + "' layer '" + l.layer + "' feature " + std::to_string(pl.fid) +
                             ": a vertex" + buf + " cannot be projected into the local frame (" + frame.description() +
                             "); choose a CRS that covers the data with BuildRequest::crs");
        }
        LocalPolyline lp;
        lp.land_left = pl.land_left;
        lp.hazard = pl.hazard;
        lp.points.resize(xs.size());
        for (std::size_t i = 0; i < xs.size(); ++i) lp.points[i] = {xs[i], ys[i]};
        lp.points.erase(std::unique(lp.points.begin(), lp.points.end()), lp.points.end());
        out.push_back(std::move(lp));
    }
    return out;
}

}  // namespace shoal::coast
