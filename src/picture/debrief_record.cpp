// The debrief record of a shard (report/debrief_record.hpp).
#include <shoal/picture/debrief_record.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <tuple>

#include <nlohmann/json.hpp>

#include <shoal/shard/shard.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/util/error.hpp>

#include "audit/run_totals.hpp"

// to_json / from_json of what the record holds, in the namespaces of the types (found by ADL).
namespace shoal::geo {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LonLat, lon, lat)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(XY, x, y)
}  // namespace shoal::geo

namespace shoal::track {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(WildFix, line, time_s, position, implied_kn, why)
}  // namespace shoal::track

namespace shoal::audit {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Event::Evidence, grade, reason, disagreement, start_not_before_s, speed_before_kn, speed_before_age_s,
                                   speed_after_kn, speed_after_age_s, stop_distance_m, stay_s, deceleration_kn_s, berth_stays, pieces,
                                   within_chart_tolerance, seen_clear_before, stay, prompt_stop, bracket_dense, between_fixes_only,
                                   left_contact, moored_at_stay, aground_at_stay, gap_distance_m)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Event, kind, start_s, end_s, min_clearance_m, penetration_m, point, ship, heading_deg, heading_source,
                                   fix_index, fix_line, hull, hit, charted_depth_m, danger, hit_name, speed_kn, speed_source, stopped_before,
                                   stopped_after_s, reference_inside_m, nav_status, reported_aground, orientation_unknown, unseen_after,
                                   area_kind, area_name, structure, evidence)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TrackSummary, id, name, file, hull, draught_m, draught_source, ship_type, ship_type_source,
                                   limiting_depth_m, limiting_depth_source, fixes, uncovered_fixes, segments, gaps, poses, groundings,
                                   close_passes, alongside, contacts_at_start, expected_contacts, chart_disagreements, cadence_s,
                                   hull_length_m, wild_fixes, jumps, unknown_heading_fixes, min_clearance_m, start_s, end_s, distance_m,
                                   lines, line_times, exercise, role)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Pose, time_s, until_s, speed_kn, heading_deg, clearance_m, contact, covered, fix_index, fix_line, hull)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TrackError, file, track, message)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ShipAt, track, position, heading_deg, fix_index, hull)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Encounter, kind, start_s, end_s, min_clearance_m, distance_m, point, a, b)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ClosestApproach, a, b, time_s, clearance_m, distance_m, a_position, b_position)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(VesselAt, position, heading_deg, velocity)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Classification, situation, give_way, stand_on, bearing_of_b_deg, bearing_of_a_deg)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Cpa, distance_m, time_s)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Manoeuvre, course, speed, time_s)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ColregEncounter, a, b, start_s, end_s, a_start, b_start, at_start, cpa_start, closest_m, closest_s,
                                   a_closest, b_closest, action_a, action_b, a_stopped, b_stopped)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ConductOptions, range_m, head_on_deg, cpa_m, early_range_m, min_course_deg, min_speed_change,
                                   action_course_deg, action_speed_change, sustain_s)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Criterion, id, kind, limit, penalty, per, area, area_name, colreg)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Breach, exercise, track, criterion, track_index, kind, start_s, end_s, worst_s, lon, lat, value, limit,
                                   penalty, other, rule, asked, did, detail)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Score, exercise, track, penalty, breaches, track_index, by_criterion, passed)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ConductRecord, exercise, track, criterion, track_index, other, other_index, situation, role, start_s,
                                   closest_m, rules, breached, did)
}  // namespace shoal::audit

