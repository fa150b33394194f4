#include <shoal/sweep/evidence.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

#include "util/parse_util.hpp"
#include <shoal/util/error.hpp>

namespace shoal::audit {

using geo::XY;

const char* to_string(World w) noexcept { return w == World::real ? "real" : "simulated"; }

std::optional<World> parse_world(std::string_view text) noexcept {
    if (text == "simulated") return World::simulated;
    if (text == "real") return World::real;
    return std::nullopt;
}

const char* to_string(LearnedPlace::Kind k) noexcept { return k == LearnedPlace::Kind::water ? "chart_lacks_water" : "learned_berth"; }

namespace {

double dist(XY a, XY b) noexcept { return std::hypot(a.x - b.x, a.y - b.y); }

/// The box a stay's fixes lie in: a vessel lies still when every fix of a window lies in a box
/// whose diagonal is at most the stop diameter, or half the hull's length for a long hull (a
/// ship of 300 m turns on its moorings or its anchor by more than 50 m).
double stay_diameter(const SweepOptions& sweep, double hull_length_m) {
    return std::max(sweep.stop_diameter_m, std::isfinite(hull_length_m) ? hull_length_m / 2 : 0.0);
}

/// Stays: maximal runs of consecutive fixes (across gaps, not across a jump) within a box of
/// diagonal `diameter`, lasting at least `min_s`. Greedy from the earliest fix.
std::vector<Stay> find_stays(const track::Track& t, const std::vector<XY>& p, double diameter, double min_s) {
    std::vector<Stay> out;
    const auto& fx = t.fixes;
    const std::size_t n = fx.size();
    std::size_t i = 0;
    while (i < n) {
        double x0 = p[i].x, x1 = p[i].x, y0 = p[i].y, y1 = p[i].y;
        std::size_t j = i;
        while (j + 1 < n && !fx[j + 1].jump_before) {
            const XY q = p[j + 1];
            const double nx0 = std::min(x0, q.x), nx1 = std::max(x1, q.x), ny0 = std::min(y0, q.y), ny1 = std::max(y1, q.y);
            if (std::hypot(nx1 - nx0, ny1 - ny0) > diameter) break;
            x0 = nx0, x1 = nx1, y0 = ny0, y1 = ny1;
            ++j;
        }
        if (fx[j].time_s - fx[i].time_s >= min_s) {
            Stay s;
            s.first = i;
            s.last = j;
            s.start_s = fx[i].time_s;
            s.end_s = fx[j].time_s;
            s.local = p[i];
            for (std::size_t k = i; k <= j; ++k) {
                s.moored |= fx[k].nav_status == track::nav_status_moored || fx[k].nav_status == track::nav_status_at_anchor;
                s.aground |= fx[k].nav_status == track::nav_status_aground;
            }
            out.push_back(s);
            i = j + 1;
        } else {
            ++i;
        }
    }
    return out;
}

std::vector<XY> project(const track::Track& t, const geo::LocalFrame& frame) {
    std::vector<XY> p;
    p.reserve(t.fixes.size());
    for (const auto& f : t.fixes) p.push_back(frame.forward(f.position));
    return p;
}

/// The median time between consecutive fixes (NaN for fewer than two).
double cadence(const track::Track& t) {
    std::vector<double> d;
    for (std::size_t i = 1; i < t.fixes.size(); ++i) d.push_back(t.fixes[i].time_s - t.fixes[i - 1].time_s);
    if (d.empty()) return NAN;
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    return d[d.size() / 2];
}

void fill_traffic(const track::Track& t, const std::vector<XY>& p, double hull_length_m, const grid::CoastGrid& grid,
                  const SweepOptions& sweep, const EvidenceOptions& opt, TrackResult& r) {
    r.stays = find_stays(t, p, stay_diameter(sweep, hull_length_m), std::min(sweep.stop_duration_s, opt.ground_stay_s));
    // Visits: a new one when the vessel went further than the berth radius between two stays.
    for (std::size_t k = 1; k < r.stays.size(); ++k) {
        const Stay& prev = r.stays[k - 1];
        bool away = false;
        for (std::size_t i = prev.last + 1; i < r.stays[k].first && !away; ++i) away = dist(p[i], prev.local) > opt.berth_radius_m;
        away = away || dist(r.stays[k].local, prev.local) > opt.berth_radius_m;
        r.stays[k].visit = prev.visit + (away ? 1 : 0);
    }
    r.over_land.clear();
    for (std::size_t i = 0; i < t.fixes.size(); ++i) {
        const track::Fix& f = t.fixes[i];
        if (f.speed_used_kn >= opt.under_way_kn && !f.stopped && grid.is_land(p[i])) r.over_land.push_back(p[i]);
    }
    r.summary.cadence_s = cadence(t);
    r.summary.hull_length_m = hull_length_m;
}

}  // namespace

TrackResult traffic_of(const track::Track& t, double hull_length_m, const geo::LocalFrame& frame, const grid::CoastGrid& grid,
                       const SweepOptions& sweep, const EvidenceOptions& options) {
    TrackResult r;
    r.summary.id = t.id;
    fill_traffic(t, project(t, frame), hull_length_m, grid, sweep, options, r);
    return r;
}

void gather_evidence(const track::Track& t, double hull_length_m, const geo::LocalFrame& frame, const grid::CoastGrid& grid,
                     const SweepOptions& sweep, const EvidenceOptions& opt, TrackResult& r) {
    gather_evidence(t, project(t, frame), hull_length_m, frame, grid, sweep, opt, r);
}

void gather_evidence(const track::Track& t, const std::vector<XY>& p, double hull_length_m, const geo::LocalFrame& frame,
                     const grid::CoastGrid& grid, const SweepOptions& sweep, const EvidenceOptions& opt, TrackResult& r) {
    if (p.size() != t.fixes.size())
        throw LibraryError("gather_evidence: " + std::to_string(p.size()) + " positions for " + std::to_string(t.fixes.size()) + " fixes");
    fill_traffic(t, p, hull_length_m, grid, sweep, opt, r);
    const auto& fx = t.fixes;
    if (fx.empty()) return;
    // Contact intervals, to tell whether a fix was seen clear.
    std::vector<std::pair<double, double>> contacts;
    for (const Event& e : r.events)
        if (is_contact(e.kind)) contacts.emplace_back(e.start_s, e.end_s);
    std::sort(contacts.begin(), contacts.end());
    // One track's contacts are disjoint intervals: the one that may hold a time is the last
    // that began at or before it.
    auto in_contact = [&](double time_s) {
        auto it = std::upper_bound(contacts.begin(), contacts.end(), std::make_pair(time_s, static_cast<double>(INFINITY)));
        return it != contacts.begin() && std::prev(it)->second >= time_s;
    };
    // The last fix of a piece of track (a gap or a jump follows, or the track ends).
    auto piece_end = [&](std::size_t i) {
        return i + 1 >= fx.size() || fx[i + 1].jump_before || fx[i + 1].time_s - fx[i].time_s > sweep.max_gap_s;
    };
    for (Event& e : r.events) {
        if (!is_contact(e.kind)) continue;
        Event::Evidence& ev = e.evidence;
        const double t0 = e.start_s;
        // a: the first fix at or after the first contact; b: the last before it.
        const auto a_it = std::lower_bound(fx.begin(), fx.end(), t0 - 1e-6, [](const track::Fix& f, double v) { return f.time_s < v; });
        const std::size_t a = static_cast<std::size_t>(a_it - fx.begin());
        const bool have_a = a < fx.size();
        const bool have_b = a > 0 && !(have_a && fx[a].jump_before && fx[a].time_s <= t0 + 1e-6);
        const std::size_t b = have_b ? a - 1 : 0;
        if (have_b) {
            ev.speed_before_kn = fx[b].speed_used_kn;
            ev.speed_before_age_s = std::max(0.0, t0 - fx[b].time_s);
            // A fix minutes before the contact (beyond the speed window) tells the speed then,
            // not on the way to the contact: when the positions say the vessel went from it to
            // the contact at twice the speed of one under way or more (which no berthing
            // averages over minutes, as sweep.cpp's "stopped before" has it), that is the speed
            // before (a vessel at anchor at 0.2 kn whose next fix, 3 minutes on, is on the shore
            // 735 m away: 7.9 kn; before, "came to rest at the contact from 0.2 kn: berthing").
            if (ev.speed_before_age_s > sweep.speed_window_s && ev.speed_before_age_s <= sweep.max_gap_s) {  // (not across a gap)
                const double implied_kn = dist(p[b], frame.forward(e.ship)) / ev.speed_before_age_s * 3600.0 / 1852.0;
                const double sog = std::isfinite(ev.speed_before_kn) ? ev.speed_before_kn : 0.0;
                if (implied_kn >= 2 * opt.under_way_kn && implied_kn > 2 * sog + 1) ev.speed_before_kn = implied_kn;
            }
            ev.seen_clear_before = !in_contact(fx[b].time_s);
            if (ev.seen_clear_before) ev.start_not_before_s = fx[b].time_s;
        }
        if (have_a) {
            ev.speed_after_kn = fx[a].speed_used_kn;
            ev.speed_after_age_s = std::max(0.0, fx[a].time_s - t0);
        }
        if (have_a && have_b) ev.gap_distance_m = dist(p[b], p[a]);
        ev.bracket_dense = have_b && have_a && ev.speed_before_age_s <= opt.abrupt_window_s && ev.speed_after_age_s <= opt.abrupt_window_s;
        // The fixes inside the contact, and whether the contact reaches any.
        std::size_t inside = 0;
        for (std::size_t k = a; k < fx.size() && fx[k].time_s <= e.end_s + 1e-6; ++k) ++inside;
        ev.between_fixes_only = inside == 0 && have_a && have_b && fx[a].time_s - fx[b].time_s >= opt.between_fixes_s;
        // Came clear again: the contact ends before the last fix of its piece (a contact still
        // open at a gap or at the track's end is closed there, not left).
        {
            const auto e_it = std::lower_bound(fx.begin(), fx.end(), e.end_s - 1e-6, [](const track::Fix& f, double v) { return f.time_s < v; });
            const std::size_t k = static_cast<std::size_t>(e_it - fx.begin());
            ev.left_contact = !(k < fx.size() && std::fabs(fx[k].time_s - e.end_s) <= 1e-6 && piece_end(k));
        }
        // Where it came to rest: the first stay long enough (a vessel lying there) that reaches
        // fix a. Shorter stays before it are a vessel creeping in (berthing, jitter at low speed).
        const XY at_contact = frame.forward(e.ship);
        if (have_a) {
            // When the vessel is next seen clear (across gaps, in contact at each fix).
            std::size_t k = a;
            while (k < fx.size() && in_contact(fx[k].time_s)) ++k;
            const double seen_clear_s = k < fx.size() ? fx[k].time_s : INFINITY;
            auto s_it = std::lower_bound(r.stays.begin(), r.stays.end(), a, [](const Stay& s, std::size_t i) { return s.last < i; });
            while (s_it != r.stays.end() && s_it->end_s - s_it->start_s < opt.ground_stay_s) ++s_it;
            if (s_it != r.stays.end()) {
                const Stay& s = *s_it;
                ev.stay = static_cast<std::size_t>(s_it - r.stays.begin());
                ev.stop_distance_m = dist(at_contact, s.local);
                // A stay that begins once the vessel is clear again is not where it came to
                // rest in the land (a ferry that leaves the berth the chart lacks and lies next
                // at the other end of its crossing, 6 km on); one a few seconds after a touch
                // at a wharf may still be its berth (decide(): within its reach).
                ev.rests_in_contact = s.start_s <= seen_clear_s;
                // How long it lay there: to the end of the visit's last stay. A vessel lying
                // still for hours is seldom one stay: its first box holds the last of its
                // approach, and GPS jitter then takes a fix out of it (a grounding of 4 h read
                // as 81 min, berth stays of 3 h as 5-7 min); the stays after it, the vessel not
                // gone beyond the berth radius, are the same visit.
                // Only stays that begin before the vessel is next seen clear (across gaps, in
                // contact at each fix): one that floats off and anchors 200 m away is the same
                // visit, but no longer lies where it touched.
                double visit_end_s = s.end_s;
                for (auto it = std::next(s_it); it != r.stays.end() && it->visit == s.visit && it->start_s < seen_clear_s; ++it)
                    visit_end_s = it->end_s;
                ev.stay_s = visit_end_s - s.start_s;
                const double rest_s = std::max(s.start_s, fx[a].time_s);
                ev.prompt_stop = s.first <= a || rest_s - t0 <= opt.abrupt_window_s;
                if (have_b && ev.speed_before_age_s <= opt.abrupt_window_s && rest_s - t0 <= opt.abrupt_window_s && rest_s > fx[b].time_s)
                    ev.deceleration_kn_s = ev.speed_before_kn / (rest_s - fx[b].time_s);
                ev.moored_at_stay = s.moored;
                ev.aground_at_stay = s.aground;
                // Stopped after, across gaps, as long as the vessel had not moved.
                e.stopped_after_s = std::max(0.0, s.start_s - t0);
            }
        }
    }
}

Traffic learn_traffic(const std::vector<const TrackResult*>& tracks, const std::vector<std::string>& ids, const geo::LocalFrame& frame,
                      const EvidenceOptions& opt) {
    Traffic out;
    out.berth_stays.resize(tracks.size());
    out.own_visits.resize(tracks.size());
    // Stays, keyed by cell of the berth radius, in an order that does not depend on the tracks'.
    struct Ref {
        std::size_t track, stay;
    };
    // Cells of the radius (a metre at least: a cell index must stay a whole number however small
    // a radius is asked for).
    const double R = std::max(opt.berth_radius_m, 1.0);
    std::vector<Ref> all;
    for (std::size_t k = 0; k < tracks.size(); ++k) {
        out.berth_stays[k].assign(tracks[k]->stays.size(), 0);
        out.own_visits[k].assign(tracks[k]->stays.size(), 0);
        for (std::size_t s = 0; s < tracks[k]->stays.size(); ++s) all.push_back({k, s});
    }
    auto stay = [&](const Ref& r) -> const Stay& { return tracks[r.track]->stays[r.stay]; };
    auto key = [&](const Ref& r) {
        const Stay& s = stay(r);
        return std::make_tuple(s.local.x, s.local.y, s.start_s, ids[r.track]);
    };
    std::sort(all.begin(), all.end(), [&](const Ref& a, const Ref& b) { return key(a) < key(b); });
    auto cell_of = [&](XY p) { return std::make_pair(static_cast<long long>(std::floor(p.x / R)), static_cast<long long>(std::floor(p.y / R))); };
    std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < all.size(); ++i) cells[cell_of(stay(all[i]).local)].push_back(i);
    auto near = [&](std::size_t i, auto&& f) {
        const auto [cx, cy] = cell_of(stay(all[i]).local);
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy)
                if (auto it = cells.find({cx + dx, cy + dy}); it != cells.end())
                    for (const std::size_t j : it->second)
                        if (j != i && dist(stay(all[i]).local, stay(all[j]).local) <= opt.berth_radius_m) f(j);
    };
    // Each stay's evidence: the others near it that did not begin while it lasted, of other
    // vessels or of this one's other visits.
    for (std::size_t i = 0; i < all.size(); ++i) {
        const Stay& s = stay(all[i]);
        std::size_t n = 0, own = 0;
        near(i, [&](std::size_t j) {
            const Stay& o = stay(all[j]);
            const bool same_track = all[j].track == all[i].track;
            if (!(same_track && o.visit == s.visit) && !(o.start_s > s.start_s && o.start_s <= s.end_s)) {
                ++n;
                own += same_track;
            }
        });
        out.berth_stays[all[i].track][all[i].stay] = n;
        out.own_visits[all[i].track][all[i].stay] = own;
    }
    // Learned berths: stays joined when within the radius of each other (single linkage),
    // kept with two stays or more.
    std::vector<std::size_t> parent(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) parent[i] = i;
    auto find = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (std::size_t i = 0; i < all.size(); ++i)
        near(i, [&](std::size_t j) {
            const std::size_t a = find(i), b = find(j);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        });
    std::map<std::size_t, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < all.size(); ++i) groups[find(i)].push_back(i);
    for (const auto& [root, members] : groups) {
        std::set<std::pair<std::size_t, std::size_t>> visits;
        for (const std::size_t i : members) visits.insert({all[i].track, stay(all[i]).visit});
        if (visits.size() < 2) continue;  // one visit, its stay broken by jitter: not a place vessels come to
        LearnedPlace pl;
        pl.kind = LearnedPlace::Kind::berth;
        std::set<std::string> vessels;
        XY c{0, 0};
        for (const std::size_t i : members) {
            const Stay& s = stay(all[i]);
            c = c + s.local;
            vessels.insert(ids[all[i].track]);
            pl.hours += (s.end_s - s.start_s) / 3600.0;
            pl.first_s = std::isnan(pl.first_s) ? s.start_s : std::min(pl.first_s, s.start_s);
            pl.last_s = std::isnan(pl.last_s) ? s.end_s : std::max(pl.last_s, s.end_s);
        }
        c = (1.0 / static_cast<double>(members.size())) * c;
        for (const std::size_t i : members) pl.size_m = std::max(pl.size_m, dist(c, stay(all[i]).local));
        pl.local = c;
        pl.count = visits.size();
        pl.vessels = vessels.size();
        out.places.push_back(pl);
    }
    // Water the chart lacks: cells where fixes under way lie on charted land.
    const double W = opt.water_cell_m;
    struct Cell {
        std::size_t fixes = 0;
        std::set<std::string> vessels;
    };
    std::map<std::pair<long long, long long>, Cell> water;
    std::vector<std::pair<long long, long long>> track_cells;  // one track's, sorted: each cell's fixes counted at once
    for (std::size_t k = 0; k < tracks.size(); ++k) {
        track_cells.clear();
        for (const XY& q : tracks[k]->over_land)
            track_cells.emplace_back(static_cast<long long>(std::floor(q.x / W)), static_cast<long long>(std::floor(q.y / W)));
        std::sort(track_cells.begin(), track_cells.end());
        for (std::size_t i = 0, j; i < track_cells.size(); i = j) {
            for (j = i + 1; j < track_cells.size() && track_cells[j] == track_cells[i]; ++j) {
            }
            Cell& c = water[track_cells[i]];
            c.fixes += j - i;
            c.vessels.insert(ids[k]);
        }
    }
    for (const auto& [at, c] : water) {
        LearnedPlace pl;
        pl.kind = LearnedPlace::Kind::water;
        pl.local = {(static_cast<double>(at.first) + 0.5) * W, (static_cast<double>(at.second) + 0.5) * W};
        pl.size_m = W;
        pl.count = c.fixes;
        pl.vessels = c.vessels.size();
        out.places.push_back(pl);
    }
    auto order = [](const LearnedPlace& a, const LearnedPlace& b) {
        return std::make_tuple(a.kind, a.local.x, a.local.y) < std::make_tuple(b.kind, b.local.x, b.local.y);
    };
    std::sort(out.places.begin(), out.places.end(), order);
    for (LearnedPlace& pl : out.places) pl.position = frame.inverse(pl.local);
    return out;
}

