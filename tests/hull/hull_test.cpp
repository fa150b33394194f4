// Tests of shoal::hull. Geometric properties of the outlines are checked with GEOS (validity,
// simplicity, containment, area, orientation), not with the hull code's own helpers.

#include <shoal/hull/hull.hpp>
#include <shoal/util/option_names.hpp>

#include "geo/geos_context.hpp"
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pathological_shapes.hpp"
#include <shoal/util/error.hpp>

namespace {

using shoal::FrontEnd;
using shoal::in_terms_of;
using shoal::InputError;
using shoal::UsageError;
using shoal::geo::XY;
using shoal::hull::Dimensions;
using shoal::hull::Hull;
using testing::AllOf;
using testing::HasSubstr;
using testing::ThrowsMessage;

std::string data_path(const std::string& name) { return std::string{SHOAL_TEST_DATA} + name; }

// ---------------------------------------------------------------------------------------------
// GEOS helpers, on the library's owners (src/geo/geos_context.hpp).

using GeosGeomPtr = shoal::geo::GeomPtr;

class Geos {
public:

    /// Polygon with the open ring `pts` as shell (GEOS needs it closed).
    GeosGeomPtr polygon(const std::vector<XY>& pts) const {
        GEOSCoordSequence* seq = closed_sequence(pts);
        GEOSGeometry* shell = GEOSGeom_createLinearRing_r(ctx(), seq);
        return GeosGeomPtr{GEOSGeom_createPolygon_r(ctx(), shell, nullptr, 0), {ctx()}};
    }
    GeosGeomPtr point(XY p) const { return GeosGeomPtr{GEOSGeom_createPointFromXY_r(ctx(), p.x, p.y), {ctx()}}; }

