#pragma once
/// Where each row of a shard's report goes in one run's report, for `merge` (report/merge.hpp):
/// the GeoJSON part's `shoal.part` member and the GeoPackage part's `part` table hold it.
///
/// Keys (JSON arrays compared element by element; a track's position is its place among the
/// run's tracks, AuditResult::track_positions):
/// - `inputs`: the files read; `tracks`: each track's position;
/// - `features` (GeoJSON): a track event's track position; an encounter (exercise mode) its
///   encounter key [start_s, position of a, position of b, kind], the order one run sorts
///   them in (audit.cpp); a breach (--assess) [its trainee's position], after both;
/// - `scores` (--assess): each score's trainee position;
/// - `problems`: [group, position] (report_fields.hpp: ProblemRow);
/// - `approaches`: [position of a, position of b] of each closest approach (one run's order);
/// - GeoPackage only: `events`, `poses` (track positions), `encounters` (encounter keys),
///   `breaches` (--assess: [trainee position]),
///   `hulls` (a track position, or an encounter key), and `project`, the QGIS project's view
///   of the part (qgis_project.hpp: ProjectView: `extent` the tracks' box, `chart` the chart's). The coast layer needs no positions: merge
///   orders its features by each one's `tile` field (a tile's features are the same in every
///   part, chart_layer.hpp).
#include <nlohmann/json.hpp>

#include <shoal/audit/audit.hpp>

namespace shoal::report {

/// The positions of `r`'s rows; `gpkg`: with the keys of the GeoPackage's own layers (the
/// project's view with the chart's lon/lat box `chart`, RunInfo::chart_lonlat).
nlohmann::ordered_json part_order(const audit::AuditResult& r, bool gpkg, const geo::Box& chart);

}  // namespace shoal::report
