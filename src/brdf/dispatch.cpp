#include "brdf/dispatch.hpp"

#include "brdf/energy.hpp"
#include "brdf/ndf.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace hilite::brdf {

namespace {

const EnergyTables& energy(const Params& p) {
    if (!p.energy) throw std::logic_error("an energy term without its tables (Params::energy: brdf::energyTables)");
    return *p.energy;
}

const NdfTable& table(const Params& p) {
    if (!p.ndfTable) throw std::logic_error("model tabulated without a table (Params::ndfTable)");
    return *p.ndfTable;
}

template <class Key, class Row>
struct Keyed {
    Key key;
    Row row;
};

template <class Key, class Row>
const Row& find(const std::vector<Keyed<Key, Row>>& rows, const Key& key, const char* what) {
    auto it = std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r.key == key; });
    if (it == rows.end()) throw std::logic_error(std::string("no ") + what + " row for this BRDF");
    return it->row;
}

const char* const kAnisoUniforms[] = {"vec2 uAlpha", "vec2 uTangent"};  // alpha_x, alpha_y; cos, sin of the angle

/// SGD's GLSL call: Lobe_SGD per channel, each with its own parameters (the published fits differ by channel).
std::string sgdCall() {
    std::string s = "vec3(";
    for (const char* c : {"x", "y", "z"}) {
        s += std::string(*c == 'x' ? "" : ", ") + "Lobe_SGD(hv, wi, wo";
        for (const char* u : {"uSgdRhoS", "uSgdAlpha", "uSgdP", "uSgdNorm", "uSgdF0", "uSgdF1", "uSgdLambda", "uSgdC",
                              "uSgdK", "uSgdTheta0"})
            s += std::string(", ") + u + "." + c;
        s += ")";
    }
    return s + ")";
}
const std::string kSgdCall = sgdCall();

// ---- Reflection lobes and the literature's whole models ----
const std::vector<Keyed<Model, LobeRow>> kLobes = {
    {Model::Phong,
     {{"Phong_Normalized",
       {},
       "Phong_Normalized(0.5 * dot(d, d), uExponent)",
       {"float uExponent"},
       [](const Params& p, const dvec3& wi, const dvec3& wo) {
           const dvec3 d = wo - dvec3(-wi.x, -wi.y, wi.z);
           return dvec3(Phong_Normalized(0.5 * glm::dot(d, d), p.exponent));
       }},
      "vec3 d = wo - vec3(-wi.x, -wi.y, wi.z);  // wo - reflect(wi): 1 - cos = |d|^2 / 2"}},
    {Model::PhongClassic,
     {{"Phong_Classic",
       {},
       "Phong_Classic(0.5 * dot(d, d), uExponent)",
       {"float uExponent"},
       [](const Params& p, const dvec3& wi, const dvec3& wo) {
           const dvec3 d = wo - dvec3(-wi.x, -wi.y, wi.z);
           return dvec3(Phong_Classic(0.5 * glm::dot(d, d), p.exponent));
       }},
      "vec3 d = wo - vec3(-wi.x, -wi.y, wi.z);  // wo - reflect(wi): 1 - cos = |d|^2 / 2"}},
    {Model::Retro,
     {{"Retro_Normalized",
       {},
       "Retro_Normalized(0.5 * dot(d, d), uExponent)",
       {"float uExponent"},
       [](const Params& p, const dvec3& wi, const dvec3& wo) {
           const dvec3 d = wo - wi;
           return dvec3(Retro_Normalized(0.5 * glm::dot(d, d), p.exponent));
       }},
      "vec3 d = wo - wi;  // 1 - cos(beta) = |d|^2 / 2"}},
    {Model::ABC,
     {{"Lobe_ABC",
       {},
       "Lobe_ABC(hv, wi, wo, uAbcA, uAbcB, uAbcC, uEta)",
       {"vec3 uAbcA", "float uAbcB", "float uAbcC", "vec3 uEta"},
       [](const Params& p, const dvec3& wi, const dvec3& wo) {
           return Lobe_ABC(halfVector(wi, wo), wi, wo, p.abcA, p.abcB, p.abcC, p.eta);
       }},
      "HalfVector hv = halfVector(wi, wo);"}},
    {Model::SGD,
     {{"Lobe_SGD",
       {},
       kSgdCall.c_str(),
       {"vec3 uSgdRhoS", "vec3 uSgdAlpha", "vec3 uSgdP", "vec3 uSgdNorm", "vec3 uSgdF0", "vec3 uSgdF1",
        "vec3 uSgdLambda", "vec3 uSgdC", "vec3 uSgdK", "vec3 uSgdTheta0"},
       [](const Params& p, const dvec3& wi, const dvec3& wo) {
           const HalfVector hv = halfVector(wi, wo);
           const SgdParams& g = p.sgd;
           dvec3 f;
           for (int c = 0; c < 3; ++c)
               f[c] = Lobe_SGD(hv, wi, wo, g.rhoS[c], g.alpha[c], g.p[c], sgdNormalization(g.alpha[c], g.p[c]), g.f0[c],
                               g.f1[c], g.lambda[c], g.c[c], g.k[c], g.theta0[c]);
           return f;
       }},
      "HalfVector hv = halfVector(wi, wo);"}},
    {Model::Lafortune,
     {{"Lobe_Lafortune",
       {},
       "uLafortuneRhoS * Lobe_Lafortune(wi, wo, uLafortuneCxy, uLafortuneCz, uExponent)",
       {"vec3 uLafortuneRhoS", "float uLafortuneCxy", "float uLafortuneCz", "float uExponent"},
       [](const Params& p, const dvec3& wi, const dvec3& wo) {
           return p.lafortuneRhoS * Lobe_Lafortune(wi, wo, p.lafortuneCxy, p.lafortuneCz, p.exponent);
       }},
      ""}},
};

