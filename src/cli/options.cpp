#include "cli/options.hpp"

#include "brdf/materials.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/spectral.hpp"
#include "core/error.hpp"
#include "render/bumps.hpp"
#include "render/shader_source.hpp"

#include <unistd.h>

#include <cmath>
#include <iostream>
#include <set>
#include <sstream>

namespace hilite::cli {

namespace {

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

double parseNumber(const std::string& flag, const std::string& text) {
    size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (...) {
        used = 0;
    }
    if (used == 0 || used != text.size()) throw InputError(flag + ": '" + text + "' is not a number");
    return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string cur;
    std::istringstream in(s);
    while (std::getline(in, cur, sep)) out.push_back(cur);
    if (!s.empty() && s.back() == sep) out.push_back("");
    return out;
}

/// Prints "hilite: warning: MSG" on stderr, once per process for each message (a sweep repeats them).
void warnOnce(const std::string& msg) {
    static std::set<std::string> said;
    if (said.insert(msg).second) std::cerr << "hilite: warning: " << msg << "\n";
}

/// A roughness in [0, 10]: 0 is a perfect mirror (the measurement says `mirror`); values in (0, 1e-7) are
/// raised to 1e-7 with a warning (see brdf::kMinNonzeroRoughness: float32 cannot render narrower lobes).
/// `used`: the model takes a roughness (else the value is only checked).
double roughnessFlag(const std::string& flag, double v, bool used) {
    checkRange(flag, v, brdf::kMinRoughness, brdf::kMaxRoughness);
    if (!used) return v;
    if (v == 0.0)
        warnOnce(flag + " 0 is a perfect mirror: its lobe is a delta no pixel can sample, rendered black and "
                        "measured as 'mirror'");
    if (v > 0.0 && v < brdf::kMinNonzeroRoughness) {
        warnOnce(flag + " " + fmt(v) + " raised to " + fmt(brdf::kMinNonzeroRoughness) +
                 ", the narrowest lobe float32 can render (it is already 'effectively_mirror')");
        return brdf::kMinNonzeroRoughness;
    }
    return v;
}

}  // namespace

double parseNumberFlag(const std::string& flag, const std::string& text) { return parseNumber(flag, text); }

double checkRange(const std::string& flag, double v, double lo, double hi) {
    if (!std::isfinite(v) || v < lo || v > hi)
        throw InputError(flag + ": must be a finite number in [" + fmt(lo) + ", " + fmt(hi) + "] (got " + fmt(v) + ")");
    return v;
}

void addSceneFlags(CLI::App& app, SceneFlags& f, const std::string& incidenceHelp) {
    app.add_option("--scene", f.sceneFile,
                   "scene file (TOML) whose keys are these flags; flags given here override it");
    std::string materials;
    for (const auto& m : brdf::materialNames()) materials += (materials.empty() ? "" : ", ") + m;
    app.add_option("--model", f.model,
                   "specular model: phong | phong-classic (reflection lobes) | retro (retroreflective lobe about the "
                   "light) | blinn | gaussian | beckmann | ggx | tabulated (microfacet; tabulated: --ndf-table) | "
                   "none (diffuse only)")
        ->capture_default_str();
    app.add_option("--ndf-table", f.ndfTable,
                   "tabulated: CSV of 'theta_h_deg, D' rows (theta_h from 0, increasing, <= 90; D >= 0), linear "
                   "between rows, normalized so that int D (n.h) dw = 1 (the factor is reported)");
    app.add_option("--exponent", f.exponent, "phong/phong-classic/blinn/retro exponent n, in [0, 1e8]")
        ->capture_default_str();
    app.add_option("--roughness", f.roughness,
                   "beckmann m / ggx alpha / gaussian m in radians (the formulas' symbols; alpha_x if anisotropic), "
                   "in [0, 10]: 0 is a perfect mirror, (0, 1e-7) is raised to 1e-7 with a warning")
        ->capture_default_str();
    app.add_option("--roughness-y", f.roughnessY,
                   "anisotropic beckmann/ggx: alpha_y, in [0, 10] as --roughness (absent: isotropic)");
    app.add_option("--tangent-angle", f.tangentAngle,
                   "anisotropic: azimuth of the alpha_x axis in degrees, [-360, 360]")
        ->capture_default_str();
    app.add_option("--fresnel", f.fresnel,
                   "none (F = 1) | schlick | dielectric | conductor (exact) | spectral (measured metal); default: the "
                   "material's, else none");
    app.add_option("--material", f.material, "Fresnel preset: " + materials + " (copper, gold: spectral)");
    app.add_option("--eta", f.eta,
                   "dielectric/conductor index eta = n_t/n_i: V or R,G,B, each in [0.01, 100] "
                   "(default: the material's, else 1.5)");
    app.add_option("--k", f.k,
                   "conductor extinction k: V or R,G,B, each in [0, 100] (default: the material's, else 0)");
    app.add_option("--f0", f.f0,
                   "Schlick F0: V or R,G,B, each in [0, 1] (default: F(0) of --eta/--k or of the "
                   "material, else 0.04)");
    app.add_option("--geometry", f.geometry,
                   "none (G = 1) | implicit (G = cos_i cos_o) | cook-torrance (V-cavity) | smith-separable | smith "
                   "(height-correlated)")
        ->capture_default_str();
    app.add_option("--diffuse", f.diffuse, "none | lambert | oren-nayar, added to the specular lobe")
        ->capture_default_str();
    app.add_option("--albedo", f.albedo, "diffuse albedo rho: V or R,G,B, each in [0, 1]")->capture_default_str();
    app.add_option("--sigma", f.sigma, "oren-nayar facet slope deviation in degrees, [0, 90]")->capture_default_str();
    app.add_option("--incidence", f.incidence, incidenceHelp)->capture_default_str();
    app.add_option("--azimuth", f.azimuth, "light azimuth phi_i in degrees, [-360, 360]")->capture_default_str();
    app.add_option("--irradiance", f.irradiance, "light irradiance E (normal to the light), in [0, 1e6]")
        ->capture_default_str();
    app.add_option("--size", f.size, "image size: PX or WxH, each in [1, 16384]")->capture_default_str();
    app.add_option("--view", f.view,
                   "render: measure (camera on the mirror direction) | photo (looking across the plane); measure always uses the measurement view")
        ->capture_default_str();
    app.add_option("--elevation", f.elevation,
                   "photo view: camera elevation in degrees, (0, 90]; default 90 - incidence");
    app.add_option("--light", f.light, "directional (distant, irradiance E) | point (intensity I, I cos / d^2)")
        ->capture_default_str();
    app.add_option("--intensity", f.intensity, "point light intensity I, in [0, 1e12]")->capture_default_str();
    app.add_option("--light-distance", f.lightDistance, "point light distance from the origin, in [1e-3, 1e6]")
        ->capture_default_str();
    app.add_option("--distance", f.distance,
                   "eye distance from the origin (photo view; measurement view under a point light), in [1e-3, 1e6]")
        ->capture_default_str();
    app.add_option("--gl-backend", f.backend, "auto | osmesa | egl (default: $HILITE_GL_BACKEND, else auto)");
    addSurfaceFlags(app, f.surface);
    app.add_option("--brdf", f.brdf,
                   "a BRDF Explorer .brdf file (analytic): its GLSL BRDF() replaces --model and its terms (only "
                   "--tangent-angle still applies); no CPU twin, so measure frames blind and estimates its error "
                   "from resolution convergence");
    app.add_option("--param", f.params,
                   "a .brdf parameter, NAME=VALUE: float within its declared range, bool 0|1, color V or R,G,B; "
                   "repeat the flag or join several with commas (n=100,tint=1,0.5,0.2)")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--shader-timeout", f.shaderTimeout,
                   "seconds a .brdf shader may take on a probe render in a child process, and on each compile and "
                   "draw, before it is stopped (exit 2), in [0.001, 3600]")
        ->capture_default_str();
}

