// shoal check: audit voyage tracks and write the grounding report.
#include "commands.hpp"
#include "options.hpp"
#include "process.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <shoal/audit/audit.hpp>
#include <shoal/audit/partition.hpp>
#include <shoal/shard/shard.hpp>
#include <shoal/coast/chart_scale.hpp>
#include <shoal/coast/expected_areas.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/picture/debrief.hpp>
#include <shoal/picture/debrief_record.hpp>
#include <shoal/picture/plot.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/report/geojson_report.hpp>
#include <shoal/report/gpkg_report.hpp>
#include <shoal/report/summary.hpp>
#include <shoal/track/reader.hpp>
#include <shoal/track/vessels_table.hpp>
#include <shoal/track/time.hpp>
#include <shoal/report/read_fingerprints.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::cli {

namespace {

/// A partition's task (a Dask task: one process, one input or a few of the run's vessels,
/// then it ends) keeps the memory it frees for what comes next: blocks up to 32 MiB (a week's
/// track unpacked, its projected positions, a block of the input read) from the heap, not
/// mapped afresh each time, and the heap not given back to the system under 512 MiB. glibc's
/// default (blocks mapped and given back, the thresholds grown as it goes) has the kernel zero
/// fresh pages again and again: a third of the CPU time of a traffic task, a quarter of a
/// read task's, a tenth of an audit's (docs/performance.md, issue 39). MALLOC_MMAP_THRESHOLD_
/// and MALLOC_TRIM_THRESHOLD_, when set, decide instead.
void keep_freed_memory() noexcept {
#if defined(__GLIBC__)
    if (std::getenv("MALLOC_MMAP_THRESHOLD_") == nullptr) mallopt(M_MMAP_THRESHOLD, 32 << 20);
    if (std::getenv("MALLOC_TRIM_THRESHOLD_") == nullptr) mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

bool is_stream(const std::string& path) {
    std::error_code ec;
    return !std::filesystem::is_regular_file(path, ec);
}

/// A progress line on stderr: fixes done, rate and time left. Only when stderr is a terminal.
class Progress {
public:
    explicit Progress(bool on) : m_on(on), m_t0(std::chrono::steady_clock::now()) {}
    void operator()(std::size_t done, std::size_t total) {
        if (!m_on || total == 0) return;
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_t0).count();
        const double rate = s > 0 ? static_cast<double>(done) / s : 0;
        const double left = rate > 0 ? static_cast<double>(total - done) / rate : 0;
        const int width = 30;
        const int fill = static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total));
        std::fprintf(stderr, "\r[%.*s%*s] %3.0f%%  %.2fM fixes/s  %3.0f s left ", fill, "==============================",
                     width - fill, "", 100.0 * static_cast<double>(done) / static_cast<double>(total), rate / 1e6, left);
        if (done == total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }

private:
    bool m_on;
    std::chrono::steady_clock::time_point m_t0;
};

class CheckCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("check", "Audit voyage tracks: sweep the hull along them, report groundings and close passes");
        m_sub->footer("Usage: shoal check --coast COAST_OR_GRID --ship SHIP.json TRACK... -o REPORT.geojson [--margin M] [--step M] [--jobs N]\n"
                      "Tracks: CSV with a header (AIS exports too), GPX, GeoJSON, NMEA 0183 logs; folders are searched.\n"
                      "Shallow water and dangers count as hazards for each vessel's limiting depth: its draught (AIS, --vessels) + --ukc,\n"
                      "else the ship file's draught + --ukc, else the grid's default; --hazard-depth sets one for every vessel.\n"
                      "--world simulated (exercise mode's default): the chart is the world, a contact that begins under way after\n"
                      "the vessel was seen clear is a grounding. --world real (the default otherwise): the chart is a model, and a\n"
                      "contact is a grounding when the vessel's motion says so (it stopped where it touched and lay there, AIS status\n"
                      "aground, a touch and go); one it sailed on through is chart_disagrees; an arrival where vessels berth is\n"
                      "alongside. Contacts of a vessel stopped or under --berthing-speed are alongside, those at a track's first\n"
                      "fix in_contact_at_start, those inside --berths areas expected_contact. Wild fixes (over --max-speed) are\n"
                      "dropped and listed.\n"
                      "Exit status: 0 no grounding, 1 at least one grounding (or ship collision), 2 bad usage or unreadable input.");
        m_opts.add(*m_sub);
        m_sub->add_option("tracks", m_tracks, "Track files or folders")->required();
        m_sub->add_option("-o,--output", m_output, "Report to write: .geojson, or .gpkg (GeoPackage)")->required();
        m_sub->add_option("--format", m_format, "geojson or gpkg (default: from the extension of -o)")
            ->check(CLI::IsMember({"geojson", "gpkg"}));
        m_sub->add_option("--margin", m_audit.sweep.margin_m, "Close pass: clearance under this many metres (default 50)")
            ->check(finite)->check(non_negative);
        m_sub->add_option("--step", m_audit.sweep.step_m, "No hull point moves more than this many metres between checks (default 5, at least 0.01)")
            ->check(finite)->check(positive);
        m_sub->add_option("--max-gap", m_audit.sweep.max_gap_s, "A gap between fixes longer than this (seconds) splits the track (default 600)")
            ->check(finite)->check(positive);
        m_sub->add_option("--jobs,-j", m_audit.jobs, "Tracks checked in parallel (default: all cores)");
        m_sub->add_option("--shard", m_shard,
                          "Audit only shard I of N (0 <= I < N): the tracks whose id hashes there (XXH3); every file is still "
                          "read, so files and lines stay true. `shoal merge` puts the N reports together as one run's. With "
                          "--encounters a shard is a whole exercise");
        // Partitions of a run on a cluster (python3 -m shoal.dask; docs/scale-out.md).
        m_sub->add_option("--partitions", m_partitions,
                          "Instead of auditing: read the one TRACK input (a file, folder or zip) and write its fixes, hashed by vessel "
                          "id into K partitions, to the new folder -o DIR (with what reading found: bad rows, fingerprints), for "
                          "--from-partitions")
            ->check(CLI::Range(1u, 1000000u));
        m_sub->add_option("--from-partitions", m_from_partitions,
                          "With --shard I/N: audit partition I of the folders written by --partitions N, one per TRACK input in "
                          "order, instead of reading the TRACK files (the report is the shard's, byte for byte); real world: with "
                          "--traffic");
        m_sub->add_flag("--traffic-only", m_traffic_only,
                        "With --from-partitions: write only the partition's traffic (stays, fixes over land) to -o FILE, for --traffic");
        m_sub->add_option("--traffic", m_traffic,
                          "With --from-partitions: the traffic files of partitions 0..N-1 (--traffic-only), every vessel's evidence; "
                          "one --traffic per file, in partition order: --traffic T0 --traffic T1 ...")
            ->allow_extra_args(false);
        m_sub->add_flag("--encounters", m_audit.encounters,
                        "Exercise mode: the tracks are one exercise; also report ship-to-ship collisions and close quarters");
        m_sub->add_option("--ship-margin", m_audit.encounter.ship_margin_m,
                          "Exercise mode: close quarters when hulls come within this many metres (default 20)")
            ->check(finite)->check(non_negative);
        // Exercises, roles and COLREG situations (issue 18).
        m_sub->add_option("--exercise-by", m_exercise_by,
                          "Exercise mode: run (the whole run is one exercise, the default), file (each track file is one), "
                          "folder (the files of one folder are one) or column:NAME (each row's exercise is the value of its column "
                          "NAME, any case; CSV columns, GeoJSON properties; one vessel in two exercises is two tracks); encounters "
                          "only within an exercise. Implies --encounters");
        m_sub->add_option("--roles", m_roles_file,
                          "Exercise mode: exercise file (JSON, schemas/exercise.schema.json) giving each track's role, trainee or "
                          "target; pairs of two targets are not reported. Default: every track is a trainee. Implies --encounters");
        m_sub->add_option("--assess", m_assess_file,
                          "Exercise mode: score each trainee against the criteria of an assessment file (JSON, "
                          "schemas/assessment.schema.json); scores and breaches go to stdout and the report. Implies --encounters");
        m_sub->add_option("--role-column", m_audit.read.role_column,
                          "Exercise mode: each track's role from its column NAME (CSV columns, GeoJSON properties): trainee (also "
                          "own, own ship), target, any case. Rows of one track that disagree make it a target. With --roles, the "
                          "exercise file's entries win for the tracks they name. Implies --encounters");
        m_sub->add_option("--encounter-range", m_audit.colreg.range_m,
                          "Exercise mode: a pair whose reference points come within this many metres is a COLREG situation "
                          "(head-on, crossing, overtaking), classified when it first does (default 3704, 2 nm)")
            ->check(finite)->check(positive);
        m_sub->add_option("--max-encounters-per-ship", m_audit.max_encounters_per_ship,
                          "Exercise mode: each ship lists at most N other ships, those it came closest to (their collisions, close "
                          "quarters, closest approach and situation; with --assess, a trainee's CPA breaches); the summary and the scores count the rest. 0: no limit (default 20)")
            ->check(finite)->check(non_negative)  // CLI11 would read -1 as the largest size_t
            ->check(at_most(max_listed_per_ship, "more ships than any exercise holds; 0 for no limit"));
        m_sub->add_option("--berths", m_berths,
                          "Areas where contact is expected (berths, harbours, anchorages): any OGR vector source, every layer; "
                          "contacts there are expected_contact, not groundings. S-57 charts given as --coast add their "
                          "BERTHS, HRBARE and ACHARE, and SLCONS as shore constructions")
            ->allow_extra_args(false);
        m_sub->add_option("--vessels", m_vessel_files,
                          "Vessels table(s), CSV: mmsi and any of name, A,B,C,D (to_bow_m, to_stern_m, to_port_m, to_stbd_m), "
                          "draught_m, shiptype; joined to tracks by id, over what the track's own file says")
            ->allow_extra_args(false);
        m_sub->add_flag("--hull-from-length-width", m_audit.read.hull_from_length_width,
                        "A vessel with Length and Width but no A,B,C,D (MarineCadastre) is swept with a hull of that size, its "
                        "position taken amidships (can miss a bow-first grounding when the antenna is aft; default: --ship/--dims)");
        m_sub->add_option("--berth-tolerance", m_berth_tolerance_m,
                          "Lines and points of --berths and S-57 berths / shore constructions count within this many metres (default 10)")
            ->check(finite)->check(positive)->check(at_most(coast::ExpectedAreas::max_tolerance_m, "a berth grown by more is no berth"));
        m_sub->add_option("--berthing-speed", m_audit.sweep.berthing_speed_kn,
                          "A contact that begins under this speed (knots) is alongside (berthing, moored), not a grounding (default 1, at most 5)")
            ->check(finite)->check(non_negative)->check(at_most(audit::SweepOptions::max_berthing_speed_kn, "faster is no berthing"));
        m_sub->add_option("--stop-diameter", m_audit.sweep.stop_diameter_m,
                          "Stopped: every fix of --stop-time seconds within a box of this diagonal, metres (default 50)")
            ->check(finite)->check(positive);
        m_sub->add_option("--stop-time", m_audit.sweep.stop_duration_s, "Stopped: a stay of at least this many seconds (default 120)")
            ->check(finite)->check(positive);
        m_sub->add_option("--world", m_world,
                          "simulated: the chart is the world (a contact under way is a grounding); real: the chart is a model and the "
                          "vessel's own motion and the run's traffic decide (default: simulated in exercise mode, else real)")
            ->check(CLI::IsMember({"simulated", "real"}));
        m_sub->add_option("--chart-scale", m_chart_scale,
                          "The chart's compilation scale denominator (250000 for GSHHG full): a contact within its positional "
                          "tolerance, 0.5 mm at that scale, is said so and graded lower (default: an S-57 chart's DSPM CSCALE, else none)")
            ->check(finite)->check(positive);
        m_sub->add_option("--berth-radius", m_audit.evidence.berth_radius_m,
                          "Real world: stays of vessels within this many metres make a learned berth (default 300)")
            ->check(finite)->check(positive);
        m_sub->add_option("--ground-time", m_audit.evidence.ground_stay_s,
                          "Real world: a vessel aground lies where it touched at least this many seconds (default 300)")
            ->check(finite)->check(positive);
        m_sub->add_option("--max-speed", m_audit.wild.max_speed_kn,
                          "Fastest plausible speed, knots: a fix that implies more against its neighbours is dropped as an "
                          "outlier, a jump that persists starts a new piece of track (default 60)")
            ->check(finite)->check(positive);
        // The report's map for QGIS (issue 17).
        m_sub->add_option("--poses-interval", m_poses_interval_s,
                          "The poses layer (the hull along each track, for replaying the run in QGIS): a fix is kept when this "
                          "many seconds have passed and the ship moved 300 m since the last kept one, or max(900, this) seconds "
                          "passed; state changes and piece ends always. 0: every fix (default 120; in exercise mode 0)")
            ->check(finite)->check(non_negative)->check(at_most(max_poses_interval_s, "a day"));
        m_sub->add_flag("--no-project", m_no_project,
                        "The events only, for QGIS: no poses layer, no coast (chart) layer and no QGIS project (a GeoPackage's "
                        "stored project; REPORT.qgz and its layer files beside a GeoJSON report)");
        m_sub->add_option("--plot", m_plot, "Also draw the run as an SVG picture: overview and zoomed panels, groundings first");
        m_sub->add_option("--debrief", m_debrief,
                          "Also write the instructor's debrief: FOLDER (created if missing) receives one self-contained HTML page "
                          "per exercise, <exercise>.html (the picture, scores, events in time order with zoomed panels, encounters)");
        m_sub->add_flag("--debrief-record", m_debrief_record,
                        "With --shard I/N: also write the shard's debrief record beside its part, REPORT.debrief.cbor, from which "
                        "shoal merge --debrief FOLDER --plot FILE makes the whole run's debrief and picture");
        m_sub->add_option("--date", m_date, "Date (YYYY-MM-DD, UTC) for logs whose times carry none (NMEA without RMC/ZDA)");
        m_sub->add_flag("--progress,!--no-progress", m_progress, "Progress bar on stderr (default: when stderr is a terminal)");
        CLI::Option* q = m_sub->add_flag("-q,--quiet", m_quiet,
                                         "Nothing on stdout and no warnings or notes on stderr: errors only (the exit status says whether "
                                         "there was a grounding; the report holds everything, warnings in its problems)");
        q->excludes(m_sub->get_option("--verbose"));  // --verbose (CoastAndShip): also every track in the summary's table
    }
    int run() override {
        set_quiet(m_quiet);
        if (m_partitions) return write_partitions();
        // Vessels files found in track folders join after the ones given with --vessels.
        std::vector<std::string> folder_vessels;
        std::vector<std::string> all_inputs = m_opts.inputs(track::expand_inputs(m_tracks, nullptr, &folder_vessels));
        all_inputs.insert(all_inputs.end(), m_tracks.begin(), m_tracks.end());  // a zip or folder as given, too
        std::sort(folder_vessels.begin(), folder_vessels.end());
        m_vessel_files.insert(m_vessel_files.end(), folder_vessels.begin(), folder_vessels.end());
        all_inputs.insert(all_inputs.end(), m_berths.begin(), m_berths.end());
        all_inputs.insert(all_inputs.end(), m_vessel_files.begin(), m_vessel_files.end());
        if (!m_roles_file.empty()) all_inputs.push_back(m_roles_file);
        if (!m_assess_file.empty()) all_inputs.push_back(m_assess_file);
        // A partitioned run reads the partitions' files and the traffic files instead.
        for (const std::string& folder : m_from_partitions) {
            std::error_code ec;
            for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) all_inputs.push_back(entry.path().string());
        }
        all_inputs.insert(all_inputs.end(), m_traffic.begin(), m_traffic.end());
        const std::string format = !m_format.empty() ? m_format
                                   : std::filesystem::path(m_output).extension() == ".gpkg" ? "gpkg" : "geojson";
        // Every output, checked before any work: none is an input or another output.
        std::vector<OutputSpec> outputs = m_traffic_only ? std::vector<OutputSpec>{{m_output, "-o", "the partition's traffic"}}
                                                         : report::report_outputs(m_output, format, !m_no_project);
        if (!m_plot.empty()) outputs.push_back({m_plot, "--plot", "the picture", report::is_shoal_picture});
        check_outputs(outputs, all_inputs);
        if (!m_shard.empty()) {
            m_audit.shard = audit::parse_shard(m_shard);
            // A shard holds its part of the run's tracks: the whole run's outputs (the debrief's
            // pages, the picture) would be written by every shard over one another, each showing
            // its own part as the run. Each writes its debrief record instead; merge makes them.
            for (const auto& [option, value] : {std::pair<const char*, const std::string*>{"--debrief", &m_debrief}, {"--plot", &m_plot}})
                if (!value->empty())
                    throw UsageError(std::string(option) + " with --shard: " + option +
                                     " writes the whole run's outputs and a shard holds only its part of the tracks (every shard would "
                                     "write over the others'); give each shard --debrief-record and " + option +
                                     " to shoal merge, which makes it from the records, or give " + option +
                                     " to one shoal check of the whole run, without --shard");
            if (m_debrief_record) {
                if (is_standard_output(m_output) || is_system_path(m_output))
                    throw UsageError("--debrief-record goes beside the part: give -o a file, not '" + m_output + "'");
                outputs.push_back({report::debrief_record_path(m_output), "--debrief-record", "the debrief record"});
                check_outputs(outputs, all_inputs);
            }
        } else if (m_debrief_record) {
            throw UsageError("--debrief-record goes with --shard I/N (a shard's record, for shoal merge --debrief/--plot); a whole run "
                             "writes its debrief itself: --debrief FOLDER, --plot FILE");
        }
        if (!m_debrief.empty()) report::check_debrief_folder(m_debrief);
        m_audit.sweep.pose_interval_s = m_poses_interval_s;
        // The poses go to the QGIS project's poses layer, the picture and the debrief only.
        m_audit.sweep.keep_poses = !m_no_project || !m_plot.empty() || !m_debrief.empty() || m_debrief_record;
        m_audit.sweep.pose_max_interval_s = std::max(audit::SweepOptions{}.pose_max_interval_s, m_poses_interval_s);
        audit::check_step(m_audit.sweep.step_m);
        // Exercises and roles (issue 18): either option turns exercise mode on.
        if (!m_exercise_by.empty()) {
            const audit::ExerciseGrouping grouping = audit::parse_exercise_grouping(m_exercise_by);
            m_audit.exercise_by = grouping.by;
            m_audit.read.exercise_column = grouping.column;
            m_audit.encounters = true;
        }
        if (!m_audit.read.role_column.empty()) m_audit.encounters = true;
        if (!m_roles_file.empty()) {
            check_readable({m_roles_file});
            m_roles = audit::Roles::load(m_roles_file);
            m_audit.roles = &m_roles;
            m_audit.encounters = true;
        }
        if (!m_assess_file.empty()) {  // scored criteria (issue 18)
            check_readable({m_assess_file});
            m_assessment = audit::Assessment::load(m_assess_file);
            m_audit.assessment = &m_assessment;
            m_audit.encounters = true;
        }
        // The world: a simulator exercise's chart is the world; real traffic's is a model.
        m_audit.world = !m_world.empty() ? *audit::parse_world(m_world) : m_audit.encounters ? audit::World::simulated : audit::World::real;
        // Exercise mode replays the exercise (issue 38): a pose at every fix unless --poses-interval
        // says otherwise, so that at any instant each ship is drawn once, where it was.
        if (m_audit.encounters && m_sub->count("--poses-interval") == 0) {
            m_audit.sweep.pose_interval_s = 0;
            m_audit.sweep.pose_max_interval_s = audit::SweepOptions{}.pose_max_interval_s;
        }
        const hull::Hull hull = m_opts.load_hull();
        apply_date();
        const grid::CoastGrid g = m_opts.load_grid(hull);
        m_audit.hazard_depth_m = m_opts.request.import.limiting_depth_m;
        m_audit.ukc_m = m_opts.ukc;
        {  // the default ship's limit; whether an --ukc is used is the vessels' affair (the audit says)
            grid::DepthPlan plan = grid::plan_vessel_depth(m_audit.hazard_depth_m, NAN, hull.draught(), m_audit.ukc_m, g);
            plan.ukc_unused = false;
            m_opts.warn_depth(plan, g);
        }
        check_readable(m_berths);
        // Expected-contact areas: --berths, and the S-57 charts the coast came from.
        std::vector<std::string> area_warnings;
        const coast::ExpectedAreas areas =
            coast::ExpectedAreas::load(m_berths, grid::coast_sources(m_opts.coast, g), g.frame(), m_berth_tolerance_m, &area_warnings);
        print_warnings(area_warnings);
        if (!areas.empty() && !quiet())
            std::fprintf(stderr, "shoal: %zu expected-contact areas (berths, harbours, anchorages) and %zu shore constructions\n",
                         areas.count(coast::AreaRole::expected), areas.count(coast::AreaRole::structure));
        m_audit.areas = &areas;
        // The chart's positional tolerance: 0.5 mm at its compilation scale.
        {
            std::optional<double> scale = m_chart_scale;
            if (!scale) scale = coast::compilation_scale(grid::coast_sources(m_opts.coast, g));
            if (scale) m_audit.evidence.chart_tolerance_m = coast::positional_tolerance_m(*scale);
        }
        // Static data: the first table that names a vessel gives its data (track::merge_vessels).
        std::vector<std::string> vessel_warnings;
        m_vessels = track::read_vessels_files(m_vessel_files, &vessel_warnings);
        print_warnings(vessel_warnings);
        if (!m_vessel_files.empty()) {
            m_audit.vessels = &m_vessels;
            if (!quiet()) std::fprintf(stderr, "shoal: static data of %zu vessels from %zu vessels files (--vessels, and vessels tables in track folders and zips)\n",
                         m_vessels.size(), m_vessel_files.size());
        }
        Progress bar(m_progress.value_or(::isatty(2) != 0));
        m_audit.progress = [&](std::size_t done, std::size_t total) { bar(done, total); };
        if (!m_from_partitions.empty() || m_traffic_only || !m_traffic.empty()) {
            if (m_from_partitions.empty()) throw UsageError("--traffic-only and --traffic go with --from-partitions");
            if (m_traffic_only && m_debrief_record)
                throw UsageError("--debrief-record goes with a part (the partition's audit, --traffic), not with --traffic-only, which writes no part");
            if (!m_audit.shard.active()) throw UsageError("--from-partitions needs --shard I/N: the partition I of N to audit");
            if (m_audit.encounters)
                throw UsageError("--from-partitions: exercise mode checks an exercise whole, not by partitions of vessels; use --shard alone");
        }
        std::vector<std::string> partition_ids;
        std::vector<std::size_t> partition_positions;
        std::optional<audit::ReadResult> partition;
        if (!m_from_partitions.empty()) {
            keep_freed_memory();
            partition = audit::read_partition(m_from_partitions, m_tracks, m_audit.read, m_audit.shard, partition_positions, &partition_ids);
            if (m_audit.vessels)
                for (std::string& w : track::unmatched_vessels_tables(*m_audit.vessels, partition_ids)) partition->warnings.push_back(std::move(w));
        }
        // What the partitions' traffic is made from (the partitions, the grid, the ship): written with it, checked where it is read.
        const std::string traffic_key = partition ? audit::traffic_key(m_from_partitions, g.source().fingerprint, m_opts.hull_label()) : "";
        if (m_traffic_only) {
            const std::vector<audit::TrackResult> traffic = audit::traffic_of_partition(*partition, g, hull, m_audit);
            audit::write_traffic(m_output, traffic, m_audit.shard, traffic_key);
            std::fprintf(stderr, "shoal: the traffic of %zu tracks of partition %s written to %s\n", traffic.size(), m_audit.shard.text().c_str(),
                         printable(m_output).c_str());
            return exit_ok;
        }
        if (partition && m_audit.world == audit::World::real && m_traffic.empty())
            throw UsageError("--from-partitions in the real world needs --traffic T0 --traffic T1 ... (one per partition, in order): every partition's traffic (--traffic-only)");
        const audit::AuditResult r =
            partition ? audit::audit_partition(std::move(*partition), std::move(partition_positions),
                                               m_audit.world == audit::World::real ? audit::read_traffic(m_traffic, m_audit.shard, traffic_key)
                                                                                   : std::vector<audit::TrackResult>{},
                                               g, hull, m_opts.hull_label(), m_audit)
                      : audit::run_audit(m_tracks, g, hull, m_opts.hull_label(), m_audit);
        for (const auto& f : r.files) {
            if (!f.error.empty()) std::fprintf(stderr, "shoal: error: %s (file skipped)\n", printable(in_cli_terms(f.error)).c_str());
            if (quiet()) continue;
            for (const auto& m : f.read.messages) std::fprintf(stderr, "shoal: warning: %s\n", printable(m).c_str());
            if (f.read.skipped > f.read.skips_said)
                std::fprintf(stderr, "shoal: warning: %s: %zu more bad rows skipped\n", printable(f.file).c_str(), f.read.skipped - f.read.skips_said);
            if (f.read.reordered)
                std::fprintf(stderr, "shoal: warning: %s: %zu fixes out of time order (sorted by time)\n", printable(f.file).c_str(), f.read.reordered);
            if (f.read.duplicates)
                std::fprintf(stderr, "shoal: warning: %s: %zu fixes repeat an earlier time of their vessel (dropped)\n", printable(f.file).c_str(),
                             f.read.duplicates);
        }
        std::size_t wild_said = 0;
        for (const auto& t : r.tracks)
            for (const auto& w : t.summary.wild_fixes)
                if (wild_said++ < 20) print_warnings({report::wild_fix_message(t.summary, w)});
        print_warnings(r.warnings);
        if (wild_said > 20 && !quiet()) std::fprintf(stderr, "shoal: warning: %zu more wild fixes dropped (listed in the report's problems)\n", wild_said - 20);
        for (const auto& e : r.errors)
            std::fprintf(stderr, "shoal: error: track '%s' in '%s': %s (track skipped)\n", printable(e.track).c_str(), printable(e.file).c_str(), printable(in_cli_terms(e.message)).c_str());
        report::RunInfo info = report::run_info(m_opts.coast, g, m_opts.ship_file.empty() ? "--dims " + m_opts.dims : hull.name(),
                                                      m_audit, m_berths, hull.draught());
        info.roles = m_roles_file;
        info.roles_fingerprint = report::files_fingerprint(m_roles_file.empty() ? std::vector<std::string>{} : std::vector<std::string>{m_roles_file});
        // Read from standard input or a pipe: what was read (the name alone would be the same for any roles).
        if (!m_roles_file.empty() && is_stream(m_roles_file)) info.roles_fingerprint = report::roles_fingerprint(m_roles);
        info.assessment = m_assess_file;
        // Everything else that changes the report, so that merge refuses parts that differ in it.
        info.berth_tolerance_m = m_berth_tolerance_m;
        if (!m_opts.ship_file.empty()) info.ship_fingerprint = report::files_fingerprint({m_opts.ship_file});  // --dims: `ship` says them
        if (!m_opts.ship_file.empty() && is_stream(m_opts.ship_file)) info.ship_fingerprint = report::hull_fingerprint(hull);  // `-`, a pipe: as read
        for (const auto& v : m_vessel_files) info.vessels += (info.vessels.empty() ? "" : ", ") + v;
        info.vessels_fingerprint = report::files_fingerprint(m_vessel_files);
        if (std::any_of(m_vessel_files.begin(), m_vessel_files.end(), is_stream)) info.vessels_fingerprint = report::vessels_fingerprint(m_vessels);
        if (m_audit.read.date_s) info.date = report::iso_time(*m_audit.read.date_s).substr(0, 10);
        info.project = !m_no_project;
        info.jobs = m_audit.jobs;
        // The chart under the run (the coast layer), the grid's sources read again: for a
        // GeoPackage, and for a GeoJSON report whose project files go beside it (not on stdout
        // or a device: report_outputs lists more than the report and its style; not a shard).
        const bool geojson_project = format != "gpkg" && !r.shard.active() && report::report_outputs(m_output, format, info.project).size() > 2;
        std::optional<report::ChartRead> chart;
        if (info.project && (format == "gpkg" || geojson_project)) {
            // On more than one thread, a GeoJSON report's chart is read while the report and its
            // other files are written; its coast layer waits for it.
            chart.emplace(m_opts.coast, g, r, format != "gpkg" && m_audit.jobs != 1);
            chart->give(info);
            if (!chart->meanwhile() && !info.chart) print_warnings({chart->warning()});
        }
        const auto t0 = std::chrono::steady_clock::now();
        // The report, its style and its picture are staged, then put in place together: an
        // interrupt before the end leaves every earlier file as it was.
        std::vector<StagedOutput> staged;
        if (format == "gpkg") {
            staged.push_back(report::stage_gpkg(m_output, r, info));
        } else {
            std::vector<std::string> style_warnings;
            // The chart's warning (its read going on meanwhile) said once it is known, also when
            // the report could not be written.
            const auto chart_said = [&] {
                if (chart && chart->meanwhile() && !chart->warning().empty()) print_warnings({chart->warning()});
            };
            try {
                staged = report::stage_geojson(m_output, r, info, &style_warnings);
            } catch (...) {
                chart_said();
                throw;
            }
            chart_said();
            print_warnings(style_warnings);
        }
        // A shard's debrief record, beside its part (fingerprinted from the part's bytes as staged).
        if (m_debrief_record && r.shard.active())
            staged.push_back(report::stage_debrief_record(staged.front(), r, info, report::GridSpec{m_opts.coast, m_opts.request}));
        // A picture that cannot be written is an error said as such, but it must not hide the
        // groundings the report holds (exit 1 stays 1).
        const auto not_written = [&](const char* what, const std::exception& e) {
            std::fprintf(stderr, "shoal: error: the %s was not written: %s (the report %s was)\n", what, printable(in_cli_terms(e.what())).c_str(),
                         printable(m_output).c_str());
        };
        bool plot_failed = false;
        if (!m_plot.empty()) {
            try {
                StagedOutput picture(m_plot);
                picture.write(report::plot_svg(r, g));
                staged.push_back(std::move(picture));
            } catch (const InputError& e) {
                not_written("picture", e);
                plot_failed = true;
            }
        }
        // The debrief pages: named by the exercises, so checked against the inputs and the
        // other outputs only now (stage_debrief); like the picture, a failure is said and the
        // report is kept.
        bool debrief_failed = false;
        std::size_t debrief_pages = 0;
        if (!m_debrief.empty()) {
            try {
                // A page refused (a file of its name that shoal did not write) fails the run
                // (exit 2), said as an error, also with --quiet.
                std::vector<std::string> refused;
                std::vector<StagedOutput> sheets = report::stage_debrief(m_debrief, r, g, info, all_inputs, outputs, {}, &refused);
                print_errors(refused);
                debrief_failed = !refused.empty();
                debrief_pages = sheets.size();
                for (auto& s : sheets) staged.push_back(std::move(s));
            } catch (const InputError& e) {
                not_written("debrief", e);
                debrief_failed = true;
            } catch (const UsageError& e) {
                not_written("debrief", e);
                debrief_failed = true;
            }
        }
        // Every output in place at once; an interrupt from here on comes too late to undo the
        // run, which ends as it would have (process.hpp: hold_interrupts).
        const sigset_t interrupts = hold_interrupts();
        try {
            commit_all(staged);
        } catch (...) {
            release_interrupts(interrupts);
            throw;
        }
        outputs_in_place(interrupts);
        const double write_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // With -o - the report is stdout: the table goes to stderr, so the JSON stays clean.
        std::FILE* table = is_standard_output(m_output) || (!m_plot.empty() && is_standard_output(m_plot)) ? stderr : stdout;
        if (!m_quiet) {
            std::fputs(report::summary_table(r, m_opts.verbose ? report::SummaryDetail::verbose : report::SummaryDetail::normal).c_str(), table);
            const double fps = r.sweep_s > 0 ? static_cast<double>(r.fixes) / r.sweep_s : 0;
            std::fprintf(table, "time: read %.3f s, sweep %.3f s (%.0f fixes/s), write %.3f s\nreport: %s\n", r.read_s, r.sweep_s, fps, write_s,
                         printable(m_output).c_str());
        }
        if (!m_debrief.empty() && !m_quiet) std::fprintf(table, "debrief: %zu page%s in %s\n", debrief_pages, debrief_pages == 1 ? "" : "s", printable(m_debrief).c_str());
        bool unreadable = r.tracks.empty() && (!r.errors.empty() || std::any_of(r.files.begin(), r.files.end(), [](const auto& f) { return !f.error.empty(); }));
        // A shard's report is a part of a run: files and tracks it could not read are listed
        // in it (problems) for the merge, and are no failure of the shard (a driver would
        // retry it, or give up on the run, for a file a single run would skip).
        if (r.shard.active()) unreadable = false;
        if (unreadable) return exit_usage;
        if (r.groundings > 0 || r.collisions > 0) return exit_found;
        return plot_failed || debrief_failed ? exit_usage : exit_ok;
    }