namespace shoal::report {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

/// The largest record read (4 GiB): a record holds every pose of its shard's tracks.
constexpr std::size_t max_record_bytes = std::size_t{1} << 32;

json info_json(const RunInfo& i) {
    return {{"coast", i.coast},
            {"frame", i.frame},
            {"cell_m", i.cell_m},
            {"limiting_depth_m", i.limiting_depth_m},
            {"limiting_depth_source", i.limiting_depth_source},
            {"ukc_m", i.ukc_m},
            {"grid_fingerprint", i.grid_fingerprint},
            {"ship", i.ship},
            {"margin_m", i.sweep.margin_m},
            {"step_m", i.sweep.step_m},
            {"world", i.world},
            {"berths", i.berths},
            {"ship_margin_m", i.ship_margin_m},
            {"exercise_by", i.exercise_by},
            {"roles", i.roles},
            {"assessment", i.assessment},
            {"role_column", i.role_column},
            {"encounter_range_m", i.encounter_range_m}};
}

RunInfo info_of(const json& j) {
    RunInfo i;
    j.at("coast").get_to(i.coast);
    j.at("frame").get_to(i.frame);
    j.at("cell_m").get_to(i.cell_m);
    j.at("limiting_depth_m").get_to(i.limiting_depth_m);
    j.at("limiting_depth_source").get_to(i.limiting_depth_source);
    j.at("ukc_m").get_to(i.ukc_m);
    j.at("grid_fingerprint").get_to(i.grid_fingerprint);
    j.at("ship").get_to(i.ship);
    j.at("margin_m").get_to(i.sweep.margin_m);
    j.at("step_m").get_to(i.sweep.step_m);
    j.at("world").get_to(i.world);
    j.at("berths").get_to(i.berths);
    j.at("ship_margin_m").get_to(i.ship_margin_m);
    j.at("exercise_by").get_to(i.exercise_by);
    j.at("roles").get_to(i.roles);
    j.at("assessment").get_to(i.assessment);
    j.at("role_column").get_to(i.role_column);
    j.at("encounter_range_m").get_to(i.encounter_range_m);
    return i;
}

json grid_json(const GridSpec& g) {
    const coast::ImportOptions& im = g.request.import;
    return {{"coast", g.coast},
            {"layers", im.layers},
            {"source_crs", im.source_crs},
            {"limiting_depth_m", im.limiting_depth_m ? json(*im.limiting_depth_m) : json(nullptr)},
            {"danger_radius_m", im.danger_radius_m},
            {"depth_field", im.depth_field},
            {"crs", g.request.crs},
            {"cell_m", g.request.cell_m},
            {"ship_length_m", g.request.ship_length_m},
            {"cache_dir", g.request.cache_dir}};
}

GridSpec grid_of(const json& j) {
    GridSpec g;
    coast::ImportOptions& im = g.request.import;
    j.at("coast").get_to(g.coast);
    j.at("layers").get_to(im.layers);
    j.at("source_crs").get_to(im.source_crs);
    if (!j.at("limiting_depth_m").is_null()) im.limiting_depth_m = j.at("limiting_depth_m").get<double>();
    j.at("danger_radius_m").get_to(im.danger_radius_m);
    j.at("depth_field").get_to(im.depth_field);
    j.at("crs").get_to(g.request.crs);
    j.at("cell_m").get_to(g.request.cell_m);
    j.at("ship_length_m").get_to(g.request.ship_length_m);
    j.at("cache_dir").get_to(g.request.cache_dir);
    return g;
}

json tracks_json(const std::vector<audit::TrackResult>& tracks) {
    json out = json::array();
    for (const audit::TrackResult& t : tracks) out.push_back({{"summary", t.summary}, {"events", t.events}, {"poses", t.poses}});
    return out;
}

json result_json(const audit::AuditResult& r) {
    json files = json::array();
    for (const audit::FileResult& f : r.files) files.push_back({{"file", f.file}, {"error", f.error}});
    json a = json::object();
    if (r.has_assessment)
        a = {{"criteria", r.assessment.criteria}, {"pass_mark", r.assessment.pass_mark}, {"source", r.assessment.source},
             {"scores", r.assessment.scores}, {"breaches", r.assessment.breaches}, {"conduct", r.assessment.conduct}};
    return {{"tracks", tracks_json(r.tracks)},
            {"track_positions", r.track_positions},
            {"errors", r.errors},
            {"files", std::move(files)},
            {"world", r.world},
            {"has_encounters", r.has_encounters},
            {"encounters", {{"events", r.encounters.events}, {"approaches", r.encounters.approaches}}},
            {"situations", r.situations},
            {"has_assessment", r.has_assessment},
            {"assessment", std::move(a)}};
}

audit::AuditResult result_of(const json& j) {
    audit::AuditResult r;
    for (const json& t : j.at("tracks")) {
        audit::TrackResult& tr = r.tracks.emplace_back();
        t.at("summary").get_to(tr.summary);
        t.at("events").get_to(tr.events);
        t.at("poses").get_to(tr.poses);
    }
    j.at("track_positions").get_to(r.track_positions);
    j.at("errors").get_to(r.errors);
    for (const json& f : j.at("files")) {
        audit::FileResult& fr = r.files.emplace_back();
        f.at("file").get_to(fr.file);
        f.at("error").get_to(fr.error);
    }
    j.at("world").get_to(r.world);
    j.at("has_encounters").get_to(r.has_encounters);
    j.at("encounters").at("events").get_to(r.encounters.events);
    j.at("encounters").at("approaches").get_to(r.encounters.approaches);
    j.at("situations").get_to(r.situations);
    j.at("has_assessment").get_to(r.has_assessment);
    if (r.has_assessment) {
        const json& a = j.at("assessment");
        a.at("criteria").get_to(r.assessment.criteria);
        a.at("pass_mark").get_to(r.assessment.pass_mark);
        a.at("source").get_to(r.assessment.source);
        a.at("scores").get_to(r.assessment.scores);
        a.at("breaches").get_to(r.assessment.breaches);
        a.at("conduct").get_to(r.assessment.conduct);
    }
    if (r.track_positions.size() != r.tracks.size()) throw std::out_of_range("track_positions and tracks differ in length");
    return r;
}

/// The run's counts from its tracks, as the audit counts them.
void recount(audit::AuditResult& r) {
    for (const audit::TrackResult& t : r.tracks) audit::add_to_totals(r, t.summary);
}

}  // namespace

