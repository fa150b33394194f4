// Travel distances and the least charted depth under a hull (include/shoal/check/surroundings.hpp).
#include <shoal/check/surroundings.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "grid/outward.hpp"
#include <shoal/util/error.hpp>

namespace shoal::check {

using geo::XY;

namespace {

/// A Detector::check that says whether the hull touches, and nothing more.
CheckOptions touch_only() {
    CheckOptions o;
    o.max_clearance_m = 0;
    o.want_penetration = false;
    o.want_polyline = false;
    o.want_contact_point = false;
    return o;
}

void check_max(double max_m, const char* who) {
    if (!(max_m > 0)) {
        char got[40];
        std::snprintf(got, sizeof got, "%g", max_m);
        throw UsageError(std::string(who) + ": max_m must be > 0 (metres; INFINITY: no limit), got " + got);
    }
}

geo::Box box_of(const std::vector<XY>& pts) {
    geo::Box b;
    for (const XY& p : pts) b.extend(p);
    return b;
}

bool inside(const geo::Box& b, const geo::Box& ext) noexcept {
    return b.minx >= ext.minx && b.miny >= ext.miny && b.maxx <= ext.maxx && b.maxy <= ext.maxy;
}

/// A contact time computed a hair below 0 is a touch at 0 (rounding); one further below is
/// a segment behind.
constexpr double behind_m = 1e-9;
/// Cells and chunk boxes are read with this much room (metres): more than the rounding of a
/// point moved into the sweep's frame and back, and than a cell's clipping slack.
constexpr double room_m = 1e-6;

/// The hull's sweep in a frame of its own: x along the direction, y across it (y = x turned
/// a quarter to the left), origin at the pose's position. Keeps the least contact time found.
struct Sweep {
    XY origin, u, n;
    std::vector<XY> hull;  ///< the outline in the sweep's frame, its first point repeated at the end
    double amin = INFINITY, amax = -INFINITY, nmin = INFINITY, nmax = -INFINITY;  ///< the hull's ranges along and across
    double best = INFINITY;  ///< least contact time found (local metres)

    XY to_frame(XY p) const noexcept {
        const XY d = p - origin;
        return {geo::dot(d, u), geo::dot(d, n)};
    }

    Sweep(const std::vector<XY>& outline, XY o, XY dir) : origin(o), u(dir), n{-dir.y, dir.x} {
        hull.reserve(outline.size() + 1);
        for (const XY& p : outline) {
            const XY q = to_frame(p);
            hull.push_back(q);
            amin = std::min(amin, q.x), amax = std::max(amax, q.x);
            nmin = std::min(nmin, q.y), nmax = std::max(nmax, q.y);
        }
        hull.push_back(hull.front());
    }

    void consider(double t) noexcept {
        if (t >= -behind_m) best = std::min(best, std::max(t, 0.0));
    }

    /// Point p moving along +x against segment ab (sweep frame): when it first meets it.
    void forward(XY p, XY a, XY b) noexcept {
        if (p.y < std::min(a.y, b.y) || p.y > std::max(a.y, b.y)) return;
        if (a.y == b.y) {  // along the direction, on p's line: its nearest end ahead of p
            if (std::max(a.x, b.x) >= p.x - behind_m) consider(std::max(std::min(a.x, b.x), p.x) - p.x);
            return;
        }
        const double f = std::clamp((p.y - a.y) / (b.y - a.y), 0.0, 1.0);
        consider(a.x + f * (b.x - a.x) - p.x);
    }

    /// Point q moving along -x against segment ab: when it first meets it.
    void backward(XY q, XY a, XY b) noexcept {
        if (q.y < std::min(a.y, b.y) || q.y > std::max(a.y, b.y)) return;
        if (a.y == b.y) {
            if (std::min(a.x, b.x) <= q.x + behind_m) consider(q.x - std::min(std::max(a.x, b.x), q.x));
            return;
        }
        const double f = std::clamp((q.y - a.y) / (b.y - a.y), 0.0, 1.0);
        consider(q.x - (a.x + f * (b.x - a.x)));
    }

    /// Whether a chunk of segments with box `b` (local metres) may hold one the hull meets
    /// sooner than the best found: the box's ranges along and across the direction.
    bool may_hold(const geo::Box& b) const noexcept {
        const XY c = to_frame({0.5 * (b.minx + b.maxx), 0.5 * (b.miny + b.maxy)});
        const double hw = 0.5 * (b.maxx - b.minx), hh = 0.5 * (b.maxy - b.miny);
        const double ra = hw * std::fabs(u.x) + hh * std::fabs(u.y) + room_m;
        const double rn = hw * std::fabs(n.x) + hh * std::fabs(n.y) + room_m;
        return c.y + rn >= nmin && c.y - rn <= nmax && c.x + ra >= amin && c.x - ra - amax < best;
    }

