#pragma once
// How contact_regions searches (src/check/contacts.cpp), for the tests that pin its shortcuts
// to the full search: each shortcut may give another deepest point of the same depth (within
// the micrometre of include/shoal/check/contacts.hpp), never another depth.

#include <vector>

#include <shoal/check/contacts.hpp>

namespace shoal::check::detail {

struct ContactSearch {
    /// The first attempt's reach (local metres; at least a thousandth of the hull's extent):
    /// grown fourfold while a depth reaches it, so the answer does not depend on it.
    double first_reach_m = 2.0;
    /// The maximum of a two-site bound (a point on the ridge between two boundary pieces, the
    /// medial axis, where the deepest point lies) tried as a deepest point itself.
    bool ridge_candidates = true;
    /// The pairs of the two nearest sites with a third each bound an interior cell as well.
    bool third_site = true;
    /// A convex hull's reach is also bounded by two slabs along and across its longest edge
    /// (grown by the reach), not by the box alone: a hull at 45 degrees fills half of its box,
    /// and the segments of the box's corners are no nearer than the reach to it.
    bool hull_slabs = true;
    /// An interior cell of a convex hull is its parent's polygon (the parent's box cut to the
    /// hull) cut to the cell's box, not the cell's box cut to the hull again.
    bool cut_from_parent = true;
};

/// contact_regions(detector, pose), searched as `how` says.
std::vector<ContactRegion> contact_regions(const Detector& detector, const LocalPose& pose, const ContactSearch& how);

}  // namespace shoal::check::detail
