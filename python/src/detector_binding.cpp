// shoal.Detector: poses (numpy arrays of lat, lon, heading) against a grid, as `shoal probe`.
#include "bindings.hpp"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <shoal/check/contacts.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/probe/probe.hpp>
#include <shoal/check/surroundings.hpp>
#include <shoal/geo/jacobian_field.hpp>
#include <shoal/util/error.hpp>


namespace shoal::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Copies of a frame for one pose at a time: each call leases one (made when none is free) and
/// gives it back, so no two threads use one at once and a frame is not made for every call.
class FramePool {
public:
    class Lease {
    public:
        Lease(FramePool& pool, const geo::LocalFrame& like) : m_pool(pool), m_frame(pool.take(like)) {}
        ~Lease() { m_pool.give(std::move(m_frame)); }
        Lease(const Lease&) = delete;
        Lease& operator=(const Lease&) = delete;
        const geo::LocalFrame& get() const noexcept { return *m_frame; }

    private:
        FramePool& m_pool;
        std::unique_ptr<geo::LocalFrame> m_frame;
    };

private:
    std::unique_ptr<geo::LocalFrame> take(const geo::LocalFrame& like) {
        {
            const std::lock_guard<std::mutex> lock(m_mutex);
            if (!m_free.empty()) {
                std::unique_ptr<geo::LocalFrame> f = std::move(m_free.back());
                m_free.pop_back();
                return f;
            }
        }
        return std::make_unique<geo::LocalFrame>(like);
    }
    void give(std::unique_ptr<geo::LocalFrame> f) noexcept {
        const std::lock_guard<std::mutex> lock(m_mutex);
        try {
            m_free.push_back(std::move(f));
        } catch (...) {  // out of memory: the frame goes
        }
    }

    std::mutex m_mutex;
    std::vector<std::unique_ptr<geo::LocalFrame>> m_free;
};

/// A ValueError for a pose the probe would refuse (probe::pose_problem), in its words.
void refuse_bad_pose(double lat, double lon, double heading) {
    if (const std::optional<std::string> problem = probe::pose_problem(lat, lon, heading))
        throw py::value_error(problem->rfind("heading", 0) == 0 ? *problem : "pose: " + *problem);
}

class PyDetector {
public:
    PyDetector(GridHandle grid, const py::object& ship, const py::object& dims, const py::object& ukc, const py::object& hazard_depth_m)
        : m_grid(std::move(grid)), m_hull(hull_of(ship, dims, &m_label)),
          m_probe(*m_grid.grid, m_hull, plan_depth(m_grid, m_hull, hazard_depth_m, ukc).depth_m) {}

    py::dict check(const Array& lat, const Array& lon, const Array& heading, double max_clearance_m) const {
        if (!(max_clearance_m > 0)) throw py::value_error("max_clearance_m must be > 0 (metres; inf: no limit)");
        // The inputs broadcast as numpy does (scalars, rows against columns, ...).
        const py::module_ np = py::module_::import("numpy");
        const py::tuple b = np.attr("broadcast_arrays")(lat, lon, heading);
        const Array la = Array::ensure(b[0]), lo = Array::ensure(b[1]), he = Array::ensure(b[2]);
        const std::vector<py::ssize_t> shape(la.shape(), la.shape() + la.ndim());
        py::array_t<bool> contact(shape), covered(shape);
        Array clearance(shape), penetration(shape);
        const auto n = static_cast<std::size_t>(la.size());
        const double *plat = la.data(), *plon = lo.data(), *phead = he.data();
        bool* pc = contact.mutable_data();
        bool* pv = covered.mutable_data();
        double* pcl = clearance.mutable_data();
        double* ppe = penetration.mutable_data();
        std::vector<check::Pose> poses(n);
        for (std::size_t k = 0; k < n; ++k) poses[k] = {{plon[k], plat[k]}, phead[k]};
        probe::Batch batch;
        {
            py::gil_scoped_release nogil;
            // One thread, the blocks in turn (as before the probe had threads of its own here).
            batch = m_probe.check(poses, {.max_clearance_m = max_clearance_m, .want_penetration = true}, 1);
        }
        for (std::size_t k = 0; k < n; ++k) {
            const probe::Answer& a = batch.answers[k];
            pc[k] = a.collision;
            pv[k] = a.covered;
            pcl[k] = a.clearance_m;
            ppe[k] = a.penetration_m;
        }
        const std::size_t bad = batch.invalid;
        const std::string first_bad = bad ? "pose " + std::to_string(batch.first_invalid) + ": " + batch.first_problem : std::string();
        if (bad)
            warn_all({std::to_string(bad) + " of " + std::to_string(n) + " poses are not valid (first: " + first_bad +
                      "): covered False, clearance NaN"});
        py::dict out;
        out["contact"] = contact;
        out["clearance_m"] = clearance;
        out["covered"] = covered;
        out["penetration_m"] = penetration;
        return out;
    }

