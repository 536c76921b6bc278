#pragma once
// Directional-albedo tables of a BRDF for its energy terms, integrated by hilite's own quadrature
// (brdf::albedo), and the C++ twins of their GLSL lookups (shaders/brdf_gl.glsl, EnergyE / EnergyEs):
//  - multiple scattering, Kulla & Conty 2017 ("Revisiting Physically Based Shading at Imageworks", SIGGRAPH
//    course): E(mu) = the lobe's single-scattering albedo with F = 1; the light masking takes from it,
//    1 - E(mu), returns as f_ms = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)) F_ms with
//    E_avg = 2 int E(mu) mu dmu, and the colour of the further bounces F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),
//    F_avg = 2 int F(mu) mu dmu (the series of bounces, each reflecting F_avg, of which a share E_avg leaves).
//    Its albedo is E(mu_i) + (1 - E(mu_i)) F_ms: exactly 1 with F = 1 (the white furnace).
//  - the coupled diffuse: E_s(mu) = the specular albedo (lobe + multiple scattering, with the scene's Fresnel);
//    f_d = rho (1 - E_s(mu_i)) (1 - E_s(mu_o)) / (pi (1 - E_s_avg)), whose albedo is rho (1 - E_s(mu_i)), so
//    specular + diffuse = E_s + rho (1 - E_s) <= 1 (the same form as Kulla & Conty's, the body taking what the
//    surface leaves; cf. Ashikhmin & Shirley 2000, Kelemen & Szirmay-Kalos 2001).
// Both terms depend on the directions through mu_i = wi.z and mu_o = wo.z alone. Derivation and measured
// accuracy: docs/terms.md, "Energy terms".

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

#include <memory>
#include <string>
#include <vector>

namespace hilite::brdf {

/// Entries of each table over mu = cos(theta) in [0, 1]: entry i holds the albedo at mu = (i / (N - 1))^2,
/// spaced evenly in sqrt(mu), denser toward grazing where E bends most, and linear in sqrt(mu) between entries.
/// 64 entries keep the worst interpolation error below 1e-3 for GGX alpha >= 0.1 (EnergyTables::eError holds it,
/// measured at the midpoints when the table is made).
constexpr int kEnergyTableSize = 64;

struct EnergyTables {
    std::vector<double> E;  ///< kulla-conty: single-scattering albedo with F = 1 per entry (empty otherwise)
    double Eavg = 1.0;      ///< 2 int E mu dmu of the interpolated table (so the compensation's own integral is exact)
    dvec3 Favg{1.0};        ///< 2 int F(mu) mu dmu of the scene's Fresnel
    dvec3 Fms{1.0};         ///< F_avg^2 E_avg / (1 - F_avg (1 - E_avg))
    double eError = 0.0;    ///< worst |table - albedo| at the midpoints between entries (sqrt(mu) midpoints)
    /// coupled: specular albedo (lobe + multiple scattering) per entry, raised by esError (at most 1) so the
    /// interpolant stays above the true E_s and specular + diffuse <= 1 holds through the table (empty otherwise)
    std::vector<dvec3> Es;
    dvec3 EsAvg{0.0};      ///< 2 int E_s mu dmu of the interpolated table
    double esError = 0.0;  ///< as eError, for E_s (the largest channel)
};

/// Why p cannot carry the energy terms it names ("" when it can): multiscatter needs an isotropic microfacet
/// model with Smith geometry (the loss it returns is Smith's masking) and an integrable roughness; the coupled
/// diffuse an isotropic built-in lobe. resolve() puts the flag in front.
std::string energyRefusal(const Params& p);

/// The tables p's terms need (kulla-conty: E, coupled: E_s): ~64 albedo integrals per table (2 with both), made
/// on every call (scene::resolve keeps them per BRDF, keyed on its registry values: scene::energyKey). std::invalid_argument with the reason when p cannot have them (see
/// energyRefusal, and a specular albedo above 1, which leaves the body a negative share).
std::shared_ptr<const EnergyTables> energyTables(const Params& p);

/// The tables' mu of entry i: (i / (N - 1))^2.
double energyTableMu(int i);
/// E(mu) from the table, linear in sqrt(mu) (mu clamped to [0, 1]); GLSL twin energyE.
double energyE(double mu, const EnergyTables& t);
/// E_s(mu) likewise; GLSL twin energyEs.
dvec3 energyEs(double mu, const EnergyTables& t);

/// What a table describes, for explain: entries, E_avg, F_ms, interpolation error.
std::string describeEnergy(const Params& p);

}  // namespace hilite::brdf
