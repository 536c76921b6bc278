#pragma once
// Material presets for the Fresnel term: the seed's materials with their measured optics and sources.
// A preset names the Fresnel mode it implies (dielectric, conductor, schlick-only or spectral) and the
// parameters of that mode; Schlick's F0 of a dielectric or conductor is its exact F at normal incidence.

#include "hilite/brdf/params.hpp"

#include <string>
#include <vector>

namespace hilite::brdf {

struct Material {
    std::string name;
    Fresnel fresnel = Fresnel::Dielectric;  ///< the mode the preset implies
    dvec3 eta{1.0}, k{0.0};                 ///< dielectric / conductor (per R, G, B); unused by schlick-only presets
    dvec3 f0{0.0};                          ///< Schlick F0: exact F(0) of eta, k, or the tabulated F0 (schlick-only)
    std::string source;                     ///< where the numbers come from
};

/// The presets, in the order the CLI lists them. copper and gold are spectral (brdf/spectral.hpp); their
/// eta, k and f0 come from the spectral data (scene/resolve.cpp resolveFresnel).
const std::vector<Material>& materials();
/// The preset of that name, or nullptr.
const Material* findMaterial(const std::string& name);
std::vector<std::string> materialNames();

}  // namespace hilite::brdf