    bool is_valid(const GEOSGeometry* g) const { return GEOSisValid_r(ctx(), g) == 1; }
    bool is_simple(const GEOSGeometry* g) const { return GEOSisSimple_r(ctx(), g) == 1; }
    std::string why_invalid(const GEOSGeometry* g) const {
        char* text = GEOSisValidReason_r(ctx(), g);
        std::string out = text ? text : "?";
        GEOSFree_r(ctx(), text);
        return out;
    }
    bool contains(const GEOSGeometry* a, const GEOSGeometry* b) const { return GEOSContains_r(ctx(), a, b) == 1; }
    double area(const GEOSGeometry* g) const {
        double a = 0.0;
        EXPECT_EQ(GEOSArea_r(ctx(), g, &a), 1);
        return a;
    }
    /// True when the ring turns counter-clockwise with x right and y up.
    bool is_ccw(const std::vector<XY>& pts) const {
        GEOSCoordSequence* seq = closed_sequence(pts);
        char ccw = 0;
        EXPECT_EQ(GEOSCoordSeq_isCCW_r(ctx(), seq, &ccw), 1);
        GEOSCoordSeq_destroy_r(ctx(), seq);
        return ccw == 1;
    }

private:
    GEOSContextHandle_t ctx() const { return m_ctx.get(); }
    GEOSCoordSequence* closed_sequence(const std::vector<XY>& pts) const {
        const auto n = static_cast<unsigned>(pts.size());
        GEOSCoordSequence* seq = GEOSCoordSeq_create_r(ctx(), n + 1, 2);
        for (unsigned i = 0; i <= n; ++i) GEOSCoordSeq_setXY_r(ctx(), seq, i, pts[i % n].x, pts[i % n].y);
        return seq;
    }
    shoal::geo::GeosContext m_ctx;
};

std::string to_wkt(const std::vector<XY>& pts) {
    std::ostringstream out;
    out.precision(17);
    out << "POLYGON((";
    for (std::size_t i = 0; i <= pts.size(); ++i) {
        const XY p = pts[i % pts.size()];
        out << (i ? "," : "") << p.x << ' ' << p.y;
    }
    out << "))";
    return out.str();
}

struct Extent {
    double minx = std::numeric_limits<double>::infinity(), miny = minx;
    double maxx = -std::numeric_limits<double>::infinity(), maxy = maxx;
};
Extent extent_of(const std::vector<XY>& pts) {
    Extent e;
    for (const XY p : pts) {
        e.minx = std::min(e.minx, p.x), e.maxx = std::max(e.maxx, p.x);
        e.miny = std::min(e.miny, p.y), e.maxy = std::max(e.maxy, p.y);
    }
    return e;
}

// ---------------------------------------------------------------------------------------------
// Generated outlines

/// A spread of AIS dimensions: typical, asymmetric antenna, antenna near the bow or the stern,
/// very narrow, a dinghy, and a very long ship.
const std::vector<Dimensions> sample_dims{
    {200, 50, 22, 22}, {62, 38, 9, 11},   {5, 95, 8, 8},   {95, 5, 8, 8},      {50, 50, 0.5, 15},
    {50, 50, 15, 0.5}, {3, 1.5, 0.8, 0.7}, {1, 1, 1, 1},   {350, 50, 30, 30.5}, {0.3, 120, 1, 20}};

/// Everything the generated outline must satisfy for any valid dimensions and n points.
void expect_fits_box(const Hull& hull, const Dimensions& dims, std::size_t n, bool reference_inside) {
    SCOPED_TRACE(testing::Message() << dims << " n=" << n << " " << to_wkt(hull.contour()));
    const auto& pts = hull.contour();
    ASSERT_EQ(pts.size(), n);

    Geos geos;
    const auto poly = geos.polygon(pts);
    EXPECT_TRUE(geos.is_valid(poly.get())) << geos.why_invalid(poly.get());
    EXPECT_TRUE(geos.is_simple(poly.get()));
    EXPECT_TRUE(geos.is_ccw(pts));

    const Extent e = extent_of(pts);
    EXPECT_EQ(e.maxx, dims.a);
    EXPECT_EQ(e.minx, -dims.b);
    EXPECT_EQ(e.miny, -dims.c);
    EXPECT_EQ(e.maxy, dims.d);

    const auto at_bow = std::count_if(pts.begin(), pts.end(), [&](XY p) { return p.x == dims.a; });
    EXPECT_EQ(at_bow, 1) << "the bow tip must be the only point at x = a";

    if (reference_inside) {
        EXPECT_TRUE(geos.contains(poly.get(), geos.point({0, 0}).get()));
    }
}

TEST(GeneratedHull, Has36PointsFitsTheBoxAndHoldsTheReferencePoint) {
    for (const auto& dims : sample_dims) {
        const Hull hull = Hull::from_dimensions(dims, "sample");
        expect_fits_box(hull, dims, 36, true);
    }
}

TEST(GeneratedHull, AreaIsBetween70And100PercentOfLengthTimesBeam) {
    Geos geos;
    for (const auto& dims : sample_dims) {
        const Hull hull = Hull::from_dimensions(dims);
        const double box_area = (dims.a + dims.b) * (dims.c + dims.d);
        const double ratio = geos.area(geos.polygon(hull.contour()).get()) / box_area;
        EXPECT_GT(ratio, 0.7) << dims;
        EXPECT_LT(ratio, 1.0) << dims;
    }
}

TEST(GeneratedHull, AccessorsReportTheDimensions) {
    const Dimensions dims{200, 50, 20, 24};
    const Hull hull = Hull::from_dimensions(dims, "Tanker");
    EXPECT_EQ(hull.name(), "Tanker");
    EXPECT_EQ(hull.dimensions(), dims);
    EXPECT_DOUBLE_EQ(hull.length(), 250.0);
    EXPECT_DOUBLE_EQ(hull.beam(), 44.0);
    EXPECT_EQ(hull.draught(), 0.0);
    // The farthest point is a stern corner or the bow tip (200, 2); the box corner bounds it.
    EXPECT_GE(hull.radius(), std::hypot(200.0, 2.0));
    EXPECT_LE(hull.radius(), std::hypot(200.0, 24.0));
    double farthest = 0.0;
    for (const XY p : hull.contour()) farthest = std::max(farthest, std::hypot(p.x, p.y));
    EXPECT_DOUBLE_EQ(hull.radius(), farthest);
}

TEST(GeneratedHull, CoarserOutlinesKeepTheShape) {
    for (const auto& dims : sample_dims)
        for (std::size_t n = 3; n <= 64; ++n)
            expect_fits_box(Hull::from_dimensions_n(dims, n), dims, n, n >= 5);
}

TEST(GeneratedHull, EightPointOutlineHasAPointedBow) {
    const Dimensions dims{80, 20, 6, 6};
    const Hull hull = Hull::from_dimensions_n(dims, 8, "bench");
    expect_fits_box(hull, dims, 8, true);
    EXPECT_EQ(hull.name(), "bench");
    // The bow tip sits on the centreline, and its neighbours are aft of it on either side.
    const auto& pts = hull.contour();
    const auto tip = std::max_element(pts.begin(), pts.end(), [](XY p, XY q) { return p.x < q.x; });
    EXPECT_EQ(tip->y, 0.0);
}

TEST(GeneratedHull, RejectsTooFewPoints) {
    EXPECT_THROW(Hull::from_dimensions_n({10, 5, 2, 2}, 2), UsageError);
}

TEST(GeneratedHull, RejectsDimensionsThatAreNotPositiveAndFinite) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_THAT([] { Hull::from_dimensions({0, 5, 2, 2}); }, ThrowsMessage<InputError>(HasSubstr("'a'")));
    EXPECT_THAT([] { Hull::from_dimensions({10, -5, 2, 2}); }, ThrowsMessage<InputError>(HasSubstr("'b'")));
    EXPECT_THAT([&] { Hull::from_dimensions({10, 5, nan, 2}); }, ThrowsMessage<InputError>(HasSubstr("'c'")));
    EXPECT_THAT([&] { Hull::from_dimensions({10, 5, 2, inf}); }, ThrowsMessage<InputError>(HasSubstr("'d'")));
}