// ---- NDFs, keyed by (model, anisotropic) ----
using DistributionKey = std::pair<Model, bool>;
const std::vector<Keyed<DistributionKey, DistributionRow>> kDistributions = {
    {{Model::Blinn, false},
     {"D_BlinnPhong",
      {},
      "D_BlinnPhong(hv.oneMinusNoH, uExponent)",
      {"float uExponent"},
      [](const Params& p, const HalfVector& hv, const dvec3&) { return D_BlinnPhong(hv.oneMinusNoH, p.exponent); }}},
    {{Model::Beckmann, false},
     {"D_Beckmann",
      {},
      "D_Beckmann(hv.NoH, hv.sin2h, uRoughness)",
      {"float uRoughness"},
      [](const Params& p, const HalfVector& hv, const dvec3&) { return D_Beckmann(hv.NoH, hv.sin2h, p.roughness); }}},
    {{Model::GGX, false},
     {"D_GGX",
      {},
      "D_GGX(hv.NoH, hv.sin2h, uRoughness)",
      {"float uRoughness"},
      [](const Params& p, const HalfVector& hv, const dvec3&) { return D_GGX(hv.NoH, hv.sin2h, p.roughness); }}},
    {{Model::Gaussian, false},
     {"D_Gaussian",
      {},
      "D_Gaussian(hv.NoH, hv.sin2h, uRoughness, uGaussianNorm)",
      {"float uRoughness", "float uGaussianNorm"},
      [](const Params& p, const HalfVector& hv, const dvec3&) {
          return D_Gaussian(hv.NoH, hv.sin2h, p.roughness, gaussianNormalization(p.roughness));
      }}},
    {{Model::Tabulated, false},
     {"D_Tabulated",
      {},
      "D_Tabulated(hv.NoH, hv.sin2h)",
      {},  // its uniforms are in the block
      [](const Params& p, const HalfVector& hv, const dvec3&) { return D_Tabulated(hv.NoH, hv.sin2h, table(p)); }}},
    {{Model::Beckmann, true},
     {"D_BeckmannAniso",
      {},
      "D_BeckmannAniso(ht.x, ht.y, hv.NoH, uAlpha.x, uAlpha.y)",
      {kAnisoUniforms[0], kAnisoUniforms[1]},
      [](const Params& p, const HalfVector& hv, const dvec3& ht) {
          return D_BeckmannAniso(ht.x, ht.y, hv.NoH, p.alphaX(), p.alphaY());
      }}},
    {{Model::GGX, true},
     {"D_GGXAniso",
      {},
      "D_GGXAniso(ht.x, ht.y, hv.NoH, uAlpha.x, uAlpha.y)",
      {kAnisoUniforms[0], kAnisoUniforms[1]},
      [](const Params& p, const HalfVector& hv, const dvec3& ht) {
          return D_GGXAniso(ht.x, ht.y, hv.NoH, p.alphaX(), p.alphaY());
      }}},
};

