#pragma once
// Fresnel reflectance F(cos theta_i) of a smooth interface, unpolarized light. Twin of the F_* blocks of
// shaders/brdf.glsl. The exact forms return the s- and p-polarized parts too (.x = Rs, .y = Rp), so
// tests can check Brewster's angle; F is their mean. eta = n_t / n_i, relative to the incident medium.
// The spectral form (a sum of F_Conductor over wavelengths) is in brdf/spectral.hpp.

#include "core/math.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::brdf {

/// Schlick's Fresnel approximation: F = F0 + (1 - F0)(1 - cos)^5. Schlick 1994 "An inexpensive BRDF
/// model for physically-based rendering". Against F_Dielectric its error peaks near grazing (< 0.07
/// for water and glass, above 80 degrees: tests/brdf/test_fresnel.cpp).
inline dvec3 F_Schlick(const dvec3& f0, double VoH) {
    const double c = std::clamp(1.0 - VoH, 0.0, 1.0);
    const double c2 = c * c;
    return f0 + (dvec3(1.0) - f0) * (c2 * c2 * c);
}

/// Exact dielectric Fresnel, polarized parts: Rs = ((ci - eta ct) / (ci + eta ct))^2,
/// Rp = ((eta ci - ct) / (eta ci + ct))^2, with Snell's sin(theta_t) = sin(theta_i) / eta.
/// Born & Wolf "Principles of optics", sec. 1.5.2; the form of pbrt-v4's FrDielectric.
inline dvec2 F_DielectricSP(double cosTheta_i, double eta) {
    // Matched index: no interface, F = 0 at every angle. At grazing the formulas below are 0/0 for eta = 1,
    // and the total-internal-reflection test would return 1 there instead.
    if (eta == 1.0) return dvec2(0.0);
    const double ci = std::clamp(cosTheta_i, 0.0, 1.0);
    const double sin2Theta_t = (1.0 - ci * ci) / (eta * eta);
    if (sin2Theta_t >= 1.0) return dvec2(1.0);  // total internal reflection (eta < 1 beyond the critical angle)
    const double ct = std::sqrt(1.0 - sin2Theta_t);
    const double rs = (ci - eta * ct) / (ci + eta * ct);
    const double rp = (eta * ci - ct) / (eta * ci + ct);
    return {rs * rs, rp * rp};
}

/// Exact unpolarized dielectric Fresnel: F = (Rs + Rp) / 2. F(0) = ((eta - 1) / (eta + 1))^2.
inline double F_Dielectric(double cosTheta_i, double eta) {
    const dvec2 r = F_DielectricSP(cosTheta_i, eta);
    return 0.5 * (r.x + r.y);
}

/// Exact conductor Fresnel for the complex index eta + i k, polarized parts, in real arithmetic:
/// a^2 + b^2 = sqrt((eta^2 - k^2 - sin^2)^2 + 4 eta^2 k^2), a^2 = (a^2 + b^2 + eta^2 - k^2 - sin^2) / 2,
/// Rs = (a^2 + b^2 - 2a cos + cos^2) / (a^2 + b^2 + 2a cos + cos^2),
/// Rp = Rs (cos^2 (a^2 + b^2) - 2a cos sin^2 + sin^4) / (cos^2 (a^2 + b^2) + 2a cos sin^2 + sin^4).
/// Born & Wolf sec. 14.2; Rp without tan(theta) (finite at grazing) as in Lagarde 2013 "Memo on Fresnel
/// equations". Equal to pbrt-v4's complex FrComplex (tests); k = 0 gives F_Dielectric, TIR included.
/// Stable forms: the numerators as sums of squares, a^2 + b^2 - 2a cos + cos^2 = (a - cos)^2 + b^2 and
/// cos^2 (a^2 + b^2) - 2a cos sin^2 + sin^4 = (a cos - sin^2)^2 + b^2 cos^2, never below 0 and without the
/// cancellation of the textbook differences, which lost every digit of a small F in float (eta = 1, k = 0:
/// +-7e-8 noise, negative at 19 of 200 angles; eta = 1.0001, cos 0.9: F = 2.6e-9 came out 0; eta = 1.001:
/// 6% off; now 5e-4 and 1e-4, tests/hard); a^2 and b^2
/// each from the sum that does not cancel (2 eta^2 k^2 / (a^2 + b^2 -+ t0)). The denominators
/// vanish only for a^2 + b^2 = 0 at cos = 0 (eta = 1, k = 0: guarded) or at cos = 1 (eta = k = 0, which
/// the CLI rejects: eta >= 0.01).
inline dvec2 F_ConductorSP(double cosTheta_i, double eta, double k) {
    // Matched index: no interface, F = 0 at every angle (at grazing the formulas are 0/0).
    if (eta == 1.0 && k == 0.0) return dvec2(0.0);
    const double c = std::clamp(cosTheta_i, 0.0, 1.0), c2 = c * c, s2 = 1.0 - c2;
    const double t0 = eta * eta - k * k - s2, e2k2 = 2.0 * eta * eta * k * k;
    const double a2b2 = std::sqrt(t0 * t0 + 2.0 * e2k2);
    const double a2 = t0 >= 0.0 ? 0.5 * (a2b2 + t0) : e2k2 / (a2b2 - t0);  // (a2b2 + t0) / 2 without cancellation
    const double b2 = t0 > 0.0 ? e2k2 / (a2b2 + t0) : 0.5 * (a2b2 - t0);   // (a2b2 - t0) / 2 likewise
    const double a = std::sqrt(a2), ac = a * c;
    const double Rs = ((a - c) * (a - c) + b2) / ((a + c) * (a + c) + b2);
    return {Rs, Rs * ((ac - s2) * (ac - s2) + b2 * c2) / ((ac + s2) * (ac + s2) + b2 * c2)};
}

/// Exact unpolarized conductor Fresnel: F = (Rs + Rp) / 2. F(0) = ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2).
inline double F_Conductor(double cosTheta_i, double eta, double k) {
    const dvec2 r = F_ConductorSP(cosTheta_i, eta, k);
    return 0.5 * (r.x + r.y);
}

}  // namespace hilite::brdf