namespace {

/// A shore construction one berths at (event's `structure`): wharves, quays, piers, pontoons,
/// dolphins, bollards, mooring walls. Breakwaters, groynes, sea walls and rip rap are not berths.
bool berthing_structure(const std::string& kind) {
    for (const char* k : {"wharf", "quay", "pier", "jetty", "pontoon", "dolphin", "bollard", "tie-up wall", "post or pile", "landing", "mooring"})
        if (kind.find(k) != std::string::npos) return true;
    return false;
}

/// How far from where it touched a ship that runs aground comes to rest: about its length,
/// and 50 m more.
double reach_of(double hull_length_m) { return (std::isfinite(hull_length_m) ? hull_length_m : 0.0) + 50.0; }

/// Whether a vessel making `speed_kn` could have gone `distance_m` in `seconds` (half as fast
/// again, and `reach_m` more): a contact first seen after a gap lies where it could have come to.
bool could_have_gone(double distance_m, double speed_kn, double seconds, double reach_m) {
    return distance_m <= 1.5 * speed_kn * 1852.0 / 3600.0 * seconds + reach_m;
}

std::string fmt1(double v) { return track::detail::fmt(std::round(v * 10) / 10); }

void recount(TrackResult& r) {
    TrackSummary& s = r.summary;
    s.groundings = s.alongside = s.contacts_at_start = s.expected_contacts = s.chart_disagreements = 0;
    for (const Event& e : r.events) count_contact(s, e.kind);
}

/// The kind a contact has by the real world's rules (its sweep kind, the simulated world's,
/// is the starting point), its grade and reason; decide() below holds it to what a charted
/// depth can be.
void decide_rules(Event& e, double hull_length_m, std::size_t berth_stays, std::size_t own_visits, const EvidenceOptions& opt) {
    Event::Evidence& ev = e.evidence;
    ev.berth_stays = berth_stays;
    const double tol = opt.chart_tolerance_m;
    ev.within_chart_tolerance = std::isfinite(tol) && e.penetration_m <= tol;
    const int tol_cut = ev.within_chart_tolerance ? 1 : 0;
    const bool expected_area = !e.area_kind.empty();
    const bool at_structure = berthing_structure(e.structure);
    const bool lay_still = ev.stay != static_cast<std::size_t>(-1) && ev.stay_s >= opt.ground_stay_s;
    const double reach_m = reach_of(hull_length_m);
    const bool at_contact = lay_still && ev.prompt_stop && ev.stop_distance_m <= reach_m;
    const bool berth = berth_stays > 0 || expected_area || at_structure || ev.moored_at_stay;
    auto berth_words = [&] {
        std::string w;
        auto add = [&](const std::string& s) { w += (w.empty() ? "" : ", ") + s; };
        if (berth_stays > 0) add(std::to_string(berth_stays) + " other stay" + (berth_stays == 1 ? "" : "s") + " there in the run");
        if (expected_area) add("in a " + e.area_kind + " area");
        if (at_structure) add("at a " + e.structure);
        if (ev.moored_at_stay) add("AIS status moored or at anchor");
        return w;
    };
    auto set = [&](EventKind k, int grade, std::string reason) {
        e.kind = k;
        ev.grade = std::clamp(grade, 1, 4);
        ev.reason = std::move(reason);
    };
    const bool under_way_before = ev.seen_clear_before && ev.speed_before_kn >= opt.under_way_kn;
    // 1. The vessel said so.
    if (e.reported_aground || (at_contact && ev.aground_at_stay)) {
        set(EventKind::grounding, 4, "AIS status aground");
        return;
    }
    // Deeper than the hull could go: a ship that runs aground stops within about its length
    // of where it touched; a hull further into charted land lies in water the chart lacks.
    const bool too_deep = std::isfinite(hull_length_m) && e.penetration_m > reach_m + (std::isfinite(tol) ? tol : 0.0);
    const std::string deep_words = fmt1(e.penetration_m) + " m into charted land, deeper than a " + fmt1(hull_length_m) + " m hull could go";
    switch (e.kind) {
        case EventKind::contact_at_start:
        case EventKind::expected_contact:
            if (!e.unseen_after.empty()) {
                // Not seen begin. After a gap, with the vessel seen clear and under way before
                // it and lying still in contact after it: a grounding inside the gap.
                const bool gap = e.unseen_after == "gap" && under_way_before && ev.speed_before_age_s <= opt.max_unseen_s;
                const bool plausible = could_have_gone(ev.gap_distance_m, ev.speed_before_kn, ev.speed_before_age_s, reach_m);
                if (gap && plausible && at_contact && !berth) {
                    e.kind = EventKind::grounding;
                    set(EventKind::grounding, 3 - tol_cut,
                        "seen under way at " + fmt1(ev.speed_before_kn) + " kn, then lying in contact for " + fmt1(ev.stay_s / 60) +
                            " min after a gap of " + fmt1(ev.speed_before_age_s) + " s, where no other vessel stays: aground inside the gap");
                    return;
                }
                if (gap && plausible && at_contact) {
                    set(e.kind == EventKind::expected_contact ? EventKind::expected_contact : EventKind::alongside, 3,
                        "arrived inside a gap and lay still where vessels berth: " + berth_words());
                    return;
                }
                set(e.kind, 2, "already in contact at the first fix after the " + e.unseen_after + ": not seen begin");
                return;
            }
            set(e.kind, 3, "began while stopped or under the berthing speed, in a " + e.area_kind + " area");
            return;
        case EventKind::alongside: {
            // Which rule made it so (sweep.cpp): stopped, moored or at anchor by its AIS status
            // and under 3 kn, or under the berthing speed.
            // (The status's rule named only where the speed was at the default berthing speed or
            // more: under it, that rule is the one the vessel met whatever its status.)
            const bool moored = (e.nav_status == track::nav_status_moored || e.nav_status == track::nav_status_at_anchor) &&
                                e.speed_kn >= SweepOptions{}.berthing_speed_kn;
            set(e.kind, e.stopped_before ? 4 : 3,
                e.stopped_before ? std::string("stopped before the contact")
                : moored         ? "began at " + fmt1(e.speed_kn) + " kn, " + track::nav_status_text(e.nav_status) + " by its AIS status (under 3 kn)"
                                 : "began under the berthing speed (" + fmt1(e.speed_kn) + " kn)");
            return;
        }
        case EventKind::chart_disagrees:
        case EventKind::close_pass: return;
        case EventKind::grounding: break;
    }
    // Began under way, seen clear before.
    const std::string speed = fmt1(ev.speed_before_kn) + " kn " + fmt1(ev.speed_before_age_s) + " s before";
    if (at_contact && too_deep) {
        set(EventKind::alongside, 2, "came to rest " + deep_words + ": in water the chart lacks" + (berth ? " (" + berth_words() + ")" : ""));
        return;
    }
    if (at_contact) {
        const bool abrupt = ev.deceleration_kn_s >= opt.abrupt_kn_s;
        if (abrupt && own_visits > 0) {  // the vessel comes here on other visits and stops so every time: its berth
            set(EventKind::alongside, 3,
                "stopped quickly at the contact (" + speed + ", " + track::detail::fmt(std::round(ev.deceleration_kn_s * 100) / 100) +
                    " kn/s) where it lies on " + std::to_string(own_visits) + " other visit" + (own_visits == 1 ? "" : "s") +
                    " in the run: its own berth (" + berth_words() + ")");
            return;
        }
        if (abrupt) {  // seen by the fixes, whatever the chart's accuracy
            set(EventKind::grounding, berth ? 3 : 4,
                "stopped abruptly at the contact (" + speed + ", at rest within " + fmt1(ev.stop_distance_m) + " m, " +
                    track::detail::fmt(std::round(ev.deceleration_kn_s * 100) / 100) + " kn/s) and lay there " + fmt1(ev.stay_s / 60) + " min" +
                    (berth ? " (" + berth_words() + ")" : ""));
            return;
        }
        if (!ev.bracket_dense && under_way_before && !berth) {
            set(EventKind::grounding, 3 - tol_cut,
                "came to rest at the contact inside a gap of the fixes (" + speed + ", at rest within " + fmt1(ev.stop_distance_m) +
                    " m) and lay there " + fmt1(ev.stay_s / 60) + " min, where no other vessel stays");
            return;
        }
        if (!ev.bracket_dense && under_way_before) {
            set(EventKind::alongside, 3, "arrived and lay still where vessels berth: " + berth_words());
            return;
        }
        set(EventKind::alongside, 3,
            ev.bracket_dense ? "slowed to rest gradually at the contact (" + speed + "), not abruptly: berthing"
                             : "came to rest at the contact from " + fmt1(ev.speed_before_kn) + " kn: berthing");
        return;
    }
    // Did not lie where it touched.
    if (ev.between_fixes_only) {
        ev.disagreement = "between_fixes";
        set(EventKind::chart_disagrees, 2,
            "contact only on the straight line between fixes " + fmt1(ev.speed_before_age_s + ev.speed_after_age_s) + " s apart");
        return;
    }
    const double bracket_s = ev.speed_before_age_s + ev.speed_after_age_s;
    if (!too_deep && ev.left_contact && ev.bracket_dense && bracket_s > 0 && ev.speed_before_kn >= opt.under_way_kn &&
        ev.speed_after_kn <= 0.5 * ev.speed_before_kn && (ev.speed_before_kn - ev.speed_after_kn) / bracket_s >= opt.abrupt_kn_s) {
        set(EventKind::grounding, 2 - tol_cut,
            "touch and go: slowed abruptly at the contact (" + speed + ", " + fmt1(ev.speed_after_kn) + " kn " + fmt1(ev.speed_after_age_s) +
                " s after), then went on");
        return;
    }
    if (lay_still && ev.speed_before_kn < opt.under_way_kn) {
        set(EventKind::alongside, 3,
            "touched at " + fmt1(ev.speed_before_kn) + " kn, under the " + fmt1(opt.under_way_kn) + " kn of a vessel under way, and came to rest " +
                fmt1(ev.stop_distance_m) + " m on: berthing" + (berth ? " (" + berth_words() + ")" : ""));
        return;
    }
    if (lay_still) {
        // Where it came to rest: in the land (an arrival the chart does not draw), or on once
        // it was seen clear of it again: a harbour basin after an entrance the chart lacks, or
        // the far end of a ferry's crossing after it clipped the land leaving (before, "went
        // on 6049.5 m through charted land and came to rest there: an arrival").
        set(EventKind::alongside, berth ? 3 : 2,
            (ev.rests_in_contact ? "went on " + fmt1(ev.stop_distance_m) + " m through charted land and came to rest there: an arrival the chart does not draw"
                                 : "went through charted land and was seen clear of it again, then came to rest " + fmt1(ev.stop_distance_m) +
                                       " m on: the chart lacks water there") +
                (berth ? " (" + berth_words() + ")" : ""));
        return;
    }
    if (too_deep) {
        ev.disagreement = "deeper_than_hull";
        set(EventKind::chart_disagrees, 3, "went on " + deep_words + ": the chart lacks water there");
        return;
    }
    ev.disagreement = "sailed_through";
    set(EventKind::chart_disagrees, 3, "sailed on through under way (" + speed + "): the chart lacks water there");
}

/// Berthing contacts at most this far apart that come to rest in the same stay are one event.
constexpr double arrival_gap_s = 60.0;

}  // namespace

