// bench_geos_probe: `shoal probe` done with GEOS alone, as a whole process, so that the two can be
// timed side by side the way a user runs them (docs/performance.md, "shoal probe against a
// GEOS-only probe"). It reads the same coastline file through OGR (shoal's import, so the same
// polylines), projects it to the same transverse Mercator frame `shoal import` chooses (centred on
// the coastline's box), reads the same poses CSV with shoal's parser and places each pose with
// check::place (PROJ, as probe does); the check itself is the GEOS tree checker of
// bench/geos_tree.hpp (STRtree of coastline pieces, GEOSDistance nearest envelope first, prepared
// land rings). It writes probe's columns (covered is always 1: the GEOS checker has no chart
// extent), so the answers can be compared with probe's, row by row.
//
// --checker polygons: the simplest careful GEOS design instead (bench/geos_tree.hpp
// GeosPolygonTree: an STRtree of prepared land polygons, GEOSPreparedIntersects, then
// GEOSPreparedDistance in a growing box), the peer issue 40 measures against.
//
// Usage: bench_geos_probe --coast COAST --dims A,B,C,D POSES.csv [-o OUT.csv] [--chunk SEGMENTS] [--jobs N]
//                         [--checker pieces|polygons]

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "geos_tree.hpp"
#include <shoal/check/detector.hpp>
#include <shoal/coast/coastline.hpp>
#include <shoal/geo/jacobian_field.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/io/pose_csv.hpp>

namespace {

void append_fixed(std::string& out, double v, int precision) {
    char buf[400];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, precision);
    if (ec != std::errc()) throw std::logic_error("a number too long to write");
    out.append(buf, end);
}

int usage() {
    std::fprintf(stderr, "usage: bench_geos_probe --coast COAST --dims A,B,C,D POSES.csv [-o OUT.csv] [--chunk SEGMENTS] [--jobs N] "
                         "[--checker pieces|polygons]\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string coast_path, dims, poses_path, output, chunk_text = "8", jobs_text = "1", checker = "pieces";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--coast" && more) coast_path = argv[++i];
        else if (a == "--dims" && more) dims = argv[++i];
        else if ((a == "-o" || a == "--output") && more) output = argv[++i];
        else if (a == "--chunk" && more) chunk_text = argv[++i];
        else if (a == "--jobs" && more) jobs_text = argv[++i];
        else if (a == "--checker" && more) checker = argv[++i];
        else if (!a.empty() && a[0] != '-' && poses_path.empty()) poses_path = a;
        else return usage();
    }
    std::size_t chunk = 0;
    const auto [end, ec] = std::from_chars(chunk_text.data(), chunk_text.data() + chunk_text.size(), chunk);
    if (ec != std::errc() || end != chunk_text.data() + chunk_text.size() || chunk == 0) {
        std::fprintf(stderr, "bench_geos_probe: --chunk '%s' is not a whole number of segments >= 1\n", chunk_text.c_str());
        return 2;
    }
    unsigned jobs = 0;
    const auto [jend, jec] = std::from_chars(jobs_text.data(), jobs_text.data() + jobs_text.size(), jobs);
    if (jec != std::errc() || jend != jobs_text.data() + jobs_text.size() || jobs > 256) {
        std::fprintf(stderr, "bench_geos_probe: --jobs '%s' is not a number of threads from 0 (every core) to 256\n", jobs_text.c_str());
        return 2;
    }
    if (coast_path.empty() || dims.empty() || poses_path.empty() || (checker != "pieces" && checker != "polygons")) return usage();
    try {
        const shoal::hull::Hull hull = shoal::hull::Hull::from_dims_string(dims);
        const shoal::io::PoseFile poses = shoal::io::read_pose_csv(poses_path);
        for (const auto& e : poses.errors) std::fprintf(stderr, "bench_geos_probe: warning: %s\n", e.c_str());
        const shoal::coast::Coastline coast = shoal::coast::import_coastline({coast_path});
        const shoal::geo::LocalFrame frame = shoal::geo::LocalFrame::transverse_mercator(
            {(coast.min.lon + coast.max.lon) / 2, (coast.min.lat + coast.max.lat) / 2});
        const std::vector<shoal::coast::LocalPolyline> lines = shoal::coast::project(coast, frame);
        // Placed as shoal probe places them (check::place_in_blocks, the Jacobian from a field
        // over the coast's box): placing is not the check being compared.
        shoal::geo::Box box;
        for (const auto& l : lines)
            for (const shoal::geo::XY& q : l.points) box.extend(q);
        const shoal::geo::JacobianField field(frame, box);
        // One tree a thread (each its own GEOS context): GEOS objects are not shared by threads.
        const unsigned threads = jobs ? jobs : std::max(1u, std::thread::hardware_concurrency());
        std::vector<std::unique_ptr<shoal::bench::GeosTree>> trees;
        std::vector<std::unique_ptr<shoal::bench::GeosPolygonTree>> polygons;
        for (unsigned w = 0; w < threads; ++w) {
            if (checker == "pieces") trees.push_back(std::make_unique<shoal::bench::GeosTree>(lines, chunk));
            else polygons.push_back(std::make_unique<shoal::bench::GeosPolygonTree>(lines));
        }
        const std::vector<shoal::io::PoseRow>& rows = poses.poses;
        std::vector<std::string> pieces((rows.size() + shoal::check::placement_block - 1) / shoal::check::placement_block);
        auto pose_of = [&](std::size_t k) { return shoal::check::Pose{{rows[k].lon, rows[k].lat}, rows[k].heading_deg}; };
        shoal::check::place_in_blocks(frame, field, rows.size(), pose_of, threads,
                                      [&](std::size_t from, std::span<const shoal::check::LocalPose> placed, unsigned worker) {
            std::string& out = pieces[from / shoal::check::placement_block];
            out.reserve(placed.size() * 48);
            for (std::size_t i = 0; i < placed.size(); ++i) {
                const shoal::io::PoseRow& p = rows[from + i];
                const std::vector<shoal::geo::XY> outline = shoal::check::hull_outline(hull, placed[i]);
                const shoal::bench::Answer a = trees.empty() ? polygons[worker]->check(outline, INFINITY) : trees[worker]->check(outline, INFINITY);
                append_fixed(out, p.lat, 7);
                out += ',';
                append_fixed(out, p.lon, 7);
                out += ',';
                append_fixed(out, p.heading_deg, 1);
                out += a.collision ? ",1," : ",0,";
                append_fixed(out, a.collision ? 0.0 : a.clearance, 3);
                out += ",1\n";
            }
        });
        std::string out = "lat,lon,heading,collision,clearance_m,covered\n";
        for (const std::string& piece : pieces) out += piece;
        FILE* f = output.empty() ? stdout : std::fopen(output.c_str(), "wb");
        if (!f) throw std::runtime_error("cannot write " + output + ": " + std::strerror(errno));
        const bool ok = std::fwrite(out.data(), 1, out.size(), f) == out.size();
        if (f != stdout && std::fclose(f) != 0) throw std::runtime_error("cannot write " + output);
        if (!ok) throw std::runtime_error("cannot write " + (output.empty() ? std::string("stdout") : output));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_geos_probe: %s\n", e.what());
        return 1;
    }
    return 0;
}