std::string debrief_record_path(const std::string& part) { return part + ".debrief.cbor"; }

std::string debrief_record(const audit::AuditResult& result, const RunInfo& info, const GridSpec& grid,
                           const std::pair<long long, std::string>& part) {
    const json doc = {{"part", {{"size", part.first}, {"fingerprint", part.second}}},
                      {"shard", result.shard.text()},
                      {"info", info_json(info)},
                      {"grid", grid_json(grid)},
                      {"result", result_json(result)}};
    std::string out(debrief_record_mark);
    json::to_cbor(doc, out);
    return out;
}

namespace {
/// Whether the file at `path` begins with the record's mark.
bool has_mark(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(debrief_record_mark.size(), '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    return in.gcount() == static_cast<std::streamsize>(head.size()) && head == debrief_record_mark;
}
}  // namespace

StagedOutput stage_debrief_record(const StagedOutput& part, const audit::AuditResult& result, const RunInfo& info, const GridSpec& grid) {
    if (part.direct())
        throw UsageError("--debrief-record: the part '" + part.target() +
                         "' is not written to a file of its own (standard output, a device): its record could not be matched to it; "
                         "give -o a file");
    const std::string path = debrief_record_path(part.target());
    std::error_code ec;
    if (fs::exists(path, ec) && !has_mark(path))
        throw InputError("'" + path + "' exists and is not a debrief record shoal wrote: the record of '" + part.target() +
                         "' was not written (move the file away)");
    StagedOutput out(path);
    out.write(debrief_record(result, info, grid, file_size_and_fingerprint(part.temp_path())));
    return out;
}

DebriefRecord parse_debrief_record(std::string_view bytes, const std::string& path) {
    DebriefRecord rec;
    rec.path = path;
    if (bytes.substr(0, debrief_record_mark.size()) != debrief_record_mark)
        throw InputError("'" + rec.path + "': not a debrief record of this shoal (no mark \"shoal debrief record 1\"); write it again with check --debrief-record");
    try {
        const json doc = json::from_cbor(bytes.substr(debrief_record_mark.size()));
        rec.shard = audit::parse_shard(doc.at("shard").get<std::string>());
        rec.part = {doc.at("part").at("size").get<long long>(), doc.at("part").at("fingerprint").get<std::string>()};
        rec.info = info_of(doc.at("info"));
        rec.grid = grid_of(doc.at("grid"));
        rec.result = result_of(doc.at("result"));
        rec.result.shard = rec.shard;
    } catch (const std::exception& e) {  // nlohmann's parse, type and range errors, a bad shard
        throw InputError("'" + rec.path + "': a damaged debrief record (" + e.what() + "); write it again with check --debrief-record");
    }
    return rec;
}

DebriefRecord read_debrief_record(const std::string& part) {
    DebriefRecord rec;
    rec.path = debrief_record_path(part);
    std::error_code ec;
    if (!fs::exists(rec.path, ec))
        throw UsageError("the part '" + part + "' has no debrief record ('" + rec.path +
                         "'): --debrief and --plot need every part's; write it with `shoal check --shard I/N -o " + part +
                         " --debrief-record` (the same options as the other shards)");
    std::ifstream in(rec.path, std::ios::binary);
    if (!in) throw InputError("'" + rec.path + "': cannot be read");
    std::string bytes;
    char buf[1 << 16];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
        bytes.append(buf, static_cast<std::size_t>(in.gcount()));
        if (bytes.size() > max_record_bytes) throw InputError("'" + rec.path + "': larger than any debrief record (4 GiB)");
    }
    rec = parse_debrief_record(bytes, rec.path);
    if (file_size_and_fingerprint(part) != rec.part)
        throw InputError("'" + rec.path + "' is not the record of the part '" + part +
                         "' as it is now (it was written with another part, or the part was written again since): write them again "
                         "together, check --shard I/N -o PART --debrief-record");
    return rec;
}

