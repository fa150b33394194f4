// A coastline's counts and the names of its kinds (coastline.hpp): what a grid's user needs of
// it, apart from its import with OGR (coastline.cpp).
#include <shoal/coast/coastline.hpp>

#include <algorithm>

namespace shoal::coast {

std::uint64_t Coastline::vertex_count() const noexcept {
    std::uint64_t n = 0;
    for (const auto& p : polylines) n += p.points.size();
    return n;
}

bool Coastline::has_land_side() const noexcept {
    return std::any_of(polylines.begin(), polylines.end(), [](const Polyline& p) { return p.land_left; });
}

std::uint64_t Coastline::count(HazardKind kind) const noexcept {
    return static_cast<std::uint64_t>(
        std::count_if(polylines.begin(), polylines.end(), [kind](const Polyline& p) { return p.hazard.kind == kind; }));
}

const char* to_string(HazardKind k) noexcept {
    switch (k) {
    case HazardKind::land: return "land";
    case HazardKind::shallow: return "shallow";
    case HazardKind::danger: return "danger";
    case HazardKind::structure: return "structure";
    }
    return "?";
}

const char* to_string(DangerKind k) noexcept {
    switch (k) {
    case DangerKind::none: return "";
    case DangerKind::rock: return "rock";
    case DangerKind::wreck: return "wreck";
    case DangerKind::obstruction: return "obstruction";
    }
    return "?";
}

}  // namespace shoal::coast