// ---- Smith Lambda, keyed as the NDFs. Blinn-Phong and the Gaussian have no closed-form Lambda: they use
// Beckmann's (docs/terms.md, "Lambda of Blinn-Phong and the Gaussian"). ----
const std::vector<Keyed<DistributionKey, LambdaRow>> kLambdas = {
    {{Model::GGX, false},
     {"Lambda_GGX",
      {},
      "Lambda_GGX(w.z, uRoughness)",
      {"float uRoughness"},
      [](const Params& p, const dvec3& w) { return Lambda_GGX(w.z, p.roughness); }}},
    {{Model::Beckmann, false},
     {"Lambda_Beckmann",
      {},
      "Lambda_Beckmann(w.z, uRoughness)",
      {"float uRoughness"},
      [](const Params& p, const dvec3& w) { return Lambda_Beckmann(w.z, p.roughness); }}},
    {{Model::Gaussian, false},
     {"Lambda_Beckmann",
      {},
      "Lambda_Beckmann(w.z, uRoughness)",
      {"float uRoughness"},
      [](const Params& p, const dvec3& w) { return Lambda_Beckmann(w.z, p.roughness); }}},
    {{Model::Blinn, false},
     {"Lambda_Beckmann",
      {"blinnExponentToBeckmann"},
      "Lambda_Beckmann(w.z, blinnExponentToBeckmann(uExponent))",
      {"float uExponent"},
      [](const Params& p, const dvec3& w) { return Lambda_Beckmann(w.z, blinnExponentToBeckmann(p.exponent)); }}},
    {{Model::Tabulated, false},
     {"Lambda_Tabulated",
      {},
      "Lambda_Tabulated(w.z)",
      {},
      [](const Params& p, const dvec3& w) { return Lambda_Tabulated(w.z, table(p)); }}},
    {{Model::Beckmann, true},
     {"Lambda_BeckmannAniso",
      {},
      "Lambda_BeckmannAniso(toTangent(w), uAlpha.x, uAlpha.y)",
      {kAnisoUniforms[0], kAnisoUniforms[1]},
      [](const Params& p, const dvec3& w) { return Lambda_BeckmannAniso(toTangent(p, w), p.alphaX(), p.alphaY()); }}},
    {{Model::GGX, true},
     {"Lambda_GGXAniso",
      {},
      "Lambda_GGXAniso(toTangent(w), uAlpha.x, uAlpha.y)",
      {kAnisoUniforms[0], kAnisoUniforms[1]},
      [](const Params& p, const dvec3& w) { return Lambda_GGXAniso(toTangent(p, w), p.alphaX(), p.alphaY()); }}},
};

