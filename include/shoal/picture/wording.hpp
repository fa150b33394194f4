#pragma once
/// Events and times in words: one wording for the picture's tooltips and titles (plot.hpp) and
/// the debrief's pages (debrief.hpp).

#include <string>

#include <shoal/sweep/sweep.hpp>

namespace shoal::report {

/// `v` with `decimals` decimals ("9.8", "182", never "-0.0"); `not_finite` when it is not finite.
std::string fixed_text(double v, int decimals, const char* not_finite = "?");
/// "19:02:33Z" (UTC time of day, cut from the ISO time, not rounded); `unknown` for no time.
std::string clock_text(double t, const char* unknown = "--:--:--");
/// "2014-08-15 19:02:33Z"; "?" for no time.
std::string date_clock_text(double t);

/// A duration in words: "0 s", "4.2 s", "42 s", "3 min 07 s", "2 h 05 min"; "duration unknown".
std::string duration_words(double seconds);

/// Exercise time: "T+12:30" (minutes and seconds after `start_s`, cut like clock_text, not
/// rounded), "T+1:02:03" past the hour, "T-0:05" before it; "T+?" when either is not finite.
std::string exercise_time_text(double t, double start_s);

/// An event in words, as the picture's tooltips say it: track (and name), kind, what was hit,
/// start and end (UTC), duration, speed and its source, penetration or clearance, heading,
/// and the evidence for the kind.
std::string event_description(const audit::TrackSummary& track, const audit::Event& event);

}  // namespace shoal::report
