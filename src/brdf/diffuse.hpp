#pragma once
// Diffuse terms, added to the specular lobe when a scene names one (no energy coupling between the
// two: f = specular + diffuse may reflect more than it receives, which `hilite brdf albedo` reports).
// Twin of the Fd_* blocks of shaders/brdf.glsl.

#include "core/math.hpp"

#include <algorithm>

namespace hilite::brdf {

/// Lambert: f = rho / pi, rho the albedo colour. Lambert 1760 "Photometria"; albedo = rho at every angle.
inline dvec3 Fd_Lambert(const dvec3& rho) { return rho * kInvPi; }

/// Oren-Nayar qualitative rough diffuse: f = rho/pi (A + B max(0, cos(phi_i - phi_o)) sin(alpha) tan(beta)),
/// A = 1 - 0.5 s^2/(s^2 + 0.33), B = 0.45 s^2/(s^2 + 0.09), alpha = max(theta_i, theta_o), beta = min,
/// s = sigma in radians. Oren & Nayar 1994 "Generalization of Lambert's reflectance model" (the
/// qualitative model). Without trig: max(0, cos dphi) sin(alpha) tan(beta) = max(0, LoV - NoL NoV) /
/// max(NoL, NoV), symmetric in wi and wo. NoL, NoV >= 0 (the caller rejects the horizon).
inline dvec3 Fd_OrenNayar(const dvec3& rho, double sigma, double NoL, double NoV, double LoV) {
    const double s2 = sigma * sigma;
    const double A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
    const double top = std::max(NoL, NoV);
    const double t = top > 0.0 ? std::max(0.0, LoV - NoL * NoV) / top : 0.0;  // both on the horizon: 0/0
    return rho * (kInvPi * (A + B * t));
}

}  // namespace hilite::brdf