    py::dict surroundings(double lat, double lon, double heading, double max_m) const {
        refuse_bad_pose(lat, lon, heading);
        if (!(max_m > 0)) throw py::value_error("max_m must be > 0 (metres; inf: no limit)");
        check::Surroundings r;
        {
            py::gil_scoped_release nogil;
            // A frame this call alone uses (PROJ transformations are not shared between
            // threads), kept for the next call: a copy of a frame costs far more than the call.
            const FramePool::Lease frame(*m_frames, m_grid.grid->frame());
            r = check::surroundings(m_probe.detector(), *m_grid.grid, check::place(frame.get(), m_probe.field(), check::Pose{{lon, lat}, heading}), max_m);
        }
        py::dict out;
        out["covered"] = r.covered;
        out["port_m"] = r.port_m;
        out["starboard_m"] = r.starboard_m;
        out["ahead_m"] = r.ahead_m;
        out["astern_m"] = r.astern_m;
        out["least_depth_m"] = r.least_depth_m;
        return out;
    }

    /// Every contact region at one pose, deepest first, as shoal_contacts gives them.
    py::list contacts(double lat, double lon, double heading) const {
        refuse_bad_pose(lat, lon, heading);
        std::vector<check::ShipFrameContact> found;
        {
            py::gil_scoped_release nogil;
            const FramePool::Lease frame(*m_frames, m_grid.grid->frame());
            const check::LocalPose pose = check::place(frame.get(), m_probe.field(), check::Pose{{lon, lat}, heading});
            for (const check::ContactRegion& r : check::contact_regions(m_probe.detector(), pose))
                found.push_back(check::in_ship_frame(r, pose, frame.get(), &m_probe.detector().grid()));
        }
        py::list out;
        for (const check::ShipFrameContact& c : found) {
            py::dict d;
            d["x_m"] = c.x_m, d["y_m"] = c.y_m, d["nx"] = c.nx, d["ny"] = c.ny, d["depth_m"] = c.depth_m;
            d["lat"] = c.point.lat, d["lon"] = c.point.lon, d["coast_lat"] = c.coast_point.lat, d["coast_lon"] = c.coast_point.lon;
            d["hazard"] = c.hazard ? coast::to_string(c.hazard->kind) : "land";
            const bool charted = c.hazard && (c.hazard->kind == coast::HazardKind::shallow || c.hazard->kind == coast::HazardKind::danger);
            d["charted_depth_m"] = charted ? c.hazard->depth_m : NAN;
            d["name"] = c.hazard ? c.hazard->name : std::string();
            out.append(d);
        }
        return out;
    }

    const GridHandle& grid() const noexcept { return m_grid; }
    const hull::Hull& hull() const noexcept { return m_hull; }
    const std::string& label() const noexcept { return m_label; }

private:
    GridHandle m_grid;  // keeps the grid alive
    std::string m_label;
    hull::Hull m_hull;
    probe::Probe m_probe;  ///< the detector and the placement (the frame's Jacobian over the grid)
    std::unique_ptr<FramePool> m_frames = std::make_unique<FramePool>();  ///< frames for surroundings(), contacts()
};

}  // namespace

