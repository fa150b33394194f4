#pragma once
/// The report's `coast` layer: the chart the run was checked against (land, and with a
/// limiting depth the shallow areas and dangers, with their charted depths), cut with GEOS
/// into tiles of a fixed lon/lat tiling and kept only in the tiles the run's tracks pass
/// within chart_margin_m of.
///
/// Merge contract: a tile's features depend only on the chart and the tile (never on the
/// tracks or the grid), one feature per (tile, kind, danger, depth), sorted by tile key then
/// kind, danger and depth; so the union of the tiles of shard reports of one run is exactly
/// the coast layer of that run done at once.
///
/// Tiles are chart_tile_deg x chart_tile_deg degrees: tile "RrrrrCcccc" covers latitudes
/// [(r - 1800) t, (r - 1799) t) and longitudes [(c - 3600) t, (c - 3599) t), t = chart_tile_deg.
///
/// Polygons are rebuilt from the coast reader's closed rings (land or hazard on the left:
/// counter-clockwise shells, clockwise holes) in order of decreasing area, a shell added and a
/// hole taken away, so that a lake in an island and an island in that lake come out right.
/// Lines with the land side unknown (a COALNE without LNDARE) bound no area and are not drawn.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/coast/coastline.hpp>

namespace shoal::report {

inline constexpr double chart_tile_deg = 0.05;
inline constexpr double chart_margin_m = 5000.0;

/// A tile of the tiling: column (longitude) and row (latitude) numbers, both >= 0.
struct ChartTile {
    int col = 0, row = 0;
    auto operator<=>(const ChartTile&) const = default;
};
std::string tile_key(ChartTile t);
/// The tile a tile_key names; none for text that is not one.
std::optional<ChartTile> parse_tile_key(const std::string& key);
/// The tile holding lon/lat `p`.
ChartTile tile_of(geo::LonLat p);

/// Adds to `out` the tiles within `margin_m` of the polyline `line` (every point and the
/// segments between them).
void add_tiles_near(std::set<ChartTile>& out, const std::vector<geo::LonLat>& line, double margin_m = chart_margin_m);

struct ChartFeature {
    ChartTile tile;
    coast::HazardKind kind = coast::HazardKind::land;
    coast::DangerKind danger = coast::DangerKind::none;
    double depth_m = 0;  ///< NaN for land or unknown
    /// Polygons of the tile (lon/lat): each polygon a shell (counter-clockwise) then its holes, closed.
    std::vector<std::vector<std::vector<geo::LonLat>>> polygons;
};

/// The chart `coast` cut to `tiles`, in the order of the merge contract above; the tiles on
/// `jobs` threads (0: every core), the same features on any number.
std::vector<ChartFeature> chart_features(const coast::Coastline& coast, const std::set<ChartTile>& tiles, unsigned jobs = 1);
/// The tiles within chart_margin_m of every piece of the run's tracks (add_tiles_near), the
/// tracks on `jobs` threads: the same tiles on any number.
std::set<ChartTile> tiles_near(const audit::AuditResult& r, unsigned jobs = 1);
/// The chart cut to the tiles near every piece of the run's tracks: the report's `coast` layer.
std::vector<ChartFeature> chart_features_near(const audit::AuditResult& r, const coast::Coastline& chart, unsigned jobs = 1);

}  // namespace shoal::report
