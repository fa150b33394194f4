#pragma once
/// Reading a CoastGrid outward from a box (a point is a box of no size): the one traversal
/// behind every nearest-coast search (CoastGrid::nearest_segment, enclosing_polyline, the
/// detector's clearance). The cells under the box come first, then rings of cells around
/// them, each ring cut to the cells within the visitor's reach of the box, until no cell not
/// read yet can matter. Inside a cell, chunks of segments far from what is sought are
/// skipped whole (visit_chunks).

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include <shoal/grid/coast_grid.hpp>

namespace shoal::grid {

/// Calls run(box, begin, end) for each chunk of `segs` (a span returned by grid.segments(i, j)),
/// in order: [begin, end) the chunk's segments that lie in `segs`, `box` the chunk's box (see
/// CoastGrid::chunk_boxes).
template <class Run>
void for_each_chunk(const CoastGrid& grid, std::span<const Segment> segs, Run&& run) {
    if (segs.empty()) return;
    constexpr std::size_t chunk = CoastGrid::chunk_segments;
    const std::size_t first = grid.index_of(segs), n = segs.size();
    const std::span<const geo::Box> boxes = grid.chunk_boxes();
    for (std::size_t k = 0; k < n;) {
        const std::size_t g = first + k, end = std::min(n, k + (chunk - g % chunk));
        run(boxes[g / chunk], segs.data() + k, segs.data() + end);
        k = end;
    }
}

/// Calls visit(segment) for the segments of `segs` (a span returned by grid.segments(i, j))
/// in the chunks whose box passes keep(box); keep is asked again for every chunk, so it may
/// tighten as visit finds things.
template <class Keep, class Visit>
void visit_chunks(const CoastGrid& grid, std::span<const Segment> segs, Keep&& keep, Visit&& visit) {
    for_each_chunk(grid, segs, [&](const geo::Box& box, const Segment* begin, const Segment* end) {
        if (keep(box))
            for (const Segment* s = begin; s != end; ++s) visit(*s);
    });
}

/// The segments of one chunk that lie in one cell, and a lower bound of the squared distance
/// from what is sought to any of them (the distance to the chunk's box).
struct ChunkRun {
    double d2;
    const Segment* begin;
    const Segment* end;
};

/// Appends to `runs` the chunks of `segs` (a span returned by grid.segments(i, j)) whose box
/// lies nearer than `limit2`: dist2(box) is the squared distance to what is sought, a lower
/// bound of every segment's in the chunk. With visit_nearest_first, a search reads the chunk
/// nearest first and its bound shrinks before the far ones are looked at.
template <class Dist2>
void gather_chunks(const CoastGrid& grid, std::span<const Segment> segs, Dist2&& dist2, double limit2,
                   std::vector<ChunkRun>& runs) {
    for_each_chunk(grid, segs, [&](const geo::Box& box, const Segment* begin, const Segment* end) {
        // Shrunk by a hair: a segment measured in another frame, rounded a little nearer than
        // its box, is still read.
        const double d2 = dist2(box) * (1 - 1e-9);
        if (d2 < limit2) runs.push_back({d2, begin, end});
    });
}

/// Calls visit(segment) for the segments of `runs`, nearest run first, while the run's bound
/// is under bound() (asked again before every run, so it may tighten as visit finds things)
/// and stop() is false; clears `runs`.
template <class Bound, class Stop, class Visit>
void visit_nearest_first(std::vector<ChunkRun>& runs, Bound&& bound, Stop&& stop, Visit&& visit) {
    // Stable, so that runs at the same bound (all those meeting the hull's box) keep the
    // order of storage; insertion for the few runs of a usual cell.
    auto nearer = [](const ChunkRun& a, const ChunkRun& b) { return a.d2 < b.d2; };
    if (runs.size() > 32) {
        std::stable_sort(runs.begin(), runs.end(), nearer);
    } else {
        for (std::size_t i = 1; i < runs.size(); ++i) {
            const ChunkRun r = runs[i];
            std::size_t j = i;
            for (; j > 0 && nearer(r, runs[j - 1]); --j) runs[j] = runs[j - 1];
            runs[j] = r;
        }
    }
    for (const ChunkRun& r : runs) {
        if (stop() || !(r.d2 < bound())) break;
        for (const Segment* s = r.begin; s != r.end && !stop(); ++s) visit(*s);
    }
    runs.clear();
}

/// Squared distance from p to box b (0 inside).
inline double box_point_dist2(const geo::Box& b, geo::XY p) noexcept {
    const double dx = std::max({b.minx - p.x, 0.0, p.x - b.maxx});
    const double dy = std::max({b.miny - p.y, 0.0, p.y - b.maxy});
    return dx * dx + dy * dy;
}

/// Whether the block of cells under `from` is read first (`read`), or was read already by
/// the caller (`skip`; then `from` must lie in the grid, so that block is the cells under it).
enum class FirstBlock { read, skip };

/// Reads the coast cells of `grid` outward from the box `from`: visit(segs) for each coast
/// cell's segments, first the block of cells under `from` (clamped into the grid: a box
/// outside starts at the nearest cells), then ring after ring around it. `visit` provides
///   bool wants(double gap) const: go on, `gap` being the distance from `from` to the nearest
///     cell not read yet (the search ends too when no cell is left);
///   double reach() const: how far from `from` a cell of the next ring may still matter
///     (INFINITY: all of it); a ring's rows and columns are cut to the cells within it;
///   optionally void ring_done(): called after the first block and after each ring, before
///     wants() and reach() are asked again (a visitor that gathers a ring's chunks reads
///     them there, nearest first over the whole ring).
/// Rings are read top row, bottom row, then the left and the right column.
template <class Visitor>
void visit_outward(const CoastGrid& grid, const geo::Box& from, Visitor& visit, FirstBlock first = FirstBlock::read) {
    if (grid.segment_count() == 0) return;
    const int nx = grid.nx(), ny = grid.ny();
    const double cell = grid.cell_size();
    const geo::Box& lb = from;
    int i0 = std::clamp(grid.col_of(lb.minx), 0, nx - 1), i1 = std::clamp(grid.col_of(lb.maxx), 0, nx - 1);
    int j0 = std::clamp(grid.row_of(lb.miny), 0, ny - 1), j1 = std::clamp(grid.row_of(lb.maxy), 0, ny - 1);
    auto read_cell = [&](int i, int j) {
        const std::span<const Segment> segs = grid.segments(i, j);
        if (!segs.empty()) visit(segs);
    };
    auto ring_done = [&] {
        if constexpr (requires { visit.ring_done(); }) visit.ring_done();
    };
    if (first == FirstBlock::read) {
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) read_cell(i, j);
        ring_done();
    }
    const geo::XY org = grid.origin();
    for (;;) {
        // Distance from the box to the nearest point outside the block read so far.
        const double gap = std::min({i0 > 0 ? lb.minx - (org.x + i0 * cell) : INFINITY,
                                     i1 < nx - 1 ? (org.x + (i1 + 1) * cell) - lb.maxx : INFINITY,
                                     j0 > 0 ? lb.miny - (org.y + j0 * cell) : INFINITY,
                                     j1 < ny - 1 ? (org.y + (j1 + 1) * cell) - lb.maxy : INFINITY});
        if (!std::isfinite(gap) || !visit.wants(gap)) break;
        const int ni0 = std::max(0, i0 - 1), ni1 = std::min(nx - 1, i1 + 1);
        const int nj0 = std::max(0, j0 - 1), nj1 = std::min(ny - 1, j1 + 1);
        // The new ring, its rows and columns cut to the cells within reach of the box (the
        // cells' boxes grown by more than the clipping slack): a cell farther away cannot hold
        // a segment the visitor still wants.
        const double reach = visit.reach() + 2e-6;
        const double span = (nx + ny + 2) * cell;  // farther than any cell
        // The cells [a, b] of a row (or column, `vertical`) of the ring spanning [lo, hi] across.
        auto cut = [&](double lo, double hi, int i_lo, int i_hi, bool vertical, int& a, int& b) {
            const double gap_across = vertical ? std::max({0.0, lo - lb.maxx, lb.minx - hi}) : std::max({0.0, lo - lb.maxy, lb.miny - hi});
            if (gap_across > reach) return false;
            const double along = std::min(span, std::sqrt(std::max(0.0, reach * reach - gap_across * gap_across)));
            a = std::max(i_lo, vertical ? grid.row_of(lb.miny - along) : grid.col_of(lb.minx - along));
            b = std::min(i_hi, vertical ? grid.row_of(lb.maxy + along) : grid.col_of(lb.maxx + along));
            return a <= b;
        };
        int a, b;
        if (nj0 < j0 && cut(org.y + nj0 * cell, org.y + (nj0 + 1) * cell, ni0, ni1, false, a, b))
            for (int i = a; i <= b; ++i) read_cell(i, nj0);
        if (nj1 > j1 && cut(org.y + nj1 * cell, org.y + (nj1 + 1) * cell, ni0, ni1, false, a, b))
            for (int i = a; i <= b; ++i) read_cell(i, nj1);
        if (ni0 < i0 && cut(org.x + ni0 * cell, org.x + (ni0 + 1) * cell, j0, j1, true, a, b))
            for (int j = a; j <= b; ++j) read_cell(ni0, j);
        if (ni1 > i1 && cut(org.x + ni1 * cell, org.x + (ni1 + 1) * cell, j0, j1, true, a, b))
            for (int j = a; j <= b; ++j) read_cell(ni1, j);
        ring_done();
        i0 = ni0, i1 = ni1, j0 = nj0, j1 = nj1;
    }
}

/// The box of no size at p.
inline geo::Box point_box(geo::XY p) noexcept { return {p.x, p.y, p.x, p.y}; }

}  // namespace shoal::grid
