// bench_detector: the per-pose cost of the pose check on every coastline of the shared data,
// by four methods on the very same LocalPose objects:
//
//   detector   check::Detector (the grid of 500 m cells),
//   GEOS tree  what a careful engineer would write with GEOS alone: an STRtree of coastline
//              pieces of <= 8 segments, queried with the hull's envelope grown by the margin
//              (grown 250 m, 1 km, 4 km, ... when the clearance is unlimited), GEOSDistance
//              on the candidates nearest envelope first with early exit, and an STRtree of
//              prepared land rings for "is the hull wholly on land",
//   GEOS prep  the other textbook GEOS way: the whole land as one prepared MultiPolygon
//              (plus a prepared MultiLineString for coastlines without a land side),
//              GEOSPreparedIntersects, then GEOSPreparedDistance (GEOSPreparedDistanceWithin
//              was slower than the distance itself in GEOS 3.11, so it is not used),
//   brute      check::BruteForce, the paper's traversal of every segment (fewer poses).
//
// Poses: "near" = hull within 0-300 m of the coastline (1/3 touching or overlapping land,
// 2/3 clear), "open" = clearance over 1 km. Hulls of 36 and 8 points. Two check options: a close-pass
// margin of 100 m (max_clearance_m = 100, no penetration: what the audit asks) and the
// unlimited clearance of `shoal probe`. Every method's answers are compared with the
// detector's on every pose; disagreements are counted and make the exit status 1.
// Batches are timed by the thread's CPU time, the methods taking turns (see time_methods);
// check::place (which calls PROJ) is timed separately. docs/performance.md has the figures.
//
// Usage: bench_detector [--data DIR] [--coast SUBSTRING]... [--near N] [--open N]
//                       [--rounds R] [--batch B] [--brute-seconds S] [--chunk SEGMENTS]
//                       [--cell M] [--seed S] [--detector-only] [--benchmark_... (Google Benchmark mode)]
// DIR defaults to $SHOAL_SHARED_DATA, else ../shared/data next to the source tree.

#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bench_data.hpp"
#include "geos_tree.hpp"
#include <shoal/check/brute_force.hpp>
#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>
#include "geo/geos_context.hpp"
#include <shoal/geo/local_frame.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/hull/hull.hpp>

namespace {

namespace fs = std::filesystem;
using shoal::geo::XY;
using shoal::geo::GeomPtr;
using shoal::geo::PreparedPtr;
using shoal::geo::TreePtr;
using Clock = std::chrono::steady_clock;

double ns_since(Clock::time_point t0) { return std::chrono::duration<double, std::nano>(Clock::now() - t0).count(); }

/// CPU time of this thread, nanoseconds. Batches are timed with it, so that the time the
/// thread spends descheduled (other processes on a shared machine) does not count.
double thread_cpu_ns() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}
double s_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}
double median(const std::vector<double>& v) { return quantile(v, 0.5); }

// ---------------------------------------------------------------------------------------
// Options and data

struct Options {
    std::string data;
    std::vector<std::string> coast_filter;
    std::size_t near = 2000, open = 1000;
    int rounds = 5;            // timed passes over the poses (in batches), per method
    std::size_t batch = 500;   // poses per timed batch
    double brute_seconds = 2;  // time budget of the brute-force traversal per pose set
    std::size_t chunk = 8;     // segments per GEOS coastline piece (4-32 tried: 8 was best near the coast)
    bool only_detector = false;  // --detector-only: skip GEOS and brute force (for profiling)
    double cell = 500;
    std::uint64_t seed = 20240611;
    bool gbench = false;
};

using shoal::bench::CoastFile;
using shoal::bench::default_data_dir;
using shoal::bench::find_coasts;

// ---------------------------------------------------------------------------------------
// The GEOS-only ways. Both take the hull outline in local metres (computed inside the timed
// call from the same LocalPose, as the detector does) and return collision + clearance with
// the detector's conventions: clearance 0 on collision, INFINITY beyond max_clearance.

using shoal::bench::Answer;
using shoal::bench::GeosTree;
using shoal::bench::HullPolygon;
using shoal::bench::box_of;
using shoal::bench::signed_area2;

