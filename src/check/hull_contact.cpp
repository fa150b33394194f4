// Hull-to-hull contact (see include/shoal/check/hull_contact.hpp): the exact all-edges
// answer and the pruned search over chunk and edge capsules (src/check/hull_shape.hpp).
#include <shoal/check/hull_contact.hpp>

#include <algorithm>

#include "check/hull_shape.hpp"
#include <shoal/util/error.hpp>

namespace shoal::check {

using geo::XY;
namespace detail {

namespace {
/// Edges per chunk of a hull outline; each chunk has a bounding capsule in the ship frame.
constexpr std::size_t chunk_edges = 6;
}  // namespace

HullShape prepare(const std::vector<XY>& contour) {
    HullShape s;
    s.contour = contour;
    const std::size_t n = contour.size();
    for (const XY& c : contour) s.radius = std::max(s.radius, std::hypot(c.x, c.y));
    for (std::size_t first = 0; first < n; first += chunk_edges) {
        Chunk ch;
        ch.first = static_cast<std::uint32_t>(first);
        ch.end = static_cast<std::uint32_t>(std::min(n, first + chunk_edges));
        const XY p = contour[first], q = contour[ch.end % n];
        ch.capsule.mid = 0.5 * (p + q);
        ch.capsule.hv = 0.5 * (q - p);
        for (std::size_t k = first; k <= ch.end; ++k)
            ch.capsule.r = std::max(ch.capsule.r, std::sqrt(geo::point_segment_dist2(contour[k % n], p, q)));
        s.chunks.push_back(ch);
    }
    return s;
}

void place_chunks(const HullShape& shape, const LocalPose& pose, Placed& out) {
    const Eigen::Matrix2d& m = pose.ship_to_local;
    out.position = pose.position;
    out.m00 = m(0, 0);
    out.m01 = m(0, 1);
    out.m10 = m(1, 0);
    out.m11 = m(1, 1);
    out.sigma = spectral_norm(out.m00, out.m01, out.m10, out.m11);
    out.chunks.resize(shape.chunks.size());
    for (std::size_t k = 0; k < shape.chunks.size(); ++k) {
        const Capsule& c = shape.chunks[k].capsule;
        out.chunks[k] = {out.map(c.mid), out.map_vector(c.hv), out.sigma * c.r + bound_slack_m};
    }
}

void place_outline(const HullShape& shape, Placed& out) {
    const std::size_t n = shape.contour.size();
    out.pts.resize(n + 1);
    for (std::size_t k = 0; k < n; ++k) out.pts[k] = out.map(shape.contour[k]);
    out.pts[n] = out.pts[0];
    out.edges.resize(n);
    for (std::size_t k = 0; k < n; ++k) out.edges[k] = {0.5 * (out.pts[k] + out.pts[k + 1]), 0.5 * (out.pts[k + 1] - out.pts[k]), bound_slack_m};
}

void place(const HullShape& shape, const LocalPose& pose, Placed& out) {
    place_chunks(shape, pose, out);
    place_outline(shape, out);
}

namespace {

/// Crossing-number test; `ring` closed. Points on the boundary are not asked about (the
/// boundaries are known to be apart when this is called).
bool inside(XY p, const std::vector<XY>& ring) {
    bool in = false;
    for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
        const XY a = ring[k], b = ring[k + 1];
        if ((a.y > p.y) != (b.y > p.y)) {
            const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (p.x < x) in = !in;
        }
    }
    return in;
}

/// The nearest edge pair found so far; ties go to the first pair in (edge of a, edge of b)
/// order, so that any search order gives the same points.
struct Nearest {
    double d2 = INFINITY;
    std::uint32_t i = UINT32_MAX, j = UINT32_MAX;
    XY on_a, on_b;

