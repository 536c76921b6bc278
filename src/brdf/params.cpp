#include "brdf/params.hpp"

#include <ostream>

namespace hilite::brdf {

const char* toString(Model m) {
    switch (m) {
        case Model::Phong: return "phong";
        case Model::Blinn: return "blinn";
        case Model::Beckmann: return "beckmann";
        case Model::GGX: return "ggx";
    }
    return "?";
}
const char* toString(Fresnel f) { return f == Fresnel::None ? "none" : "schlick"; }
const char* toString(Geometry g) { return g == Geometry::Implicit ? "implicit" : "smith"; }

std::optional<Model> parseModel(const std::string& s) {
    for (Model m : {Model::Phong, Model::Blinn, Model::Beckmann, Model::GGX})
        if (s == toString(m)) return m;
    return std::nullopt;
}
std::optional<Fresnel> parseFresnel(const std::string& s) {
    for (Fresnel f : {Fresnel::None, Fresnel::Schlick})
        if (s == toString(f)) return f;
    return std::nullopt;
}
std::optional<Geometry> parseGeometry(const std::string& s) {
    for (Geometry g : {Geometry::Implicit, Geometry::Smith})
        if (s == toString(g)) return g;
    return std::nullopt;
}
std::vector<std::string> modelNames() { return {"phong", "blinn", "beckmann", "ggx"}; }

bool isMicrofacet(Model m) { return m != Model::Phong; }
bool usesExponent(Model m) { return m == Model::Phong || m == Model::Blinn; }

std::ostream& operator<<(std::ostream& os, Model m) { return os << toString(m); }
std::ostream& operator<<(std::ostream& os, Fresnel f) { return os << toString(f); }
std::ostream& operator<<(std::ostream& os, Geometry g) { return os << toString(g); }

std::ostream& operator<<(std::ostream& os, const Params& p) {
    os << "model=" << toString(p.model);
    if (usesExponent(p.model)) os << " exponent=" << p.exponent;
    else os << " roughness=" << p.roughness;
    if (isMicrofacet(p.model)) {
        os << " fresnel=" << toString(p.fresnel);
        if (p.fresnel == Fresnel::Schlick) os << " f0=" << p.f0.x << "," << p.f0.y << "," << p.f0.z;
        os << " geometry=" << toString(p.geometry);
    }
    return os;
}

}  // namespace hilite::brdf
