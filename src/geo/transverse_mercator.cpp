// shoal's own transverse Mercator: PROJ 9.1.1's computation of its pipeline, step for step (see
// the header). Each function names the PROJ function it follows; the expressions are PROJ's, in
// PROJ's order, so that the rounding is the same.
#include "geo/transverse_mercator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace shoal::geo {

namespace {

constexpr double deg_to_rad = .017453292519943296;  // proj_internal.h DEG_TO_RAD
constexpr double half_pi = M_PI_2;                    // M_HALFPI
constexpr double two_pi = 6.28318530717958647693;     // M_TWOPI
constexpr double eps_lat = 1e-12;                     // PJ_EPS_LAT
constexpr int order = 6;                              // PROJ_ETMERC_ORDER

/// adjlon.cpp: reduce to -pi..pi.
double adjlon(double lon) {
    if (std::fabs(lon) < M_PI + 1e-12) return lon;
    lon += M_PI;
    lon -= two_pi * std::floor(lon / two_pi);
    lon -= M_PI;
    return lon;
}

/// tmerc.cpp gatg.
inline double gatg(const double* p1, int len_p1, double B, double cos_2B, double sin_2B) {
    double h = 0, h1, h2 = 0;
    const double two_cos_2B = 2 * cos_2B;
    const double* p = p1 + len_p1;
    h1 = *--p;
    while (p - p1) {
        h = -h2 + two_cos_2B * h1 + *--p;
        h2 = h1;
        h1 = h;
    }
    return (B + h * sin_2B);
}

/// tmerc.cpp clenS: complex Clenshaw summation.
inline double clenS(const double* a, int size, double sin_arg_r, double cos_arg_r, double sinh_arg_i, double cosh_arg_i, double* R,
                    double* I) {
    double r, i, hr, hr1, hr2, hi, hi1, hi2;
    const double* p = a + size;
    r = 2 * cos_arg_r * cosh_arg_i;
    i = -2 * sin_arg_r * sinh_arg_i;
    hi1 = hr1 = hi = 0;
    hr = *--p;
    for (; a - p;) {
        hr2 = hr1;
        hi2 = hi1;
        hr1 = hr;
        hi1 = hi;
        hr = -hr2 + r * hr1 - i * hi1 + *--p;
        hi = -hi2 + i * hr1 + r * hi1;
    }
    r = sin_arg_r * cosh_arg_i;
    i = cos_arg_r * sinh_arg_i;
    *R = r * hr - i * hi;
    *I = r * hi + i * hr;
    return *R;
}

/// tmerc.cpp clens: real Clenshaw summation.
double clens(const double* a, int size, double arg_r) {
    double r, hr, hr1, hr2, cos_arg_r;
    const double* p = a + size;
    cos_arg_r = std::cos(arg_r);
    r = 2 * cos_arg_r;
    hr1 = 0;
    hr = *--p;
    for (; a - p;) {
        hr2 = hr1;
        hr1 = hr;
        hr = -hr2 + r * hr1 + *--p;
    }
    return std::sin(arg_r) * hr;
}

}  // namespace

// init.cpp: +lat_0, +lon_0 by dmstor (the number times DEG_TO_RAD), +k=1.
TransverseMercator::TransverseMercator(double lat0_deg, double lon0_deg) : TransverseMercator(lat0_deg * deg_to_rad, lon0_deg * deg_to_rad, 1., 0., 0.) {}

TransverseMercator TransverseMercator::utm(int zone, bool south) {
    if (zone < 1 || zone > 60) throw std::invalid_argument("UTM zone " + std::to_string(zone) + " is not 1 to 60");
    // tmerc.cpp PJ_PROJECTION(utm): x0, y0, the zone counted from 0, lam0, k0 = 0.9996, phi0 = 0.
    const int z = zone - 1;
    return TransverseMercator(0., (z + .5) * M_PI / 30. - M_PI, 0.9996, 500000., south ? 10000000. : 0.);
}

