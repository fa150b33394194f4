// The C API (include/shoal/shoal.h) over the C++ library: opaque handles, and every call
// through one translating wrapper so that no exception crosses into C (as GEOS's geos_c does
// with its execute()).

#include <shoal/shoal.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>


#include <shoal/check/contacts.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/check/hull_contact.hpp>
#include <shoal/check/surroundings.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/probe/probe.hpp>
#include <shoal/util/error.hpp>
#include <shoal/version.hpp>

struct shoal_grid {
    std::shared_ptr<const shoal::grid::CoastGrid> grid;
};

struct shoal_detector {
    std::shared_ptr<const shoal::grid::CoastGrid> grid;  // keeps the grid alive
    shoal::probe::Probe probe;  // the detector and the placement (one projection per check)
    const shoal::check::Detector& detector() const noexcept { return probe.detector(); }
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

/// A ship file as Hull::load reads it, from a plain file: Hull::load reads through GDAL's virtual
/// file layer (gzip, zip, standard input, /vsi paths), which libshoal_c does without (no GDAL
/// at run time). The same messages for a missing file, a folder and one too large.
shoal::hull::Hull load_ship_file(const std::string& path) {
    using shoal::hull::Hull;
    const std::string opening = "Cannot open ship file '" + path + "': ";
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw shoal::InputError{opening + "it is a folder"};
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw shoal::InputError{opening + (errno == ENOENT ? "no such file" : std::strerror(errno))};
    std::string text(Hull::max_file_bytes + 1, '\0');
    text.resize(std::fread(text.data(), 1, text.size(), f.get()));
    if (std::ferror(f.get())) throw shoal::InputError{path + ": cannot read (" + std::strerror(errno) + ")"};
    static_assert(Hull::max_file_bytes == std::size_t{1} << 20, "the message below says 1 MiB");
    if (text.size() > Hull::max_file_bytes)
        throw shoal::InputError{path + ": larger than 1 MiB, the most a ship file may be; not read further"};
    return Hull::parse(text, path);
}

/// At limiting depth `limit` (none: land only).
shoal_detector* make_detector(const shoal_grid* grid, shoal::hull::Hull hull, std::optional<double> limit) {
    if (!grid) throw std::invalid_argument("shoal_detector: the grid is NULL");
    return new shoal_detector{grid->grid, shoal::probe::Probe(*grid->grid, std::move(hull), limit)};
}

/// At the grid's default limiting depth.
shoal_detector* make_detector(const shoal_grid* grid, shoal::hull::Hull hull) {
    if (!grid) throw std::invalid_argument("shoal_detector: the grid is NULL");
    return new shoal_detector{grid->grid, shoal::probe::Probe(*grid->grid, std::move(hull))};
}

/// At limiting depth `depth_m` as the C API gives it (NaN: land only; infinite is refused).
shoal_detector* make_detector_at(const shoal_grid* grid, shoal::hull::Hull hull, double depth_m) {
    if (std::isinf(depth_m)) throw std::invalid_argument("shoal_detector: the limiting depth must be finite (or NAN: land only)");
    return make_detector(grid, std::move(hull), std::isnan(depth_m) ? std::nullopt : std::optional<double>(depth_m));
}

void check_pose(const char* fn, double lat, double lon, double heading_deg) {
    if (shoal::probe::pose_problem(lat, lon, heading_deg))
        throw std::invalid_argument(std::string(fn) + ": lat must be in [-90, 90], lon in [-180, 180] and the heading finite");
}

shoal::check::LocalPose place(const shoal_detector* d, double lat, double lon, double heading_deg) {
    return d->probe.place(shoal::check::Pose{{lon, lat}, heading_deg});
}

/// A region as the C API gives it.
void fill(const shoal::check::ShipFrameContact& c, int hazard, shoal_contact_point& out) {
    out.x_m = c.x_m, out.y_m = c.y_m;
    out.nx = c.nx, out.ny = c.ny;
    out.depth_m = c.depth_m;
    out.lat = c.point.lat, out.lon = c.point.lon;
    out.coast_lat = c.coast_point.lat, out.coast_lon = c.coast_point.lon;
    out.hazard = hazard;
    out.charted_depth_m = NAN;
    out.name = "";
}

int hazard_code(shoal::coast::HazardKind k) {
    switch (k) {
        case shoal::coast::HazardKind::land: return SHOAL_HAZARD_LAND;
        case shoal::coast::HazardKind::shallow: return SHOAL_HAZARD_SHALLOW;
        case shoal::coast::HazardKind::danger: return SHOAL_HAZARD_DANGER;
        case shoal::coast::HazardKind::structure: return SHOAL_HAZARD_STRUCTURE;
    }
    return SHOAL_HAZARD_LAND;
}

void check_out(const char* fn, const void* out, int capacity) {
    if (capacity < 0) throw std::invalid_argument(std::string(fn) + ": capacity must be >= 0");
    if (capacity > 0 && !out) throw std::invalid_argument(std::string(fn) + ": the output array is NULL with a capacity of " + std::to_string(capacity));
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
            return make_detector(grid, load_ship_file(ship_json));
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
            return make_detector_at(grid, load_ship_file(ship_json), limiting_depth_m);
        },
        static_cast<shoal_detector*>(nullptr));
}

void shoal_detector_free(shoal_detector* detector) { delete detector; }

