#pragma once
// An adaptive Simpson quadrature for the tests, independent of the library's graded Gauss-Legendre
// (src/brdf/integrate.hpp), so the checks of normalization and albedo do not grade their own homework.

#include <cmath>
#include <functional>

namespace hilite::test {

namespace detail {
inline double simpsonStep(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                          double whole, double tol, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double delta = left + right - whole;
    if (depth <= 0 || std::abs(delta) <= 15.0 * tol) return left + right + delta / 15.0;  // Richardson step
    return simpsonStep(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1) +
           simpsonStep(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1);
}
}  // namespace detail

/// int_a^b f, adaptive Simpson to absolute tolerance `tol` (depth <= 40).
inline double adaptiveSimpson(const std::function<double(double)>& f, double a, double b, double tol) {
    const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
    return detail::simpsonStep(f, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), tol, 40);
}

/// int_0^end f for a peak at 0 of width w: adaptive Simpson on [0, w/64], [w/64, w/32], ... so that the
/// first look at the integrand already sees the peak.
inline double adaptiveGraded(const std::function<double(double)>& f, double end, double width, double tol) {
    double sum = 0.0, a = 0.0, b = std::min(width / 64.0, end / 8.0);
    for (; b < end; a = b, b = std::min(2.0 * b, end)) sum += adaptiveSimpson(f, a, b, tol);
    return sum + adaptiveSimpson(f, a, end, tol);
}

}  // namespace hilite::test