/// The whole land as one prepared (valid) MultiPolygon, and the lines without a land side
/// as one prepared MultiLineString.
class GeosPrepared {
public:
    explicit GeosPrepared(const std::vector<shoal::coast::LocalPolyline>& lines) : m_hull(m_ctx.get()) {
        // The import writes each polygon as its shell (counter-clockwise) then its holes.
        // The parts are released: GEOSGeom_createCollection_r takes them over.
        std::vector<GEOSGeometry*> polys, strings;
        std::vector<std::vector<XY>> rings;
        auto flush = [&] {
            if (!rings.empty()) polys.push_back(shoal::geo::make_polygon(m_ctx, rings).release());
            rings.clear();
        };
        for (const auto& l : lines) {
            if (!l.land_left) {
                strings.push_back(shoal::geo::make_linestring(m_ctx, l.points.data(), l.points.size()).release());
                continue;
            }
            if (signed_area2(l.points) > 0) flush();
            rings.push_back(l.points);
        }
        flush();
        if (!polys.empty()) {
            m_land = GeomPtr(GEOSGeom_createCollection_r(m_ctx, GEOS_MULTIPOLYGON, polys.data(), static_cast<unsigned>(polys.size())),
                             {m_ctx.get()});
            if (GEOSisValid_r(m_ctx, m_land.get()) != 1) {  // overlapping parts (S-57 LNDARE): dissolve them
                m_land = GeomPtr(GEOSUnaryUnion_r(m_ctx, m_land.get()), {m_ctx.get()});  // the union made, then the parts freed
                m_unioned = true;
            }
            m_land_prep = PreparedPtr(GEOSPrepare_r(m_ctx, m_land.get()), {m_ctx.get()});
        }
        if (!strings.empty()) {
            m_lines = GeomPtr(GEOSGeom_createCollection_r(m_ctx, GEOS_MULTILINESTRING, strings.data(), static_cast<unsigned>(strings.size())),
                              {m_ctx.get()});
            m_lines_prep = PreparedPtr(GEOSPrepare_r(m_ctx, m_lines.get()), {m_ctx.get()});
        }
        // Build the prepared indexes outside the timed calls.
        const std::vector<XY> tiny{{0, 0}, {1, 0}, {0, 1}};
        check(tiny, INFINITY);
        check(tiny, 1.0);
    }
    GeosPrepared(const GeosPrepared&) = delete;
    GeosPrepared& operator=(const GeosPrepared&) = delete;
    bool unioned() const noexcept { return m_unioned; }

    Answer check(const std::vector<XY>& outline, double max_clearance) {
        const GeomPtr hull(m_hull.make(outline), {m_ctx.get()});
        Answer a;
        for (const GEOSPreparedGeometry* p : {m_land_prep.get(), m_lines_prep.get()})
            if (p && GEOSPreparedIntersects_r(m_ctx, p, hull.get()) == 1) a.collision = true;
        if (a.collision) {
            a.clearance = 0;
        } else {
            double best = INFINITY;
            for (const GEOSPreparedGeometry* p : {m_land_prep.get(), m_lines_prep.get()}) {
                if (!p) continue;
                double d = INFINITY;
                GEOSPreparedDistance_r(m_ctx, p, hull.get(), &d);
                best = std::min(best, d);
            }
            if (best <= max_clearance) a.clearance = best;
        }
        return a;
    }

private:
    shoal::geo::GeosContext m_ctx;
    HullPolygon m_hull;
    GeomPtr m_land{nullptr, {m_ctx.get()}};  // the geometries before their prepared forms: destroyed after them
    GeomPtr m_lines{nullptr, {m_ctx.get()}};
    PreparedPtr m_land_prep{nullptr, {m_ctx.get()}};
    PreparedPtr m_lines_prep{nullptr, {m_ctx.get()}};
    bool m_unioned = false;
};

// ---------------------------------------------------------------------------------------
// One coastline: grid, detectors, GEOS structures, pose sets.

struct PoseSet {
    std::string name;                          // "near" or "open"
    std::vector<shoal::check::Pose> geo;       // WGS84 pose (for check::place)
    std::vector<shoal::check::LocalPose> local; // the same, placed once
    std::vector<std::size_t> touching, clear;   // indices of poses with and without contact
    std::size_t collisions = 0;
    std::size_t tries = 0;
};

struct HullCase {
    std::string name;  // "36" or "8"
    shoal::hull::Hull hull;
    std::unique_ptr<shoal::check::Detector> detector;
    std::unique_ptr<shoal::check::BruteForce> brute;
    PoseSet near, open;
};

