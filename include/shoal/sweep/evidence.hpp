#pragma once
/// Two worlds. In a simulator exercise the chart is the world: a contact under way is a
/// grounding (the sweep's kinds, sweep.hpp). In real traffic the chart is a model: a 1:250,000
/// coast does not draw harbour basins, piers or canals, and fixes minutes apart cut corners.
/// There the vessel's own motion and the whole run's traffic are evidence too: a ship that runs
/// aground stops where it touched, suddenly, and stays; a ship that arrives slows over minutes
/// and lies where others lie; a ship that sails on through charted land shows that the chart
/// lacks water there. This file holds those rules (docs/method.md, section 7).
///
/// The work is in three steps, so that shards of a run decide as one run does:
///   1. gather_evidence, per track (after its sweep): the track's stays, the fixes under way
///      on charted land, and for each contact the facts around it (the fixes that bracket it,
///      their speeds and ages, where and how soon the vessel came to rest, for how long);
///   2. learn_traffic, over every track read: places where vessels stay (learned berths) and
///      cells where vessels under way pass over charted land (water the chart lacks);
///   3. decide_kinds, per track: each contact's kind and grade, from its facts and the places,
///      and one event per stay.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <shoal/sweep/sweep.hpp>
#include <shoal/geo/local_frame.hpp>
#include <shoal/grid/coast_grid.hpp>
#include <shoal/track/track.hpp>

