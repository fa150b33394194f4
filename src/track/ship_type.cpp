#include "track/ship_type.hpp"

namespace shoal::track {

namespace {

/// Ships of 20-29 and 40-99: the kind (first digit), then the cargo (second digit).
const char* kind_of(int first_digit) {
    switch (first_digit) {
        case 2: return "Wing in ground (WIG)";
        case 4: return "High speed craft (HSC)";
        case 6: return "Passenger";
        case 7: return "Cargo";
        case 8: return "Tanker";
        case 9: return "Other type";
        default: return nullptr;
    }
}

constexpr const char* cargo_of[10] = {
    "all ships of this type",  "hazardous category A",    "hazardous category B",    "hazardous category C",
    "hazardous category D",    "reserved for future use", "reserved for future use", "reserved for future use",
    "reserved for future use", "no additional information"};

/// 30-39 (vessels) and 50-59 (special craft), by their second digit.
constexpr const char* vessels[10] = {"Fishing",
                                     "Towing",
                                     "Towing, length exceeds 200 m or breadth exceeds 25 m",
                                     "Dredging or underwater operations",
                                     "Diving operations",
                                     "Military operations",
                                     "Sailing",
                                     "Pleasure craft",
                                     "Reserved for future use",
                                     "Reserved for future use"};
constexpr const char* special_craft[10] = {"Pilot vessel",
                                           "Search and rescue vessel",
                                           "Tug",
                                           "Port tender",
                                           "Anti-pollution equipment",
                                           "Law enforcement",
                                           "Spare - local vessel",
                                           "Spare - local vessel",
                                           "Medical transport",
                                           "Noncombatant ship according to RR Resolution No. 18"};

}  // namespace

std::string ship_type_text(int type) {
    if (type < 0 || type > 255) return "";
    if (type == 0) return "Not available";
    if (type < 20 || type >= 200) return "Reserved for future use";
    if (type >= 100) return "Reserved for regional use";
    const int first = type / 10, second = type % 10;
    if (first == 3) return vessels[second];
    if (first == 5) return special_craft[second];
    return std::string(kind_of(first)) + ", " + cargo_of[second];
}

}  // namespace shoal::track