struct CoastBench {
    CoastFile file;
    shoal::coast::Coastline coast;
    std::unique_ptr<shoal::geo::LocalFrame> frame;
    std::vector<shoal::coast::LocalPolyline> lines;
    std::unique_ptr<shoal::grid::CoastGrid> grid;
    std::unique_ptr<GeosTree> geos_tree;
    std::unique_ptr<GeosPrepared> geos_prep;
    std::vector<HullCase> hulls;
    std::uint64_t vertices = 0;
    double import_s = 0, grid_s = 0, tree_s = 0, prep_s = 0;
};

constexpr double near_limit_m = 300, open_min_m = 1000;

/// Random poses: "near" ones at a random point of a random coastline segment (segments
/// equally likely) moved up to hull radius + 300 m in a random direction, kept when the
/// hull's clearance is <= 300 m, a third of them touching land and two thirds clear; "open" ones anywhere in the extent, kept when the clearance
/// exceeds 1 km. Both: random heading, hull inside the grid's extent.
void make_poses(CoastBench& cb, HullCase& hc, std::size_t n_near, std::size_t n_open, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<std::size_t> seg_end;  // cumulative segment counts per line
    std::size_t total = 0;
    for (const auto& l : cb.lines) seg_end.push_back(total += l.points.size() - 1);
    const shoal::geo::Box ext = cb.grid->extent();
    const double radius = hc.hull.radius();
    const shoal::check::CheckOptions unlimited{INFINITY, false};
    auto accept = [&](PoseSet& set, XY pos, bool near) {
        const double heading = 360 * unit(rng);
        const shoal::check::Pose pose{cb.frame->inverse(pos), heading};
        const shoal::check::LocalPose lp = shoal::check::place(*cb.frame, pose);
        const shoal::check::Contact c = hc.detector->check(lp, unlimited);
        ++set.tries;
        if (!c.covered) return;
        if (near ? !(c.collision || c.clearance_m <= near_limit_m) : (c.collision || !(c.clearance_m > open_min_m))) return;
        // Near the coast: one pose in three touching, two clear (within 300 m).
        if (near && (c.collision ? set.collisions >= n_near / 3 : set.geo.size() - set.collisions >= n_near - n_near / 3)) return;
        (c.collision ? set.touching : set.clear).push_back(set.geo.size());
        set.geo.push_back(pose);
        set.local.push_back(lp);
        set.collisions += c.collision;
    };
    hc.near.name = "near";
    while (hc.near.geo.size() < n_near && hc.near.tries < 100 * n_near + 1000) {
        const std::size_t g = static_cast<std::size_t>(unit(rng) * static_cast<double>(total)) % total;
        const std::size_t li = static_cast<std::size_t>(std::upper_bound(seg_end.begin(), seg_end.end(), g) - seg_end.begin());
        const std::size_t k = g - (li ? seg_end[li - 1] : 0);
        const auto& pts = cb.lines[li].points;
        const XY on = pts[k] + unit(rng) * (pts[k + 1] - pts[k]);
        const double r = (radius + near_limit_m) * unit(rng), a = 2 * std::numbers::pi * unit(rng);
        accept(hc.near, on + XY{r * std::cos(a), r * std::sin(a)}, true);
    }
    hc.open.name = "open";
    while (hc.open.geo.size() < n_open && hc.open.tries < 1000 * n_open + 1000) {
        const XY pos{ext.minx + radius + unit(rng) * (ext.maxx - ext.minx - 2 * radius),
                     ext.miny + radius + unit(rng) * (ext.maxy - ext.miny - 2 * radius)};
        accept(hc.open, pos, false);
    }
}