// ---- Fresnel ----
const std::vector<Keyed<Fresnel, FresnelRow>> kFresnels = {
    {Fresnel::None, {"", {}, "vec3(1.0)", {}, [](const Params&, double) { return dvec3(1.0); }}},
    {Fresnel::Schlick,
     {"F_Schlick",
      {},
      "F_Schlick(uF0, VoH)",
      {"vec3 uF0"},
      [](const Params& p, double VoH) { return F_Schlick(p.f0, VoH); }}},
    {Fresnel::Dielectric,
     {"F_Dielectric",
      {},
      "vec3(F_Dielectric(VoH, uEta.r), F_Dielectric(VoH, uEta.g), F_Dielectric(VoH, uEta.b))",
      {"vec3 uEta"},
      [](const Params& p, double VoH) {
          return dvec3(F_Dielectric(VoH, p.eta.x), F_Dielectric(VoH, p.eta.y), F_Dielectric(VoH, p.eta.z));
      }}},
    {Fresnel::Conductor,
     {"F_Conductor",
      {},
      "vec3(F_Conductor(VoH, uEta.r, uK.r), F_Conductor(VoH, uEta.g, uK.g), F_Conductor(VoH, uEta.b, uK.b))",
      {"vec3 uEta", "vec3 uK"},
      [](const Params& p, double VoH) {
          return dvec3(F_Conductor(VoH, p.eta.x, p.k.x), F_Conductor(VoH, p.eta.y, p.k.y),
                       F_Conductor(VoH, p.eta.z, p.k.z));
      }}},
    {Fresnel::Spectral,
     {"F_Spectral",
      {},
      "F_Spectral(VoH, uSpectralEtaK, uSpectralWeight)",
      {"vec2 uSpectralEtaK[HILITE_SPECTRAL_SAMPLES]", "vec3 uSpectralWeight[HILITE_SPECTRAL_SAMPLES]"},
      [](const Params& p, double VoH) {
          if (!p.spectrum) throw std::logic_error("fresnel spectral without a sampled spectrum (Params::spectrum)");
          return F_Spectral(VoH, *p.spectrum);
      }}},
};
/// Fresnel::Spectral read from the spectrum's table (Params::spectralTable).
const FresnelRow kSpectralTable = {"F_SpectralTable",
                                   {},
                                   "F_SpectralTable(VoH)",
                                   {},  // its uniform is in the block
                                   [](const Params& p, double VoH) {
                                       if (!p.spectrum)
                                           throw std::logic_error("fresnel spectral without a sampled spectrum");
                                       return F_SpectralTable(VoH, *p.spectrum);
                                   }};

// ---- Geometry: D G / (4 cos_i cos_o) from s = D (the Lambdas of the model's row, for the Smith rows) ----
const std::vector<Keyed<Geometry, GeometryRow>> kGeometries = {
    {Geometry::None,
     {"",
      {},
      "s /= 4.0 * wi.z * wo.z;  // G = 1",
      {},
      [](const HalfVector&, const dvec3& wi, const dvec3& wo, double D, double, double) {
          return D / (4.0 * wi.z * wo.z);
      }}},
    {Geometry::Implicit,
     {"",
      {},
      "s *= 0.25;  // implicit G = cos(theta_i) cos(theta_o) cancels the denominator",
      {},
      [](const HalfVector&, const dvec3&, const dvec3&, double D, double, double) { return D * 0.25; }}},
    {Geometry::CookTorrance,
     {"G_CookTorrance",
      {},
      "s *= G_CookTorrance(hv.NoH, wo.z, wi.z, hv.VoH) / (4.0 * wi.z * wo.z);",
      {},
      [](const HalfVector& hv, const dvec3& wi, const dvec3& wo, double D, double, double) {
          return D * G_CookTorrance(hv.NoH, wo.z, wi.z, hv.VoH) / (4.0 * wi.z * wo.z);
      }}},
    {Geometry::SmithSeparable,
     {"G2_SmithSeparable",
      {},
      "s *= G2_SmithSeparable(lambda(wi), lambda(wo)) / (4.0 * wi.z * wo.z);",
      {},
      [](const HalfVector&, const dvec3& wi, const dvec3& wo, double D, double lambdaI, double lambdaO) {
          return D * G2_SmithSeparable(lambdaI, lambdaO) / (4.0 * wi.z * wo.z);
      }}},
    {Geometry::Smith,
     {"G2_SmithCorrelated",
      {},
      "s *= G2_SmithCorrelated(lambda(wi), lambda(wo)) / (4.0 * wi.z * wo.z);",
      {},
      [](const HalfVector&, const dvec3& wi, const dvec3& wo, double D, double lambdaI, double lambdaO) {
          return D * G2_SmithCorrelated(lambdaI, lambdaO) / (4.0 * wi.z * wo.z);
      }}},
};

