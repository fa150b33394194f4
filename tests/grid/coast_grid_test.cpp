// Tests of grid::CoastGrid. Every answer is compared with GEOS on the same shapes:
//  - the segments of a cell with GEOS clipping the projected coastline (coast::project) to that
//    cell's box alone (GEOSClipByRect_r, and GEOSIntersection_r with the box as a polygon);
//  - land or water with GEOS point-in-polygon on the land polygons read by OGR directly (not by
//    the importer) and projected vertex by vertex with the grid's own frame.
// The grid clips with each cell's box grown by CoastGrid::clip_slack() (a few ulps, so a segment
// lying on a cell border is kept by both neighbours); the reference clip uses the same grown box.

#include <shoal/grid/coast_grid.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <shoal/coast/coastline.hpp>
#include "geo/geos_context.hpp"
#include <shoal/geo/local_frame.hpp>
#include "test_support.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::InputError;
using shoal::UsageError;
using shoal::coast::LocalPolyline;
using shoal::geo::Box;
using shoal::geo::GeomPtr;
using shoal::geo::LocalFrame;
using shoal::geo::LonLat;
using shoal::geo::XY;
using shoal::grid::CellState;
using shoal::grid::CoastGrid;
using shoal::grid::Segment;
using testing::HasSubstr;
using testing::ThrowsMessage;
namespace t = shoal::test;


std::string cell_name(int i, int j) { return "cell (" + std::to_string(i) + "," + std::to_string(j) + ")"; }

/// GEOS view of a grid: the reference clip of any cell, and cell-by-cell comparisons.
class GridChecker {
public:
    GridChecker(const shoal::geo::GeosContext& geos, const std::vector<LocalPolyline>& lines) : m_geos(geos) {
        for (const auto& l : lines) {
            if (l.points.size() < 2) continue;
            Box b;
            for (const XY& p : l.points) b.extend(p);
            m_boxes.push_back(b);
            m_lines.push_back(t::line(geos, l.points));
        }
    }

    /// Pieces of the coastline inside `box`: GEOSClipByRect of every line meeting the box.
    std::vector<std::vector<XY>> clip(const Box& box) const {
        std::vector<std::vector<XY>> out;
        for (std::size_t k = 0; k < m_lines.size(); ++k) {
            if (m_boxes[k].distance_to(box) > 0) continue;
            auto c = t::check(m_geos, GEOSClipByRect_r(m_geos, m_lines[k].get(), box.minx, box.miny, box.maxx, box.maxy), "clip");
            shoal::geo::collect_lines(m_geos, c.get(), out);
        }
        return out;
    }

    /// Length of the coastline inside `box` by polygon overlay (another GEOS algorithm).
    double overlay_length(const Box& box) const {
        auto poly = t::box_polygon(m_geos, box);
        double len = 0;
        for (std::size_t k = 0; k < m_lines.size(); ++k) {
            if (m_boxes[k].distance_to(box) > 0) continue;
            auto c = t::check(m_geos, GEOSIntersection_r(m_geos, m_lines[k].get(), poly.get()), "intersection");
            len += t::length(m_geos, c.get());
        }
        return len;
    }

    double total_length() const {
        double len = 0;
        for (const auto& l : m_lines) len += t::length(m_geos, l.get());
        return len;
    }