std::unique_ptr<CoastBench> setup_coast(const CoastFile& f, const Options& opt) {
    auto cb = std::make_unique<CoastBench>();
    cb->file = f;
    auto t0 = Clock::now();
    cb->coast = shoal::coast::import_coastline({f.path});
    cb->frame = std::make_unique<shoal::geo::LocalFrame>(shoal::geo::LocalFrame::transverse_mercator(
        {(cb->coast.min.lon + cb->coast.max.lon) / 2, (cb->coast.min.lat + cb->coast.max.lat) / 2}));
    cb->lines = shoal::coast::project(cb->coast, *cb->frame);
    cb->import_s = s_since(t0);
    for (const auto& l : cb->lines) cb->vertices += l.points.size();
    t0 = Clock::now();
    cb->grid = std::make_unique<shoal::grid::CoastGrid>(shoal::grid::CoastGrid::build(cb->lines, *cb->frame, opt.cell));
    cb->grid_s = s_since(t0);
    t0 = Clock::now();
    cb->geos_tree = std::make_unique<GeosTree>(cb->lines, opt.chunk);
    cb->tree_s = s_since(t0);
    t0 = Clock::now();
    cb->geos_prep = std::make_unique<GeosPrepared>(cb->lines);
    cb->prep_s = s_since(t0);
    // A 190 m x 32 m ship (AIS A/B/C/D = 150/40/14/18), outlines of 36 and 8 points.
    const shoal::hull::Dimensions dims{150, 40, 14, 18};
    cb->hulls.reserve(2);
    for (std::size_t n : {std::size_t{36}, std::size_t{8}}) {
        HullCase hc{std::to_string(n), shoal::hull::Hull::from_dimensions_n(dims, n, "bench ship"), nullptr, nullptr, {}, {}};
        hc.detector = std::make_unique<shoal::check::Detector>(*cb->grid, hc.hull);
        hc.brute = std::make_unique<shoal::check::BruteForce>(cb->lines, hc.hull);
        cb->hulls.push_back(std::move(hc));
    }
    // The same positions and headings for both hulls' near sets would not both be "near";
    // each hull gets its own sets, drawn with the same seed.
    for (HullCase& hc : cb->hulls) make_poses(*cb, hc, opt.near, opt.open, opt.seed);
    return cb;
}

// ---------------------------------------------------------------------------------------
// Timing

struct Timing {
    double batch_median_ns = NAN;  // median over batches of (batch time / poses in the batch)
    double batch_min_ns = NAN;     // fastest batch (least disturbed by other processes)
    double pose_median_ns = NAN;   // median over poses of single timed calls
    double pose_p99_ns = NAN;
    std::size_t poses = 0;
};

double timer_overhead_ns() {
    std::vector<double> v;
    for (int i = 0; i < 10001; ++i) {
        const auto t0 = Clock::now();
        v.push_back(ns_since(t0));
    }
    return median(v);
}

/// `fs[m](i)` checks pose i by method m. The methods take turns pass by pass, so that a
/// change in the machine's load affects them alike; each turn is an untimed warm-up pass
/// over the poses, then a pass timed in batches by the thread's CPU time (one method's
/// passes do not run between another's batches, which would evict its data from the
/// caches). Then one pass of single calls per method, timed by the steady clock.
std::vector<Timing> time_methods(std::size_t n, int rounds, std::size_t batch,
                                 const std::vector<std::function<void(std::size_t)>>& fs) {
    std::vector<Timing> out(fs.size());
    if (n == 0) return out;
    std::vector<std::vector<double>> per_batch(fs.size()), single(fs.size(), std::vector<double>(n));
    for (int r = 0; r < rounds; ++r)
        for (std::size_t m = 0; m < fs.size(); ++m) {
            for (std::size_t i = 0; i < n; ++i) fs[m](i);
            for (std::size_t b = 0; b < n; b += batch) {
                const std::size_t e = std::min(n, b + batch);
                const double t0 = thread_cpu_ns();
                for (std::size_t i = b; i < e; ++i) fs[m](i);
                per_batch[m].push_back((thread_cpu_ns() - t0) / static_cast<double>(e - b));
            }
        }
    for (std::size_t m = 0; m < fs.size(); ++m)
        for (std::size_t i = 0; i < n; ++i) {
            const auto t0 = Clock::now();
            fs[m](i);
            single[m][i] = ns_since(t0);
        }
    for (std::size_t m = 0; m < fs.size(); ++m) {
        Timing& t = out[m];
        t.poses = n;
        t.batch_median_ns = median(per_batch[m]);
        t.batch_min_ns = quantile(per_batch[m], 0);
        t.pose_median_ns = median(single[m]);
        t.pose_p99_ns = quantile(single[m], 0.99);
    }
    return out;
}

Timing time_method(std::size_t n, int rounds, std::size_t batch, const std::function<void(std::size_t)>& f) {
    return time_methods(n, rounds, batch, {f}).front();
}

// ---------------------------------------------------------------------------------------
// Agreement

bool same_answer(bool c1, double d1, bool c2, double d2, double limit) {
    if (c1 != c2) return false;
    if (c1) return true;
    constexpr double tol = 1e-6;
    if (std::isinf(d1) && std::isinf(d2)) return true;
    if (std::isfinite(d1) && std::isfinite(d2)) return std::fabs(d1 - d2) <= tol;
    const double fin = std::isfinite(d1) ? d1 : d2;  // one beyond the limit, the other not
    return std::fabs(fin - limit) <= tol;
}

