#include <shoal/geo/jacobian_field.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <shoal/util/error.hpp>

namespace shoal::geo {

namespace {

/// T_0(u) .. T_n(u) into t.
void chebyshev(double u, int n, double* t) noexcept {
    t[0] = 1;
    if (n >= 1) t[1] = u;
    for (int i = 2; i <= n; ++i) t[i] = 2 * u * t[i - 1] - t[i - 2];
}

constexpr int check_points = 17;  ///< per side of the check lattice, on [-1, 1]
constexpr int max_degree = 16;

/// The frame's Jacobian at p, from a fourth-order central difference over 50 and 100 m: its
/// error is the projection's rounding (~1e-9 m) over those distances, about 3e-11, where
/// LocalFrame::jacobian's 1 m difference carries about 3e-9.
Eigen::Matrix2d fine_jacobian(const LocalFrame& frame, LonLat p) {
    constexpr double h = 50.0;
    const Eigen::Vector2d mpd = metres_per_degree(p.lat);
    const double dlon = h / mpd.x(), dlat = h / mpd.y();
    auto d = [&](double ex, double ny) {  // f(+h) - f(-h) along (ex, ny) steps of h
        const XY a = frame.forward({p.lon + ex * dlon, p.lat + ny * dlat}), b = frame.forward({p.lon - ex * dlon, p.lat - ny * dlat});
        return a - b;
    };
    const XY e1 = d(1, 0), e2 = d(2, 0), n1 = d(0, 1), n2 = d(0, 2);
    const XY e = (1 / (12 * h)) * (8 * e1 - e2), n = (1 / (12 * h)) * (8 * n1 - n2);
    Eigen::Matrix2d j;
    j << e.x, n.x, e.y, n.y;
    return j;
}

}  // namespace

JacobianField::JacobianField(const LocalFrame& frame, const Box& box)
    : m_x0(box.minx), m_y0(box.miny), m_x1(box.maxx), m_y1(box.maxy) {
    if (!(m_x1 > m_x0 && m_y1 > m_y0) || !std::isfinite(m_x1 - m_x0) || !std::isfinite(m_y1 - m_y0)) return;
    // The frame's own Jacobian on a lattice over the box: what a fit must reproduce.
    std::vector<Eigen::Matrix2d> want;
    std::vector<XY> points;
    try {
        for (int a = 0; a < check_points; ++a)
            for (int b = 0; b < check_points; ++b) {
                const XY p{x_of(-1 + 2.0 * a / (check_points - 1)), y_of(-1 + 2.0 * b / (check_points - 1))};
                want.push_back(fine_jacobian(frame, frame.inverse(p)));
                points.push_back(p);
            }
    } catch (const InputError&) {
        return;
    }
    for (int n = 4; n <= max_degree; n += 2) {
        if (!fit(frame, n)) break;
        double worst = 0;
        for (std::size_t k = 0; k < points.size(); ++k) worst = std::max(worst, (at(points[k]) - want[k]).cwiseAbs().maxCoeff());
        m_worst = std::min(m_worst, worst);
        if (worst <= tolerance) return;
    }
    m_degree = 0;
    m_coef.clear();
}

bool JacobianField::fit(const LocalFrame& frame, int n) {
    const int m = n + 1;
    std::vector<double> node(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k) node[static_cast<std::size_t>(k)] = std::cos(std::numbers::pi * (k + 0.5) / m);
    // f at the nodes, entry by entry.
    std::vector<std::array<double, 4>> f(static_cast<std::size_t>(m * m));
    try {
        for (int k = 0; k < m; ++k)
            for (int l = 0; l < m; ++l) {
                const Eigen::Matrix2d j = fine_jacobian(frame, frame.inverse({x_of(node[static_cast<std::size_t>(k)]), y_of(node[static_cast<std::size_t>(l)])}));
                f[static_cast<std::size_t>(k * m + l)] = {j(0, 0), j(0, 1), j(1, 0), j(1, 1)};
            }
    } catch (const InputError&) {
        return false;
    }
    // T_i at the nodes.
    std::vector<double> t(static_cast<std::size_t>(m * m));
    for (int k = 0; k < m; ++k) chebyshev(node[static_cast<std::size_t>(k)], n, &t[static_cast<std::size_t>(k * m)]);
    // c_ij = a_i a_j / m^2 sum_k sum_l f(u_k, v_l) T_i(u_k) T_j(v_l), a_0 = 1, a_i = 2: the
    // discrete orthogonality of the T_i at the m zeros of T_m.
    m_coef.assign(static_cast<std::size_t>(4 * m * m), 0.0);
    for (int e = 0; e < 4; ++e)
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j) {
                double sum = 0;
                for (int k = 0; k < m; ++k)
                    for (int l = 0; l < m; ++l)
                        sum += f[static_cast<std::size_t>(k * m + l)][static_cast<std::size_t>(e)] * t[static_cast<std::size_t>(k * m + i)] *
                               t[static_cast<std::size_t>(l * m + j)];
                const double a = (i == 0 ? 1.0 : 2.0) * (j == 0 ? 1.0 : 2.0) / (m * m);
                m_coef[static_cast<std::size_t>((i * m + j) * 4 + e)] = a * sum;
            }
    m_degree = n;
    return true;
}

Eigen::Matrix2d JacobianField::at(XY p) const noexcept {
    const int n = m_degree, m = n + 1;
    double tu[max_degree + 1], tv[max_degree + 1];
    chebyshev((2 * p.x - (m_x0 + m_x1)) / (m_x1 - m_x0), n, tu);
    chebyshev((2 * p.y - (m_y0 + m_y1)) / (m_y1 - m_y0), n, tv);
    // The four entries side by side (SIMD lanes where there are), each lane the same
    // operations in the same order as one entry alone: row = sum_j c_ij T_j(v), then
    // sum = sum_i T_i(u) row.
    const double* c = m_coef.data();
    Eigen::Array4d sum = Eigen::Array4d::Zero();
    for (int i = 0; i < m; ++i) {
        Eigen::Array4d row = Eigen::Array4d::Zero();
        for (int j = 0; j < m; ++j, c += 4) row += Eigen::Map<const Eigen::Array4d>(c) * tv[j];
        sum += tu[i] * row;
    }
    Eigen::Matrix2d out;
    out << sum[0], sum[1], sum[2], sum[3];
    return out;
}

}  // namespace shoal::geo