    /// Compares the segments of cell (i, j) with GEOS's clip of the coastline to the cell's
    /// grown box; returns "" when they are the same geometry, else what differs.
    std::string compare_cell(const CoastGrid& g, int i, int j, bool with_overlay) const {
        const Box box = g.cell_box(i, j).grown(g.clip_slack());
        const auto pieces = clip(box);
        std::vector<std::vector<XY>> segs;
        double grid_len = 0;
        for (const Segment& s : g.segments(i, j)) {
            segs.push_back({s.a, s.b});
            grid_len += shoal::geo::distance(s.a, s.b);
        }
        auto ref = t::multi_line(m_geos, pieces);
        auto ours = t::multi_line(m_geos, segs);
        const double ref_len = t::length(m_geos, ref.get());
        std::ostringstream why;
        why.precision(17);
        const bool ref_empty = ref_len == 0.0;
        if (ref_empty != segs.empty())
            why << cell_name(i, j) << ": grid has " << segs.size() << " segments, GEOS clip has length " << ref_len;
        else if (std::abs(grid_len - ref_len) > 1e-7)
            why << cell_name(i, j) << ": length " << grid_len << " vs GEOS " << ref_len;
        else if (!segs.empty()) {
            double h = 0;
            if (!GEOSHausdorffDistanceDensify_r(m_geos, ours.get(), ref.get(), 0.25, &h)) return "Hausdorff failed";
            if (h > 1e-6) why << cell_name(i, j) << ": Hausdorff distance " << h << " m from GEOS clip";
        }
        if (why.str().empty() && (g.state(i, j) == CellState::coast) != !segs.empty())
            why << cell_name(i, j) << " is " << to_string(g.state(i, j)) << " with " << segs.size() << " segments";
        if (why.str().empty() && with_overlay) {
            const double ov = overlay_length(box);
            if (std::abs(ov - grid_len) > 1e-6) why << cell_name(i, j) << ": length " << grid_len << " vs overlay " << ov;
        }
        if (!why.str().empty()) why << "\n  grid: " << t::wkt(m_geos, ours.get()) << "\n  GEOS: " << t::wkt(m_geos, ref.get());
        return why.str();
    }

private:
    const shoal::geo::GeosContext& m_geos;
    std::vector<GeomPtr> m_lines;
    std::vector<Box> m_boxes;
};

double grid_total_length(const CoastGrid& g) {
    double len = 0;
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i)
            for (const Segment& s : g.segments(i, j)) len += shoal::geo::distance(s.a, s.b);
    return len;
}

// ---------------------------------------------------------------------------------------------
// Real coastlines from tests/data

struct RealCoast {
    const char* name;
    const char* file;
    const char* import_layer;  ///< "" = the default layers; else layer names separated by commas
    const char* land_layer;    ///< layer of the land polygons ("" = none: lines only)
    double cell_m;
};

std::ostream& operator<<(std::ostream& os, const RealCoast& c) { return os << c.name; }

class GridOnRealCoast : public testing::TestWithParam<RealCoast> {
protected:
    void SetUp() override {
        const RealCoast& rc = GetParam();
        shoal::coast::ImportOptions opt;
        for (std::string rest = rc.import_layer; !rest.empty();) {
            const auto comma = rest.find(',');
            opt.layers.push_back(rest.substr(0, comma));
            rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
        }
        m_coast = shoal::coast::import_coastline({t::data_path(rc.file)}, opt);
        m_frame = LocalFrame::transverse_mercator({(m_coast.min.lon + m_coast.max.lon) / 2, (m_coast.min.lat + m_coast.max.lat) / 2});
        m_grid = std::make_unique<CoastGrid>(CoastGrid::build(m_coast, m_frame, rc.cell_m));
        m_lines = shoal::coast::project(m_coast, m_frame);
    }

    shoal::coast::Coastline m_coast;
    LocalFrame m_frame = LocalFrame::transverse_mercator({0, 0});
    std::unique_ptr<CoastGrid> m_grid;
    std::vector<LocalPolyline> m_lines;
    shoal::geo::GeosContext m_geos;
};

TEST_P(GridOnRealCoast, SegmentsOfEachCellEqualGeosClipOfThatCell) {
    const CoastGrid& g = *m_grid;
    GridChecker check(m_geos, m_lines);
    // Every cell against GEOSClipByRect, and >= 300 random coast cells also against overlay.
    std::vector<std::pair<int, int>> coast_cells;
    int failures = 0;
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
            const std::string why = check.compare_cell(g, i, j, false);
            if (!why.empty() && ++failures <= 5) ADD_FAILURE() << why;
            if (g.state(i, j) == CellState::coast) coast_cells.emplace_back(i, j);
        }
    EXPECT_EQ(failures, 0);
    ASSERT_GE(coast_cells.size(), 200u);
    std::mt19937_64 rng(5);
    std::shuffle(coast_cells.begin(), coast_cells.end(), rng);
    for (std::size_t k = 0; k < 300 && k < coast_cells.size(); ++k) {
        const std::string why = check.compare_cell(g, coast_cells[k].first, coast_cells[k].second, true);
        EXPECT_TRUE(why.empty()) << why;
    }
    EXPECT_EQ(g.coast_cell_count(), coast_cells.size());
    RecordProperty("cells", std::to_string(g.cell_count()));
    RecordProperty("coast_cells", std::to_string(coast_cells.size()));
}

