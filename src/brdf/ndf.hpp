#pragma once
// Normal distribution functions D(h), each normalized so that int D(h) (n.h) dw_h = 1 (checked by
// tests/brdf/test_ndf.cpp). Twin of the D_* blocks of shaders/brdf.glsl.

#include "brdf/common.hpp"

#include <cmath>

namespace hilite::brdf {

/// Blinn-Phong NDF: D(h) = (n+2)/(2 pi) cos^n(theta_h). Blinn 1977 "Models of light reflection
/// for computer synthesized pictures"; normalized so that int D (n.h) dw = 1.
inline double D_BlinnPhong(double oneMinusNoH, double n) {
    return (n + 2.0) * (0.5 * kInvPi) * powCosStable(oneMinusNoH, n);
}

/// Beckmann NDF: D(h) = exp(-tan^2(theta_h) / m^2) / (pi m^2 cos^4(theta_h)).
/// Beckmann & Spizzichino 1963; tan^2 = sin2h / NoH^2 avoids 1 - NoH^2 cancellation.
inline double D_Beckmann(double NoH, double sin2h, double m) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    if (m == 0.0) return 0.0;    // a perfect mirror: D is a delta at h = n (0/0 there), no finite sample of it
    const double cos2 = NoH * NoH, m2 = m * m;
    const double e = std::exp(-sin2h / (cos2 * m2));
    // h near the horizon: cos2^2 underflows (to 0 in float below NoH ~ 1e-10) only where the exponential
    // already has; without this, 0/0.
    if (e == 0.0) return 0.0;
    return e / (kPi * m2 * cos2 * cos2);
}

/// Trowbridge-Reitz / GGX NDF: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
/// Walter et al. 2007 "Microfacet models for refraction through rough surfaces"; the denominator as
/// NoH^2 alpha^2 + |n x h|^2 (Filament) keeps its digits for alpha -> 0.
inline double D_GGX(double NoH, double sin2h, double alpha) {
    if (NoH <= 0.0) return 0.0;   // back-facing microfacet
    if (alpha == 0.0) return 0.0;  // a perfect mirror: D is a delta at h = n (0/0 there), no finite sample of it
    const double a2 = alpha * alpha;
    const double d = NoH * NoH * a2 + sin2h;
    return a2 / (kPi * d * d);
}

/// theta from its sine and cosine, exactly: atan2 in double. The GLSL twin reduces by three half-angle
/// steps and sums the atan series (relative error < 3e-10), because GLSL's atan is only ~1e-6 rad
/// accurate, too coarse near theta = 0 for exp(-(theta/m)^2) with small m.
inline double angleFromSinCos(double s, double c) { return std::atan2(s, c); }

/// Gaussian NDF in the angle: D(h) = k_G exp(-(theta_h / m)^2), k_G = gaussianNormalization(m).
/// Cook & Torrance 1982 "A reflectance model for computer graphics" (their D = c exp(-(alpha/m)^2)).
/// theta_h from (|n x h|, n.h): acos(NoH) would lose half its digits as theta_h -> 0.
inline double D_Gaussian(double NoH, double sin2h, double m, double kG) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    if (m == 0.0) return 0.0;    // a perfect mirror: D is a delta at h = n (theta / m is 0/0 there)
    const double t = angleFromSinCos(std::sqrt(sin2h), NoH) / m;
    return kG * std::exp(-t * t);
}

/// k_G = 1 / (2 pi int_0^{pi/2} exp(-(theta/m)^2) cos(theta) sin(theta) dtheta): no closed form on the
/// hemisphere, so integrated numerically (Gauss-Legendre on panels graded to m, relative error < 1e-12)
/// and cached per m. For m -> 0 it tends to 1 / (pi m^2 (1 - 2 m^2 / 3)). m = 0 (a delta, k_G infinite)
/// returns 0, so that no product with it becomes inf or NaN; D_Gaussian returns 0 for m = 0 anyway.
double gaussianNormalization(double m);

/// Anisotropic Beckmann NDF: D(h) = exp(-((hx/ax)^2 + (hy/ay)^2) / hz^2) / (pi ax ay hz^4), h in the
/// tangent frame (HoX, HoY, NoH). Heitz 2014 "Understanding the masking-shadowing function in
/// microfacet-based BRDFs" (the stretched Beckmann); ax = ay gives D_Beckmann.
inline double D_BeckmannAniso(double HoX, double HoY, double NoH, double ax, double ay) {
    if (NoH <= 0.0) return 0.0;          // back-facing microfacet
    if (ax * ay == 0.0) return 0.0;      // smooth along an axis: a delta there (HoX / 0), no finite sample of it
    const double cos2 = NoH * NoH, x = HoX / ax, y = HoY / ay;
    const double e = std::exp(-(x * x + y * y) / cos2);
    if (e == 0.0) return 0.0;  // as in D_Beckmann: cos2^2 may underflow only where e has, 0/0 otherwise
    return e / (kPi * ax * ay * cos2 * cos2);
}

/// Anisotropic GGX NDF: D(h) = 1 / (pi ax ay ((hx/ax)^2 + (hy/ay)^2 + hz^2)^2), h in the tangent frame.
/// Burley 2012 "Physically-based shading at Disney"; Heitz 2014. ax = ay gives D_GGX.
inline double D_GGXAniso(double HoX, double HoY, double NoH, double ax, double ay) {
    if (NoH <= 0.0) return 0.0;      // back-facing microfacet
    if (ax * ay == 0.0) return 0.0;  // smooth along an axis: a delta there (HoX / 0), no finite sample of it
    const double x = HoX / ax, y = HoY / ay;
    const double d = x * x + y * y + NoH * NoH;
    return 1.0 / (kPi * ax * ay * d * d);
}

}  // namespace hilite::brdf
