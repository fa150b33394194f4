// Label placement: labels set where they overlap nothing placed before, inside the panel.
#include "picture/plot_labels.hpp"

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

// ---------------------------------------------------------------- labels


void leader(std::string& out, XY anchor, const Rect& box, double min_px, const char* colour) {
    const XY near{std::clamp(anchor.x, box.x0, box.x1), std::clamp(anchor.y, box.y0, box.y1)};
    if (geo::distance(anchor, near) < min_px) return;
    out += "<line class=\"leader\" x1=\"" + num(anchor.x) + "\" y1=\"" + num(anchor.y) + "\" x2=\"" + num(near.x) + "\" y2=\"" +
           num(near.y) + "\" stroke=\"" + colour + "\" stroke-width=\"0.8\"/>\n";
}

void label(std::string& out, const Rect& box, const std::string& text, double size, const char* colour,
           const char* cls, bool bold) {
    out += "<g class=\"" + std::string(cls) + "\"><rect x=\"" + num(box.x0) + "\" y=\"" + num(box.y0) + "\" width=\"" +
           num(box.w()) + "\" height=\"" + num(box.h()) +
           "\" rx=\"2\" fill=\"#ffffff\" fill-opacity=\"0.8\"/><text x=\"" + num(box.x0 + 2) + "\" y=\"" +
           num(box.y0 + size * 0.95 + 1) + "\" font-size=\"" + num(size) + "\" fill=\"" + colour + "\"" +
           (bold ? " font-weight=\"bold\"" : "") + ">" + markup_text(text) + "</text></g>\n";
}


Labels::Labels(Rect bounds) : m_bounds(bounds) {
    m_cols = std::max(1, static_cast<int>(std::ceil(bounds.w() / bucket_px)));
    m_rows = std::max(1, static_cast<int>(std::ceil(bounds.h() / bucket_px)));
    m_buckets.resize(static_cast<std::size_t>(m_cols) * static_cast<std::size_t>(m_rows));
}

void Labels::block(const Rect& r) {
    const Span s = span(r);
    if (s.empty()) return;  // outside the panel: no label there can overlap it
    const auto id = static_cast<std::uint32_t>(m_used.size());
    m_used.push_back(r);
    for (int j = s.j0; j <= s.j1; ++j)
        for (int i = s.i0; i <= s.i1; ++i) m_buckets[static_cast<std::size_t>(j) * m_cols + i].push_back(id);
}

std::optional<Rect> Labels::place(XY anchor, double w, double h, double gap, double reach) {
    // A step of at least 2 px: with no gap (an area's name, placed on its centre first) the
    // step d / 2 from d = 0 was 0, and a name whose first tries were all taken never left the loop.
    for (double d = gap; d <= std::max(gap, reach); d += std::max(d < 2 * gap ? gap : d / 2, 2.0)) {
        const Rect tries[] = {
            {anchor.x + d, anchor.y - d - h, anchor.x + d + w, anchor.y - d},
            {anchor.x + d, anchor.y + d, anchor.x + d + w, anchor.y + d + h},
            {anchor.x - d - w, anchor.y - d - h, anchor.x - d, anchor.y - d},
            {anchor.x - d - w, anchor.y + d, anchor.x - d, anchor.y + d + h},
            {anchor.x - w / 2, anchor.y - 2 * d - h, anchor.x + w / 2, anchor.y - 2 * d},
            {anchor.x - w / 2, anchor.y + 2 * d, anchor.x + w / 2, anchor.y + 2 * d + h},
            {anchor.x + 2 * d, anchor.y - h / 2, anchor.x + 2 * d + w, anchor.y + h / 2},
            {anchor.x - 2 * d - w, anchor.y - h / 2, anchor.x - 2 * d, anchor.y + h / 2},
        };
        for (const Rect& r : tries) {
            if (!r.within(m_bounds) || taken(r)) continue;
            block(r);
            return r;
        }
    }
    return std::nullopt;
}

Labels::Span Labels::span(const Rect& r) const noexcept {
    if (!r.overlaps(m_bounds)) return {};  // then it overlaps no label (labels lie within the panel)
    auto at = [&](double v, double v0, int n) {
        return static_cast<int>(std::clamp(std::floor((v - v0) / bucket_px), 0.0, static_cast<double>(n - 1)));
    };
    return {at(r.x0, m_bounds.x0, m_cols), at(r.y0, m_bounds.y0, m_rows), at(r.x1, m_bounds.x0, m_cols), at(r.y1, m_bounds.y0, m_rows)};
}

bool Labels::taken(const Rect& r) const {
    const Span s = span(r);
    for (int j = s.j0; j <= s.j1; ++j)
        for (int i = s.i0; i <= s.i1; ++i)
            for (const std::uint32_t id : m_buckets[static_cast<std::size_t>(j) * m_cols + i])
                if (m_used[id].overlaps(r)) return true;
    return false;
}


}  // namespace shoal::report::plot_parts