TEST(GeneratedHull, PlacedAtAPoseRotatesClockwiseFromGridNorth) {
    const Hull hull = Hull::from_dimensions({80, 20, 4, 6});  // bow tip at (80, 1) in the ship frame
    const XY pos{1000, 2000};
    const auto tip_at = [&](double heading) {
        const auto pts = hull.placed(pos, heading);
        return pts.front();
    };
    ASSERT_EQ(hull.contour().front(), (XY{80, 1}));
    const XY north = tip_at(0);  // bow north, starboard east
    EXPECT_NEAR(north.x, 1001, 1e-9);
    EXPECT_NEAR(north.y, 2080, 1e-9);
    const XY east = tip_at(90);  // bow east, starboard south
    EXPECT_NEAR(east.x, 1080, 1e-9);
    EXPECT_NEAR(east.y, 1999, 1e-9);
    const XY south_west = tip_at(225);
    EXPECT_NEAR(south_west.x, 1000 - 81 / std::sqrt(2.0), 1e-9);
    EXPECT_NEAR(south_west.y, 2000 - 79 / std::sqrt(2.0), 1e-9);

    std::vector<XY> buffer;
    hull.place(pos, 90, buffer);
    EXPECT_EQ(buffer.size(), hull.contour().size());
    EXPECT_EQ(buffer, hull.placed(pos, 90));
}

// ---------------------------------------------------------------------------------------------
// --dims

TEST(DimsString, ParsesFourNumbers) {
    EXPECT_EQ(Hull::from_dims_string("120,30,8,10").dimensions(), (Dimensions{120, 30, 8, 10}));
    EXPECT_EQ(Hull::from_dims_string(" 12.5 , 3.5,2 ,2.25 ").dimensions(), (Dimensions{12.5, 3.5, 2, 2.25}));
    EXPECT_EQ(Hull::from_dims_string("120,30,8,10").contour().size(), 36u);
}

struct BadDims {
    std::string text;
    std::string expected;
};

class DimsStringRejects : public testing::TestWithParam<BadDims> {};

TEST_P(DimsStringRejects, NamingTheBadPart) {
    const auto& p = GetParam();
    EXPECT_THAT([&] { Hull::from_dims_string(p.text); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("Hull::dims"), HasSubstr(p.expected))));
    // The option as each front end names it: the CLI's --dims, Python's dims; never a flag in the library.
    try {
        Hull::from_dims_string(p.text);
    } catch (const InputError& e) {
        EXPECT_EQ(in_terms_of(e.what(), FrontEnd::cli).rfind("--dims", 0), 0u) << in_terms_of(e.what(), FrontEnd::cli);
        EXPECT_EQ(in_terms_of(e.what(), FrontEnd::python).rfind("dims", 0), 0u) << in_terms_of(e.what(), FrontEnd::python);
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Hull, DimsStringRejects,
                         testing::Values(BadDims{"120,30,8", "got 3 parts"}, BadDims{"120,30,8,10,2", "got 5 parts"},
                                         BadDims{"", "got 1 part"}, BadDims{"120,x,8,10", "B 'x' is not a number"},
                                         BadDims{"120m,30,8,10", "A '120m' is not a number"},
                                         BadDims{"120,30,,10", "C is empty"},
                                         BadDims{"120,30,0,10", "C must be a finite number > 0 (got 0"},
                                         BadDims{"120,30,8,-1", "D must be a finite number > 0 (got -1"},
                                         BadDims{"nan,30,8,10", "A must be a finite number > 0 (got nan"},
                                         BadDims{"120;30;8;10", "got 1 part"}));

