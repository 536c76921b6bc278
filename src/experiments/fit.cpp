#include "hilite/experiments/fit.hpp"

#include "core/text.hpp"
#include "experiments/fit_values.hpp"
#include "experiments/plot.hpp"
#include "hilite/brdf/params.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/scene/registry.hpp"
#include "io/image_io.hpp"
#include "measurement/diagnose.hpp"
#include "render/renderer.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace hilite::experiments {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The row flags that leave no shape to compare (analysis/highlight.hpp): nothing measured, or no lobe.
const char* const kUnusable[] = {"no_highlight",   "mirror",          "unbounded_at_horizon", "effectively_mirror",
                                 "float_overflow", "float_underflow", "no_mirror_lobe"};
/// The flags of a target's region that is not the highlight's own shape, left out of the fit: its edge is the
/// frame's (clipped, covers_frame: a diffuse floor above the threshold) or the horizon's (its semi-axes then
/// follow the BRDF at grazing view, where measured data hold nothing reliable: Ngan et al. 2005 cut MERL at 80
/// deg, and a table's bins below the horizon hold no data; a Beckmann table moved such samples by 20% against
/// its generator). A model's sample with them is compared all the same: the flag turns on at a border the fit
/// must be able to cross.
const char* const kNotOwnShape[] = {"clipped", "covers_frame", "horizon_cut", "peak_on_horizon"};

/// What a model's fit varies: x[0] = ln(width parameter), then ln(roughness_y / roughness) or the literature's
/// second shape parameter, then the amplitude (Schlick's F0, or the literature's height in log); the values fit
/// appends the albedo, which the shape fit then holds (albedo, or none when negative).
struct Space {
    brdf::Model model;
    const char* width;       ///< "exponent", "roughness", "abc_b", "sgd_alpha"
    double lo, hi, guess;    ///< bounds and a start for ln(width)
    bool aniso, f0;          ///< f0: the amplitude is fitted (see `amplitude`)
    bool fitAlbedo = false;  ///< the values fit varies a Lambertian albedo
    double albedo = -1;      ///< the albedo the model carries (< 0: no diffuse term)
    std::string geometry;    ///< microfacet models' G ("auto": chosen by the values fit)
    bool rgb = false;        ///< F0 and the albedo per channel (FitOptions::color), in f0Rgb, albedoRgb
    dvec3 f0Rgb{0.0}, albedoRgb{0.0};
    double f0Held = -1;  ///< amplitude set by the values fit and held by the shape fit (f0 false then; < 0: none)
    /// The amplitude's parameter: "f0" (in [0, 1]), or the literature's height (abc_a, sgd_rho_s, lafortune_rho_s:
    /// fitted in log, positive without bound)
    const char* amplitude = "f0";
    /// The literature's second shape parameter (abc_c in log, sgd_p linear), fitted with the width; "" for none.
    const char* shape = "";
    double shapeLo = 0, shapeHi = 0, shapeStart = 0;
    bool shapeLog = false;
    bool widerWhenLarger = true;  ///< roughness, sgd_alpha; false for an exponent and abc_b

    bool literature() const { return brdf::isLiterature(model); }
    bool logAmplitude() const { return literature(); }
    bool hasShape() const { return *shape != 0; }
    /// The amplitude's value at its coordinate.
    double amplitudeAt(double x) const { return logAmplitude() ? std::exp(x) : x; }
    double amplitudeCoordinate(double v) const { return logAmplitude() ? std::log(std::max(v, 1e-300)) : v; }
    double amplitudeLo() const { return logAmplitude() ? std::log(1e-8) : 0.0; }
    double amplitudeHi() const { return logAmplitude() ? std::log(1e8) : 1.0; }
    double shapeAt(double x) const { return shapeLog ? std::exp(x) : x; }
};

Space spaceOf(const std::string& name, const FitOptions& o) {
    const auto model = brdf::parseModel(name);
    Space s{*model, "roughness", std::log(1e-3), std::log(2.0), std::log(0.1), false, false, false,
            -1,     "",          false,          dvec3(0.0),    dvec3(0.0),    -1};
    if (brdf::usesExponent(*model))
        s = {*model, "exponent", std::log(1.0), std::log(1e6), std::log(100.0), false, false, false,
             -1,     "",         false,         dvec3(0.0),    dvec3(0.0),      -1};
    s.widerWhenLarger = !brdf::usesExponent(*model);
    s.aniso = o.anisotropy && brdf::allowsAnisotropy(*model);
    s.f0 = o.f0 && o.fresnel == "schlick" && brdf::isMicrofacet(*model);
    switch (*model) {  // the literature's models: each fits its height always, its own F and G held
        case brdf::Model::ABC:
            s.width = "abc_b", s.lo = std::log(1.0), s.hi = std::log(1e9), s.guess = std::log(1e4);
            s.widerWhenLarger = false;
            s.shape = "abc_c", s.shapeLo = std::log(0.01), s.shapeHi = std::log(20.0), s.shapeStart = 0.0;
            s.shapeLog = true;
            s.amplitude = "abc_a", s.f0 = true;
            break;
        case brdf::Model::SGD:
            s.width = "sgd_alpha", s.lo = std::log(1e-6), s.hi = std::log(5.0), s.guess = std::log(0.01);
            s.shape = "sgd_p", s.shapeLo = 0.0, s.shapeHi = 3.0, s.shapeStart = 0.5;
            s.amplitude = "sgd_rho_s", s.f0 = true;
            break;
        case brdf::Model::Lafortune: s.amplitude = "lafortune_rho_s", s.f0 = true; break;
        default: break;
    }
    s.fitAlbedo = o.diffuse != "off";
    s.geometry = o.geometry;
    return s;
}

/// Sets a fitted parameter of p (the fields the registry entry of that name writes: one place per name here).
void setParam(brdf::Params& p, const std::string& name, const dvec3& v) {
    if (name == "exponent") p.exponent = v.x;
    else if (name == "roughness") p.roughness = v.x;
    else if (name == "abc_b") p.abcB = v.x;
    else if (name == "abc_c") p.abcC = v.x;
    else if (name == "sgd_alpha") p.sgd.alpha = v;
    else if (name == "sgd_p") p.sgd.p = v;
    else if (name == "f0") p.f0 = v;
    else if (name == "abc_a") p.abcA = v;
    else if (name == "sgd_rho_s") p.sgd.rhoS = v;
    else if (name == "lafortune_rho_s") p.lafortuneRhoS = v;
    else if (name == "albedo") p.albedo = v;
    else throw std::logic_error("fit: no field for parameter " + name);
}

/// A scene's values without its material: the light, camera and measurement keys every model shares.
scene::Values withoutMaterial(const scene::Values& v) {
    scene::Values out;
    for (const auto& [name, value] : v.given())
        if (scene::find(name)->table != scene::Table::Material) out.set(name, value.text, value.origin);
    for (const auto& [name, items] : v.lists())
        if (scene::find(name)->table != scene::Table::Material)
            for (const auto& item : items) out.set(name, item.text, item.origin);
    return out;
}

