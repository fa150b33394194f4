// The picture's style: its colours, the event kinds' colours and order, text and numbers as
// the SVG writes them.
#include "picture/plot_style.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <iterator>
#include <unordered_map>
#include <unordered_set>

#include <shoal/picture/plot.hpp>
#include <shoal/picture/wording.hpp>
#include <shoal/report/markup.hpp>
#include <shoal/report/run_info.hpp>
#include <shoal/util/error.hpp>
#include "picture/event_phrases.hpp"

namespace shoal::report::plot_parts {

using namespace detail;  // the event phrases (picture/event_phrases.hpp)

// ---------------------------------------------------------------- text and numbers

void put(std::string& out, double v) {
    if (!std::isfinite(v)) v = 0;
    char b[40];
    int n = std::snprintf(b, sizeof b, "%.1f", v);
    if (n >= 2 && b[n - 2] == '.' && b[n - 1] == '0') n -= 2;
    if (n == 2 && b[0] == '-' && b[1] == '0') {
        b[0] = '0';
        n = 1;
    }
    out.append(b, static_cast<std::size_t>(n));
}

std::string num(double v) {
    std::string s;
    put(s, v);
    return s;
}


std::size_t glyphs(std::string_view s) {
    return static_cast<std::size_t>(
        std::count_if(s.begin(), s.end(), [](char ch) { return (static_cast<unsigned char>(ch) & 0xC0) != 0x80; }));
}

double text_width(std::string_view s, double size) { return static_cast<double>(glyphs(s)) * 0.6 * size; }

std::string fit_text(const std::string& s, double size, double max_px) {
    const auto max_glyphs = static_cast<std::size_t>(std::max(4.0, std::floor(max_px / (0.6 * size))));
    if (glyphs(s) <= max_glyphs) return s;
    std::string cut;
    std::size_t count = 0;
    for (char ch : s) {
        if ((static_cast<unsigned char>(ch) & 0xC0) != 0x80 && ++count > max_glyphs - 1) break;
        cut += ch;
    }
    return cut + "\xE2\x80\xA6";
}


std::string metres_text(double m) {
    char b[40];
    if (m >= 1000) std::snprintf(b, sizeof b, "%g km", m / 1000);
    else std::snprintf(b, sizeof b, "%g m", m);
    return b;
}

// ---------------------------------------------------------------- the kinds' colours and order
// (what an event is, in words: wording.cpp)


KindStyle kind_style(EventKind k) noexcept {
    switch (k) {
    case EventKind::grounding: return {red, red_dark};
    case EventKind::alongside: return {steel, steel_dark};
    case EventKind::contact_at_start: return {slate, slate_dark};
    case EventKind::expected_contact: return {green, green_dark};
    case EventKind::close_pass: return {amber, amber_dark};
    case EventKind::chart_disagrees: return {teal, teal_dark};
    }
    return {red, red_dark};
}


std::size_t severity(EventKind k) noexcept {
    switch (k) {
    case EventKind::grounding: return 0;
    case EventKind::alongside: return 1;
    case EventKind::contact_at_start: return 2;
    case EventKind::expected_contact: return 3;
    case EventKind::close_pass: return 4;
    case EventKind::chart_disagrees: return 5;
    }
    return 0;
}


}  // namespace shoal::report::plot_parts
