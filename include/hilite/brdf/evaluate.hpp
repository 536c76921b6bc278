#pragma once
// The CPU double-precision BRDF: the oracle the GL path is tested against. It calls the terms of
// brdf/terms.hpp through the C++ side of the rows of brdf/dispatch.hpp, whose GLSL side the generated
// GLSL dispatch calls (src/render/shader_source.cpp).

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

namespace hilite::brdf {

/// f(wi, wo) = specular + multiple scattering + diffuse for unit directions in the local frame (n = +z). Zero when either is
/// below the horizon.
dvec3 evaluate(const Params& p, const dvec3& wi, const dvec3& wo);
/// The model's lobe with its Fresnel and geometry terms (0 for Model::None); a measured table's lookup when
/// Params::measured is set (the table holds everything, so evaluateDiffuse is then 0).
dvec3 evaluateSpecular(const Params& p, const dvec3& wi, const dvec3& wo);
/// The diffuse term (0 for Diffuse::None).
dvec3 evaluateDiffuse(const Params& p, const dvec3& wi, const dvec3& wo);
/// The multiple-scattering term (0 for Multiscatter::None; brdf/energy.hpp).
dvec3 evaluateMultiscatter(const Params& p, const dvec3& wi, const dvec3& wo);

/// Reflected radiance from a distant light of irradiance E (normal to the light): f(wi, wo) E cos(theta_i).
dvec3 radiance(const Params& p, const dvec3& wi, const dvec3& wo, double irradiance);

/// The scalar lobe value the measurement uses: Rec. 709 luminance of the radiance.
inline double luminance(const dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

/// F of the scene's Fresnel term at cos(theta) (1 for Fresnel::None). Spectral needs p.spectrum
/// (std::logic_error without it).
dvec3 fresnel(const Params& p, double cosTheta);
/// D(h) of a microfacet model for a unit h in the local frame; 0 for the reflection lobes and none.
double distribution(const Params& p, const dvec3& h);
/// w in the tangent frame: rotated by -tangentAngle about n, so the tangent x axis becomes +x.
dvec3 toTangent(const Params& p, const dvec3& w);

}  // namespace hilite::brdf
