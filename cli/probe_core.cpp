// shoal probe: collision and clearance of single poses (the options and the run; probe.hpp).
#include "commands.hpp"
#include "probe.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <shoal/check/detector.hpp>
#include <shoal/geo/jacobian_field.hpp>
#include <shoal/util/output_file.hpp>
#include <shoal/util/printable.hpp>

namespace shoal::cli {

namespace {

/// Appends `v` as printf's "%.<precision>f" would (std::to_chars is exact, as glibc's printf is).
void append_fixed(std::string& out, double v, int precision) {
    char buf[400];  // enough for any double in fixed notation with 7 decimals
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, precision);
    if (ec != std::errc()) throw std::logic_error("probe: a number too long to write");
    out.append(buf, end);
}

}  // namespace

CLI::App* ProbeArgs::add(CLI::App& app) {
    CLI::App* sub = app.add_subcommand("probe", "Check single poses (lat,lon,heading per CSV row): collision and clearance");
    sub->footer("Usage: shoal probe --coast COAST_OR_GRID --ship SHIP.json POSES.csv [-o OUT.csv] [--jobs N]\n"
                "Writes lat,lon,heading,collision,clearance_m,covered per pose (collision 0/1; clearance 0 when touching;\n"
                "covered 0 for a pose outside the chart, whose collision and clearance are then empty).\n"
                "A bad row is reported on stderr with its line number and skipped.\n"
                "Shallow water and dangers count as hazards for a limiting depth: --hazard-depth, else the ship's draught + --ukc,\n"
                "else the grid's default (import --hazard-depth), else land only.");
    opts.add(*sub);
    sub->add_option("poses", poses, "CSV of poses: lat,lon,heading (a header line is optional)")->required();
    sub->add_option("-o,--output", output, "Write the CSV here instead of stdout (written atomically)");
    sub->add_option("--jobs,-j", jobs, "Threads checking poses (default: all cores); the output is the same whatever the number");
    return sub;
}

int run_probe(const ProbeArgs& args, const ProbeInputs& inputs) {
    check_outputs({{args.output, "-o", "the poses CSV", io::is_probe_output}}, args.opts.inputs({args.poses}));
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
    const check::Detector detector(g, hull, depth.depth_m);
    // Only what is written: no penetration depth, no enclosing polyline, not where a contact is.
    check::CheckOptions asked;
    asked.want_penetration = false;
    asked.want_polyline = false;
    asked.want_contact_point = false;
    // Poses placed a block at a time (one projection each, the Jacobian from a field fitted
    // once over the chart) and checked on --jobs threads; each block's rows are written
    // into a piece of their own, and the pieces go out in input order.
    const geo::JacobianField field(g.frame(), g.extent());
    const std::vector<io::PoseRow>& rows = poses.poses;
    std::vector<std::string> pieces((rows.size() + check::placement_block - 1) / check::placement_block);
    std::atomic<std::size_t> uncovered{0};
    auto pose_of = [&](std::size_t k) { return check::Pose{{rows[k].lon, rows[k].lat}, rows[k].heading_deg}; };
    check::place_in_blocks(g.frame(), field, rows.size(), pose_of, args.jobs, [&](std::size_t from, std::span<const check::LocalPose> placed, unsigned) {
        std::string& out = pieces[from / check::placement_block];
        out.reserve(placed.size() * 48);
        std::size_t outside = 0;
        for (std::size_t i = 0; i < placed.size(); ++i) {
            const io::PoseRow& p = rows[from + i];
            const check::Contact c = detector.check(placed[i], asked);
            append_fixed(out, p.lat, 7);
            out += ',';
            append_fixed(out, p.lon, 7);
            out += ',';
            append_fixed(out, p.heading_deg, 1);
            // Outside the chart nothing is claimed: no collision found there means nothing.
            if (c.covered || c.collision) {
                out += c.collision ? ",1," : ",0,";
                append_fixed(out, c.collision ? 0.0 : c.clearance_m, 3);
                out += c.covered ? ",1\n" : ",0\n";
            } else {
                out += ",,,0\n";
            }
            outside += c.covered ? 0 : 1;
        }
        uncovered += outside;
    });
    if (uncovered)
        std::fprintf(stderr, "shoal: warning: %zu of %zu poses lie (partly) outside the chart's area: covered 0, collision and clearance unknown\n",
                     uncovered.load(), poses.poses.size());
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