// ---------------------------------------------------------------------------------------------
// Custom contours

const std::vector<XY> ferry_ccw{{62, 1}, {45, 11}, {-30, 11}, {-38, 8}, {-38, -6}, {-30, -9}, {45, -9}};

TEST(CustomContour, RoundTripsAndDerivesDimensionsFromItsExtent) {
    const Hull hull = Hull::from_contour(ferry_ccw, "Ferry");
    EXPECT_EQ(hull.contour(), ferry_ccw);
    EXPECT_EQ(hull.name(), "Ferry");
    EXPECT_EQ(hull.dimensions(), (Dimensions{62, 38, 9, 11}));
    EXPECT_DOUBLE_EQ(hull.length(), 100.0);
    EXPECT_DOUBLE_EQ(hull.beam(), 20.0);
    EXPECT_DOUBLE_EQ(hull.radius(), std::hypot(62.0, 1.0));
}

TEST(CustomContour, DropsAClosingPointEqualToTheFirst) {
    auto closed = ferry_ccw;
    closed.push_back(closed.front());
    EXPECT_EQ(Hull::from_contour(closed).contour(), ferry_ccw);
}

TEST(CustomContour, StoresAClockwiseOutlineCounterClockwiseFromTheSameFirstPoint) {
    const std::vector<XY> cw{{62, 1}, {45, -9}, {-30, -9}, {-38, -6}, {-38, 8}, {-30, 11}, {45, 11}};
    Geos geos;
    ASSERT_FALSE(geos.is_ccw(cw));
    EXPECT_EQ(Hull::from_contour(cw).contour(), ferry_ccw);
}

TEST(CustomContour, AcceptsAConcaveOutline) {
    // A hull with a notch in the starboard side: valid, not convex.
    const std::vector<XY> notched{{10, 0}, {5, 3}, {0, 3}, {-1, 1}, {-2, 3}, {-5, 3}, {-5, -3}, {5, -3}};
    EXPECT_EQ(Hull::from_contour(notched).contour(), notched);
}

TEST(CustomContour, AcceptsExactlyWhatGeosCallsAValidPolygonAroundTheReferencePoint) {
    // Small integer coordinates provoke the degenerate cases: collinear edges, a vertex touching
    // an edge, spikes, the reference point on the boundary.
    std::mt19937 rng{20240611};
    std::uniform_int_distribution<int> coord{-3, 3};
    std::uniform_int_distribution<std::size_t> count{3, 7};
    Geos geos;
    int accepted = 0, rejected = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        std::vector<XY> pts(count(rng));
        for (auto& p : pts) p = {static_cast<double>(coord(rng)), static_cast<double>(coord(rng))};
        bool repeats = false;  // GEOS tolerates these; the hull rejects them on purpose
        for (std::size_t i = 0; i < pts.size(); ++i) repeats |= pts[i] == pts[(i + 1) % pts.size()];
        if (repeats) continue;

        const auto poly = geos.polygon(pts);
        const bool geos_ok = geos.is_valid(poly.get()) && geos.contains(poly.get(), geos.point({0, 0}).get());
        bool hull_ok = true;
        try {
            Hull::from_contour(pts);
        } catch (const InputError&) {
            hull_ok = false;
        }
        ASSERT_EQ(hull_ok, geos_ok) << to_wkt(pts) << (geos_ok ? "" : ": " + geos.why_invalid(poly.get()));
        (hull_ok ? accepted : rejected)++;
    }
    EXPECT_GT(accepted, 100);  // the sample holds both kinds
    EXPECT_GT(rejected, 100);
}

