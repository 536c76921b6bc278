#pragma once
// Every model and term combination of the BRDF, for the tests that sweep them all.

#include "brdf/spectral.hpp"
#include "hilite/brdf/params.hpp"

#include <vector>

namespace hilite::test {

struct ModelCase {
    brdf::Model model;
    bool anisotropic;
};

inline std::vector<ModelCase> allModels() {
    using brdf::Model;
    return {{Model::Phong, false},    {Model::PhongClassic, false}, {Model::Blinn, false},   {Model::Gaussian, false},
            {Model::Beckmann, false}, {Model::GGX, false},          {Model::Beckmann, true}, {Model::GGX, true},
            {Model::None, false},     {Model::Retro, false}};
}

/// Every model x geometry x Fresnel x diffuse, with parameters that give lobes of moderate width.
inline std::vector<brdf::Params> allCombinations() {
    using namespace brdf;
    std::vector<Params> out;
    const auto copper = loadSpectrum(HILITE_DATA_DIR, "copper", kGpuStepNm);
    for (ModelCase m : allModels())
        for (Geometry g :
             {Geometry::None, Geometry::Implicit, Geometry::CookTorrance, Geometry::SmithSeparable, Geometry::Smith})
            for (Fresnel f :
                 {Fresnel::None, Fresnel::Schlick, Fresnel::Dielectric, Fresnel::Conductor, Fresnel::Spectral})
                for (Diffuse d : {Diffuse::None, Diffuse::Lambert, Diffuse::OrenNayar}) {
                    Params p;
                    p.model = m.model;
                    p.exponent = 40.0;
                    p.roughness = 0.3;
                    if (m.anisotropic) {
                        p.roughnessY = 0.08;
                        p.tangentAngleDeg = 30.0;
                    }
                    p.geometry = g;
                    p.fresnel = f;
                    p.f0 = {0.9, 0.6, 0.3};
                    p.eta = {0.2, 1.0, 1.5};
                    p.k = {3.6, 2.6, 0.0};
                    if (f == Fresnel::Dielectric) p.eta = {1.33, 1.5, 0.7};  // 0.7: total internal reflection
                    if (f == Fresnel::Spectral) p.spectrum = copper;
                    p.diffuse = d;
                    p.albedo = {0.8, 0.5, 0.2};
                    p.sigmaDeg = 30.0;
                    out.push_back(p);
                }
    return out;
}

}  // namespace hilite::test
