// A ship's conduct under COLREG rules 8 and 13-17 (see include/shoal/exercise/colreg_conduct.hpp).
#include <shoal/exercise/colreg_conduct.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <shoal/track/time.hpp>
#include <shoal/util/error.hpp>
#include "sweep/local_track.hpp"

namespace shoal::audit {

namespace {

using geo::XY;

constexpr double deg = 180.0 / std::numbers::pi;
constexpr double knot_ms = 1852.0 / 3600.0;

/// A track for judging conduct: the local track (never broken), per fix a heading and a speed
/// (m/s); between fixes the fraction of the interval holding a moment is clamped to it.
struct ShipMotion {
    LocalTrack track;
    std::vector<double> heading, speed;

    ShipMotion(const track::Track& tr, const geo::LocalFrame& frame) : track(tr, frame, {}, Placing::positions) {
        const std::size_t n = tr.fixes.size();
        auto seg_v = [&](std::size_t i) { return (1.0 / (track.time(i + 1) - track.time(i))) * (track.position(i + 1) - track.position(i)); };
        for (std::size_t j = 0; j < n; ++j) {
            const track::Fix& f = tr.fixes[j];
            // Speed: as resolved (SOG, else positions), else SOG, else the mean of the segments' speeds.
            double v = std::isfinite(f.speed_used_kn) ? f.speed_used_kn * knot_ms : std::isfinite(f.sog_kn) ? f.sog_kn * knot_ms : NAN;
            XY dir{};
            if (n >= 2) {
                const XY v0 = seg_v(j == 0 ? 0 : j - 1), v1 = seg_v(std::min(j, n - 2));
                if (!std::isfinite(v)) v = 0.5 * (std::sqrt(geo::norm2(v0)) + std::sqrt(geo::norm2(v1)));
                dir = v0 + v1;
            }
            speed.push_back(std::isfinite(v) ? v : 0.0);
            double h = f.heading_source != track::HeadingSource::none && std::isfinite(f.heading_used_deg) ? f.heading_used_deg
                       : std::isfinite(f.cog_deg)                                                            ? f.cog_deg
                                                                                                             : NAN;
            if (!std::isfinite(h)) h = geo::norm2(dir) > 0 ? std::atan2(dir.x, dir.y) * deg : (j > 0 ? heading[j - 1] : 0.0);
            heading.push_back(std::fmod(std::fmod(h, 360.0) + 360.0, 360.0));
        }
    }
    Where where(double tt) const {
        if (track.size() < 2) return {};
        const std::size_t i = track.interval(tt);
        return {i, std::clamp(track.fraction(i, tt), 0.0, 1.0)};
    }
    XY at(double tt) const { return track.position(where(tt)); }
    double heading_at(double tt) const { return track.interpolate_heading(heading, where(tt)); }
    double speed_at(double tt) const { return track.interpolate(speed, where(tt)); }
};

std::string clock(double t) { return track::format_iso8601(t, 0).substr(11); }
std::string num(double v, int decimals) {
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return b;
}
std::string nm(double m) { return num(m / 1852.0, 2) + " nm"; }
std::string kn(double ms) { return num(ms / knot_ms, 1) + " kn"; }
std::string course(double h) {
    char b[16];
    std::snprintf(b, sizeof b, "%03.0f", std::fmod(std::round(h) + 360.0, 360.0));
    return b;
}

const char* situation_rule(Situation s) {
    switch (s) {
        case Situation::overtaking: return "13";
        case Situation::head_on: return "14";
        case Situation::crossing: break;
    }
    return "15";
}

}  // namespace

std::vector<Conduct> judge_conduct(const track::Track& own, const std::vector<const track::Track*>& others, const geo::LocalFrame& frame,
                                   const ConductOptions& o, double max_gap_s) {
    if (!(o.cpa_m > 0) || !std::isfinite(o.cpa_m)) throw UsageError("ConductOptions::cpa_m must be > 0 metres");
    if (!(o.early_range_m >= 0) || !std::isfinite(o.early_range_m)) throw UsageError("ConductOptions::early_range_m must be >= 0 metres");
    if (!(o.min_course_deg > 0 && o.min_course_deg <= 180)) throw UsageError("ConductOptions::min_course_deg must be in (0, 180] degrees");
    if (!(o.min_speed_change > 0) || !std::isfinite(o.min_speed_change)) throw UsageError("ConductOptions::min_speed_change must be > 0");
    ColregOptions co;
    co.range_m = o.range_m;
    co.head_on_tolerance_deg = o.head_on_deg;
    co.course_change_deg = o.action_course_deg;
    co.speed_change = o.action_speed_change;
    co.sustain_s = o.sustain_s;
    std::vector<Conduct> out;
    if (own.fixes.size() < 2) return out;
    const ShipMotion me(own, frame);
    for (std::size_t i = 0; i < others.size(); ++i) {
        const track::Track* other = others[i];
        if (!other || other->fixes.size() < 2) continue;
        const auto found = find_situations({&own, other}, frame, co, max_gap_s);
        if (found.empty()) continue;
        const ShipMotion them(*other, frame);
        for (const ColregEncounter& e : found) {
            Conduct c;
            c.other = i;
            c.situation = e;
            const Classification& k = e.at_start;
            const bool give = k.give_way == Party::a || k.give_way == Party::both;
            const bool stand = k.stand_on == Party::a;
            // Risk of collision: the CPA projected at the start is under cpa_m and ahead, or the
            // ships did come closer than that (the projection from logged speed and course can miss it).
            const bool risk = (e.cpa_start.distance_m < o.cpa_m && e.cpa_start.time_s > 0) || e.closest_m < o.cpa_m;
            if (!risk || (!give && !stand)) {
                if (!risk)
                    c.did = "no risk of collision: " + (e.cpa_start.time_s > 0 ? "CPA projected at the start " + nm(e.cpa_start.distance_m) + ", "
                                                                                : std::string("the ships already drawing apart at the start, ")) +
                            "closest approach " + nm(e.closest_m) + " (the rules ask something under " + nm(o.cpa_m) + ")";
                else if (e.a_stopped) c.did = "no duty: " + own.id + " was not under way when the situation began";
                else if (e.b_stopped) c.did = "no duty: " + other->id + " was not under way when the situation began";
                else c.did = "no duty in this situation";
                out.push_back(std::move(c));
                continue;
            }
            const Situation s = k.situation;
            const double t_close = e.closest_s > e.start_s ? e.closest_s : e.end_s;
            const double h0 = e.a_start.heading_deg, v0 = std::sqrt(geo::norm2(e.a_start.velocity));
            const double v_ref = std::max(v0, knot_ms);
            // The largest changes of heading and speed from the start up to the closest approach.
            std::vector<double> times{e.start_s, t_close};
            for (std::size_t j = 0; j < me.track.size(); ++j)
                if (const double tt = me.track.time(j); tt > e.start_s && tt < t_close) times.push_back(tt);
            for (const double tt : times) {
                const double dh = turn(h0, me.heading_at(tt));
                if (std::fabs(dh) > std::fabs(c.course_change_deg)) c.course_change_deg = dh;
                const double dv = (me.speed_at(tt) - v0) / v_ref;
                if (std::fabs(dv) > std::fabs(c.speed_change)) c.speed_change = dv;
            }
            const bool acted = std::isfinite(e.action_a.time_s) && e.action_a.time_s <= t_close;
            if (acted) {
                c.action_s = e.action_a.time_s;
                c.action_range_m = std::sqrt(geo::norm2(them.at(c.action_s) - me.at(c.action_s)));
            }
            const std::string& who = own.id;
            const std::string& whom = other->id;
            auto add = [&](const char* rule, double t, std::string asked, std::string did) {
                c.breaches.push_back({rule, t, frame.inverse(me.at(t)), std::move(asked), std::move(did)});
            };
            // What it did, in words.
            std::string action_words;
            if (acted) {
                std::vector<std::string> parts;
                if (std::fabs(c.course_change_deg) >= o.action_course_deg)
                    parts.push_back("altered course " + num(std::fabs(c.course_change_deg), 0) + " degrees to " +
                                    (c.course_change_deg > 0 ? "starboard" : "port"));
                if (std::fabs(c.speed_change) >= o.action_speed_change)
                    parts.push_back(std::string(c.speed_change < 0 ? "slowed" : "sped up") + " from " + kn(v0) + " to " + kn(v0 + c.speed_change * v_ref));
                if (parts.empty()) parts.push_back("altered course " + num(std::fabs(c.course_change_deg), 0) + " degrees");
                for (std::size_t j = 0; j < parts.size(); ++j) action_words += (j ? (j + 1 == parts.size() ? " and " : ", ") : "") + parts[j];
                action_words += " from " + clock(c.action_s) + ", " + nm(c.action_range_m) + " from " + whom;
            }
            const std::string held = who + " kept her course (" + course(h0) + ") and speed (" + kn(v0) + ") from " + clock(e.start_s) + ", " +
                                     nm(std::sqrt(geo::norm2(e.b_start.position - e.a_start.position))) + " from " + whom +
                                     ", to the closest approach, " + nm(e.closest_m) + " at " + clock(e.closest_s);
            c.did = acted ? who + " " + action_words : held;
            const std::string early_words = "early (begun at least " + nm(o.early_range_m) + " off), readily apparent (course altered at least " +
                                            num(o.min_course_deg, 0) + " degrees or speed changed by " + num(100 * o.min_speed_change, 0) +
                                            "%) and passing at least " + nm(o.cpa_m) + " clear";
            if (give) {
                c.role = "give-way";
                if (s == Situation::head_on) c.rules = {"14", "8"};
                else c.rules = {situation_rule(s), "16", "8"};
                if (!acted) {
                    std::string asked;
                    switch (s) {
                        case Situation::head_on: asked = "rule 14 (head-on with " + whom + "): both ships alter course to starboard, early and substantially (rule 8)"; break;
                        case Situation::overtaking: asked = "rule 13 (overtaking " + whom + "): keep out of the way of the ship overtaken, by early and substantial action (rule 16)"; break;
                        case Situation::crossing:
                            asked = "rule 15 (crossing, " + whom + " on the starboard side): keep out of the way, by early and substantial action (rule 16), avoiding crossing ahead";
                            break;
                    }
                    add(situation_rule(s), e.closest_s, asked, held);
                } else {
                    if (s == Situation::head_on && c.course_change_deg < o.action_course_deg)
                        add("14", c.action_s, "rule 14 (head-on with " + whom + "): alter course to starboard",
                            who + " " + action_words + (c.course_change_deg <= -o.action_course_deg ? ": a turn to port" : ": no turn to starboard"));
                    if (s == Situation::crossing) {
                        // Crossing ahead: where the ship crosses the other's heading line, is she ahead of it?
                        std::vector<double> ts{e.start_s, e.end_s};
                        for (const auto* m : {&me, &them})
                            for (std::size_t j = 0; j < m->track.size(); ++j)
                                if (const double tt = m->track.time(j); tt > e.start_s && tt < e.end_s) ts.push_back(tt);
                        std::sort(ts.begin(), ts.end());
                        auto lateral = [&](double tt) {
                            const double h = them.heading_at(tt) / deg;
                            const XY d{std::sin(h), std::cos(h)}, r = me.at(tt) - them.at(tt);
                            return std::pair{d.x * r.y - d.y * r.x, geo::dot(d, r)};
                        };
                        for (std::size_t j = 0; j + 1 < ts.size(); ++j) {
                            const double l0 = lateral(ts[j]).first, l1 = lateral(ts[j + 1]).first;
                            if (!((l0 < 0 && l1 >= 0) || (l0 > 0 && l1 <= 0))) continue;
                            const double tx = ts[j] + (ts[j + 1] - ts[j]) * l0 / (l0 - l1);
                            const double along = lateral(tx).second;
                            if (along > 0)
                                add("15", tx, "rule 15 (crossing, " + whom + " on the starboard side): avoid crossing ahead of her",
                                    who + " " + action_words + " and crossed " + num(along, 0) + " m ahead of " + whom + " at " + clock(tx));
                            break;
                        }
                    }
                    const bool late = c.action_range_m < o.early_range_m;
                    const bool small = std::fabs(c.course_change_deg) < o.min_course_deg && std::fabs(c.speed_change) < o.min_speed_change;
                    const bool close = e.closest_m < o.cpa_m;
                    if (late || small || close) {
                        std::vector<std::string> wrong;
                        if (late) wrong.push_back("late");
                        if (small) wrong.push_back("too small to be readily apparent");
                        if (close) wrong.push_back("passed " + nm(e.closest_m) + " from " + whom);
                        std::string w;
                        for (std::size_t j = 0; j < wrong.size(); ++j) w += (j ? (j + 1 == wrong.size() ? " and " : ", ") : "") + wrong[j];
                        const bool head_on = s == Situation::head_on;
                        add(head_on ? "8" : "16", c.action_s,
                            std::string(head_on ? "rule 8" : "rule 16 (with rule 8)") + ": the give-way ship's action " + early_words, who + " " + action_words + ": " + w);
                    }
                }
            } else if (stand) {
                c.role = "stand-on";
                c.rules = {situation_rule(s), "17"};
                if (acted) {
                    const bool other_acted = std::isfinite(e.action_b.time_s) && e.action_b.time_s <= c.action_s;
                    const bool allowed = c.action_range_m < o.early_range_m && !other_acted;
                    const std::string asked = "rule 17 (stand-on, " + whom + " gives way): keep course and speed; act only once " + whom +
                                              " is plainly not acting (no action while she is still " + nm(o.early_range_m) +
                                              " off) or collision cannot be avoided by her alone";
                    if (!allowed) {
                        add("17", c.action_s, asked,
                            who + " " + action_words +
                                (other_acted ? ", after " + whom + " had begun her own action at " + clock(e.action_b.time_s)
                                             : ", while " + whom + " still had room to act"));
                    } else if (s == Situation::crossing && c.course_change_deg <= -o.action_course_deg && k.bearing_of_b_deg > 180) {
                        add("17", c.action_s, "rule 17(c): a stand-on ship that acts does not alter course to port for a ship on her own port side",
                            who + " " + action_words);
                    }
                }
            }
            out.push_back(std::move(c));
        }
    }
    return out;
}

}  // namespace shoal::audit
