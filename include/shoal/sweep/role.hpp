#pragma once
/// A vessel's role in an exercise: the trainee (own ship, audited) or a target (its traffic).
/// Each swept track carries one (TrackSummary::role); exercises (exercise/exercise.hpp) decide
/// it from the exercise file, the role column or the default.

#include <string>

namespace shoal::audit {

enum class Role { trainee, target };
const char* to_string(Role r) noexcept;  ///< "trainee", "target"

/// Parses a role value ("trainee", "own", "own ship", "own_ship", "target"; any case); false if
/// it is none of them.
bool parse_role(const std::string& s, Role& role);

}  // namespace shoal::audit