brdf::Params brdfParams(const SceneFlags& f) {
    using brdf::Fresnel;
    // One value or R,G,B, each a finite number in [lo, hi].
    auto rgbFlag = [](const std::string& flag, const std::string& text, double lo, double hi) {
        const auto parts = split(text, ',');
        if (parts.size() != 1 && parts.size() != 3)
            throw InputError(flag + ": expected V or R,G,B (got '" + text + "')");
        dvec3 v;
        for (int c = 0; c < 3; ++c)
            v[c] = checkRange(flag, parseNumber(flag, parts[parts.size() == 1 ? 0 : size_t(c)]), lo, hi);
        return v;
    };
    auto choice = [](const std::string& flag, const std::string& text, auto parse,
                     const std::vector<std::string>& allowed) {
        if (auto v = parse(text)) return *v;
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw InputError(flag + ": unknown '" + text + "' (allowed: " + list + ")");
    };
    brdf::Params p;
    p.model = choice("--model", f.model, brdf::parseModel, brdf::modelNames());
    p.exponent = checkRange("--exponent", f.exponent, brdf::kMinExponent, brdf::kMaxExponent);
    const bool usesRoughness = p.model != brdf::Model::None && !brdf::usesExponent(p.model);
    p.roughness = roughnessFlag("--roughness", f.roughness, usesRoughness);
    if (!f.roughnessY.empty()) {
        if (!brdf::allowsAnisotropy(p.model))
            throw InputError("--roughness-y: anisotropy needs --model beckmann or ggx (got '" + f.model + "')");
        p.roughnessY = roughnessFlag("--roughness-y", parseNumber("--roughness-y", f.roughnessY), true);
    }
    p.tangentAngleDeg = checkRange("--tangent-angle", f.tangentAngle, -360, 360);
    if (p.model == brdf::Model::Tabulated && f.ndfTable.empty())
        throw InputError("--model tabulated: needs --ndf-table FILE (rows 'theta_h_deg, D')");
    if (!f.ndfTable.empty() && p.model != brdf::Model::Tabulated)
        throw InputError("--ndf-table: the table is the NDF of --model tabulated (got --model " + f.model + ")");
    if (!f.ndfTable.empty()) p.ndfTable = brdf::loadNdfTable(f.ndfTable);
    p.geometry = choice("--geometry", f.geometry, brdf::parseGeometry, brdf::geometryNames());
    p.diffuse = choice("--diffuse", f.diffuse, brdf::parseDiffuse, brdf::diffuseNames());
    p.albedo = rgbFlag("--albedo", f.albedo, 0.0, 1.0);
    p.sigmaDeg = checkRange("--sigma", f.sigma, brdf::kMinSigmaDeg, brdf::kMaxSigmaDeg);

    // Fresnel: a material names a mode and its constants; --fresnel, --eta, --k, --f0 override them.
    const brdf::Material* mat = f.material.empty() ? nullptr : brdf::findMaterial(f.material);
    if (!f.material.empty() && !mat) {
        std::string list;
        for (const auto& m : brdf::materialNames()) list += (list.empty() ? "" : ", ") + m;
        throw InputError("--material: unknown '" + f.material + "' (allowed: " + list + ")");
    }
    // An F0 without a named mode asks for Schlick, the only mode that takes one.
    p.fresnel = !f.fresnel.empty() ? choice("--fresnel", f.fresnel, brdf::parseFresnel, brdf::fresnelNames())
                : mat              ? mat->fresnel
                : !f.f0.empty()    ? Fresnel::Schlick
                                   : Fresnel::None;
    if (mat && brdf::hasSpectralData(mat->name)) {
        p.spectrum = brdf::loadSpectrum(render::dataDirectory(), mat->name, f.spectralStepNm);
        // The metal's RGB stand-ins for the other modes: eta, k at 650 / 550 / 450 nm, F0 = spectral F(0).
        for (int c = 0; c < 3; ++c) {
            const dvec2 ek = p.spectrum->etaK(650.0 - 100.0 * c);
            p.eta[c] = ek.x;
            p.k[c] = ek.y;
        }
        p.f0 = brdf::F_Spectral(1.0, *p.spectrum);
    } else if (mat) {
        p.eta = mat->eta, p.k = mat->k, p.f0 = mat->f0;
    }
    const std::string fresnelName = brdf::toString(p.fresnel);
    if (mat && mat->fresnel == Fresnel::Schlick &&
        (p.fresnel == Fresnel::Dielectric || p.fresnel == Fresnel::Conductor))
        throw InputError("--fresnel " + fresnelName + ": " + mat->name + " has an F0 preset only (use schlick)");
    if (mat && mat->fresnel != Fresnel::Dielectric && p.fresnel == Fresnel::Dielectric)
        throw InputError("--fresnel dielectric: " + mat->name + " is a metal (use conductor, schlick or spectral)");
    if (p.fresnel == Fresnel::Spectral && !p.spectrum)
        throw InputError("--fresnel spectral: needs --material copper or gold (the measured spectra)");
    if ((!f.eta.empty() || !f.k.empty()) && p.fresnel == Fresnel::Spectral)
        throw InputError(std::string(f.eta.empty() ? "--k" : "--eta") +
                         ": not used by --fresnel spectral (the material's spectrum is)");
    if (!f.k.empty() && p.fresnel == Fresnel::Dielectric) throw InputError("--k: only for --fresnel conductor");
    if (!f.eta.empty()) p.eta = rgbFlag("--eta", f.eta, brdf::kMinEta, brdf::kMaxEta);
    if (!f.k.empty()) p.k = rgbFlag("--k", f.k, brdf::kMinK, brdf::kMaxK);
    if (!f.f0.empty() && p.fresnel != Fresnel::Schlick)
        throw InputError("--f0: only for --fresnel schlick (--fresnel " + fresnelName +
                         (p.fresnel == Fresnel::Spectral ? " uses the material's measured eta, k)"
                                                         : " does not use F0)"));
    if (!f.f0.empty())
        p.f0 = rgbFlag("--f0", f.f0, 0.0, 1.0);
    else if (!f.eta.empty() || !f.k.empty())  // Schlick's F0 of the index given
        for (int c = 0; c < 3; ++c) p.f0[c] = brdf::F_Conductor(1.0, p.eta[c], p.k[c]);
    return p;
}

