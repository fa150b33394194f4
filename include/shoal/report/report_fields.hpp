#pragma once
/// The report's fields, listed once for both writers. Each layer of the report is a table of
/// fields (name, type, unit, rounding, and how to get the value from the audit's result); the
/// GeoJSON writer (geojson_report.cpp) and the GeoPackage writer (gpkg_report.cpp) both iterate
/// these tables, so the two reports carry the same fields with the same names, units and
/// rounding. docs/user-guide.md and schemas/report.schema.json list the same fields (a test
/// checks that).
///
/// Layers and where they go:
///   layer               GeoJSON                                  GeoPackage
///   events              Point features                           Point layer `events`
///   encounters          Point features (exercise mode)           Point layer `encounters` (exercise mode)
///   tracks              `shoal.tracks[]`                         MultiLineString layer `tracks`
///   hulls               (none: one geometry per feature)         Polygon layer `hulls`
///   poses               (none: one geometry per feature)         Polygon layer `poses`
///   coast               (none)                                   MultiPolygon layer `coast` (when the chart is readable)
///   problems            `shoal.problems[]` (null keys left out)  table `problems`
///   closest_approaches  `shoal.closest_approaches[]`             table `closest_approaches` (exercise mode)
///   breaches            Point features, kind "breach" (--assess) Point layer `breaches` (--assess)
///   learned             (none: REPORT.learned.geojson beside it)  Point layer `learned` (--world real)
///   scores              `shoal.assessment.scores[]`              table `scores` (--assess)
///   criteria            `shoal.assessment.criteria[]`            (none)
///   run                 members of `shoal`                       table `run` (one row)
///   summary             `shoal.summary`                          table `summary` (one row)

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <shoal/audit/audit.hpp>
#include <shoal/report/run_info.hpp>

namespace shoal::report {
struct ChartFeature;  // one feature of the `coast` layer (the QGIS packaging: report/qgis/chart_layer.hpp)
}  // namespace shoal::report

