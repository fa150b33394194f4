#pragma once
/// Wild fixes: positions a vessel cannot have reached. A fix that implies an impossible speed
/// against its neighbours (a jump and back, a fix at 0,0, a receiver's bogus position) is an
/// outlier: dropped, counted and listed with its line, and never swept through. A jump that
/// persists (the fixes after it agree with each other, not with the ones before) is not an
/// outlier but a break: a new piece of track starts there, as after a gap.

#include <cstddef>
#include <string>
#include <vector>

#include <shoal/track/track.hpp>

namespace shoal::track {

struct WildFixOptions {
    /// Fastest plausible speed over ground, knots (high-speed craft reach 40-50 kn).
    double max_speed_kn = 60.0;
    /// Distance always allowed between two fixes, metres, whatever the time between them:
    /// GPS and AIS position error (fixes a fraction of a second apart from two receivers).
    double tolerance_m = 50.0;
    /// A fix that leaves the track is an outlier when one of the fixes in the next
    /// `lookahead_s` seconds (at most `lookahead` of them) comes back: is plausible from the
    /// last good fix and not from the jumped one (or nearer the good one); otherwise the jump
    /// persists.
    std::size_t lookahead = 256;
    double lookahead_s = 300.0;
    /// A gap longer than this (the sweep's --max-gap) starts afresh: the fix after it is not
    /// judged against the one before.
    double max_gap_s = 600.0;
};

/// One dropped fix, for the report.
struct WildFix {
    std::size_t line = 0;   ///< its line (or point number) in the file
    double time_s = 0;
    geo::LonLat position;
    double implied_kn = 0;  ///< speed it implies from the last good fix (INFINITY: at 0,0 or the same time)
    std::string why;        ///< "position 0,0", "jump of 5.2 km in 10 s (1011 kn) and back", "lone fix between jumps"
};

/// True when `b` can follow `a`: the distance between them is at most
/// tolerance_m + max_speed_kn x the time between them.
bool plausible(const Fix& a, const Fix& b, const WildFixOptions& options) noexcept;

/// Drops the wild fixes of `track` (fixes sorted by time) and marks with Fix::jump_before the
/// first fix after each jump that persists. Rules, in order:
///  - a fix at 0,0 (within 1e-7 degrees) is wild;
///  - walking the fixes in time order, a fix not plausible from the last good fix is wild when
///    a fix of the next `lookahead_s` comes back (plausible from that good fix, and not from
///    the jumped one or nearer the good one): every fix up to the returning one is wild;
///    otherwise a new piece starts at it. After a gap over max_gap_s the walk starts afresh;
///  - a piece of a single fix with a jump on one side agrees with nothing: it is wild too,
///    when another piece holds two fixes or more (of a track of lone fixes, none can be told
///    wild: each stays, a piece of its own);
///  - a spike against the vessel's own SOG: a fix whose legs from and to its neighbours are
///    both sailed faster than max(2 x SOG, SOG + 10 kn) (after tolerance_m), while the two
///    neighbours' own displacement agrees with their SOG (within half of it + 2 kn), is wild.
/// Returns the dropped fixes in time order.
std::vector<WildFix> drop_wild_fixes(Track& track, const WildFixOptions& options = {});

}  // namespace shoal::track
