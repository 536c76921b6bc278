#pragma once
// Masking-shadowing: Smith's Lambda per NDF and the G factors built from it, and the Cook-Torrance
// V-cavity G. Twin of the Lambda_* / G* blocks of shaders/brdf.glsl. The implicit G = cos_i cos_o and
// G = 1 need no function: the dispatch folds them into the 1 / (4 cos_i cos_o) denominator.

#include "core/math.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::brdf {

/// Smith Lambda for GGX: Lambda(w) = (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2. Heitz 2014
/// "Understanding the masking-shadowing function", eq. 72; tan^2 = sin^2 / cos^2. cosTheta in (0, 1]:
/// at cosTheta -> 0 Lambda -> +inf (G -> 0, the right limit; the G2 forms below turn it into 0).
inline double Lambda_GGX(double cosTheta, double alpha) {
    if (alpha == 0.0) return 0.0;  // a smooth surface masks nothing (and 0 * inf at the horizon is NaN)
    const double cos2 = cosTheta * cosTheta;
    const double tan2 = std::max(0.0, 1.0 - cos2) / cos2;
    return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

/// The rational fit of Beckmann's Lambda in a = 1 / (m tan theta), Walter et al. 2007 (< 0.35% rel.
/// error in G1): Lambda = (1 - 1.259a + 0.396a^2) / (3.535a + 2.181a^2) for a < 1.6, else 0.
inline double lambdaBeckmannRational(double a) {
    if (a >= 1.6) return 0.0;  // the fit's own cut: G1 = 1 within its error
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}

/// Smith Lambda for Beckmann by the rational approximation above.
inline double Lambda_Beckmann(double cosTheta, double m) {
    if (m == 0.0) return 0.0;  // a smooth surface masks nothing (and 0 / 0 at the horizon)
    const double sinTheta = safeSqrt(1.0 - cosTheta * cosTheta);
    if (sinTheta == 0.0) return 0.0;  // normal incidence: no masking
    return lambdaBeckmannRational(cosTheta / (m * sinTheta));
}

/// alpha^2 tan^2(theta) of the stretched (anisotropic) surface seen from w = (x, y, z) in the tangent
/// frame: (x^2 ax^2 + y^2 ay^2) / z^2, i.e. the isotropic Lambda with alpha projected on w's azimuth.
/// Heitz 2014, the anisotropic forms of Lambda. x, y enter squared: no 1 - cos^2 cancellation. z > 0: the
/// callers have rejected directions at or below the horizon.
inline double alphaTan2Aniso(const dvec3& w, double ax, double ay) {
    const double num = w.x * w.x * ax * ax + w.y * w.y * ay * ay;
    if (num == 0.0) return 0.0;  // normal incidence or a smooth surface: 0, also where z^2 underflows (0/0)
    return num / (w.z * w.z);
}

/// Smith Lambda for anisotropic GGX: (-1 + sqrt(1 + alpha(phi)^2 tan^2(theta))) / 2.
inline double Lambda_GGXAniso(const dvec3& w, double ax, double ay) {
    return 0.5 * (-1.0 + std::sqrt(1.0 + alphaTan2Aniso(w, ax, ay)));
}

/// Smith Lambda for anisotropic Beckmann: the rational fit at a = 1 / (alpha(phi) tan(theta)).
inline double Lambda_BeckmannAniso(const dvec3& w, double ax, double ay) {
    const double a2t2 = alphaTan2Aniso(w, ax, ay);
    if (a2t2 == 0.0) return 0.0;  // normal incidence or a smooth surface: no masking
    return lambdaBeckmannRational(1.0 / std::sqrt(a2t2));
}

/// Height-correlated Smith masking-shadowing: G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Heitz 2014, eq. 99.
inline double G2_SmithCorrelated(double lambdaI, double lambdaO) { return 1.0 / (1.0 + lambdaI + lambdaO); }

/// Separable Smith masking-shadowing: G2 = G1(wi) G1(wo) = 1 / ((1 + Lambda(wi)) (1 + Lambda(wo))).
/// Heitz 2014, the separable form (eq. 98); <= the height-correlated G2, so darker at grazing.
inline double G2_SmithSeparable(double lambdaI, double lambdaO) { return 1.0 / ((1.0 + lambdaI) * (1.0 + lambdaO)); }

/// Cook-Torrance V-cavity masking-shadowing: G = min(1, 2 NoH NoV / VoH, 2 NoH NoL / VoH).
/// Torrance & Sparrow 1967; Cook & Torrance 1982. VoH = LoH > 0 whenever both directions are above
/// the horizon; the guard only keeps a degenerate pair finite.
inline double G_CookTorrance(double NoH, double NoV, double NoL, double VoH) {
    if (VoH <= 0.0) return 0.0;  // wi = -wo: no half vector, no reflection
    return std::min(1.0, 2.0 * NoH * std::min(NoV, NoL) / VoH);
}

/// Beckmann slope width equivalent to a Blinn-Phong exponent: m = sqrt(2 / (n + 2)) (Walter et al. 2007).
inline double blinnExponentToBeckmann(double n) { return std::sqrt(2.0 / (n + 2.0)); }

}  // namespace hilite::brdf