    /// Tests edge pair (ei, ej); true when it is the new nearest.
    bool test(const std::vector<XY>& a, std::uint32_t ei, const std::vector<XY>& b, std::uint32_t ej) {
        XY pa, pb;
        const double d = geo::segment_segment_dist2(a[ei], a[ei + 1], b[ej], b[ej + 1], &pa, &pb);
        if (!(d < d2 || (d == d2 && (ei < i || (ei == i && ej < j))))) return false;
        d2 = d;
        i = ei;
        j = ej;
        on_a = pa;
        on_b = pb;
        return true;
    }
};

/// Contact from the nearest edge pair; `maybe_nested`: one outline may hold the other.
HullContact finish(const Nearest& n, const std::vector<XY>& a, const std::vector<XY>& b, bool maybe_nested) {
    HullContact c;
    if (n.d2 == 0) {
        c.collision = true;
        c.clearance_m = 0;
        c.on_a = c.on_b = n.on_a;
        return c;
    }
    if (maybe_nested) {
        for (const auto& [p, ring] : {std::pair{a[0], &b}, std::pair{b[0], &a}})
            if (inside(p, *ring)) {
                c.collision = true;
                c.clearance_m = 0;
                c.on_a = c.on_b = p;
                return c;
            }
    }
    c.clearance_m = std::sqrt(n.d2);
    c.on_a = n.on_a;
    c.on_b = n.on_b;
    return c;
}

}  // namespace

HullContact contact_all(const std::vector<XY>& a, const std::vector<XY>& b) {
    Nearest n;
    const auto na = static_cast<std::uint32_t>(a.size() - 1), nb = static_cast<std::uint32_t>(b.size() - 1);
    for (std::uint32_t i = 0; i < na; ++i)
        for (std::uint32_t j = 0; j < nb; ++j) n.test(a, i, b, j);
    return finish(n, a, b, true);
}

namespace {

/// Can one outline hold the other? Not when the circles around the reference points holding the hulls are apart.
bool may_nest(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b) {
    const double reach = a.sigma * sa.radius + b.sigma * sb.radius + bound_slack_m;
    return geo::norm2(b.position - a.position) <= reach * reach;
}

}  // namespace

bool chunks_apart(const Placed& a, const Placed& b, double margin_m, double best_m) {
    for (const Capsule& ca : a.chunks)
        for (const Capsule& cb : b.chunks)
            if (!apart(ca, cb, margin_m) || !apart(ca, cb, best_m, true)) return false;
    return true;
}

bool contact_pruned(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b, double margin_m,
                    double best_m, HullContact& out, EdgePair* hint) {
    if (chunks_apart(a, b, margin_m, best_m)) return false;
    const std::size_t na = sa.chunks.size(), nb = sb.chunks.size();

    Nearest n;
    double best_d = INFINITY;  // sqrt(n.d2)
    auto test = [&](std::uint32_t i, std::uint32_t j) {
        if (n.test(a.pts, i, b.pts, j)) best_d = std::sqrt(n.d2);
    };
    if (hint && hint->i < a.edges.size() && hint->j < b.edges.size()) test(hint->i, hint->j);
    for (std::size_t ci = 0; ci < na; ++ci)
        for (std::size_t cj = 0; cj < nb; ++cj) {
            if (apart(a.chunks[ci], b.chunks[cj], best_d)) continue;
            const Chunk& ca = sa.chunks[ci];
            const Chunk& cb = sb.chunks[cj];
            for (std::uint32_t i = ca.first; i < ca.end; ++i) {
                if (apart(a.edges[i], b.chunks[cj], best_d)) continue;
                for (std::uint32_t j = cb.first; j < cb.end; ++j)
                    if (!apart(a.edges[i], b.edges[j], best_d)) test(i, j);
            }
        }
    out = finish(n, a.pts, b.pts, may_nest(sa, a, sb, b));
    if (hint) *hint = {n.i, n.j};
    return true;
}

bool touching_pruned(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b, EdgePair* hint) {
    auto touch = [&](std::uint32_t i, std::uint32_t j) {
        return geo::segment_segment_dist2(a.pts[i], a.pts[i + 1], b.pts[j], b.pts[j + 1], nullptr, nullptr) == 0;
    };
    if (hint && hint->i < a.edges.size() && hint->j < b.edges.size() && touch(hint->i, hint->j)) return true;
    for (std::size_t ci = 0; ci < sa.chunks.size(); ++ci)
        for (std::size_t cj = 0; cj < sb.chunks.size(); ++cj) {
            if (apart(a.chunks[ci], b.chunks[cj], 0)) continue;
            for (std::uint32_t i = sa.chunks[ci].first; i < sa.chunks[ci].end; ++i) {
                if (apart(a.edges[i], b.chunks[cj], 0)) continue;
                for (std::uint32_t j = sb.chunks[cj].first; j < sb.chunks[cj].end; ++j)
                    if (!apart(a.edges[i], b.edges[j], 0) && touch(i, j)) {
                        if (hint) *hint = {i, j};
                        return true;
                    }
            }
        }
    return may_nest(sa, a, sb, b) && (inside(a.pts[0], b.pts) || inside(b.pts[0], a.pts));
}

}  // namespace detail

HullContact hull_contact(const std::vector<XY>& a, const std::vector<XY>& b) {
    auto closed = [](std::vector<XY> r) {
        if (r.size() > 1 && r.front() == r.back()) r.pop_back();
        if (r.empty()) throw UsageError("hull_contact: empty outline");
        r.push_back(r.front());
        return r;
    };
    return detail::contact_all(closed(a), closed(b));
}

HullContact hull_contact(const hull::Hull& a, const LocalPose& pose_a, const hull::Hull& b, const LocalPose& pose_b) {
    using namespace detail;
    const HullShape sa = prepare(a.contour()), sb = prepare(b.contour());
    Placed pa, pb;
    place(sa, pose_a, pa);
    place(sb, pose_b, pb);
    HullContact c;
    contact_pruned(sa, pa, sb, pb, INFINITY, INFINITY, c);
    return c;
}

}  // namespace shoal::check