/// decide_rules(), then: a charted depth (a shoal, a danger) is no berth's face. A vessel that
/// came onto one and lay there, where no vessel berths (no other stays there, no berth,
/// harbour or anchorage area, no structure), is aground whatever its speed or AIS status: a
/// ship dragging its anchor, or drifting at 1.5 kn, onto a 3.6 m shoal in the open bay (before:
/// "alongside ... berthing", or "in water the chart lacks" of a shoal area that is large).
void decide(Event& e, double hull_length_m, std::size_t berth_stays, std::size_t own_visits, const EvidenceOptions& opt) {
    decide_rules(e, hull_length_m, berth_stays, own_visits, opt);
    const Event::Evidence& ev = e.evidence;
    const bool depth = e.hit == coast::HazardKind::shallow || e.hit == coast::HazardKind::danger;
    const bool lay_still = ev.stay != static_cast<std::size_t>(-1) && ev.stay_s >= opt.ground_stay_s && ev.rests_in_contact;
    if (!depth || !lay_still || e.kind != EventKind::alongside || berth_stays > 0 || !e.area_kind.empty() || berthing_structure(e.structure))
        return;
    const std::string what = e.hit == coast::HazardKind::shallow
                                 ? "shallow water (" + (std::isfinite(e.charted_depth_m) ? fmt1(e.charted_depth_m) + " m" : std::string("depth unknown")) + " charted)"
                                 : std::string("danger") + (e.danger == coast::DangerKind::none ? "" : std::string(" (") + coast::to_string(e.danger) + ")");
    e.kind = EventKind::grounding;
    e.evidence.grade = ev.within_chart_tolerance ? 2 : 3;
    e.evidence.reason = "came onto charted " + what + " at " + fmt1(e.speed_kn) + " kn and lay there " + fmt1(ev.stay_s / 60) +
                        " min, where no vessel berths: a charted depth is no berth, aground";
}

