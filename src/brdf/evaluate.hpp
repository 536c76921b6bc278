#pragma once
// The CPU double-precision BRDF: the oracle the GL path is tested against.

#include "brdf/params.hpp"
#include "core/math.hpp"

namespace hilite::brdf {

/// f(wi, wo) for unit directions in the local frame (n = +z). Zero when either is below the horizon.
dvec3 evaluate(const Params& p, const dvec3& wi, const dvec3& wo);

/// Reflected radiance from a distant light of irradiance E (normal to the light): f(wi, wo) E cos(theta_i).
dvec3 radiance(const Params& p, const dvec3& wi, const dvec3& wo, double irradiance);

/// The scalar lobe value the measurement uses: Rec. 709 luminance of the radiance.
inline double luminance(const dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

}  // namespace hilite::brdf