render::Scene sceneOf(const SceneFlags& f) {
    render::Scene s;
    s.brdf = brdfParams(f);
    checkRange("--shader-timeout", f.shaderTimeout, 1e-3, 3600);
    if (!f.params.empty() && f.brdf.empty())
        throw InputError("--param: only with --brdf FILE (built-in models take --exponent, --roughness, ...)");
    if (!f.brdf.empty()) {
        auto file = std::make_shared<brdf_file::BrdfFile>(brdf_file::load(f.brdf));
        for (const std::string& a : f.params) brdf_file::assign(*file, a);
        s.brdfFile = std::move(file);
    }
    s.light.azimuthDeg = checkRange("--azimuth", f.azimuth, -360, 360);
    s.light.irradiance = checkRange("--irradiance", f.irradiance, 0, 1e6);
    if (f.light == "point") s.light.type = render::LightType::Point;
    else if (f.light != "directional")
        throw InputError("--light: unknown light '" + f.light + "' (allowed: directional, point)");
    s.light.intensity = checkRange("--intensity", f.intensity, 0, 1e12);
    s.light.distance = checkRange("--light-distance", f.lightDistance, 1e-3, 1e6);
    s.eyeDistance = checkRange("--distance", f.distance, 1e-3, 1e6);
    s.surface = surfaceOf(f.surface);
    if (s.surface.bumps) {
        if (s.brdfFile)
            throw InputError("--bumps: the bump field's facets are mirrors with a known slope distribution; a .brdf "
                             "file's BRDF() has none (drop --brdf or --bumps)");
        render::bumpSpec(s);  // the material must have a slope distribution (InputError naming --bumps)
        if (s.brdf.diffuse != brdf::Diffuse::None)
            throw InputError("--bumps: the bump render is specular only (drop --diffuse)");
        if (s.surface.filter == render::BumpFilter::Moments && s.brdf.model != brdf::Model::Beckmann)
            throw InputError("--bump-filter moments: the prefilter's Gaussian is the slope distribution of beckmann "
                             "bumps only (ggx bumps are a remapped normal map; use supersample or auto)");
    }
    return s;
}