int shoal_check(const shoal_detector* detector, double lat, double lon, double heading_deg, double max_clearance_m, shoal_contact* out) {
    return execute(
        [&] {
            if (!detector || !out) throw std::invalid_argument("shoal_check: the detector or the result is NULL");
            check_pose("shoal_check", lat, lon, heading_deg);
            if (!(max_clearance_m > 0)) throw std::invalid_argument("shoal_check: max_clearance_m must be > 0");
            const shoal::probe::Answer a =
                detector->probe.check(shoal::check::Pose{{lon, lat}, heading_deg}, {.max_clearance_m = max_clearance_m, .want_penetration = false});
            out->covered = a.covered ? 1 : 0;
            out->contact = a.collision ? 1 : 0;  // a contact found is real, chart or not
            // Outside the chart nothing is claimed: -1.
            out->clearance_m = a.claimed() ? std::min(a.clearance_m, max_clearance_m) : -1.0;
            return 0;
        },
        1);
}

int shoal_contacts(const shoal_detector* detector, double lat, double lon, double heading_deg, shoal_contact_point* out, int capacity) {
    return execute(
        [&] {
            if (!detector) throw std::invalid_argument("shoal_contacts: the detector is NULL");
            check_pose("shoal_contacts", lat, lon, heading_deg);
            check_out("shoal_contacts", out, capacity);
            const shoal::check::LocalPose pose = place(detector, lat, lon, heading_deg);
            const std::vector<shoal::check::ContactRegion> regions = shoal::check::contact_regions(detector->detector(), pose);
            const shoal::grid::CoastGrid& g = detector->detector().grid();
            for (std::size_t i = 0; i < regions.size() && i < static_cast<std::size_t>(capacity); ++i) {
                const shoal::check::ShipFrameContact c = shoal::check::in_ship_frame(regions[i], pose, g.frame(), &g);
                shoal_contact_point& o = out[i];
                fill(c, c.hazard ? hazard_code(c.hazard->kind) : SHOAL_HAZARD_LAND, o);
                if (c.hazard) {
                    if (c.hazard->kind == shoal::coast::HazardKind::shallow || c.hazard->kind == shoal::coast::HazardKind::danger)
                        o.charted_depth_m = c.hazard->depth_m;
                    o.name = c.hazard->name.c_str();
                }
            }
            return static_cast<int>(std::min<std::size_t>(regions.size(), 1 << 30));
        },
        -1);
}

int shoal_ship_contacts(const shoal_detector* a, double lat_a, double lon_a, double heading_a_deg, const shoal_detector* b, double lat_b,
                        double lon_b, double heading_b_deg, shoal_ship_contact* out, shoal_contact_point* points, int capacity) {
    return execute(
        [&] {
            if (!a || !b || !out) throw std::invalid_argument("shoal_ship_contacts: a detector or the result is NULL");
            check_pose("shoal_ship_contacts", lat_a, lon_a, heading_a_deg);
            check_pose("shoal_ship_contacts", lat_b, lon_b, heading_b_deg);
            check_out("shoal_ship_contacts", points, capacity);
            // Both hulls in a's frame.
            const shoal::check::LocalPose pa = place(a, lat_a, lon_a, heading_a_deg);
            const shoal::check::LocalPose pb = place(a, lat_b, lon_b, heading_b_deg);
            const shoal::check::HullContact hc = shoal::check::hull_contact(a->detector().hull(), pa, b->detector().hull(), pb);
            const shoal::geo::LocalFrame& frame = a->grid->frame();
            const double scale = shoal::check::local_scale(pa);
            out->contact = hc.collision ? 1 : 0;
            out->clearance_m = hc.collision ? 0.0 : hc.clearance_m / scale;
            const shoal::geo::LonLat ca = frame.inverse(hc.on_a), cb = frame.inverse(hc.on_b);
            out->a_lat = ca.lat, out->a_lon = ca.lon, out->b_lat = cb.lat, out->b_lon = cb.lon;
            if (!hc.collision) return 0;
            const std::vector<shoal::check::ContactRegion> regions = shoal::check::hull_contact_regions(
                shoal::check::hull_outline(a->detector().hull(), pa), shoal::check::hull_outline(b->detector().hull(), pb), scale);
            for (std::size_t i = 0; i < regions.size() && i < static_cast<std::size_t>(capacity); ++i)
                fill(shoal::check::in_ship_frame(regions[i], pa, frame, nullptr), SHOAL_HAZARD_SHIP, points[i]);
            // Touching outlines overlap in no area: the contact point, depth 0.
            if (regions.empty() && capacity > 0) {
                shoal::check::ContactRegion r;
                r.hull_point = r.coast_point = hc.on_a;
                const shoal::geo::XY v = pa.position - hc.on_a;
                const double len = std::hypot(v.x, v.y);
                r.normal = len > 0 ? shoal::geo::XY{v.x / len, v.y / len} : shoal::geo::XY{1, 0};
                fill(shoal::check::in_ship_frame(r, pa, frame, nullptr), SHOAL_HAZARD_SHIP, points[0]);
            }
            return regions.empty() ? 1 : static_cast<int>(regions.size());
        },
        -1);
}

int shoal_surroundings_at(const shoal_detector* detector, double lat, double lon, double heading_deg, double max_m,
                          shoal_surroundings* out) {
    return execute(
        [&] {
            if (!detector || !out) throw std::invalid_argument("shoal_surroundings_at: the detector or the result is NULL");
            check_pose("shoal_surroundings_at", lat, lon, heading_deg);
            if (!(max_m > 0)) throw std::invalid_argument("shoal_surroundings_at: max_m must be > 0 (metres; INFINITY: no limit)");
            const shoal::check::Surroundings r =
                shoal::check::surroundings(detector->detector(), *detector->grid, place(detector, lat, lon, heading_deg), max_m);
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
