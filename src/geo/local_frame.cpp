#include <shoal/geo/local_frame.hpp>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <thread>
#include <proj.h>

#include <shoal/util/error.hpp>

namespace shoal::geo {

namespace {

std::string format_centre(LonLat c) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.5f%c %.5f%c", std::fabs(c.lon), c.lon < 0 ? 'W' : 'E', std::fabs(c.lat),
                  c.lat < 0 ? 'S' : 'N');
    return buf;
}

/// WGS84 lon/lat (degrees) -> local x/y (metres) in `ctx`, or null.
PJ* make_operation(PJ_CONTEXT* ctx, const std::string& local_wkt) {
    PJ* op = proj_create_crs_to_crs(ctx, "EPSG:4326", local_wkt.c_str(), nullptr);
    if (!op) return nullptr;
    PJ* normalised = proj_normalize_for_visualization(ctx, op);  // lon, lat order in; x, y out
    proj_destroy(op);
    return normalised;
}

/// A PROJ context and operation of one thread's own.
struct Projection {
    PJ_CONTEXT* ctx = nullptr;
    PJ* op = nullptr;
    Projection() = default;
    Projection(const Projection&) = delete;
    Projection& operator=(const Projection&) = delete;
    ~Projection() { reset(); }
    void reset() noexcept {
        if (op) proj_destroy(op);
        if (ctx) proj_context_destroy(ctx);
        op = nullptr;
        ctx = nullptr;
    }
    /// Makes the operation in a new context: from `pipeline` (a PROJ pipeline string) when it
    /// is not empty, else by PROJ's search for one to `local_wkt`; false if PROJ cannot.
    bool make(const std::string& pipeline, const std::string& local_wkt) {
        reset();
        ctx = proj_context_create();
        proj_log_level(ctx, PJ_LOG_NONE);
        if (!pipeline.empty()) {
            proj_context_set_file_finder(ctx, no_resource_files, nullptr);
            // PROJ 9.1 says it found no proj.db through the logger whatever the log level
            // (c_api.cpp's proj_log_debug calls it directly): none of it on our stderr.
            proj_log_func(ctx, nullptr, [](void*, int, const char*) {});
        }
        op = pipeline.empty() ? make_operation(ctx, local_wkt) : proj_create(ctx, pipeline.c_str());
        return op != nullptr;
    }

    /// A PROJ file finder that finds nothing: every resource file (proj.db, grids, init files)
    /// is "at" a path that cannot exist (a file under /dev/null). The pipeline of shoal's own
    /// transverse Mercator (unit conversion, then tmerc on the WGS84 ellipsoid) needs none, but
    /// PROJ 9.1's proj_create opens proj.db for any coordinate operation it makes (c_api.cpp,
    /// pj_obj_create: the database only given to the formatter that writes the operation back
    /// as the PROJ string it then instantiates, which for these steps it does not consult):
    /// 26 M instructions, a third of a 1-pose probe. With no database found, PROJ makes the
    /// same operation from the same string (tests: bit for bit the searched operation's numbers).
    static const char* no_resource_files(PJ_CONTEXT*, const char*, void*) { return "/dev/null/shoal-frame-needs-no-proj-files"; }
};

/// The text of shoal's own transverse Mercator frame centred on (lat, lon) (degrees).
std::string tmerc_definition(double lat, double lon) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "+proj=tmerc +lat_0=%.9f +lon_0=%.9f +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +towgs84=0,0,0 +units=m +no_defs", lat, lon);
    return buf;
}

/// PROJ, reading a PROJ string into a CRS, rounds an angle within about 1e-8 of a whole
/// degree to it (PROJ 9.1: 12.000000001 becomes 12); the pipeline below would not.
bool near_whole_degree(double v) {
    const double r = std::round(v);
    return v != r && std::fabs(v - r) <= 1.5e-8;
}