audit::AuditResult join_debrief_records(std::vector<DebriefRecord> records, const std::vector<std::size_t>& sets,
                                        const std::vector<bool>& first_of_set) {
    audit::AuditResult run;
    if (records.empty()) return run;
    // What the pages print of the run: the same in every record.
    // Compared as CBOR bytes: NaN (a limiting depth of land only) is never equal to itself as a number.
    const auto bytes = [](const json& j) { return json::to_cbor(j); };
    const auto info0 = bytes(info_json(records[0].info));
    const auto criteria0 = bytes(records[0].result.assessment.criteria);
    for (const DebriefRecord& r : records) {
        if (bytes(info_json(r.info)) != info0)
            throw InputError("the debrief records '" + records[0].path + "' and '" + r.path + "' are not of one run (their run headers differ)");
        if (r.result.has_encounters != records[0].result.has_encounters || r.result.has_assessment != records[0].result.has_assessment ||
            bytes(r.result.assessment.criteria) != criteria0)
            throw InputError("the debrief records '" + records[0].path + "' and '" + r.path + "' are not of one run (exercise mode or criteria differ)");
    }
    // The tracks in one run's order: by (set, position).
    struct Slot {
        std::size_t set, position, record, index;
    };
    std::vector<Slot> slots;
    for (std::size_t k = 0; k < records.size(); ++k)
        for (std::size_t i = 0; i < records[k].result.tracks.size(); ++i) slots.push_back({sets[k], records[k].result.track_positions[i], k, i});
    std::sort(slots.begin(), slots.end(), [](const Slot& a, const Slot& b) { return std::tie(a.set, a.position) < std::tie(b.set, b.position); });
    std::vector<std::vector<std::size_t>> renumber(records.size());
    for (std::size_t k = 0; k < records.size(); ++k) renumber[k].resize(records[k].result.tracks.size());
    for (std::size_t g = 0; g < slots.size(); ++g) {
        const Slot& s = slots[g];
        if (g > 0 && slots[g - 1].set == s.set && slots[g - 1].position == s.position)
            throw InputError("the debrief records '" + records[slots[g - 1].record].path + "' and '" + records[s.record].path +
                             "' hold the same track (shards of different runs?)");
        renumber[s.record][s.index] = g;
        run.tracks.push_back(std::move(records[s.record].result.tracks[s.index]));
        run.track_positions.push_back(s.position);
    }
    const auto at = [&](std::size_t k, std::size_t i) {
        if (i >= renumber[k].size()) throw InputError("'" + records[k].path + "': an index into its tracks is out of range (damaged?)");
        return renumber[k][i];
    };
    audit::AuditResult& first = records[0].result;
    run.world = first.world;
    run.has_encounters = first.has_encounters;
    run.has_assessment = first.has_assessment;
    if (run.has_assessment) {
        run.assessment.criteria = first.assessment.criteria;
        run.assessment.pass_mark = first.assessment.pass_mark;
        run.assessment.source = first.assessment.source;
    }
    for (std::size_t k = 0; k < records.size(); ++k) {
        audit::AuditResult& r = records[k].result;
        // The files read: the same in every part of a set of inputs (the merge checked their problems).
        if (first_of_set[k])
            for (audit::FileResult& f : r.files) run.files.push_back(std::move(f));
        for (audit::TrackError& e : r.errors) run.errors.push_back(std::move(e));
        for (audit::Encounter& e : r.encounters.events) {
            e.a.track = at(k, e.a.track);
            e.b.track = at(k, e.b.track);
            run.encounters.events.push_back(std::move(e));
        }
        for (audit::ClosestApproach& a : r.encounters.approaches) {
            a.a = at(k, a.a);
            a.b = at(k, a.b);
            run.encounters.approaches.push_back(std::move(a));
        }
        for (audit::ColregEncounter& c : r.situations) {
            c.a = at(k, c.a);
            c.b = at(k, c.b);
            run.situations.push_back(std::move(c));
        }
        for (audit::Score& s : r.assessment.scores) {
            s.track_index = at(k, s.track_index);
            run.assessment.scores.push_back(std::move(s));
        }
        for (audit::Breach& b : r.assessment.breaches) {
            b.track_index = at(k, b.track_index);
            run.assessment.breaches.push_back(std::move(b));
        }
        for (audit::ConductRecord& c : r.assessment.conduct) {
            c.track_index = at(k, c.track_index);
            c.other_index = at(k, c.other_index);
            run.assessment.conduct.push_back(std::move(c));
        }
    }
    // As the audit sorts them (audit.cpp; assessment.hpp): a pair, a trainee, is in one shard.
    std::sort(run.encounters.approaches.begin(), run.encounters.approaches.end(),
              [](const audit::ClosestApproach& x, const audit::ClosestApproach& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
    std::sort(run.situations.begin(), run.situations.end(),
              [](const audit::ColregEncounter& x, const audit::ColregEncounter& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
    std::stable_sort(run.encounters.events.begin(), run.encounters.events.end(), [](const audit::Encounter& x, const audit::Encounter& y) {
        return std::tie(x.start_s, x.a.track, x.b.track, x.kind) < std::tie(y.start_s, y.a.track, y.b.track, y.kind);
    });
    std::stable_sort(run.assessment.scores.begin(), run.assessment.scores.end(),
                     [](const audit::Score& x, const audit::Score& y) { return x.track_index < y.track_index; });
    std::stable_sort(run.assessment.breaches.begin(), run.assessment.breaches.end(),
                     [](const audit::Breach& x, const audit::Breach& y) { return x.track_index < y.track_index; });
    std::stable_sort(run.assessment.conduct.begin(), run.assessment.conduct.end(),
                     [](const audit::ConductRecord& x, const audit::ConductRecord& y) { return x.track_index < y.track_index; });
    recount(run);
    return run;
}

grid::CoastGrid load_recorded_grid(const DebriefRecord& record, const std::vector<std::string>& coast) {
    const std::vector<std::string>& inputs = coast.empty() ? record.grid.coast : coast;
    std::string named;
    for (const auto& p : inputs) named += (named.empty() ? "'" : ", '") + p + "'";
    const std::string how = coast.empty() ? "the --coast the shards were given, " + named : "merge --coast " + named;
    grid::CoastGrid g = [&] {
        try {
            return grid::load_or_build(inputs, record.grid.request);
        } catch (const std::runtime_error& e) {
            throw InputError("the debrief and the picture need the grid the run was checked against, and " + how + " cannot be loaded (" +
                             e.what() + "): give merge --coast GRID_OR_SOURCES");
        }
    }();
    const std::string fp = grid::fingerprint_hex(g.source().fingerprint);
    if (fp != record.info.grid_fingerprint)
        throw InputError("the debrief and the picture need the grid the run was checked against (fingerprint " + record.info.grid_fingerprint +
                         "), but " + how + " gives the grid " + fp + " (the sources changed since?): give merge --coast the run's grid");
    return g;
}

}  // namespace shoal::report
