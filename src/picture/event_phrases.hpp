#pragma once
/// The phrases an event's wording is made of (private to src/picture): the picture's titles,
/// legend and tooltips use them one by one, event_description (wording.hpp) whole.

#include <cstddef>
#include <string>

#include <shoal/sweep/sweep.hpp>

namespace shoal::report::detail {

/// "1 track", "3 tracks".
std::string plural(std::size_t n, const char* one, const char* many);
/// "3 groundings", "2 alongside", "37 in contact at the start", "1 expected contact", "8 close passes".
std::string count_text(audit::EventKind k, std::size_t n);
/// What was hit when it is not land: "shallow 3.6 m", "rock", "wreck 2.1 m", "pier 'Pier 25'";
/// "" for land.
std::string hazard_text(const audit::Event& e);
/// The kind in words: "grounding", "alongside (not a grounding)", "close pass", ...
std::string kind_words(const audit::Event& e);
/// "9.8 kn SOG", "0.3 kn from positions", "speed unknown".
std::string speed_text(const audit::Event& e);
/// " at contact" (a contact whose speed is known), " at least clearance" (a close pass's), "".
std::string speed_when(const audit::Event& e);
/// "heading 182°" (with its source when `source`), "heading unknown (hull circle)".
std::string heading_text(const audit::Event& e, bool source);
/// "penetration 1.2 m" (contacts), "least clearance 12.3 m" (close passes).
std::string depth_text(const audit::Event& e);
/// "track 230123456 AAVA" (the name only when it says more than the id).
std::string track_text(const audit::TrackSummary& t);
/// The evidence for the kind, for tooltips: "stopped after 40 s; reference point 3.2 m inside
/// land; AIS status moored; ...".
std::string evidence_text(const audit::Event& e);

}  // namespace shoal::report::detail