TransverseMercator::TransverseMercator(double phi0, double lam0, double k0, double x0, double y0) : m_x0(x0), m_y0(y0) {
    // ell_set.cpp, +ellps=WGS84 (a=6378137.0 rf=298.257223563): ellps_shape, then
    // pj_calc_ellipsoid_params.
    // The numbers of PROJ's table of ellipsoids ("a=6378137.0", "rf=298.257223563"), which it
    // reads with a correctly rounding strtod in the C locale: the same doubles as these literals.
    const double a = 6378137.0;
    const double rf = 298.257223563;
    const double f = 1 / rf;
    const double es = 2 * f - f * f;
    const double e = std::sqrt(es);
    const double alpha = std::asin(e);
    const double n = std::pow(std::tan(alpha / 2), 2);
    m_a = a;
    m_ra = 1. / a;
    m_lam0 = lam0;

    // tmerc.cpp setup_exact, as written there.
    double np = n;
    double* const cgb = m_cgb;
    double* const cbg = m_cbg;
    double* const utg = m_utg;
    double* const gtu = m_gtu;
    /* COEF. OF TRIG SERIES GEO <-> GAUSS */
    /* cgb := Gaussian -> Geodetic, KW p190 - 191 (61) - (62) */
    /* cbg := Geodetic -> Gaussian, KW p186 - 187 (51) - (52) */
    /* order = 6th degree : Engsager and Poder: ICC2007 */

    cgb[0] = n*( 2 + n*(-2/3.0  + n*(-2      + n*(116/45.0 + n*(26/45.0 +
                n*(-2854/675.0 ))))));
    cbg[0] = n*(-2 + n*( 2/3.0  + n*( 4/3.0  + n*(-82/45.0 + n*(32/45.0 +
                n*( 4642/4725.0))))));
    np     *= n;
    cgb[1] = np*(7/3.0 + n*( -8/5.0  + n*(-227/45.0 + n*(2704/315.0 +
                n*( 2323/945.0)))));
    cbg[1] = np*(5/3.0 + n*(-16/15.0 + n*( -13/9.0  + n*( 904/315.0 +
                n*(-1522/945.0)))));
    np     *= n;
    /* n^5 coeff corrected from 1262/105 -> -1262/105 */
    cgb[2] = np*( 56/15.0  + n*(-136/35.0 + n*(-1262/105.0 +
                n*( 73814/2835.0))));
    cbg[2] = np*(-26/15.0  + n*(  34/21.0 + n*(    8/5.0   +
                n*(-12686/2835.0))));
    np     *= n;
    /* n^5 coeff corrected from 322/35 -> 332/35 */
    cgb[3] = np*(4279/630.0 + n*(-332/35.0 + n*(-399572/14175.0)));
    cbg[3] = np*(1237/630.0 + n*( -12/5.0  + n*( -24832/14175.0)));
    np     *= n;
    cgb[4] = np*(4174/315.0 + n*(-144838/6237.0 ));
    cbg[4] = np*(-734/315.0 + n*( 109598/31185.0));
    np     *= n;
    cgb[5] = np*(601676/22275.0 );
    cbg[5] = np*(444337/155925.0);

    /* Constants of the projections */
    /* Transverse Mercator (UTM, ITM, etc) */
    np = n*n;
    /* Norm. mer. quad, K&W p.50 (96), p.19 (38b), p.5 (2) */
    m_qn = k0/(1 + n) * (1 + np*(1/4.0 + np*(1/64.0 + np/256.0)));
    /* coef of trig series */
    /* utg := ell. N, E -> sph. N, E,  KW p194 (65) */
    /* gtu := sph. N, E -> ell. N, E,  KW p196 (69) */
    utg[0] = n*(-0.5  + n*( 2/3.0 + n*(-37/96.0 + n*( 1/360.0 +
                n*(  81/512.0 + n*(-96199/604800.0))))));
    gtu[0] = n*( 0.5  + n*(-2/3.0 + n*(  5/16.0 + n*(41/180.0 +
                n*(-127/288.0 + n*(  7891/37800.0 ))))));
    utg[1] = np*(-1/48.0 + n*(-1/15.0 + n*(437/1440.0 + n*(-46/105.0 +
                n*( 1118711/3870720.0)))));
    gtu[1] = np*(13/48.0 + n*(-3/5.0  + n*(557/1440.0 + n*(281/630.0 +
                n*(-1983433/1935360.0)))));
    np      *= n;
    utg[2] = np*(-17/480.0 + n*(  37/840.0 + n*(  209/4480.0  +
                n*( -5569/90720.0 ))));
    gtu[2] = np*( 61/240.0 + n*(-103/140.0 + n*(15061/26880.0 +
                n*(167603/181440.0))));
    np      *= n;
    utg[3] = np*(-4397/161280.0 + n*(  11/504.0 + n*( 830251/7257600.0)));
    gtu[3] = np*(49561/161280.0 + n*(-179/168.0 + n*(6601661/7257600.0)));
    np     *= n;
    utg[4] = np*(-4583/161280.0 + n*(  108847/3991680.0));
    gtu[4] = np*(34729/80640.0  + n*(-3418889/1995840.0));
    np     *= n;
    utg[5] = np*(-20648693/638668800.0);
    gtu[5] = np*(212378941/319334400.0);

    /* Gaussian latitude value of the origin latitude */
    const double Z = gatg (cbg, order, phi0, std::cos(2*phi0), std::sin(2*phi0));

    /* Origin northing minus true northing at the origin latitude */
    /* i.e. true northing = N - P->Zb                         */
    m_zb  = - m_qn*(Z + clens(gtu, order, 2*Z));
}