void parseSize(const std::string& s, int& width, int& height) {
    const auto x = s.find('x');
    const double w = parseNumber("--size", s.substr(0, x));
    const double h = x == std::string::npos ? w : parseNumber("--size", s.substr(x + 1));
    for (double v : {w, h})
        if (!(v >= 1 && v <= 16384) || v != std::floor(v))
            throw InputError("--size: each side must be a whole number in [1, 16384] (got '" + s + "')");
    width = int(w);
    height = int(h);
    // Colour + depth attachments and the readback: 36 bytes a pixel. Refuse what the machine cannot hold.
    const double bytes = 36.0 * w * h;
    const double avail = double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    if (avail > 0 && bytes > 0.8 * avail)
        throw InputError("--size: " + s + " needs " + fmt(bytes / 1e9) + " GB, more than this machine has free");
}

std::vector<double> parseIncidence(const std::string& s, bool allowMany) {
    std::vector<double> out;
    if (s.find(':') != std::string::npos) {
        const auto p = split(s, ':');
        if (p.size() != 3) throw InputError("--incidence: a range is START:STOP:STEP (got '" + s + "')");
        const double a = checkRange("--incidence", parseNumber("--incidence", p[0]), 0, 90);
        const double b = checkRange("--incidence", parseNumber("--incidence", p[1]), 0, 90);
        const double step = parseNumber("--incidence", p[2]);
        if (!(step > 0) || b < a) throw InputError("--incidence: range needs START <= STOP and STEP > 0 (got '" + s + "')");
        const long n = std::lround(std::floor((b - a) / step + 1e-9));
        if (n > 100000) throw InputError("--incidence: more than 100000 angles in '" + s + "'");
        for (long i = 0; i <= n; ++i) out.push_back(a + double(i) * step);
    } else {
        for (const auto& part : split(s, ','))
            out.push_back(checkRange("--incidence", parseNumber("--incidence", part), 0, 90));
    }
    if (out.empty()) throw InputError("--incidence: no angle given");
    if (!allowMany && out.size() > 1) throw InputError("--incidence: render takes one angle (got '" + s + "')");
    return out;
}