std::string angleList(const std::vector<double>& angles) {
    std::vector<std::string> t;
    for (double a : angles) t.push_back(exactText(a));
    return join(t, ",");
}

/// A sample from a measurement's numbers and its flags (the row's spelling); not usable without a finite shape.
FitSample sampleOf(double incidence, double threshold, double major, double minor, double aspect, double peak,
                   const std::vector<std::string>& flags) {
    FitSample s{incidence, threshold, major, minor, aspect, peak, false, "", ""};
    std::vector<std::string> bad;
    for (const std::string& f : flags)
        for (const char* u : kUnusable)
            if (f == u) bad.push_back(u);
    s.usable = bad.empty() && s.major > 0 && s.minor > 0 && std::isfinite(s.major) && std::isfinite(s.minor);
    s.flags = join(flags, ",");
    s.why = bad.empty() && !s.usable ? "no shape" : join(bad, ",");
    return s;
}

/// A row of Session::measure (a non-finite number is null there: rowNumber reads it as NaN).
FitSample sampleOf(const nlohmann::json& row, double threshold) {
    std::vector<std::string> flags;
    for (const auto& f : row.value("flags", nlohmann::json::array())) flags.push_back(f.get<std::string>());
    return sampleOf(measurement::rowNumber(row, "incidence_deg"), threshold, measurement::rowNumber(row, "major_deg"),
                    measurement::rowNumber(row, "minor_deg"), measurement::rowNumber(row, "aspect"),
                    measurement::rowNumber(row, "peak"), flags);
}

/// The resolved scenes of one sweep: one per threshold, each over every angle.
std::vector<scene::Resolved> sweepScenes(scene::Values v, const FitResult& r) {
    v.set("incidence", angleList(r.angles));
    std::vector<scene::Resolved> out;
    for (double t : r.thresholds) {
        v.set("threshold", exactText(t));
        out.push_back(scene::resolve(v));
    }
    return out;
}

FitSample sampleOf(const analysis::Shape& shape, double incidence, double threshold) {
    std::vector<std::string> flags;
    for (analysis::Flag f : shape.flags) flags.push_back(analysis::toString(f));
    return sampleOf(incidence, threshold, shape.major_deg, shape.minor_deg, shape.aspect, shape.peak, flags);
}

/// The peak of a measurement image (channel 0 of (L, u, v, w)) between pixels: the brightest pixel raised by the
/// parabola through it and its neighbours along each axis. A frame made for the lowest threshold has a coarser
/// pitch than one made for a high threshold, and a peak taken at the brightest pixel alone is low by O(pitch^2)
/// of the curvature: at threshold 0.9 that moved the semi-axes by 0.2% (0 deg) to 1.4% (70 deg), GGX 0.1, 256 px.
double peakBetweenPixels(const ImageF& img) {
    const int W = img.width, H = img.height;
    auto L = [&](int x, int y) { return double(img.data[4 * (size_t(y) * size_t(W) + size_t(x))]); };
    auto w = [&](int x, int y) { return img.data[4 * (size_t(y) * size_t(W) + size_t(x)) + 3] > 0.f; };
    int bx = 0, by = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (L(x, y) > L(bx, by)) bx = x, by = y;
    const double b = L(bx, by);
    double peak = b;
    auto raise = [&](double a, double c) {
        const double curve = a - 2.0 * b + c;
        if (curve < 0.0) peak += -(a - c) * (a - c) / (8.0 * curve);
    };
    if (bx > 0 && bx + 1 < W && w(bx - 1, by) && w(bx + 1, by)) raise(L(bx - 1, by), L(bx + 1, by));
    if (by > 0 && by + 1 < H && w(bx, by - 1) && w(bx, by + 1)) raise(L(bx, by - 1), L(bx, by + 1));
    return peak;
}

/// A higher threshold's region measured in the lowest one's frame with fewer pixels than this across its minor axis
/// is measured in a frame of its own: below it the shared frame's semi-axes drifted past 2e-3 of the own frame's.
constexpr double kOneFrameMinPixels = 40;

/// Whether a sweep may take the one-frame route below: GL, automatic framing with a twin, one sample per pixel,
/// and nothing the row's own path adds (tolerance search, reference, bump fields, the mirror lobe's mask).
bool oneFrame(const scene::Resolved& r) {
    return !r.reference && r.tolerance == 0 && !r.setup.cpu && render::hasTwin(r.scene) && !r.scene.surface.bumps &&
           r.setup.fovDeg == 0 && r.setup.supersample == 1 && r.setup.options.lobe == analysis::Lobe::All;
}

/// Measures a sweep, incidence-major (the order of FitResult::samples). One frame serves every threshold of an
/// angle: the region at the lowest threshold is framed and measured as always, and the higher thresholds' regions,
/// nested inside it ({L >= t peak} shrinks as t grows), are measured on a render of that same frame. Where the
/// lowest threshold's measurement or a higher one's says anything (a flag, several parts), that threshold is
/// measured on its own instead, so every sample is one the full measurement would give or stand behind.
std::vector<FitSample> measureSweep(measurement::Session& session, const std::vector<scene::Resolved>& scenes,
                                    const FitResult& r) {
    const size_t nt = r.thresholds.size();
    std::vector<FitSample> out(r.angles.size() * nt);
    if (!oneFrame(scenes.front())) {
        for (size_t j = 0; j < nt; ++j) {
            const auto rows = session.measure(scenes[j]);
            for (size_t i = 0; i < rows.size(); ++i)
                out[i * nt + j] = sampleOf(measurement::toJson(rows[i]), r.thresholds[j]);
        }
        return out;
    }
    const size_t jmin = size_t(std::min_element(r.thresholds.begin(), r.thresholds.end()) - r.thresholds.begin());
    render::Renderer& renderer = session.rendererFor(scenes[jmin]);
    ImageF img;
    for (size_t i = 0; i < r.angles.size(); ++i) {
        auto alone = [&](size_t j) {
            render::Scene sc = scenes[j].scene;
            sc.light.incidenceDeg = r.angles[i];
            out[i * nt + j] =
                sampleOf(measurement::measure(&renderer, sc, scenes[j].setup).shape, r.angles[i], r.thresholds[j]);
        };
        render::Scene sc = scenes[jmin].scene;
        sc.light.incidenceDeg = r.angles[i];
        scene::MeasureSetup setup = scenes[jmin].setup;
        setup.keepImage = true;  // the final render, measured again at the higher thresholds' levels
        measurement::Measurement m = measurement::measure(&renderer, sc, setup);
        out[i * nt + jmin] = sampleOf(m.shape, r.angles[i], r.thresholds[jmin]);
        double peak = 0;
        const bool shared =
            m.shape.flags.empty() && m.shape.components == 1 && m.framing == "automatic" && !m.image.data.empty();
        if (shared) {
            img = std::move(m.image);
            peak = peakBetweenPixels(img);
        }
        for (size_t j = 0; j < nt; ++j) {
            if (j == jmin) continue;
            if (!shared) {
                alone(j);
                continue;
            }
            analysis::Options opt = scenes[j].setup.options;
            opt.level = opt.threshold * peak;
            analysis::Shape shape = analysis::measureImage(img.data.data(), img.width, img.height, opt);
            measurement::diagnose(sc, opt.threshold, measurement::Path::Gl, shape);
            if (!shape.flags.empty() || shape.components != 1 || shape.minor_pixels < kOneFrameMinPixels) alone(j);
            else out[i * nt + j] = sampleOf(shape, r.angles[i], r.thresholds[j]);
        }
    }
    return out;
}

