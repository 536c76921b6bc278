#pragma once
// The half vector of a direction pair and its scalars, computed once per pair: the twin of the GLSL
// block "HalfVector" in shaders/brdf.glsl.

#include "core/math.hpp"

#include <cmath>
#include <limits>

namespace hilite::brdf {

/// Half vector h = (wi + wo) / |wi + wo| and the clamped scalars the terms take.
struct HalfVector {
    double NoH = 0, sin2h = 0, oneMinusNoH = 1, VoH = 0;
    dvec3 h{0.0};
    bool valid = false;  ///< false when wi = -wo: no half vector exists
};

/// The scalars of a unit h: NoH, |n x h|^2 from h's tangential part (1 - NoH^2 would cancel to 0 for
/// h near n: in float every theta_h below 2.4e-4 rad), and 1 - NoH = sin^2 / (1 + cos) likewise.
inline HalfVector halfVectorOf(const dvec3& h) {
    HalfVector hv;
    hv.h = h;
    hv.NoH = h.z;
    hv.sin2h = h.x * h.x + h.y * h.y;
    hv.oneMinusNoH = h.z > 0 ? hv.sin2h / (1.0 + h.z) : 1.0;
    hv.valid = true;
    return hv;
}

/// halfVector(wi, wo), and VoH = wo.h. Above the horizon s = wi + wo has s.z = wi.z + wo.z > 0, a sum
/// without cancellation, so h exists and is accurate even for a mirror pair at grazing (s = (0, 0, 2 cos)).
/// Only wi = -wo (possible below the horizon alone) has none: the guard below catches |s|^2 = 0 (or below
/// the smallest normal double, where s / |s| would overflow) and returns valid = false.
inline HalfVector halfVector(const dvec3& wi, const dvec3& wo) {
    const dvec3 s = wi + wo;
    const double len2 = glm::dot(s, s);
    if (!(len2 >= std::numeric_limits<double>::min())) return {};  // wi = -wo: no half vector (0/0)
    HalfVector hv = halfVectorOf(s / std::sqrt(len2));
    hv.VoH = glm::dot(wo, hv.h);
    return hv;
}

}  // namespace hilite::brdf
