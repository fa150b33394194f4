// A vessel's role in an exercise (sweep/role.hpp).
#include <shoal/sweep/role.hpp>

#include <string_view>

#include <shoal/track/track.hpp>

namespace shoal::audit {

const char* to_string(Role r) noexcept { return r == Role::target ? "target" : "trainee"; }

bool parse_role(const std::string& s, Role& role) {
    const char* v = track::role_value(s);
    if (!v) return false;
    role = std::string_view(v) == "target" ? Role::target : Role::trainee;
    return true;
}

}  // namespace shoal::audit