TEST_P(GridOnRealCoast, TotalLengthOfAllCellsEqualsCoastlineLength) {
    GridChecker check(m_geos, m_lines);
    const double coast_len = check.total_length();
    const double grid_len = grid_total_length(*m_grid);
    // Cells overlap by the slack, so a crossing is counted about 2 x clip_slack() too long.
    const double rel = (grid_len - coast_len) / coast_len;
    EXPECT_GE(grid_len, coast_len * (1 - 1e-12)) << "coastline lost in the grid";
    EXPECT_LT(std::abs(rel), 1e-9) << "grid " << grid_len << " m vs coastline " << coast_len << " m";
    RecordProperty("relative_excess", std::to_string(rel));
    std::printf("[ measured ] %s: coastline %.3f m, grid %.3f m, relative excess %.3g\n", GetParam().name, coast_len, grid_len, rel);
}

TEST_P(GridOnRealCoast, LandOrWaterAgreesWithGeosPointInPolygon) {
    const RealCoast& rc = GetParam();
    const CoastGrid& g = *m_grid;
    if (!*rc.land_layer) {
        // Lines only: no land side, so nowhere is land.
        EXPECT_FALSE(g.has_land_side());
        EXPECT_EQ(g.land_cell_count(), 0u);
        std::mt19937_64 rng(3);
        const Box e = g.extent();
        std::uniform_real_distribution<double> ux(e.minx, e.maxx), uy(e.miny, e.maxy);
        for (int k = 0; k < 10000; ++k) ASSERT_FALSE(g.is_land({ux(rng), uy(rng)}));
        return;
    }
    ASSERT_TRUE(g.has_land_side());
    const auto land = t::projected_land(m_geos, t::read_polygons_with_ogr(t::data_path(rc.file), rc.land_layer), g.frame());
    const auto prepared = t::prepare(m_geos, land.get());
    const GEOSPreparedGeometry* prep = prepared.get();
    auto geos_land = [&](XY p) {
        auto pt = t::point(m_geos, p);
        return GEOSPreparedIntersects_r(m_geos, prep, pt.get()) == 1;
    };
    int disagreements = 0, land_points = 0, total = 0;
    auto test_point = [&](XY p, const char* kind) {
        ++total;
        const bool ours = g.is_land(p), geos = geos_land(p);
        land_points += geos;
        if (ours != geos && ++disagreements <= 10) {
            ADD_FAILURE() << kind << " point (" << std::setprecision(17) << p.x << ", " << p.y << ") in "
                          << cell_name(g.col_of(p.x), g.row_of(p.y)) << ": grid says " << (ours ? "land" : "water")
                          << ", GEOS " << (geos ? "land" : "water");
        }
    };
    std::mt19937_64 rng(17);
    const Box e = g.extent();
    std::uniform_real_distribution<double> ux(e.minx, e.maxx), uy(e.miny, e.maxy), u01(0.0, 1.0);
    // 1. Uniform over the grid's extent.
    for (int k = 0; k < 10000; ++k) test_point({ux(rng), uy(rng)}, "uniform");
    const int uniform_land = land_points;
    // 2. Within 200 m of the coastline: a random point of a random segment, moved up to 200 m.
    std::vector<std::pair<std::size_t, std::size_t>> segs;
    for (std::size_t l = 0; l < m_lines.size(); ++l)
        for (std::size_t k = 0; k + 1 < m_lines[l].points.size(); ++k) segs.emplace_back(l, k);
    std::uniform_int_distribution<std::size_t> pick(0, segs.size() - 1);
    for (int k = 0; k < 10000; ++k) {
        const auto [l, s] = segs[pick(rng)];
        const XY a = m_lines[l].points[s], b = m_lines[l].points[s + 1];
        const double r = 200 * std::sqrt(u01(rng)), th = 2 * std::numbers::pi * u01(rng);
        test_point(a + u01(rng) * (b - a) + XY{r * std::cos(th), r * std::sin(th)}, "near-coast");
    }
    // 3. Exactly on cell borders and at cell corners (same arithmetic as CoastGrid::cell_box).
    std::uniform_int_distribution<int> ui(0, g.nx()), uj(0, g.ny());
    for (int k = 0; k < 3000; ++k) {
        const int i = ui(rng), j = uj(rng);
        const double bx = g.cell_box(i, j).minx, by = g.cell_box(i, j).miny;
        const XY candidates[] = {{bx, by}, {bx, uy(rng)}, {ux(rng), by}};
        for (XY p : candidates)
            if (p.x < e.maxx && p.y < e.maxy) test_point(p, "cell-border");
    }
    EXPECT_EQ(disagreements, 0) << "out of " << total << " points";
    EXPECT_GT(uniform_land, 1000) << "the sample should hold both land and water";
    EXPECT_LT(uniform_land, 9000) << "the sample should hold both land and water";
    RecordProperty("points", std::to_string(total));
    RecordProperty("disagreements", std::to_string(disagreements));
    std::printf("[ measured ] %s: %d points (%d land), %d disagreements with GEOS\n", rc.name, total, land_points, disagreements);
}

