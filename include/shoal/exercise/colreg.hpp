#pragma once
/// COLREG situations between two ships of an exercise (the steering and sailing rules 13-17 of
/// the International Regulations for Preventing Collisions at Sea), judged at the moment the
/// two reference points first come within `range_m` of each other:
///
/// - *Relative bearing* of the other ship: the bearing from one reference point to the other,
///   clockwise from the ship's heading, in [0, 360).
/// - *Overtaking* (rule 13): a ship that sees the other more than 22.5 degrees abaft her beam
///   (relative bearing strictly between 112.5 and 247.5 degrees) is being overtaken; the other
///   is the overtaking ship and keeps out of the way (give-way), the overtaken ship stands on.
///   If each is abaft the other's beam, the faster over ground is taken as the overtaking one.
/// - *Head-on* (rule 14): headings reciprocal within `head_on_tolerance_deg` and each ship sees
///   the other within that tolerance of right ahead. Both ships alter course to starboard:
///   both are give-way, none is stand-on.
/// - *Crossing* (rule 15): any other case. The ship that has the other on her own starboard
///   side (relative bearing in (0, 180)) keeps out of the way; the other stands on. When each
///   has the other to starboard (nearly reciprocal, passing starboard to starboard), both give
///   way; when each has the other to port (passing port to port) neither does.
///
/// Then over the encounter (from that moment until the pair is out of range again, or one ship
/// ends) each ship's *action* (rules 16 and 17): the first fix from which her heading differs
/// from the heading at the start by at least `course_change_deg`, or her speed over ground by
/// at least `speed_change` of the speed at the start (of 1 knot if she was slower), and keeps
/// differing at every fix for at least `sustain_s` seconds.

#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include <shoal/geo/local_frame.hpp>
#include <shoal/geo/point.hpp>
#include <shoal/track/track.hpp>

namespace shoal::audit {

enum class Situation { head_on, crossing, overtaking };
const char* to_string(Situation s) noexcept;  ///< "head-on", "crossing", "overtaking"

/// Which ship of the pair (a, b).
enum class Party { a, b, both, neither };

struct ColregOptions {
    double range_m = 3704.0;            ///< a pair within this distance (reference points, metres) is an encounter (2 nm)
    double head_on_tolerance_deg = 6.0; ///< head-on: reciprocal headings and right ahead within this
    double course_change_deg = 10.0;    ///< an action: heading changed by at least this
    double speed_change = 0.2;          ///< or speed over ground by at least this fraction
    double sustain_s = 30.0;            ///< kept for at least this long
    /// A ship slower than this over ground (knots) at the start is taken as not under way
    /// (moored, at anchor, stopped): the rules give her no duty, so the pair has no give-way
    /// and no stand-on ship (the situation is still the geometry's).
    double under_way_kn = 0.5;
};

/// A ship at one moment, in local metres (x east, y north).
struct VesselAt {
    geo::XY position;
    double heading_deg = 0;  ///< true heading, clockwise from north
    geo::XY velocity;        ///< over ground, m/s
};

/// Relative bearing of `to` from `from`: clockwise from from's heading, in [0, 360).
double relative_bearing_deg(const VesselAt& from, geo::XY to);

struct Classification {
    Situation situation = Situation::crossing;
    Party give_way = Party::neither, stand_on = Party::neither;
    double bearing_of_b_deg = 0;  ///< relative bearing of b from a
    double bearing_of_a_deg = 0;  ///< relative bearing of a from b
};
Classification classify(const VesselAt& a, const VesselAt& b, double head_on_tolerance_deg = 6.0);

/// Closest point of approach if both kept their velocities: distance (m) and time from now
/// (s; negative when the ships are already opening, 0 when they do not move relative to each other).
struct Cpa {
    double distance_m = 0, time_s = 0;
};
Cpa cpa(const VesselAt& a, const VesselAt& b);

/// A ship's action in an encounter; time NaN: none.
struct Manoeuvre {
    bool course = false, speed = false;
    double time_s = NAN;
};

struct ColregEncounter {
    std::size_t a = 0, b = 0;  ///< indices in the tracks given, a < b
    double start_s = 0;        ///< first moment within range
    double end_s = 0;          ///< first moment out of range again after it (or the end of either track)
    VesselAt a_start, b_start; ///< both at the start
    Classification at_start;
    Cpa cpa_start;
    double closest_m = 0, closest_s = 0;  ///< least distance between the reference points while both are present
    geo::LonLat a_closest, b_closest;
    Manoeuvre action_a, action_b;
    bool a_stopped = false, b_stopped = false;  ///< slower than ColregOptions::under_way_kn at the start
};

/// Every pair of `tracks` (fix times strictly increasing, headings resolved) that comes within
/// options.range_m while both are present (a ship is absent across a fix interval longer than
/// `max_gap_s` or a jump), for which `wanted(a, b)` holds (null: all). Positions are linear
/// between fixes in `frame`; distances are exact on that motion. By (a, b).
/// Throws UsageError on bad options.
std::vector<ColregEncounter> find_situations(const std::vector<const track::Track*>& tracks, const geo::LocalFrame& frame,
                                             const ColregOptions& options, double max_gap_s,
                                             const std::function<bool(std::size_t, std::size_t)>& wanted = nullptr);
/// The same, each situation given to `found` as it is judged (by (a, b)) and none kept: for
/// callers that keep only some (a crowd has a situation for nearly every pair of ships).
void for_each_situation(const std::vector<const track::Track*>& tracks, const geo::LocalFrame& frame, const ColregOptions& options,
                        double max_gap_s, const std::function<bool(std::size_t, std::size_t)>& wanted,
                        const std::function<void(ColregEncounter&)>& found);

}  // namespace shoal::audit
