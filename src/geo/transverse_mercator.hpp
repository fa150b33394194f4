#pragma once
/// `TransverseMercator`: shoal's own frame (WGS84 ellipsoid, scale 1, no false origin) computed
/// without PROJ, operation for operation as PROJ 9.1 computes the pipeline
///
///     +proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad
///                    +step +proj=tmerc +lat_0=.. +lon_0=.. +k=1 +x_0=0 +y_0=0 +ellps=WGS84
///
/// (the Poder/Engsager "exact" algorithm, PROJ's default: src/projections/tmerc.cpp; the steps
/// around it: fwd.cpp, inv.cpp, adjlon.cpp, ell_set.cpp, conversions/unitconvert.cpp). The same
/// numbers bit for bit, forward and inverse, and the same points refused (tests:
/// geo_test TransverseMercator.*), with no library to load: the `shoal` executable's probe of a
/// grid and a simulator's grid need neither PROJ's tree of shared libraries nor its database.
/// Its source is compiled without floating-point contraction (as PROJ's is, for x86-64), so a
/// build for a CPU with FMA gives the same numbers.

namespace shoal::geo {

class TransverseMercator {
public:
    /// Centred on (lat0_deg, lon0_deg), the numbers of the definition's text as strtod reads them.
    TransverseMercator(double lat0_deg, double lon0_deg);

    /// UTM zone `zone` (1-60) of WGS84, north or south: PROJ's `+proj=utm +zone=.. [+south]
    /// +ellps=WGS84` (tmerc.cpp PJ_PROJECTION(utm): its central meridian from the zone, scale
    /// 0.9996, false easting 500 km, false northing 10,000 km in the south), the numbers of EPSG's
    /// WGS 84 / UTM zones as PROJ computes them (geo_test TransverseMercator.UtmZonesAre*).
    static TransverseMercator utm(int zone, bool south);

    /// WGS84 degrees -> metres; false where PROJ gives no point (a latitude beyond the poles, a
    /// longitude beyond 10 radians, a point more than about 150 degrees from the centre).
    bool forward(double lon_deg, double lat_deg, double& x, double& y) const;
    /// Metres -> WGS84 degrees; false where PROJ gives no point.
    bool inverse(double x, double y, double& lon_deg, double& lat_deg) const;

private:
    static constexpr int order = 6;
    TransverseMercator(double phi0, double lam0, double k0, double x0, double y0);
    double m_x0 = 0;    ///< false easting, metres
    double m_y0 = 0;    ///< false northing, metres
    double m_lam0 = 0;  ///< central meridian, radians
    double m_a = 0;     ///< semi-major axis, metres
    double m_ra = 0;    ///< 1 / a
    double m_qn = 0;    ///< meridian quadrant, scaled to the projection
    double m_zb = 0;    ///< northing of the origin latitude
    double m_cgb[order]{};  ///< Gaussian -> geodetic latitude
    double m_cbg[order]{};  ///< geodetic -> Gaussian latitude
    double m_utg[order]{};  ///< transverse Mercator -> geographic
    double m_gtu[order]{};  ///< geographic -> transverse Mercator
};

}  // namespace shoal::geo
