#include <shoal/audit/encounters.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>

#include <shoal/audit/motion.hpp>
#include <shoal/util/error.hpp>

namespace shoal::audit {

using geo::XY;

const char* to_string(EncounterKind k) noexcept { return k == EncounterKind::collision ? "collision" : "close_quarters"; }

namespace {

constexpr double deg = std::numbers::pi / 180.0;
/// Edges per chunk of a hull outline; each chunk has a bounding capsule in the ship frame.
constexpr std::size_t chunk_edges = 6;
/// Slack (metres) subtracted from every lower bound so that rounding in the placed points
/// cannot make a bound exceed a distance computed from them.
constexpr double bound_slack_m = 1e-4;
/// Verlet skin of the broad phase as a fraction of the largest threshold (and at least two
/// steps): candidates are pairs within threshold + skin at the last build, rebuilt when some
/// ship has moved half a skin.
constexpr double skin_fraction = 0.5;

// ---------------------------------------------------------------------------------------
// Hull geometry

/// A segment grown by a radius: every point within `r` of the segment mid +- hv.
struct Capsule {
    XY mid;  ///< midpoint of the axis
    XY hv;   ///< half the axis: the axis runs from mid - hv to mid + hv
    double r = 0;
};

/// Lower bound of the distance between anything in two capsules, by the separating axis
/// through their midpoints: |D| - |hv_a . u| - |hv_b . u| - r_a - r_b with u = D / |D|.
/// True when that bound exceeds `d` (strictly; `or_equal`: or equals it). No square root:
/// q = |D|^2 - |hv_a . D| - |hv_b . D| is compared with (d + r_a + r_b) |D|, both squared.
inline bool apart(const Capsule& a, const Capsule& b, double d, bool or_equal = false) noexcept {
    const XY D = b.mid - a.mid;
    const double L2 = geo::norm2(D);
    const double q = L2 - std::fabs(geo::dot(a.hv, D)) - std::fabs(geo::dot(b.hv, D));
    if (!(q > 0)) return false;
    const double R = d + a.r + b.r;
    return or_equal ? q * q >= R * R * L2 : q * q > R * R * L2;
}

/// A run of consecutive edges [first, end) of an outline and the capsule holding it, in the
/// ship frame: the chord from its first to its last point, grown by the farthest point's
/// distance (small on a straight side, so facing sides of two ships are told apart early).
struct Chunk {
    std::uint32_t first = 0, end = 0;
    Capsule capsule;
};

/// A hull outline prepared for contact checks.
struct HullShape {
    std::vector<XY> contour;  ///< ship frame, open ring
    double radius = 0;        ///< max distance of a contour point from the reference point
    std::vector<Chunk> chunks;
};

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

/// A hull placed at a pose, in local metres.
struct Placed {
    XY position;
    double m00 = 1, m01 = 0, m10 = 0, m11 = 1;  ///< ship -> local map
    double sigma = 1;                           ///< its largest stretch (spectral norm)
    std::vector<XY> pts;                        ///< the outline, first point repeated at the end
    std::vector<Capsule> edges;                 ///< per edge: the edge itself, grown by the slack
    std::vector<Capsule> chunks;                ///< per chunk: its capsule mapped, radius times sigma plus the slack