double residualOf(const FitResult& r, const std::vector<FitSample>& model, bool peak) {
    double sum = 0, weight = 0;
    const size_t nt = r.thresholds.size();
    for (size_t k = 0; k < model.size(); ++k) {
        const FitSample &t = r.samples[k], &m = model[k];
        if (!t.usable) continue;
        const double w = r.weights[k % nt];
        if (!m.usable) {
            sum += w * 2.0;  // both semi-axes at log ratio 1
        } else {
            const double a = std::log(m.major / t.major), b = std::log(m.minor / t.minor);
            sum += w * (a * a + b * b);
        }
        weight += 2.0 * w;
        if (peak && k % nt == 0 && t.peak > 0) {
            const double p = m.peak > 0 ? std::log(m.peak / t.peak) : 1.0;
            sum += w * p * p;
            weight += w;
        }
    }
    return weight > 0 ? std::sqrt(sum / weight) : kNaN;
}

std::string rgbText(const dvec3& c) { return exactText(c.x) + "," + exactText(c.y) + "," + exactText(c.z); }

/// The model's values at x (the space's parameters).
scene::Values modelValues(const scene::Values& common, const Space& s, const FitOptions& o,
                          const std::vector<double>& x) {
    scene::Values v = common;
    v.set("model", brdf::toString(s.model));
    v.set(s.width, exactText(std::exp(x[0])));
    size_t k = 1;
    if (s.aniso) v.set("roughness_y", exactText(std::exp(x[0] + x[k++])));
    if (s.hasShape()) v.set(s.shape, exactText(s.shapeAt(x[k++])));
    if (s.literature()) {
        if (s.f0) v.set(s.amplitude, s.rgb ? rgbText(s.f0Rgb) : exactText(s.amplitudeAt(x[k])));
        else if (s.f0Held >= 0) v.set(s.amplitude, s.rgb ? rgbText(s.f0Rgb) : exactText(s.f0Held));
    }
    if (brdf::isMicrofacet(s.model)) {
        v.set("geometry", s.geometry == "auto" ? "smith" : s.geometry);
        v.set("fresnel", o.fresnel);
        if (s.f0) v.set("f0", s.rgb ? rgbText(s.f0Rgb) : exactText(x[k]));
        else if (s.f0Held >= 0) v.set("f0", s.rgb ? rgbText(s.f0Rgb) : exactText(s.f0Held));
    }
    if (s.albedo >= 0) {
        v.set("diffuse", "lambert");
        v.set("albedo", s.rgb ? rgbText(s.albedoRgb) : exactText(s.albedo));
    }
    return v;
}

/// The space's parameters at ln(width) w, isotropic, with Schlick's F0 of 0.04 (where the space has them).
std::vector<double> pointAt(const Space& s, double w) {
    std::vector<double> x{w};
    if (s.aniso) x.push_back(0.0);
    if (s.hasShape()) x.push_back(s.shapeStart);
    if (s.f0) x.push_back(s.logAmplitude() ? 0.0 : 0.04);
    return x;
}

