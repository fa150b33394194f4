#pragma once
/// A ship's conduct under the steering and sailing rules (COLREG rules 8 and 13-17), read from
/// its track in each situation (colreg.hpp) with another ship: which rules applied and whether
/// what it did met them. The `colreg` criterion of an assessment file (assessment.hpp) scores
/// it; docs/user-guide.md ("Conduct under the rules") gives every reading and its source.
///
/// The situation is classified when the pair first comes within `range_m` (head-on within
/// `head_on_deg`; overtaking from 112.5 to 247.5 degrees relative bearing). The rules then ask
/// something only when there is a risk of collision: the CPA projected at that moment is under
/// `cpa_m` and still ahead, or the ships did pass closer than `cpa_m`. An *action* is the first change of heading by `action_course_deg`
/// or of speed by `action_speed_change` (a fraction) kept `sustain_s` seconds, before the
/// closest approach; its *size* is the largest change of heading (signed, + to starboard) and
/// of speed from the start up to the closest approach.
///
/// - Give-way (rule 13 overtaking, 15 crossing; both ships in a head-on situation, 14): a ship
///   that does not act breaches its situation's rule. One that acts breaches rule 16 (8 in a
///   head-on situation) when the action begins with the ships closer than `early_range_m`
///   (not early), is smaller than `min_course_deg` of course and `min_speed_change` of speed
///   (not readily apparent), or still leaves a closest approach under `cpa_m` (not well clear);
///   rule 14 when in a head-on situation it turns to port or does not alter course to
///   starboard; rule 15 when in a crossing it crosses ahead of the other ship.
/// - Stand-on (rule 17; the ship overtaken, or crossing with the other on her port side): any
///   action breaches rule 17 unless it begins with the ships closer than `early_range_m` while
///   the give-way ship has not yet acted (17(a)(ii), 17(b)); one so allowed still breaches 17(c)
///   when in a crossing it turns to port for a ship on her own port side.
/// A ship that is stopped (ColregOptions::under_way_kn) or in a situation without risk has no
/// duty and no breach.

#include <cstddef>
#include <string>
#include <vector>

#include <shoal/exercise/colreg.hpp>

namespace shoal::audit {

struct ConductOptions {
    double range_m = 3704.0;          ///< the situation is judged when the pair first comes within this (2 nm)
    double head_on_deg = 5.0;         ///< head-on: reciprocal and right ahead within this (DNV's sector)
    double cpa_m = 926.0;             ///< risk of collision: CPA at the start under this; well clear: passing at least this (0.5 nm)
    double early_range_m = 1852.0;    ///< an early action begins with the ships at least this far apart (1 nm)
    double min_course_deg = 30.0;     ///< readily apparent: course altered by at least this
    double min_speed_change = 0.5;    ///< or speed changed by at least this fraction (half)
    double action_course_deg = 10.0;  ///< an action: heading changed by at least this
    double action_speed_change = 0.2; ///< or speed by this fraction
    double sustain_s = 30.0;          ///< kept this long
};

/// One rule not met.
struct ConductBreach {
    std::string rule;  ///< "8", "13", "14", "15", "16", "17"
    double time_s = 0; ///< the moment: the action's start, else the closest approach
    geo::LonLat at;    ///< the ship there
    std::string asked, did;  ///< what the rule asked, what the ship did
};

/// A ship's conduct in one situation with another ship.
struct Conduct {
    std::size_t other = 0;            ///< index in the `others` given
    ColregEncounter situation;        ///< the ship judged is `a`
    std::string role;                 ///< "give-way", "stand-on" or "" (no duty)
    std::vector<std::string> rules;   ///< the rules that applied
    double action_s = NAN;            ///< when it acted (NaN: it did not)
    double course_change_deg = 0;     ///< the largest heading change before the closest approach, + starboard
    double speed_change = 0;          ///< the largest speed change, a fraction of the speed at the start
    double action_range_m = NAN;      ///< the distance between the ships when it acted
    /// What the ship did, in words: how it acted (or that it kept its course and speed) when it
    /// had a duty; why it had none otherwise (no risk of collision, no duty in the situation).
    std::string did;
    std::vector<ConductBreach> breaches;  ///< empty: every rule met
};

/// `own`'s situations with each of `others` (motion resolved, fix times increasing), judged.
/// Throws UsageError on bad options.
std::vector<Conduct> judge_conduct(const track::Track& own, const std::vector<const track::Track*>& others, const geo::LocalFrame& frame,
                                   const ConductOptions& options, double max_gap_s);

}  // namespace shoal::audit