bool TransverseMercator::forward(double lon_deg, double lat_deg, double& x, double& y) const {
    x = y = HUGE_VAL;
    if (HUGE_VAL == lon_deg || HUGE_VAL == lat_deg) return false;  // fwd.cpp fwd_prepare
    // unitconvert.cpp forward_2d: degrees to radians.
    double lam = lon_deg * deg_to_rad;
    double phi = lat_deg * deg_to_rad;
    // fwd.cpp fwd_prepare, angular input.
    const double t = (phi < 0 ? -phi : phi) - half_pi;
    if (t > eps_lat) return false;
    if (lam > 10 || lam < -10) return false;
    if (phi > half_pi) phi = half_pi;
    if (phi < -half_pi) phi = -half_pi;
    lam = adjlon(lam);
    lam = (lam - 0.0) - m_lam0;  // from_greenwich 0
    lam = adjlon(lam);

    // tmerc.cpp exact_e_fwd.
    double Cn = gatg(m_cbg, order, phi, std::cos(2 * phi), std::sin(2 * phi));
    const double sin_Cn = std::sin(Cn);
    const double cos_Cn = std::cos(Cn);
    const double sin_Ce = std::sin(lam);
    const double cos_Ce = std::cos(lam);
    const double cos_Cn_cos_Ce = cos_Cn * cos_Ce;
    Cn = std::atan2(sin_Cn, cos_Cn_cos_Ce);
    const double inv_denom_tan_Ce = 1. / std::hypot(sin_Cn, cos_Cn_cos_Ce);
    const double tan_Ce = sin_Ce * cos_Cn * inv_denom_tan_Ce;
    double Ce = std::asinh(tan_Ce);
    const double two_inv_denom_tan_Ce = 2 * inv_denom_tan_Ce;
    const double two_inv_denom_tan_Ce_square = two_inv_denom_tan_Ce * inv_denom_tan_Ce;
    const double tmp_r = cos_Cn_cos_Ce * two_inv_denom_tan_Ce_square;
    const double sin_arg_r = sin_Cn * tmp_r;
    const double cos_arg_r = cos_Cn_cos_Ce * tmp_r - 1;
    const double sinh_arg_i = tan_Ce * two_inv_denom_tan_Ce;
    const double cosh_arg_i = two_inv_denom_tan_Ce_square - 1;
    double dCn, dCe;
    Cn += clenS(m_gtu, order, sin_arg_r, cos_arg_r, sinh_arg_i, cosh_arg_i, &dCn, &dCe);
    Ce += dCe;
    if (!(std::fabs(Ce) <= 2.623395162778)) return false;
    double px = m_qn * Ce;        // easting
    double py = m_qn * Cn + m_zb;  // northing
    if (HUGE_VAL == px) return false;  // fwd.cpp pj_fwd4d
    // fwd.cpp fwd_finalize, classic units: times a, then the false origin and units (1).
    px *= m_a;
    py *= m_a;
    x = 1. * (px + m_x0);
    y = 1. * (py + m_y0);
    return true;
}

bool TransverseMercator::inverse(double x, double y, double& lon_deg, double& lat_deg) const {
    lon_deg = lat_deg = HUGE_VAL;
    // inv.cpp inv_prepare, classic units.
    if (x == HUGE_VAL || y == HUGE_VAL) return false;
    double px = 1. * x - m_x0;
    double py = 1. * y - m_y0;
    px *= m_ra;
    py *= m_ra;

    // tmerc.cpp exact_e_inv.
    double Cn = (py - m_zb) / m_qn;
    double Ce = px / m_qn;
    if (!(std::fabs(Ce) <= 2.623395162778)) return false;
    const double sin_arg_r = std::sin(2 * Cn);
    const double cos_arg_r = std::cos(2 * Cn);
    const double exp_2_Ce = std::exp(2 * Ce);
    const double half_inv_exp_2_Ce = 0.5 / exp_2_Ce;
    const double sinh_arg_i = 0.5 * exp_2_Ce - half_inv_exp_2_Ce;
    const double cosh_arg_i = 0.5 * exp_2_Ce + half_inv_exp_2_Ce;
    double dCn_ignored, dCe;
    Cn += clenS(m_utg, order, sin_arg_r, cos_arg_r, sinh_arg_i, cosh_arg_i, &dCn_ignored, &dCe);
    Ce += dCe;
    const double sin_Cn = std::sin(Cn);
    const double cos_Cn = std::cos(Cn);
    const double sinhCe = std::sinh(Ce);
    Ce = std::atan2(sinhCe, cos_Cn);
    const double modulus_Ce = std::hypot(sinhCe, cos_Cn);
    Cn = std::atan2(sin_Cn, modulus_Ce);
    const double tmp = 2 * modulus_Ce / (sinhCe * sinhCe + 1);
    const double sin_2_Cn = sin_Cn * tmp;
    const double cos_2_Cn = tmp * modulus_Ce - 1.;
    const double phi = gatg(m_cgb, order, Cn, cos_2_Cn, sin_2_Cn);
    double lam = Ce;
    if (HUGE_VAL == lam) return false;  // inv.cpp pj_inv4d
    // inv.cpp inv_finalize, angular output.
    lam = lam + 0.0 + m_lam0;
    lam = adjlon(lam);
    // unitconvert.cpp reverse_2d: radians to degrees.
    lon_deg = lam / deg_to_rad;
    lat_deg = phi / deg_to_rad;
    return true;
}

}  // namespace shoal::geo