TEST_P(GridOnRealCoast, CellsWithoutCoastlineAreWhollyLandOrWhollyWater) {
    const RealCoast& rc = GetParam();
    const CoastGrid& g = *m_grid;
    if (!*rc.land_layer) {
        // Lines only: with no land side known, every cell off the coastline is water.
        for (int j = 0; j < g.ny(); ++j)
            for (int i = 0; i < g.nx(); ++i) ASSERT_NE(g.state(i, j), CellState::land) << cell_name(i, j);
        return;
    }
    const auto land = t::projected_land(m_geos, t::read_polygons_with_ogr(t::data_path(rc.file), rc.land_layer), g.frame());
    const auto prepared = t::prepare(m_geos, land.get());
    const GEOSPreparedGeometry* prep = prepared.get();
    int wrong = 0, land_cells = 0, water_cells = 0;
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
            const CellState s = g.state(i, j);
            if (s == CellState::coast) continue;
            auto box = t::box_polygon(m_geos, g.cell_box(i, j));
            const bool ok = s == CellState::land ? GEOSPreparedCovers_r(m_geos, prep, box.get()) == 1
                                                 : GEOSPreparedIntersects_r(m_geos, prep, box.get()) == 0;
            (s == CellState::land ? land_cells : water_cells) += 1;
            if (!ok && ++wrong <= 5) ADD_FAILURE() << cell_name(i, j) << " is " << to_string(s) << " but GEOS disagrees";
        }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(land_cells, 0);
    EXPECT_GT(water_cells, 0);
    EXPECT_EQ(static_cast<std::size_t>(land_cells), g.land_cell_count());
}

TEST_P(GridOnRealCoast, GeometryOfTheCells) {
    const CoastGrid& g = *m_grid;
    EXPECT_EQ(g.cell_size(), GetParam().cell_m);
    EXPECT_EQ(g.cell_count(), static_cast<std::size_t>(g.nx()) * static_cast<std::size_t>(g.ny()));
    // The extent covers every projected vertex, and every vertex's cell is a coast cell.
    const Box e = g.extent();
    for (const auto& l : m_lines)
        for (const XY& p : l.points) {
            ASSERT_TRUE(p.x > e.minx && p.x < e.maxx && p.y > e.miny && p.y < e.maxy);
            ASSERT_EQ(g.state(g.col_of(p.x), g.row_of(p.y)), CellState::coast);
            const Box b = g.cell_box(g.col_of(p.x), g.row_of(p.y));
            ASSERT_TRUE(p.x >= b.minx && p.x <= b.maxx && p.y >= b.miny && p.y <= b.maxy);
        }
    EXPECT_EQ(g.state(-1, 0), CellState::outside);
    EXPECT_EQ(g.state(0, g.ny()), CellState::outside);
    EXPECT_TRUE(g.segments(g.nx(), 0).empty());
    EXPECT_FALSE(g.is_land({e.minx - 1000, e.miny - 1000}));
    std::uint64_t vertices = 0;
    for (const auto& l : m_coast.layers) vertices += l.vertices;
    EXPECT_EQ(g.source().input_vertices, vertices);
    EXPECT_EQ(g.source().polylines, m_coast.polylines.size());
    EXPECT_GT(g.segment_count(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    RealData, GridOnRealCoast,
    testing::Values(RealCoast{"solent_land", "coast/uk_solent_land.geojson", "", "uk_solent_land", 400.0},
                    RealCoast{"solent_shoreline", "coast/uk_solent_shoreline.geojson", "", "", 400.0},
                    RealCoast{"piraeus_shp", "coast/gr_saronic_piraeus_land.shp", "", "gr_saronic_piraeus_land", 500.0},
                    RealCoast{"s57_lndare_coalne", "coast/US4MD81M_cut.000", "LNDARE,COALNE", "LNDARE", 300.0}),
    [](const testing::TestParamInfo<RealCoast>& param_info) { return std::string(param_info.param.name); });

// ---------------------------------------------------------------------------------------------
// Hand-made shapes in metres

LocalPolyline ring(std::vector<XY> pts, bool ccw) {
    if (!(pts.front() == pts.back())) pts.push_back(pts.front());
    double a = 0;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) a += shoal::geo::cross(pts[k], pts[k + 1]);
    if ((a > 0) != ccw) std::reverse(pts.begin(), pts.end());
    return {pts, true};
}

std::vector<XY> rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}; }

