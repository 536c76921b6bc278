#include "brdf/evaluate.hpp"

#include "brdf/terms.hpp"

namespace hilite::brdf {

namespace {

/// Half vector, NoH, |n x h|^2 and VoH, computed once for a direction pair.
struct HalfVector {
    double NoH = 0, sin2h = 0, oneMinusNoH = 0, VoH = 0;
    bool valid = false;  ///< false when wi = -wo: no half vector exists
};

HalfVector halfVector(const dvec3& wi, const dvec3& wo) {
    HalfVector hv;
    const dvec3 s = wi + wo;
    const double len = glm::length(s);
    if (len < 1e-12) return hv;  // wi = -wo (only possible with wo below the horizon): degenerate
    const dvec3 h = s / len;
    hv.NoH = h.z;
    hv.sin2h = h.x * h.x + h.y * h.y;                     // |n x h|^2, exact where 1 - NoH^2 cancels
    hv.oneMinusNoH = hv.NoH > 0 ? hv.sin2h / (1.0 + hv.NoH) : 1.0;  // 1 - cos = sin^2 / (1 + cos)
    hv.VoH = glm::dot(wo, h);
    hv.valid = true;
    return hv;
}

double distribution(const Params& p, const HalfVector& hv) {
    switch (p.model) {
        case Model::Blinn: return D_BlinnPhong(hv.oneMinusNoH, p.exponent);
        case Model::Beckmann: return D_Beckmann(hv.NoH, hv.sin2h, p.roughness);
        case Model::GGX: return D_GGX(hv.NoH, hv.sin2h, p.roughness);
        case Model::Phong: break;
    }
    return 0.0;
}

double lambda(const Params& p, double cosTheta) {
    switch (p.model) {
        case Model::GGX: return Lambda_GGX(cosTheta, p.roughness);
        case Model::Beckmann: return Lambda_Beckmann(cosTheta, p.roughness);
        case Model::Blinn: return Lambda_Beckmann(cosTheta, blinnExponentToBeckmann(p.exponent));
        case Model::Phong: break;
    }
    return 0.0;
}

}  // namespace

dvec3 evaluate(const Params& p, const dvec3& wi, const dvec3& wo) {
    const double NoL = wi.z, NoV = wo.z;
    if (NoL <= 0.0 || NoV <= 0.0) return dvec3(0.0);  // light or viewer below the horizon
    if (p.model == Model::Phong) {
        const dvec3 wr(-wi.x, -wi.y, wi.z);
        const dvec3 d = wo - wr;
        return dvec3(Phong_Normalized(0.5 * glm::dot(d, d), p.exponent));  // 1 - cos = |wo - wr|^2 / 2
    }
    const HalfVector hv = halfVector(wi, wo);
    if (!hv.valid) return dvec3(0.0);
    const double D = distribution(p, hv);
    const dvec3 F = p.fresnel == Fresnel::Schlick ? F_Schlick(p.f0, hv.VoH) : dvec3(1.0);
    if (p.geometry == Geometry::Implicit) return D * F * 0.25;  // G = NoL NoV cancels the denominator
    const double G = G2_SmithCorrelated(lambda(p, NoL), lambda(p, NoV));
    return D * G * F / (4.0 * NoL * NoV);
}

dvec3 radiance(const Params& p, const dvec3& wi, const dvec3& wo, double irradiance) {
    return evaluate(p, wi, wo) * (irradiance * std::max(0.0, wi.z));
}

}  // namespace hilite::brdf
