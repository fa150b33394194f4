// The run header of a report (report::run_info): what was checked, against what, by which rules.
#include <shoal/report/run_info.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <algorithm>
#include <vector>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <shoal/grid/coast_grid.hpp>
#include <shoal/grid/grid_builder.hpp>
#include <shoal/grid/limiting_depth.hpp>

#include "util/input_file.hpp"

namespace shoal::report {

namespace {

std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out;
}

/// Feeds the size and bytes of the file at `path` to `st`; the size (-1, and the name fed instead,
/// when it is not a regular file or cannot be read).
long long feed_file(XXH3_state_t* st, const std::string& path) {
    const auto feed = [&](const void* p, std::size_t n) { XXH3_64bits_update(st, p, n); };
    long long size = 0;
    XXH3_state_t* content = XXH3_createState();
    XXH3_64bits_reset(content);
    // Only a regular file is read (detail::read_blocks): a FIFO would wait for a writer, a
    // device never end.
    const bool read = shoal::detail::read_blocks(path, std::size_t{1} << 20, [&](const char* p, std::size_t n) {
        XXH3_64bits_update(content, p, n);
        size += static_cast<long long>(n);
    });
    const std::uint64_t digest = XXH3_64bits_digest(content);
    XXH3_freeState(content);
    if (!read) {
        const long long none = -1;
        feed(&none, sizeof none);
        feed(path.data(), path.size());
        return -1;
    }
    feed(&size, sizeof size);
    feed(&digest, sizeof digest);
    return size;
}

/// The files of each vector source, as GDAL lists them (a Shapefile's .shp, .shx, .dbf, .prj;
/// grid::dataset_files), sorted; the path itself when GDAL lists none (or cannot open it, or it
/// is not a regular file).
std::vector<std::string> source_files(const std::vector<std::string>& paths) {
    std::vector<std::string> out;
    for (const std::string& path : paths) {
        std::vector<std::string> files;
        if (shoal::detail::is_regular_input(path)) files = grid::dataset_files(path);
        std::sort(files.begin(), files.end());
        if (files.empty()) files.push_back(path);
        out.insert(out.end(), files.begin(), files.end());
    }
    return out;
}

}  // namespace

std::string files_fingerprint(const std::vector<std::string>& paths) {
    if (paths.empty()) return "";
    XXH3_state_t* st = XXH3_createState();
    XXH3_64bits_reset(st);
    for (const auto& p : paths) feed_file(st, p);
    const std::uint64_t digest = XXH3_64bits_digest(st);
    XXH3_freeState(st);
    return grid::fingerprint_hex(digest);
}

std::pair<long long, std::string> file_size_and_fingerprint(const std::string& path) {
    XXH3_state_t* st = XXH3_createState();
    XXH3_64bits_reset(st);
    const long long size = feed_file(st, path);
    const std::uint64_t digest = XXH3_64bits_digest(st);
    XXH3_freeState(st);
    return {size, grid::fingerprint_hex(digest)};
}

std::pair<long long, std::string> read_file_fingerprint(const audit::FileResult& f) {
    if (const auto& d = f.read.stream_digest) return {static_cast<long long>(d->second), grid::fingerprint_hex(d->first)};
    return file_size_and_fingerprint(f.file);
}

geo::Box chart_box_lonlat(const grid::CoastGrid& grid) {
    geo::Box out;
    const geo::Box e = grid.extent();
    if (!(e.minx <= e.maxx && e.miny <= e.maxy)) return out;
    // The border sampled (a box in the frame's metres is curved in lon/lat), 16 points a side.
    for (int i = 0; i <= 16; ++i)
        for (int j = 0; j <= 16; ++j) {
            if (i != 0 && i != 16 && j != 0 && j != 16) continue;
            try {
                const geo::LonLat p = grid.frame().inverse({e.minx + (e.maxx - e.minx) * i / 16, e.miny + (e.maxy - e.miny) * j / 16});
                if (std::isfinite(p.lon) && std::isfinite(p.lat)) out.extend(geo::XY{p.lon, p.lat});
            } catch (const std::exception&) {  // a corner the frame cannot take back: the others say enough
            }
        }
    return out;
}

RunInfo run_info(const std::vector<std::string>& coast, const grid::CoastGrid& grid, const std::string& ship,
                 const audit::AuditOptions& options, const std::vector<std::string>& berths, double default_draught_m) {
    RunInfo info;
    info.coast = joined(coast);
    info.frame = grid.frame().description();
    info.cell_m = grid.cell_size();
    info.chart_lonlat = chart_box_lonlat(grid);
    const grid::DepthPlan depth = grid::plan_vessel_depth(options.hazard_depth_m, NAN, default_draught_m, options.ukc_m, grid);
    info.limiting_depth_m = depth.depth_m.value_or(NAN);
    info.limiting_depth_source = grid::to_string(depth.source);
    info.ukc_m = options.ukc_m.value_or(0.0);
    info.grid_fingerprint = grid::fingerprint_hex(grid.source().fingerprint);
    // A grid file's chart sources are read again (berths, shore constructions, the scale, the
    // coast layer): their bytes now, which the grid's fingerprint (of its build) does not say.
    if (const auto sources = grid::coast_sources(coast, grid); sources != coast && !sources.empty())
        info.chart_fingerprint = grid::fingerprint_hex(grid::fingerprint_sources(sources, {}, "", 0));
    info.ship = ship;
    info.sweep = options.sweep;
    info.world = options.world;
    info.evidence = options.evidence;
    info.wild = options.wild;
    info.berths = joined(berths);
    info.berths_fingerprint = files_fingerprint(source_files(berths));  // a Shapefile's .prj and .dbf too
    info.hull_from_length_width = options.read.hull_from_length_width;
    info.ship_margin_m = options.encounter.ship_margin_m;
    info.exercise_by = audit::exercise_by_text(options.exercise_by, options.read.exercise_column);
    info.role_column = options.read.role_column;
    info.encounter_range_m = options.colreg.range_m;
    info.max_encounters_per_ship = options.max_encounters_per_ship;
    return info;
}

}  // namespace shoal::report
