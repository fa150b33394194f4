// shoal probe in the full command module: its inputs read through GDAL's virtual files (a .gz,
// a zip, /vsi paths, FIFOs) and coastline sources built into a cached grid. The executable
// runs a probe of a grid file from plain files itself (grid_probe.cpp), the same way.
#include "commands.hpp"
#include "probe_core.hpp"

#include <CLI/CLI.hpp>

namespace shoal::cli {

namespace {

class ProbeCommand final : public Command {
public:
    void setup(CLI::App& app) override { m_sub = m_args.add(app); }
    int run() override {
        return run_probe(m_args, ProbeInputs{[&] { return m_args.opts.load_hull(); }, [&] { return io::read_pose_csv(m_args.poses); },
                                             [&](const hull::Hull& hull) { return m_args.opts.load_grid(hull); }});
    }

private:
    ProbeArgs m_args;
};

}  // namespace

std::unique_ptr<Command> make_probe_command() { return std::make_unique<ProbeCommand>(); }

}  // namespace shoal::cli
