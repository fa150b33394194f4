#pragma once
/// The AIS "type of ship and cargo" (ITU-R M.1371, message 5 / 19 / 24 B, table 53): what the
/// number means, the one table of it in shoal (the report's `ship_type_text`).

#include <string>

namespace shoal::track {

/// The meaning of AIS ship type `type` (0-255) in words: "Not available" (0), "Fishing" (30),
/// "Tug" (52), "Cargo, all ships of this type" (70), "Tanker, hazardous category A" (81), ...
/// The first digit of 20-29 and 40-99 is the kind of ship, the second the cargo: 0 all ships
/// of this type, 1-4 carrying dangerous goods, harmful substances or marine pollutants of
/// hazard category A-D (M.1371-5 names them X, Y, Z and OS), 5-8 reserved for future use,
/// 9 no additional information. 1-19, 38, 39 and 200-255 are reserved for future use,
/// 100-199 for regional use. "" for a number outside 0-255 (-1: not known).
std::string ship_type_text(int type);

}  // namespace shoal::track