struct Row {
    std::string coast, set, hull, margin;
    std::size_t poses = 0, collisions = 0;
    Timing det, tree, prep, brute;
    Timing det_touching, det_clear;  // the detector on the touching / clear poses alone
    std::size_t tree_agree = 0, prep_agree = 0, brute_agree = 0;
};

std::string fmt_us(double ns) {
    char b[32];
    if (std::isnan(ns)) return "-";
    const double us = ns / 1000;
    std::snprintf(b, sizeof b, us < 10 ? "%.2f" : us < 100 ? "%.1f" : "%.0f", us);
    return b;
}
std::string fmt_ratio(double x) {
    char b[32];
    if (std::isnan(x)) return "-";
    std::snprintf(b, sizeof b, x < 10 ? "%.1f" : "%.0f", x);
    return b;
}
std::string fmt_ms(double ns) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", ns / 1e6);
    return b;
}

std::vector<Row> run_coast(CoastBench& cb, const Options& opt) {
    std::vector<Row> rows;
    for (HullCase& hc : cb.hulls) {
        for (PoseSet* set : {&hc.near, &hc.open}) {
            const std::size_t n = set->local.size();
            // Brute force: as many poses as fit the time budget (at least 20), all margins alike.
            Timing brute;
            std::vector<shoal::check::Contact> brute_ans;
            if (n > 0 && !opt.only_detector) {
                const auto t0 = Clock::now();
                brute_ans.push_back(hc.brute->check(set->local[0]));
                const double one = s_since(t0);
                const std::size_t nb = std::min(n, std::max<std::size_t>(20, static_cast<std::size_t>(opt.brute_seconds / std::max(one, 1e-9))));
                std::vector<double> single;
                for (std::size_t i = 0; i < nb; ++i) {
                    const double t1 = thread_cpu_ns();
                    shoal::check::Contact c = hc.brute->check(set->local[i]);
                    single.push_back(thread_cpu_ns() - t1);
                    if (i > 0) brute_ans.push_back(c);
                }
                brute.poses = nb;
                brute.pose_median_ns = median(single);
                brute.pose_p99_ns = quantile(single, 0.99);
                brute.batch_median_ns = brute.pose_median_ns;
            }
            for (double margin : {100.0, static_cast<double>(INFINITY)}) {
                Row row;
                row.coast = cb.file.name;
                row.set = set->name;
                row.hull = hc.name;
                row.margin = std::isfinite(margin) ? "100 m" : "unlimited";
                row.poses = n;
                row.collisions = set->collisions;
                const shoal::check::CheckOptions co{margin, false};
                std::vector<shoal::check::Contact> det_ans(n);
                for (std::size_t i = 0; i < n; ++i) det_ans[i] = hc.detector->check(set->local[i], co);
                for (std::size_t i = 0; i < n && !opt.only_detector; ++i) {
                    const std::vector<XY> outline = shoal::check::hull_outline(hc.hull, set->local[i]);
                    const Answer t = cb.geos_tree->check(outline, margin);
                    const Answer p = cb.geos_prep->check(outline, margin);
                    row.tree_agree += same_answer(det_ans[i].collision, det_ans[i].clearance_m, t.collision, t.clearance, margin);
                    row.prep_agree += same_answer(det_ans[i].collision, det_ans[i].clearance_m, p.collision, p.clearance, margin);
                }
                for (std::size_t i = 0; i < brute_ans.size(); ++i) {
                    const double bd = brute_ans[i].clearance_m <= margin ? brute_ans[i].clearance_m : INFINITY;
                    row.brute_agree += same_answer(det_ans[i].collision, det_ans[i].clearance_m, brute_ans[i].collision, bd, margin);
                }
                row.brute = brute;
                const auto& poses = set->local;
                const shoal::check::Detector& det = *hc.detector;
                auto det_f = [&](std::size_t i) {
                    shoal::check::Contact c = det.check(poses[i], co);
                    benchmark::DoNotOptimize(c);
                };
                auto tree_f = [&](std::size_t i) {
                    Answer a = cb.geos_tree->check(shoal::check::hull_outline(hc.hull, poses[i]), margin);
                    benchmark::DoNotOptimize(a);
                };
                auto prep_f = [&](std::size_t i) {
                    Answer a = cb.geos_prep->check(shoal::check::hull_outline(hc.hull, poses[i]), margin);
                    benchmark::DoNotOptimize(a);
                };
                if (opt.only_detector) {
                    row.det = time_method(n, opt.rounds, opt.batch, det_f);
                } else {
                    const std::vector<Timing> t = time_methods(n, opt.rounds, opt.batch, {det_f, tree_f, prep_f});
                    row.det = t[0];
                    row.tree = t[1];
                    row.prep = t[2];
                }
                for (auto [subset, timing] : {std::pair{&set->touching, &row.det_touching}, std::pair{&set->clear, &row.det_clear}}) {
                    const std::vector<std::size_t>& idx = *subset;
                    if (idx.empty() || idx.size() == n) continue;
                    *timing = time_method(idx.size(), opt.rounds, opt.batch, [&](std::size_t i) { det_f(idx[i]); });
                }
                if (opt.only_detector) {
                    rows.push_back(row);
                    std::fprintf(stderr, "  %s %s-pt %s: detector %s us (fastest batch %s)\n", set->name.c_str(), hc.name.c_str(),
                                 row.margin.c_str(), fmt_us(row.det.batch_median_ns).c_str(), fmt_us(row.det.batch_min_ns).c_str());
                    continue;
                }
                rows.push_back(row);
                std::fprintf(stderr, "  %s %s-pt %s: detector %s us, GEOS tree %s us, GEOS prepared %s us, brute %s us\n",
                             set->name.c_str(), hc.name.c_str(), row.margin.c_str(), fmt_us(row.det.batch_median_ns).c_str(),
                             fmt_us(row.tree.batch_median_ns).c_str(), fmt_us(row.prep.batch_median_ns).c_str(),
                             fmt_us(brute.pose_median_ns).c_str());
            }
        }
    }
    return rows;
}

