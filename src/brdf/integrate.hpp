#pragma once
// Quadrature in double for the physics of the BRDF: the NDF's normalization int D(h) (n.h) dw and the
// directional-hemispherical reflectance (albedo). Lobes as narrow as n = 1e4 or alpha = 0.02 are
// resolved by Gauss-Legendre panels graded geometrically about the lobe's peak, ending on the horizon.

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace hilite::brdf {

/// Gauss-Legendre nodes and weights on [-1, 1], 32 points (exact for polynomials of degree 63).
struct GaussLegendre {
    static constexpr int kN = 32;
    std::array<double, kN> x{}, w{};
};
const GaussLegendre& gaussLegendre();

/// int_a^b f(x) dx with one Gauss-Legendre panel; f returns double or dvec3.
template <class F>
auto integratePanel(F&& f, double a, double b) -> decltype(f(a)) {
    using R = decltype(f(a));
    const GaussLegendre& g = gaussLegendre();
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    R sum = R(0.0);
    for (int i = 0; i < GaussLegendre::kN; ++i) sum += g.w[size_t(i)] * f(mid + half * g.x[size_t(i)]);
    return sum * half;
}

/// int_0^end f(x) dx with panels graded about 0 on the scale `width`: [0, w/8], [w/8, w/4], [w/4, w/2],
/// ... doubling up to `end` (at least 3 panels), so a peak at 0 of width w and its tails are resolved:
/// the integrand is smooth on every panel, where Gauss-Legendre converges spectrally.
template <class F>
auto integrateGraded(F&& f, double end, double width) -> decltype(f(end)) {
    using R = decltype(f(end));
    R sum = R(0.0);
    double a = 0.0, b = std::min(width / 8.0, end / 4.0);
    for (; b < end; a = b, b = std::min(2.0 * b, end)) sum += integratePanel(f, a, b);
    return sum + integratePanel(f, a, end);
}

/// The same with further panel edges `extra` (those in (0, end) are used): where the integrand has a kink
/// or a jump, so that it stays smooth on every panel.
template <class F>
auto integrateGraded(F&& f, double end, double width, const std::vector<double>& extra) -> decltype(f(end)) {
    using R = decltype(f(end));
    std::vector<double> edges{0.0};
    for (double b = std::min(width / 8.0, end / 4.0); b < end; b *= 2.0) edges.push_back(b);
    for (double e : extra)
        if (e > 0.0 && e < end) edges.push_back(e);
    std::sort(edges.begin(), edges.end());
    edges.push_back(end);
    R sum = R(0.0);
    for (size_t i = 0; i + 1 < edges.size(); ++i)
        if (edges[i + 1] > edges[i]) sum += integratePanel(f, edges[i], edges[i + 1]);
    return sum;
}

/// Angular width of the model's lobe in radians (the grading scale): Blinn/Phong sqrt(2 / (n + 2)),
/// Beckmann / Gaussian m, GGX alpha (the smaller of the two when anisotropic); at most pi/2.
double lobeWidth(const Params& p);

/// int D(h) (n.h) dw_h over the hemisphere: 1 for a normalized NDF. Microfacet models only (0 otherwise).
double ndfIntegral(const Params& p);

/// Directional-hemispherical reflectance rho(wi) = int f(wi, wo) cos(theta_o) dwo per channel, light
/// at (thetaDeg, phiDeg). The specular part is integrated over the half vector (dwo = 4 (wi.h) dwh) or
/// about the mirror direction (reflection lobes), the diffuse part over wo. The horizon cut (wo.z = 0) is a
/// panel edge in closed form per azimuth, so the integrand is smooth on every panel. Measured
/// (tests/brdf/test_albedo_exact.cpp): the closed forms at normal incidence with G = 1 (GGX, Beckmann,
/// Blinn-Phong) within 8e-16; an adaptive Gauss-Kronrod reference over wo at 30, 60, 85 deg within 1.1e-7
/// for every model and geometry term, anisotropic too, and 5e-13 for narrow lobes (alpha 0.02, n = 1e4)
/// up to 89 deg. Tabulated NDFs of more than 64 rows and the Beckmann Lambda's cut are kinks inside panels.
dvec3 albedo(const Params& p, double thetaDeg, double phiDeg = 0.0);

}  // namespace hilite::brdf