TEST(CustomContour, AcceptsAThousandPointsAndRefusesMoreThanTheLimit) {
    const Hull big = Hull::from_contour(shoal::test::wavy_hull(1000));
    EXPECT_EQ(big.contour().size(), 1000u);
    Geos geos;
    EXPECT_TRUE(geos.is_valid(geos.polygon(big.contour()).get()));
    EXPECT_EQ(Hull::from_contour(shoal::test::wavy_hull(Hull::max_points)).contour().size(), Hull::max_points);
    EXPECT_THAT([] { Hull::from_contour(shoal::test::wavy_hull(Hull::max_points + 1)); },
                ThrowsMessage<InputError>(HasSubstr("a contour of 10001 points is more than the 10000 supported")));
}

struct BadContour {
    std::string label;
    std::vector<XY> points;
    std::string expected;
};

class CustomContourRejects : public testing::TestWithParam<BadContour> {};

TEST_P(CustomContourRejects, WithAReason) {
    const auto& p = GetParam();
    EXPECT_THAT([&] { Hull::from_contour(p.points); }, ThrowsMessage<InputError>(HasSubstr(p.expected)));
}

const double nan = std::numeric_limits<double>::quiet_NaN();

INSTANTIATE_TEST_SUITE_P(
    Hull, CustomContourRejects,
    testing::Values(
        BadContour{"TwoPoints", {{10, 0}, {-5, 2}}, "at least 3 points (got 2)"},
        BadContour{"TriangleClosedIsTwoPoints", {{10, 0}, {-5, 2}, {10, 0}}, "at least 3 points (got 2)"},
        BadContour{"RepeatedPoint", {{10, 0}, {-5, 2}, {-5, 2}, {-5, -2}}, "points 1 and 2 are the same point"},
        BadContour{"BowTie", {{10, 2}, {-5, -2}, {-5, 2}, {10, -2}}, "edge 0-1 crosses or touches edge 2-3"},
        BadContour{"PinchedFigureEight", {{10, 0}, {0, 2}, {-10, 0}, {-12, 2}, {-12, -2}, {-10, 0}, {0, -2}},
                   "not a simple polygon"},
        BadContour{"Spike", {{10, 0}, {14, 0}, {12, 0}, {-5, 2}, {-5, -2}}, "not a simple polygon"},
        BadContour{"Collinear", {{10, 0}, {-10, 0}, {0, 0}}, "edge 0-1 doubles back along edge 2-0"},
        BadContour{"ReferenceOutside", {{10, 0}, {2, 2}, {2, -2}}, "(0,0) is outside"},
        BadContour{"ReferenceOnAnEdge", {{10, 0}, {0, 2}, {0, -2}}, "(0,0) lies on contour edge 1-2"},
        BadContour{"NotFinite", {{10, 0}, {-5, nan}, {-5, -2}}, "contour point 1"}),
    [](const testing::TestParamInfo<BadContour>& param_info) { return param_info.param.label; });

// ---------------------------------------------------------------------------------------------
// Ship files

TEST(ShipFile, LoadsAShipWithoutContour) {
    const Hull hull = Hull::load(data_path("ships/tanker.json"));
    EXPECT_EQ(hull.name(), "Example Tanker");
    EXPECT_EQ(hull.dimensions(), (Dimensions{200, 50, 20, 24}));
    EXPECT_DOUBLE_EQ(hull.length(), 250.0);
    EXPECT_DOUBLE_EQ(hull.beam(), 44.0);
    EXPECT_DOUBLE_EQ(hull.draught(), 14.5);
    expect_fits_box(hull, {200, 50, 20, 24}, 36, true);
}

TEST(ShipFile, LoadsAShipWithContour) {
    const Hull hull = Hull::load(data_path("ships/ferry-contour.json"));
    EXPECT_EQ(hull.name(), "Example Ferry");
    EXPECT_EQ(hull.contour(), ferry_ccw);  // the file closes the ring; the closing point is dropped
    EXPECT_EQ(hull.dimensions(), (Dimensions{62, 38, 9, 11}));
    EXPECT_DOUBLE_EQ(hull.draught(), 4.8);
}

/// Writes `text` to a fresh file in the test's temporary folder and returns its path.
std::string temp_ship(const std::string& file, const std::string& text) {
    const std::string path = testing::TempDir() + file;
    std::ofstream{path} << text;
    return path;
}

