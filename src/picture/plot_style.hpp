#pragma once
/// The picture's style: its colours, the event kinds' colours and order, text and numbers as
/// the SVG writes them.
/// Private to src/picture (plot.cpp puts the parts on the page); namespace plot_parts.

#include <cstddef>
#include <string>
#include <string_view>
#include <shoal/sweep/sweep.hpp>


namespace shoal::report::plot_parts {

using audit::Event;
using audit::EventKind;
using geo::Box;
using geo::LonLat;
using geo::XY;

inline constexpr double pi = 3.14159265358979323846;

// Colours: pale water, sand land, grey "no chart"; red for groundings, amber for close passes,
// muted blue, grey and green for the contacts that are not groundings (alongside, in contact
// at the first fix, in an expected-contact area).
inline constexpr const char* water_fill = "#f3f8fc";
inline constexpr const char* land_fill = "#e8dec3";
inline constexpr const char* outside_fill = "#d4d4d4";
inline constexpr const char* coast_stroke = "#3b3b3b";
inline constexpr const char* red = "#d62728";
inline constexpr const char* red_dark = "#9e0e12";
inline constexpr const char* amber = "#f0a000";
inline constexpr const char* amber_dark = "#8f5600";
inline constexpr const char* steel = "#4a7fa8";
inline constexpr const char* steel_dark = "#2b5478";
inline constexpr const char* slate = "#6a7f95";
inline constexpr const char* slate_dark = "#3e4f60";
inline constexpr const char* green = "#33a02c";
inline constexpr const char* green_dark = "#1d6419";
inline constexpr const char* teal = "#17becf";       ///< the chart disagrees with the traffic
inline constexpr const char* teal_dark = "#0b6f7a";
inline constexpr const char* contact_violet = "#8a76b8";  ///< a track with contacts, none of them a grounding
inline constexpr const char* clear_grey = "#7f8b96";
inline constexpr const char* trainee_blue = "#0a58ca";  ///< exercise mode: a trainee's track
inline constexpr const char* trainee_dark = "#063a87";
inline constexpr const char* no_entry_stroke = "#b42318";
inline constexpr const char* speed_area_stroke = "#8f5600";
inline constexpr const char* cpa_ink = "#111111";
inline constexpr const char* ink = "#222222";
inline constexpr const char* font_family = "DejaVu Sans, Verdana, Arial, Helvetica, sans-serif";

/// Fill and dark (stroke, text) colours of an event kind.
struct KindStyle {
    const char* fill;
    const char* dark;
};

/// Every kind, most severe first: the order of the zoomed panels.
inline constexpr EventKind kinds_by_severity[] = {EventKind::grounding, EventKind::alongside, EventKind::contact_at_start,
                                           EventKind::expected_contact, EventKind::close_pass, EventKind::chart_disagrees};

/// Appends `v` with one decimal ("12.3", "12", "0"): a tenth of a pixel is plenty.
void put(std::string& out, double v);
std::string num(double v);
/// Characters (code points) in UTF-8 text, for estimating its width.
std::size_t glyphs(std::string_view s);
/// Rough width in px of `s` at `size` px in a sans-serif font (DejaVu Sans is among the widest).
double text_width(std::string_view s, double size);
/// `s` cut (with an ellipsis) to about `max_px` at `size` px.
std::string fit_text(const std::string& s, double size, double max_px);
std::string metres_text(double m);
KindStyle kind_style(EventKind k) noexcept;
/// The place of `k` in kinds_by_severity (0 to 5).
std::size_t severity(EventKind k) noexcept;

}  // namespace shoal::report::plot_parts