const LocalFrame& any_frame() {
    static const LocalFrame f = LocalFrame::transverse_mercator({0.0, 0.0});
    return f;
}

TEST(CoastGridHandMade, LongDiagonalLeavesSegmentsInEveryCellItCrosses) {
    shoal::geo::GeosContext geos;
    // Two vertices 11.3 km apart, 100 m cells: the line crosses ~150 cells that hold no vertex.
    const std::vector<LocalPolyline> lines = {{{{13.7, 21.1}, {9876.5, 5432.1}}, false}};
    const CoastGrid g = CoastGrid::build(lines, any_frame(), 100.0);
    GridChecker check(geos, lines);
    auto line = t::line(geos, lines[0].points);
    int crossed = 0;
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
            // Independent of the slack: GEOS says the line passes through the cell's interior.
            auto box = t::box_polygon(geos, g.cell_box(i, j));
            auto inter = t::check(geos, GEOSIntersection_r(geos, line.get(), box.get()), "intersection");
            if (t::length(geos, inter.get()) > 1e-6) {
                ++crossed;
                EXPECT_FALSE(g.segments(i, j).empty()) << cell_name(i, j) << " is crossed but holds no segment";
            }
            const std::string why = check.compare_cell(g, i, j, false);
            EXPECT_TRUE(why.empty()) << why;
        }
    EXPECT_GT(crossed, 140);
    EXPECT_EQ(g.coast_cell_count(), static_cast<std::size_t>(crossed));  // no vertex cell is extra
    EXPECT_NEAR(grid_total_length(g), check.total_length(), 1e-9 * check.total_length());
}

TEST(CoastGridHandMade, SegmentOnACellBorderIsKeptByBothNeighbours) {
    shoal::geo::GeosContext geos;
    // A square frame fixes the grid's origin; learn it, then add a line lying exactly on the
    // border between columns 4 and 5 (same arithmetic as CoastGrid::cell_box).
    std::vector<LocalPolyline> lines = {{rect(0, 0, 1000, 1000), false}};
    const CoastGrid g0 = CoastGrid::build(lines, any_frame(), 100.0);
    const double border_x = g0.cell_box(5, 0).minx;
    ASSERT_EQ(border_x, g0.cell_box(4, 0).maxx);
    lines.push_back({{{border_x, 250.0}, {border_x, 750.0}}, false});
    const CoastGrid g = CoastGrid::build(lines, any_frame(), 100.0);
    ASSERT_EQ(g.origin(), g0.origin());
    GridChecker check(geos, lines);
    for (int row = g.row_of(260.0); row <= g.row_of(740.0); ++row) {
        for (int col : {4, 5}) {
            bool found = false;
            for (const Segment& s : g.segments(col, row)) found = found || (s.a.x == border_x && s.b.x == border_x);
            EXPECT_TRUE(found) << cell_name(col, row) << " lost the segment on its border x = " << border_x;
            const std::string why = check.compare_cell(g, col, row, false);
            EXPECT_TRUE(why.empty()) << why;
        }
    }
}

class IslandGrid : public testing::Test {
protected:
    // A 5 km island (cell 100 m) with a 1 km lake; a second island overlapping its east
    // side; a third polygon overlapping the lake's edge; two islets far away that widen the
    // grid's extent so that open water surrounds everything.
    void SetUp() override {
        polys = {
            {rect(1000, 1000, 6000, 6000), rect(2000, 2000, 3000, 3000)},  // island with lake (hole)
            {rect(5000, 2000, 7000, 4000)},                                // overlaps the island
            {rect(2500, 2500, 3500, 2700)},                                // overlaps the lake's east shore
            {rect(0, 0, 10, 10)},
            {rect(8990, 8990, 9000, 9000)},
        };
        for (const auto& p : polys)
            for (std::size_t r = 0; r < p.size(); ++r) lines.push_back(ring(p[r], r == 0));
        grid = std::make_unique<CoastGrid>(CoastGrid::build(lines, any_frame(), 100.0));
        std::vector<GeomPtr> parts;
        for (const auto& p : polys) parts.push_back(t::polygon(geos, p));
        land = t::check(geos, GEOSUnaryUnion_r(geos, t::collection(geos, GEOS_GEOMETRYCOLLECTION, std::move(parts)).get()), "union");
    }
    bool geos_land(XY p) const {
        auto pt = t::point(geos, p);
        return GEOSIntersects_r(geos, land.get(), pt.get()) == 1;
    }

