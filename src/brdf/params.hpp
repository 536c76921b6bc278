#pragma once
// The BRDF a scene names: model, its parameters, and the terms switched in. Every enum parses from
// and prints to the CLI's spelling, so every run can log exactly what it evaluated.

#include "core/math.hpp"

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace hilite::brdf {

/// Specular model: a reflection lobe about the mirror direction, or a microfacet NDF of the half vector.
enum class Model {
    Phong,     ///< normalized Phong reflection lobe (n+2)/(2 pi) cos^n(alpha_r)
    Blinn,     ///< microfacet, Blinn-Phong NDF (n+2)/(2 pi) cos^n(theta_h)
    Beckmann,  ///< microfacet, Beckmann NDF with rms slope m
    GGX,       ///< microfacet, Trowbridge-Reitz / GGX NDF with width alpha
};
enum class Fresnel {
    None,     ///< F = 1
    Schlick,  ///< F0 + (1 - F0)(1 - cos)^5
};
enum class Geometry {
    Implicit,  ///< G = cos(theta_i) cos(theta_o), so f = D F / 4
    Smith,     ///< height-correlated Smith G2 = 1 / (1 + Lambda(wi) + Lambda(wo))
};

const char* toString(Model);
const char* toString(Fresnel);
const char* toString(Geometry);
std::optional<Model> parseModel(const std::string&);
std::optional<Fresnel> parseFresnel(const std::string&);
std::optional<Geometry> parseGeometry(const std::string&);
std::vector<std::string> modelNames();

bool isMicrofacet(Model m);
bool usesExponent(Model m);  ///< phong, blinn take an exponent; beckmann, ggx a roughness

struct Params {
    Model model = Model::GGX;
    double exponent = 1000.0;  ///< phong / blinn n
    double roughness = 0.1;    ///< beckmann m, ggx alpha (the symbols of the formulas, not perceptual)
    Fresnel fresnel = Fresnel::None;
    dvec3 f0{0.04, 0.04, 0.04};
    Geometry geometry = Geometry::Implicit;
};

std::ostream& operator<<(std::ostream&, const Params&);
std::ostream& operator<<(std::ostream&, Model);
std::ostream& operator<<(std::ostream&, Fresnel);
std::ostream& operator<<(std::ostream&, Geometry);

/// Allowed ranges, checked at the CLI boundary (the error names the flag and the range).
constexpr double kMinExponent = 0.0, kMaxExponent = 1e8;
constexpr double kMinRoughness = 1e-4, kMaxRoughness = 10.0;

}  // namespace hilite::brdf
