// shoal info: what a grid file holds.
#include "commands.hpp"
#include "options.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>

#include <shoal/grid/grid_cache.hpp>

namespace shoal::cli {

namespace {

class InfoCommand final : public Command {
public:
    void setup(CLI::App& app) override {
        m_sub = app.add_subcommand("info", "Print what a grid file holds");
        m_sub->footer("Usage: shoal info GRID");
        m_sub->add_option("grid", m_path, "Grid file written by shoal import")->required();
    }
    int run() override {
        const grid::CoastGrid g = grid::GridFile::load(m_path);
        std::printf("grid file:      %s (format version %u)\n", m_path.c_str(), grid::grid_format_version);
        print_grid(g);
        return exit_ok;
    }

private:
    std::string m_path;
};

}  // namespace

std::unique_ptr<Command> make_info_command() { return std::make_unique<InfoCommand>(); }

}  // namespace shoal::cli
