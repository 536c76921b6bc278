#include "hilite/brdf/params.hpp"

#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/rgl.hpp"
#include "brdf/spectral.hpp"

#include <ostream>

namespace hilite::brdf {

namespace {

template <class E, size_t N>
std::optional<E> parseEnum(const std::string& s, const E (&all)[N]) {
    for (E e : all)
        if (s == toString(e)) return e;
    return std::nullopt;
}

template <class E, size_t N>
std::vector<std::string> names(const E (&all)[N]) {
    std::vector<std::string> out;
    for (E e : all) out.emplace_back(toString(e));
    return out;
}

constexpr Model kModels[] = {Model::Phong,     Model::PhongClassic, Model::Blinn, Model::Gaussian,
                             Model::Beckmann,  Model::GGX,          Model::None,  Model::Retro,
                             Model::Tabulated, Model::ABC,          Model::SGD,   Model::Lafortune};
constexpr Fresnel kFresnels[] = {Fresnel::None, Fresnel::Schlick, Fresnel::Dielectric, Fresnel::Conductor,
                                 Fresnel::Spectral};
constexpr Geometry kGeometries[] = {Geometry::None, Geometry::Implicit, Geometry::CookTorrance,
                                    Geometry::SmithSeparable, Geometry::Smith};
constexpr Diffuse kDiffuses[] = {Diffuse::None, Diffuse::Lambert, Diffuse::OrenNayar, Diffuse::Coupled};
constexpr Multiscatter kMultiscatters[] = {Multiscatter::None, Multiscatter::KullaConty};

void printRgb(std::ostream& os, const char* name, const dvec3& v) {
    os << " " << name << "=" << v.x;
    if (v.y != v.x || v.z != v.x) os << "," << v.y << "," << v.z;
}

}  // namespace

const char* toString(Model m) {
    switch (m) {
        case Model::Phong: return "phong";
        case Model::Blinn: return "blinn";
        case Model::Beckmann: return "beckmann";
        case Model::GGX: return "ggx";
        case Model::PhongClassic: return "phong-classic";
        case Model::Gaussian: return "gaussian";
        case Model::None: return "none";
        case Model::Retro: return "retro";
        case Model::Tabulated: return "tabulated";
        case Model::ABC: return "abc";
        case Model::SGD: return "sgd";
        case Model::Lafortune: return "lafortune";
    }
    return "?";
}
const char* toString(Fresnel f) {
    switch (f) {
        case Fresnel::None: return "none";
        case Fresnel::Schlick: return "schlick";
        case Fresnel::Dielectric: return "dielectric";
        case Fresnel::Conductor: return "conductor";
        case Fresnel::Spectral: return "spectral";
    }
    return "?";
}
const char* toString(Geometry g) {
    switch (g) {
        case Geometry::Implicit: return "implicit";
        case Geometry::Smith: return "smith";
        case Geometry::None: return "none";
        case Geometry::CookTorrance: return "cook-torrance";
        case Geometry::SmithSeparable: return "smith-separable";
    }
    return "?";
}
const char* toString(Diffuse d) {
    switch (d) {
        case Diffuse::None: return "none";
        case Diffuse::Lambert: return "lambert";
        case Diffuse::OrenNayar: return "oren-nayar";
        case Diffuse::Coupled: return "coupled";
    }
    return "?";
}
const char* toString(Multiscatter m) {
    switch (m) {
        case Multiscatter::None: return "none";
        case Multiscatter::KullaConty: return "kulla-conty";
    }
    return "?";
}

std::optional<Model> parseModel(const std::string& s) { return parseEnum(s, kModels); }
std::optional<Fresnel> parseFresnel(const std::string& s) { return parseEnum(s, kFresnels); }
std::optional<Geometry> parseGeometry(const std::string& s) { return parseEnum(s, kGeometries); }
std::optional<Diffuse> parseDiffuse(const std::string& s) { return parseEnum(s, kDiffuses); }
std::optional<Multiscatter> parseMultiscatter(const std::string& s) { return parseEnum(s, kMultiscatters); }
std::vector<std::string> modelNames() { return names(kModels); }
std::vector<std::string> fresnelNames() { return names(kFresnels); }
std::vector<std::string> geometryNames() { return names(kGeometries); }
std::vector<std::string> diffuseNames() { return names(kDiffuses); }
std::vector<std::string> multiscatterNames() { return names(kMultiscatters); }

bool isMicrofacet(Model m) {
    return m == Model::Blinn || m == Model::Beckmann || m == Model::GGX || m == Model::Gaussian ||
           m == Model::Tabulated;
}
bool usesExponent(Model m) {
    return m == Model::Phong || m == Model::PhongClassic || m == Model::Blinn || m == Model::Retro ||
           m == Model::Lafortune;
}
bool isLiterature(Model m) { return m == Model::ABC || m == Model::SGD || m == Model::Lafortune; }
bool allowsAnisotropy(Model m) { return m == Model::Beckmann || m == Model::GGX; }
bool isDelta(const Params& p) {
    if (!isMicrofacet(p.model) || usesExponent(p.model)) return false;  // an exponent is finite (<= 1e8)
    return p.roughness == 0.0 || (p.anisotropic() && allowsAnisotropy(p.model) && p.alphaY() == 0.0);
}

std::ostream& operator<<(std::ostream& os, Model m) { return os << toString(m); }
std::ostream& operator<<(std::ostream& os, Fresnel f) { return os << toString(f); }
std::ostream& operator<<(std::ostream& os, Geometry g) { return os << toString(g); }
std::ostream& operator<<(std::ostream& os, Diffuse d) { return os << toString(d); }
std::ostream& operator<<(std::ostream& os, Multiscatter m) { return os << toString(m); }

std::ostream& operator<<(std::ostream& os, const Params& p) {
    if (p.rgl) return os << "measured=" << p.rgl->path << " (RGL material, " << p.rgl->description << ")";
    if (p.measured)
        return os << "measured=" << p.measured->path << " (MERL table, multilinear; no_data_bins=" << p.measured->noData
                  << ")";
    os << "model=" << toString(p.model);
    if (usesExponent(p.model)) os << " exponent=" << p.exponent;
    else if (p.model == Model::Tabulated && p.ndfTable)
        os << " ndf_table=" << p.ndfTable->file << " rows=" << p.ndfTable->theta.size()
           << " normalization=" << p.ndfTable->normalization;
    else if (p.model == Model::ABC)
        printRgb(os << " B=" << p.abcB << " C=" << p.abcC, "A", p.abcA), printRgb(os, "eta", p.eta);
    else if (p.model == Model::SGD) {
        printRgb(os, "rho_s", p.sgd.rhoS), printRgb(os, "alpha", p.sgd.alpha), printRgb(os, "p", p.sgd.p);
        printRgb(os, "f0", p.sgd.f0), printRgb(os, "f1", p.sgd.f1), printRgb(os, "lambda", p.sgd.lambda);
        printRgb(os, "c", p.sgd.c), printRgb(os, "k", p.sgd.k), printRgb(os, "theta0", p.sgd.theta0);
    } else if (p.model != Model::None) os << " roughness=" << p.roughness;
    if (p.model == Model::Lafortune)
        printRgb(os << " Cxy=" << p.lafortuneCxy << " Cz=" << p.lafortuneCz, "rho_s", p.lafortuneRhoS);
    if (p.anisotropic() && allowsAnisotropy(p.model))
        os << " roughness-y=" << p.alphaY() << " tangent-angle=" << p.tangentAngleDeg;
    if (isMicrofacet(p.model)) {
        os << " fresnel=" << toString(p.fresnel);
        if (p.fresnel == Fresnel::Schlick) os << " f0=" << p.f0.x << "," << p.f0.y << "," << p.f0.z;
        if (p.fresnel == Fresnel::Dielectric || p.fresnel == Fresnel::Conductor) printRgb(os, "eta", p.eta);
        if (p.fresnel == Fresnel::Conductor) printRgb(os, "k", p.k);
        if (p.fresnel == Fresnel::Spectral && p.spectrum)
            os << " material=" << p.spectrum->name << " wavelengths=" << p.spectrum->size()
               << (p.spectralTable ? " table" : " exact");
        os << " geometry=" << toString(p.geometry);
        if (p.multiscatter != Multiscatter::None) os << " multiscatter=" << toString(p.multiscatter);
    }
    if (p.diffuse != Diffuse::None) {
        os << " diffuse=" << toString(p.diffuse);
        printRgb(os, "albedo", p.albedo);
        if (p.diffuse == Diffuse::OrenNayar) os << " sigma=" << p.sigmaDeg;
    }
    return os;
}

}  // namespace hilite::brdf
