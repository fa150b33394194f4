#pragma once
/// `JacobianField`: a frame's Jacobian (`LocalFrame::jacobian`: scale and meridian
/// convergence) over a box of local metres, as one Chebyshev series in x and y per entry,
/// fitted once from the frame and kept only where it reproduces the frame. Placing a pose
/// then costs one projection (its position) instead of five (the position and the four of
/// the central difference).

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include <shoal/geo/local_frame.hpp>
#include <shoal/geo/point.hpp>

namespace shoal::geo {

class JacobianField {
public:
    /// Largest difference, entry by entry, between the series and the frame's Jacobian (by
    /// a fourth-order difference over 50-100 m, good to about 3e-11) at the check points (a
    /// lattice between the nodes, corners and edges included) for the fit to be kept: a
    /// 500 m hull placed with it moves by under 0.25 µm. LocalFrame::jacobian's 1 m central
    /// difference carries about 3e-9 of the projection's rounding.
    static constexpr double tolerance = 5e-10;

    /// Fits the Jacobian of `frame` over `box` (local metres) with the lowest degree (4 to
    /// 16) that stays within `tolerance`. When none does, or the frame fails at a node, the
    /// field covers nothing (`covers` is false everywhere). It holds no reference to the
    /// frame: use it only with frames of the same definition.
    JacobianField(const LocalFrame& frame, const Box& box);

    /// Whether p lies in the fitted box (and a fit was kept).
    bool covers(XY p) const noexcept {
        return m_degree > 0 && p.x >= m_x0 && p.x <= m_x1 && p.y >= m_y0 && p.y <= m_y1;
    }
    /// The Jacobian at local p, for p that `covers`.
    Eigen::Matrix2d at(XY p) const noexcept;

    /// The degree kept (0: none) and the largest difference found at the check points (with
    /// no fit kept: the least of the fits tried; INFINITY when none could be tried: an empty
    /// box, or the frame failing on the check lattice).
    int degree() const noexcept { return m_degree; }
    double worst_difference() const noexcept { return m_worst; }

private:
    /// Fits degree n; false when the frame fails at a node.
    bool fit(const LocalFrame& frame, int n);
    double x_of(double u) const noexcept { return (m_x0 + m_x1) / 2 + u * (m_x1 - m_x0) / 2; }
    double y_of(double v) const noexcept { return (m_y0 + m_y1) / 2 + v * (m_y1 - m_y0) / 2; }

    double m_x0 = 0, m_y0 = 0, m_x1 = 0, m_y1 = 0;
    int m_degree = 0;
    double m_worst = INFINITY;
    /// (n + 1)^2 coefficients per entry, the four entries side by side: c[(i * (n + 1) + j)
    /// * 4 + e] multiplies T_i(u) T_j(v) for entry e of (0,0), (0,1), (1,0), (1,1).
    std::vector<double> m_coef;
};

}  // namespace shoal::geo