    shoal::geo::GeosContext geos;
    std::vector<std::vector<std::vector<XY>>> polys;
    std::vector<LocalPolyline> lines;
    std::unique_ptr<CoastGrid> grid;
    GeomPtr land;
};

TEST_F(IslandGrid, MiddleOfALargeIslandIsALandCell) {
    const CoastGrid& g = *grid;
    const XY middle{1500, 4500};  // 500 m from the nearest shore, 5 cells away
    EXPECT_EQ(g.state(g.col_of(middle.x), g.row_of(middle.y)), CellState::land);
    EXPECT_TRUE(g.segments(g.col_of(middle.x), g.row_of(middle.y)).empty());
    EXPECT_TRUE(g.is_land(middle));
    EXPECT_TRUE(geos_land(middle));
    EXPECT_GT(g.land_cell_count(), 1000u);
}

TEST_F(IslandGrid, LakeIsWater) {
    const CoastGrid& g = *grid;
    const XY lake{2300, 2300};
    EXPECT_EQ(g.state(g.col_of(lake.x), g.row_of(lake.y)), CellState::water);
    EXPECT_FALSE(g.is_land(lake));
    EXPECT_FALSE(geos_land(lake));
    EXPECT_FALSE(g.is_land({2450, 2950}));  // in the lake, in a coast cell near its shore
    EXPECT_TRUE(g.is_land({2550, 2600}));   // the third polygon, inside the lake
    EXPECT_TRUE(g.is_land({3200, 2600}));   // the third polygon, on the island
    EXPECT_FALSE(g.is_land({8000, 1000}));  // open sea
    EXPECT_EQ(g.state(g.col_of(8000), g.row_of(1000)), CellState::water);
}

TEST_F(IslandGrid, OverlapOfTwoLandPolygonsIsLand) {
    const CoastGrid& g = *grid;
    EXPECT_TRUE(g.is_land({5500, 3000}));   // in both islands, a land cell
    EXPECT_TRUE(g.is_land({5950, 2050}));   // in both, near both shores
    EXPECT_TRUE(g.is_land({6050, 3950}));   // in the second only
    EXPECT_TRUE(g.is_land({5999.999, 3000}));
    EXPECT_TRUE(g.is_land({6000.001, 3000}));
    EXPECT_FALSE(g.is_land({7000.001, 3000}));
    for (XY p : {XY{5500, 3000}, XY{5950, 2050}, XY{6050, 3950}}) EXPECT_TRUE(geos_land(p));
}

TEST_F(IslandGrid, RandomPointsAgreeWithGeos) {
    const CoastGrid& g = *grid;
    std::mt19937_64 rng(99);
    const Box e = g.extent();
    std::uniform_real_distribution<double> ux(e.minx, e.maxx), uy(e.miny, e.maxy);
    int disagreements = 0;
    for (int k = 0; k < 20000; ++k) {
        const XY p{ux(rng), uy(rng)};
        if (g.is_land(p) != geos_land(p) && ++disagreements <= 10) ADD_FAILURE() << "(" << p.x << ", " << p.y << ")";
    }
    // Near the shores: every shore segment, points up to 2 m away.
    std::uniform_real_distribution<double> near(-2.0, 2.0), u01(0.0, 1.0);
    for (const auto& l : lines)
        for (std::size_t k = 0; k + 1 < l.points.size(); ++k)
            for (int n = 0; n < 200; ++n) {
                const XY p = l.points[k] + u01(rng) * (l.points[k + 1] - l.points[k]) + XY{near(rng), near(rng)};
                if (g.is_land(p) != geos_land(p) && ++disagreements <= 10) ADD_FAILURE() << "(" << p.x << ", " << p.y << ")";
            }
    EXPECT_EQ(disagreements, 0);
}

