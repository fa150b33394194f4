// The C API (include/shoal/shoal.h) over the C++ library: opaque handles, and every call
// through one translating wrapper so that no exception crosses into C (as GEOS's geos_c does
// with its execute()).

#include <shoal/shoal.h>

#include <cmath>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <string>

#include <shoal/check/detector.hpp>
#include <shoal/check/surroundings.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/version.hpp>

struct shoal_grid {
    std::shared_ptr<const shoal::grid::CoastGrid> grid;
};

struct shoal_detector {
    std::shared_ptr<const shoal::grid::CoastGrid> grid;  // keeps the grid alive
    shoal::check::Detector detector;
    shoal::geo::JacobianField field;  // the frame's Jacobian over the grid: one projection per check
};

namespace {

thread_local std::string last_error;
thread_local bool has_error = false;

void fail(std::string message) {
    last_error = std::move(message);
    has_error = true;
}

/// Runs `f`, turning every exception into a NULL (or `error_value`) result and a message.
template <typename F, typename R>
R execute(F&& f, R error_value) noexcept {
    has_error = false;
    try {
        return f();
    } catch (const std::bad_alloc&) {
        fail("out of memory");
    } catch (const std::exception& e) {
        fail(e.what());
    } catch (...) {
        fail("unknown error");
    }
    return error_value;
}

/// At limiting depth `limit` (none: land only).
shoal_detector* make_detector(const shoal_grid* grid, shoal::hull::Hull hull, std::optional<double> limit) {
    if (!grid) throw std::invalid_argument("shoal_detector: the grid is NULL");
    return new shoal_detector{grid->grid, shoal::check::Detector(*grid->grid, std::move(hull), limit),
                              shoal::geo::JacobianField(grid->grid->frame(), grid->grid->extent())};
}

/// At the grid's default limiting depth.
shoal_detector* make_detector(const shoal_grid* grid, shoal::hull::Hull hull) {
    if (!grid) throw std::invalid_argument("shoal_detector: the grid is NULL");
    return new shoal_detector{grid->grid, shoal::check::Detector(*grid->grid, std::move(hull)),
                              shoal::geo::JacobianField(grid->grid->frame(), grid->grid->extent())};
}

/// At limiting depth `depth_m` as the C API gives it (NaN: land only; infinite is refused).
shoal_detector* make_detector_at(const shoal_grid* grid, shoal::hull::Hull hull, double depth_m) {
    if (std::isinf(depth_m)) throw std::invalid_argument("shoal_detector: the limiting depth must be finite (or NAN: land only)");
    return make_detector(grid, std::move(hull), std::isnan(depth_m) ? std::nullopt : std::optional<double>(depth_m));
}

}  // namespace

extern "C" {

const char* shoal_version(void) { return SHOAL_VERSION_STRING; }

const char* shoal_last_error(void) { return has_error ? last_error.c_str() : nullptr; }

shoal_grid* shoal_grid_load(const char* path) {
    return execute(
        [&]() -> shoal_grid* {
            if (!path) throw std::invalid_argument("shoal_grid_load: the path is NULL");
            return new shoal_grid{std::make_shared<const shoal::grid::CoastGrid>(shoal::grid::GridFile::load(path))};
        },
        static_cast<shoal_grid*>(nullptr));
}

void shoal_grid_free(shoal_grid* grid) { delete grid; }

shoal_detector* shoal_detector_new(const shoal_grid* grid, double a, double b, double c, double d) {
    return execute([&] { return make_detector(grid, shoal::hull::Hull::from_dimensions({a, b, c, d})); },
                   static_cast<shoal_detector*>(nullptr));
}

shoal_detector* shoal_detector_from_ship_file(const shoal_grid* grid, const char* ship_json) {
    return execute(
        [&] {
            if (!ship_json) throw std::invalid_argument("shoal_detector_from_ship_file: the path is NULL");
            return make_detector(grid, shoal::hull::Hull::load(ship_json));
        },
        static_cast<shoal_detector*>(nullptr));
}

shoal_detector* shoal_detector_new_at_depth(const shoal_grid* grid, double a, double b, double c, double d, double limiting_depth_m) {
    return execute([&] { return make_detector_at(grid, shoal::hull::Hull::from_dimensions({a, b, c, d}), limiting_depth_m); },
                   static_cast<shoal_detector*>(nullptr));
}

shoal_detector* shoal_detector_from_ship_file_at_depth(const shoal_grid* grid, const char* ship_json, double limiting_depth_m) {
    return execute(
        [&] {
            if (!ship_json) throw std::invalid_argument("shoal_detector_from_ship_file_at_depth: the path is NULL");
            return make_detector_at(grid, shoal::hull::Hull::load(ship_json), limiting_depth_m);
        },
        static_cast<shoal_detector*>(nullptr));
}

void shoal_detector_free(shoal_detector* detector) { delete detector; }

int shoal_check(const shoal_detector* detector, double lat, double lon, double heading_deg, double max_clearance_m, shoal_contact* out) {
    return execute(
        [&] {
            if (!detector || !out) throw std::invalid_argument("shoal_check: the detector or the result is NULL");
            if (!(std::fabs(lat) <= 90) || !(std::fabs(lon) <= 180) || !std::isfinite(heading_deg))
                throw std::invalid_argument("shoal_check: lat must be in [-90, 90], lon in [-180, 180] and the heading finite");
            if (!(max_clearance_m > 0)) throw std::invalid_argument("shoal_check: max_clearance_m must be > 0");
            const shoal::check::Contact c =
                detector->detector.check(shoal::check::place(detector->grid->frame(), detector->field, shoal::check::Pose{{lon, lat}, heading_deg}),
                                         {.max_clearance_m = max_clearance_m, .want_penetration = false, .want_polyline = false, .want_contact_point = false});
            out->covered = c.covered ? 1 : 0;
            out->contact = c.collision ? 1 : 0;  // a contact found is real, chart or not
            out->clearance_m = c.collision ? 0.0 : !c.covered ? -1.0 : std::min(c.clearance_m, max_clearance_m);
            return 0;
        },
        1);
}

int shoal_surroundings_at(const shoal_detector* detector, double lat, double lon, double heading_deg, double max_m,
                          shoal_surroundings* out) {
    return execute(
        [&] {
            if (!detector || !out) throw std::invalid_argument("shoal_surroundings_at: the detector or the result is NULL");
            if (!(std::fabs(lat) <= 90) || !(std::fabs(lon) <= 180) || !std::isfinite(heading_deg))
                throw std::invalid_argument("shoal_surroundings_at: lat must be in [-90, 90], lon in [-180, 180] and the heading finite");
            if (!(max_m > 0)) throw std::invalid_argument("shoal_surroundings_at: max_m must be > 0 (metres; INFINITY: no limit)");
            const shoal::check::Surroundings r = shoal::check::surroundings(
                detector->detector, *detector->grid,
                shoal::check::place(detector->grid->frame(), detector->field, shoal::check::Pose{{lon, lat}, heading_deg}), max_m);
            out->covered = r.covered ? 1 : 0;
            out->port_m = r.port_m;
            out->starboard_m = r.starboard_m;
            out->ahead_m = r.ahead_m;
            out->astern_m = r.astern_m;
            out->least_depth_m = r.least_depth_m;
            return 0;
        },
        1);
}

}  // extern "C"
