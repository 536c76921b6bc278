#pragma once
// Reflectance terms in double precision: the CPU twin of shaders/brdf.glsl. Same names, same argument
// order, same split into terms; each carries the equation it evaluates and where it comes from.
// Arguments are the clamped scalars computed once per direction pair (see evaluate.cpp):
//   NoH = n.h, sin2h = |n x h|^2 = 1 - (n.h)^2 computed without cancellation, VoH = wo.h.

#include "core/math.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::brdf {

/// log(1 - x) for x in [0, 1): exact near 0 where log(1 - x) would lose every digit of x.
inline double log1mStable(double x) { return std::log1p(-x); }

/// cos^n(theta) written as exp(n log(1 - oneMinusCos)), with 1 - cos passed in from a stable form
/// (|a - b|^2 / 2 for unit vectors): for n = 1e6 and cos = 1 - 1e-7 direct pow() is off by 10%.
inline double powCosStable(double oneMinusCos, double n) {
    if (oneMinusCos >= 1.0) return n == 0.0 ? 1.0 : 0.0;  // cos <= 0: the clamped lobe is 0
    return std::exp(n * log1mStable(oneMinusCos));
}

/// Normalized Phong reflection lobe: f = (n+2)/(2 pi) cos^n(alpha_r), alpha_r = angle(wo, reflect(wi)).
/// Phong 1975 "Illumination for computer generated pictures"; normalization Lewis 1994.
inline double Phong_Normalized(double oneMinusCosR, double n) {
    return (n + 2.0) * (0.5 * kInvPi) * powCosStable(oneMinusCosR, n);
}

/// Blinn-Phong NDF: D(h) = (n+2)/(2 pi) cos^n(theta_h). Blinn 1977 "Models of light reflection
/// for computer synthesized pictures"; normalized so that int D (n.h) dw = 1.
inline double D_BlinnPhong(double oneMinusNoH, double n) {
    return (n + 2.0) * (0.5 * kInvPi) * powCosStable(oneMinusNoH, n);
}

/// Beckmann NDF: D(h) = exp(-tan^2(theta_h) / m^2) / (pi m^2 cos^4(theta_h)).
/// Beckmann & Spizzichino 1963; tan^2 = sin2h / NoH^2 avoids 1 - NoH^2 cancellation.
inline double D_Beckmann(double NoH, double sin2h, double m) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    const double cos2 = NoH * NoH, m2 = m * m;
    return std::exp(-sin2h / (cos2 * m2)) / (kPi * m2 * cos2 * cos2);
}

/// Trowbridge-Reitz / GGX NDF: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
/// Walter et al. 2007 "Microfacet models for refraction through rough surfaces"; the denominator as
/// NoH^2 alpha^2 + |n x h|^2 (Filament) keeps its digits for alpha -> 0.
inline double D_GGX(double NoH, double sin2h, double alpha) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    const double a2 = alpha * alpha;
    const double d = NoH * NoH * a2 + sin2h;
    return a2 / (kPi * d * d);
}

/// Schlick's Fresnel approximation: F = F0 + (1 - F0)(1 - cos)^5. Schlick 1994.
inline dvec3 F_Schlick(const dvec3& f0, double VoH) {
    const double c = std::clamp(1.0 - VoH, 0.0, 1.0);
    const double c2 = c * c;
    return f0 + (dvec3(1.0) - f0) * (c2 * c2 * c);
}

/// Smith Lambda for GGX: Lambda(w) = (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2. Heitz 2014
/// "Understanding the masking-shadowing function", eq. 72; tan^2 = sin^2 / cos^2.
inline double Lambda_GGX(double cosTheta, double alpha) {
    const double cos2 = cosTheta * cosTheta;
    const double tan2 = std::max(0.0, 1.0 - cos2) / cos2;
    return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

/// Smith Lambda for Beckmann, Walter et al. 2007 rational approximation (< 0.35% rel. error in G1):
/// a = 1/(m tan theta); Lambda = (1 - 1.259a + 0.396a^2) / (3.535a + 2.181a^2) for a < 1.6, else 0.
inline double Lambda_Beckmann(double cosTheta, double m) {
    const double sinTheta = safeSqrt(1.0 - cosTheta * cosTheta);
    if (sinTheta == 0.0) return 0.0;  // normal incidence: no masking
    const double a = cosTheta / (m * sinTheta);
    if (a >= 1.6) return 0.0;
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}

/// Height-correlated Smith masking-shadowing: G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Heitz 2014, eq. 99.
inline double G2_SmithCorrelated(double lambdaI, double lambdaO) { return 1.0 / (1.0 + lambdaI + lambdaO); }

/// Beckmann slope width equivalent to a Blinn-Phong exponent: m = sqrt(2 / (n + 2)) (Walter et al. 2007).
inline double blinnExponentToBeckmann(double n) { return std::sqrt(2.0 / (n + 2.0)); }

}  // namespace hilite::brdf
