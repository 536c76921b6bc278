#include "brdf/materials.hpp"

#include "hilite/brdf/terms.hpp"

namespace hilite::brdf {

namespace {

Material dielectric(const char* name, double eta, const char* source) {
    Material m{name, Fresnel::Dielectric, dvec3(eta), dvec3(0.0), dvec3(F_Dielectric(1.0, eta)), source};
    return m;
}

Material conductor(const char* name, const dvec3& eta, const dvec3& k, const char* source) {
    dvec3 f0;
    for (int c = 0; c < 3; ++c) f0[c] = F_Conductor(1.0, eta[c], k[c]);
    return {name, Fresnel::Conductor, eta, k, f0, source};
}

// Sources. Dielectrics: refractive index at the sodium D line (589 nm), dispersion ignored.
//   water   1.333  Hale & Querry 1973, Appl. Opt. 12, 555 (25 C)               F0 = 0.0204
//   glass   1.5    typical crown / soda-lime glass (Schott N-BK7: n_d = 1.5168) F0 = 0.0400
//   plastic 1.49   PMMA, Sultanova et al. 2009, Acta Phys. Pol. A 116, 585      F0 = 0.0387
//   diamond 2.417  Phillip & Taft 1964, Phys. Rev. 136, A1445                   F0 = 0.1720
// Metals, eta and k per channel at R = 652.5, G = 551.0, B = 450.9 nm (rows of the table pbrt-v4 and
// Mitsuba ship, pbrt-v4 src/pbrt/util/spectrum.cpp Ag_eta/Ag_k, Al_eta/Al_k, "data from www.luxpop.com"):
//   silver     eta (0.140, 0.124, 0.151)  k (4.150, 3.348, 2.479)   F0 = (0.97, 0.96, 0.92)
//   aluminium  eta (1.490, 0.963, 0.620)  k (7.820, 6.700, 5.480)   F0 = (0.91, 0.92, 0.92)
// iron: F0 only, linear (0.562, 0.565, 0.578), Real-Time Rendering 4th ed. (Akenine-Moller et al. 2018),
//   table 9.2 (Hoffman); no eta, k table of iron is in data/, so iron is a Schlick preset.
// copper, gold: spectral, data/metals/{Cu,Au}_eta_k.csv (sources on their first lines).
std::vector<Material> makeMaterials() {
    std::vector<Material> m;
    m.push_back(dielectric("water", 1.333, "Hale & Querry 1973, n at 589 nm"));
    m.push_back(dielectric("glass", 1.5, "crown glass, n_d ~ 1.5 (N-BK7 1.5168)"));
    m.push_back(dielectric("plastic", 1.49, "PMMA, Sultanova et al. 2009, n at 589 nm"));
    m.push_back(dielectric("diamond", 2.417, "Phillip & Taft 1964, n at 589 nm"));
    m.push_back(conductor("silver", {0.140000, 0.124375, 0.151063}, {4.150000, 3.348125, 2.478750},
                          "pbrt-v4 Ag_eta/Ag_k (luxpop) at 652.5/551.0/450.9 nm"));
    m.push_back(conductor("aluminium", {1.490000, 0.963000, 0.620313}, {7.820000, 6.700000, 5.480000},
                          "pbrt-v4 Al_eta/Al_k (luxpop) at 652.5/551.0/450.9 nm"));
    m.push_back({"iron",
                 Fresnel::Schlick,
                 dvec3(1.0),
                 dvec3(0.0),
                 {0.562, 0.565, 0.578},
                 "F0 from Real-Time Rendering 4th ed., table 9.2"});
    m.push_back({"copper", Fresnel::Spectral, dvec3(1.0), dvec3(0.0), dvec3(0.0), "data/metals/Cu_eta_k.csv"});
    m.push_back({"gold", Fresnel::Spectral, dvec3(1.0), dvec3(0.0), dvec3(0.0), "data/metals/Au_eta_k.csv"});
    return m;
}

}  // namespace

const std::vector<Material>& materials() {
    static const std::vector<Material> all = makeMaterials();
    return all;
}

const Material* findMaterial(const std::string& name) {
    for (const Material& m : materials())
        if (m.name == name) return &m;
    return nullptr;
}

std::vector<std::string> materialNames() {
    std::vector<std::string> out;
    for (const Material& m : materials()) out.push_back(m.name);
    return out;
}

}  // namespace hilite::brdf
