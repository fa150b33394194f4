#pragma once
/// Scored criteria for the instructor's debrief: an assessment file (JSON,
/// schemas/assessment.schema.json) lists criteria, each with a limit and a penalty; assess()
/// turns an exercise-mode audit into a score per trainee and the breaches behind it.
/// Targets are never scored.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <shoal/geo/point.hpp>

namespace shoal::audit {

struct AuditResult;

enum class CriterionKind {
    land_clearance,       ///< clearance of the hull to land or hazards at least `limit` metres
    under_keel_clearance, ///< under-keel clearance at least `limit` metres
    cpa,                  ///< closest approach to another ship of the exercise at least `limit` metres
    speed_limit,          ///< speed over ground inside `area` at most `limit` knots
    no_entry,             ///< never inside `area`
    close_quarters_time,  ///< at most `limit` seconds in close quarters (per encounter)
};
const char* to_string(CriterionKind k) noexcept;

/// How a breach is charged: `penalty` once per breach, per second over the limit, or per metre
/// (per knot for a speed limit) beyond it at the worst moment.
enum class PenaltyPer { breach, second, metre };
const char* to_string(PenaltyPer p) noexcept;

struct Criterion {
    std::string id;  ///< as the file names it (or "<kind>-<n>"), unique
    CriterionKind kind = CriterionKind::land_clearance;
    double limit = 0;
    double penalty = 0;
    PenaltyPer per = PenaltyPer::breach;
    std::vector<geo::LonLat> area;  ///< speed_limit and no_entry: the polygon's outer ring, lon/lat
    std::string area_name;
};

struct Assessment {
    std::vector<Criterion> criteria;
    /// Reads an assessment file; throws InputError naming the file and the criterion that is wrong.
    static Assessment load(const std::string& path);
    static Assessment parse(const std::string& text, const std::string& source);
};

/// One breach of one criterion by one trainee: from `start_s` to `end_s` (epoch seconds; equal
/// for an instantaneous one), at its worst moment `worst_s` at (lon, lat) with `value` against `limit`.
struct Breach {
    std::string exercise, track, criterion;
    CriterionKind kind = CriterionKind::land_clearance;
    double start_s = NAN, end_s = NAN, worst_s = NAN;
    double lon = NAN, lat = NAN;
    double value = NAN, limit = NAN;
    double penalty = 0;
    std::string other;   ///< cpa, close_quarters_time: the other ship's track id
    std::string detail;  ///< one line a person reads
};

/// A trainee's score: the sum of the penalties of her breaches (0: none).
struct Score {
    std::string exercise, track;
    double penalty = 0;
    std::size_t breaches = 0;
};

struct AssessmentResult {
    std::vector<Score> scores;      ///< every trainee, by exercise then track
    std::vector<Breach> breaches;   ///< by exercise, then time
};

}  // namespace shoal::audit
