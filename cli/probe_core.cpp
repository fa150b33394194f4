// shoal probe: collision and clearance of single poses (the options and the run; probe.hpp).
#include "commands.hpp"
#include "probe_core.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <shoal/probe/probe.hpp>
#include <shoal/util/error.hpp>
#include <shoal/util/output_file.hpp>
#include <shoal/util/printable.hpp>

#include "util/standard_input.hpp"

namespace shoal::cli {

CLI::App* ProbeArgs::add(CLI::App& app) {
    CLI::App* sub = app.add_subcommand("probe", "Check single poses (lat,lon,heading per CSV row): collision and clearance");
    sub->footer("Usage: shoal probe --coast COAST_OR_GRID --ship SHIP.json POSES.csv [-o OUT.csv] [--jobs N]\n"
                "Writes lat,lon,heading,collision,clearance_m,covered per pose (collision 0/1; clearance 0 when touching;\n"
                "covered 0 for a pose outside the chart, whose collision and clearance are then empty).\n"
                "A bad row is reported on stderr with its line number and skipped.\n"
                "Shallow water and dangers count as hazards for a limiting depth: --hazard-depth, else the ship's draught + --ukc,\n"
                "else the grid's default (import --hazard-depth), else land only.");
    opts.add(*sub);
    sub->add_option("poses", poses, "CSV of poses: lat,lon,heading (a header line is optional; - for standard input)")->required();
    sub->add_option("-o,--output", output, "Write the CSV here instead of stdout (written atomically)");
    sub->add_option("--jobs,-j", jobs, "Threads checking poses (default: all cores); the output is the same whatever the number");
    return sub;
}

int run_probe(const ProbeArgs& args, const ProbeInputs& inputs) {
    const std::vector<std::string> read = args.opts.inputs({args.poses});
    check_outputs({{args.output, "-o", "the poses CSV", io::is_probe_output}}, read);
    // Standard input can be read once: the ship file read first would leave the poses nothing.
    std::vector<std::string> named;
    auto name = [&](const std::string& path, const std::string& what) {
        if (detail::reads_standard_input(path)) named.push_back(what + " ('" + path + "')");
    };
    name(args.poses, "the poses");
    for (const std::string& c : args.opts.coast) name(c, "--coast");
    name(args.opts.ship_file, "--ship");
    if (named.size() > 1)
        throw UsageError("standard input can be read once, and both " + named[0] + " and " + named[1] + " name it: give one of them as a file");
    const hull::Hull hull = inputs.hull();
    const io::PoseFile poses = inputs.poses();
    for (const auto& e : poses.errors) std::fprintf(stderr, "shoal: warning: %s\n", printable(e).c_str());
    if (poses.skipped > poses.errors.size())
        std::fprintf(stderr, "shoal: warning: %zu more bad rows skipped\n", poses.skipped - poses.errors.size());
    const grid::CoastGrid g = inputs.grid(hull);
    const grid::DepthPlan depth =
        grid::plan_vessel_depth(args.opts.request.import.limiting_depth_m, NAN, hull.draught(), args.opts.ukc, g);
    args.opts.warn_depth(depth, g);
    if (depth.source == grid::DepthPlan::Source::grid_default)
        std::fprintf(stderr, "shoal: limiting depth %.2f m (the grid's default, import --hazard-depth)\n", *depth.depth_m);
    const probe::Probe prober(g, hull, depth.depth_m);
    // Poses checked a block at a time on --jobs threads (probe::Probe: placed with one
    // projection each, the Jacobian from a field fitted once over the chart); each block's
    // rows are written into a piece of their own, and the pieces go out in input order.
    const std::vector<io::PoseRow>& rows = poses.poses;
    std::vector<std::string> pieces((rows.size() + check::placement_block - 1) / check::placement_block);
    auto pose_of = [&](std::size_t k) { return check::Pose{{rows[k].lon, rows[k].lat}, rows[k].heading_deg}; };
    const probe::Batch batch = prober.check_blocks(rows.size(), pose_of, probe::Ask{}, args.jobs, [&](std::size_t from, std::span<const probe::Answer> answers, unsigned) {
        std::string& out = pieces[from / check::placement_block];
        out.reserve(answers.size() * 48);
        for (std::size_t i = 0; i < answers.size(); ++i) {
            const probe::Answer& a = answers[i];
            io::append_probe_row(out, rows[from + i], a.claimed(), a.collision, a.clearance_m, a.covered);
        }
    });
    // Every row was read valid: a pose refused here is one PROJ cannot place, and fails the run.
    if (batch.invalid) throw InputError(batch.first_problem);
    const std::size_t uncovered = batch.uncovered;
    if (uncovered)
        std::fprintf(stderr, "shoal: warning: %zu of %zu poses lie (partly) outside the chart's area: covered 0, collision and clearance unknown\n",
                     uncovered, poses.poses.size());
    StagedOutput output(args.output);
    output.write_streamed([&](const StagedOutput::Sink& sink) {
        sink(io::probe_output_header);
        for (std::string& piece : pieces) {
            sink(piece);
            std::string().swap(piece);
        }
    });
    output.commit();
    return exit_ok;
}

}  // namespace shoal::cli
