// shoal merge: the reports of a run's shards (check --shard I/N) put together as one run's.
#include "commands.hpp"
#include "options.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include <shoal/report/merge.hpp>
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
                      "Exit status: as check's for the merged report: 0 no grounding, 1 a grounding (or ship collision), 2 bad parts.");
        m_sub->add_option("parts", m_parts, "Shard reports (written by shoal check --shard I/N -o PART.geojson or PART.gpkg)")->required();
        m_sub->add_option("-o,--output", m_output, "Report to write: .gpkg from GeoPackage parts, else GeoJSON (its QGIS style beside it)")->required();
    }
    int run() override {
        std::vector<std::string> warnings;
        const report::MergeSummary s = report::merge_reports(m_parts, m_output, &warnings);
        print_warnings(warnings);
        std::FILE* out = is_standard_output(m_output) ? stderr : stdout;
        const std::string collisions = s.collisions ? ", " + std::to_string(s.collisions) + " collisions" : "";
        std::fprintf(out, "merged %zu parts: %zu tracks, %zu events, %zu groundings%s\nreport: %s\n", s.parts, s.tracks, s.events, s.groundings,
                     collisions.c_str(), printable(m_output).c_str());
        return s.groundings > 0 || s.collisions > 0 ? exit_found : exit_ok;
    }

private:
    std::vector<std::string> m_parts;
    std::string m_output;
};

}  // namespace

std::unique_ptr<Command> make_merge_command() { return std::make_unique<MergeCommand>(); }

}  // namespace shoal::cli