void decide_kinds(TrackResult& r, const std::vector<std::size_t>& berth_stays, const std::vector<std::size_t>& own_visits,
                  const EvidenceOptions& opt) {
    for (Event& e : r.events) {
        if (!is_contact(e.kind)) continue;
        const std::size_t s = e.evidence.stay;
        decide(e, r.summary.hull_length_m, s < berth_stays.size() ? berth_stays[s] : 0, s < own_visits.size() ? own_visits[s] : 0, opt);
    }
    // One event per stay: a contact that begins and ends within the stay that the one before
    // it ended in (the vessel has not moved) is part of it.
    std::vector<Event> merged;
    merged.reserve(r.events.size());
    std::size_t last_contact = static_cast<std::size_t>(-1);
    // Stays are disjoint and in time order: the one that may hold a time is the last that began
    // at or before it.
    auto stay_at = [&](double time_s) -> std::size_t {
        auto it = std::upper_bound(r.stays.begin(), r.stays.end(), time_s + 1e-6, [](double v, const Stay& s) { return v < s.start_s; });
        if (it == r.stays.begin() || std::prev(it)->end_s + 1e-6 < time_s) return static_cast<std::size_t>(-1);
        return static_cast<std::size_t>(std::prev(it) - r.stays.begin());
    };
    std::size_t open_stay = static_cast<std::size_t>(-1);
    for (Event& e : r.events) {
        if (!is_contact(e.kind)) {
            merged.push_back(std::move(e));
            continue;
        }
        const std::size_t s = stay_at(e.start_s);
        // One arrival: berthing contacts seconds apart that come to rest in the same stay (a
        // vessel creeping in across a coastline drawn a few metres off, GPS jitter taking it
        // in and out of contact: four alongside events within two minutes, before).
        const bool one_arrival = last_contact != static_cast<std::size_t>(-1) && e.kind == EventKind::alongside &&
                                 merged[last_contact].kind == EventKind::alongside && e.evidence.stay != static_cast<std::size_t>(-1) &&
                                 e.evidence.stay == merged[last_contact].evidence.stay && e.start_s - merged[last_contact].end_s <= arrival_gap_s;
        if (one_arrival || (last_contact != static_cast<std::size_t>(-1) && s != static_cast<std::size_t>(-1) && s == open_stay)) {
            Event& m = merged[last_contact];
            m.end_s = std::max(m.end_s, e.end_s);
            m.penetration_m = std::max(m.penetration_m, e.penetration_m);
            m.evidence.pieces += e.evidence.pieces;
            // One arrival lies in its stay as long as its last contact says (the first was seen
            // clear again, between the touches); its reason names no minutes.
            if (one_arrival && e.evidence.stay_s > m.evidence.stay_s) m.evidence.stay_s = e.evidence.stay_s;
            if (e.reported_aground && m.kind != EventKind::grounding) {
                m.reported_aground = true;
                m.kind = EventKind::grounding;
                m.evidence.grade = 4;
                m.evidence.reason = "AIS status aground";
            }
            open_stay = stay_at(m.end_s);  // the merged event now ends where this one did
            continue;
        }
        merged.push_back(std::move(e));
        last_contact = merged.size() - 1;
        open_stay = stay_at(merged.back().end_s);
    }
    r.events = std::move(merged);
    recount(r);
}