    XY map(XY c) const noexcept { return {position.x + m00 * c.x + m01 * c.y, position.y + m10 * c.x + m11 * c.y}; }
    XY map_vector(XY v) const noexcept { return {m00 * v.x + m01 * v.y, m10 * v.x + m11 * v.y}; }
};

/// Largest singular value of a 2x2 matrix.
double spectral_norm(double a, double b, double c, double d) {
    const double s = a * a + b * b + c * c + d * d;
    const double det = a * d - b * c;
    return std::sqrt((s + std::sqrt(std::max(0.0, s * s - 4 * det * det))) / 2);
}

/// The pose and the chunk capsules: enough for chunks_apart.
void place_chunks(const HullShape& shape, const check::LocalPose& pose, Placed& out) {
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

/// The outline and its edges, after place_chunks.
void place_outline(const HullShape& shape, Placed& out) {
    const std::size_t n = shape.contour.size();
    out.pts.resize(n + 1);
    for (std::size_t k = 0; k < n; ++k) out.pts[k] = out.map(shape.contour[k]);
    out.pts[n] = out.pts[0];
    out.edges.resize(n);
    for (std::size_t k = 0; k < n; ++k) out.edges[k] = {0.5 * (out.pts[k] + out.pts[k + 1]), 0.5 * (out.pts[k + 1] - out.pts[k]), bound_slack_m};
}

void place(const HullShape& shape, const check::LocalPose& pose, Placed& out) {
    place_chunks(shape, pose, out);
    place_outline(shape, out);
}

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

/// Every edge pair: the reference.
HullContact contact_all(const std::vector<XY>& a, const std::vector<XY>& b) {
    Nearest n;
    const auto na = static_cast<std::uint32_t>(a.size() - 1), nb = static_cast<std::uint32_t>(b.size() - 1);
    for (std::uint32_t i = 0; i < na; ++i)
        for (std::uint32_t j = 0; j < nb; ++j) n.test(a, i, b, j);
    return finish(n, a, b, true);
}

/// An edge pair (edge of a, edge of b); UINT32_MAX: none.
struct EdgePair {
    std::uint32_t i = UINT32_MAX, j = UINT32_MAX;
};

/// Can one outline hold the other? Not when the circles around the reference points holding the hulls are apart.
bool may_nest(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b) {
    const double reach = a.sigma * sa.radius + b.sigma * sb.radius + bound_slack_m;
    return geo::norm2(b.position - a.position) <= reach * reach;
}

/// The same answer as contact_all, testing only the edge pairs that capsule bounds (of chunks
/// of edges, of an edge against a chunk, of two edges) cannot prove farther apart than the
/// nearest pair found so far. `hint` (the nearest pair last time, updated) gives a good bound
/// at once. Returns false without an answer ("far": clearance > `margin_m` and >= `best_m`)
/// when the chunk bounds prove that; margin_m = INFINITY never gives up. Every bound has
/// `bound_slack_m` to spare and ties are never pruned, so the nearest pair (and of equals the
/// first) is always tested.
/// Do the chunk capsules prove the clearance > margin_m and >= best_m? (Needs place_chunks only.)
bool chunks_apart(const Placed& a, const Placed& b, double margin_m, double best_m) {
    for (const Capsule& ca : a.chunks)
        for (const Capsule& cb : b.chunks)
            if (!apart(ca, cb, margin_m) || !apart(ca, cb, best_m, true)) return false;
    return true;
}

bool contact_pruned(const HullShape& sa, const Placed& a, const HullShape& sb, const Placed& b, double margin_m,
                    double best_m, HullContact& out, EdgePair* hint = nullptr) {
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

/// contact_all(...).collision, sooner: stops at the first edge pair in contact and reads only
/// the pairs whose capsules touch.
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

// ---------------------------------------------------------------------------------------
// The exercise

struct Ship {
    const track::Track* track = nullptr;
    std::vector<LocalFix> local;
    std::optional<Motion> motion;
    const hull::Hull* hull = nullptr;
    HullShape shape;
    double sigma_max = 1;       ///< largest stretch of the frame over the track's fixes
    double reach = 0;           ///< sigma_max * hull radius + slack: a circle around the position holds the hull
    std::vector<double> speed;  ///< per fix interval: bound on any hull point's speed, m/s; < 0 across a gap
    /// Per fix: bound on how far any hull point has moved since the first fix (gaps count 0).
    /// Between two moments, the difference bounds the motion of every hull point.
    std::vector<double> odometer;

    // Running state.
    std::size_t next_fix = 0;   ///< next fix not yet reached
    std::size_t cur = 0;        ///< last fix at or before the current instant
    bool present = false, moving = false;
    std::uint64_t entered = 0;  ///< instant at which it last became present
    XY pos;                     ///< reference point at the current instant
    double f = 0;               ///< fraction of fix interval `cur` at the current instant
    /// The odometer at the current instant.
    double odometer_now() const {
        return f == 0 ? odometer[cur] : odometer[cur] + f * (odometer[cur + 1] - odometer[cur]);
    }
    std::uint64_t posed_at = UINT64_MAX;     ///< instant of placed's pose and chunks
    std::uint64_t outlined_at = UINT64_MAX;  ///< instant of placed's outline
    Placed placed;
    XY built_pos;               ///< reference point at the last broad-phase build
    std::size_t slot = 0;       ///< index in the active list

    /// Fix interval and fraction at time t (within the track's span).
    std::pair<std::size_t, double> locate(double t) const {
        const auto& fx = track->fixes;
        auto it = std::upper_bound(fx.begin(), fx.end(), t, [](double v, const track::Fix& x) { return v < x.time_s; });
        const std::size_t i = it == fx.begin() ? 0 : static_cast<std::size_t>(it - fx.begin()) - 1;
        return {i, fraction(i, t)};
    }
    double fraction(std::size_t i, double t) const {
        const auto& fx = track->fixes;
        if (i + 1 >= fx.size() || t == fx[i].time_s) return 0;
        return (t - fx[i].time_s) / (fx[i + 1].time_s - fx[i].time_s);
    }
};

/// What one check of a pair found.
struct Sample {
    double t = 0;
    bool far = false;  ///< proved clearance > margin (and no better than the closest approach so far) without computing it
    HullContact contact;
    XY pos_a, pos_b;
    bool touching() const noexcept { return !far && contact.collision; }
};

struct PairState {
    std::uint32_t a = 0, b = 0;
    std::uint64_t last_instant = 0;
    bool checked = false, listed = false;
    bool prev_contact = false;
    bool in_collision = false, in_near = false, near_contact = false;
    double prev_t = 0;
    std::size_t collision_event = 0;  ///< index in the result's events while in_collision
    double near_start = 0, near_end = 0, near_min = INFINITY, near_t = 0;
    XY near_on_a, near_on_b;
    double best = INFINITY, best_t = 0;  ///< closest approach so far
    XY best_pos_a, best_pos_b;
    EdgePair hint;  ///< the nearest (or touching) edge pair at the last exact check
    /// Clearance at the last exact check, the pair checked at every instant since, and both
    /// ships' odometers then: the clearance can have shrunk by at most what they moved since.
    bool clear_known = false;
    double last_clear = 0;
    double odometer_a = 0, odometer_b = 0;
    bool open() const noexcept { return in_collision || in_near; }
};

struct Candidate {
    std::uint32_t a = 0, b = 0, state = 0;
    double threshold2 = 0;
};

class Exercise {
public:
    Exercise(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
             const geo::LocalFrame& frame, const EncounterOptions& options, bool brute)
        : m_frame(frame), m_opt(options), m_brute(brute), m_ships(tracks.size()) {
        validate(tracks, hulls);
        double max_radius = 0;
        for (std::size_t k = 0; k < tracks.size(); ++k) {
            Ship& s = m_ships[k];
            s.track = tracks[k];
            s.hull = &hulls[k];
            s.shape = prepare(hulls[k].contour());
            max_radius = std::max(max_radius, s.shape.radius);
            s.local = project_fixes(*tracks[k], frame);
            s.motion.emplace(*tracks[k], s.local);
            for (const LocalFix& lf : s.local) {
                const Eigen::Matrix2d& j = lf.jacobian;
                s.sigma_max = std::max(s.sigma_max, spectral_norm(j(0, 0), j(0, 1), j(1, 0), j(1, 1)));
            }
            s.sigma_max *= 1 + 1e-9;
            s.reach = s.sigma_max * s.shape.radius + bound_slack_m;
            const auto& fx = tracks[k]->fixes;
            s.odometer.assign(1, 0.0);
            for (std::size_t i = 0; i + 1 < fx.size(); ++i) {
                const double dt = fx[i + 1].time_s - fx[i].time_s;
                if (dt > m_opt.max_gap_s) {
                    s.speed.push_back(-1);
                    s.odometer.push_back(s.odometer.back());
                    continue;
                }
                const double rot = std::fabs(turn(fx[i].heading_used_deg, fx[i + 1].heading_used_deg)) * deg;
                // Any hull point: the reference point's move, the turn, and the change of the
                // frame's local map (scale and convergence) over the hull's radius.
                const Eigen::Matrix2d dj = s.local[i + 1].jacobian - s.local[i].jacobian;
                const double moved = geo::distance(s.local[i].position, s.local[i + 1].position) + s.sigma_max * s.shape.radius * rot +
                                     spectral_norm(dj(0, 0), dj(0, 1), dj(1, 0), dj(1, 1)) * s.shape.radius;
                s.speed.push_back(moved / dt);
                s.odometer.push_back(s.odometer.back() + moved);
            }
        }
        m_auto_threshold = !(m_opt.threshold_m > 0);
        m_result.threshold_m = m_auto_threshold ? m_opt.ship_margin_m + m_opt.step_m + 2 * max_radius : m_opt.threshold_m;
        m_skin = std::max(2 * m_opt.step_m, skin_fraction * m_result.threshold_m);
    }

    EncounterResult run() {
        // Every fix of every ship, in time order.
        std::vector<std::pair<double, std::uint32_t>> fixes;
        for (std::uint32_t k = 0; k < m_ships.size(); ++k)
            for (const track::Fix& f : m_ships[k].track->fixes) fixes.push_back({f.time_s, k});
        std::sort(fixes.begin(), fixes.end());
        std::multiset<double> speeds;  // of the moving ships
        for (std::size_t e = 0; e < fixes.size();) {
            const double t = fixes[e].first;
            std::size_t end = e;
            while (end < fixes.size() && fixes[end].first == t) ++end;
            for (std::size_t k = e; k < end; ++k) {
                Ship& s = m_ships[fixes[k].second];
                if (s.moving) speeds.erase(speeds.find(s.speed[s.cur]));
                s.cur = s.next_fix++;
                if (!s.present) {
                    s.present = true;
                    s.entered = m_instant;
                    s.slot = m_active.size();
                    m_active.push_back(fixes[k].second);
                    m_need_build = true;
                }
            }
            instant(t);
            for (std::size_t k = e; k < end; ++k) {
                Ship& s = m_ships[fixes[k].second];
                s.moving = s.cur < s.speed.size() && s.speed[s.cur] >= 0;
                if (s.moving) {
                    speeds.insert(s.speed[s.cur]);
                } else {
                    s.present = false;
                    m_ships[m_active.back()].slot = s.slot;
                    m_active[s.slot] = m_active.back();
                    m_active.pop_back();
                }
            }
            e = end;
            if (e == fixes.size() || m_active.size() < 2) continue;
            // Instants between this fix time and the next: relative motion <= step between them.
            const double next = fixes[e].first, dt = next - t;
            const double v = *speeds.rbegin() + *std::next(speeds.rbegin());
            const double n = std::max(1.0, std::ceil(v * dt / m_opt.step_m));
            for (double j = 1; j < n; ++j) {
                const double ti = t + dt * j / n;
                if (ti > t && ti < next) instant(ti);
            }
        }
        close_open(true);
        return finish();
    }

private:
    void validate(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls) const {
        if (hulls.size() != tracks.size())
            throw UsageError("find_encounters: " + std::to_string(tracks.size()) + " tracks but " + std::to_string(hulls.size()) +
                             " hulls (one hull per track)");
        if (!(m_opt.step_m > 0) || !std::isfinite(m_opt.step_m)) throw UsageError("--step must be > 0 metres");
        if (!(m_opt.ship_margin_m >= 0) || !std::isfinite(m_opt.ship_margin_m)) throw UsageError("--ship-margin must be >= 0 metres");
        if (!(m_opt.threshold_m >= 0) || !std::isfinite(m_opt.threshold_m)) throw UsageError("the encounter threshold must be >= 0 metres (0 = automatic)");
        if (!(m_opt.max_gap_s > 0)) throw UsageError("--max-gap must be > 0 seconds");
        if (!(m_opt.time_tolerance_s > 0)) throw UsageError("the time tolerance must be > 0 seconds");
        for (const track::Track* t : tracks) {
            if (!t) throw UsageError("find_encounters: null track");
            for (std::size_t i = 0; i < t->fixes.size(); ++i) {
                const track::Fix& f = t->fixes[i];
                auto fail = [&](const char* what) {
                    throw InputError("track '" + t->id + "' in '" + t->file + "', fix at line " + std::to_string(f.line) + ": " + what);
                };
                if (!std::isfinite(f.time_s)) fail("no time");
                if (!std::isfinite(f.heading_used_deg)) fail("no heading (headings not resolved)");
                if (i > 0 && !(f.time_s > t->fixes[i - 1].time_s)) fail("fix times not strictly increasing");
            }
        }
    }

    double threshold2(std::uint32_t a, std::uint32_t b) const {
        const double t = m_auto_threshold ? m_opt.ship_margin_m + m_opt.step_m + m_ships[a].shape.radius + m_ships[b].shape.radius
                                          : m_opt.threshold_m;
        return t * t;
    }
    static double dist2(XY a, XY b) { return geo::norm2(b - a); }

    std::uint32_t state_of(std::uint32_t a, std::uint32_t b) {
        const std::uint64_t key = (std::uint64_t{a} << 32) | b;
        auto [it, fresh] = m_index.try_emplace(key, static_cast<std::uint32_t>(m_states.size()));
        if (fresh) {
            PairState& p = m_states.emplace_back();
            p.a = a;
            p.b = b;
        }
        return it->second;
    }

    /// Ship s's pose and chunk capsules at the current instant.
    const Placed& posed_now(Ship& s) {
        if (s.posed_at != m_instant) {
            place_chunks(s.shape, s.motion->pose(s.cur, s.f), s.placed);
            s.posed_at = m_instant;
        }
        return s.placed;
    }
    /// Ship s's hull at the current instant.
    const Placed& placed_now(Ship& s) {
        posed_now(s);
        if (s.outlined_at != m_instant) {
            place_outline(s.shape, s.placed);
            s.outlined_at = m_instant;
        }
        return s.placed;
    }

    /// The pair at an arbitrary moment (both ships present there), for bisection: whether
    /// the hulls touch, and where. The fast way may answer "far" (not touching) early.
    Sample sample_at(std::uint32_t a, std::uint32_t b, double t) {
        Ship& sa = m_ships[a];
        Ship& sb = m_ships[b];
        const auto [ia, fa] = sa.locate(t);
        const auto [ib, fb] = sb.locate(t);
        place(sa.shape, sa.motion->pose(ia, fa), m_scratch_a);
        place(sb.shape, sb.motion->pose(ib, fb), m_scratch_b);
        Sample s;
        s.t = t;
        s.pos_a = m_scratch_a.position;
        s.pos_b = m_scratch_b.position;
        if (m_brute)
            s.contact = contact_all(m_scratch_a.pts, m_scratch_b.pts);
        else
            s.far = !contact_pruned(sa.shape, m_scratch_a, sb.shape, m_scratch_b, 0, 0, s.contact);
        m_result.hull_checks += !s.far;
        return s;
    }

    /// Between a moment without contact and one with, the moment of change, to the tolerance;
    /// returns the sample on the contact side. Works either way in time.
    Sample bisect(std::uint32_t a, std::uint32_t b, double t_clear, Sample hit) {
        for (int it = 0; it < 60 && std::fabs(hit.t - t_clear) > m_opt.time_tolerance_s; ++it) {
            const double mid = (t_clear + hit.t) / 2;
            Sample m = sample_at(a, b, mid);
            if (m.touching())
                hit = m;
            else
                t_clear = mid;
        }
        return hit;
    }

    void instant(double t) {
        ++m_result.instants;
        double moved2 = 0;
        for (const std::uint32_t k : m_active) {
            Ship& s = m_ships[k];
            s.f = s.fraction(s.cur, t);
            s.pos = s.motion->position(s.cur, s.f);
            moved2 = std::max(moved2, dist2(s.pos, s.built_pos));
        }
        if (m_brute) {
            std::vector<std::uint32_t> order(m_active);
            std::sort(order.begin(), order.end());
            for (std::size_t x = 0; x < order.size(); ++x)
                for (std::size_t y = x + 1; y < order.size(); ++y) {
                    const std::uint32_t a = order[x], b = order[y];
                    if (dist2(m_ships[a].pos, m_ships[b].pos) <= threshold2(a, b)) check(state_of(a, b), t);
                }
        } else {
            if (m_need_build || moved2 > (m_skin / 2) * (m_skin / 2)) build();
            for (const Candidate& c : m_candidates) {
                const Ship& sa = m_ships[c.a];
                const Ship& sb = m_ships[c.b];
                if (!sa.present || !sb.present) continue;
                if (dist2(sa.pos, sb.pos) <= c.threshold2) check(c.state, t);
            }
        }
        close_open(false);
        ++m_instant;
    }

    /// Candidate pairs: within threshold + skin now, found with a uniform hash grid.
    void build() {
        ++m_result.rebuilds;
        m_need_build = false;
        m_candidates.clear();
        const double cell = m_result.threshold_m + m_skin;
        const std::size_t n = m_active.size();
        std::size_t buckets = 1;
        while (buckets < 2 * n) buckets *= 2;
        struct Entry {
            std::int64_t cx, cy;
            std::uint32_t ship;
        };
        auto bucket_of = [&](std::int64_t cx, std::int64_t cy) {
            const std::uint64_t h = static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(cy) * 0xC2B2AE3D27D4EB4Full;
            return static_cast<std::size_t>((h ^ (h >> 29)) & (buckets - 1));
        };
        std::vector<Entry> entries(n);
        std::vector<std::size_t> start(buckets + 1, 0);
        std::vector<std::size_t> bucket(n);
        for (std::size_t k = 0; k < n; ++k) {
            Ship& s = m_ships[m_active[k]];
            s.built_pos = s.pos;
            const Entry e{static_cast<std::int64_t>(std::floor(s.pos.x / cell)), static_cast<std::int64_t>(std::floor(s.pos.y / cell)), m_active[k]};
            bucket[k] = bucket_of(e.cx, e.cy);
            ++start[bucket[k] + 1];
            entries[k] = e;
        }
        for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
        std::vector<Entry> sorted(n);
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (std::size_t k = 0; k < n; ++k) sorted[fill[bucket[k]]++] = entries[k];
        for (const Entry& e : sorted) {
            const XY p = m_ships[e.ship].pos;
            for (std::int64_t dx = -1; dx <= 1; ++dx)
                for (std::int64_t dy = -1; dy <= 1; ++dy) {
                    const std::int64_t cx = e.cx + dx, cy = e.cy + dy;
                    const std::size_t b = bucket_of(cx, cy);
                    for (std::size_t q = start[b]; q < start[b + 1]; ++q) {
                        const Entry& o = sorted[q];
                        if (o.ship <= e.ship || o.cx != cx || o.cy != cy) continue;
                        const double t = std::sqrt(threshold2(e.ship, o.ship)) + m_skin;
                        if (dist2(p, m_ships[o.ship].pos) <= t * t)
                            m_candidates.push_back({e.ship, o.ship, 0, threshold2(e.ship, o.ship)});
                    }
                }
        }
        std::sort(m_candidates.begin(), m_candidates.end(),
                  [](const Candidate& x, const Candidate& y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
        for (Candidate& c : m_candidates) c.state = state_of(c.a, c.b);
    }

    /// One check of pair `index` at the current instant, time t: narrow phase and events.
    void check(std::uint32_t index, double t) {
        ++m_result.pairs_checked;
        PairState& p = m_states[index];
        Ship& sa = m_ships[p.a];
        Ship& sb = m_ships[p.b];
        const bool contiguous = p.checked && p.last_instant + 1 == m_instant && sa.entered < m_instant && sb.entered < m_instant;
        if (!contiguous && p.open()) close(p);
        if (!contiguous) p.clear_known = false;

        Sample s;
        s.t = t;
        s.pos_a = sa.pos;
        s.pos_b = sb.pos;
        const double margin = m_opt.ship_margin_m;
        if (m_brute) {
            s.contact = contact_all(placed_now(sa).pts, placed_now(sb).pts);
            ++m_result.hull_checks;
        } else {
            double lb = std::sqrt(dist2(sa.pos, sb.pos)) - sa.reach - sb.reach;
            if (p.clear_known) {
                const double moved = (sa.odometer_now() - p.odometer_a) + (sb.odometer_now() - p.odometer_b);
                lb = std::max(lb, p.last_clear - moved * (1 + 1e-9) - bound_slack_m);
            }
            s.far = lb > margin && lb >= p.best;
            // In a collision that goes on, only "still touching?" matters: the event has its
            // first contact and the closest approach is 0 already.
            const bool touch_only = p.in_collision && contiguous;
            if (!s.far && touch_only && touching_pruned(sa.shape, placed_now(sa), sb.shape, placed_now(sb), &p.hint)) {
                ++m_result.hull_checks;
                s.contact.collision = true;
                s.contact.clearance_m = 0;
            } else if (!s.far) {
                s.far = chunks_apart(posed_now(sa), posed_now(sb), margin, p.best);
                if (!s.far) {
                    contact_pruned(sa.shape, placed_now(sa), sb.shape, placed_now(sb), INFINITY, INFINITY, s.contact, &p.hint);
                    ++m_result.hull_checks;
                }
            }
        }
        if (!m_brute && !s.far) {
            p.clear_known = true;
            p.last_clear = s.contact.clearance_m;
            p.odometer_a = sa.odometer_now();
            p.odometer_b = sb.odometer_now();
        }
        const bool touching = s.touching();
        const bool near = touching || (!s.far && s.contact.clearance_m < margin);

        // Collisions: intervals of contact, first and last contact refined by bisection.
        if (touching && !p.in_collision) {
            const Sample first = contiguous && !p.prev_contact ? bisect(p.a, p.b, p.prev_t, s) : s;
            p.in_collision = true;
            p.collision_event = m_result.events.size();
            m_result.events.push_back(make_event(EncounterKind::collision, p, first.t, first.contact));
            m_result.events.back().end_s = t;
            offer(p, first);
        } else if (touching) {
            m_result.events[p.collision_event].end_s = t;
        } else if (p.in_collision) {
            Sample last_contact;  // the previous check (contiguous, or the pair would have been closed)
            last_contact.t = p.prev_t;
            m_result.events[p.collision_event].end_s = bisect(p.a, p.b, t, last_contact).t;
            p.in_collision = false;
        }
        // Close quarters: intervals under the margin that never reach contact.
        if (near) {
            if (!p.in_near) {
                p.in_near = true;
                p.near_contact = false;
                p.near_min = INFINITY;
                p.near_start = t;
            }
            p.near_end = t;
            if (touching) {
                p.near_contact = true;
            } else if (s.contact.clearance_m < p.near_min) {
                p.near_min = s.contact.clearance_m;
                p.near_t = t;
                p.near_on_a = s.contact.on_a;
                p.near_on_b = s.contact.on_b;
            }
        } else if (p.in_near) {
            finish_near(p);
        }
        if (!s.far && !touching) offer(p, s);

        p.prev_t = t;
        p.prev_contact = touching;
        p.last_instant = m_instant;
        p.checked = true;
        if (p.open() && !p.listed) {
            p.listed = true;
            m_open.push_back(index);
        }
    }

    void offer(PairState& p, const Sample& s) {
        if (!(s.contact.clearance_m < p.best)) return;
        p.best = s.contact.clearance_m;
        p.best_t = s.t;
        p.best_pos_a = s.pos_a;
        p.best_pos_b = s.pos_b;
    }

    /// Ends the open intervals of a pair that was not checked at the next instant: they end at its last check.
    void close(PairState& p) {
        p.in_collision = false;
        if (p.in_near) finish_near(p);
    }

    void finish_near(PairState& p) {
        p.in_near = false;
        if (p.near_contact) return;  // it reached contact: the collision tells it
        const XY mid = 0.5 * (p.near_on_a + p.near_on_b);
        HullContact c;
        c.clearance_m = p.near_min;
        c.on_a = c.on_b = mid;
        Encounter e = make_event(EncounterKind::close_quarters, p, p.near_t, c);
        e.start_s = p.near_start;
        e.end_s = p.near_end;
        e.min_clearance_m = p.near_min;
        m_result.events.push_back(std::move(e));
    }

    /// After an instant (or at the end): closes the intervals of pairs not checked at it.
    void close_open(bool all) {
        std::size_t kept = 0;
        for (const std::uint32_t index : m_open) {
            PairState& p = m_states[index];
            if (p.open() && (all || p.last_instant != m_instant)) close(p);
            if (p.open()) {
                m_open[kept++] = index;
            } else {
                p.listed = false;
            }
        }
        m_open.resize(kept);
    }

    ShipAt ship_at(std::uint32_t k, double t, XY* position) const {
        const Ship& s = m_ships[k];
        const auto [i, f] = s.locate(t);
        const check::LocalPose pose = s.motion->pose(i, f);
        ShipAt out;
        out.track = k;
        out.position = m_frame.inverse(pose.position);
        out.heading_deg = s.motion->heading(i, f);
        out.fix_index = i;
        for (const XY& q : check::hull_outline(*s.hull, pose)) out.hull.push_back(m_frame.inverse(q));
        if (!out.hull.empty()) out.hull.push_back(out.hull.front());
        *position = pose.position;
        return out;
    }

    Encounter make_event(EncounterKind kind, const PairState& p, double t, const HullContact& c) const {
        Encounter e;
        e.kind = kind;
        e.start_s = e.end_s = t;
        e.min_clearance_m = kind == EncounterKind::collision ? 0 : c.clearance_m;
        e.point = m_frame.inverse(c.on_a);
        XY pa, pb;
        e.a = ship_at(p.a, t, &pa);
        e.b = ship_at(p.b, t, &pb);
        e.distance_m = geo::distance(pa, pb);
        return e;
    }

    EncounterResult finish() {
        for (const PairState& p : m_states) {
            if (!p.checked || !std::isfinite(p.best)) continue;
            ClosestApproach c;
            c.a = p.a;
            c.b = p.b;
            c.time_s = p.best_t;
            c.clearance_m = p.best;
            c.distance_m = geo::distance(p.best_pos_a, p.best_pos_b);
            c.a_position = m_frame.inverse(p.best_pos_a);
            c.b_position = m_frame.inverse(p.best_pos_b);
            m_result.approaches.push_back(c);
        }
        std::sort(m_result.approaches.begin(), m_result.approaches.end(), [](const ClosestApproach& x, const ClosestApproach& y) {
            return x.a < y.a || (x.a == y.a && x.b < y.b);
        });
        std::sort(m_result.events.begin(), m_result.events.end(), [](const Encounter& x, const Encounter& y) {
            if (x.start_s != y.start_s) return x.start_s < y.start_s;
            if (x.a.track != y.a.track) return x.a.track < y.a.track;
            if (x.b.track != y.b.track) return x.b.track < y.b.track;
            return x.kind < y.kind;
        });
        return std::move(m_result);
    }

    const geo::LocalFrame& m_frame;
    EncounterOptions m_opt;
    bool m_brute = false;
    std::vector<Ship> m_ships;
    bool m_auto_threshold = true;
    double m_skin = 0;
    EncounterResult m_result;

    std::uint64_t m_instant = 0;
    std::vector<std::uint32_t> m_active;
    bool m_need_build = true;
    std::vector<Candidate> m_candidates;
    std::vector<PairState> m_states;
    std::unordered_map<std::uint64_t, std::uint32_t> m_index;
    std::vector<std::uint32_t> m_open;
    Placed m_scratch_a, m_scratch_b;
};

}  // namespace

namespace {

EncounterResult run_exercise(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                             const geo::LocalFrame& frame, const EncounterOptions& options, bool brute) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    Exercise exercise(tracks, hulls, frame, options, brute);
    const auto ready = Clock::now();
    EncounterResult r = exercise.run();
    r.setup_s = std::chrono::duration<double>(ready - start).count();
    r.sweep_s = std::chrono::duration<double>(Clock::now() - ready).count();
    return r;
}

}  // namespace

EncounterResult find_encounters(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                                const geo::LocalFrame& frame, const EncounterOptions& options) {
    return run_exercise(tracks, hulls, frame, options, false);
}

EncounterResult find_encounters_brute(const std::vector<const track::Track*>& tracks, const std::vector<hull::Hull>& hulls,
                                      const geo::LocalFrame& frame, const EncounterOptions& options) {
    return run_exercise(tracks, hulls, frame, options, true);
}

HullContact hull_contact(const std::vector<XY>& a, const std::vector<XY>& b) {
    auto closed = [](std::vector<XY> r) {
        if (r.size() > 1 && r.front() == r.back()) r.pop_back();
        if (r.empty()) throw UsageError("hull_contact: empty outline");
        r.push_back(r.front());
        return r;
    };
    return contact_all(closed(a), closed(b));
}

HullContact hull_contact(const hull::Hull& a, const check::LocalPose& pose_a, const hull::Hull& b, const check::LocalPose& pose_b) {
    const HullShape sa = prepare(a.contour()), sb = prepare(b.contour());
    Placed pa, pb;
    place(sa, pose_a, pa);
    place(sb, pose_b, pb);
    HullContact c;
    contact_pruned(sa, pa, sb, pb, INFINITY, INFINITY, c);
    return c;
}

}  // namespace shoal::audit