void bind_detector(py::module_& m) {
    py::class_<PyDetector>(m, "Detector", "A ship's hull against a grid: Detector(grid, ship=PATH | dims=(a, b, c, d), ukc=None)")
        .def(py::init<GridHandle, py::object, py::object, py::object, py::object>(), py::arg("grid"), py::kw_only(),
             py::arg("ship") = py::none(), py::arg("dims") = py::none(), py::arg("ukc") = py::none(), py::arg("hazard_depth_m") = py::none(),
             "ship: a ship file (schemas/ship.schema.json); dims: AIS a, b, c, d (metres from the position reference point to "
             "bow, stern, port, starboard). ukc / hazard_depth_m: the limiting depth the run needs (the ship's draught + ukc, "
             "or hazard_depth_m); a grid built for another depth is warned about.")
        .def("check", &PyDetector::check, py::arg("lat"), py::arg("lon"), py::arg("heading"), py::kw_only(),
             py::arg("max_clearance_m") = INFINITY,
             "Checks poses (WGS84 degrees, true heading in degrees; arrays broadcast together) without the GIL. Returns a dict of "
             "arrays: contact (bool: the hull touches or overlaps land or a hazard), clearance_m (0 on contact, NaN outside the "
             "chart, inf beyond max_clearance_m), covered (bool: the hull's box lies inside the grid), penetration_m (on contact). "
             "The same answers as `shoal probe` on the same poses. An invalid pose (NaN, |lat| > 90, ...) gets covered False, "
             "clearance NaN, and one warning says how many there were.")
        .def("contacts", &PyDetector::contacts, py::arg("lat"), py::arg("lon"), py::arg("heading"),
             "Every region where the hull overlaps land or a hazard at one pose (WGS84 degrees, true heading in degrees), "
             "deepest first, as the C API's shoal_contacts gives them, without the GIL: a list of dicts with x_m, y_m (the "
             "region's deepest hull point, ship frame: x forward, y starboard, metres from the reference point), nx, ny (unit "
             "normal, ship frame: moving the point along it by depth_m frees it), depth_m, lat, lon, coast_lat, coast_lon "
             "(the nearest boundary point), hazard ('land', 'shallow', 'danger', 'structure'), charted_depth_m (NaN unless "
             "shallow or danger), name. Empty when the hull is clear.")
        .def("surroundings", &PyDetector::surroundings, py::arg("lat"), py::arg("lon"), py::arg("heading"), py::kw_only(),
             py::arg("max_m") = INFINITY,
             "What a bridge simulator asks beside the contacts, for one pose (WGS84 degrees, true heading in degrees), without "
             "the GIL. Returns a dict: port_m, starboard_m, ahead_m, astern_m (how far the hull can move along each of its axes "
             "before it touches land or a hazard, metres on the ground; 0 in contact, capped at max_m, inf with no limit when "
             "nothing lies that way), least_depth_m (the least charted depth of the depth areas and dangers the hull touches; "
             "0 on land; NaN where none is charted or its depth is unknown), covered (bool: the hull and the reach of the "
             "searches lie inside the grid). The same numbers as the C API's shoal_surroundings_at.")
        .def_property_readonly("grid", [](const PyDetector& d) { return d.grid(); })
        .def_property_readonly("hull_label", &PyDetector::label, "where the hull came from, as the report's hull field says it")
        .def_property_readonly("dims", [](const PyDetector& d) {
            const auto x = d.hull().dimensions();
            return py::make_tuple(x.a, x.b, x.c, x.d);
        })
        .def_property_readonly("draught_m", [](const PyDetector& d) -> py::object {
            return d.hull().draught() > 0 ? py::cast(d.hull().draught()) : py::none();
        });
}

}  // namespace shoal::python