namespace shoal::report::fields {

/// datetime: a UTC time, ISO 8601 text in GeoJSON and a DateTime field in the GeoPackage.
enum class Type { text, integer, real, boolean, datetime };

/// A field's value; std::monostate is null.
using Value = std::variant<std::monostate, std::string, std::int64_t, double, bool>;

/// How report::merge combines a summary field of the parts into one run's.
enum class Merge {
    sum,        ///< added up (tracks, fixes, events)
    per_input,  ///< a figure of the files read, which every shard of the same inputs reads: counted once per set of inputs
    min_time,   ///< the earliest (ISO 8601 UTC; null when none)
    max_time,   ///< the latest
};

template <class Row>
struct Field {
    const char* name;
    Type type;
    const char* unit;  ///< "m", "s", "kn", "deg", "degrees (WGS84)", "ISO 8601 UTC", or "" (none)
    int decimals;      ///< reals: rounded to this many decimals (-1: as computed); a value that is not finite is null
    Value (*get)(const Row&);
    /// The field exists only when this holds (exercise-mode fields); null: always.
    bool (*present)(const audit::AuditResult&) = nullptr;
    /// Summary fields: how `merge` combines the parts' values into one run's.
    Merge merge = Merge::sum;
};

/// `v` rounded to `decimals` decimal places (half away from zero).
double round_to(double v, int decimals);

/// The value of field `f` for `row`, rounded as the field says; null for a real that is not finite.
template <class Row>
Value value_of(const Field<Row>& f, const Row& row) {
    Value v = f.get(row);
    if (const double* d = std::get_if<double>(&v)) {
        if (!std::isfinite(*d)) return std::monostate{};
        if (f.decimals >= 0) return round_to(*d, f.decimals);
    }
    return v;
}

/// Coordinates of points in both reports are rounded to this many decimals (about 1 cm).
inline constexpr int coordinate_decimals = 7;

// The rows of each layer.
struct EventRow {
    const audit::TrackSummary& track;
    const audit::Event& event;
};
struct EncounterRow {
    const audit::AuditResult& result;
    const audit::Encounter& encounter;
};
struct TrackRow {
    const audit::TrackSummary& track;
    std::size_t skipped_rows;  ///< bad rows skipped in the track's file
};
struct HullRow {
    std::string track;
    const char* kind;
    const char* hit;  ///< null for an encounter's hull
    double start_s;
    std::string label;
    const std::vector<geo::LonLat>& ring;
    std::string exercise;  ///< the track's exercise (exercise mode)
};
struct PoseRow {
    const audit::TrackSummary& track;
    const audit::Pose& pose;
};
/// One feature of the `coast` layer: the chart's land, shallow areas or dangers in one tile.
struct CoastRow {
    std::string tile;   ///< the tile's key (src/report/qgis/chart_layer.hpp)
    const char* kind;   ///< "land", "shallow", "danger", "structure"
    const char* danger; ///< the danger's kind ("rock", ...), "" otherwise
    double depth_m;     ///< the charted depth (least depth of the areas, danger's sounding); NaN unknown or land
};
/// The `coast` layer's row of a chart feature.
CoastRow coast_row(const ChartFeature& c);
struct ProblemRow {
    std::string file, track;  ///< track "": none (null)
    std::size_t line = 0;     ///< 0: none (null)
    std::string message;
    /// Where it goes in one run's order (merge): `group` 0 a file's (every shard of a run
    /// lists them), 1 a failed track's, 2 a track's (wild fixes); `position` the track's
    /// position among the run's tracks (AuditResult::track_positions), 0 for group 0.
    int group = 0;
    std::size_t position = 0;
};
struct ApproachRow {
    const audit::AuditResult& result;
    const audit::ClosestApproach& approach;
};
struct RunRow {
    const audit::AuditResult& result;
    const RunInfo& info;
};
struct BreachRow {
    const audit::AuditResult& result;
    const audit::Breach& breach;
};
struct ScoreRow {
    const audit::AuditResult& result;
    const audit::Score& score;
};
struct CriterionRow {
    const audit::Criterion& criterion;
};
/// A place the run's traffic taught (--world real): the `learned` layer.
struct LearnedRow {
    const audit::LearnedPlace& place;
};

const std::vector<Field<EventRow>>& event_fields();
const std::vector<Field<EncounterRow>>& encounter_fields();
const std::vector<Field<TrackRow>>& track_fields();
const std::vector<Field<HullRow>>& hull_fields();
const std::vector<Field<ProblemRow>>& problem_fields();
const std::vector<Field<PoseRow>>& pose_fields();
const std::vector<Field<CoastRow>>& coast_fields();
const std::vector<Field<ApproachRow>>& approach_fields();
const std::vector<Field<RunRow>>& run_fields();
const std::vector<Field<RunRow>>& summary_fields();
const std::vector<Field<BreachRow>>& breach_fields();
const std::vector<Field<LearnedRow>>& learned_fields();
const std::vector<Field<ScoreRow>>& score_fields();
const std::vector<Field<CriterionRow>>& criterion_fields();

/// The rows of the layers that are not one-to-one with a vector of the result.
std::vector<TrackRow> track_rows(const audit::AuditResult& r);
/// Each track event's hull, then both ships' hulls of each encounter (part_order.cpp keys
/// the GeoPackage `hulls` rows in this order: change both together).
std::vector<HullRow> hull_rows(const audit::AuditResult& r);
std::vector<ProblemRow> problem_rows(const audit::AuditResult& r);

/// Row k's position among all the rows of one run (AuditResult::track_positions or
/// error_positions); k itself when the run was not a shard (no positions kept).
inline std::size_t position_in_run(const std::vector<std::size_t>& positions, std::size_t k) {
    return k < positions.size() ? positions[k] : k;
}

/// "collision 10:03:12Z", "close quarters 10:03:12Z".
std::string encounter_label(const audit::Encounter& e);

}  // namespace shoal::report::fields
