#pragma once
/// `CoastGrid`: the coastline in local metres, cut into square cells of size s.
///
/// A cell is *coast* when coastline passes through it (it then holds its clipped segments,
/// point order kept), *land* when land covers it wholly, else *water*. Cells are indexed
/// (i, j) from the grid's south-west corner. For each coast cell the winding number of a
/// reference point inside it is kept, so a point's side (land or water) is exact from that
/// one cell's segments: count the signed crossings of the path from the reference point.
///
/// "Land" here is anything the hull must not touch: land, structures, and shallow water and
/// dangers, stored exactly like land. Which one a segment bounds is kept per polyline (`hazard`).
///
/// A grid built from a chart holds every depth area and danger with its charted depth; its
/// own queries (state, segments, winding) see all of them. What is a hazard for one vessel
/// depends on its limiting depth: `for_depth(limit)` gives the grid of exactly the hazards
/// for that limit (land, and the depth areas and dangers charted shallower, or of unknown
/// depth), derived from this one without clipping again (each distinct charted depth is a
/// *level*: per coast cell the winding number of its reference point at every level where it
/// changes, per land cell the first level that covers it). One build serves a whole fleet.

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <shoal/coast/coastline.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::grid {

enum class CellState : std::uint8_t { water, land, coast, outside };

const char* to_string(CellState s) noexcept;

struct Segment {
    geo::XY a;
    geo::XY b;
};

/// Where the grid came from: the sources and how they were read. Kept in the cache.
struct GridSource {
    /// The grid's default limiting depth (metres; `shoal import --hazard-depth`): the one a
    /// Detector made without a depth of its own uses. NaN: none (land only), and in a grid
    /// made by CoastGrid::for_depth.
    double limiting_depth_m = NAN;
    double danger_radius_m = 0;            ///< radius of the polygons point dangers became
    std::string depth_field;               ///< --depth-field ("" = none)
    std::uint64_t shallow_polylines = 0;   ///< polylines bounding shallow water
    std::uint64_t danger_polylines = 0;    ///< polylines bounding dangers
    std::uint64_t hazard_features = 0;     ///< depth areas and dangers kept (features)
    std::uint64_t unknown_depth = 0;       ///< of which with no depth in the chart (a hazard for any limit)
    std::uint64_t structure_polylines = 0; ///< polylines bounding structures (piers, wharves, pontoons, dolphins, hulks)
    std::uint64_t structure_features = 0;  ///< structures kept (features): hazards for every vessel
    std::vector<std::string> inputs;       ///< paths as given to import
    std::vector<std::string> layers;       ///< "file:layer" of every layer read
    std::vector<std::string> layer_option; ///< --layer names ("" = default set)
    std::string source_crs;                ///< --source-crs ("" = none)
    std::uint64_t fingerprint = 0;         ///< XXH3 of the sources' bytes and the options
    std::uint64_t input_vertices = 0;      ///< vertices read
    std::uint64_t polylines = 0;           ///< boundary polylines made of them
    std::uint64_t land_polylines = 0;      ///< of which with the land side known
};

/// A grid fingerprint as 16 hex digits, as reports, `info` and the cache's file names show it.
std::string fingerprint_hex(std::uint64_t fingerprint);

/// The segment of a grid nearest to a point (CoastGrid::nearest_segment).
struct NearestSegment {
    double dist2 = INFINITY;            ///< squared distance; INFINITY when none was found
    geo::XY point{};                    ///< the nearest point on the segment
    const Segment* segment = nullptr;   ///< the segment (an element of some segments(i, j)), or null
    std::uint32_t polyline = 0xFFFFFFFFu;  ///< the polyline it was clipped from (CoastGrid::no_polyline if none)
};

/// Figures of one build, for `shoal import` and the benchmark (seconds).
struct BuildStats {
    double project_s = 0, clip_s = 0, state_s = 0, total_s = 0;
    std::uint64_t incidences = 0;  ///< (cell, segment) pairs found by walking the data
    std::uint64_t clip_calls = 0;  ///< GEOSClipByRect calls
};

class CoastGrid {
public:
    /// Largest number of cells a grid may have (4 bytes each).
    static constexpr std::uint64_t max_cells = std::uint64_t{1} << 27;
    /// Largest cell edge (100 km: the default for the whole globe is about 5 km); a larger one
    /// leaves no cell whose reference point is clear of the coast.
    static constexpr double max_cell_m = 100'000.0;

    /// Builds the grid of `coast` in `frame` with cells of `cell_m` metres. Throws UsageError
    /// when `cell_m` is not in (0, max_cell_m] or the extent needs more than `max_cells` cells.
    static CoastGrid build(const coast::Coastline& coast, geo::LocalFrame frame, double cell_m,
                           BuildStats* stats = nullptr);
    /// Same from already projected polylines (tests use hand-made shapes in metres).
    static CoastGrid build(const std::vector<coast::LocalPolyline>& lines, geo::LocalFrame frame, double cell_m,
                           BuildStats* stats = nullptr);

    const geo::LocalFrame& frame() const noexcept { return m_frame; }
    double cell_size() const noexcept { return m_cell; }
    geo::XY origin() const noexcept { return {m_x0, m_y0}; }
    int nx() const noexcept { return m_nx; }
    int ny() const noexcept { return m_ny; }
    /// The covered area: everything outside it is "outside" (uncovered, never clear).
    geo::Box extent() const noexcept { return {m_x0, m_y0, m_x0 + m_nx * m_cell, m_y0 + m_ny * m_cell}; }
    bool has_land_side() const noexcept { return m_has_land_side; }
    /// Cells were clipped with their box grown by this many metres (a few units in the last
    /// place of the coordinates), so a segment lying on a cell border is kept by both cells.
    double clip_slack() const noexcept { return m_clip_slack; }

    bool valid_cell(int i, int j) const noexcept { return i >= 0 && j >= 0 && i < m_nx && j < m_ny; }
    /// Cell of a point (may be out of range: check valid_cell).
    int col_of(double x) const noexcept { return cell_index((x - m_x0) / m_cell); }
    int row_of(double y) const noexcept { return cell_index((y - m_y0) / m_cell); }
    geo::Box cell_box(int i, int j) const noexcept {
        return {m_x0 + i * m_cell, m_y0 + j * m_cell, m_x0 + (i + 1) * m_cell, m_y0 + (j + 1) * m_cell};
    }
    CellState state(int i, int j) const noexcept;
    /// The clipped segments of cell (i, j): empty unless it is a coast cell.
    std::span<const Segment> segments(int i, int j) const noexcept;
    /// Whether segment k of `segments(i, j)` bounds land (land side known).
    bool segment_is_boundary(int i, int j, std::size_t k) const noexcept;
    /// Reference point of cell (i, j) and its winding number (coast cells).
    geo::XY reference_point(int i, int j) const noexcept;

    /// What polyline `k` bounds (land, shallow water, a danger, a structure, with its kind and
    /// name); `k` < polyline_count().
    const coast::Hazard& hazard(std::uint32_t k) const noexcept { return m_hazards[k]; }
    std::size_t polyline_count() const noexcept { return m_hazards.size(); }
    /// The polyline a segment was clipped from (`s` must be an element of some segments(i, j)).
    std::uint32_t polyline_of(const Segment& s) const noexcept {
        return m_seg_info[static_cast<std::size_t>(&s - m_segments.data())] & ~boundary_bit;
    }
    /// The segment nearest to p (any segment), read outward from p's cell, skipping the cells
    /// and chunks of segments farther than the nearest found; none farther than `max_m`
    /// (one at max_m may be returned: compare the distance).
    NearestSegment nearest_segment(geo::XY p, double max_m = INFINITY) const noexcept;
    /// The polyline nearest to p (any segment); no_polyline for a grid without segments.
    std::uint32_t nearest_polyline(geo::XY p) const noexcept;
    /// For p inside land or hazards: the nearest boundary ring that holds p (p lies on its
    /// land side at the ring's nearest point), i.e. the innermost ring around p: the area
    /// p is in. Falls back to the nearest polyline when no ring is found to hold p.
    std::uint32_t enclosing_polyline(geo::XY p) const;
    static constexpr std::uint32_t no_polyline = 0xFFFFFFFFu;

    /// Winding number of land around p: > 0 is land. 0 outside the grid. Exact from one cell.
    /// `on_boundary` is set when p lies on a land boundary segment.
    int winding(geo::XY p, bool* on_boundary = nullptr) const noexcept;
    /// The same winding number as winding(p), counted from another point of p's cell whose
    /// winding is known: `from`, with `w_from` = winding(from) and `from` on no boundary (as
    /// winding() said). A path inside one cell meets the cell's segments only, so the count is
    /// the same; a short path meets fewer of them than the one from the cell's reference point.
    /// `from` must lie in p's cell (col_of, row_of): else this is winding(p).
    int winding_from(geo::XY from, int w_from, geo::XY p, bool* on_boundary = nullptr) const noexcept;
    /// winding_from(from, w_from, p), trying only `segs` (indices in the grid's array of
    /// segments): they must hold every land boundary segment of p's cell whose box meets a box
    /// that holds both from and p. Many points asked near one place then try a few segments each.
    int winding_along(geo::XY from, int w_from, geo::XY p, std::span<const std::uint32_t> segs, bool* on_boundary = nullptr) const noexcept;
    bool is_land(geo::XY p) const noexcept;

    /// Consecutive segments (by their index in the grid's array of segments, so a chunk may
    /// straddle two cells) are grouped in chunks of this many, each with its box: a reader can
    /// skip a whole chunk that is far from what it looks for. A cell crossed by thousands of
    /// segments then costs in proportion to the chunks near the hull, not to all its segments.
    static constexpr std::size_t chunk_segments = 8;
    /// Box of chunk k: segments [k * chunk_segments, (k + 1) * chunk_segments).
    std::span<const geo::Box> chunk_boxes() const noexcept { return m_chunk_box; }
    /// Chunks are grouped again in blocks of this many segments (8 chunks), each with its box:
    /// a coast cell of a harbour holds ~760 segments, ~95 chunks, and a reader (the winding
    /// number's path, a contact's reach) meets few of them.
    static constexpr std::size_t block_segments = 64;
    /// Box of block k: segments [k * block_segments, (k + 1) * block_segments).
    std::span<const geo::Box> block_boxes() const noexcept { return m_block_box; }
    /// Index in the grid's array of segments of the first element of `segs`, a non-empty span
    /// returned by segments(i, j).
    std::size_t index_of(std::span<const Segment> segs) const noexcept {
        return static_cast<std::size_t>(segs.data() - m_segments.data());
    }

    std::size_t cell_count() const noexcept { return m_slot.size(); }
    std::size_t coast_cell_count() const noexcept { return m_ref_winding.size(); }
    std::size_t land_cell_count() const noexcept;
    std::size_t segment_count() const noexcept { return m_segments.size(); }
    /// Bytes the grid's arrays occupy in memory.
    std::size_t memory_bytes() const noexcept;

    /// The grid of the hazards for a vessel of limiting depth `limit_m` (metres): land, and the
    /// depth areas and dangers whose charted depth is under it or unknown; none: land only.
    /// Exact (the same segments, cut the same way) and built once per level, then kept: the
    /// reference stays valid while this grid lives, and calls from several threads are safe.
    /// This grid itself when the limit covers every hazard it holds (or it holds none).
    const CoastGrid& for_depth(std::optional<double> limit_m) const;
    /// Distinct charted depths of the depth areas and dangers held (NaN first when some have
    /// none), ascending: limits between two of them give the same hazards.
    std::span<const double> charted_depths() const noexcept { return m_level_depth; }
    /// Which level a limit selects: 0 land only, else how many charted depths are hazards.
    std::size_t level_of(std::optional<double> limit_m) const noexcept;

    GridSource& source() noexcept { return m_source; }
    const GridSource& source() const noexcept { return m_source; }

    friend bool operator==(const CoastGrid& a, const CoastGrid& b);

    /// A number no other grid object of this process has had: a copy, a moved-to grid and a
    /// grid assigned to take a new one. A key for answers about this grid kept outside it (the
    /// windings a thread knows, check/contacts.cpp).
    std::uint64_t instance() const noexcept { return m_instance.number; }

private:
    friend class GridFile;
    /// floor(f) as a cell index, clamped to +-2^30 (far outside any grid, with room for i + 1):
    /// a point millions of cells away, or NaN, must not overflow the int.
    static int cell_index(double f) noexcept {
        constexpr double limit = 1073741824.0;
        const double c = std::floor(f);
        return c >= -limit ? (c <= limit ? static_cast<int>(c) : static_cast<int>(limit)) : static_cast<int>(-limit);
    }
    static constexpr std::uint32_t water_slot = 0xFFFFFFFFu;
    static constexpr std::uint32_t land_slot = 0xFFFFFFFEu;
    static constexpr std::uint32_t boundary_bit = 0x80000000u;

    explicit CoastGrid(geo::LocalFrame frame) : m_frame(std::move(frame)) {}
    void assign_windings(const std::vector<coast::LocalPolyline>& lines);
    /// Fills m_chunk_box and m_block_box from m_segments (after a build or a load: they are not
    /// saved); false when a segment has a coordinate that is not finite (its boxes are then
    /// not to be used).
    bool compute_chunk_boxes();
    bool reference_points_clear() const;
    /// Winding at p of coast cell slot `s`, counted from `r` (winding `w`) in the same cell.
    int winding_in_cell(std::uint32_t s, geo::XY r, int w, geo::XY p, bool* on_boundary) const noexcept;
    std::uint32_t slot(int i, int j) const noexcept {
        return m_slot[static_cast<std::size_t>(j) * static_cast<std::size_t>(m_nx) + static_cast<std::size_t>(i)];
    }

    /// Levels: the level of a polyline (0 land, k the k-th charted depth) and the grid of one level.
    void assign_levels();
    CoastGrid make_level(std::size_t level) const;
    std::uint16_t polyline_level(std::uint32_t k) const noexcept { return m_poly_level.empty() ? 0 : m_poly_level[k]; }
    /// Reference winding of coast cell `s` at `level` (< the top level).
    std::int32_t level_winding(std::uint32_t s, std::size_t level) const noexcept;

    /// Grids made by for_depth, by level; a copy of the grid starts with none.
    struct Levels;
    struct LevelCache {
        std::unique_ptr<Levels> p;
        LevelCache();
        LevelCache(const LevelCache&);
        LevelCache& operator=(const LevelCache&);
        LevelCache(LevelCache&&) noexcept;
        LevelCache& operator=(LevelCache&&) noexcept;
        ~LevelCache();
    };

    /// instance(): drawn anew whenever the grid is made, copied, moved or assigned.
    struct InstanceNumber {
        std::uint64_t number;
        InstanceNumber() noexcept;
        InstanceNumber(const InstanceNumber&) noexcept;
        InstanceNumber& operator=(const InstanceNumber&) noexcept;
    };

    InstanceNumber m_instance;
    geo::LocalFrame m_frame;
    double m_cell = 0;
    double m_x0 = 0, m_y0 = 0;
    int m_nx = 0, m_ny = 0;
    double m_clip_slack = 0;
    double m_ref_fx = 0, m_ref_fy = 0;  ///< reference point of a cell, as fractions of the cell
    bool m_has_land_side = false;
    std::vector<std::uint32_t> m_slot;        ///< per cell: water_slot, land_slot or coast index
    std::vector<std::uint32_t> m_seg_offset;  ///< per coast cell + 1: CSR offsets into m_segments
    std::vector<std::int32_t> m_ref_winding;  ///< per coast cell: winding of its reference point
    std::vector<Segment> m_segments;          ///< clipped segments, cell by cell, order kept
    std::vector<std::uint32_t> m_seg_info;    ///< per segment: polyline index | boundary_bit
    std::vector<coast::Hazard> m_hazards;     ///< per polyline: what it bounds
    std::vector<geo::Box> m_chunk_box;        ///< per chunk of chunk_segments segments: its box
    std::vector<geo::Box> m_block_box;        ///< per block of block_segments segments: its box
    // Levels (empty for a grid of land only, or one made by for_depth):
    std::vector<double> m_level_depth;        ///< charted depth of level k + 1 (NaN: unknown), ascending
    std::vector<std::uint32_t> m_lw_offset;   ///< per coast cell + 1: CSR offsets into m_lw_level / m_lw_winding
    std::vector<std::uint16_t> m_lw_level;    ///< level where the reference winding changes (below the top level)
    std::vector<std::int32_t> m_lw_winding;   ///< the winding from that level on
    std::vector<std::uint16_t> m_land_level;  ///< per cell: for a land cell, the first level it is land at
    std::vector<std::uint16_t> m_poly_level;  ///< per polyline: its level (derived, not saved)
    GridSource m_source;
    LevelCache m_levels;
};

/// The cell size for `shoal import`: `cell_m` if > 0, else 2.5 x `ship_length_m` if > 0,
/// else the default (2.5 x a 200 m ship = 500 m); raised when the extent would need more
/// than CoastGrid::max_cells cells and nothing was given. `note` says which rule applied.
double choose_cell_size(double cell_m, double ship_length_m, const geo::Box& extent, std::string* note);

}  // namespace shoal::grid