void ground_inside_gaps(TrackResult& r, const track::Track& t, const SweepOptions& opt, const EvidenceOptions& evidence, double hull_length_m) {
    const auto& fx = t.fixes;
    bool changed = false;
    for (Event& e : r.events) {
        if (e.kind != EventKind::contact_at_start || e.unseen_after != "gap") continue;
        // a: the first fix of the piece (in contact); b: the last one before the gap.
        const auto a_it = std::lower_bound(fx.begin(), fx.end(), e.start_s - 1e-6, [](const track::Fix& f, double v) { return f.time_s < v; });
        const std::size_t a = static_cast<std::size_t>(a_it - fx.begin());
        if (a == 0 || a >= fx.size() || fx[a].jump_before) continue;
        const track::Fix& b = fx[a - 1];
        // Seen clear there: no contact of the track holds its time.
        const bool clear = std::none_of(r.events.begin(), r.events.end(), [&](const Event& o) {
            return is_contact(o.kind) && o.start_s <= b.time_s + 1e-6 && o.end_s >= b.time_s - 1e-6;
        });
        const double gap_s = fx[a].time_s - b.time_s;
        const bool under_way = !b.stopped && b.speed_used_kn >= opt.berthing_speed_kn;
        const bool plausible = could_have_gone(track::distance_m(b.position, fx[a].position), b.speed_used_kn, gap_s, reach_of(hull_length_m));
        if (!clear || !under_way || !plausible || gap_s > evidence.max_unseen_s) continue;
        e.kind = EventKind::grounding;
        e.evidence.seen_clear_before = true;
        e.evidence.start_not_before_s = b.time_s;
        e.evidence.speed_before_kn = b.speed_used_kn;
        e.evidence.speed_before_age_s = std::max(0.0, e.start_s - b.time_s);
        changed = true;
    }
    if (changed) recount(r);
}

