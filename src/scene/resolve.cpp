#include "hilite/scene/resolve.hpp"

#include "gl/context.hpp"

#include "brdf/energy.hpp"
#include "brdf/materials.hpp"
#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/rgl.hpp"
#include "brdf/spectral.hpp"
#include "core/text.hpp"
#include "hilite/core/error.hpp"
#include "hilite/render/ltc.hpp"
#include "render/bumps.hpp"
#include "render/shader_source.hpp"
#include "scene/fit_table.hpp"

#include <unistd.h>

#include <cmath>
#include <iostream>
#include <map>
#include <mutex>
#include <ostream>
#include <set>
#include <stdexcept>

namespace hilite::scene {

namespace {

// The parameters resolve() reads, combines or names in a message by hand (every entry with a field writes it
// itself: Param::write), each name checked by the compiler (scene::Name).
constexpr Name kBrdf{"brdf"}, kBumpFilter{"bump_filter"}, kBumps{"bumps"}, kDiffuse{"diffuse"}, kElevation{"elevation"},
    kEta{"eta"}, kF0{"f0"}, kFitTable{"fit_table"}, kFitMaterial{"fit_material"}, kFov{"fov"}, kFresnel{"fresnel"},
    kGpu{"gpu"}, kIncidence{"incidence"}, kK{"k"}, kLight{"light"}, kLightRadius{"light_radius"},
    kLightRule{"light_rule"}, kMaterial{"material"}, kMeasured{"measured"}, kModel{"model"},
    kMultiscatter{"multiscatter"}, kNdfTable{"ndf_table"}, kParam{"param"}, kRenderer{"renderer"}, kLobe{"lobe"},
    kRoughness{"roughness"}, kRoughnessY{"roughness_y"}, kSize{"size"}, kSupersample{"supersample"},
    kTolerance{"tolerance"};

/// Prints "hilite: warning: MSG" on stderr, once per process for each message (a sweep repeats them).
void warnOnce(const std::string& msg) {
    static std::set<std::string> said;
    if (said.insert(msg).second) std::cerr << "hilite: warning: " << msg << "\n";
}

/// Reads the values of one resolve(): each parameter checked by its registry entry, errors naming where
/// the value came from.
class Reader {
public:
    explicit Reader(const Values& v) : m_v(v) {}
    const Values& values() const { return m_v; }
    bool given(Name n) const { return m_v.given(n.text); }
    bool given(const Param& p) const { return m_v.given(p.name); }
    std::string where(Name n) const { return m_v.where(n.text); }
    std::string where(const Param& p) const { return m_v.where(p.name); }
    /// The checked text of a parameter (given or default).
    std::string text(Name n) const { return text(param(n)); }
    std::string text(const Param& p) const {
        const std::string t = m_v.text(p.name);
        if (!t.empty() || m_v.given(p.name))
            if (const std::string err = check(p, t); !err.empty()) throw InputError(m_v.where(p.name) + ": " + err);
        return t;
    }
    double number(Name name) const {
        const std::string t = text(name);
        return t.empty() ? 0.0 : *parseNumber(t);
    }
    dvec3 rgb(Name name) const {
        const auto parts = split(text(name), ',');
        dvec3 v;
        for (int c = 0; c < 3; ++c) v[c] = *parseNumber(parts[parts.size() == 1 ? 0 : size_t(c)]);
        return v;
    }
    /// "0:85:5", "0,30,60" or "30", each angle checked against the entry's range.
    std::vector<double> angles(Name name) const;
    void size(Name name, int& width, int& height) const;

private:
    /// A Name is one of kNames, and kNames are the registry's entries (test_registry_defaults).
    static const Param& param(Name n) { return *find(n.text); }
    const Values& m_v;
};

std::vector<double> Reader::angles(Name name) const {
    const Param& p = param(name);
    const std::string s = m_v.text(name.text), w = where(name);
    auto angle = [&](const std::string& t) {
        const auto v = parseNumber(t);
        if (!v) throw InputError(w + ": '" + t + "' is not a number");
        if (!std::isfinite(*v) || *v < p.lo || *v > p.hi)
            throw InputError(w + ": must be a finite number in [" + fmt(p.lo) + ", " + fmt(p.hi) + "] (got " + fmt(*v) +
                             ")");
        return *v;
    };
    std::vector<double> out;
    if (s.find(':') != std::string::npos) {
        const auto parts = split(s, ':');
        if (parts.size() != 3) throw InputError(w + ": a range is START:STOP:STEP (got '" + s + "')");
        const double a = angle(parts[0]), b = angle(parts[1]);
        const auto step = parseNumber(parts[2]);
        if (!step) throw InputError(w + ": '" + parts[2] + "' is not a number");
        if (!(*step > 0) || !std::isfinite(*step) || b < a)
            throw InputError(w + ": range needs START <= STOP and a finite STEP > 0 (got '" + s + "')");
        const double n = std::floor((b - a) / *step + 1e-9);
        if (!(n <= 100000)) throw InputError(w + ": more than 100000 angles in '" + s + "'");
        for (long i = 0; i <= long(n); ++i) out.push_back(a + double(i) * *step);
    } else {
        for (const auto& part : split(s, ',')) out.push_back(angle(part));
    }
    if (out.empty()) throw InputError(w + ": no angle given");
    return out;
}

void Reader::size(Name name, int& width, int& height) const {
    const Param& p = param(name);
    const std::string s = m_v.text(name.text), w = where(name);
    const auto x = s.find('x');
    const auto a = parseNumber(s.substr(0, x));
    const auto b = x == std::string::npos ? a : parseNumber(s.substr(x + 1));
    for (const auto& v : {a, b})
        if (!v || !(*v >= p.lo && *v <= p.hi) || *v != std::floor(*v))
            throw InputError(w + ": each side must be a whole number in [" + fmt(p.lo) + ", " + fmt(p.hi) + "] (got '" +
                             s + "')");
    width = int(*a);
    height = int(*b);
    // Colour + depth attachments and the readback: 36 bytes a pixel. Refuse what the machine cannot hold.
    const double bytes = 36.0 * double(width) * double(height);
    const double avail = double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    if (avail > 0 && bytes > 0.8 * avail)
        throw InputError(w + ": " + s + " needs " + fmt(bytes / 1e9) + " GB, more than this machine has free");
}

/// A roughness: 0 is a perfect mirror (the measurement says `mirror`); values in (0, 1e-7) are raised to
/// 1e-7 with a warning (brdf::kMinNonzeroRoughness: float32 cannot render narrower lobes). `used`: the
/// model takes a roughness (else the value is only checked).
double roughness(const Reader& in, Name name, bool used) {
    const double v = in.number(name);
    if (!used) return v;
    const std::string w = in.where(name);
    if (v == 0.0)
        warnOnce(w +
                 " 0 is a perfect mirror: its lobe is a delta no pixel can sample, rendered black and measured "
                 "as 'mirror'");
    if (v > 0.0 && v < brdf::kMinNonzeroRoughness) {
        warnOnce(w + " " + fmt(v) + " raised to " + fmt(brdf::kMinNonzeroRoughness) +
                 ", the narrowest lobe float32 can render (it is already 'effectively_mirror')");
        return brdf::kMinNonzeroRoughness;
    }
    return v;
}

/// brdf::energyTables, kept per process by the registry values of the BRDF they were integrated for
/// (scene::energyKey: a parameter added to the registry enters the key).
std::shared_ptr<const brdf::EnergyTables> cachedEnergyTables(const brdf::Params& p) {
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const brdf::EnergyTables>> cache;
    const std::string key = energyKey(p);
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (auto it = cache.find(key); it != cache.end()) return it->second;
    }
    auto t = brdf::energyTables(p);
    std::lock_guard<std::mutex> lock(mutex);
    return cache.emplace(key, std::move(t)).first->second;
}

/// Fresnel: a material names a mode and its constants; fresnel, eta, k, f0 override them.
void resolveFresnel(const Reader& in, brdf::Params& p, int spectralStepNm) {
    using brdf::Fresnel;
    const std::string materialName = in.text(kMaterial);
    const brdf::Material* mat = materialName.empty() ? nullptr : brdf::findMaterial(materialName);
    const bool eta = in.given(kEta), k = in.given(kK), f0 = in.given(kF0);
    // An F0 without a named mode asks for Schlick, the only mode that takes one.
    p.fresnel = in.given(kFresnel) ? *brdf::parseFresnel(in.text(kFresnel))
                : mat              ? mat->fresnel
                : f0               ? Fresnel::Schlick
                                   : Fresnel::None;
    if (mat && brdf::hasSpectralData(mat->name)) {
        p.spectrum = brdf::loadSpectrum(render::dataDirectory(), mat->name, spectralStepNm);
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
    const std::string fresnelName = brdf::toString(p.fresnel), w = in.where(kFresnel);
    if (mat && mat->fresnel == Fresnel::Schlick &&
        (p.fresnel == Fresnel::Dielectric || p.fresnel == Fresnel::Conductor))
        throw InputError(w + " " + fresnelName + ": " + mat->name + " has an F0 preset only (use schlick)");
    if (mat && mat->fresnel != Fresnel::Dielectric && p.fresnel == Fresnel::Dielectric)
        throw InputError(w + " dielectric: " + mat->name + " is a metal (use conductor, schlick or spectral)");
    if (p.fresnel == Fresnel::Spectral && !p.spectrum)
        throw InputError(w + " spectral: needs --material copper or gold (the measured spectra)");
    if ((eta || k) && p.fresnel == Fresnel::Spectral)
        throw InputError(in.where(eta ? kEta : kK) + ": not used by --fresnel spectral (the material's spectrum is)");
    if (k && p.fresnel == Fresnel::Dielectric) throw InputError(in.where(kK) + ": only for --fresnel conductor");
    if (eta) p.eta = in.rgb(kEta);
    if (k) p.k = in.rgb(kK);
    if (f0 && p.fresnel != Fresnel::Schlick)
        throw InputError(
            in.where(kF0) + ": only for --fresnel schlick (--fresnel " + fresnelName +
            (p.fresnel == Fresnel::Spectral ? " uses the material's measured eta, k)" : " does not use F0)"));
    if (f0) p.f0 = in.rgb(kF0);
    else if (eta || k)  // Schlick's F0 of the index given
        for (int c = 0; c < 3; ++c) p.f0[c] = brdf::F_Conductor(1.0, p.eta[c], p.k[c]);
}

/// A measured table is the whole BRDF: any other material term given would go unused.
void checkMeasuredAlone(const Reader& in) {
    if (in.given(kMeasured))
        for (const Param& other : registry())
            if (other.table == Table::Material && other.name != "measured" && in.given(other))
                throw InputError(in.where(other) + ": not with " + in.where(kMeasured) +
                                 " (the MERL table is the whole BRDF: its lobe, F, G and diffuse)");
}

/// The BRDF's combined parameters, over the fields the registry's entries have written into `p`.
void resolveBrdf(const Reader& in, Purpose purpose, int spectralStepNm, brdf::Params& p) {
    const bool usesRoughness =
        p.model != brdf::Model::None && !brdf::usesExponent(p.model) && !brdf::isLiterature(p.model);
    if (purpose == Purpose::Brdf && usesRoughness && brdf::isMicrofacet(p.model)) {
        // The quadrature of `brdf albedo` resolves lobes down to kMinIntegrableRoughness; a mirror would
        // integrate to a silent 0.
        const double v = in.number(kRoughness);
        if (v < brdf::kMinIntegrableRoughness)
            throw InputError(in.where(kRoughness) + ": must be a finite number in [" +
                             fmt(brdf::kMinIntegrableRoughness) + ", " + fmt(brdf::kMaxRoughness) + "] (got " + fmt(v) +
                             ")");
    }
    p.roughness = roughness(in, kRoughness, usesRoughness);
    if (in.given(kRoughnessY)) {
        if (!brdf::allowsAnisotropy(p.model))
            throw InputError(in.where(kRoughnessY) + ": anisotropy needs --model beckmann or ggx (got '" +
                             in.text(kModel) + "')");
        p.roughnessY = roughness(in, kRoughnessY, true);
        if (purpose == Purpose::Brdf && *p.roughnessY < brdf::kMinIntegrableRoughness)
            throw InputError(in.where(kRoughnessY) + ": must be a finite number in [" +
                             fmt(brdf::kMinIntegrableRoughness) + ", " + fmt(brdf::kMaxRoughness) + "] (got " +
                             fmt(*p.roughnessY) + ")");
    }
    if (p.model == brdf::Model::Lafortune && p.lafortuneCxy == 0.0 && p.lafortuneCz == 0.0)
        throw InputError(in.where(kModel) +
                         " lafortune: --lafortune-cxy and --lafortune-cz are both 0 (no lobe: give either != 0)");
    const bool table = in.given(kNdfTable);
    if (p.model == brdf::Model::Tabulated && !table)
        throw InputError(in.where(kModel) + " tabulated: needs --ndf-table FILE (rows 'theta_h_deg, D')");
    if (table && p.model != brdf::Model::Tabulated)
        throw InputError(in.where(kNdfTable) + ": the table is the NDF of --model tabulated (got --model " +
                         in.text(kModel) + ")");
    if (table)  // an RGL .bsdf file gives its measured NDF (and projected area), told apart by content
        p.ndfTable = brdf::isRglNdfFile(in.text(kNdfTable))
                         ? brdf::rglNdfTable(in.text(kNdfTable), in.where(kNdfTable), render::dataDirectory())
                         : brdf::loadNdfTable(in.text(kNdfTable));
    resolveFresnel(in, p, spectralStepNm);
    if (in.given(kMeasured)) {
        // Told apart by content, not by name: an RGL file starts with "tensor_file", a MERL file with 90, 90, 180.
        const std::string file = in.text(kMeasured);
        if (brdf::rgl::fileIsTensorFile(file))
            p.rgl = brdf::rgl::load(file, in.where(kMeasured), render::dataDirectory());
        else p.measured = brdf::merl::load(file, in.where(kMeasured));
        p.model = brdf::Model::None;  // no analytic term runs: evaluate() and the shader use the table alone
        p.fresnel = brdf::Fresnel::None;
        p.diffuse = brdf::Diffuse::None;
        p.roughnessY.reset();
    }
    const bool ms = p.multiscatter != brdf::Multiscatter::None, coupled = p.diffuse == brdf::Diffuse::Coupled;
    if (ms || coupled) {  // the albedo tables of the energy terms, integrated (and cached) here
        const std::string w =
            ms ? in.where(kMultiscatter) + " " + in.text(kMultiscatter) : in.where(kDiffuse) + " coupled";
        try {
            p.energy = cachedEnergyTables(p);
        } catch (const std::invalid_argument& e) {
            throw InputError(w + ": " + e.what());
        }
    }
}

/// The scene's cross-parameter rules: what a .brdf file and a bump field can be combined with.
void checkScene(const Reader& in, const render::Scene& s) {
    if (in.given(kParam) && !s.brdfFile)
        throw InputError(in.where(kParam) +
                         ": only with --brdf FILE (built-in models take --exponent, --roughness, ...)");
    // A .brdf file's BRDF() is the whole BRDF: an energy term given with it would be dropped without a word.
    if (s.brdfFile)
        for (const Name& n : {kDiffuse, kMultiscatter})
            if (in.given(n) && in.text(n) != "none")
                throw InputError(in.where(n) + " " + in.text(n) + ": not with " + in.where(kBrdf) +
                                 " (its BRDF() is the whole BRDF; write a diffuse term into the file instead)");
    if (!s.surface.bumps) return;
    const std::string w = in.where(kBumps);
    if (s.brdf.isMeasured())
        throw InputError(w +
                         ": the bump field's facets take a slope distribution; a measured table has none "
                         "(drop --measured or --bumps)");
    if (s.brdfFile)
        throw InputError(w +
                         ": the bump field's facets are mirrors with a known slope distribution; a .brdf file's "
                         "BRDF() has none (drop --brdf or --bumps)");
    render::bumpSpec(s);  // the material must have a slope distribution (InputError naming --bumps)
    if (s.brdf.diffuse != brdf::Diffuse::None)
        throw InputError(w + ": the bump render is specular only (drop --diffuse)");
    if (s.brdf.multiscatter != brdf::Multiscatter::None)
        throw InputError(w + ": the bump render's facets are mirrors lit once (drop --multiscatter)");
    if (s.surface.filter == render::BumpFilter::Moments && s.brdf.model != brdf::Model::Beckmann)
        throw InputError(in.where(kBumpFilter) +
                         " moments: the prefilter's Gaussian is the slope distribution of beckmann bumps only (ggx "
                         "bumps are a remapped normal map; use supersample or auto)");
}

/// A light's own rules: a sphere must stay above the plane at every incidence of the sweep (its centre at height
/// light_distance cos(theta_i) > R; then no point of the plane sees any of it below the horizon); a light with size
/// is integrated by hilite's terms, which a .brdf file's GLSL and the bump render's Gaussian sun are not.
void checkLight(const Reader& in, const render::Light& l, const std::vector<double>& angles) {
    // Like every parameter, a light's size given to a light without one is checked and unused (`explain` writes
    // every key of the resolved scene, and its output must read back).
    if (!l.area()) return;
    const std::string w = in.where(kLight) + " " + render::toString(l.type);
    if (in.given(kBrdf))
        throw InputError(w + ": not with " + in.where(kBrdf) +
                         " (a .brdf file has no CPU twin to check the light's "
                         "quadrature against; use a point or directional light)");
    if (in.given(kBumps) && in.text(kBumps) == "explicit")
        throw InputError(w + ": not with --bumps explicit (the bump render is lit by its own Gaussian sun, --sun)");
    if (l.type != render::LightType::Sphere) return;
    for (double a : angles) {
        double c, unused;
        cosSinDeg(a, c, unused);
        const double height = l.distance * c;
        if (!(l.radius < height))
            throw InputError(in.where(kLightRadius) + ": a sphere of radius " + fmt(l.radius) + " at distance " +
                             fmt(l.distance) + " and incidence " + fmt(a) + " deg reaches the plane (its centre is " +
                             fmt(height) + " above it): the radius must be below " + fmt(height));
    }
}

/// --gpu N: only for the backends that render on an EGL device, and below the number of devices (checked
/// here, before anything is written, not when the context is made).
int gpuIndex(const Reader& in, gl::Backend backend) {
    if (backend != gl::Backend::EGLDevice && backend != gl::Backend::Auto)
        throw InputError(in.where(kGpu) + ": only with --gl-backend egl-device or auto (got " + gl::toString(backend) +
                         ")");
    // The range in the message is this machine's devices, not the registry's bound, so it is checked here.
    const std::string t = in.values().text(kGpu.text);
    const auto v = parseNumber(t);
    std::string why;
    const size_t count = gl::eglDevices(why).size();
    if (!v || *v < 0 || *v != std::floor(*v) || !(*v < double(count)))
        throw InputError(in.where(kGpu) + ": must be a whole number in [0, " + std::to_string(count) + ") (got '" + t +
                         "'; " + (count ? std::to_string(count) + " EGL devices here" : why) + ")");
    return int(*v);
}

/// The measurement's own rules: which accuracy knobs combine with the reference, a .brdf and bumps.
void checkMeasurement(const Reader& in, const Resolved& r) {
    const render::Scene& scene = r.scene;
    if (r.reference && scene.surface.bumps)
        throw InputError("--reference: the CPU reference evaluates the analytic BRDF (drop --bumps explicit)");
    if (r.reference && scene.brdfFile)
        throw InputError(
            "--reference: no CPU twin for a .brdf file (hilite cannot run its GLSL on the CPU); the GL "
            "measurement reports error_estimate from resolution convergence instead");
    if (r.setup.options.lobe == analysis::Lobe::Mirror && scene.brdfFile)
        throw InputError(
            in.where(kLobe) +
            " mirror: needs the CPU twin to find the lobe, which a .brdf file does not have (use --lobe all)");
    if (r.setup.options.lobe == analysis::Lobe::Mirror && scene.surface.bumps)
        throw InputError(in.where(kLobe) + " mirror: not with --bumps explicit (a bump field is measured whole)");
    if (r.tolerance > 0 && r.reference)
        throw InputError(in.where(kTolerance) + ": not with --reference (the reference has no settings to choose)");
    if (scene.brdfFile && r.setup.cpu)
        throw InputError(in.where(kRenderer) + " cpu: the CPU path cannot run a .brdf file's GLSL (use --renderer gl)");
    if (scene.brdfFile && r.setup.supersample > 1)
        throw InputError(in.where(kSupersample) +
                         ": a .brdf file is framed blind and measured at one sample per "
                         "pixel with the sub-pixel boundary (its error estimate comes from "
                         "resolution convergence)");
    if (scene.brdfFile && r.tolerance > 0)
        throw InputError(in.where(kTolerance) +
                         ": needs the CPU twin to estimate errors, which a .brdf file does not "
                         "have (its measurement reports error_estimate from resolution "
                         "convergence instead)");
    // A bump field renders on the GL path only; the CPU path would silently measure the analytic BRDF instead.
    if (scene.surface.bumps && r.setup.cpu)
        throw InputError(in.where(kRenderer) +
                         " cpu: the CPU path renders the analytic BRDF, not a bump field (drop "
                         "--bumps explicit, or use --renderer gl)");
    // --tolerance predicts the error of a size from the analytic lobe's convergence; a bump field's image changes
    // with the size itself (its period is set in pixels), so the prediction would not hold.
    if (scene.surface.bumps && r.tolerance > 0)
        throw InputError(in.where(kTolerance) +
                         ": calibrated on analytic lobes; a bump field's render changes with "
                         "the size (--bump-period-px is in pixels): choose --size and "
                         "--bump-samples instead");
}

}  // namespace

/// --fit-table FILE --fit-material NAME: the table's material as the values it sets (scene/fit_table.hpp), each
/// checked as a value given by hand and named by its line of the table in messages.
namespace {
Values withPreset(const Values& v) {
    const Reader in(v);
    const bool table = in.given(kFitTable), material = in.given(kFitMaterial);
    if (!table && !material) return v;
    if (!table) throw InputError(in.where(kFitMaterial) + ": only with --fit-table FILE (a table of published fits)");
    if (!material)
        throw InputError(in.where(kFitTable) + ": needs --fit-material NAME (the table's materials: " +
                         join(presetMaterials(in.text(kFitTable), in.where(kFitTable))) + ")");
    for (const Param& other : registry())
        if (other.table == Table::Material && other.name != kFitTable.text && other.name != kFitMaterial.text &&
            in.given(other))
            throw InputError(in.where(other) + ": not with " + in.where(kFitTable) +
                             " (the preset is the whole BRDF: its model, parameters and diffuse)");
    Values out = v;
    for (const PresetValue& p : presetValues(in.text(kFitTable), in.text(kFitMaterial), in.where(kFitTable))) {
        const std::string err = check(*find(p.name), p.text);
        if (!err.empty()) throw InputError(p.origin + ": " + p.name + ": " + err);
        out.set(p.name, p.text, p.origin);
    }
    return out;
}
}  // namespace

Resolved resolve(const Values& given, Purpose purpose) {
    const Values values = withPreset(given);
    const Reader in(values);
    Resolved r;
    r.values = values;
    r.spectralStepNm = purpose == Purpose::Brdf ? brdf::kFullStepNm : 5;
    render::Scene& s = r.scene;
    checkMeasuredAlone(in);
    // Every parameter bound to a field writes it (registry.cpp); the setters below combine the others.
    for (const Param& p : registry())
        if (p.write) p.write(r, in.text(p));
    resolveBrdf(in, purpose, r.spectralStepNm, s.brdf);
    if (s.brdf.isMeasured() && in.given(kBrdf))  // before reading the .brdf: the combination is the error
        throw InputError(in.where(kMeasured) + ": not with " + in.where(kBrdf) + " (each is the whole BRDF: give one)");
    if (in.given(kBrdf)) {
        auto file = std::make_shared<brdf_file::BrdfFile>(brdf_file::load(in.text(kBrdf)));
        for (const auto& a : values.list(kParam.text)) {
            try {
                brdf_file::assign(*file, a.text);
            } catch (const InputError& e) {  // from a scene or experiment file: its line first, then the .brdf's
                if (a.origin.empty()) throw;
                throw InputError(a.origin + ": " + e.what());
            }
        }
        s.brdfFile = std::move(file);
    }
    checkScene(in, s);
    r.angles = in.angles(kIncidence);
    s.light.incidenceDeg = r.angles.front();
    checkLight(in, s.light, r.angles);
    if (s.light.area() && s.light.ltc)
        if (const std::string why = render::ltcRefusal(s); !why.empty())
            throw InputError(in.where(kLightRule) + " ltc: " + why + " (allowed here: rings)");

    in.size(kSize, r.setup.width, r.setup.height);
    // r.fovDeg 0: automatic (the registry refuses a given 0)
    if (purpose == Purpose::Measure && r.fovDeg > 160)
        throw InputError(in.where(kFov) + ": fixed framing takes a field of view in (0, 160] (got " + fmt(r.fovDeg) +
                         ")");
    r.setup.fovDeg = r.fovDeg;
    if (r.view == View::Photo && r.elevationDeg == 0.0)  // a valid view, but a black image needs saying why
        warnOnce(in.where(kElevation) + " 0: the camera lies in the plane and sees it edge-on: no surface in view");
    if (in.given(kGpu)) r.gpu = gpuIndex(in, backendOf(r.backend));
    // The light's rule takes a quarter of the error budget: its radiance error moves the contour by about as much
    // relative to the lobe's width (render/area_light.hpp).
    if (r.tolerance > 0) s.light.ruleTarget = 0.25 * r.tolerance;
    if (purpose == Purpose::Measure) checkMeasurement(in, r);
    return r;
}

gl::Backend backendOf(const std::string& name) {
    if (name.empty()) return gl::backendFromEnvironment();
    if (auto b = gl::parseBackend(name)) return *b;
    throw InputError("--gl-backend: unknown '" + name + "' (allowed: " + join(gl::backendNames()) + ")");
}

brdf::Params resolveFresnel(Values v, bool spectral) {
    if (spectral) {
        if (!brdf::hasSpectralData(v.text(kMaterial.text)))
            throw InputError("--spectral: measured spectra exist for --material copper and gold only");
        if (v.given(kFresnel.text) && v.text(kFresnel.text) != "spectral")
            throw InputError("--spectral: conflicts with " + v.where(kFresnel.text) + " " + v.text(kFresnel.text));
        v.set(kFresnel.text, "spectral", "--spectral");
    }
    const brdf::Params p = resolve(v, Purpose::Brdf).scene.brdf;
    if (p.fresnel == brdf::Fresnel::None)
        throw InputError(v.where(kFresnel.text) +
                         ": give --material NAME or --fresnel schlick|dielectric|conductor|spectral");
    return p;
}

void dropEnergyTerms(brdf::Params& p) {
    p.multiscatter = brdf::Multiscatter::None;
    if (p.diffuse == brdf::Diffuse::Coupled) p.diffuse = brdf::Diffuse::None;
    p.energy.reset();
}

PinholeCamera viewCamera(const Resolved& r, View view, int width, int height) {
    const render::Scene& scene = r.scene;
    if (view == View::Measure) {
        const double fov = r.fovDeg > 0 ? r.fovDeg : 30.0;
        const MirrorChart chart = scene.light.chart();
        // Keep the camera above the plane when the mirror direction is at the horizon.
        dvec3 center = chart.wr();
        if (center.z < 1e-6) center = glm::normalize(dvec3(center.x, center.y, 1e-6));
        return PinholeCamera::measurementFrom(chart, render::eyePosition(scene), center, fov, width, height);
    }
    // Automatic: opposite the light, kept 0.5 deg above the plane so a grazing light still shows the plane.
    const double elevation = r.elevationDeg ? *r.elevationDeg : std::max(0.5, 90.0 - scene.light.incidenceDeg);
    const double fov = r.fovDeg > 0 ? r.fovDeg : 40.0;
    return PinholeCamera::photo(elevation, scene.light.azimuthDeg + 180.0, scene.eyeDistance, fov, width, height);
}

nlohmann::json parameterColumns(const Resolved& r) {
    nlohmann::json j = nlohmann::json::object();
    for (const Param& p : registry())
        if (!p.column.empty() && p.usedBy(r)) j[p.column] = p.value(r);
    return j;
}

}  // namespace hilite::scene
