#include "hilite/scene/registry.hpp"

#include "brdf/materials.hpp"
#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/rgl.hpp"
#include "brdf/spectral.hpp"
#include "core/text.hpp"
#include "gl/context.hpp"
#include "hilite/brdf/params.hpp"
#include "hilite/render/area_light.hpp"
#include "hilite/render/surface.hpp"
#include "hilite/scene/resolve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <unordered_map>

namespace hilite::scene {

namespace {

using brdf::Model;
using nlohmann::json;

/// A rule's rings as users name them: 0 for the cap's centre alone (render::kCentreRule).
int userRings(int n) { return n == render::kCentreRule ? 0 : n; }

// ---- What a parameter applies to ----

bool builtin(const Resolved& r) { return !r.scene.brdfFile && !r.scene.brdf.isMeasured(); }
bool measured(const Resolved& r) { return r.scene.brdf.isMeasured(); }
/// The measured file as named (MERL or RGL).
const std::string& measuredPath(const Resolved& r) {
    return r.scene.brdf.rgl ? r.scene.brdf.rgl->path : r.scene.brdf.measured->path;
}
bool usesExponent(const Resolved& r) { return builtin(r) && brdf::usesExponent(r.scene.brdf.model); }
bool usesRoughness(const Resolved& r) {
    const Model m = r.scene.brdf.model;
    return builtin(r) && m != Model::None && m != Model::Tabulated && !brdf::usesExponent(m) && !brdf::isLiterature(m);
}
bool fitTable(const Resolved& r) { return r.values.given("fit_table"); }
bool abc(const Resolved& r) { return builtin(r) && r.scene.brdf.model == Model::ABC; }
bool sgd(const Resolved& r) { return builtin(r) && r.scene.brdf.model == Model::SGD; }
bool lafortune(const Resolved& r) { return builtin(r) && r.scene.brdf.model == Model::Lafortune; }
bool anisotropic(const Resolved& r) {
    return builtin(r) && r.scene.brdf.anisotropic() && brdf::allowsAnisotropy(r.scene.brdf.model);
}
bool tangentFrame(const Resolved& r) { return anisotropic(r) || r.scene.brdfFile; }
bool microfacet(const Resolved& r) { return builtin(r) && brdf::isMicrofacet(r.scene.brdf.model); }
bool schlick(const Resolved& r) { return microfacet(r) && r.scene.brdf.fresnel == brdf::Fresnel::Schlick; }
bool exactIndex(const Resolved& r) {
    return abc(r) || (microfacet(r) && (r.scene.brdf.fresnel == brdf::Fresnel::Dielectric ||
                                        r.scene.brdf.fresnel == brdf::Fresnel::Conductor));
}
bool spectral(const Resolved& r) { return microfacet(r) && r.scene.brdf.fresnel == brdf::Fresnel::Spectral; }
bool conductor(const Resolved& r) { return microfacet(r) && r.scene.brdf.fresnel == brdf::Fresnel::Conductor; }
bool hasMaterial(const Resolved& r) { return builtin(r) && r.values.given("material"); }
bool diffuse(const Resolved& r) { return builtin(r) && r.scene.brdf.diffuse != brdf::Diffuse::None; }
bool orenNayar(const Resolved& r) { return builtin(r) && r.scene.brdf.diffuse == brdf::Diffuse::OrenNayar; }
bool tabulated(const Resolved& r) { return builtin(r) && r.scene.brdf.model == Model::Tabulated; }
bool brdfFile(const Resolved& r) { return bool(r.scene.brdfFile); }
bool sphere(const Resolved& r) { return r.scene.light.type == render::LightType::Sphere; }
bool disk(const Resolved& r) { return r.scene.light.type == render::LightType::Disk; }
bool distant(const Resolved& r) { return r.scene.light.distant(); }
bool atDistance(const Resolved& r) { return !r.scene.light.distant(); }  ///< point, sphere
bool area(const Resolved& r) { return r.scene.light.area(); }
bool bumps(const Resolved& r) { return r.scene.surface.bumps; }
bool fixedFraming(const Resolved& r) { return r.fovDeg > 0; }
bool tolerance(const Resolved& r) { return r.tolerance > 0; }

json rgb(const dvec3& v) { return json::array({v.x, v.y, v.z}); }

// ---- Binding a parameter to its field ----
// `get` is one generic accessor, [](auto& r) -> auto& { return r.scene.brdf.exponent; }, for the write and the
// read: a misspelt field is a compile error, and the default is read from a default-constructed Resolved.

template <class T>
T parseAs(const std::string& t) {  // the text check() has passed
    if constexpr (std::is_same_v<T, dvec3>) {
        const auto parts = split(t, ',');
        dvec3 v;
        for (int c = 0; c < 3; ++c) v[c] = *parseNumber(parts[parts.size() == 1 ? 0 : size_t(c)]);
        return v;
    } else if constexpr (std::is_same_v<T, bool>) {
        return t == "true";
    } else if constexpr (std::is_same_v<T, std::string>) {
        return t;
    } else {
        return T(*parseNumber(t));
    }
}

template <class T>
std::string printAs(const T& v, bool exact) {
    if constexpr (std::is_same_v<T, dvec3>) {
        if (v.y == v.x && v.z == v.x) return printAs(v.x, exact);
        return printAs(v.x, exact) + "," + printAs(v.y, exact) + "," + printAs(v.z, exact);
    } else if constexpr (std::is_same_v<T, std::optional<double>>) {
        return v ? printAs(*v, exact) : "";
    } else if constexpr (std::is_same_v<T, bool>) {
        return v ? "true" : "false";
    } else if constexpr (std::is_same_v<T, std::string>) {
        return v;
    } else if constexpr (std::is_same_v<T, double>) {
        return exact ? exactText(v) : fmt(v);
    } else if constexpr (std::is_enum_v<T>) {
        return toString(v);
    } else {
        return std::to_string(v);
    }
}

template <class Get>
using FieldOf = std::decay_t<decltype(std::declval<Get>()(std::declval<Resolved&>()))>;

/// The field's value printed (and, with `withDefault`, the entry's default); resolve() writes it itself.
template <class Get>
void bindRead(Param& e, Get get, bool withDefault = true) {
    e.read = [get](const Resolved& r, bool exact) { return printAs(get(r), exact); };
    if (withDefault) e.def = e.read(Resolved{}, false);
}

/// The field written from the checked text and printed back; its default is the struct's.
template <class Get>
void bind(Param& e, Get get) {
    e.write = [get](Resolved& r, const std::string& t) { get(r) = parseAs<FieldOf<Get>>(t); };
    bindRead(e, get);
}

/// A field whose value-initialized state (0, none) means `word`, the entry's automatic word.
template <class Get>
void bindAutomatic(Param& e, Get get, const char* word) {
    using T = FieldOf<Get>;
    e.automatic = word;
    e.write = [get, word](Resolved& r, const std::string& t) {
        if (t == word) get(r) = T{};
        else if constexpr (std::is_same_v<T, std::optional<double>>) get(r) = *parseNumber(t);
        else get(r) = parseAs<T>(t);
    };
    e.read = [get, word](const Resolved& r, bool exact) {
        return get(r) == T{} ? std::string(word) : printAs(get(r), exact);
    };
    e.def = e.read(Resolved{}, false);
}

/// A field that is `unset` when the parameter is not given (default "").
template <class Get, class T>
void bindUnset(Param& e, Get get, T unset) {
    e.write = [get, unset](Resolved& r, const std::string& t) { get(r) = t.empty() ? unset : parseAs<T>(t); };
    e.read = [get, unset](const Resolved& r, bool exact) { return get(r) == unset ? "" : printAs(get(r), exact); };
    e.def = e.read(Resolved{}, false);
}

/// A choice: the names are the table's, the field the value of the name (check() refused any other name).
template <class Get, class E, size_t N>
void bindChoice(Param& e, Get get, const Named<E> (&table)[N]) {
    e.choices = namesIn(table);
    e.write = [get, &table](Resolved& r, const std::string& t) { get(r) = parseIn(table, t).value(); };
    e.read = [get, &table](const Resolved& r, bool) { return std::string(nameIn(table, get(r))); };
    e.def = e.read(Resolved{}, false);
}

/// A brdf enum: its names, parse and toString come from one array each (brdf/params.cpp).
template <class Get, class Parse>
void bindChoice(Param& e, Get get, std::vector<std::string> names, Parse parse) {
    e.choices = std::move(names);
    e.write = [get, parse](Resolved& r, const std::string& t) { get(r) = parse(t).value(); };
    e.read = [get](const Resolved& r, bool) { return std::string(brdf::toString(get(r))); };
    e.def = e.read(Resolved{}, false);
}

// The choices whose field is a bool: their spellings, once.
constexpr Named<bool> kSpectralFresnel[] = {{true, "table"}, {false, "exact"}};
constexpr Named<bool> kBumps[] = {{false, "none"}, {true, "explicit"}};
constexpr Named<bool> kBoundaries[] = {{true, "subpixel"}, {false, "pixel"}};
constexpr Named<bool> kLightRules[] = {{false, "rings"}, {true, "ltc"}};
constexpr Named<bool> kRenderers[] = {{false, "gl"}, {true, "cpu"}};
constexpr Named<bool> kCrops[] = {{true, "on"}, {false, "off"}};
constexpr Named<analysis::Lobe> kLobes[] = {{analysis::Lobe::All, "all"}, {analysis::Lobe::Mirror, "mirror"}};

std::string sizeText(int w, int h) { return w == h ? std::to_string(w) : std::to_string(w) + "x" + std::to_string(h); }

/// A loaded table by its object: the caches that key on it hold the scene (and so the table) while the key
/// lives, so no other table can take its address meanwhile. "" for none.
std::string identity(const void* p) {
    if (!p) return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "@%p", p);
    return buf;
}

/// An NDF table by its contents (a small table; the energy cache outlives the scenes it was made for).
std::string tableText(const brdf::NdfTable* t) {
    if (!t) return "";
    std::string s = t->file;
    for (size_t i = 0; i < t->theta.size(); ++i) s += " " + exactText(t->theta[i]) + ":" + exactText(t->D[i]);
    return s;
}

const char* kModelHelp =
    "specular model: phong | phong-classic (reflection lobes) | retro (retroreflective lobe about the light) | "
    "blinn | gaussian | beckmann | ggx | tabulated (microfacet; tabulated: --ndf-table) | abc (Low et al. 2012) | "
    "sgd (Bagher et al. 2012) | lafortune (Ngan et al. 2005's lobe): the literature's models, each with its own F "
    "and G (--abc-*, --sgd-*, --lafortune-*; the published fits as presets: --fit-table, --fit-material) | none "
    "(diffuse only)";

/// A parameter of one of the literature's models (abc, sgd, lafortune): a number or an RGB value of the model's
/// field, a column of its own.
template <class Get>
Param literatureParam(const char* name, Kind kind, double lo, double hi, bool openLo, const char* unit,
                      const std::string& help, const char* appliesTo, bool (*applies)(const Resolved&), Get get) {
    Param e{name, Table::Material, kind, "", lo, hi, openLo, false, {}, unit, help, appliesTo, applies, name, nullptr};
    e.value = [get](const Resolved& r) -> json {
        if constexpr (std::is_same_v<FieldOf<Get>, dvec3>) return rgb(get(const_cast<Resolved&>(r)));
        else return get(const_cast<Resolved&>(r));
    };
    bind(e, get);
    return e;
}

std::vector<Param> build() {
    using K = Kind;
    using T = Table;
    std::vector<Param> p;
    auto add = [&](Param e) { p.push_back(std::move(e)); };
    const std::string materials = join(brdf::materialNames());

    // ---- [material] ----
    add({"model",
         T::Material,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         kModelHelp,
         "every scene",
         nullptr,
         "model",
         [](const Resolved& r) -> json {
             if (r.scene.brdfFile) return r.scene.brdfFile->path.substr(r.scene.brdfFile->path.rfind('/') + 1);
             if (r.scene.brdf.isMeasured()) return "measured:" + measuredPath(r).substr(measuredPath(r).rfind('/') + 1);
             return brdf::toString(r.scene.brdf.model);
         }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.model; }, brdf::modelNames(), brdf::parseModel);
    add({"exponent",
         T::Material,
         K::Number,
         "",
         brdf::kMinExponent,
         brdf::kMaxExponent,
         false,
         false,
         {},
         "",
         "phong/phong-classic/blinn/retro/lafortune exponent n",
         "phong, phong-classic, blinn, retro, lafortune",
         usesExponent,
         "exponent",
         [](const Resolved& r) -> json { return r.scene.brdf.exponent; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.exponent; });
    add({"roughness",
         T::Material,
         K::Number,
         "",
         brdf::kMinRoughness,
         brdf::kMaxRoughness,
         false,
         false,
         {},
         "",
         "beckmann m / ggx alpha / gaussian m in radians (the formulas' symbols; alpha_x if anisotropic): 0 is a "
         "perfect mirror, (0, 1e-7) is raised to 1e-7 with a warning",
         "beckmann, ggx, gaussian",
         usesRoughness,
         "roughness",
         [](const Resolved& r) -> json { return r.scene.brdf.roughness; }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.roughness; });  // set by resolve.cpp roughness()
    add({"roughness_y",
         T::Material,
         K::Number,
         "",
         brdf::kMinRoughness,
         brdf::kMaxRoughness,
         false,
         false,
         {},
         "",
         "anisotropic beckmann/ggx: alpha_y, as --roughness (absent: isotropic)",
         "anisotropic beckmann, ggx",
         anisotropic,
         "roughness_y",
         [](const Resolved& r) -> json { return r.scene.brdf.alphaY(); }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.roughnessY; });  // resolve.cpp roughness()
    add({"tangent_angle",
         T::Material,
         K::Number,
         "",
         -360,
         360,
         false,
         false,
         {},
         "deg",
         "anisotropic (or a .brdf's X, Y): azimuth of the alpha_x axis from +x",
         "anisotropic beckmann, ggx; .brdf",
         tangentFrame,
         "tangent_angle",
         [](const Resolved& r) -> json { return r.scene.brdf.tangentAngleDeg; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.tangentAngleDeg; });
    add({"fresnel", T::Material, K::Choice, "", 0, 0, false, false, brdf::fresnelNames(), "",
         "none (F = 1) | schlick | dielectric | conductor (exact) | spectral (measured metal); default: the "
         "material's, schlick when --f0 is given, else none",
         "microfacet models", microfacet, "fresnel",
         [](const Resolved& r) -> json { return brdf::toString(r.scene.brdf.fresnel); }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.fresnel; }, false);  // resolve.cpp resolveFresnel()
    add({"material", T::Material, K::Choice, "", 0, 0, false, false, brdf::materialNames(), "",
         "Fresnel preset: " + materials + " (copper, gold: spectral)", "microfacet models", hasMaterial, "material",
         [](const Resolved& r) -> json { return r.values.text("material"); }});
    add({"spectral_fresnel",
         T::Material,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "table (F over cos theta_d, 512 entries computed in double per metal, linear between them: within 1e-5 of "
         "exact, at the cost of one lookup) | exact (the sum over the wavelengths at every pixel: 81 on the GPU)",
         "fresnel spectral",
         spectral,
         "spectral_fresnel",
         [](const Resolved& r) -> json { return r.scene.brdf.spectralTable ? "table" : "exact"; }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.spectralTable; }, kSpectralFresnel);
    add({"eta",
         T::Material,
         K::Rgb,
         "",
         brdf::kMinEta,
         brdf::kMaxEta,
         false,
         false,
         {},
         "",
         "dielectric/conductor index eta = n_t/n_i (default: the material's, else 1.5); abc's F",
         "fresnel dielectric, conductor; abc",
         exactIndex,
         "eta",
         [](const Resolved& r) -> json { return rgb(r.scene.brdf.eta); }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.eta; }, false);  // resolveFresnel()
    add({"k",
         T::Material,
         K::Rgb,
         "",
         brdf::kMinK,
         brdf::kMaxK,
         false,
         false,
         {},
         "",
         "conductor extinction k (default: the material's, else 0)",
         "fresnel conductor",
         conductor,
         "k",
         [](const Resolved& r) -> json { return rgb(r.scene.brdf.k); }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.k; }, false);  // resolveFresnel()
    add({"f0",
         T::Material,
         K::Rgb,
         "",
         0,
         1,
         false,
         false,
         {},
         "",
         "Schlick F0 (default: F(0) of --eta/--k or of the material, else 0.04)",
         "fresnel schlick",
         schlick,
         "f0",
         [](const Resolved& r) -> json { return rgb(r.scene.brdf.f0); }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.f0; }, false);  // resolveFresnel()
    add({"geometry",
         T::Material,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "none (G = 1) | implicit (G = cos_i cos_o) | cook-torrance (V-cavity) | smith-separable | smith "
         "(height-correlated)",
         "microfacet models",
         microfacet,
         "geometry",
         [](const Resolved& r) -> json { return brdf::toString(r.scene.brdf.geometry); }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.geometry; }, brdf::geometryNames(), brdf::parseGeometry);
    add({"multiscatter",
         T::Material,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "none (single scattering) | kulla-conty (Kulla & Conty 2017: the energy Smith masking takes from single "
         "scattering, 1 - E(mu), returned as (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)) times F_avg^2 E_avg / (1 - "
         "F_avg (1 - E_avg)); E integrated by hilite at 64 angles; isotropic microfacet models, --geometry smith or "
         "smith-separable)",
         "microfacet models",
         microfacet,
         "multiscatter",
         [](const Resolved& r) -> json { return brdf::toString(r.scene.brdf.multiscatter); }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.multiscatter; }, brdf::multiscatterNames(),
        brdf::parseMultiscatter);
    add({"diffuse",
         T::Material,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "none | lambert | oren-nayar, added to the specular lobe | coupled (rho (1 - E_s(mu_i)) (1 - E_s(mu_o)) / (pi "
         "(1 - E_s_avg)), E_s the specular albedo: the body takes what the surface leaves, specular + diffuse "
         "albedo <= 1)",
         "built-in models",
         builtin,
         "diffuse",
         [](const Resolved& r) -> json { return brdf::toString(r.scene.brdf.diffuse); }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.diffuse; }, brdf::diffuseNames(), brdf::parseDiffuse);
    add({"albedo",
         T::Material,
         K::Rgb,
         "",
         0,
         1,
         false,
         false,
         {},
         "",
         "diffuse albedo rho",
         "diffuse lambert, oren-nayar, coupled",
         diffuse,
         "albedo",
         [](const Resolved& r) -> json { return rgb(r.scene.brdf.albedo); }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.albedo; });
    add({"sigma",
         T::Material,
         K::Number,
         "",
         brdf::kMinSigmaDeg,
         brdf::kMaxSigmaDeg,
         false,
         false,
         {},
         "deg",
         "oren-nayar facet slope deviation",
         "diffuse oren-nayar",
         orenNayar,
         "sigma",
         [](const Resolved& r) -> json { return r.scene.brdf.sigmaDeg; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.brdf.sigmaDeg; });
    // ---- The literature's models: the published formulas' symbols (docs/literature.md) ----
    const char* perChannel = " (V or R,G,B: the published fits are per channel)";
    add(literatureParam(
        "abc_a", K::Rgb, 0, 1e8, false, "", std::string("abc A, the lobe's height") + perChannel, "abc", abc,
        [](auto& r) -> auto& { return r.scene.brdf.abcA; }));
    add(literatureParam(
        "abc_b", K::Number, 0, 1e9, false, "",
        "abc B: (1 + B (1 - cos theta_h))^-C; larger is narrower (width ~ 1 / sqrt(B C))", "abc", abc,
        [](auto& r) -> auto& { return r.scene.brdf.abcB; }));
    add(literatureParam(
        "abc_c", K::Number, 0, 100, false, "", "abc C, the tail's fall-off (its F uses --eta)", "abc", abc,
        [](auto& r) -> auto& { return r.scene.brdf.abcC; }));
    add(literatureParam(
        "sgd_rho_s", K::Rgb, 0, 1e8, false, "",
        std::string("sgd rho_s, the height of the normalized D (a published fit's rho_s kap / K)") + perChannel, "sgd",
        sgd, [](auto& r) -> auto& { return r.scene.brdf.sgd.rhoS; }));
    add(literatureParam(
        "sgd_alpha", K::Rgb, 0, 10, true, "",
        std::string("sgd alpha in a = alpha + tan^2 theta_h / alpha; smaller is narrower") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.alpha; }));
    add(literatureParam(
        "sgd_p", K::Rgb, 0, 10, false, "", std::string("sgd p, the power of a^-p") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.p; }));
    add(literatureParam(
        "sgd_f0", K::Rgb, -100, 100, false, "",
        std::string("sgd Fresnel f0 in f0 - f1 cos theta_d + (1 - cos theta_d)^5 (1 - f0)") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.f0; }));
    add(literatureParam(
        "sgd_f1", K::Rgb, -100, 100, false, "", std::string("sgd Fresnel f1") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.f1; }));
    add(literatureParam(
        "sgd_lambda", K::Rgb, 0, 1e9, false, "",
        std::string("sgd masking lambda in G1 = clamp(1 + lambda (1 - exp(c max(0, theta - theta0)^k)), "
                    "0, 1); 0: no masking") +
            perChannel,
        "sgd", sgd, [](auto& r) -> auto& { return r.scene.brdf.sgd.lambda; }));
    add(literatureParam(
        "sgd_c", K::Rgb, 0, 1e38, false, "", std::string("sgd masking c") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.c; }));
    add(literatureParam(
        "sgd_k", K::Rgb, 0, 1e4, false, "", std::string("sgd masking k") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.k; }));
    add(literatureParam(
        "sgd_theta0", K::Rgb, -kPi / 2, kPi / 2, false, "rad",
        std::string("sgd masking theta0, in radians as published") + perChannel, "sgd", sgd,
        [](auto& r) -> auto& { return r.scene.brdf.sgd.theta0; }));
    add(literatureParam(
        "lafortune_rho_s", K::Rgb, 0, 1e8, false, "",
        std::string("lafortune rho_s: the lobe's albedo at normal incidence when |C_z| >= |C_xy|") + perChannel,
        "lafortune", lafortune, [](auto& r) -> auto& { return r.scene.brdf.lafortuneRhoS; }));
    add(literatureParam(
        "lafortune_cxy", K::Number, -100, 100, false, "",
        "lafortune C_xy (C_xy = -C_z: the lobe about the mirror direction; C_xy > 0: back toward the "
        "light; the exponent is --exponent)",
        "lafortune", lafortune, [](auto& r) -> auto& { return r.scene.brdf.lafortuneCxy; }));
    add(literatureParam(
        "lafortune_cz", K::Number, -100, 100, false, "",
        "lafortune C_z (only C_z / C_xy matters: the lobe is divided by max(|C_xy|, |C_z|)^n)", "lafortune", lafortune,
        [](auto& r) -> auto& { return r.scene.brdf.lafortuneCz; }));
    add({"fit_table",
         T::Material,
         K::Path,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "a table of the literature's fits to the MERL materials (tab-separated: Low et al. 2012's abc, Bagher et al. "
         "2012's sgd or Ngan et al. 2005's lafortune, told by its header; docs/literature.md): with --fit-material "
         "NAME, that material's fit is the BRDF (model, parameters, lambert diffuse; not with any other material "
         "flag)",
         "every scene",
         fitTable,
         "fit_table",
         [](const Resolved& r) -> json { return r.values.text("fit_table"); }});
    add({"fit_material",
         T::Material,
         K::Text,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "the material of --fit-table (chrome-steel, gray-plastic, ...)",
         "--fit-table",
         fitTable,
         "fit_material",
         [](const Resolved& r) -> json { return r.values.text("fit_material"); }});
    add({"ndf_table",
         T::Material,
         K::Path,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "tabulated: CSV of 'theta_h_deg, D' rows (theta_h from 0, increasing, <= 90; D >= 0), linear between rows, "
         "normalized so that int D (n.h) dw = 1 (the factor is reported as ndf_table_normalization); or an RGL .bsdf "
         "file, told apart by content: its measured NDF (averaged over phi_m) and, for Smith masking, its measured "
         "projected area (sigma)",
         "model tabulated",
         tabulated,
         "ndf_table",
         [](const Resolved& r) -> json { return r.scene.brdf.ndfTable->file; }});
    p.back().read = [](const Resolved& r, bool) { return tableText(r.scene.brdf.ndfTable.get()); };
    add({"measured",
         T::Material,
         K::Path,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "a measured material, the whole BRDF (lobe, F, G, diffuse), told apart by content: a MERL .binary table "
         "(90 x 90 x 180, Matusik 2003; cubic in theta_h and linear in theta_d, phi_d between bin centres, multilinear "
         "where a bin lacks data) or an RGL .bsdf file (Dupuy & Jakob 2018, rgl.epfl.ch/materials; its tables "
         "indexed by the light direction); replaces --model and its terms (the row's model says measured:FILE; not "
         "with any other "
         "material flag, nor --bumps)",
         "every scene",
         measured,
         "measured",
         [](const Resolved& r) -> json { return measuredPath(r); }});
    p.back().read = [](const Resolved& r, bool) {
        return r.scene.brdf.rgl ? identity(r.scene.brdf.rgl.get()) : identity(r.scene.brdf.measured.get());
    };
    add({"brdf",
         T::Material,
         K::Path,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "a BRDF Explorer .brdf file (analytic): its GLSL BRDF() replaces --model and its terms (only "
         "--tangent-angle still applies); no CPU twin, so measure frames blind and estimates its error from "
         "resolution convergence",
         "every scene",
         brdfFile,
         "brdf",
         [](const Resolved& r) -> json { return r.scene.brdfFile->path; }});
    p.back().read = [](const Resolved& r, bool) { return identity(r.scene.brdfFile.get()); };
    add({"param",
         T::Material,
         K::List,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "a .brdf parameter, NAME=VALUE: float within its declared range, bool 0|1, color V or R,G,B; repeat the "
         "flag or join several with commas (n=100,tint=1,0.5,0.2)",
         "--brdf",
         brdfFile,
         "param",
         [](const Resolved& r) -> json {
             std::vector<std::string> all;
             for (const auto& a : r.values.list("param")) all.push_back(a.text);
             return join(all, ",");
         }});

    // ---- [light] ----
    add({"incidence",
         T::Light,
         K::Angles,
         "",
         0,
         90,
         false,
         false,
         {},
         "deg",
         "angle of incidence theta_i: one angle (60), a list (0,30,60) or a range START:STOP:STEP (0:85:5); render "
         "takes one",
         "every scene",
         nullptr,
         "incidence_deg",
         [](const Resolved& r) -> json { return r.scene.light.incidenceDeg; }});
    bindRead(
        p.back(), [](auto& r) -> auto& { return r.scene.light.incidenceDeg; });  // resolve.cpp: the angles
    add({"azimuth",
         T::Light,
         K::Number,
         "",
         -360,
         360,
         false,
         false,
         {},
         "deg",
         "light azimuth phi_i",
         "every scene",
         nullptr,
         "azimuth_deg",
         [](const Resolved& r) -> json { return r.scene.light.azimuthDeg; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.light.azimuthDeg; });
    add({"light",
         T::Light,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "directional (distant, irradiance E) | point (intensity I, I cos / d^2) | sphere (radius R, intensity I: "
         "radiance I / (pi R^2)) | disk (distant, angular radius delta, irradiance E: radiance E / (pi sin^2 delta))",
         "every scene",
         nullptr,
         "light",
         [](const Resolved& r) -> json { return render::toString(r.scene.light.type); }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.light.type; }, render::kLightTypes);
    add({"irradiance",
         T::Light,
         K::Number,
         "",
         0,
         1e6,
         false,
         false,
         {},
         "",
         "light irradiance E (normal to the light)",
         "light directional, disk",
         distant,
         "irradiance",
         [](const Resolved& r) -> json { return r.scene.light.irradiance; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.light.irradiance; });
    add({"intensity",
         T::Light,
         K::Number,
         "",
         0,
         1e12,
         false,
         false,
         {},
         "",
         "point or sphere light intensity I (the sphere's power is the point's, 4 pi I)",
         "light point, sphere",
         atDistance,
         "intensity",
         [](const Resolved& r) -> json { return r.scene.light.intensity; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.light.intensity; });
    add({"light_distance",
         T::Light,
         K::Number,
         "",
         1e-3,
         1e6,
         false,
         false,
         {},
         "",
         "point light (sphere: its centre) distance from the origin",
         "light point, sphere",
         atDistance,
         "light_distance",
         [](const Resolved& r) -> json { return r.scene.light.distance; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.light.distance; });
    // From 1e-100: below ~1e-155 the double twin's cap (1 - cos alpha ~ R^2 / 2d^2) underflows and the sphere
    // lit nothing there (no_highlight, or float_overflow of L); GL holds L R^2, any R (shade.frag).
    add({"light_radius",
         T::Light,
         K::Number,
         "",
         1e-100,
         1e6,
         false,
         false,
         {},
         "",
         "sphere radius R, below its centre's height light_distance x cos(incidence) (a sphere that reaches the "
         "plane is refused; a tiny one measures as the point light)",
         "light sphere",
         sphere,
         "light_radius",
         [](const Resolved& r) -> json { return r.scene.light.radius; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.light.radius; });
    // From 1e-100 deg: below ~1e-155 deg the double twin's cap underflows (the reference said no_highlight).
    add({"light_angle",
         T::Light,
         K::Number,
         "",
         1e-100,
         90,
         false,
         true,
         {},
         "deg",
         "disk angular radius delta (the sun: 0.266); a disk that reaches below the horizon is integrated over "
         "its visible part (light_visible says how much)",
         "light disk",
         disk,
         "light_angle",
         [](const Resolved& r) -> json { return r.scene.light.angleDeg; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.light.angleDeg; });
    add({"light_rings",
         T::Light,
         K::Integer,
         "",
         0,
         render::kMaxRings,
         false,
         false,
         {},
         "",
         "sphere, disk: the GL rule over the light, n rings (Gauss-Legendre in 1 - cos) x 4n azimuths = 4n^2 "
         "points per pixel; 0: the cap's centre alone (1 point: for a light much smaller than the lobe, e.g. the "
         "sun on a lobe 0.1 wide); auto: the cheapest of these whose radiance error against the exact integral is "
         "within 1e-3 of the peak (tolerance / 4 with --tolerance)",
         "light sphere, disk",
         area,
         "light_rings",
         [](const Resolved& r) -> json { return userRings(render::lightRings(r.scene)); }});
    bindAutomatic(
        p.back(), [](auto& r) -> auto& { return r.scene.light.rings; }, "auto");
    {  // the user's 0 (the centre's rule) is render::kCentreRule: the field's 0 means auto
        Param& e = p.back();
        e.write = [](Resolved& r, const std::string& t) {
            const int n = t == "auto" ? 0 : parseAs<int>(t);
            r.scene.light.rings = t == "auto" ? 0 : n == 0 ? render::kCentreRule : n;
        };
        e.read = [](const Resolved& r, bool) {
            const int n = r.scene.light.rings;
            return n == 0 ? std::string("auto") : std::to_string(userRings(n));
        };
    }
    add({"light_rule",
         T::Light,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "sphere, disk: how GL integrates the light: rings (the rule, light_rings) | ltc (linearly transformed "
         "cosines: a cosine lobe fitted per view elevation to the isotropic BRDF, the light a 16-gon; the fit "
         "costs about a second per BRDF, once per process; the reference stays exact)",
         "light sphere, disk",
         area,
         "light_rule",
         [](const Resolved& r) -> json { return r.scene.light.ltc ? "ltc" : "rings"; }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.light.ltc; }, kLightRules);

    // ---- [camera] ----
    add({"size",
         T::Camera,
         K::Size,
         "",
         1,
         16384,
         false,
         false,
         {},
         "px",
         "image size: PX or WxH",
         "every scene",
         nullptr,
         "",
         nullptr});  // the row's size is the one rendered (measurement field `size`)
    // Written by resolve.cpp (Reader::size: the memory check).
    p.back().read = [](const Resolved& r, bool) { return sizeText(r.setup.width, r.setup.height); };
    p.back().def = p.back().read(Resolved{}, false);
    add({"fov",
         T::Camera,
         K::Number,
         "",
         0,
         179,
         true,
         false,
         {},
         "deg",
         "field of view across the width; auto: the view's default (render: 30 measure, 40 photo) or automatic "
         "framing (measure); a number: that field of view (measure: fixed framing, at most 160)",
         "fixed framing",
         fixedFraming,
         "fov",
         [](const Resolved& r) -> json { return r.fovDeg; }});
    bindAutomatic(
        p.back(), [](auto& r) -> auto& { return r.fovDeg; }, "auto");
    add({"view",
         T::Camera,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "render: measure (camera on the mirror direction) | photo (looking across the plane); measure always "
         "uses the measurement view",
         "render",
         nullptr,
         "",
         nullptr});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.view; }, kViews);
    add({"elevation",
         T::Camera,
         K::Number,
         "",
         0,
         90,
         false,
         false,
         {},
         "deg",
         "photo view: camera elevation; auto: 90 - incidence, at least 0.5 (0: the plane seen edge-on)",
         "render --view photo",
         nullptr,
         "",
         nullptr});
    bindAutomatic(
        p.back(), [](auto& r) -> auto& { return r.elevationDeg; }, "auto");
    add({"distance",
         T::Camera,
         K::Number,
         "",
         1e-3,
         1e6,
         false,
         false,
         {},
         "",
         "eye distance from the origin (photo view; measurement view under a point or sphere light)",
         "light point, sphere; photo view",
         atDistance,
         "distance",
         [](const Resolved& r) -> json { return r.scene.eyeDistance; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.eyeDistance; });
    add({"gl_backend", T::Camera, K::Choice, "", 0, 0, false, false, gl::backendNames(), "",
         "auto (a GPU through EGL device if there is one, else osmesa, else egl) | osmesa | egl (surfaceless) | "
         "egl-device (EGL_EXT_platform_device: --gpu N, default the first GPU, else Mesa's software device) "
         "(default: $HILITE_GL_BACKEND, else auto)",
         "GL renders", nullptr, "", nullptr});
    bind(
        p.back(), [](auto& r) -> auto& { return r.backend; });
    add({"gpu",
         T::Camera,
         K::Integer,
         "",
         0,
         1023,
         false,
         false,
         {},
         "",  // the devices' range: resolve.cpp gpuIndex
         "egl-device (or auto): the index of the EGL device to render on, below the number of devices EGL lists "
         "(default: the first that is not Mesa's software device, else 0)",
         "--gl-backend egl-device, auto",
         nullptr,
         "",
         nullptr});
    p.back().read = [](const Resolved& r, bool) {
        return r.gpu < 0 ? std::string() : std::to_string(r.gpu);
    };  // gpuIndex()
    add({"shader_timeout",
         T::Camera,
         K::Number,
         "",
         1e-3,
         3600,
         false,
         false,
         {},
         "s",
         "seconds a .brdf shader may take on a probe render in a child process, and on each compile and draw, "
         "before it is stopped (exit 2)",
         "--brdf",
         nullptr,
         "",
         nullptr});
    bind(
        p.back(), [](auto& r) -> auto& { return r.shaderTimeoutS; });

    // ---- [surface] ----
    add({"bumps",
         T::Surface,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "none (flat: the analytic BRDF) | explicit (the material's beckmann/ggx NDF as a seeded bump field of "
         "mirror facets, lit by a soft sun)",
         "every scene",
         nullptr,
         "bumps",
         [](const Resolved& r) -> json { return r.scene.surface.bumps ? "explicit" : "none"; }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.bumps; }, kBumps);
    add({"bump_period_px",
         T::Surface,
         K::Number,
         "",
         render::kMinBumpPeriodPx,
         render::kMaxBumpPeriodPx,
         false,
         false,
         {},
         "px",
         "bump period in pixels of the view (at the image centre, across it)",
         "bumps explicit",
         bumps,
         "bump_period_px",
         [](const Resolved& r) -> json { return r.scene.surface.bumpPeriodPx; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.bumpPeriodPx; });
    add({"bump_seed",
         T::Surface,
         K::Integer,
         "",
         0,
         9007199254740992.0,
         false,
         false,
         {},
         "",
         "seed of the bump field",
         "bumps explicit",
         bumps,
         "bump_seed",
         [](const Resolved& r) -> json { return r.scene.surface.seed; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.seed; });
    add({"bump_samples",
         T::Surface,
         K::Integer,
         "",
         0,
         render::kMaxBumpSamples,
         false,
         false,
         {},
         "",
         "sub-pixel patches per axis; 0 = automatic (4 per bump period across the footprint)",
         "bumps explicit",
         bumps,
         "bump_samples",
         [](const Resolved& r) -> json { return r.scene.surface.samples; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.samples; });
    add({"sun",
         T::Surface,
         K::Number,
         "",
         render::kMinSunDeg,
         render::kMaxSunDeg,
         false,
         false,
         {},
         "deg",
         "the light's angular standard deviation per axis (Gaussian sun)",
         "bumps explicit",
         bumps,
         "sun",
         [](const Resolved& r) -> json { return r.scene.surface.sunDeg; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.sunDeg; });
    add({"bump_filter",
         T::Surface,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "how a pixel integrates its bumps: supersample (Gaussian mirror patches) | moments (the footprint's "
         "realised slope moments, LEAN mapping: a prefilter; beckmann bumps) | auto (supersample while the centre "
         "pixel needs <= 64 patches per axis, moments beyond; ggx bumps: always supersample)",
         "bumps explicit",
         bumps,
         "bump_filter",
         [](const Resolved& r) -> json { return render::toString(r.scene.surface.filter); }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.filter; }, render::kBumpFilters);
    add({"prefilter_check",
         T::Surface,
         K::Switch,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "measure also renders the same frame with the moments prefilter and with the next seed, and reports the "
         "prefilter's error against supersampling (prefilter_* fields)",
         "bumps explicit",
         bumps,
         "prefilter_check",
         [](const Resolved& r) -> json { return r.scene.surface.prefilterCheck; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.scene.surface.prefilterCheck; });

    // ---- [measurement] ----
    add({"threshold",
         T::Measurement,
         K::Number,
         "",
         0,
         1,
         true,
         true,
         {},
         "",
         "region = lobe >= FRAC x peak",
         "every measurement",
         nullptr,
         "threshold",
         [](const Resolved& r) -> json { return r.setup.options.threshold; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.setup.options.threshold; });
    add({"lobe",
         T::Measurement,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "all (the region at threshold x the global peak, every part of it) | mirror (the lobe around the mirror "
         "direction: the maximum a climb from the mirror direction reaches, and the part of its region at threshold x "
         "that maximum that holds it, ended at a valley where the radiance rises again towards a brighter part; "
         "no_mirror_lobe where that region leaves the mirror direction out; needs the CPU twin)",
         "every measurement",
         nullptr,
         "lobe",
         [](const Resolved& r) -> json { return analysis::toString(r.setup.options.lobe); }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.setup.options.lobe; }, kLobes);
    add({"min_pixels",
         T::Measurement,
         K::Integer,
         "",
         1,
         100000,
         false,
         false,
         {},
         "px",
         "under_resolved below this many pixels across the minor axis",
         "every measurement",
         nullptr,
         "min_pixels",
         [](const Resolved& r) -> json { return r.setup.options.minPixelsAcross; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.setup.options.minPixelsAcross; });
    add({"boundary",
         T::Measurement,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "subpixel (contour pixels count their covered fraction) | pixel (in/out)",
         "every measurement",
         nullptr,
         "boundary",
         [](const Resolved& r) -> json { return r.setup.options.subpixel ? "subpixel" : "pixel"; }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.setup.options.subpixel; }, kBoundaries);
    add({"supersample",
         T::Measurement,
         K::Integer,
         "",
         1,
         8,
         false,
         false,
         {},
         "",
         "N: render the final frame N x N times with jittered sub-pixel sample points and count each pixel's "
         "covered fraction (replaces --boundary)",
         "every measurement",
         nullptr,
         "supersample",
         [](const Resolved& r) -> json { return r.setup.supersample; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.setup.supersample; });
    add({"renderer",
         T::Measurement,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "gl (float shader) | cpu (the double-precision twin on every core)",
         "every measurement",
         nullptr,
         "renderer",
         [](const Resolved& r) -> json { return r.setup.cpu ? "cpu" : "gl"; }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.setup.cpu; }, kRenderers);
    add({"crop",
         T::Measurement,
         K::Choice,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "on: automatic framing shades, reads and analyses only the region's box of the final frame (same numbers, "
         "less time) | off: the whole frame",
         "every measurement",
         nullptr,
         "crop",
         [](const Resolved& r) -> json { return r.setup.crop ? "on" : "off"; }});
    bindChoice(
        p.back(), [](auto& r) -> auto& { return r.setup.crop; }, kCrops);
    add({"aim_size",
         T::Measurement,
         K::Integer,
         "",
         16,
         1024,
         false,
         false,
         {},
         "px",
         "automatic framing: side of the coarse aiming renders that find and zoom onto the region before the final "
         "render (larger: fewer clipped first aims on thin lobes, more time)",
         "automatic framing",
         [](const Resolved& r) { return r.fovDeg == 0; },
         "aim_size",
         [](const Resolved& r) -> json { return r.setup.coarseSize; }});
    bind(
        p.back(), [](auto& r) -> auto& { return r.setup.coarseSize; });
    add({"tolerance",
         T::Measurement,
         K::Number,
         "",
         kMinTolerance,
         kMaxTolerance,
         false,
         false,
         {},
         "",
         "E: choose the cheapest settings (size, sub-pixel boundary) predicted to reach aspect error E, check them "
         "against the next finer size, report settings, error_estimate and time_ms; --size, --boundary, "
         "--supersample, --fov are chosen, not read",
         "measure",
         tolerance,
         "tolerance",
         [](const Resolved& r) -> json { return r.tolerance; }});
    bindUnset(
        p.back(), [](auto& r) -> auto& { return r.tolerance; }, 0.0);
    add({"reference",
         T::Measurement,
         K::Switch,
         "",
         0,
         0,
         false,
         false,
         {},
         "",
         "use the CPU double-precision reference instead of GL",
         "measure",
         nullptr,
         "",
         nullptr});
    bind(
        p.back(), [](auto& r) -> auto& { return r.reference; });
    return p;
}

std::string normalize(std::string name) {
    if (name.rfind("--", 0) == 0) name = name.substr(2);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

}  // namespace

const char* toString(Table t) {
    switch (t) {
        case Table::Material: return "material";
        case Table::Light: return "light";
        case Table::Camera: return "camera";
        case Table::Surface: return "surface";
        case Table::Measurement: return "measurement";
    }
    return "?";
}

const std::vector<Table>& tables() {
    static const std::vector<Table> all = {Table::Material, Table::Light, Table::Camera, Table::Surface,
                                           Table::Measurement};
    return all;
}

std::optional<Table> parseTable(const std::string& s) {
    for (Table t : tables())
        if (s == toString(t)) return t;
    return std::nullopt;
}

std::string Param::flag() const {
    std::string f = name;
    std::replace(f.begin(), f.end(), '_', '-');
    return "--" + f;
}

std::string Param::key() const { return std::string(toString(table)) + "." + name; }

std::string Param::allowed() const {
    auto interval = [&] { return rangeText(lo, hi, openLo, openHi); };
    switch (kind) {
        case Kind::Number: return (automatic.empty() ? "" : automatic + " | ") + interval();
        case Kind::Integer: return (automatic.empty() ? "" : automatic + " | ") + interval();
        case Kind::Choice: return join(choices, " | ");
        case Kind::Rgb: return "V or R,G,B, each in " + interval();
        case Kind::Switch: return "true | false";
        case Kind::Path: return "a file";
        case Kind::Angles: return "A, A,B,C or START:STOP:STEP, each in " + interval();
        case Kind::Size: return "PX or WxH, each in " + interval();
        case Kind::List: return "NAME=VALUE, repeated";
        case Kind::Text: return "a name";
    }
    return "";
}

const std::vector<Param>& registry() {
    static const std::vector<Param> all = build();
    return all;
}

const Param* find(const std::string& name) {
    // A map, not a scan: resolve() looks up every parameter, and validating 10^6 configurations resolves each.
    static const std::unordered_map<std::string, const Param*> byName = [] {
        std::unordered_map<std::string, const Param*> m;
        for (const Param& p : registry()) m.emplace(p.name, &p);
        return m;
    }();
    auto it = byName.find(name);
    if (it == byName.end()) it = byName.find(normalize(name));
    return it == byName.end() ? nullptr : it->second;
}

std::vector<std::string> names(Table t) {
    std::vector<std::string> out;
    for (const Param& p : registry())
        if (p.table == t) out.push_back(p.name);
    return out;
}

std::vector<std::string> columns() {
    std::vector<std::string> out;
    for (const Param& p : registry())
        if (!p.column.empty()) out.push_back(p.column);
    return out;
}

const char* kindName(Kind k) {
    switch (k) {
        case Kind::Number: return "number";
        case Kind::Integer: return "integer";
        case Kind::Choice: return "choice";
        case Kind::Rgb: return "rgb";
        case Kind::Switch: return "switch";
        case Kind::Path: return "path";
        case Kind::Angles: return "angles";
        case Kind::Size: return "size";
        case Kind::List: return "list";
        case Kind::Text: return "text";
    }
    return "text";
}

std::string sceneKey(const render::Scene& scene) {
    Resolved r;
    r.scene = scene;
    std::string key;
    for (const Param& p : registry())
        if (p.read) key += p.name + "=" + p.read(r, true) + ";";
    // The fields of the scene no parameter sets.
    const render::Light& l = scene.light;
    key += "rule_target=" + exactText(l.ruleTarget);
    if (l.twinRings != 0) key += ";twin_rings=" + std::to_string(l.twinRings);
    if (l.chartCenter)
        key += ";chart_centre=" + exactText(l.chartCenter->x) + "," + exactText(l.chartCenter->y) + "," +
               exactText(l.chartCenter->z);
    if (const auto& sp = scene.brdf.spectrum) key += ";spectrum=" + sp->name + ":" + std::to_string(sp->size());
    const render::Surface& f = scene.surface;
    key += ";bump_tile=" + std::to_string(f.texels) + "," + std::to_string(f.bumpsPerTile) + "," +
           exactText(f.samplesPerPeriod);
    return key;
}

std::string energyKey(const brdf::Params& p) {
    render::Scene s;
    s.brdf = p;
    // The tables are the specular lobe's albedo: the diffuse term enters them only as coupled or not, its
    // albedo and sigma not at all (brdf/energy.cpp makeEs).
    const brdf::Params plain;
    if (p.diffuse != brdf::Diffuse::Coupled) s.brdf.diffuse = plain.diffuse;
    s.brdf.albedo = plain.albedo;
    s.brdf.sigmaDeg = plain.sigmaDeg;
    s.brdf.energy.reset();
    return sceneKey(s);
}

std::string markdownTable() {
    auto escape = [](std::string s) {
        for (size_t i = 0; (i = s.find('|', i)) != std::string::npos; i += 2) s.replace(i, 1, "\\|");
        return s;
    };
    std::string t = "| flag | scene key | values | default | applies to | what it sets |\n|---|---|---|---|---|---|\n";
    for (const Param& p : registry())
        t += "| `" + p.flag() + "` | `" + p.key() + "` | " +
             escape(p.allowed() + (p.unit.empty() ? "" : " " + p.unit)) + " | " +
             (p.def.empty() ? "-" : "`" + p.def + "`") + " | " + p.appliesTo + " | " + escape(p.help) + " |\n";
    return t;
}

std::string check(const Param& p, const std::string& text) {
    auto number = [&](const std::string& t, std::string& err) -> double {
        const auto v = parseNumber(t);
        if (!v) err = "'" + t + "' is not a number";
        return v.value_or(0);
    };
    auto inRange = [&](double v) {
        return std::isfinite(v) && (p.openLo ? v > p.lo : v >= p.lo) && (p.openHi ? v < p.hi : v <= p.hi);
    };
    std::string err;
    switch (p.kind) {
        case Kind::Number: {
            if (!p.automatic.empty() && text == p.automatic) break;
            const double v = number(text, err);
            if (err.empty() && inRange(v)) break;  // the words only for a refusal: check() runs per configuration
            const std::string range = rangeText(p.lo, p.hi, p.openLo, p.openHi);
            const std::string either = p.automatic.empty() ? "" : p.automatic + " or ";
            if (!err.empty() && !either.empty())
                err = "expected " + either + "a number in " + range + " (got '" + text + "')";
            else if (err.empty()) err = "must be " + either + "a finite number in " + range + " (got " + fmt(v) + ")";
            break;
        }
        case Kind::Integer: {
            if (!p.automatic.empty() && text == p.automatic) break;
            const auto v = parseNumber(text);
            // Above 2^53 a double holds no odd number: the text itself must not exceed what was read.
            const bool exact = !v || std::abs(*v) < 9007199254740992.0 || text == exactText(*v);
            if (!v || !inRange(*v) || *v != std::floor(*v) || !exact)
                err = "must be " + (p.automatic.empty() ? std::string() : p.automatic + " or ") + "a whole number in " +
                      rangeText(p.lo, p.hi, p.openLo, p.openHi) + " (got '" + text + "')";
            break;
        }
        case Kind::Choice:
            if (std::find(p.choices.begin(), p.choices.end(), text) == p.choices.end())
                err = "unknown '" + text + "' (allowed: " + join(p.choices) + ")";
            break;
        case Kind::Rgb: {
            const auto parts = split(text, ',');
            if (parts.size() != 1 && parts.size() != 3) return "expected V or R,G,B (got '" + text + "')";
            for (const auto& part : parts) {
                const double v = number(part, err);
                if (!err.empty()) break;
                if (!inRange(v)) {
                    err = "must be a finite number in " + rangeText(p.lo, p.hi, p.openLo, p.openHi) + " (got " +
                          fmt(v) + ")";
                    break;
                }
            }
            break;
        }
        case Kind::Switch:
            if (text != "true" && text != "false") err = "expected true or false (got '" + text + "')";
            break;
        case Kind::Path:
            if (text.empty()) err = "expected a file name";
            // A C string ends at a NUL: "x.binary\0zz" would open x.binary (the library and Python can pass one).
            else if (text.find('\0') != std::string::npos) err = "a file name cannot contain a NUL character";
            break;
        case Kind::Text:
            if (text.empty() || text.size() > 80 || text != printable(text))
                err = "expected a name: one line of printable characters, at most 80 (got '" + printable(text) + "')";
            break;
        case Kind::Angles:  // the list and range syntax is checked by resolve (scene/resolve.cpp: parseAngles)
        case Kind::Size:
        case Kind::List: break;
    }
    return err;
}

}  // namespace hilite::scene
