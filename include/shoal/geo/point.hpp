#pragma once
/// 2-D points and the exact-as-doubles-allow primitives the grid and the detector use:
/// side test, point-segment distance, segment intersection and segment-segment distance.
/// `LonLat` is WGS84 degrees; `XY` is metres in a `LocalFrame`. They are separate types so
/// that geographic and projected coordinates cannot be mixed by accident.

#include <algorithm>
#include <cmath>

namespace shoal::geo {

/// WGS84 longitude and latitude in degrees.
struct LonLat {
    double lon = 0.0;
    double lat = 0.0;
    friend bool operator==(const LonLat&, const LonLat&) = default;
};

/// Local projected coordinates in metres (x east-ish, y north-ish: grid axes of the frame).
struct XY {
    double x = 0.0;
    double y = 0.0;
    friend bool operator==(const XY&, const XY&) = default;
    friend XY operator+(XY a, XY b) noexcept { return {a.x + b.x, a.y + b.y}; }
    friend XY operator-(XY a, XY b) noexcept { return {a.x - b.x, a.y - b.y}; }
    friend XY operator*(double k, XY a) noexcept { return {k * a.x, k * a.y}; }
};

inline double dot(XY a, XY b) noexcept { return a.x * b.x + a.y * b.y; }
inline double cross(XY a, XY b) noexcept { return a.x * b.y - a.y * b.x; }
inline double norm2(XY a) noexcept { return dot(a, a); }
inline double distance(XY a, XY b) noexcept { return std::hypot(a.x - b.x, a.y - b.y); }

/// Twice the signed area of triangle (a, b, p): > 0 when p is left of a->b (counter-clockwise),
/// < 0 when right, 0 when collinear. The paper's S(A,B,P) is half of this.
inline double orient(XY a, XY b, XY p) noexcept {
    return (a.x - p.x) * (b.y - p.y) - (a.y - p.y) * (b.x - p.x);
}

/// Squared distance from p to segment ab, and the parameter of the closest point in [0,1].
inline double point_segment_dist2(XY p, XY a, XY b, double* t_out = nullptr) noexcept {
    const XY ab = b - a;
    const double len2 = norm2(ab);
    double t = len2 > 0.0 ? dot(p - a, ab) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    if (t_out) *t_out = t;
    const XY foot = a + t * ab;
    return norm2(p - foot);
}

/// True when closed segments ab and cd share at least one point (touching counts).
inline bool segments_intersect(XY a, XY b, XY c, XY d) noexcept {
    const double d1 = orient(c, d, a);
    const double d2 = orient(c, d, b);
    const double d3 = orient(a, b, c);
    const double d4 = orient(a, b, d);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return true;
    auto on_segment = [](XY p, XY q, XY r) {  // r collinear with pq: is it within pq's box?
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
               r.y <= std::max(p.y, q.y);
    };
    if (d1 == 0 && on_segment(c, d, a)) return true;
    if (d2 == 0 && on_segment(c, d, b)) return true;
    if (d3 == 0 && on_segment(a, b, c)) return true;
    if (d4 == 0 && on_segment(a, b, d)) return true;
    return false;
}

/// Closest points between segments ab and cd. Returns the squared distance (0 when they
/// intersect, with both points at a shared point) and writes the closest point on each.
inline double segment_segment_dist2(XY a, XY b, XY c, XY d, XY* on_ab, XY* on_cd) noexcept {
    if (segments_intersect(a, b, c, d)) {
        // A shared point: the intersection of the lines, or an endpoint for collinear overlap.
        const XY r = b - a, s = d - c;
        const double den = cross(r, s);
        XY p;
        if (den != 0.0) {
            const double t = std::clamp(cross(c - a, s) / den, 0.0, 1.0);
            p = a + t * r;
        } else {
            double t;
            point_segment_dist2(a, c, d, &t);
            p = point_segment_dist2(a, c, d) == 0.0 ? a : (c + t * s);
            if (point_segment_dist2(c, a, b) == 0.0) p = c;
        }
        if (on_ab) *on_ab = p;
        if (on_cd) *on_cd = p;
        return 0.0;
    }
    double best;
    double t;
    XY pa, pc;
    // a to cd
    best = point_segment_dist2(a, c, d, &t);
    pa = a;
    pc = c + t * (d - c);
    // b to cd
    double dd = point_segment_dist2(b, c, d, &t);
    if (dd < best) { best = dd; pa = b; pc = c + t * (d - c); }
    // c to ab
    dd = point_segment_dist2(c, a, b, &t);
    if (dd < best) { best = dd; pa = a + t * (b - a); pc = c; }
    // d to ab
    dd = point_segment_dist2(d, a, b, &t);
    if (dd < best) { best = dd; pa = a + t * (b - a); pc = d; }
    if (on_ab) *on_ab = pa;
    if (on_cd) *on_cd = pc;
    return best;
}

/// Axis-aligned box in local metres; empty when min > max.
struct Box {
    double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
    void extend(XY p) noexcept {
        minx = std::min(minx, p.x); miny = std::min(miny, p.y);
        maxx = std::max(maxx, p.x); maxy = std::max(maxy, p.y);
    }
    void extend(const Box& b) noexcept {
        minx = std::min(minx, b.minx); miny = std::min(miny, b.miny);
        maxx = std::max(maxx, b.maxx); maxy = std::max(maxy, b.maxy);
    }
    bool empty() const noexcept { return minx > maxx || miny > maxy; }
    Box grown(double m) const noexcept { return {minx - m, miny - m, maxx + m, maxy + m}; }
    /// Euclidean distance between two boxes (0 when they overlap or touch).
    double distance_to(const Box& b) const noexcept {
        const double dx = std::max({0.0, b.minx - maxx, minx - b.maxx});
        const double dy = std::max({0.0, b.miny - maxy, miny - b.maxy});
        return std::hypot(dx, dy);
    }
};

}  // namespace shoal::geo