// ---------------------------------------------------------------------------------------
// Google Benchmark mode: the same methods as registered benchmarks (one iteration = one pose,
// cycling through the set), for --benchmark_filter, --benchmark_repetitions and JSON output.

void register_gbench(std::vector<std::unique_ptr<CoastBench>>& coasts) {
    for (auto& cbp : coasts) {
        CoastBench* cb = cbp.get();
        for (HullCase& hc : cb->hulls)
            for (PoseSet* set : {&hc.near, &hc.open})
                for (double margin : {100.0, static_cast<double>(INFINITY)}) {
                    const std::string tag = cb->file.name + "/" + set->name + "/" + hc.name + "pt/" +
                                            (std::isfinite(margin) ? "m100" : "unlimited");
                    HullCase* h = &hc;
                    benchmark::RegisterBenchmark(("detector/" + tag).c_str(), [h, set, margin](benchmark::State& st) {
                        const shoal::check::CheckOptions co{margin, false};
                        std::size_t i = 0;
                        for (auto _ : st) {
                            benchmark::DoNotOptimize(h->detector->check(set->local[i], co));
                            if (++i == set->local.size()) i = 0;
                        }
                    });
                    benchmark::RegisterBenchmark(("geos_tree/" + tag).c_str(), [cb, h, set, margin](benchmark::State& st) {
                        std::size_t i = 0;
                        for (auto _ : st) {
                            benchmark::DoNotOptimize(cb->geos_tree->check(shoal::check::hull_outline(h->hull, set->local[i]), margin));
                            if (++i == set->local.size()) i = 0;
                        }
                    });
                    benchmark::RegisterBenchmark(("geos_prepared/" + tag).c_str(), [cb, h, set, margin](benchmark::State& st) {
                        std::size_t i = 0;
                        for (auto _ : st) {
                            benchmark::DoNotOptimize(cb->geos_prep->check(shoal::check::hull_outline(h->hull, set->local[i]), margin));
                            if (++i == set->local.size()) i = 0;
                        }
                    });
                }
        HullCase* h36 = &cb->hulls.front();
        benchmark::RegisterBenchmark(("place/" + cb->file.name).c_str(), [cb, h36](benchmark::State& st) {
            std::size_t i = 0;
            for (auto _ : st) {
                benchmark::DoNotOptimize(shoal::check::place(*cb->frame, h36->near.geo[i]));
                if (++i == h36->near.geo.size()) i = 0;
            }
        });
        benchmark::RegisterBenchmark(("brute/" + cb->file.name + "/near/36pt").c_str(), [h36](benchmark::State& st) {
            std::size_t i = 0;
            for (auto _ : st) {
                benchmark::DoNotOptimize(h36->brute->check(h36->near.local[i]));
                if (++i == h36->near.local.size()) i = 0;
            }
        })->Unit(benchmark::kMillisecond);
    }
}

