#pragma once
/// A chart's compilation scale and the positional tolerance that goes with it. A line drawn on
/// a chart of scale 1:N is placed to about 0.5 mm on paper (the US National Map Accuracy
/// Standard's 1/50 inch at 1:20,000 or smaller is 0.508 mm), so N x 0.5 mm on the ground: 125 m
/// for GSHHG full (about 1:250,000), 7.5 m for a 1:15,000 harbour cell.

#include <optional>
#include <string>
#include <vector>

namespace shoal::coast {

/// The compilation scale denominator of the S-57 charts among `paths` (the DSPM record's
/// CSCALE; the largest, the coarsest, when there are several); none when no S-57 chart gives one.
/// Paths that are not S-57 charts, or cannot be opened, are passed over (they are read, and
/// their errors told, elsewhere).
std::optional<double> compilation_scale(const std::vector<std::string>& paths);

/// The positional tolerance of a chart of scale 1:`scale`, metres: 0.5 mm at that scale.
constexpr double positional_tolerance_m(double scale) noexcept { return scale * 0.0005; }

}  // namespace shoal::coast