/// For exactly the text tmerc_definition() writes (a finite centre, not within 1.5e-8 of a
/// whole degree, written with decimal points): the PROJ pipeline that PROJ's own search (WGS84
/// to that CRS, lon/lat order) gives for it, degrees to radians then the projection, with the
/// definition's numbers. Made from it, a frame needs no GDAL parse of the CRS (which opens
/// PROJ's database in a context of its own) and no search: a tenth of the instructions a run
/// spends before its first row (tests: the same numbers as the searched operation, bit for
/// bit, on random centres, centres a hair off whole degrees, and points). Else "".
std::string own_tmerc_pipeline(const std::string& definition) {
    double lat = NAN, lon = NAN;
    if (std::sscanf(definition.c_str(), "+proj=tmerc +lat_0=%lf +lon_0=%lf", &lat, &lon) != 2) return "";
    if (!(std::fabs(lat) <= 90 && std::fabs(lon) <= 180) || near_whole_degree(lat) || near_whole_degree(lon)) return "";
    if (definition != tmerc_definition(lat, lon)) return "";
    // The projection's step is the definition up to its datum shift (a null one, which the
    // search drops). A locale with decimal commas (set by a program linking shoal) would have
    // written "59,85", which PROJ reads as 59: only the C locale's text is taken.
    const std::string tmerc = definition.substr(0, definition.find(" +towgs84"));
    if (tmerc.find(',') != std::string::npos) return "";
    return "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad +step " + tmerc;
}

std::atomic<std::uint64_t> next_frame_serial{1};

/// The user's CRS as PROJ reads it (what GDAL's SetFromUserInput hands PROJ for the same text:
/// "EPSG:32633", a URN, WKT, PROJJSON, a name, or a PROJ string, made a CRS with +type=crs as
/// GDAL does). PROJ only, no GDAL: the grid-loading path (libshoal_c) needs no GDAL at run time.
struct UserCrs {
    std::string wkt;   ///< WKT2_2019, for the operation from WGS84
    std::string name;  ///< the CRS's name, or ""
};

/// The horizontal CRS of `crs` (a bound CRS's source, a compound CRS's first component) is
/// projected. Takes ownership of nothing.
bool is_projected(PJ_CONTEXT* ctx, const PJ* crs) {
    switch (proj_get_type(crs)) {
    case PJ_TYPE_PROJECTED_CRS: return true;
    case PJ_TYPE_BOUND_CRS: {
        PJ* base = proj_get_source_crs(ctx, crs);
        const bool p = base && is_projected(ctx, base);
        if (base) proj_destroy(base);
        return p;
    }
    case PJ_TYPE_COMPOUND_CRS: {
        PJ* horizontal = proj_crs_get_sub_crs(ctx, crs, 0);
        const bool p = horizontal && is_projected(ctx, horizontal);
        if (horizontal) proj_destroy(horizontal);
        return p;
    }
    default: return false;
    }
}

/// Throws UsageError naming `text` when PROJ cannot read it as a CRS, or it is not projected.
UserCrs read_user_crs(const std::string& text) {
    std::string input = text;
    const auto first = input.find_first_not_of(" \t\n");
    if (first != std::string::npos && input[first] == '+' && input.find("+type=crs") == std::string::npos) input += " +type=crs";
    PJ_CONTEXT* ctx = proj_context_create();
    proj_log_level(ctx, PJ_LOG_NONE);  // PROJ's complaint about a bad definition: the error below says it
    if (input.find("+init=") != std::string::npos) proj_context_use_proj4_init_rules(ctx, 1);  // "+init=epsg:32633", as GDAL reads it
    PJ* crs = input.empty() ? nullptr : proj_create(ctx, input.c_str());
    UserCrs out;
    const bool is_crs = crs && proj_is_crs(crs);
    const bool projected = is_crs && is_projected(ctx, crs);
    if (projected) {
        const char* const options[] = {"MULTILINE=NO", nullptr};
        const char* wkt = proj_as_wkt(ctx, crs, PJ_WKT2_2019, options);
        out.wkt = wkt ? wkt : "";
        const char* name = proj_get_name(crs);
        out.name = name ? name : "";
    }
    if (crs) proj_destroy(crs);
    proj_context_destroy(ctx);
    if (!is_crs) throw UsageError("CRS '" + text + "' is not one GDAL understands");
    if (!projected) throw UsageError("CRS '" + text + "' is not a projected CRS in metres; give a projected one (e.g. a UTM zone)");
    if (out.wkt.empty()) throw UsageError("CRS '" + text + "' cannot be written as WKT");
    return out;
}

}  // namespace

