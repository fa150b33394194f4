// The `shoal` executable's own probe of a grid file: no GDAL. It runs only a command line it can
// run exactly as the full front end (main.cpp, in the module) would: `probe` parsed by the same
// options, --coast one .shoalgrid, the ship file and the poses plain regular files (not
// compressed, not standard input, a FIFO or a /vsi path), within their size limits, the grid in
// shoal's own frame (no PROJ: frame_without_proj.cpp). Anything
// else is left, untouched, to the module: nothing has been printed or read from a stream then.
#include "launcher.hpp"

#include <CLI/CLI.hpp>

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "probe_core.hpp"
#include "process.hpp"
#include <shoal/geo/local_frame.hpp>
#include <shoal/grid/grid_cache.hpp>
#include <shoal/grid/grid_file.hpp>
#include <shoal/version.hpp>

namespace shoal::cli {

namespace {

/// The whole content of `path` when it is a regular file of at most `limit` bytes that GDAL would
/// read as it is (not a gzip or a zip, which it unpacks; not `-` or a /vsi path), into `out`.
bool read_plain_file(const std::string& path, std::size_t limit, std::string& out) {
    if (path.empty() || path == "-" || path.rfind("/vsi", 0) == 0) return false;
    struct stat st{};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || static_cast<std::size_t>(st.st_size) > limit) return false;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    out.resize(static_cast<std::size_t>(st.st_size) + 1);  // one more: a file grown since is seen
    const std::size_t got = std::fread(out.data(), 1, out.size(), f);
    const bool ok = !std::ferror(f) && got <= limit;
    std::fclose(f);
    out.resize(got);
    if (!ok) return false;
    const std::string_view head(out.data(), std::min<std::size_t>(got, 4));
    const bool gzip = head.substr(0, 2) == "\x1f\x8b";
    const bool zip = head == std::string_view("PK\x03\x04", 4) || head == std::string_view("PK\x05\x06", 4);
    return !gzip && !zip;
}

/// The `--coast` grid file, as grid::load_or_build loads one (the only case run here).
grid::CoastGrid load_grid_file(const std::vector<std::string>& paths, const grid::BuildRequest&, grid::LoadReport* report) {
    const auto t0 = std::chrono::steady_clock::now();
    report->how = "loaded grid";
    grid::CoastGrid g = grid::GridFile::load(paths.at(0));
    report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return g;
}

}  // namespace

bool run_grid_probe(int argc, char** argv, int& rc) {
    if (argc < 3 || std::strcmp(argv[1], "probe") != 0) return false;
    // main.cpp's app with only the probe: the options parse the same; any parse error, help or
    // version request goes to the module, which says it.
    CLI::App app{"shoal: audit ship tracks against chart coastlines"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("shoal ") + SHOAL_VERSION_STRING);
    ProbeArgs args;
    CLI::App* sub = args.add(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Error&) {
        return false;
    }
    if (!sub->parsed()) return false;
    for (const CLI::Option* o : sub->get_options())  // an empty value: main.cpp's usage error
        if (!o->get_positional() && o->get_type_size_min() > 0)
            for (const std::string& value : o->results())
                if (value.empty()) return false;
    const CoastAndShip& opts = args.opts;
    if (opts.coast.size() != 1 || opts.coast[0].rfind("/vsi", 0) == 0 || !grid::looks_like_grid(opts.coast[0])) return false;
    // shoal's own transverse Mercator is computed here; any other frame needs PROJ (the module).
    if (!geo::LocalFrame::is_own_transverse_mercator(grid::GridFile::frame_definition(opts.coast[0]))) return false;
    std::string ship_text, pose_text;
    if (!opts.ship_file.empty() && !read_plain_file(opts.ship_file, hull::Hull::max_file_bytes, ship_text)) return false;
    if (!read_plain_file(args.poses, io::max_pose_file_bytes, pose_text)) return false;

    ProbeInputs inputs{
        [&] { return opts.hull_with([&](const std::string& path) { return hull::Hull::parse(ship_text, path); }); },
        [&] {
            io::PoseFile poses = io::parse_pose_csv(pose_text, args.poses);
            std::string().swap(pose_text);
            return poses;
        },
        [&](const hull::Hull& hull) { return opts.load_grid_with(hull, load_grid_file); }};
    rc = run_reporting_errors([&] { return run_probe(args, inputs); });
    return true;
}

}  // namespace shoal::cli
