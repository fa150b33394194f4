// A user's CRS for LocalFrame, by PROJ (no GDAL): geo/crs_projection.hpp.
#include "geo/crs_projection.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <thread>
#include <proj.h>

#include <shoal/util/error.hpp>

#include "util/lazy_libraries.hpp"

namespace shoal::geo::detail {

namespace {

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
    /// Makes PROJ's operation to `local_wkt` in a new context; false if PROJ cannot.
    bool make(const std::string& local_wkt) {
        reset();
        ctx = proj_context_create();
        proj_log_level(ctx, PJ_LOG_NONE);
        op = make_operation(ctx, local_wkt);
        return op != nullptr;
    }
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

/// The user's CRS as PROJ reads it (what GDAL's SetFromUserInput hands PROJ for the same text:
/// "EPSG:32633", a URN, WKT, PROJJSON, a name, or a PROJ string, made a CRS with +type=crs as
/// GDAL does). PROJ only, no GDAL: the grid-loading path (libshoal_c) needs no GDAL at run time.
struct UserCrs {
    std::string wkt;   ///< WKT2_2019, for the operation from WGS84
    std::string name;  ///< the CRS's name, or ""
};

/// Throws UsageError naming `text` when PROJ cannot read it as a CRS, or it is not projected.
UserCrs read_user_crs(const std::string& text) {
    shoal::detail::need_proj();  // loaded first when this program was linked without it (util/lazy_libraries.hpp)
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

std::atomic<std::uint64_t> next_serial{1};

/// A PROJ object must not be used by two threads at once, so the thread that made the
/// projection uses its own operation, and any other thread a copy of its own, made on its first
/// use there and kept in a small per-thread cache keyed by the projection's serial number (never
/// reused). A frame (and the grid or detector holding it) may then be used by several threads
/// at once, with no lock.
class ProjProjection final : public CrsProjection {
public:
    explicit ProjProjection(const std::string& definition) {
        UserCrs crs = read_user_crs(definition);
        m_wkt = std::move(crs.wkt);
        m_name = std::move(crs.name);
        if (!m_own.make(m_wkt)) throw UsageError("no transformation between WGS84 and CRS '" + definition + "'");
    }
    const std::string& name() const override { return m_name; }
    void forward(double* xs, double* ys, std::size_t n) const override {
        // A point alone is given the time a batch's points get (none: HUGE_VAL, the
        // operation's own epoch), so that a time-dependent step places it as in a batch (time
        // 0 would be the year 0).
        if (n == 1) {
            const PJ_COORD c = proj_trans(op(), PJ_FWD, proj_coord(*xs, *ys, 0, HUGE_VAL));
            *xs = c.xy.x;
            *ys = c.xy.y;
            return;
        }
        proj_trans_generic(op(), PJ_FWD, xs, sizeof(double), n, ys, sizeof(double), n, nullptr, 0, 0, nullptr, 0, 0);
    }
    void inverse(double& x, double& y) const override {
        const PJ_COORD c = proj_trans(op(), PJ_INV, proj_coord(x, y, 0, HUGE_VAL));
        x = c.lp.lam;
        y = c.lp.phi;
    }

private:
    /// The operation for the calling thread.
    PJ* op() const {
        if (std::this_thread::get_id() == m_owner) return m_own.op;
        struct Slot {
            std::uint64_t serial = 0;
            Projection projection;
        };
        thread_local std::array<Slot, 4> slots;
        thread_local unsigned next = 0;
        for (Slot& s : slots)
            if (s.serial == m_serial) return s.projection.op;
        Slot& s = slots[next++ % slots.size()];
        s.serial = 0;
        if (!s.projection.make(m_wkt)) throw InputError("PROJ cannot make the transformation to the local frame on this thread");
        s.serial = m_serial;
        return s.projection.op;
    }

    std::string m_wkt;
    std::string m_name;
    Projection m_own;
    std::thread::id m_owner = std::this_thread::get_id();
    std::uint64_t m_serial = next_serial.fetch_add(1, std::memory_order_relaxed);
};

}  // namespace

std::unique_ptr<CrsProjection> make_crs_projection(const std::string& definition) {
    shoal::detail::need_proj();
    return std::make_unique<ProjProjection>(definition);
}

}  // namespace shoal::geo::detail
