#include <shoal/grid/grid_builder.hpp>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "util/gdal_support.hpp"
#include "util/input_file.hpp"
#include <shoal/grid/grid_file.hpp>
#include <shoal/util/error.hpp>

namespace shoal::grid {

namespace fs = std::filesystem;

namespace {

/// A coastline source as a file to read: a coast is never standard input (OGR reads a source
/// more than once), so `-` is a file of that name, as input_exists takes it; the input layer
/// reads `-` as standard input.
std::string as_file(const std::string& path) { return path == "-" ? "./-" : path; }

}  // namespace

std::uint64_t fingerprint_sources(const std::vector<std::string>& paths, const coast::ImportOptions& options,
                                  const std::string& crs, double cell_m) {
    XXH3_state_t* st = XXH3_createState();
    XXH3_64bits_reset(st);
    auto feed = [&](const std::string& s) {
        const std::uint64_t n = s.size();
        XXH3_64bits_update(st, &n, sizeof n);
        XXH3_64bits_update(st, s.data(), s.size());
    };
    feed("shoal-grid-v" + std::to_string(grid_format_version));
    for (const std::string& path : paths) {
        if (!detail::input_exists(path)) {
            XXH3_freeState(st);
            throw InputError("'" + path + "': no such file or directory");
        }
        try {
            detail::require_dataset_file(path, "a coastline");
        } catch (...) {
            XXH3_freeState(st);
            throw;
        }
        std::vector<std::string> files = dataset_files(path);
        std::sort(files.begin(), files.end());
        for (const std::string& f : files) {
            if (detail::is_folder_input(f)) continue;
            feed(fs::path(f).filename().string());
            // Its bytes as they are stored (a member of a zip unpacked by GDAL).
            detail::read_blocks(as_file(f), std::size_t{1} << 20, [&](const char* data, std::size_t n) { XXH3_64bits_update(st, data, n); });
        }
    }
    for (const auto& l : options.layers) feed("layer:" + l);
    feed("source_crs:" + options.source_crs);
    // Hazards: the danger radius and the depth field shape the grid. The limiting depth does
    // not: the grid holds every depth area and danger, for every vessel's limit.
    char hazards[96];
    std::snprintf(hazards, sizeof hazards, "radius:%.17g", options.danger_radius_m);
    feed(hazards);
    feed("depth_field:" + options.depth_field);
    // Structures: the widths lines and points become (constants of this shoal, fed so that a
    // cache made by a shoal with other widths is not taken for this one's).
    std::snprintf(hazards, sizeof hazards, "structures:%.17g,%.17g,%d", coast::structure_line_half_width_m,
                  coast::structure_point_radius_m, coast::structure_quadrant_segments);
    feed(hazards);
    feed("crs:" + crs);
    XXH3_64bits_update(st, &cell_m, sizeof cell_m);
    const std::uint64_t h = XXH3_64bits_digest(st);
    XXH3_freeState(st);
    return h;
}

CoastGrid build_grid(const std::vector<std::string>& paths, const BuildRequest& request, std::vector<std::string>* warnings,
                     BuildStats* stats, std::string* cell_note) {
    coast::Coastline coast = coast::import_coastline(paths, request.import);
    if (warnings) warnings->insert(warnings->end(), coast.warnings.begin(), coast.warnings.end());
    geo::LocalFrame frame = request.crs.empty()
                                ? geo::LocalFrame::transverse_mercator({(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2})
                                : geo::LocalFrame::from_user_crs(request.crs);
    const double scale_error = frame.max_scale_error(coast.min, coast.max);
    if (scale_error > 1e-4 && warnings) {
        char buf[240];
        std::snprintf(buf, sizeof buf,
                      "the data spans %.2f x %.2f degrees: the local frame's scale error reaches %.2g (over 1 in 10,000); "
                      "distances are off by up to that fraction (split the area or choose a CRS with BuildRequest::crs)",
                      coast.max.lon - coast.min.lon, coast.max.lat - coast.min.lat, scale_error);
        warnings->push_back(buf);
    }
    // Extent in local metres, for the default cell size.
    geo::Box ext;
    for (double fx : {0.0, 0.5, 1.0})
        for (double fy : {0.0, 0.5, 1.0}) {
            try {
                ext.extend(frame.forward({coast.min.lon + fx * (coast.max.lon - coast.min.lon),
                                          coast.min.lat + fy * (coast.max.lat - coast.min.lat)}));
            } catch (const InputError&) {
            }
        }
    const double cell = choose_cell_size(request.cell_m, request.ship_length_m, ext, cell_note);
    CoastGrid g = CoastGrid::build(coast, std::move(frame), cell, stats);
    g.source().inputs = paths;
    g.source().layer_option = request.import.layers;
    g.source().source_crs = request.import.source_crs;
    g.source().limiting_depth_m = request.import.limiting_depth_m.value_or(NAN);
    g.source().danger_radius_m = request.import.danger_radius_m;
    g.source().depth_field = request.import.depth_field;
    g.source().fingerprint =
        fingerprint_sources(paths, request.import, request.crs, request.cell_m > 0 ? request.cell_m : 2.5 * request.ship_length_m);
    return g;
}

std::vector<std::string> coast_sources(const std::vector<std::string>& coast, const CoastGrid& g) {
    if (!(coast.size() == 1 && looks_like_grid(coast[0]))) return coast;
    std::vector<std::string> out;
    for (const std::string& in : g.source().inputs)
        if (detail::is_regular_input(as_file(in)) || detail::is_folder_input(in)) out.push_back(in);  // a Shapefile folder too
    return out;
}

}  // namespace shoal::grid