/// A start for ln(width): the model whose twin half-width at the first angle and the threshold nearest 0.5
/// equals the target's semi-major axis there (bisection in log(parameter), as an experiment's [match]).
double startingWidth(const scene::Values& common, const Space& s, const FitOptions& o, const FitResult& r) {
    const size_t nt = r.thresholds.size();
    size_t jt = 0;
    for (size_t j = 0; j < nt; ++j)
        if (std::abs(r.thresholds[j] - 0.5) < std::abs(r.thresholds[jt] - 0.5)) jt = j;
    const FitSample* target = nullptr;
    for (size_t i = 0; i < r.angles.size() && !target; ++i)
        if (r.samples[i * nt + jt].usable) target = &r.samples[i * nt + jt];
    if (!target) return s.guess;
    std::vector<double> x = pointAt(s, s.guess);
    scene::Values v = modelValues(common, s, o, x);
    v.set("incidence", exactText(target->incidence));
    scene::Resolved res = scene::resolve(v);
    scene::dropEnergyTerms(res.scene.brdf);  // the search sets the roughness directly (scene/resolve.hpp)
    double lo = s.lo, hi = s.hi;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        setParam(res.scene.brdf, s.width, dvec3(std::exp(mid)));
        const double w = rad2deg(measurement::twinHalfWidth(res.scene, target->threshold));
        ((w > target->major) != s.widerWhenLarger ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Where the optimizer starts: the width matched at the first angle; with anisotropy, both ways the target's
/// aspect there can split between the axes (the semi-axes do not say which axis is wider, and from an
/// isotropic start the two are a saddle: GGX 0.1 x 0.2 stalled at 0.148 x 0.139); with F0, the F0 that gives
/// the target's peak at the first angle (the peak scales with F0 where F = F0, at normal incidence).
std::vector<std::vector<double>> startingPoints(measurement::Session& session, const scene::Values& common,
                                                const Space& s, const FitOptions& o, const FitResult& r) {
    const double w = startingWidth(common, s, o, r);
    const FitSample* first = nullptr;
    for (size_t k = 0; k < r.samples.size() && !first; ++k)
        if (r.samples[k].usable) first = &r.samples[k];
    std::vector<std::vector<double>> out;
    if (s.aniso && first && first->aspect > 0 && first->aspect < 1) {
        const double a = std::log(first->aspect);  // < 0
        out.push_back({w + a, -a});                // y wider: alpha_x the minor axis's, alpha_y = alpha_x e^-a
        out.push_back({w, a});                     // x wider
    } else {
        out.push_back(s.aniso ? std::vector<double>{w, 0.0} : std::vector<double>{w});
    }
    if (s.hasShape())
        for (auto& x : out) x.push_back(s.shapeStart);
    if (s.f0 && s.logAmplitude()) {  // the literature's height: the values fit scans it; else the peak's ratio
        double a = 0.0;
        if (first && !r.hasValues) {
            std::vector<double> x = out.front();
            x.push_back(0.0);
            const scene::Values v = modelValues(common, s, o, x);
            FitResult one = r;
            one.angles = {first->incidence};
            one.thresholds = {first->threshold};
            const auto m = measureSweep(session, sweepScenes(v, one), one);
            if (!m.empty() && m[0].peak > 0 && first->peak > 0)
                a = std::clamp(std::log(first->peak / m[0].peak), s.amplitudeLo(), s.amplitudeHi());
        }
        for (auto& x : out) x.push_back(a);
    } else if (s.f0) {  // with the values criterion its fit sets F0 instead
        double f0 = 0.04;
        if (first && !r.hasValues) {
            std::vector<double> x = out.front();
            x.push_back(f0);
            const scene::Values v = modelValues(common, s, o, x);
            FitResult one = r;
            one.angles = {first->incidence};
            one.thresholds = {first->threshold};
            const auto m = measureSweep(session, sweepScenes(v, one), one);
            if (!m.empty() && m[0].peak > 0 && first->peak > 0) f0 = std::clamp(f0 * first->peak / m[0].peak, 0.0, 1.0);
        }
        for (auto& x : out) x.push_back(f0);
    }
    return out;
}

std::string stopText(nlopt::result res) {
    switch (res) {
        case nlopt::SUCCESS: return "success";
        case nlopt::STOPVAL_REACHED: return "stopval reached";
        case nlopt::FTOL_REACHED: return "ftol reached";
        case nlopt::XTOL_REACHED: return "xtol reached";
        case nlopt::MAXEVAL_REACHED: return "maxeval reached";
        case nlopt::MAXTIME_REACHED: return "maxtime reached";
        default: return "failure";
    }
}

/// The limits of one BOBYQA run (Powell 2009, NLopt's LN_BOBYQA).
struct Search {
    std::vector<double> lo, hi, step;
    double xtolAbs = 1e-4, ftolRel = 1e-8;
    int maxEvaluations = 200;
};

/// Minimises `f` (a callable of the point) from `x` (clamped into the bounds) and says why it stopped. A stop by
/// round-off or force is a stop like the others: the caller keeps the best point it saw.
template <class F>
std::string bobyqa(F& f, std::vector<double> x, const Search& s) {
    for (size_t i = 0; i < x.size(); ++i) x[i] = std::clamp(x[i], s.lo[i], s.hi[i]);
    nlopt::opt opt(nlopt::LN_BOBYQA, unsigned(x.size()));
    opt.set_lower_bounds(s.lo);
    opt.set_upper_bounds(s.hi);
    opt.set_initial_step(s.step);
    opt.set_xtol_abs(s.xtolAbs);
    opt.set_ftol_rel(s.ftolRel);
    opt.set_maxeval(s.maxEvaluations);
    opt.set_min_objective(
        [](const std::vector<double>& xv, std::vector<double>&, void* data) { return (*static_cast<F*>(data))(xv); },
        &f);
    double value = 0;
    try {
        return stopText(opt.optimize(x, value));
    } catch (const nlopt::roundoff_limited&) {
        return "roundoff limited";
    } catch (const nlopt::forced_stop&) {
        return "forced stop";
    }
}

/// The scene's material in words, for the result.
std::string targetText(const scene::Values& v) {
    if (v.given("measured")) return "measured:" + v.text("measured");
    if (v.given("brdf")) return "brdf:" + v.text("brdf");
    std::string s = v.text("model");
    for (const auto& [name, value] : v.given())
        if (scene::find(name)->table == scene::Table::Material && name != "model") s += " " + name + "=" + value.text;
    return s;
}

}  // namespace

void checkFitOptions(const FitOptions& o) {
    if (o.models.empty()) throw InputError("--models: give at least one model (phong, blinn, beckmann, ggx, ...)");
    for (size_t i = 0; i < o.models.size(); ++i) {
        const std::string& m = o.models[i];
        const auto model = brdf::parseModel(m);
        if (!model || *model == brdf::Model::None || *model == brdf::Model::Tabulated)
            throw InputError("--models: '" + m +
                             "' is not a model with a width to fit (allowed: phong, phong-classic, "
                             "retro, blinn, gaussian, beckmann, ggx, abc, sgd, lafortune)");
        // A model twice would be fitted twice and ranked against itself.
        if (std::find(o.models.begin(), o.models.begin() + long(i), m) != o.models.begin() + long(i))
            throw InputError("--models: '" + m + "' is given twice");
    }
    if (o.thresholds.empty()) throw InputError("--thresholds: give at least one threshold in (0, 1)");
    for (double t : o.thresholds)
        if (!(t > 0 && t < 1)) throw InputError("--thresholds: each must be in (0, 1) (got " + fmt(t) + ")");
    if (!o.weights.empty()) {
        if (o.weights.size() != o.thresholds.size())
            throw InputError("--weights: one per threshold (" + std::to_string(o.thresholds.size()) + "), got " +
                             std::to_string(o.weights.size()));
        double sum = 0;
        for (double w : o.weights) {
            if (!(w >= 0) || !std::isfinite(w))
                throw InputError("--weights: each must be a finite number >= 0 (got " + fmt(w) + ")");
            sum += w;
        }
        if (!(sum > 0)) throw InputError("--weights: at least one must be > 0");
        // Relative weights, divided by their sum: an infinite sum would make every weight 0 and every fit a tie.
        if (!std::isfinite(sum))
            throw InputError("--weights: their sum must be finite (got " + fmt(sum) +
                             "): they are relative, scale them down");
    }
    if (o.anisotropy && std::none_of(o.models.begin(), o.models.end(),
                                     [](const std::string& m) { return brdf::allowsAnisotropy(*brdf::parseModel(m)); }))
        throw InputError("--fit-anisotropy: needs beckmann or ggx among --models");
    auto among = [](const std::string& flag, const std::string& v, const std::vector<std::string>& allowed) {
        if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
            throw InputError(flag + ": '" + printable(v) + "' (allowed: " + join(allowed, ", ") + ")");
    };
    among("--fit-geometry", o.geometry, fitGeometries());
    among("--fit-fresnel", o.fresnel, {"schlick", "none"});
    among("--fit-diffuse", o.diffuse, fitDiffuseChoices());
    among("--rank-by", o.rankBy, fitCriteria());
    if (o.maxEvaluations < 1 || o.maxEvaluations > 10000)
        throw InputError("--max-evaluations: an integer in [1, 10000] (got " + std::to_string(o.maxEvaluations) + ")");
}

const std::vector<std::string>& fitGeometries() {
    static const std::vector<std::string> v = {"auto", "smith", "smith-separable", "cook-torrance", "implicit", "none"};
    return v;
}
const std::vector<std::string>& fitDiffuseChoices() {
    static const std::vector<std::string> v = {"auto", "on", "off"};
    return v;
}
const std::vector<std::string>& fitCriteria() {
    static const std::vector<std::string> v = {"shape", "values"};
    return v;
}

namespace {

FitResult emptyResult(const scene::Values& target, const FitOptions& o) {
    FitResult r;
    r.target = targetText(target);
    r.thresholds = o.thresholds;
    r.weights = o.weights.empty() ? std::vector<double>(o.thresholds.size(), 1.0) : o.weights;
    r.angles = scene::resolve(target).angles;
    r.aspectThreshold = *std::min_element(r.thresholds.begin(), r.thresholds.end(),
                                          [](double a, double b) { return std::abs(a - 0.5) < std::abs(b - 0.5); });
    return r;
}

}  // namespace

void checkFitScenes(const scene::Values& target, const FitOptions& o) {
    checkFitOptions(o);
    if (target.given("brdf")) {  // a .brdf file is GLSL: no values to compare or to fit an albedo by
        if (o.rankBy == "values")
            throw InputError(
                "--rank-by values: the target has no double evaluation (a .brdf file runs as GLSL "
                "only); rank by shape");
        if (o.color)
            throw InputError(
                "--fit-color: F0 and the albedo per channel are fitted by values, and the target has no "
                "double evaluation (a .brdf file runs as GLSL only)");
        if (o.diffuse == "on")
            throw InputError(
                "--fit-diffuse on: the albedo is fitted by values, and the target has no double "
                "evaluation (a .brdf file runs as GLSL only); give auto or off");
    }
    const FitResult r = emptyResult(target, o);
    sweepScenes(target, r);
    const scene::Values common = withoutMaterial(target);
    for (const std::string& m : o.models) {
        const Space s = spaceOf(m, o);
        sweepScenes(modelValues(common, s, o, pointAt(s, s.guess)), r);
    }
}

namespace {

/// The values fit of one model: BOBYQA over the space's parameters (and the albedo where the space fits one)
/// against the target's values, from the best of a coarse scan of the width (and F0) around `x0`. Cheap: double
/// evaluations only. Returns the parameters (the albedo last, where fitted) and sets `residual`, `evaluations`.
std::vector<double> fitValues(const scene::Values& common, const Space& s, const FitOptions& o,
                              const std::vector<std::vector<double>>& starts, const values::Directions& dirs,
                              const std::vector<double>& target, double& residual, int& evaluations) {
    Space base = s;
    if (s.fitAlbedo) base.albedo = 0.5;  // resolved with a diffuse term whose albedo the search then sets
    scene::Resolved res = scene::resolve(modelValues(common, base, o, starts.front()));
    scene::dropEnergyTerms(res.scene.brdf);
    auto apply = [&](const std::vector<double>& x) {
        brdf::Params p = res.scene.brdf;
        setParam(p, s.width, dvec3(std::exp(x[0])));
        size_t k = 1;
        if (s.aniso) p.roughnessY = std::exp(x[0] + x[k++]);
        if (s.hasShape()) setParam(p, s.shape, dvec3(s.shapeAt(x[k++])));
        if (s.f0) setParam(p, s.amplitude, dvec3(s.amplitudeAt(x[k++])));
        if (s.fitAlbedo) p.albedo = dvec3(x[k]);
        return p;
    };
    std::vector<double> lo{s.lo}, hi{s.hi}, step{0.1};
    if (s.aniso) lo.push_back(std::log(0.1)), hi.push_back(std::log(10.0)), step.push_back(0.1);
    if (s.hasShape()) lo.push_back(s.shapeLo), hi.push_back(s.shapeHi), step.push_back(0.1);
    if (s.f0)
        lo.push_back(s.amplitudeLo()), hi.push_back(s.amplitudeHi()), step.push_back(s.logAmplitude() ? 0.2 : 0.02);
    if (s.fitAlbedo) lo.push_back(0.0), hi.push_back(1.0), step.push_back(0.02);
    double best = std::numeric_limits<double>::infinity();
    std::vector<double> bestX;
    auto objective = [&](const std::vector<double>& x) {
        ++evaluations;
        const double r = values::residual(values::sample(apply(x), dirs), target);
        if (r < best) best = r, bestX = x;
        return std::isfinite(r) ? r * r : 1e12;  // the mean square: smooth at an exact fit, where the RMS is a cone
    };
    // The coarse scan: ln(width) from the start in steps of 0.5 either way; F0 at 0.04, 0.3 and 0.9 (a dielectric's
    // and a metal's), a literature model's height at the ratio of the target's largest value to the model's at
    // height 1, and 1/e and e times it; the albedo at 0: the residual in log space has a plateau far from the lobe.
    std::vector<double> start;
    double startValue = std::numeric_limits<double>::infinity();
    auto largest = [](const std::vector<double>& v) {  // the samples' largest number (NaN: no data there)
        double m = 0;
        for (double x : v)
            if (x > m) m = x;
        return m;
    };
    const double targetPeak = largest(target);
    for (const std::vector<double>& x0 : starts)
        for (int i = -4; i <= 4; ++i) {
            std::vector<double> x = x0;
            x[0] = std::clamp(x0[0] + 0.5 * i, s.lo, s.hi);
            std::vector<double> amplitudes{0.0};
            if (s.f0 && s.logAmplitude()) {
                // The height that gives the model the target's largest value (f cos theta_i), the lobe alone.
                std::vector<double> unit = x;
                unit.back() = 0.0;
                if (s.fitAlbedo) unit.push_back(0.0);
                const double peak = largest(values::sample(apply(unit), dirs));
                const double a = peak > 0 && targetPeak > 0
                                     ? std::clamp(std::log(targetPeak / peak), s.amplitudeLo(), s.amplitudeHi())
                                     : 0.0;
                amplitudes = {a - 1.0, a, a + 1.0};
            } else if (s.f0) {
                amplitudes = {0.04, 0.3, 0.9};
            }
            for (double amp : amplitudes) {
                std::vector<double> y = x;
                if (s.f0) y.back() = amp;
                if (s.fitAlbedo) y.push_back(0.0);
                const double v = objective(y);
                if (v < startValue) startValue = v, start = y;
            }
        }
    bobyqa(objective, start, {lo, hi, step, o.xtolAbs, 1e-8, std::max(o.maxEvaluations, 200)});  // no rendering
    residual = best;
    return bestX;
}

/// FitOptions::color: F0 and the albedo of the model at x fitted per channel against the target's channel
/// values, the width and geometry held (BOBYQA, 2 parameters a channel, from the luminance fit's). Sets
/// s.rgb, s.f0Rgb, s.albedoRgb and returns the RMS over the three channels' values residuals.
double fitColour(const scene::Values& common, Space& s, const FitOptions& o, const std::vector<double>& x,
                 const values::Directions& dirs, const std::vector<std::vector<double>>& target, int& evaluations) {
    scene::Resolved res = scene::resolve(modelValues(common, s, o, x), scene::Purpose::Brdf);
    scene::dropEnergyTerms(res.scene.brdf);
    const bool hasF0 = s.f0 || s.f0Held >= 0;
    const double f0 = s.f0 ? s.amplitudeAt(x.back()) : std::max(s.f0Held, 0.0);
    s.f0Rgb = dvec3(f0);
    s.albedoRgb = dvec3(std::max(s.albedo, 0.0));
    double sum = 0;
    for (int c = 0; c < 3; ++c) {
        std::vector<double> y, lo, hi, step;
        if (hasF0) {
            y.push_back(s.amplitudeCoordinate(f0));
            lo.push_back(s.amplitudeLo()), hi.push_back(s.amplitudeHi()), step.push_back(s.logAmplitude() ? 0.1 : 0.02);
        }
        if (s.albedo >= 0) y.push_back(s.albedo), lo.push_back(0.0), hi.push_back(1.0), step.push_back(0.02);
        auto apply = [&](const std::vector<double>& yv) {
            brdf::Params p = res.scene.brdf;
            size_t k = 0;
            if (hasF0) setParam(p, s.amplitude, dvec3(s.amplitudeAt(yv[k++])));
            if (s.albedo >= 0) p.albedo = dvec3(yv[k]);
            return p;
        };
        double best = std::numeric_limits<double>::infinity();
        std::vector<double> bestY = y;
        auto objective = [&](const std::vector<double>& yv) {
            ++evaluations;
            const double r = values::residual(values::sample(apply(yv), dirs, c), target[size_t(c)]);
            if (r < best) best = r, bestY = yv;
            return std::isfinite(r) ? r * r : 1e12;
        };
        objective(y);
        if (!y.empty()) bobyqa(objective, y, {lo, hi, step, o.xtolAbs, 1e-8, 200});
        size_t k = 0;
        if (hasF0) s.f0Rgb[c] = s.amplitudeAt(bestY[k++]);
        if (s.albedo >= 0) s.albedoRgb[c] = bestY[k];
        sum += best * best;
    }
    s.rgb = true;
    return std::sqrt(sum / 3.0);
}

/// The target's values at the grid's directions, or empty when it has none (a .brdf file; a bump field).
std::vector<double> targetValues(const scene::Values& target, const values::Directions& dirs, int channel = -1) {
    if (target.given("brdf")) return {};
    scene::Resolved res = scene::resolve(target);
    // A bump field's appearance is not its material's BRDF: there is no BRDF to compare values with.
    if (res.scene.surface.bumps) return {};
    return values::sample(res.scene.brdf, dirs, channel);
}

/// The verdict of a ranked result: see fit.hpp.
void judge(FitResult& r) {
    r.tolerance = std::max(10.0 * r.resolution, 0.01);
    r.tieMargin = std::max(r.resolution, 1e-4);
    const double best = r.fits.front().residual;
    for (ModelFit& m : r.fits) m.tie = false;
    for (size_t k = 1; k < r.fits.size(); ++k)
        if (r.fits[k].residual - best < r.tieMargin) r.fits[k].tie = r.fits.front().tie = true;
    r.verdict = r.resolution > kMaxResolution ? "target_unresolved"
                : !(best <= r.tolerance)      ? "no_model_fits"
                : r.fits.front().tie          ? "tie"
                                              : "fits";
}

}  // namespace

FitResult fitModels(measurement::Session& session, const scene::Values& target, const FitOptions& o) {
    // Every scene resolved before the first measurement: the target's, and each model's at its start.
    checkFitScenes(target, o);
    FitResult r = emptyResult(target, o);
    r.rankBy = o.rankBy;
    const auto targetScenes = sweepScenes(target, r);
    const scene::Values common = withoutMaterial(target);
    std::vector<Space> spaces;
    auto leaveOut = [](std::vector<FitSample> samples) {  // the target's samples that are not its own shape
        for (FitSample& s : samples)
            for (const char* f : kNotOwnShape)
                if (s.usable && s.flags.find(f) != std::string::npos) s.usable = false, s.why = s.flags;
        return samples;
    };
    for (const std::string& m : o.models) spaces.push_back(spaceOf(m, o));
    const values::Directions dirs = values::grid(o.anisotropy);
    const std::vector<double> tv = targetValues(target, dirs);
    r.hasValues = !tv.empty();
    r.samples = leaveOut(measureSweep(session, targetScenes, r));
    // A threshold whose level underflows float at every angle measures nothing (the region becomes "every pixel
    // above 0", the same for every model: a fit at a search bound ranked first): refused, not fitted around.
    for (size_t j = 0; j < r.thresholds.size(); ++j) {
        bool under = true;
        for (size_t i = 0; i < r.angles.size() && under; ++i)
            under = r.samples[i * r.thresholds.size() + j].why.find("float_underflow") != std::string::npos;
        if (under)
            throw InputError("--thresholds: " + fmt(r.thresholds[j]) +
                             " cannot be measured: threshold x the target's peak is below the smallest normal float "
                             "(1.2e-38) at every incidence (float_underflow); give thresholds in (0, 1) whose level "
                             "stays above it");
    }
    if (std::none_of(r.samples.begin(), r.samples.end(), [](const FitSample& s) { return s.usable; }))
        throw InputError("fit: the target shows no measurable highlight at any incidence and threshold (" +
                         r.samples.front().why + ")" +
                         (targetScenes.front().setup.options.lobe == analysis::Lobe::All
                              ? "; a measured material's radiance often peaks at the horizon: --lobe mirror measures "
                                "the lobe about the mirror direction"
                              : ""));
    // The shape criterion's resolution: the target's own semi-axes at 1.5x the size against the fit's size.
    if (o.rankBy == "shape") {
        // Half as many pixels again, within the size limit (16384) and the memory check: else 3/4 of the size.
        const int w = targetScenes.front().setup.width, h = targetScenes.front().setup.height;
        scene::Values finer = target;
        finer.set("size", std::to_string(w * 3 / 2) + "x" + std::to_string(h * 3 / 2));
        std::vector<scene::Resolved> finerScenes;
        try {
            finerScenes = sweepScenes(finer, r);
        } catch (const InputError&) {
            finer.set("size", std::to_string(std::max(1, w * 3 / 4)) + "x" + std::to_string(std::max(1, h * 3 / 4)));
            finerScenes = sweepScenes(finer, r);
        }
        r.resolution = residualOf(r, leaveOut(measureSweep(session, finerScenes, r)), false);
        if (!std::isfinite(r.resolution)) r.resolution = 0;
    }

    for (size_t k = 0; k < o.models.size(); ++k) {
        Space s = spaces[k];
        const auto t0 = Clock::now();
        ModelFit fit;
        fit.model = o.models[k];
        fit.valuesResidual = kNaN;
        const bool f0Fitted = s.f0;
        std::vector<std::vector<double>> starts = startingPoints(session, common, s, o, r);
        if (r.hasValues) {
            // The values fit seeds the shape fit (and sets the albedo, which the shape fit holds). With geometry
            // auto, a microfacet model is fitted with Smith's G and with the implicit G (masking or none, the two
            // families of measured and idealized lobes) and keeps the one whose values fit is closer.
            std::vector<double> x;
            std::vector<std::string> geometries{s.geometry};
            if (s.geometry == "auto")
                geometries = brdf::isMicrofacet(s.model) ? std::vector<std::string>{"smith", "implicit"}
                                                         : std::vector<std::string>{"smith"};
            fit.valuesResidual = std::numeric_limits<double>::infinity();
            std::string chosen = geometries.front();
            for (const std::string& g : geometries) {
                Space sg = s;
                sg.geometry = g;
                double res = kNaN;
                std::vector<double> xg = fitValues(common, sg, o, starts, dirs, tv, res, fit.valueEvaluations);
                if (res < fit.valuesResidual || x.empty()) fit.valuesResidual = res, x = xg, chosen = g;
            }
            s.geometry = chosen;
            if (s.fitAlbedo) {
                s.albedo = x.back();
                x.pop_back();
                if (o.diffuse == "auto" && s.albedo < kMinFittedAlbedo) s.albedo = -1;  // no diffuse part
            }
            if (s.f0) {  // F0 sets the magnitude, which the semi-axes do not see: the values fit's is held
                s.f0Held = s.amplitudeAt(x.back());
                x.pop_back();
                s.f0 = false;
            }
            starts = {x};
        } else {
            s.fitAlbedo = false;
            if (s.geometry == "auto") {  // no values to choose by: the shape residual at the start chooses
                double lowest = std::numeric_limits<double>::infinity();
                std::string chosen = "smith";
                for (const char* g : {"smith", "implicit"}) {
                    if (!brdf::isMicrofacet(s.model)) break;
                    Space sg = s;
                    sg.geometry = g;
                    ++fit.evaluations;
                    const double res = residualOf(
                        r, measureSweep(session, sweepScenes(modelValues(common, sg, o, starts.front()), r), r), sg.f0);
                    if (res < lowest) lowest = res, chosen = g;
                }
                s.geometry = chosen;
            }
        }
        // Seeded by the values fit, the shape fit starts near its answer (smaller first steps) and varies the
        // width alone (and the anisotropy); without values (a .brdf file) it fits F0 against the peaks too.
        const double scale = r.hasValues ? 0.4 : 1.0;
        std::vector<double> lo{s.lo}, hi{s.hi}, step{0.05 * scale};
        if (s.aniso) lo.push_back(std::log(0.1)), hi.push_back(std::log(10.0)), step.push_back(0.1 * scale);
        if (s.hasShape()) lo.push_back(s.shapeLo), hi.push_back(s.shapeHi), step.push_back(0.1 * scale);
        if (s.f0)
            lo.push_back(s.amplitudeLo()), hi.push_back(s.amplitudeHi()),
                step.push_back((s.logAmplitude() ? 0.2 : 0.02) * scale);
        double best = std::numeric_limits<double>::infinity();
        std::vector<double> bestX = starts.front();
        std::vector<FitSample> bestSamples;
        auto objective = [&](const std::vector<double>& xv) {
            ++fit.evaluations;
            const auto samples = measureSweep(session, sweepScenes(modelValues(common, s, o, xv), r), r);
            const double res = residualOf(r, samples, s.f0);
            if (res < best || bestSamples.empty()) best = res, bestX = xv, bestSamples = samples;
            return std::isfinite(res) ? res * res : 1e12;  // the mean square, as the values fit
        };
        // ftol 1e-3 of the mean square: the residual to 5e-4 of itself, and a flat residual (phong against a
        // microfacet lobe) stops before xtol.
        auto optimize = [&](const std::vector<double>& x) {
            fit.stop = bobyqa(objective, x, {lo, hi, step, o.xtolAbs, 1e-3, o.maxEvaluations});
        };
        if (o.rankBy == "values") {
            objective(starts.front());  // the shape residual at the values fit's parameters
            fit.stop = "values fit";
        } else {
            for (const std::vector<double>& x : starts) optimize(x);
            if (r.hasValues) {  // the values residual at the parameters reported
                scene::Resolved res = scene::resolve(modelValues(common, s, o, bestX), scene::Purpose::Brdf);
                fit.valuesResidual = values::residual(values::sample(res.scene.brdf, dirs), tv);
            }
        }
        if (o.color && r.hasValues && (f0Fitted || s.albedo >= 0)) {
            // Per channel: F0 and the albedo refitted by values at the width found, then the shape measured there.
            std::vector<std::vector<double>> tc;
            for (int c = 0; c < 3; ++c) tc.push_back(targetValues(target, dirs, c));
            fit.valuesResidual = fitColour(common, s, o, bestX, dirs, tc, fit.valueEvaluations);
            const auto samples = measureSweep(session, sweepScenes(modelValues(common, s, o, bestX), r), r);
            ++fit.evaluations;
            best = residualOf(r, samples, s.f0);
            bestSamples = samples;
        }
        fit.shapeResidual = best;
        fit.residual = o.rankBy == "values" ? fit.valuesResidual : fit.shapeResidual;
        fit.samples = bestSamples;
        fit.params[s.width] = std::exp(bestX[0]);
        size_t j = 1;
        auto rgbJson = [](const dvec3& c) { return nlohmann::ordered_json::array({c.x, c.y, c.z}); };
        if (s.aniso) fit.params["roughness_y"] = std::exp(bestX[0] + bestX[j++]);
        if (s.hasShape()) fit.params[s.shape] = s.shapeAt(bestX[j++]);
        if (f0Fitted)
            fit.params[s.amplitude] =
                s.rgb ? rgbJson(s.f0Rgb) : nlohmann::ordered_json(s.f0 ? s.amplitudeAt(bestX[j]) : s.f0Held);
        if (s.albedo >= 0) fit.params["albedo"] = s.rgb ? rgbJson(s.albedoRgb) : nlohmann::ordered_json(s.albedo);
        if (brdf::isMicrofacet(s.model)) fit.params["geometry"] = s.geometry;
        // A parameter at its search bound is named: the target wanted it beyond, so its number is the bound's (a
        // degenerate fit that ranks first would otherwise read as an answer).
        auto atBound = [&](const std::string& name, double x, double a, double b) {
            const double margin = 1e-3 * (b - a);
            if ((x <= a + margin || x >= b - margin) &&
                std::find(fit.atBound.begin(), fit.atBound.end(), name) == fit.atBound.end())
                fit.atBound.push_back(name);
        };
        atBound(s.width, bestX[0], s.lo, s.hi);
        j = 1;
        if (s.aniso) atBound("roughness_y", bestX[j++], std::log(0.1), std::log(10.0));
        if (s.hasShape()) atBound(s.shape, bestX[j++], s.shapeLo, s.shapeHi);
        // Schlick's F0 and the albedo have physical bounds, not search bounds: F0 = 1 is F = 1 (a target without
        // Fresnel), the albedo's ends are the target's; only F0 = 0, a lobe switched off, is degenerate.
        if (f0Fitted)
            for (double v : s.rgb ? std::vector<double>{s.f0Rgb.x, s.f0Rgb.y, s.f0Rgb.z}
                                  : std::vector<double>{s.f0 ? s.amplitudeAt(bestX[j]) : s.f0Held}) {
                if (s.logAmplitude()) atBound(s.amplitude, s.amplitudeCoordinate(v), s.amplitudeLo(), s.amplitudeHi());
                else if (v <= 1e-3 && fit.atBound.end() == std::find(fit.atBound.begin(), fit.atBound.end(), "f0"))
                    fit.atBound.push_back("f0");
            }
        fit.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        r.fits.push_back(std::move(fit));
    }
    // Ranked; a residual that is not a number (nothing measured) ranks last.
    std::stable_sort(r.fits.begin(), r.fits.end(), [](const ModelFit& a, const ModelFit& b) {
        const bool fa = std::isfinite(a.residual), fb = std::isfinite(b.residual);
        return fa != fb ? fa : fa && a.residual < b.residual;
    });
    for (size_t i = 0; i < r.fits.size(); ++i) r.fits[i].rank = int(i) + 1;
    judge(r);
    return r;
}

size_t aspectIndex(const FitResult& r) {
    return size_t(std::find(r.thresholds.begin(), r.thresholds.end(), r.aspectThreshold) - r.thresholds.begin());
}

std::vector<double> aspectResiduals(const FitResult& r, const ModelFit& m) {
    const size_t nt = r.thresholds.size();
    const size_t jt = aspectIndex(r);
    std::vector<double> out;
    for (size_t i = 0; i < r.angles.size(); ++i) {
        const FitSample &t = r.samples[i * nt + jt], &f = m.samples[i * nt + jt];
        out.push_back(t.usable && f.usable ? f.aspect - t.aspect : kNaN);
    }
    return out;
}

nlohmann::ordered_json toJson(const FitResult& r, const ModelFit& m) {
    nlohmann::ordered_json j;
    j["model"] = m.model;
    j["params"] = m.params;
    j["at_bound"] = m.atBound;
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
    j["residual"] = number(m.residual);
    j["shape_residual"] = number(m.shapeResidual);
    j["values_residual"] = number(m.valuesResidual);
    j["rank"] = m.rank;
    j["rank_by"] = r.rankBy;
    j["tie"] = m.tie;
    j["verdict"] = r.verdict;
    j["resolution"] = r.resolution;
    j["tolerance"] = r.tolerance;
    j["target"] = r.target;
    j["evaluations"] = m.evaluations;
    j["value_evaluations"] = m.valueEvaluations;
    j["time_ms"] = m.ms;
    j["stop"] = m.stop;
    j["thresholds"] = r.thresholds;
    j["weights"] = r.weights;
    j["incidence_deg"] = r.angles;
    j["aspect_threshold"] = r.aspectThreshold;
    nlohmann::ordered_json res = nlohmann::ordered_json::array(), target = nlohmann::ordered_json::array(),
                           fitted = nlohmann::ordered_json::array();
    const size_t nt = r.thresholds.size();
    const size_t jt = aspectIndex(r);
    const auto d = aspectResiduals(r, m);
    for (size_t i = 0; i < d.size(); ++i) {
        res.push_back(std::isfinite(d[i]) ? nlohmann::ordered_json(d[i]) : nlohmann::ordered_json());
        const FitSample &t = r.samples[i * nt + jt], &f = m.samples[i * nt + jt];
        target.push_back(t.usable ? nlohmann::ordered_json(t.aspect) : nlohmann::ordered_json());
        fitted.push_back(f.usable ? nlohmann::ordered_json(f.aspect) : nlohmann::ordered_json());
    }
    j["target_aspect"] = target;
    j["aspect"] = fitted;
    j["aspect_residual"] = res;
    return j;
}

bool writeFitFolder(const std::string& dir, const FitResult& r, std::string& why) {
    std::ostringstream js, csv;
    for (const ModelFit& m : r.fits) js << toJson(r, m).dump() << "\n";
    csv.precision(17);
    csv << "series,model,params,incidence_deg,threshold,major_deg,minor_deg,aspect,peak,usable\n";
    auto rows = [&](const std::string& series, const std::string& model, const std::string& params,
                    const std::vector<FitSample>& ss) {
        for (const FitSample& s : ss)
            csv << series << "," << model << ",\"" << params << "\"," << s.incidence << "," << s.threshold << ","
                << s.major << "," << s.minor << "," << s.aspect << "," << s.peak << "," << (s.usable ? 1 : 0) << "\n";
    };
    std::string target = r.target;
    std::replace(target.begin(), target.end(), '"', '\'');
    std::replace(target.begin(), target.end(), ',', ';');
    rows("target", target, "", r.samples);
    for (const ModelFit& m : r.fits) {
        std::string p = m.params.dump();
        std::replace(p.begin(), p.end(), '"', '\'');
        rows("fit", m.model, p, m.samples);
    }
    io::writeFileAtomic(dir + "/fit.json", js.str());
    io::writeFileAtomic(dir + "/fit.csv", csv.str());
    // Plots: aspect at the aspect threshold against incidence, the target and each fit; and the residual.
    std::vector<nlohmann::json> aspectRows, residualRows;
    const size_t nt = r.thresholds.size();
    const size_t jt = aspectIndex(r);
    for (size_t i = 0; i < r.angles.size(); ++i)
        if (r.samples[i * nt + jt].usable)
            aspectRows.push_back(
                {{"incidence", r.angles[i]}, {"aspect", r.samples[i * nt + jt].aspect}, {"series", "target"}});
    for (const ModelFit& m : r.fits) {
        const std::string name = m.model + " (rank " + std::to_string(m.rank) + ")";
        const auto d = aspectResiduals(r, m);
        for (size_t i = 0; i < r.angles.size(); ++i) {
            if (m.samples[i * nt + jt].usable)
                aspectRows.push_back(
                    {{"incidence", r.angles[i]}, {"aspect", m.samples[i * nt + jt].aspect}, {"series", name}});
            if (std::isfinite(d[i]))
                residualRows.push_back({{"incidence", r.angles[i]}, {"residual", d[i]}, {"series", name}});
        }
    }
    PlotSpec a;
    a.file = "fit_aspect.png";
    a.title = "aspect at threshold " + fmt(r.aspectThreshold) + ": " + r.target +
              " and each fit (verdict: " + r.verdict + ", ranked by " + r.rankBy + ")";
    a.x = "incidence";
    a.y = "aspect";
    a.series = "series";
    a.xlabel = "incidence (deg)";
    a.ylabel = "aspect (minor / major)";
    PlotSpec b = a;
    b.file = "fit_residual.png";
    b.title = "aspect residual (fit - target) at threshold " + fmt(r.aspectThreshold) + " (verdict: " + r.verdict + ")";
    b.y = "residual";
    b.ylabel = "aspect residual";
    b.key = "top left";
    a.colourOrder = {"target"};  // one colour per model in both plots, the target's first
    for (const ModelFit& m : r.fits) a.colourOrder.push_back(m.model + " (rank " + std::to_string(m.rank) + ")");
    b.colourOrder = a.colourOrder;
    std::string w1, w2;
    const bool ok1 = plot(dir, a, aspectRows, w1), ok2 = plot(dir, b, residualRows, w2);
    why = !ok1 ? w1 : w2;
    return ok1 && ok2;
}

}  // namespace hilite::experiments