TEST(ShipFile, KeepsTheFilesDimensionsWhenTheContourIsSmallerThanTheBox) {
    const auto path = temp_ship("small-contour.json", R"({"name": "S", "a": 10, "b": 5, "c": 2, "d": 2,
        "contour": [[9, 0], [-4, 1.5], [-4, -1.5]]})");
    const Hull hull = Hull::load(path);
    EXPECT_EQ(hull.dimensions(), (Dimensions{10, 5, 2, 2}));
    EXPECT_EQ(hull.contour().size(), 3u);
}

TEST(ShipFile, AcceptsSmallDisagreementsWithinTheTolerances) {
    // length within 1 % of a + b (200 * 1 % = 2 m > 0.5 m); beam within 0.5 m of c + d (1 % = 0.1 m).
    EXPECT_NO_THROW(Hull::load(temp_ship(
        "tol-length.json", R"({"name": "T", "length": 201.9, "beam": 10.45, "a": 150, "b": 50, "c": 5, "d": 5})")));
    // A contour point up to 1 cm beyond the box.
    EXPECT_NO_THROW(Hull::load(temp_ship("tol-contour.json",
                                         R"({"name": "T", "a": 10, "b": 5, "c": 2, "d": 2,
                                            "contour": [[10.009, 0], [-5.009, 2.009], [-5, -2.009]]})")));
    EXPECT_THAT(
        [] { Hull::load(temp_ship("tol-beam.json", R"({"name": "T", "beam": 10.6, "a": 150, "b": 50, "c": 5, "d": 5})")); },
                ThrowsMessage<InputError>(HasSubstr("'beam' (10.6) disagrees with 'c' + 'd'")));
    EXPECT_THAT(
        [] {
            Hull::load(temp_ship("tol-length-far.json", R"({"name": "T", "length": 203, "a": 150, "b": 50, "c": 5, "d": 5})"));
        },
                ThrowsMessage<InputError>(HasSubstr("'length' (203) disagrees with 'a' + 'b' (150 + 50 = 200)")));
    EXPECT_THAT([] {
        Hull::load(temp_ship("tol-contour-far.json", R"({"name": "T", "a": 10, "b": 5, "c": 2, "d": 2,
                                                        "contour": [[10.011, 0], [-5, 2], [-5, -2]]})"));
    }, ThrowsMessage<InputError>(HasSubstr("'contour[0]' = [10.011,0] lies outside the box")));
}

TEST(ShipFile, MissingFileIsNamed) {
    EXPECT_THAT([] { Hull::load(data_path("ships/does-not-exist.json")); },
                ThrowsMessage<InputError>(AllOf(HasSubstr("does-not-exist.json"), HasSubstr("Cannot open"))));
}

struct BadShipFile {
    std::string file;                   ///< in tests/data/ships/
    std::vector<std::string> expected;  ///< substrings of the message besides the file name
};

class ShipFileRejects : public testing::TestWithParam<BadShipFile> {};

TEST_P(ShipFileRejects, NamingTheFileAndTheField) {
    const auto& p = GetParam();
    try {
        Hull::load(data_path("ships/" + p.file));
        FAIL() << p.file << " was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_THAT(message, HasSubstr("In ship file '"));
        EXPECT_THAT(message, HasSubstr(p.file + "'"));
        for (const auto& s : p.expected) EXPECT_THAT(message, HasSubstr(s));
    }
}

const std::vector<BadShipFile> bad_ship_files{
        BadShipFile{"bad-not-json.json", {"not valid JSON at byte 25", "line 1, column 25"}},
        BadShipFile{"bad-empty.json", {"not valid JSON at byte 1"}},
        BadShipFile{"bad-number-overflow.json", {"not valid JSON", "1e999"}},
        BadShipFile{"bad-top-level-array.json", {"top level must be a JSON object (got array)"}},
        BadShipFile{"bad-unknown-field.json", {"unknown field 'lenght' (did you mean 'length'?)"}},
        BadShipFile{"bad-missing-name.json", {"'name' is required"}},
        BadShipFile{"bad-name-not-string.json", {"'name' must be a string (got 42)"}},
        BadShipFile{"bad-missing-d.json", {"'d' is required"}},
        BadShipFile{"bad-a-not-number.json", {"'a' must be a number (got \"10\")"}},
        BadShipFile{"bad-zero-c.json", {"'c' must be > 0 (got 0)"}},
        BadShipFile{"bad-negative-beam.json", {"'beam' must be > 0 (got -3.5)"}},
        BadShipFile{"bad-length-mismatch.json", {"'length' (120) disagrees with 'a' + 'b' (80 + 20 = 100)"}},
        BadShipFile{"bad-beam-mismatch.json", {"'beam' (20) disagrees with 'c' + 'd' (8 + 8 = 16)"}},
        BadShipFile{"bad-negative-draught.json", {"'draught' must be >= 0 (got -1)"}},
        BadShipFile{"bad-contour-not-array.json", {"'contour' must be an array"}},
        BadShipFile{"bad-contour-too-few.json", {"'contour' needs at least 3 points (got 2)"}},
        BadShipFile{"bad-contour-point-not-pair.json", {"'contour[1]' must be a pair", "[-5,2,0]"}},
        BadShipFile{"bad-contour-outside-box.json",
                    {"'contour[2]' = [-5,-2.5] lies outside the box", "x must be in [-5, 10] and y in [-2, 2]"}},
        BadShipFile{"bad-contour-self-intersecting.json", {"'contour': contour is not a simple polygon"}},
        BadShipFile{"bad-contour-repeated-point.json", {"'contour': contour points 1 and 2 are the same point"}},
        BadShipFile{"bad-contour-reference-outside.json", {"'contour': the reference point (0,0) is outside"}}};

INSTANTIATE_TEST_SUITE_P(
    Hull, ShipFileRejects, testing::ValuesIn(bad_ship_files),
    [](const testing::TestParamInfo<BadShipFile>& param_info) {
        const std::string& file = param_info.param.file;
        std::string name = file.substr(0, file.find('.'));
        std::replace(name.begin(), name.end(), '-', '_');
        return name;
    });

TEST(ShipFile, EveryFixtureHasATest) {
    // A bad-*.json fixture must be listed above; every other ship file must load.
    std::size_t good = 0;
    for (const auto& entry : std::filesystem::directory_iterator{data_path("ships")}) {
        const std::string file = entry.path().filename().string();
        if (file.rfind("bad-", 0) == 0) {
            EXPECT_TRUE(std::any_of(bad_ship_files.begin(), bad_ship_files.end(),
                                    [&](const BadShipFile& b) { return b.file == file; }))
                << file << " has no test in bad_ship_files";
        } else {
            EXPECT_NO_THROW(Hull::load(entry.path().string())) << file;
            ++good;
        }
    }
    EXPECT_GE(good, 2u);
}

/// The schema cannot be run from C++ here (no validator in the toolchain), so this keeps the
/// reader and schemas/ship.schema.json in step: the same field names, the same required ones.
TEST(ShipFile, ReaderAgreesWithTheSchemaOnFieldNames) {
    std::ifstream in{data_path("../../schemas/ship.schema.json")};
    ASSERT_TRUE(in) << "schemas/ship.schema.json not found";
    const auto schema = nlohmann::json::parse(in);
    ASSERT_EQ(schema.at("additionalProperties"), false);

    const nlohmann::json full = {{"name", "S"},   {"length", 15}, {"beam", 4},     {"a", 10},
                                 {"b", 5},        {"c", 2},       {"d", 2},        {"draught", 1},
                                 {"$schema", "x"}, {"contour", {{10, 0}, {-5, 2}, {-5, -2}}}};
    std::set<std::string> schema_fields, example_fields;
    for (const auto& [key, value] : schema.at("properties").items()) schema_fields.insert(key);
    for (const auto& [key, value] : full.items()) example_fields.insert(key);
    ASSERT_EQ(schema_fields, example_fields) << "update this test together with the schema and the reader";
    EXPECT_NO_THROW(Hull::load(temp_ship("full.json", full.dump())));

    const std::set<std::string> required(schema.at("required").begin(), schema.at("required").end());
    for (const auto& key : schema_fields) {
        auto doc = full;
        doc.erase(key);
        const auto path = temp_ship("without-" + std::string{key == "$schema" ? "schema" : key} + ".json", doc.dump());
        if (required.count(key))
            EXPECT_THAT([&] { Hull::load(path); }, ThrowsMessage<InputError>(HasSubstr("'" + key + "' is required")));
        else
            EXPECT_NO_THROW(Hull::load(path)) << key << " is optional in the schema";
    }
}

}  // namespace
