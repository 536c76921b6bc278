#pragma once
// The BRDF a scene names: model, its parameters, and the terms switched in. Every enum parses from
// and prints to the CLI's spelling, so every run can log exactly what it evaluated.
// f = specular (the model's lobe, with its Fresnel and geometry terms) + diffuse (when one is named).

#include "hilite/core/math.hpp"

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hilite::brdf {

struct Spectrum;      // brdf/spectral.hpp
struct NdfTable;      // brdf/ndf_table.hpp
struct EnergyTables;  // brdf/energy.hpp
namespace merl {
struct MeasuredBrdf;  // brdf/merl.hpp
}
namespace rgl {
struct Material;  // brdf/rgl.hpp
}

/// Specular model: a reflection lobe about the mirror direction, or a microfacet NDF of the half vector.
enum class Model {
    Phong,         ///< normalized Phong reflection lobe (n+2)/(2 pi) cos^n(alpha_r)
    Blinn,         ///< microfacet, Blinn-Phong NDF (n+2)/(2 pi) cos^n(theta_h)
    Beckmann,      ///< microfacet, Beckmann NDF with rms slope m (anisotropic with roughnessY)
    GGX,           ///< microfacet, Trowbridge-Reitz / GGX NDF with width alpha (anisotropic with roughnessY)
    PhongClassic,  ///< classic unnormalized Phong lobe cos^n(alpha_r) (k_s = 1): not energy-conserving
    Gaussian,      ///< microfacet, Gaussian NDF k_G exp(-(theta_h / m)^2) in the angle theta_h
    None,          ///< no specular lobe: the diffuse term alone
    Retro,         ///< retroreflective lobe (n+2)/(2 pi) cos^n(beta), beta = angle(wo, wi): back toward the light
    Tabulated,     ///< microfacet, a hand-painted NDF: D(theta_h) from a table (Params::ndfTable, brdf/ndf_table.hpp)
    // The literature's fitted models, each whole as published, with its own Fresnel and masking (isLiterature):
    ABC,        ///< Low et al. 2012: F(eta) A G_CT / ((1 + B (1 - cos theta_h))^C pi cos_i cos_o)
    SGD,        ///< Bagher et al. 2012, shifted gamma distribution: rho_s F_sgd D_sgd G1 G1 / (pi cos_i cos_o)
    Lafortune,  ///< one Lafortune lobe as Ngan et al. 2005 fit it: rho_s (n+2)/(2 pi) max(0, C.(wi * wo))^n / max|C|^n
};
enum class Fresnel {
    None,        ///< F = 1
    Schlick,     ///< F0 + (1 - F0)(1 - cos)^5
    Dielectric,  ///< exact, unpolarized, real relative index eta per channel (eta < 1: total internal reflection)
    Conductor,   ///< exact, unpolarized, complex index eta + i k per channel
    Spectral,    ///< exact conductor per wavelength of a measured metal, integrated to linear sRGB
};
enum class Geometry {
    Implicit,        ///< G = cos(theta_i) cos(theta_o), so f = D F / 4
    Smith,           ///< height-correlated Smith G2 = 1 / (1 + Lambda(wi) + Lambda(wo))
    None,            ///< G = 1: f = D F / (4 cos_i cos_o), diverges at grazing
    CookTorrance,    ///< V-cavity G = min(1, 2 NoH NoV / VoH, 2 NoH NoL / VoH)
    SmithSeparable,  ///< separable Smith G2 = G1(wi) G1(wo), G1 = 1 / (1 + Lambda)
};
enum class Diffuse {
    None,       ///< no diffuse term
    Lambert,    ///< rho / pi
    OrenNayar,  ///< Oren-Nayar qualitative rough diffuse, facet slope deviation sigma
    Coupled,    ///< rho (1 - E_s(mu_i)) (1 - E_s(mu_o)) / (pi (1 - E_s_avg)): what the specular albedo E_s leaves
};
/// Energy the single-scattering microfacet lobe loses to masking (light that bounces more than once).
enum class Multiscatter {
    None,        ///< single scattering only
    KullaConty,  ///< Kulla & Conty 2017: (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)) F_ms (brdf/energy.hpp)
};

const char* toString(Model);
const char* toString(Fresnel);
const char* toString(Geometry);
const char* toString(Diffuse);
const char* toString(Multiscatter);
std::optional<Model> parseModel(const std::string&);
std::optional<Fresnel> parseFresnel(const std::string&);
std::optional<Geometry> parseGeometry(const std::string&);
std::optional<Diffuse> parseDiffuse(const std::string&);
std::optional<Multiscatter> parseMultiscatter(const std::string&);
std::vector<std::string> modelNames();
std::vector<std::string> fresnelNames();
std::vector<std::string> geometryNames();
std::vector<std::string> diffuseNames();
std::vector<std::string> multiscatterNames();

bool isMicrofacet(Model m);
bool usesExponent(
    Model m);  ///< phong, phong-classic, blinn, retro take an exponent; beckmann, ggx, gaussian a roughness
bool allowsAnisotropy(Model m);  ///< beckmann, ggx
/// abc, sgd, lafortune: a published model whole (its lobe, Fresnel and masking in one term, docs/literature.md);
/// --fresnel, --geometry and --multiscatter do not apply, a diffuse term does.
bool isLiterature(Model m);

/// Bagher et al. 2012's shifted gamma distribution, per channel (the published fits differ by channel).
/// D = K exp(-a) / (pi a^p cos^4 theta_h), a = alpha + tan^2 theta_h / alpha, K = 1 / (alpha Gamma(1 - p, alpha))
/// so that int D cos theta_h dw = 1 (the paper's k_ap; the published fits' kap enters rho_s, brdf/literature.hpp);
/// F = f0 - f1 cos theta_d + (1 - cos theta_d)^5 (1 - f0); G1 = clamp(1 + lambda (1 - exp(c max(0, theta -
/// theta0)^k)), 0, 1). Defaults: near MERL gray-plastic's green channel as Bagher et al. fit it, with lambda 2 for
/// its 1.77: G1 then reaches 0 before the horizon (at 1.77 it ends at 0.08 and f grows as 1 / cos(theta_o) there).
struct SgdParams {
    dvec3 rhoS{0.5};  ///< height of the normalized D (a published fit's rho_s kap / K)
    dvec3 alpha{0.0085}, p{0.55};
    dvec3 f0{0.044}, f1{0.022};
    dvec3 lambda{2.0}, c{5.3e-08}, k{63.2}, theta0{0.284};  ///< theta0 in radians
};

struct Params {
    Model model = Model::GGX;
    double exponent = 1000.0;  ///< phong / phong-classic / blinn n
    double roughness =
        0.1;  ///< beckmann m, ggx alpha, gaussian m in radians (the formulas' symbols); alpha_x if anisotropic
    std::optional<double> roughnessY;  ///< beckmann / ggx alpha_y: present = anisotropic (even when equal to roughness)
    double tangentAngleDeg = 0.0;      ///< azimuth of the tangent x axis (the alpha_x direction) from +x
    Fresnel fresnel = Fresnel::None;
    dvec3 f0{0.04, 0.04, 0.04};                ///< schlick
    dvec3 eta{1.5, 1.5, 1.5};                  ///< dielectric / conductor: real part of the relative index n_t / n_i
    dvec3 k{0.0, 0.0, 0.0};                    ///< conductor: extinction coefficient
    std::shared_ptr<const Spectrum> spectrum;  ///< spectral: the sampled metal (see brdf/spectral.hpp)
    /// spectral: F from the spectrum's table over cos theta_d (F_SpectralTable, within 1e-5) instead of the
    /// per-wavelength sum at every evaluation (F_Spectral, exact); --spectral-fresnel table | exact
    bool spectralTable = true;
    std::shared_ptr<const NdfTable> ndfTable;  ///< tabulated: the normalized table (see brdf/ndf_table.hpp)
    /// measured: a MERL table (brdf/merl.hpp) that is the whole BRDF (lobe with its F and G, and any diffuse):
    /// when set, model, fresnel, geometry and diffuse are unused (resolve sets them to none) and evaluate()
    /// returns the table's multilinear lookup.
    std::shared_ptr<const merl::MeasuredBrdf> measured;
    /// measured: an RGL `.bsdf` material (brdf/rgl.hpp), the whole BRDF as a MERL table is (at most one of the two)
    std::shared_ptr<const rgl::Material> rgl;
    /// Whether a measured table (MERL or RGL) is the whole BRDF.
    bool isMeasured() const { return measured || rgl; }
    Geometry geometry = Geometry::Implicit;
    Diffuse diffuse = Diffuse::None;
    dvec3 albedo{0.5, 0.5, 0.5};  ///< lambert / oren-nayar rho
    double sigmaDeg = 20.0;       ///< oren-nayar facet slope standard deviation, degrees
    Multiscatter multiscatter = Multiscatter::None;
    /// abc: A per channel, B, C (defaults: near MERL gray-plastic as Low et al. fit it; its F uses eta)
    dvec3 abcA{200.0};
    double abcB = 34000.0, abcC = 1.02;
    SgdParams sgd;  ///< sgd
    /// lafortune: rho_s per channel, C_xy, C_z (the exponent is `exponent`); C_xy = -C_z is a lobe about the mirror
    /// direction (rho_s times the normalized Phong lobe)
    dvec3 lafortuneRhoS{0.3};
    double lafortuneCxy = -1.0, lafortuneCz = 1.0;
    /// kulla-conty, coupled: the directional albedo tables of this BRDF (brdf::energyTables(p), made by
    /// scene::resolve); they belong to the parameters they were made for, so set them again after a change.
    std::shared_ptr<const EnergyTables> energy;

    bool anisotropic() const { return roughnessY.has_value(); }
    double alphaX() const { return roughness; }
    double alphaY() const { return roughnessY.value_or(roughness); }
};

/// A perfect mirror: a microfacet model with roughness 0 (along either axis when anisotropic). Its lobe is
/// a delta: every term returns 0 (no finite point sample of it exists) and the measurement says `mirror`.
bool isDelta(const Params& p);

std::ostream& operator<<(std::ostream&, const Params&);
std::ostream& operator<<(std::ostream&, Model);
std::ostream& operator<<(std::ostream&, Fresnel);
std::ostream& operator<<(std::ostream&, Geometry);
std::ostream& operator<<(std::ostream&, Diffuse);
std::ostream& operator<<(std::ostream&, Multiscatter);

/// Allowed ranges, checked at the CLI boundary (the error names the flag and the range).
constexpr double kMinExponent = 0.0, kMaxExponent = 1e8;
/// Roughness 0 is accepted: a perfect mirror (isDelta). Values in (0, kMinNonzeroRoughness) are clamped up
/// to it at the CLI, with a warning: below it float32 breaks down in the shader (GGX's alpha^4 in the
/// denominator underflows for alpha < 3e-10, and 1 / (pi alpha^2) nears FLT_MAX), and every lobe is
/// already 8x narrower than what float directions resolve (measurement flag `effectively_mirror`).
constexpr double kMinRoughness = 0.0, kMaxRoughness = 10.0;
constexpr double kMinNonzeroRoughness = 1e-7;
/// `hilite brdf albedo` and `normalization` integrate the lobe numerically: graded Gauss-Legendre panels
/// resolve lobes down to this width (brdf/integrate.hpp).
constexpr double kMinIntegrableRoughness = 1e-4;
/// eta below 0.01 (or eta = k = 0) makes the conductor formula 0/0; measured visible metals have
/// eta in [0.03, 5] and k below 10, dielectrics eta in [1, 4].
constexpr double kMinEta = 0.01, kMaxEta = 100.0;
constexpr double kMinK = 0.0, kMaxK = 100.0;
/// Oren-Nayar sigma: 0 is Lambert; beyond 90 degrees a slope deviation means nothing.
constexpr double kMinSigmaDeg = 0.0, kMaxSigmaDeg = 90.0;

}  // namespace hilite::brdf