void grade_simulated(TrackResult& r) {
    for (Event& e : r.events) {
        if (!is_contact(e.kind)) continue;
        e.evidence.grade = 4;
        switch (e.kind) {
            case EventKind::grounding:
                if (e.unseen_after.empty()) {
                    e.evidence.reason = "contact under way, seen clear before: the chart is the world";
                } else {  // the speed at the contact was not seen: grade 3
                    e.evidence.grade = 3;
                    e.evidence.reason = "seen clear under way at " + fmt1(e.evidence.speed_before_kn) + " kn, in contact after a gap of " +
                                        fmt1(e.evidence.speed_before_age_s) + " s: aground inside the gap (its speed at the contact not seen); the chart is the world";
                }
                break;
            case EventKind::alongside: e.evidence.reason = "began while stopped or under the berthing speed"; break;
            case EventKind::contact_at_start: e.evidence.reason = "already in contact at the first fix after the " + e.unseen_after; break;
            case EventKind::expected_contact: e.evidence.reason = "in a " + e.area_kind + " area, not under way"; break;
            default: break;
        }
    }
}

void merge_stays(TrackResult& r, const track::Track& t, const SweepOptions& opt, double under_way_kn) {
    const auto mergeable = [](EventKind k) { return k == EventKind::alongside || k == EventKind::contact_at_start; };
    const std::vector<track::Fix>& fixes = t.fixes;
    // Whether the vessel lay at one place, not under way, from `from_s` to `to_s`, within the
    // stop diameter of `at` (the first fix at or before from_s to the first at or after to_s).
    const auto lay_still = [&](double from_s, double to_s, geo::LonLat at) {
        auto first = std::upper_bound(fixes.begin(), fixes.end(), from_s, [](double v, const track::Fix& f) { return v < f.time_s; });
        if (first != fixes.begin()) --first;
        const Eigen::Vector2d m = geo::metres_per_degree(at.lat);
        bool any = false;
        for (auto f = first; f != fixes.end(); ++f) {
            if (f != first && f->jump_before) return false;
            const double dx = (f->position.lon - at.lon) * m.x(), dy = (f->position.lat - at.lat) * m.y();  // (per degree lon, lat)
            const bool under_way = !f->stopped && !(f->speed_used_kn < under_way_kn);
            if (under_way || std::hypot(dx, dy) > opt.stop_diameter_m) return false;
            any = true;
            if (f->time_s >= to_s) break;
        }
        return any;
    };
    std::vector<Event> merged;
    merged.reserve(r.events.size());
    std::size_t last_contact = static_cast<std::size_t>(-1);
    for (Event& e : r.events) {
        if (!is_contact(e.kind)) {
            merged.push_back(std::move(e));
            continue;
        }
        if (last_contact != static_cast<std::size_t>(-1) && mergeable(e.kind) && mergeable(merged[last_contact].kind) &&
            lay_still(merged[last_contact].end_s, e.start_s, merged[last_contact].ship)) {
            Event& m = merged[last_contact];
            m.end_s = std::max(m.end_s, e.end_s);
            m.penetration_m = std::max(m.penetration_m, e.penetration_m);
            m.evidence.pieces += e.evidence.pieces;
            m.reported_aground = m.reported_aground || e.reported_aground;
            continue;
        }
        merged.push_back(std::move(e));
        last_contact = merged.size() - 1;
    }
    r.events = std::move(merged);
    recount(r);
}

}  // namespace shoal::audit
