#include "brdf/evaluate.hpp"

#include "brdf/ndf.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/spectral.hpp"
#include "brdf/terms.hpp"

#include <stdexcept>

namespace hilite::brdf {

namespace {

const NdfTable& table(const Params& p) {
    if (!p.ndfTable) throw std::logic_error("model tabulated without a table (Params::ndfTable)");
    return *p.ndfTable;
}

double distribution(const Params& p, const HalfVector& hv) {
    if (p.anisotropic() && allowsAnisotropy(p.model)) {
        const dvec3 ht = toTangent(p, hv.h);
        return p.model == Model::GGX ? D_GGXAniso(ht.x, ht.y, hv.NoH, p.alphaX(), p.alphaY())
                                     : D_BeckmannAniso(ht.x, ht.y, hv.NoH, p.alphaX(), p.alphaY());
    }
    switch (p.model) {
        case Model::Blinn: return D_BlinnPhong(hv.oneMinusNoH, p.exponent);
        case Model::Beckmann: return D_Beckmann(hv.NoH, hv.sin2h, p.roughness);
        case Model::GGX: return D_GGX(hv.NoH, hv.sin2h, p.roughness);
        case Model::Gaussian: return D_Gaussian(hv.NoH, hv.sin2h, p.roughness, gaussianNormalization(p.roughness));
        case Model::Tabulated: return D_Tabulated(hv.NoH, hv.sin2h, table(p));
        case Model::Phong:
        case Model::PhongClassic:
        case Model::Retro:
        case Model::None: break;
    }
    return 0.0;
}

/// Smith Lambda of the model. Blinn-Phong and the Gaussian have no closed-form Lambda: they use Beckmann's
/// (Blinn with m = sqrt(2 / (n + 2)), Walter et al. 2007; the Gaussian with its own m, the two NDFs
/// agreeing to O(theta^2) near the normal). Good for narrow lobes only: the albedo stays <= 1 for
/// n >= 100 and m <= 0.1 but reaches 1.35 (blinn n = 1) and 1.06 (gaussian m = 0.7) at grazing
/// (tests/brdf/test_integrate.cpp reports them).
double lambda(const Params& p, const dvec3& w) {
    if (p.anisotropic() && allowsAnisotropy(p.model)) {
        const dvec3 wt = toTangent(p, w);
        return p.model == Model::GGX ? Lambda_GGXAniso(wt, p.alphaX(), p.alphaY())
                                     : Lambda_BeckmannAniso(wt, p.alphaX(), p.alphaY());
    }
    switch (p.model) {
        case Model::GGX: return Lambda_GGX(w.z, p.roughness);
        case Model::Beckmann:
        case Model::Gaussian: return Lambda_Beckmann(w.z, p.roughness);
        case Model::Blinn: return Lambda_Beckmann(w.z, blinnExponentToBeckmann(p.exponent));
        case Model::Tabulated: return Lambda_Tabulated(w.z, table(p));
        case Model::Phong:
        case Model::PhongClassic:
        case Model::Retro:
        case Model::None: break;
    }
    return 0.0;
}

/// D G / (4 NoL NoV) with the geometry term of the scene.
double microfacet(const Params& p, const HalfVector& hv, const dvec3& wi, const dvec3& wo) {
    const double D = distribution(p, hv), NoL = wi.z, NoV = wo.z;
    switch (p.geometry) {
        case Geometry::None: return D / (4.0 * NoL * NoV);  // G = 1
        case Geometry::Implicit: return D * 0.25;           // G = NoL NoV cancels the denominator
        case Geometry::CookTorrance: return D * G_CookTorrance(hv.NoH, NoV, NoL, hv.VoH) / (4.0 * NoL * NoV);
        case Geometry::SmithSeparable: return D * G2_SmithSeparable(lambda(p, wi), lambda(p, wo)) / (4.0 * NoL * NoV);
        case Geometry::Smith: return D * G2_SmithCorrelated(lambda(p, wi), lambda(p, wo)) / (4.0 * NoL * NoV);
    }
    return 0.0;
}

}  // namespace

dvec3 toTangent(const Params& p, const dvec3& w) {
    double c, s;
    cosSinDeg(p.tangentAngleDeg, c, s);
    return {w.x * c + w.y * s, -w.x * s + w.y * c, w.z};
}

double distribution(const Params& p, const dvec3& h) { return distribution(p, halfVectorOf(h)); }

dvec3 fresnel(const Params& p, double cosTheta) {
    switch (p.fresnel) {
        case Fresnel::None: return dvec3(1.0);
        case Fresnel::Schlick: return F_Schlick(p.f0, cosTheta);
        case Fresnel::Dielectric:
            return {F_Dielectric(cosTheta, p.eta.x), F_Dielectric(cosTheta, p.eta.y), F_Dielectric(cosTheta, p.eta.z)};
        case Fresnel::Conductor:
            return {F_Conductor(cosTheta, p.eta.x, p.k.x), F_Conductor(cosTheta, p.eta.y, p.k.y),
                    F_Conductor(cosTheta, p.eta.z, p.k.z)};
        case Fresnel::Spectral:
            if (!p.spectrum) throw std::logic_error("fresnel spectral without a sampled spectrum (Params::spectrum)");
            return F_Spectral(cosTheta, *p.spectrum);
    }
    return dvec3(1.0);
}

dvec3 evaluateSpecular(const Params& p, const dvec3& wi, const dvec3& wo) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return dvec3(0.0);  // light or viewer below the horizon
    if (p.model == Model::None) return dvec3(0.0);
    if (p.model == Model::Phong || p.model == Model::PhongClassic) {
        const dvec3 d = wo - dvec3(-wi.x, -wi.y, wi.z);  // wo - reflect(wi): 1 - cos = |d|^2 / 2
        const double oneMinusCosR = 0.5 * glm::dot(d, d);
        return dvec3(p.model == Model::Phong ? Phong_Normalized(oneMinusCosR, p.exponent)
                                             : Phong_Classic(oneMinusCosR, p.exponent));
    }
    if (p.model == Model::Retro) {
        const dvec3 d = wo - wi;  // 1 - cos(beta) = |d|^2 / 2
        return dvec3(Retro_Normalized(0.5 * glm::dot(d, d), p.exponent));
    }
    const HalfVector hv = halfVector(wi, wo);
    if (!hv.valid) return dvec3(0.0);
    return microfacet(p, hv, wi, wo) * fresnel(p, hv.VoH);
}

dvec3 evaluateDiffuse(const Params& p, const dvec3& wi, const dvec3& wo) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return dvec3(0.0);  // light or viewer below the horizon
    switch (p.diffuse) {
        case Diffuse::None: return dvec3(0.0);
        case Diffuse::Lambert: return Fd_Lambert(p.albedo);
        case Diffuse::OrenNayar: return Fd_OrenNayar(p.albedo, deg2rad(p.sigmaDeg), wi.z, wo.z, glm::dot(wi, wo));
    }
    return dvec3(0.0);
}

dvec3 evaluate(const Params& p, const dvec3& wi, const dvec3& wo) {
    return evaluateSpecular(p, wi, wo) + evaluateDiffuse(p, wi, wo);
}

dvec3 radiance(const Params& p, const dvec3& wi, const dvec3& wo, double irradiance) {
    return evaluate(p, wi, wo) * (irradiance * std::max(0.0, wi.z));
}

}  // namespace hilite::brdf