    /// One coast segment: every hull vertex's ray against it, and its two ends' rays back
    /// against the hull's edges.
    void segment(const grid::Segment& s) noexcept {
        const XY a = to_frame(s.a), b = to_frame(s.b);
        if (std::max(a.y, b.y) < nmin || std::min(a.y, b.y) > nmax) return;
        if (std::max(a.x, b.x) < amin - behind_m || std::min(a.x, b.x) - amax >= best) return;
        const std::size_t m = hull.size() - 1;
        for (std::size_t i = 0; i < m; ++i) forward(hull[i], a, b);
        for (const XY q : {a, b}) {
            if (q.y < nmin || q.y > nmax || q.x < amin - behind_m || q.x - amax >= best) continue;
            for (std::size_t i = 0; i < m; ++i) backward(q, hull[i], hull[i + 1]);
        }
    }
};

/// Which cells of each row a sweep has read: [lo, hi] per row (lo > hi: none). One per
/// thread, as long as the tallest grid swept; the rows a sweep touched are reset after it.
struct RowsRead {
    std::vector<std::pair<int, int>> range;
    std::vector<int> touched;
    std::pair<int, int>& row(int j) {
        auto& r = range[static_cast<std::size_t>(j)];
        if (r.first > r.second) touched.push_back(j);
        return r;
    }
    void reset() noexcept {
        for (int j : touched) range[static_cast<std::size_t>(j)] = {1, 0};
        touched.clear();
    }
};

RowsRead& rows_read(int ny) {
    thread_local RowsRead r;
    r.reset();
    if (r.range.size() < static_cast<std::size_t>(ny)) r.range.resize(static_cast<std::size_t>(ny), {1, 0});
    return r;
}

/// How far the hull `outline` (box `box`) at `origin` moves along `u` before it touches a
/// segment of `g`, capped at max_m (local metres). The hull at rest is known clear.
double sweep_distance(const grid::CoastGrid& g, const std::vector<XY>& outline, const geo::Box& box, XY origin, XY u,
                      double max_m) {
    if (g.segment_count() == 0 || outline.empty()) return max_m;
    Sweep sweep(outline, origin, u);
    const double grow = g.clip_slack() + room_m;
    const geo::Box ext = g.extent().grown(grow);
    // Beyond t_exit the moved box lies wholly outside the grid (and moves away): no cell is left.
    auto leaves = [](double lo, double hi, double elo, double ehi, double v) {
        if (v > 0) return std::max(0.0, (ehi - lo) / v);
        if (v < 0) return std::max(0.0, (elo - hi) / v);
        return hi < elo || lo > ehi ? 0.0 : INFINITY;
    };
    const double t_exit = std::min(leaves(box.minx, box.maxx, ext.minx, ext.maxx, u.x), leaves(box.miny, box.maxy, ext.miny, ext.maxy, u.y));
    const double limit = std::min(max_m, t_exit);

    const int nx = g.nx(), ny = g.ny();
    const double cell = g.cell_size();
    const XY org = g.origin();
    RowsRead& rows = rows_read(ny);
    auto read_cell = [&](int i, int j) {
        grid::visit_chunks(g, g.segments(i, j), [&](const geo::Box& cb) { return sweep.may_hold(cb); },
                           [&](const grid::Segment& s) { sweep.segment(s); });
    };
    // Reads the cells under the hull's box swept from 0 to T that were not read yet: per row,
    // the times when the moving box overlaps the row's band, and the columns it passes then.
    auto read_swept = [&](double T) {
        const double ylo = box.miny + std::min(0.0, T * u.y) - grow, yhi = box.maxy + std::max(0.0, T * u.y) + grow;
        const int j0 = std::max(0, g.row_of(ylo)), j1 = std::min(ny - 1, g.row_of(yhi));
        for (int j = j0; j <= j1; ++j) {
            const double y0 = org.y + j * cell - grow, y1 = org.y + (j + 1) * cell + grow;
            double tl = 0, th = T;
            if (u.y != 0) {
                const double ta = (y0 - box.maxy) / u.y, tb = (y1 - box.miny) / u.y;
                tl = std::max(0.0, std::min(ta, tb));
                th = std::min(T, std::max(ta, tb));
                if (tl > th) continue;
            }
            const double xlo = box.minx + std::min(tl * u.x, th * u.x) - grow, xhi = box.maxx + std::max(tl * u.x, th * u.x) + grow;
            const int ca = std::max(0, g.col_of(xlo)), cb = std::min(nx - 1, g.col_of(xhi));
            if (ca > cb) continue;
            auto& [lo, hi] = rows.row(j);
            if (lo > hi) {
                for (int i = ca; i <= cb; ++i) read_cell(i, j);
                lo = ca, hi = cb;
                continue;
            }
            const int na = std::min(ca, lo), nb = std::max(cb, hi);  // the gap between, if any, too
            for (int i = na; i < lo; ++i) read_cell(i, j);
            for (int i = hi + 1; i <= nb; ++i) read_cell(i, j);
            lo = na, hi = nb;
        }
    };
    // Outward by doubling: once the least contact time found is within the sweep read, no
    // segment further out can come sooner.
    double T = std::min(limit, std::max(cell, 1.0));
    for (;;) {
        read_swept(T);
        if (sweep.best <= T || T >= limit) break;
        T = std::min(limit, 2 * T);
    }
    return std::min(sweep.best, max_m);
}

/// The limit selecting level `level` of `base` (CoastGrid::level_of): none for level 0.
std::optional<double> limit_of_level(std::span<const double> depths, std::size_t level) {
    if (level == 0) return std::nullopt;
    const double d = depths[level - 1];
    if (std::isnan(d)) return -INFINITY;  // the unknown depths alone (they come first)
    return std::nextafter(d, INFINITY);
}

}  // namespace

double travel_distance(const Detector& detector, const LocalPose& pose, XY direction_local_unit, double max_m) {
    check_max(max_m, "travel_distance");
    const double len = std::hypot(direction_local_unit.x, direction_local_unit.y);
    if (!(std::fabs(len - 1) <= 1e-9))
        throw UsageError("travel_distance: the direction must be a unit vector (its length is " + std::to_string(len) + ")");
    if (detector.check(pose, touch_only()).collision) return 0;
    const std::vector<XY> outline = hull_outline(detector.hull(), pose);
    return sweep_distance(detector.grid(), outline, box_of(outline), pose.position, direction_local_unit, max_m);
}

double least_charted_depth(const grid::CoastGrid& base, const hull::Hull& hull, const LocalPose& pose) {
    const std::span<const double> depths = base.charted_depths();
    const CheckOptions quick = touch_only();
    auto touches = [&](std::size_t level) { return Detector(base, hull, limit_of_level(depths, level)).check(pose, quick).collision; };
    // The least level whose hazards the hull touches: 0 land (and structures), k the k-th depth.
    const std::size_t top = depths.size();
    if (!touches(top)) return NAN;
    std::size_t lo = 0, hi = top;  // touches(hi); every level below lo does not
    while (lo < hi) {
        const std::size_t mid = lo + (hi - lo) / 2;
        if (touches(mid))
            hi = mid;
        else
            lo = mid + 1;
    }
    return hi == 0 ? 0.0 : depths[hi - 1];
}

Surroundings surroundings(const Detector& detector, const grid::CoastGrid& base, const LocalPose& pose, double max_m) {
    check_max(max_m, "surroundings");
    const grid::CoastGrid& g = detector.grid();
    if (base.nx() != g.nx() || base.ny() != g.ny() || base.cell_size() != g.cell_size() || !(base.origin() == g.origin()) ||
        base.polyline_count() != g.polyline_count())
        throw UsageError("surroundings: the base grid is not the one the detector was made from (its cells differ)");
    Surroundings out;
    const std::vector<XY> outline = hull_outline(detector.hull(), pose);
    const geo::Box box = box_of(outline);
    const geo::Box ext = g.extent();
    const bool contact = detector.check(pose, touch_only()).collision;
    out.covered = inside(box, ext);
    // Ship frame port (-y), starboard (+y), ahead (+x), astern (-x).
    const std::array<XY, 4> axes{{{0, -1}, {0, 1}, {1, 0}, {-1, 0}}};
    const std::array<double*, 4> fields{&out.port_m, &out.starboard_m, &out.ahead_m, &out.astern_m};
    const Eigen::Matrix2d& m = pose.ship_to_local;
    for (std::size_t k = 0; k < axes.size(); ++k) {
        const XY w{m(0, 0) * axes[k].x + m(0, 1) * axes[k].y, m(1, 0) * axes[k].x + m(1, 1) * axes[k].y};
        const double scale = std::hypot(w.x, w.y);  // local metres per metre on the ground, that way
        const XY u{w.x / scale, w.y / scale};
        const double local_max = max_m * scale;
        const double local = contact ? 0.0 : sweep_distance(g, outline, box, pose.position, u, local_max);
        *fields[k] = std::min(local / scale, max_m);
        const double reach = std::min(local, local_max);
        out.covered = out.covered && std::isfinite(reach) &&
                      inside({box.minx + reach * u.x, box.miny + reach * u.y, box.maxx + reach * u.x, box.maxy + reach * u.y}, ext);
    }
    out.least_depth_m = least_charted_depth(base, detector.hull(), pose);
    return out;
}

}  // namespace shoal::check
