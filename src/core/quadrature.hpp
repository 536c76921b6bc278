#pragma once
// Adaptive Gauss-Kronrod (7/15) quadrature in one dimension, QUADPACK's qag strategy: the panel with the
// largest error estimate is halved until the summed estimate meets the tolerance or the panel budget runs
// out. Nodes and weights from QUADPACK's qk15 (Piessens et al. 1983). Nested calls integrate in 2-D.
// The error estimate is |K15 - G7| per panel: G7's own error, so an upper bound on K15's for smooth
// integrands (QUADPACK's (200 |K - G|)^1.5 rescaling is left out: it is tuned for lower precision).

#include "hilite/core/math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <vector>

namespace hilite {

namespace gk15 {
/// Kronrod nodes on [-1, 1] (positive half, the last is 0) and weights; the Gauss 7-point weights of the
/// odd-indexed nodes (kXgk[1], [3], [5], [7]).
constexpr std::array<double, 8> kXgk = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                        0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                        0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                        0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kWgk = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                        0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                        0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                        0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kWg = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                       0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
}  // namespace gk15

/// Gauss-Legendre nodes and weights on [-1, 1] for n points (exact for polynomials of degree 2n - 1): roots of
/// P_n by Newton's method from Chebyshev guesses, w = 2 / ((1 - x^2) P_n'(x)^2). Ascending x.
inline void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
    x.assign(size_t(n), 0.0);
    w.assign(size_t(n), 0.0);
    for (int i = 0; i < n; ++i) {
        double xi = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = xi;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * xi * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (xi * p1 - p0) / (xi * xi - 1.0);
            const double dx = p1 / dp;
            xi -= dx;
            if (std::abs(dx) < 1e-16) break;  // converged to double precision (|x| < 1)
        }
        x[size_t(n - 1 - i)] = xi;
        w[size_t(n - 1 - i)] = 2.0 / ((1.0 - xi * xi) * dp * dp);
    }
    if (n == 1) x[0] = 0.0, w[0] = 2.0;
}

/// Largest absolute component: the error norm of a scalar or an RGB integral.
inline double quadratureNorm(double x) { return std::abs(x); }
inline double quadratureNorm(const dvec3& x) { return std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)}); }

template <class T>
struct QuadratureResult {
    T value{0.0};
    double error = 0;  ///< estimated absolute error (norm of the components)
    int evaluations = 0;
    bool converged = true;  ///< false: the panel budget ran out first
};

/// One Gauss-Kronrod 7/15 panel: the Kronrod estimate and |K - G|.
template <class T, class F>
std::pair<T, double> gaussKronrodPanel(F& f, double a, double b) {
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    const T fc = f(mid);
    T kronrod = gk15::kWgk[7] * fc, gauss = gk15::kWg[3] * fc;
    for (int i = 0; i < 7; ++i) {
        const double dx = half * gk15::kXgk[size_t(i)];
        const T s = f(mid - dx) + f(mid + dx);
        kronrod += gk15::kWgk[size_t(i)] * s;
        if (i % 2 == 1) gauss += gk15::kWg[size_t(i / 2)] * s;
    }
    return {kronrod * half, quadratureNorm((kronrod - gauss) * half)};
}

/// How a panel's error is estimated from e = |K15 - G7|.
enum class PanelError {
    /// e itself: G7's error, an upper bound on K15's for any smooth integrand.
    GaussBound,
    /// e min(1, sqrt(e / |K15|)): for an integrand analytic on the panel, G7's error falls as rho^-14 and K15's
    /// as rho^-23 or faster (Bernstein ellipse rho), so K15's relative error is below G7's to the power 1.5;
    /// QUADPACK's qk15 scales it likewise (to the power 1.5, Piessens et al. 1983). Only for panels whose
    /// edges are the integrand's kinks (measured against GaussBound at 1e-12: docs/area-lights.md).
    Analytic,
};

/// int_a^b f(x) dx to max(absTol, relTol |integral|), at most maxPanels panels. f returns double or dvec3.
template <class T, class F>
QuadratureResult<T> integrateAdaptive(F&& f, double a, double b, double relTol, double absTol, int maxPanels = 256,
                                      PanelError model = PanelError::GaussBound) {
    struct Panel {
        double a, b;
        T value;
        double error;
        bool operator<(const Panel& o) const { return error < o.error; }
    };
    QuadratureResult<T> r;
    if (!(b > a)) return r;
    auto panel = [&](double x0, double x1) {
        auto p = gaussKronrodPanel<T>(f, x0, x1);
        const double n = quadratureNorm(p.first);
        if (model == PanelError::Analytic && n > 0) p.second *= std::min(1.0, std::sqrt(p.second / n));
        return p;
    };
    std::priority_queue<Panel> panels;
    auto first = panel(a, b);
    panels.push({a, b, first.first, first.second});
    r.value = first.first;
    r.error = first.second;
    r.evaluations = 15;
    int count = 1;
    while (r.error > std::max(absTol, relTol * quadratureNorm(r.value))) {
        if (count >= maxPanels) {
            r.converged = false;
            break;
        }
        const Panel p = panels.top();
        panels.pop();
        const double m = 0.5 * (p.a + p.b);
        if (!(m > p.a && m < p.b)) {  // rounding: the panel cannot be halved any more
            r.converged = false;
            panels.push(p);
            break;
        }
        const auto left = panel(p.a, m), right = panel(m, p.b);
        r.evaluations += 30;
        ++count;
        r.value += left.first + right.first - p.value;
        r.error = std::max(0.0, r.error + left.second + right.second - p.error);  // running sums: drift ~1e-16
        panels.push({p.a, m, left.first, left.second});
        panels.push({m, p.b, right.first, right.second});
    }
    return r;
}

}  // namespace hilite