TEST_F(IslandGrid, PointsOnCellBordersAndCornersAgreeWithGeos) {
    const CoastGrid& g = *grid;
    int disagreements = 0, checked = 0;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
            const Box b = g.cell_box(i, j);
            for (XY p : {XY{b.minx, b.miny}, XY{b.minx, b.miny + u01(rng) * g.cell_size()}, XY{b.minx + u01(rng) * g.cell_size(), b.miny}}) {
                ++checked;
                if (g.is_land(p) != geos_land(p) && ++disagreements <= 10)
                    ADD_FAILURE() << "border point (" << p.x << ", " << p.y << ") of " << cell_name(i, j);
            }
        }
    EXPECT_EQ(disagreements, 0) << "of " << checked;
}

TEST_F(IslandGrid, PointsOnTheShoreAreOnTheBoundaryAndCountAsLand) {
    const CoastGrid& g = *grid;
    // On straight shores (away from corners), GEOS: the boundary intersects the land.
    for (XY p : {XY{1234.5, 1000.0}, XY{1000.0, 4321.0}, XY{2000.0, 2222.0}, XY{4567.0, 6000.0}, XY{7000.0, 3333.0}}) {
        bool on = false;
        EXPECT_GT(g.winding(p, &on), 0) << "(" << p.x << ", " << p.y << ")";
        EXPECT_TRUE(on) << "(" << p.x << ", " << p.y << ")";
        EXPECT_TRUE(g.is_land(p));
        EXPECT_TRUE(geos_land(p));
    }
    bool on = true;
    g.winding({1500, 4500}, &on);
    EXPECT_FALSE(on);
}

TEST_F(IslandGrid, SegmentsEqualGeosClipInEveryCell) {
    const CoastGrid& g = *grid;
    GridChecker check(geos, lines);
    for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
            const std::string why = check.compare_cell(g, i, j, false);
            ASSERT_TRUE(why.empty()) << why;
        }
    EXPECT_NEAR(grid_total_length(g), check.total_length(), 1e-9 * check.total_length());
}

// ---------------------------------------------------------------------------------------------
// Parameters

TEST(CoastGridBuild, BadParameters) {
    const std::vector<LocalPolyline> lines = {{{{0, 0}, {1000, 1000}}, false}};
    EXPECT_THAT([&] { CoastGrid::build(lines, any_frame(), 0.0); }, ThrowsMessage<UsageError>(HasSubstr("cell size")));
    EXPECT_THAT([&] { CoastGrid::build(lines, any_frame(), -5.0); }, ThrowsMessage<UsageError>(HasSubstr("cell size")));
    EXPECT_THAT([&] { CoastGrid::build(lines, any_frame(), NAN); }, ThrowsMessage<UsageError>(HasSubstr("cell size")));
    // 1000 km x 1000 km in 5 cm cells: 4e14 cells, over the limit.
    const std::vector<LocalPolyline> big = {{{{0, 0}, {1e6, 1e6}}, false}};
    EXPECT_THAT([&] { CoastGrid::build(big, any_frame(), 0.05); }, ThrowsMessage<UsageError>(HasSubstr("BuildRequest::cell_m")));
    EXPECT_THROW(CoastGrid::build(std::vector<LocalPolyline>{}, any_frame(), 100.0), InputError);
}

TEST(CoastGridBuild, ChooseCellSize) {
    std::string note;
    const Box ext{0, 0, 50e3, 40e3};
    EXPECT_EQ(shoal::grid::choose_cell_size(250, 100, ext, &note), 250);
    EXPECT_THAT(note, HasSubstr("BuildRequest::cell_m"));
    EXPECT_EQ(shoal::grid::choose_cell_size(0, 100, ext, &note), 250);  // 2.5 x ship length
    EXPECT_THAT(note, HasSubstr("BuildRequest::ship_length_m"));
    EXPECT_EQ(shoal::grid::choose_cell_size(0, 0, ext, &note), 500);  // 2.5 x a 200 m ship
    // A continent-sized extent: the default cell grows so the grid stays well under the cap.
    const Box huge{0, 0, 5e6, 5e6};
    const double cell = shoal::grid::choose_cell_size(0, 0, huge, &note);
    EXPECT_GT(cell, 500);
    EXPECT_LE((5e6 / cell) * (5e6 / cell), static_cast<double>(CoastGrid::max_cells));
    EXPECT_THAT(note, HasSubstr("raised"));
}

}  // namespace
