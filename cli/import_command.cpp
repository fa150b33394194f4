// shoal import: build a coastline grid and save it as a .shoalgrid file.
#include "commands.hpp"
#include "options.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include <shoal/grid/grid_cache.hpp>
#include <shoal/grid/grid_file.hpp>
#include <shoal/util/output_file.hpp>

namespace shoal::cli {

namespace {

class ImportCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("import", "Build a coastline grid and save it as a .shoalgrid cache file");
        m_sub->footer("Usage: shoal import COAST... -o GRID [--cell M | --ship-length M] [--crs CRS] [--layer NAME] [--hazard-depth M]\n"
                      "With --hazard-depth, depth areas shallower and dangers with a sounding under it (or none) are hazards like land.");
        m_sub->add_option("coast", m_inputs, "Coastline sources: any OGR vector file (Shapefile, GeoJSON, GeoPackage, S-57 .000, ...)")
            ->required();
        m_sub->add_option("-o,--output", m_output, "Grid file to write (.shoalgrid)")->required();
        auto* cell = m_sub->add_option("--cell", m_request.cell_m, "Cell edge in metres (default 500, or 2.5 x --ship-length)")
                         ->check(finite)->check(positive)->check(at_most(grid::CoastGrid::max_cell_m, "the largest cell"));
        m_sub->add_option("--ship-length", m_request.ship_length_m, "Largest ship length in metres: cell = 2.5 x this")
            ->check(finite)->check(positive)->check(at_most(hull::Hull::max_length_m, "longer than any ship"))->excludes(cell);
        m_sub->add_option("--crs", m_request.crs, "Projected CRS for the local frame (default: transverse Mercator centred on the data)");
        m_sub->add_option("--layer", m_request.import.layers,
                          "Layer(s) to read (default: all; S-57: LNDARE and COALNE, with --hazard-depth also DEPARE, DRGARE, UWTROC, WRECKS, OBSTRN)")
            ->delimiter(',');
        m_sub->add_option("--source-crs", m_request.import.source_crs, "CRS of sources that carry none (default: WGS84 if all coordinates are lon/lat)");
        add_hazard_options(*m_sub, m_request.import);
    }
    int run() override {
        check_outputs({{m_output, "-o", "the grid", grid::looks_like_grid}}, m_inputs);
        check_readable(m_inputs);
        std::vector<std::string> warnings;
        grid::BuildStats stats;
        std::string cell_note;
        grid::CoastGrid g = grid::build_grid(m_inputs, m_request, &warnings, &stats, &cell_note);
        print_warnings(warnings);
        grid::GridFile::save(g, m_output);
        std::printf("%s\n", in_cli_terms(cell_note).c_str());
        print_grid(g);
        std::printf("build time:     %.3f s (project %.3f s, clip %.3f s with %llu GEOSClipByRect calls, cell states %.3f s)\n",
                    stats.total_s, stats.project_s, stats.clip_s, static_cast<unsigned long long>(stats.clip_calls), stats.state_s);
        std::error_code ec;  // no size to tell of a device (-o /dev/null)
        const std::uintmax_t bytes = std::filesystem::file_size(m_output, ec);
        if (ec) std::printf("wrote:          %s\n", m_output.c_str());
        else std::printf("wrote:          %s (%llu bytes)\n", m_output.c_str(), static_cast<unsigned long long>(bytes));
        return exit_ok;
    }

private:
    std::vector<std::string> m_inputs;
    std::string m_output;
    grid::BuildRequest m_request;
};

}  // namespace

std::unique_ptr<Command> make_import_command() { return std::make_unique<ImportCommand>(); }

}  // namespace shoal::cli
