#pragma once
// Shadowing and masking from geometry: visibility rays traced against a bump field's true height field,
// aggregated over its facets and set beside Smith's G (Smith 1967; Heitz 2014 "Understanding the
// masking-shadowing function in microfacet-based BRDFs").
//
// A facet at a uniformly random point of the tile, with normal m, counts with its projected area toward wo
// per unit area of the plane, a = max(0, wo.m) / m.z; it is visible from w when the ray from it along w
// leaves the field without passing below the surface (marched in quarter-texel steps on the bilinear heights).
//   G1(wo) over all facets = sum a V(wo) / sum a. Every line of sight meets a height field once, so
//     sum a V = cos(theta_o): traced G1 = cos(theta_o) / mean(a) = 1 / (1 + Lambda) of the realised slopes,
//     exactly Smith's G1 (a check of the tracer, not of Smith).
//   The highlight's facets: those whose normal is near the half vector h of the specular pair (wi the mirror
//     image of wo, so h = n), |s - s_h| < roughness / 2. Smith assumes a facet's visibility does not depend on
//     its normal: G1(wo, m) = G1(wo) and, height-correlated, G2(wi, wo, m) = 1 / (1 + Lambda(wi) + Lambda(wo)).
//     These are what the traced values test.

#include "hilite/micro/bump_field.hpp"

#include <cstdint>
#include <vector>

namespace hilite::micro {

/// Beckmann's exact Smith Lambda: (erf(a) - 1)/2 + exp(-a^2) / (2 a sqrt(pi)), a = 1 / (m tan theta).
/// Beckmann & Spizzichino 1963; Walter et al. 2007 eq. 27 (the rational fit lambdaBeckmannRational in shaders/brdf.glsl is within 0.35%).
double lambdaBeckmannExact(double cosTheta, double m);

struct MaskingRow {
    double thetaDeg = 0;
    long samples = 0;  ///< facets traced (all), and of those near h
    long highlightFacets = 0;
    double g1 = 0, g1Err = 0;    ///< traced over all facets, and one standard error of the ratio estimate
    double g1Realized = 0;       ///< cos(theta) / mean(a): Smith's G1 of the realised slopes (no tracing)
    double g1Smith = 0;          ///< 1 / (1 + Lambda) with the nominal roughness (exact Beckmann Lambda)
    double g1h = 0, g1hErr = 0;  ///< traced over the highlight's facets (m near h = n)
    double g2 = 0, g2Err = 0;    ///< traced, highlight's facets, wi = mirror image of wo
    double g2Smith = 0;          ///< height-correlated 1 / (1 + 2 Lambda)
    double g2Uncorrelated = 0;   ///< separable G1(wi) G1(wo) = 1 / (1 + Lambda)^2
};

/// Traces `samples` random facets (seeded) for each exitant angle (azimuth 0). Beckmann fields only
/// (a GGX field is a normal map, not a height field): throws std::invalid_argument otherwise.
std::vector<MaskingRow> traceMasking(const BumpField& f, const std::vector<double>& thetasDeg, long samples,
                                     uint64_t seed);

}  // namespace hilite::micro