// ---- Diffuse ----
const std::vector<Keyed<Diffuse, DiffuseRow>> kDiffuses = {
    {Diffuse::None, {"", {}, "vec3(0.0)", {}, [](const Params&, const dvec3&, const dvec3&) { return dvec3(0.0); }}},
    {Diffuse::Lambert,
     {"Fd_Lambert",
      {},
      "Fd_Lambert(uAlbedo)",
      {"vec3 uAlbedo"},
      [](const Params& p, const dvec3&, const dvec3&) { return Fd_Lambert(p.albedo); }}},
    {Diffuse::OrenNayar,
     {"Fd_OrenNayar",
      {},
      "Fd_OrenNayar(uAlbedo, uSigma, wi.z, wo.z, dot(wi, wo))",
      {"vec3 uAlbedo", "float uSigma"},  // sigma in radians
      [](const Params& p, const dvec3& wi, const dvec3& wo) {
          return Fd_OrenNayar(p.albedo, deg2rad(p.sigmaDeg), wi.z, wo.z, glm::dot(wi, wo));
      }}},
    {Diffuse::Coupled,
     {"Fd_Coupled",
      {"EnergyEs"},
      "Fd_Coupled(uAlbedo, energyEs(wi.z), energyEs(wo.z), uEnergyEsAvg)",
      {"vec3 uAlbedo", "vec3 uEnergyEsAvg"},
      [](const Params& p, const dvec3& wi, const dvec3& wo) {
          const EnergyTables& t = energy(p);
          return Fd_Coupled(p.albedo, energyEs(wi.z, t), energyEs(wo.z, t), t.EsAvg);
      }}},
};

// ---- Multiple scattering ----
const std::vector<Keyed<Multiscatter, MultiscatterRow>> kMultiscatters = {
    {Multiscatter::None,
     {"", {}, "vec3(0.0)", {}, [](const Params&, const dvec3&, const dvec3&) { return dvec3(0.0); }}},
    {Multiscatter::KullaConty,
     {"MS_KullaConty",
      {"EnergyE"},
      "MS_KullaConty(energyE(wi.z), energyE(wo.z), uEnergyEavg, uEnergyFms)",
      {"float uEnergyEavg", "vec3 uEnergyFms"},
      [](const Params& p, const dvec3& wi, const dvec3& wo) {
          const EnergyTables& t = energy(p);
          return MS_KullaConty(energyE(wi.z, t), energyE(wo.z, t), t.Eavg, t.Fms);
      }}},
};

}  // namespace

bool anisotropicTerms(const Params& p) { return p.anisotropic() && allowsAnisotropy(p.model); }
bool usesSmith(const Params& p) { return p.geometry == Geometry::Smith || p.geometry == Geometry::SmithSeparable; }

const LobeRow& lobeRow(Model m) { return find(kLobes, m, "reflection lobe"); }
const DistributionRow& distributionRow(const Params& p) {
    return find(kDistributions, DistributionKey{p.model, anisotropicTerms(p)}, "NDF");
}
const LambdaRow& lambdaRow(const Params& p) {
    return find(kLambdas, DistributionKey{p.model, anisotropicTerms(p)}, "Smith Lambda");
}
const FresnelRow& fresnelRow(Fresnel f) { return find(kFresnels, f, "Fresnel"); }
const FresnelRow& fresnelRow(const Params& p) {
    return p.fresnel == Fresnel::Spectral && p.spectralTable ? kSpectralTable : fresnelRow(p.fresnel);
}
const GeometryRow& geometryRow(Geometry g) { return find(kGeometries, g, "geometry"); }
const DiffuseRow& diffuseRow(Diffuse d) { return find(kDiffuses, d, "diffuse"); }
const MultiscatterRow& multiscatterRow(Multiscatter m) { return find(kMultiscatters, m, "multiple-scattering"); }

}  // namespace hilite::brdf