/// PROJ reads the user's CRS and runs the transformations (no GDAL). A PROJ
/// object must not be used by two threads at once, so the thread that made the frame uses the
/// frame's own, and any other thread a copy of its own, made on its first use there and kept in
/// a small per-thread cache keyed by the frame's serial number (never reused). A frame (and the
/// grid or detector holding it) may then be used by several threads at once, with no lock.
struct LocalFrame::Impl {
    std::string local_name;  ///< the user CRS's name; empty for shoal's own transverse Mercator (pipeline set)
    std::string local_wkt;
    std::string pipeline;  ///< own_tmerc_pipeline() of the definition, or ""
    Projection own;
    std::thread::id owner = std::this_thread::get_id();
    std::uint64_t serial = next_frame_serial.fetch_add(1, std::memory_order_relaxed);

    /// The operation for the calling thread.
    PJ* op() const {
        if (std::this_thread::get_id() == owner) return own.op;
        struct Slot {
            std::uint64_t serial = 0;
            Projection projection;
        };
        thread_local std::array<Slot, 4> slots;
        thread_local unsigned next = 0;
        for (Slot& s : slots)
            if (s.serial == serial) return s.projection.op;
        Slot& s = slots[next++ % slots.size()];
        s.serial = 0;
        if (!s.projection.make(pipeline, local_wkt)) throw InputError("PROJ cannot make the transformation to the local frame on this thread");
        s.serial = serial;
        return s.projection.op;
    }
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
    if (own_tmerc) m_impl->pipeline = own_tmerc_pipeline(m_definition);
    if (!m_impl->pipeline.empty()) {
        if (!m_impl->own.make(m_impl->pipeline, "")) throw UsageError("PROJ cannot make the transverse Mercator '" + m_definition + "'");
        return;
    }
    UserCrs crs = read_user_crs(m_definition);
    m_impl->local_wkt = std::move(crs.wkt);
    m_impl->local_name = std::move(crs.name);
    if (!m_impl->own.make("", m_impl->local_wkt)) throw UsageError("no transformation between WGS84 and CRS '" + m_definition + "'");
}

LocalFrame LocalFrame::transverse_mercator(LonLat centre) {
    return LocalFrame(tmerc_definition(centre.lat, centre.lon), "transverse Mercator centred on " + format_centre(centre), true);
}

LocalFrame LocalFrame::from_user_crs(const std::string& crs) {
    LocalFrame f(crs, "", false);
    const std::string& name = f.m_impl->local_name;
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

bool LocalFrame::made_from_pipeline() const noexcept { return m_impl && !m_impl->pipeline.empty(); }

LocalFrame::LocalFrame(const LocalFrame& other)
    : LocalFrame(other.m_definition, other.m_description, other.made_from_pipeline()) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
    if (this != &other) *this = LocalFrame(other);
    return *this;
}
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;
LocalFrame::~LocalFrame() = default;

XY LocalFrame::forward(LonLat p) const {
    const PJ_COORD c = proj_trans(m_impl->op(), PJ_FWD, proj_coord(p.lon, p.lat, 0, 0));
    if (!std::isfinite(c.xy.x) || !std::isfinite(c.xy.y) || std::fabs(c.xy.x) > 1e30) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "point (lon %.7f, lat %.7f) cannot be projected into the local frame", p.lon, p.lat);
        throw InputError(std::string(buf) + " (" + m_description + "); choose a frame that covers it with BuildRequest::crs");
    }
    return {c.xy.x, c.xy.y};
}

LonLat LocalFrame::inverse(XY p) const {
    const PJ_COORD c = proj_trans(m_impl->op(), PJ_INV, proj_coord(p.x, p.y, 0, 0));
    if (!std::isfinite(c.lp.lam) || !std::isfinite(c.lp.phi) || std::fabs(c.lp.lam) > 1e30) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "local point (%.3f, %.3f) m has no WGS84 position", p.x, p.y);
        throw InputError(buf);
    }
    return {c.lp.lam, c.lp.phi};
}

bool LocalFrame::forward(std::vector<double>& xs, std::vector<double>& ys, std::size_t* failed_index) const {
    const std::size_t n = xs.size();
    if (n == 0) return true;
    proj_trans_generic(m_impl->op(), PJ_FWD, xs.data(), sizeof(double), n, ys.data(), sizeof(double), n, nullptr, 0, 0,
                       nullptr, 0, 0);
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