namespace shoal::audit {

enum class World : std::uint8_t {
    simulated,  ///< the chart is the world: any contact under way is a grounding
    real,       ///< the chart is a model: the vessel's motion and the run's traffic are evidence too
};
const char* to_string(World w) noexcept;  ///< "simulated", "real"
/// "simulated" or "real" (case-sensitive); none for anything else.
std::optional<World> parse_world(std::string_view text) noexcept;

/// The real world's rules; every default has its reason in docs/method.md, section 7.
struct EvidenceOptions {
    /// Seen under way: the speed at the fix before the contact (knots). Berthing is done under
    /// 1 kn and a vessel manoeuvring in a basin at 2 kn; a grounding worth the name is faster.
    double under_way_kn = 3.0;
    /// Abrupt: the speed falls to rest at this rate or faster (knots a second). DMA's
    /// AisAbnormal grounding indicator: from over 7 kn to under 1 kn within 30 s (0.2 kn/s,
    /// 0.1 m/s^2); a ship berthing slows at a tenth of that.
    double abrupt_kn_s = 0.2;
    /// The deceleration is seen only when the fixes around the contact lie within this many
    /// seconds of it (else it happened inside a gap: its start is an interval).
    double abrupt_window_s = 60.0;
    /// Lying where it touched: a stay at least this long (seconds; minutes, as the issue's
    /// AisAbnormal holds 60 s and a refloated touch lasts seconds).
    double ground_stay_s = 300.0;
    /// A contact first seen after a gap is a grounding inside the gap only when the gap is at
    /// most this long (seconds): beyond, "seen under way before" says little.
    double max_unseen_s = 3600.0;
    /// A contact that reaches no fix, between fixes at least this far apart (seconds), exists
    /// only on the straight line between them.
    double between_fixes_s = 60.0;
    /// A learned berth: stays of vessels within this many metres of each other.
    double berth_radius_m = 300.0;
    /// Water the chart lacks: fixes under way on charted land, counted in square cells of this side.
    double water_cell_m = 250.0;
    /// The chart's positional tolerance (metres; 0.5 mm at its compilation scale); NaN: not known.
    double chart_tolerance_m = NAN;
};

/// Step 1, for one swept track (`t` as swept: wild fixes dropped, motion resolved): fills
/// r.stays, r.over_land, r.summary.cadence_s and hull_length_m, and each contact's
/// Event::evidence facts. `grid` tells charted land; `frame` projects.
void gather_evidence(const track::Track& t, double hull_length_m, const geo::LocalFrame& frame, const grid::CoastGrid& grid,
                     const SweepOptions& sweep, const EvidenceOptions& options, TrackResult& r);
/// The same with the fixes' local positions already known (`positions[i]` fix i's, in `frame`:
/// what SweepContext::positions receives from the track's sweep).
void gather_evidence(const track::Track& t, const std::vector<geo::XY>& positions, double hull_length_m, const geo::LocalFrame& frame,
                     const grid::CoastGrid& grid, const SweepOptions& sweep, const EvidenceOptions& options, TrackResult& r);

/// The traffic a track shows, without sweeping it (a track of another shard): r.stays and
/// r.over_land only.
TrackResult traffic_of(const track::Track& t, double hull_length_m, const geo::LocalFrame& frame, const grid::CoastGrid& grid,
                       const SweepOptions& sweep, const EvidenceOptions& options);

/// A place the run's traffic teaches (a layer of the report).
struct LearnedPlace {
    enum class Kind : std::uint8_t {
        berth,   ///< vessels stay here: two stays or more (several vessels, or one coming back)
        water,   ///< vessels under way pass over charted land here: water the chart lacks
    };
    Kind kind = Kind::berth;
    geo::XY local;           ///< centre (berth: the mean of its stays; water: the cell's centre)
    geo::LonLat position;
    double size_m = 0;       ///< berth: the radius that holds its stays; water: the cell's side
    std::size_t vessels = 0; ///< distinct vessels
    std::size_t count = 0;   ///< berth: visits (stays of a vessel that did not go away between count once); water: fixes
    double hours = 0;        ///< berth: hours of the stays together
    double first_s = NAN, last_s = NAN;
};
const char* to_string(LearnedPlace::Kind k) noexcept;  ///< "learned_berth", "chart_lacks_water"

/// Step 2: what the run's traffic teaches. `tracks` are every track read (swept, or
/// traffic_of), in any order (the places do not depend on it); `ids` their vessel ids.
struct Traffic {
    std::vector<LearnedPlace> places;  ///< berths, then water cells; each sorted by position
    /// Per track, per stay: how many other stays lie within the berth radius and did not begin
    /// during it (responders, salvage and queues arriving after a vessel stopped do not make
    /// its place a berth). Indexed like the tracks given.
    std::vector<std::vector<std::size_t>> berth_stays;
    /// Of those, the stays of the same track's other visits (a ferry's other calls).
    std::vector<std::vector<std::size_t>> own_visits;
};
Traffic learn_traffic(const std::vector<const TrackResult*>& tracks, const std::vector<std::string>& ids, const geo::LocalFrame& frame,
                      const EvidenceOptions& options);

/// Step 3, for one track (`berth_stays`, `own_visits`: Traffic's of it): each contact's kind,
/// grade and reason by the real world's rules, then one event per stay; recounts r.summary's
/// kinds.
void decide_kinds(TrackResult& r, const std::vector<std::size_t>& berth_stays, const std::vector<std::size_t>& own_visits,
                  const EvidenceOptions& options);

/// The simulated world's grades: every contact's kind stands by the chart (grade 4), with its
/// reason; recounts nothing.
void grade_simulated(TrackResult& r);

/// The simulated world's one event per stay (docs/method.md, "One event per stay"): a contact
/// that is `alongside` or `in_contact_at_start` and follows such a contact of the same track is
/// part of it when the vessel lay at one place, not under way, from the end of the first to the
/// start of the second: every fix from the last one at or before the first's end to the first
/// one at or after the second's start is stopped or under `under_way_kn` (EvidenceOptions::
/// under_way_kn: a moored vessel's SOG noise reaches 1-2 kn), lies within
/// `options.stop_diameter_m` of where the first contact began, and comes after no jump.
/// Gaps between them count as the stay when the fixes on both sides say so. The merged event
/// keeps the first's kind, start and evidence, ends at the last's end, has the deepest
/// penetration and adds up the pieces. Groundings, expected contacts, chart disagreements and
/// close passes are never merged, nor merged into. `track` is the swept track (motion resolved).
/// Recounts the summary's contacts.
void merge_stays(TrackResult& r, const track::Track& track, const SweepOptions& options, double under_way_kn = EvidenceOptions{}.under_way_kn);

/// The simulated world's contacts that began inside a gap of the fixes: an `in_contact_at_start`
/// after a gap (not a jump, not the track's start) of at most `evidence.max_unseen_s`, whose fix
/// before the gap was seen clear and under way (not stopped, at `sweep.berthing_speed_kn` or
/// more) and lies no farther from the first fix after it than 1.5 times that speed over the gap
/// plus the hull's length and 50 m, is a grounding: the chart is the world, and the vessel came
/// into contact under way, unseen. Its `start_not_before` is that fix, with its speed and age as
/// evidence. Before, such a vessel, last seen clear at 11 kn and lying aground after a gap of
/// 35 min, was only "already in contact at the first fix after the gap". Recounts the summary's
/// contacts.
void ground_inside_gaps(TrackResult& r, const track::Track& track, const SweepOptions& sweep, const EvidenceOptions& evidence,
                        double hull_length_m);

}  // namespace shoal::audit
