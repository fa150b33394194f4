#include <shoal/geo/local_frame.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include <shoal/util/error.hpp>

#include "geo/crs_projection.hpp"
#include "geo/transverse_mercator.hpp"

namespace shoal::geo {

namespace {

std::string format_centre(LonLat c) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.5f%c %.5f%c", std::fabs(c.lon), c.lon < 0 ? 'W' : 'E', std::fabs(c.lat),
                  c.lat < 0 ? 'S' : 'N');
    return buf;
}

/// The text of shoal's own transverse Mercator frame centred on (lat, lon) (degrees).
std::string tmerc_definition(double lat, double lon) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "+proj=tmerc +lat_0=%.9f +lon_0=%.9f +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +towgs84=0,0,0 +units=m +no_defs", lat, lon);
    return buf;
}

/// PROJ, reading a PROJ string into a CRS, rounds an angle within about 1e-8 of a whole
/// degree to it (PROJ 9.1: 12.000000001 becomes 12); its pipeline, and so shoal's own
/// transverse Mercator, would not.
bool near_whole_degree(double v) {
    const double r = std::round(v);
    return v != r && std::fabs(v - r) <= 1.5e-8;
}

/// For exactly the text tmerc_definition() writes (a finite centre, not within 1.5e-8 of a
/// whole degree, written with decimal points): its centre (degrees), which shoal's own
/// transverse Mercator computes as PROJ computes the pipeline that PROJ's own search (WGS84 to
/// that CRS, lon/lat order) gives for it, degrees to radians then the projection, with the
/// definition's numbers: no PROJ, no search of its database (tests: the same numbers as the
/// searched operation, bit for bit, on random centres, centres a hair off whole degrees, and
/// points). Else nothing: PROJ reads the definition.
std::optional<LonLat> own_tmerc_centre(const std::string& definition) {
    double lat = NAN, lon = NAN;
    if (std::sscanf(definition.c_str(), "+proj=tmerc +lat_0=%lf +lon_0=%lf", &lat, &lon) != 2) return std::nullopt;
    if (!(std::fabs(lat) <= 90 && std::fabs(lon) <= 180) || near_whole_degree(lat) || near_whole_degree(lon)) return std::nullopt;
    if (definition != tmerc_definition(lat, lon)) return std::nullopt;
    // A locale with decimal commas (set by a program linking shoal) would have written "59,85",
    // which PROJ reads as 59: only the C locale's text is taken.
    if (definition.substr(0, definition.find(" +towgs84")).find(',') != std::string::npos) return std::nullopt;
    return LonLat{lon, lat};
}

}  // namespace

/// One of two ways: shoal's own transverse Mercator (no PROJ; thread-safe, as it is constants),
/// or a user's CRS by PROJ (which keeps an operation per thread).
struct LocalFrame::Impl {
    std::optional<TransverseMercator> tm;
    std::unique_ptr<detail::CrsProjection> crs;
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

LocalFrame::LocalFrame(std::string definition, std::string description, bool own_tmerc)
    : m_impl(std::make_unique<Impl>()), m_definition(std::move(definition)), m_description(std::move(description)) {
    if (own_tmerc) {
        if (const std::optional<LonLat> c = own_tmerc_centre(m_definition)) {
            m_impl->tm.emplace(c->lat, c->lon);
            return;
        }
    }
    m_impl->crs = detail::make_crs_projection(m_definition);
}

LocalFrame LocalFrame::transverse_mercator(LonLat centre) {
    return LocalFrame(tmerc_definition(centre.lat, centre.lon), "transverse Mercator centred on " + format_centre(centre), true);
}

LocalFrame LocalFrame::from_user_crs(const std::string& crs) {
    LocalFrame f(crs, "", false);
    const std::string& name = f.m_impl->crs ? f.m_impl->crs->name() : std::string();
    f.m_description = (name.empty() ? std::string("user CRS") : name) + " (" + crs + ")";
    return f;
}

LocalFrame LocalFrame::from_definition(const std::string& definition) {
    if (definition.rfind("+proj=tmerc", 0) == 0) {
        double lat = 0, lon = 0;
        if (std::sscanf(definition.c_str(), "+proj=tmerc +lat_0=%lf +lon_0=%lf", &lat, &lon) == 2)
            return LocalFrame(definition, "transverse Mercator centred on " + format_centre({lon, lat}), true);
    }
    return from_user_crs(definition);
}

bool LocalFrame::computed_by_shoal() const noexcept { return m_impl && m_impl->tm.has_value(); }

bool LocalFrame::is_own_transverse_mercator(const std::string& definition) { return own_tmerc_centre(definition).has_value(); }

LocalFrame::LocalFrame(const LocalFrame& other)
    : LocalFrame(other.m_definition, other.m_description, other.computed_by_shoal()) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
    if (this != &other) *this = LocalFrame(other);
    return *this;
}
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;
LocalFrame::~LocalFrame() = default;

XY LocalFrame::forward(LonLat p) const {
    double x = p.lon, y = p.lat;
    if (m_impl->tm)
        m_impl->tm->forward(p.lon, p.lat, x, y);
    else
        m_impl->crs->forward(&x, &y, 1);
    if (!std::isfinite(x) || !std::isfinite(y) || std::fabs(x) > 1e30) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "point (lon %.7f, lat %.7f) cannot be projected into the local frame", p.lon, p.lat);
        throw InputError(std::string(buf) + " (" + m_description + "); choose a frame that covers it with BuildRequest::crs");
    }
    return {x, y};
}

LonLat LocalFrame::inverse(XY p) const {
    double lon = p.x, lat = p.y;
    if (m_impl->tm)
        m_impl->tm->inverse(p.x, p.y, lon, lat);
    else
        m_impl->crs->inverse(lon, lat);
    if (!std::isfinite(lon) || !std::isfinite(lat) || std::fabs(lon) > 1e30) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "local point (%.3f, %.3f) m has no WGS84 position", p.x, p.y);
        throw InputError(buf);
    }
    return {lon, lat};
}

bool LocalFrame::forward(std::vector<double>& xs, std::vector<double>& ys, std::size_t* failed_index) const {
    const std::size_t n = xs.size();
    if (n == 0) return true;
    if (m_impl->tm) {
        for (std::size_t i = 0; i < n; ++i) m_impl->tm->forward(xs[i], ys[i], xs[i], ys[i]);
    } else {
        m_impl->crs->forward(xs.data(), ys.data(), n);
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(xs[i]) || !std::isfinite(ys[i]) || std::fabs(xs[i]) > 1e30 || std::fabs(ys[i]) > 1e30) {
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