[[noreturn]] void usage(const char* msg) {
    std::fprintf(stderr,
                 "bench_detector: %s\nusage: bench_detector [--data DIR] [--coast SUBSTRING]... [--near N] [--open N] "
                 "[--rounds R] [--batch B] [--brute-seconds S] [--chunk SEGMENTS] [--cell M] [--seed S] [--detector-only] [--benchmark_...]\n",
                 msg);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    opt.data = default_data_dir();
    std::vector<char*> gargs{argv[0]};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(("missing value after " + a).c_str());
            return argv[++i];
        };
        try {
            if (a == "--data") opt.data = value();
            else if (a == "--coast") opt.coast_filter.push_back(value());
            else if (a == "--near") opt.near = std::stoul(value());
            else if (a == "--open") opt.open = std::stoul(value());
            else if (a == "--rounds") opt.rounds = std::stoi(value());
            else if (a == "--batch") opt.batch = std::max<std::size_t>(1, std::stoul(value()));
            else if (a == "--brute-seconds") opt.brute_seconds = std::stod(value());
            else if (a == "--chunk") opt.chunk = std::max<std::size_t>(1, std::stoul(value()));
            else if (a == "--cell") opt.cell = std::stod(value());
            else if (a == "--seed") opt.seed = std::stoull(value());
            else if (a == "--detector-only") opt.only_detector = true;
            else if (a.rfind("--benchmark_", 0) == 0) { opt.gbench = true; gargs.push_back(argv[i]); }
            else if (a == "--help" || a == "-h") usage("per-pose cost of the pose check");
            else usage(("unknown argument " + a).c_str());
        } catch (const std::logic_error&) {
            usage(("bad value for " + a).c_str());
        }
    }
    std::vector<CoastFile> files = find_coasts(opt.data);
    if (files.empty()) {
        std::fprintf(stderr,
                     "bench_detector: no shared data at '%s' (expected coast/gshhg/*_land.geojson and "
                     "coast/s57/US4MD81M/US4MD81M.000); pass --data DIR or set SHOAL_SHARED_DATA. Nothing measured.\n",
                     opt.data.c_str());
        return 2;
    }
    if (!opt.coast_filter.empty())
        std::erase_if(files, [&](const CoastFile& f) {
            return std::none_of(opt.coast_filter.begin(), opt.coast_filter.end(),
                                [&](const std::string& s) { return f.name.find(s) != std::string::npos; });
        });
    if (files.empty()) {
        std::fprintf(stderr, "%s: no coastline in '%s' matches --coast. Nothing measured.\n", "bench_detector", opt.data.c_str());
        return 2;
    }

    std::vector<std::unique_ptr<CoastBench>> coasts;
    for (const CoastFile& f : files) {
        std::fprintf(stderr, "setting up %s ...\n", f.name.c_str());
        coasts.push_back(setup_coast(f, opt));
    }
    if (opt.gbench) {
        int gargc = static_cast<int>(gargs.size());
        benchmark::Initialize(&gargc, gargs.data());
        register_gbench(coasts);
        benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        return 0;
    }

    std::printf("# bench_detector\n\ndata: %s; cell %.0f m; hull 190 x 32 m (A/B/C/D 150/40/14/18); GEOS %s; "
                "pieces of <= %zu segments; timer overhead %.0f ns per single timed call\n\n",
                opt.data.c_str(), opt.cell, GEOSversion(), opt.chunk, timer_overhead_ns());
    std::printf("## Setup\n\n| coastline | vertices | polylines | cells | coast cells | segments | GEOS pieces | land rings | "
                "import s | grid s | GEOS tree s | GEOS prepared s | near poses (36-pt: colliding) | open poses (tries) | place() median us |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    std::vector<std::vector<Row>> all;
    std::vector<double> place_ns;
    for (auto& cbp : coasts) {
        CoastBench& cb = *cbp;
        const HullCase& h36 = cb.hulls.front();
        const Timing pl = time_method(h36.near.geo.size(), 3, opt.batch, [&](std::size_t i) {
            shoal::check::LocalPose lp = shoal::check::place(*cb.frame, h36.near.geo[i]);
            benchmark::DoNotOptimize(lp);
        });
        place_ns.push_back(pl.batch_median_ns);
        std::printf("| %s | %llu | %zu | %zu | %zu | %zu | %zu | %zu | %.2f | %.3f | %.3f | %.3f%s | %zu (%zu) | %zu (%zu) | %s |\n",
                    cb.file.name.c_str(), static_cast<unsigned long long>(cb.vertices), cb.lines.size(), cb.grid->cell_count(),
                    cb.grid->coast_cell_count(), cb.grid->segment_count(), cb.geos_tree->pieces(), cb.geos_tree->rings(),
                    cb.import_s, cb.grid_s, cb.tree_s, cb.prep_s, cb.geos_prep->unioned() ? " (union)" : "", h36.near.local.size(),
                    h36.near.collisions, h36.open.local.size(), h36.open.tries, fmt_us(pl.batch_median_ns).c_str());
        std::fflush(stdout);
    }
    for (auto& cbp : coasts) {
        std::fprintf(stderr, "measuring %s ...\n", cbp->file.name.c_str());
        all.push_back(run_coast(*cbp, opt));
    }

    std::printf("\n## Per pose, microseconds (median over batches of %zu poses, thread CPU time; median and p99 of single calls, "
                "steady clock, in brackets; brute force: median of single calls, thread CPU time)\n\n"
                "GEOS = the faster of the two GEOS-only ways on that row; ratios are method / detector. Agreement: poses where the "
                "method's collision flag and clearance (to 1e-6 m) equal the detector's.\n\n"
                "| coastline | poses | hull | margin | detector | det. touching / clear | GEOS tree | GEOS prepared | brute (poses) | GEOS / det | brute / det | agree tree / prep / brute |\n"
                "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---|\n",
                opt.batch);
    std::size_t disagreements = 0;
    for (const auto& rows : all)
        for (const Row& r : rows) {
            const double geos = std::min(r.tree.batch_median_ns, r.prep.batch_median_ns);
            std::printf("| %s | %s %zu | %s | %s | %s [%s, %s] | %s / %s | %s | %s | %s (%zu) | %s | %s | %zu / %zu / %zu of %zu / %zu / %zu |\n",
                        r.coast.c_str(), r.set.c_str(), r.poses, r.hull.c_str(), r.margin.c_str(), fmt_us(r.det.batch_median_ns).c_str(),
                        fmt_us(r.det.pose_median_ns).c_str(), fmt_us(r.det.pose_p99_ns).c_str(), fmt_us(r.det_touching.batch_median_ns).c_str(),
                        fmt_us(r.det_clear.batch_median_ns).c_str(), fmt_us(r.tree.batch_median_ns).c_str(),
                        fmt_us(r.prep.batch_median_ns).c_str(), fmt_us(r.brute.pose_median_ns).c_str(), r.brute.poses,
                        fmt_ratio(geos / r.det.batch_median_ns).c_str(), fmt_ratio(r.brute.pose_median_ns / r.det.batch_median_ns).c_str(),
                        r.tree_agree, r.prep_agree, r.brute_agree, r.poses, r.poses, r.brute.poses);
            disagreements += (r.poses - r.tree_agree) + (r.poses - r.prep_agree) + (r.brute.poses - r.brute_agree);
        }

    std::printf("\n## Headline: near-coast poses, 36-point hull, 100 m margin\n\n"
                "| coastline | vertices | detector us | GEOS tree us | GEOS prepared us | GEOS / det | brute ms | brute / det | place() us |\n"
                "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (std::size_t c = 0; c < all.size(); ++c)
        for (const Row& r : all[c])
            if (r.set == "near" && r.hull == "36" && r.margin == "100 m") {
                const double geos = std::min(r.tree.batch_median_ns, r.prep.batch_median_ns);
                std::printf("| %s | %llu | %s | %s | %s | %s | %s | %s | %s |\n", r.coast.c_str(),
                            static_cast<unsigned long long>(coasts[c]->vertices), fmt_us(r.det.batch_median_ns).c_str(),
                            fmt_us(r.tree.batch_median_ns).c_str(), fmt_us(r.prep.batch_median_ns).c_str(),
                            fmt_ratio(geos / r.det.batch_median_ns).c_str(), fmt_ms(r.brute.pose_median_ns).c_str(),
                            fmt_ratio(r.brute.pose_median_ns / r.det.batch_median_ns).c_str(), fmt_us(place_ns[c]).c_str());
            }
    std::printf("\ndisagreements with the detector over all rows: %zu\n", disagreements);
    return disagreements == 0 ? 0 : 1;
}
