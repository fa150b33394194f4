#pragma once
/// `LocalFrame`: the one projected frame of a run. WGS84 lon/lat <-> local metres, by
/// default a transverse Mercator centred on the data, or any CRS GDAL understands.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include <shoal/geo/point.hpp>


namespace shoal::geo {

class LocalFrame {
public:
    /// Transverse Mercator (WGS84 ellipsoid, scale 1) with its origin at `centre`.
    static LocalFrame transverse_mercator(LonLat centre);
    /// Any projected CRS GDAL understands ("EPSG:32633", a PROJ string, WKT). Throws
    /// UsageError naming the text when GDAL cannot use it or it is geographic.
    static LocalFrame from_user_crs(const std::string& crs);
    /// Rebuilds a frame from `definition()` (as stored in a grid cache).
    static LocalFrame from_definition(const std::string& definition);

    LocalFrame(LocalFrame&&) noexcept;
    LocalFrame& operator=(LocalFrame&&) noexcept;
    LocalFrame(const LocalFrame& other);
    LocalFrame& operator=(const LocalFrame& other);
    ~LocalFrame();

    /// WGS84 -> local metres. Throws InputError when PROJ cannot project the point.
    XY forward(LonLat p) const;
    LonLat inverse(XY p) const;
    /// In-place batch versions; return false (leaving values undefined) if any point failed,
    /// with the index of the first failure in `*failed_index`.
    bool forward(std::vector<double>& lon_to_x, std::vector<double>& lat_to_y, std::size_t* failed_index) const;

    /// The linear map from (east, north) metres on the ellipsoid at `p` to local (x, y) metres:
    /// scale and meridian convergence of the projection at p, from a central difference.
    Eigen::Matrix2d jacobian(LonLat p) const;

    /// Text that `from_definition` accepts (a PROJ string or WKT).
    const std::string& definition() const noexcept { return m_definition; }
    /// Human-readable description, e.g. "transverse Mercator centred on 23.91E 60.10N".
    const std::string& description() const noexcept { return m_description; }

    /// Whether the frame is computed by shoal's own transverse Mercator (PROJ's numbers for the
    /// pipeline of that projection, bit for bit, without PROJ): for tests and diagnostics.
    bool computed_by_shoal() const noexcept;
    /// Whether a frame made from `definition` is shoal's own transverse Mercator, which needs no
    /// PROJ (any other CRS is read and transformed by PROJ).
    static bool is_own_transverse_mercator(const std::string& definition);

    /// Largest relative scale error of the frame over the lon/lat box, sampled on a grid.
    double max_scale_error(LonLat min, LonLat max) const;

private:
    /// `own_tmerc`: the definition may be shoal's own transverse Mercator, made without GDAL.
    LocalFrame(std::string definition, std::string description, bool own_tmerc);
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    std::string m_definition;
    std::string m_description;
};

/// Metres per degree of latitude and of longitude at latitude `lat_deg` on WGS84.
Eigen::Vector2d metres_per_degree(double lat_deg);

}  // namespace shoal::geo