View parseView(const std::string& s) {
    if (s == "measure") return View::Measure;
    if (s == "photo") return View::Photo;
    throw InputError("--view: unknown view '" + s + "' (allowed: measure, photo)");
}

gl::Backend parseBackendFlag(const std::string& s) {
    if (s.empty()) return gl::backendFromEnvironment();
    if (auto b = gl::parseBackend(s)) return *b;
    throw InputError("--gl-backend: unknown backend '" + s + "' (allowed: auto, osmesa, egl)");
}

PinholeCamera viewCamera(const SceneFlags& f, View view, const render::Scene& scene, int width, int height) {
    if (view == View::Measure) {
        const double fov = f.fov > 0 ? f.fov : 30.0;
        const MirrorChart chart = scene.light.chart();
        // Keep the camera above the plane when the mirror direction is at the horizon.
        dvec3 center = chart.wr();
        if (center.z < 1e-6) center = glm::normalize(dvec3(center.x, center.y, 1e-6));
        return PinholeCamera::measurementFrom(chart, render::eyePosition(scene), center, fov, width, height);
    }
    const double elevation = f.elevation > 0 ? f.elevation : std::max(0.5, 90.0 - scene.light.incidenceDeg);
    checkRange("--elevation", elevation, 1e-3, 90.0);
    checkRange("--distance", f.distance, 1e-3, 1e6);
    const double fov = f.fov > 0 ? f.fov : 40.0;
    return PinholeCamera::photo(elevation, scene.light.azimuthDeg + 180.0, f.distance, fov, width, height);
}

}  // namespace hilite::cli
