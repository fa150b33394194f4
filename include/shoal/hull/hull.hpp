#pragma once
/// The ship's outline in the *ship frame*: x forward, y starboard, metres from the position
/// reference point (the GNSS antenna that AIS positions refer to). A hull comes from AIS
/// dimensions A/B/C/D (a generated outline with a pointed bow), from a custom contour, or from
/// a ship file (schemas/ship.schema.json). Every hull's contour is a simple polygon that holds
/// the reference point strictly inside (except the 3-point triangle of `from_dimensions_n`).

#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::hull {

/// AIS dimensions: metres from the position reference point to bow (a), stern (b), port (c), starboard (d).
struct Dimensions {
    double a = 0, b = 0, c = 0, d = 0;
    friend bool operator==(const Dimensions&, const Dimensions&) = default;
    /// "a=120 b=30 c=8 d=10", for messages and test output.
    friend std::ostream& operator<<(std::ostream& os, const Dimensions& dims);
};

class Hull {
public:
    /// Number of points of the generated outline.
    static constexpr std::size_t default_points = 36;
    /// Most points a custom outline may have: the check costs time in proportion to the points,
    /// and validating the outline compares every pair of edges.
    static constexpr std::size_t max_points = 10000;
    /// Largest hull accepted, metres: the longest ships are about 400 m long and 70 m wide, so
    /// more is a wrong unit or a corrupt value (and would make every check slow).
    static constexpr double max_length_m = 500.0;
    static constexpr double max_beam_m = 100.0;
    /// Smallest length (a + b) and beam (c + d) of a hull made from dimensions, metres (a
    /// millimetre: a hull of a centimetre is a point probe): a smaller one makes an outline
    /// whose edges' lengths and area round to nothing (before, --dims 1e-300,... gave an
    /// outline of no area, said of every track as if the tracks were wrong).
    static constexpr double min_extent_m = 0.001;
    /// Most bytes a ship file may hold.
    static constexpr std::size_t max_file_bytes = std::size_t{1} << 20;
    /// True when a + b and c + d lie within [min_extent_m, max_length_m] and [min_extent_m,
    /// max_beam_m] (a track's AIS dimensions that are not: the default hull serves it).
    static bool plausible(const Dimensions& dims) noexcept;

    /// 36-point outline with a pointed bow that exactly fits the box x in [-b, a], y in [-c, d]
    /// (touches all four extents: bow tip at x=a, stern at x=-b, sides at y=-c and y=d).
    /// Throws InputError unless a, b, c, d are finite and > 0 and the hull is plausible().
    static Hull from_dimensions(const Dimensions& dims, std::string name = {});

    /// The same outline with n points (n >= 3), e.g. coarser ones for benchmarks: a parabolic
    /// pointed bow, parallel midbody, transom stern with rounded quarters when n allows.
    /// n = 3 is the triangle bow tip + stern corners, which may miss the reference point.
    static Hull from_dimensions_n(const Dimensions& dims, std::size_t n, std::string name = {});

    /// Custom outline (x forward, y starboard); validated: >= 3 points, finite, simple polygon
    /// (no self-intersection, no repeated consecutive points; a closing point equal to the first
    /// is dropped), at most max_points points, reference point (0,0) strictly inside. Dimensions come from its extent (not bounded: the audit's circle around a hull is one).
    /// A clockwise outline is reversed, so contour() is always counter-clockwise (see below).
    static Hull from_contour(std::vector<geo::XY> contour, std::string name = {});

    /// Parses "A,B,C,D" (the CLI's --dims); the error message names the bad part, and the
    /// option as `Hull::dims` (in_terms_of gives the front end's name).
    static Hull from_dims_string(const std::string& text);

    /// Loads a ship file per schemas/ship.schema.json. Every error names the file and the field,
    /// e.g. "In ship file 'x.json': 'beam' must be > 0 (got -3.5)". Read through GDAL's virtual
    /// file layer (a .gz, a zip of one file, `-` for standard input), at most max_file_bytes.
    static Hull load(const std::string& path);
    /// The same, from a ship file's text already in memory; `name` stands for the file in messages.
    static Hull parse(std::string_view text, const std::string& name);

    const std::string& name() const noexcept { return m_name; }
    /// Open ring (first point not repeated), counter-clockwise when x and y are read as a
    /// right-handed plane (positive shoelace area): bow tip, starboard side, stern, port side.
    const std::vector<geo::XY>& contour() const noexcept { return m_contour; }
    /// From the file or the arguments, or derived from the contour's extent.
    Dimensions dimensions() const noexcept { return m_dims; }
    double length() const noexcept { return m_dims.a + m_dims.b; }  ///< a + b, metres
    double beam() const noexcept { return m_dims.c + m_dims.d; }    ///< c + d, metres
    double draught() const noexcept { return m_draught_m; }         ///< metres; 0 when not given
    /// Max distance from the reference point to a contour point, metres: a circle of this
    /// radius around the position holds the hull at any heading.
    double radius() const noexcept { return m_radius_m; }

    /// The contour at a pose: reference point at `position` (local metres), bow pointing at
    /// `heading_deg`, clockwise from the local +y axis (grid north). Writes into `out`
    /// (resized to contour().size()) so a per-frame caller reuses one buffer.
    void place(geo::XY position, double heading_deg, std::vector<geo::XY>& out) const;
    std::vector<geo::XY> placed(geo::XY position, double heading_deg) const;

private:
    Hull(std::string name, std::vector<geo::XY> contour, Dimensions dims, double draught_m);

    std::string m_name;
    std::vector<geo::XY> m_contour;
    Dimensions m_dims;
    double m_draught_m = 0.0;
    double m_radius_m = 0.0;
};  // class Hull

}  // namespace shoal::hull
