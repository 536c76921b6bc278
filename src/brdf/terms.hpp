#pragma once
// Reflectance terms in double precision: the CPU twin of shaders/brdf.glsl. Same names, same argument
// order, same split into terms; each carries the equation it evaluates and where it comes from.
// Arguments are the clamped scalars computed once per direction pair (see evaluate.cpp):
//   NoH = n.h, sin2h = |n x h|^2 = 1 - (n.h)^2 computed without cancellation, VoH = wo.h, and for the
//   anisotropic terms HoX, HoY = h in the tangent frame.
// The terms live in one header per kind; this header gathers them and holds the reflection lobes.

#include "brdf/common.hpp"
#include "brdf/diffuse.hpp"
#include "brdf/fresnel.hpp"
#include "brdf/geometry.hpp"
#include "brdf/ndf.hpp"

namespace hilite::brdf {

/// Normalized Phong reflection lobe: f = (n+2)/(2 pi) cos^n(alpha_r), alpha_r = angle(wo, reflect(wi)).
/// Phong 1975 "Illumination for computer generated pictures"; normalization Lewis 1994.
inline double Phong_Normalized(double oneMinusCosR, double n) {
    return (n + 2.0) * (0.5 * kInvPi) * powCosStable(oneMinusCosR, n);
}

/// Classic (unnormalized) Phong lobe as a BRDF: f = cos^n(alpha_r), k_s = 1. Phong 1975. Kept for
/// comparison: its albedo at normal incidence is 2 pi / (n + 2), above 1 for n < 2 pi - 2, and it
/// dims as n grows (Lewis 1994 "Making shaders more physically plausible").
inline double Phong_Classic(double oneMinusCosR, double n) { return powCosStable(oneMinusCosR, n); }

/// Retroreflective lobe: f = (n+2)/(2 pi) cos^n(beta), beta = angle(wo, wi): light goes back toward the light
/// (street signs, cat's eyes). Lafortune et al. 1997 "Non-linear approximation of reflectance functions" (their
/// cosine lobe (Cx ux vx + Cy uy vy + Cz uz vz)^n with Cx = Cy = Cz = 1, i.e. (wi.wo)^n); normalized as Phong's
/// (albedo 1 at normal incidence, less elsewhere), reciprocal. oneMinusCosB = |wo - wi|^2 / 2.
inline double Retro_Normalized(double oneMinusCosB, double n) {
    return (n + 2.0) * (0.5 * kInvPi) * powCosStable(oneMinusCosB, n);
}

}  // namespace hilite::brdf
