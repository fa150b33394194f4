#pragma once
/// Fingerprints of inputs as read, for the run header (RunInfo) when an input is no regular
/// file (standard input, a pipe) whose bytes cannot be read again: what was read stands for them.
#include <map>
#include <string>
#include <shoal/exercise/exercise.hpp>
#include <shoal/hull/hull.hpp>
#include <shoal/track/reader.hpp>
#include <shoal/track/vessels_table.hpp>

namespace shoal::report {

/// Roles as read (each entry, the default role).
std::string roles_fingerprint(const audit::Roles& roles);
/// The ship as read (name, contour, A,B,C,D, draught).
std::string hull_fingerprint(const hull::Hull& h);
/// The vessels as read (every field of every vessel).
std::string vessels_fingerprint(const std::map<std::string, track::VesselInfo>& vessels);

}  // namespace shoal::report
