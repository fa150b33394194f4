#include "geo/local_frame.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <ogr_spatialref.h>

#include "util/error.hpp"

namespace shoal::geo {

namespace {

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const noexcept { OGRCoordinateTransformation::DestroyCT(t); }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

OGRSpatialReference wgs84() {
    OGRSpatialReference srs;
    srs.SetWellKnownGeogCS("WGS84");
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

std::string format_centre(LonLat c) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.5f%c %.5f%c", std::fabs(c.lon), c.lon < 0 ? 'W' : 'E', std::fabs(c.lat),
                  c.lat < 0 ? 'S' : 'N');
    return buf;
}

}  // namespace

struct LocalFrame::Impl {
    OGRSpatialReference local;
    TransformPtr to_local;
    TransformPtr to_wgs84;
};

Eigen::Vector2d metres_per_degree(double lat_deg) {
    // WGS84 radii of curvature: meridional M and prime vertical N.
    constexpr double a = 6378137.0;
    constexpr double f = 1.0 / 298.257223563;
    constexpr double e2 = f * (2 - f);
    const double phi = lat_deg * std::numbers::pi / 180.0;
    const double s = std::sin(phi);
    const double w = std::sqrt(1 - e2 * s * s);
    const double n = a / w;
    const double m = a * (1 - e2) / (w * w * w);
    const double rad = std::numbers::pi / 180.0;
    return {n * std::cos(phi) * rad, m * rad};  // (per degree lon, per degree lat)
}

LocalFrame::LocalFrame(std::string definition, std::string description)
    : m_impl(std::make_unique<Impl>()), m_definition(std::move(definition)), m_description(std::move(description)) {
    if (m_impl->local.SetFromUserInput(m_definition.c_str()) != OGRERR_NONE)
        throw UsageError("CRS '" + m_definition + "' is not one GDAL understands");
    if (!m_impl->local.IsProjected())
        throw UsageError("CRS '" + m_definition + "' is not a projected CRS in metres; give a projected one (e.g. a UTM zone)");
    m_impl->local.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    const OGRSpatialReference geo = wgs84();
    m_impl->to_local.reset(OGRCreateCoordinateTransformation(&geo, &m_impl->local));
    m_impl->to_wgs84.reset(OGRCreateCoordinateTransformation(&m_impl->local, &geo));
    if (!m_impl->to_local || !m_impl->to_wgs84)
        throw UsageError("no transformation between WGS84 and CRS '" + m_definition + "'");
}

LocalFrame LocalFrame::transverse_mercator(LonLat centre) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "+proj=tmerc +lat_0=%.9f +lon_0=%.9f +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +towgs84=0,0,0 +units=m +no_defs",
                  centre.lat, centre.lon);
    return LocalFrame(buf, "transverse Mercator centred on " + format_centre(centre));
}

LocalFrame LocalFrame::from_user_crs(const std::string& crs) {
    LocalFrame f(crs, "");
    const char* name = f.m_impl->local.GetName();
    f.m_description = std::string(name ? name : "user CRS") + " (" + crs + ")";
    return f;
}

LocalFrame LocalFrame::from_definition(const std::string& definition) {
    if (definition.rfind("+proj=tmerc", 0) == 0) {
        double lat = 0, lon = 0;
        if (std::sscanf(definition.c_str(), "+proj=tmerc +lat_0=%lf +lon_0=%lf", &lat, &lon) == 2)
            return LocalFrame(definition, "transverse Mercator centred on " + format_centre({lon, lat}));
    }
    return from_user_crs(definition);
}

LocalFrame::LocalFrame(const LocalFrame& other) : LocalFrame(other.m_definition, other.m_description) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
    if (this != &other) *this = LocalFrame(other);
    return *this;
}
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;
LocalFrame::~LocalFrame() = default;

XY LocalFrame::forward(LonLat p) const {
    double x = p.lon, y = p.lat;
    int ok = 0;
    if (!m_impl->to_local->Transform(1, &x, &y, nullptr, &ok) || !ok || !std::isfinite(x) || !std::isfinite(y)) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "point (lon %.7f, lat %.7f) cannot be projected into the local frame", p.lon, p.lat);
        throw InputError(std::string(buf) + " (" + m_description + "); choose a frame that covers it with --crs");
    }
    return {x, y};
}

LonLat LocalFrame::inverse(XY p) const {
    double x = p.x, y = p.y;
    int ok = 0;
    if (!m_impl->to_wgs84->Transform(1, &x, &y, nullptr, &ok) || !ok) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "local point (%.3f, %.3f) m has no WGS84 position", p.x, p.y);
        throw InputError(buf);
    }
    return {x, y};
}

bool LocalFrame::forward(std::vector<double>& xs, std::vector<double>& ys, std::size_t* failed_index) const {
    const std::size_t n = xs.size();
    if (n == 0) return true;
    std::vector<int> ok(n, 0);
    m_impl->to_local->Transform(n, xs.data(), ys.data(), nullptr, ok.data());
    for (std::size_t i = 0; i < n; ++i) {
        if (!ok[i] || !std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
            if (failed_index) *failed_index = i;
            return false;
        }
    }
    return true;
}

Eigen::Matrix2d LocalFrame::jacobian(LonLat p) const {
    const double h = 1.0;  // metres on the ellipsoid; central difference
    const Eigen::Vector2d mpd = metres_per_degree(p.lat);
    const double dlon = h / mpd.x(), dlat = h / mpd.y();
    const XY e1 = forward({p.lon + dlon, p.lat}), e0 = forward({p.lon - dlon, p.lat});
    const XY n1 = forward({p.lon, p.lat + dlat}), n0 = forward({p.lon, p.lat - dlat});
    Eigen::Matrix2d j;
    j << (e1.x - e0.x) / (2 * h), (n1.x - n0.x) / (2 * h), (e1.y - e0.y) / (2 * h), (n1.y - n0.y) / (2 * h);
    return j;
}

double LocalFrame::max_scale_error(LonLat min, LonLat max) const {
    double worst = 0;
    constexpr int steps = 8;
    for (int i = 0; i <= steps; ++i) {
        for (int j = 0; j <= steps; ++j) {
            const LonLat p{min.lon + (max.lon - min.lon) * i / steps, min.lat + (max.lat - min.lat) * j / steps};
            try {
                const Eigen::Matrix2d jac = jacobian(p);
                // Scale along each axis; for a conformal frame both equal the point scale k.
                worst = std::max({worst, std::fabs(jac.col(0).norm() - 1), std::fabs(jac.col(1).norm() - 1)});
            } catch (const InputError&) {
                return INFINITY;
            }
        }
    }
    return worst;
}

}  // namespace shoal::geo
