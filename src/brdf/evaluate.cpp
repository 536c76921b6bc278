#include "hilite/brdf/evaluate.hpp"

#include "brdf/dispatch.hpp"
#include "brdf/merl.hpp"
#include "brdf/rgl.hpp"

namespace hilite::brdf {

namespace {

/// D of the model's row; ht (the tangent frame) for the anisotropic rows only.
double distribution(const Params& p, const HalfVector& hv) {
    const dvec3 ht = anisotropicTerms(p) ? toTangent(p, hv.h) : dvec3(0.0);
    return distributionRow(p).cpp(p, hv, ht);
}

/// D G / (4 NoL NoV) with the geometry term of the scene.
double microfacet(const Params& p, const HalfVector& hv, const dvec3& wi, const dvec3& wo) {
    const double D = distribution(p, hv);
    double lambdaI = 0.0, lambdaO = 0.0;
    if (usesSmith(p)) {
        const LambdaRow& lambda = lambdaRow(p);
        lambdaI = lambda.cpp(p, wi);
        lambdaO = lambda.cpp(p, wo);
    }
    return geometryRow(p.geometry).cpp(hv, wi, wo, D, lambdaI, lambdaO);
}

}  // namespace

dvec3 toTangent(const Params& p, const dvec3& w) {
    double c, s;
    cosSinDeg(p.tangentAngleDeg, c, s);
    return {w.x * c + w.y * s, -w.x * s + w.y * c, w.z};
}

double distribution(const Params& p, const dvec3& h) {
    return isMicrofacet(p.model) ? distribution(p, halfVectorOf(h)) : 0.0;
}

dvec3 fresnel(const Params& p, double cosTheta) { return fresnelRow(p).cpp(p, cosTheta); }

dvec3 evaluateSpecular(const Params& p, const dvec3& wi, const dvec3& wo) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return dvec3(0.0);    // light or viewer below the horizon
    if (p.measured) return p.measured->evaluate(wi, wo);  // the table is the whole BRDF (multilinear, brdf/merl.hpp)
    if (p.rgl) return p.rgl->evaluate(wi, wo);            // an RGL material, indexed by the light (brdf/rgl.hpp)
    if (p.model == Model::None) return dvec3(0.0);
    if (!isMicrofacet(p.model)) return lobeRow(p.model).cpp(p, wi, wo);  // reflection lobes, the literature's models
    const HalfVector hv = halfVector(wi, wo);
    if (!hv.valid) return dvec3(0.0);
    return microfacet(p, hv, wi, wo) * fresnel(p, hv.VoH);
}

dvec3 evaluateDiffuse(const Params& p, const dvec3& wi, const dvec3& wo) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return dvec3(0.0);  // light or viewer below the horizon
    return diffuseRow(p.diffuse).cpp(p, wi, wo);
}

dvec3 evaluateMultiscatter(const Params& p, const dvec3& wi, const dvec3& wo) {
    if (p.multiscatter == Multiscatter::None) return dvec3(0.0);
    if (wi.z <= 0.0 || wo.z <= 0.0) return dvec3(0.0);  // light or viewer below the horizon
    return multiscatterRow(p.multiscatter).cpp(p, wi, wo);
}

dvec3 evaluate(const Params& p, const dvec3& wi, const dvec3& wo) {
    return evaluateSpecular(p, wi, wo) + evaluateMultiscatter(p, wi, wo) + evaluateDiffuse(p, wi, wo);
}

dvec3 radiance(const Params& p, const dvec3& wi, const dvec3& wo, double irradiance) {
    return evaluate(p, wi, wo) * (irradiance * std::max(0.0, wi.z));
}

}  // namespace hilite::brdf