private:
    /// --date, when given, into the read options.
    void apply_date() {
        if (m_date.empty()) return;
        const auto day = track::parse_date(m_date);
        if (!day) throw UsageError("--date '" + m_date + "' is not a date YYYY-MM-DD");
        m_audit.read.date_s = *day;
    }
    /// --partitions K: the one TRACK input read and written, hashed by vessel, into K partition
    /// files in the new folder -o (audit::write_partitions). Only what changes the reading
    /// matters here (--date, --hull-from-length-width); no grid is built.
    int write_partitions() {
        if (m_tracks.size() != 1)
            throw UsageError("--partitions writes the partitions of one TRACK input (a file, folder or zip), not " + std::to_string(m_tracks.size()) +
                             ": one task per input");
        if (!m_from_partitions.empty() || !m_shard.empty() || m_traffic_only || !m_traffic.empty() || m_debrief_record)
            throw UsageError("--partitions writes partitions: it goes without --from-partitions, --shard, --traffic, --traffic-only and --debrief-record");
        if (m_audit.encounters || !m_exercise_by.empty() || !m_audit.read.role_column.empty() || !m_roles_file.empty() || !m_assess_file.empty())
            throw UsageError("--partitions: exercise mode checks an exercise whole, not by partitions of vessels; use --shard");
        apply_date();
        const auto t0 = std::chrono::steady_clock::now();
        keep_freed_memory();
        const audit::PartitionSummary s = audit::write_partitions(m_output, m_tracks.front(), m_audit.read, m_partitions, m_audit.jobs,
                                                                  report::read_file_fingerprint);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // One line for the driver's task log: what was read, once.
        std::fprintf(stderr, "shoal: partitions: %s: %zu files, %zu bytes read, %zu tracks, %zu fixes into %u partitions in %s (%.2f s)\n",
                     printable(m_tracks.front()).c_str(), s.files, s.bytes_read, s.tracks, s.fixes, m_partitions, printable(m_output).c_str(), seconds);
        return exit_ok;
    }

    unsigned m_partitions = 0;
    std::vector<std::string> m_from_partitions, m_traffic;
    bool m_traffic_only = false;
    CoastAndShip m_opts;
    std::vector<std::string> m_tracks;
    std::string m_output;
    std::string m_format;
    std::optional<bool> m_progress;
    std::string m_date;
    std::string m_plot;
    std::string m_debrief;
    bool m_debrief_record = false;
    std::string m_shard;
    std::string m_world;
    std::optional<double> m_chart_scale;
    std::vector<std::string> m_berths;
    std::vector<std::string> m_vessel_files;
    std::map<std::string, track::VesselInfo> m_vessels;
    double m_berth_tolerance_m = 10.0;
    static constexpr double max_poses_interval_s = 86400;
    static constexpr double max_listed_per_ship = 1e6;  // --max-encounters-per-ship
    double m_poses_interval_s = audit::SweepOptions{}.pose_interval_s;
    bool m_no_project = false;
    bool m_quiet = false;
    audit::AuditOptions m_audit;
    std::string m_exercise_by;  // exercises and roles (issue 18)
    std::string m_roles_file;
    audit::Roles m_roles;
    std::string m_assess_file;  // scored criteria (issue 18)
    audit::Assessment m_assessment;
};

}  // namespace

std::unique_ptr<Command> make_check_command() { return std::make_unique<CheckCommand>(); }

}  // namespace shoal::cli
