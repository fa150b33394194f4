// shoal merge: the reports of a run's shards (check --shard I/N) put together as one run's.
#include "commands.hpp"
#include "options.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include <shoal/merge/merge_parts.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::cli {

namespace {

class MergeCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("merge", "Merge the reports of a run's shards (check --shard I/N) into the report one run would write");
        m_sub->footer("Usage: shoal merge PART.geojson... -o REPORT.geojson | shoal merge PART.gpkg... -o REPORT.gpkg\n"
                      "Parts of the same inputs must be every shard 0..N-1 once; parts of different inputs (one run per file)\n"
                      "follow one another in the order given and must share no file and no vessel. Parts whose run header\n"
                      "differs (version, grid, ship, rules) are refused, naming the field.\n"
                      "The debrief and the picture of a sharded run are made here, from the debrief record each shard writes beside\n"
                      "its part (check --shard I/N -o PART --debrief-record writes PART.debrief.cbor):\n"
                      "  shoal merge PART... -o REPORT --debrief FOLDER --plot FILE.svg\n"
                      "writes the pages and the picture one shoal check --debrief FOLDER --plot FILE.svg of the whole run writes.\n"
                      "Exit status: as check's for the merged report: 0 no grounding, 1 a grounding (or ship collision), 2 bad parts.");
        m_sub->add_option("parts", m_parts, "Shard reports (written by shoal check --shard I/N -o PART.geojson or PART.gpkg)")->required();
        m_sub->add_option("-o,--output", m_output, "Report to write: .gpkg from GeoPackage parts, else GeoJSON (its QGIS style beside it)")->required();
        m_sub->add_option("--debrief", m_options.debrief,
                          "Also write the run's debrief: FOLDER receives one HTML page per exercise, as check --debrief writes "
                          "(every part needs its debrief record: check --shard I/N --debrief-record)");
        m_sub->add_option("--plot", m_options.plot, "Also draw the run as an SVG picture, as check --plot draws it (from the parts' debrief records)");
        m_sub->add_option("--coast", m_options.coast,
                          "With --debrief or --plot: the grid (or coastline sources) the run was checked against, when the --coast the "
                          "shards were given cannot be loaded here (another folder); checked against the run's grid fingerprint")
            ->allow_extra_args(false);
    }
    int run() override {
        std::vector<std::string> warnings;
        if (!m_options.coast.empty() && m_options.debrief.empty() && m_options.plot.empty())
            throw UsageError("merge --coast goes with --debrief or --plot (the grid they are drawn on)");
        const report::MergeSummary s = report::merge_reports(m_parts, m_output, &warnings, m_options);
        print_warnings(warnings);
        print_errors(s.pages_refused);
        std::FILE* out = is_standard_output(m_output) || (!m_options.plot.empty() && is_standard_output(m_options.plot)) ? stderr : stdout;
        const std::string collisions = s.collisions ? ", " + std::to_string(s.collisions) + " collisions" : "";
        std::fprintf(out, "merged %zu parts: %zu tracks, %zu events, %zu groundings%s\nreport: %s\n", s.parts, s.tracks, s.events, s.groundings,
                     collisions.c_str(), printable(m_output).c_str());
        if (!m_options.plot.empty()) std::fprintf(out, "picture: %s\n", printable(m_options.plot).c_str());
        if (!m_options.debrief.empty())
            std::fprintf(out, "debrief: %zu page%s in %s\n", s.pages, s.pages == 1 ? "" : "s", printable(m_options.debrief).c_str());
        if (s.groundings > 0 || s.collisions > 0) return exit_found;
        return s.pages_refused.empty() ? exit_ok : exit_usage;
    }

private:
    std::vector<std::string> m_parts;
    std::string m_output;
    report::MergeOptions m_options;
};

}  // namespace

std::unique_ptr<Command> make_merge_command() { return std::make_unique<MergeCommand>(); }

}  // namespace shoal::cli
