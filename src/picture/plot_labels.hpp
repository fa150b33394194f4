#pragma once
/// Label placement: labels set where they overlap nothing placed before, inside the panel.
/// Private to src/picture (plot.cpp puts the parts on the page); namespace plot_parts.

#include <cstdint>
#include <optional>
#include <vector>

#include "picture/plot_scene.hpp"

namespace shoal::report::plot_parts {

/// Places labels where they overlap nothing placed or blocked before, inside the panel. The
/// rectangles taken are kept in buckets of a coarse grid over the panel, so that a try looks
/// only at the rectangles near it: placing a label costs the same with 100 vessels or 100,000
/// (before, every try was tested against every rectangle taken: quadratic in vessels).
class Labels {
public:
    explicit Labels(Rect bounds);
    /// Marks `r` as taken (a label placed, or something no label may cover).
    void block(const Rect& r);
    /// Tries the four corners around `anchor` (px) at `gap`, then above and below, then the
    /// same further out up to `reach` px; the box of the label, or nothing.
    std::optional<Rect> place(XY anchor, double w, double h, double gap, double reach = 0);

private:
    static constexpr double bucket_px = 48;
    struct Span {
        int i0 = 0, j0 = 0, i1 = -1, j1 = -1;
        bool empty() const noexcept { return i1 < i0 || j1 < j0; }
    };
    /// The buckets `r` touches (clamped to the panel).
    Span span(const Rect& r) const noexcept;
    bool taken(const Rect& r) const;

    Rect m_bounds;
    int m_cols = 1, m_rows = 1;
    std::vector<Rect> m_used;
    std::vector<std::vector<std::uint32_t>> m_buckets;  ///< per bucket (row-major): ids in m_used
};

/// A thin line from `anchor` to the nearest point of a label placed away from it.
void leader(std::string& out, XY anchor, const Rect& box, double min_px, const char* colour);
/// A label on a pale box (readable over lines), text left-aligned in `box`.
void label(std::string& out, const Rect& box, const std::string& text, double size, const char* colour, const char* cls = "label", bool bold = false);

}  // namespace shoal::report::plot_parts
