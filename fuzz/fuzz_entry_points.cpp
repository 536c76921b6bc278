// libFuzzer target: the C++ entry points the Python module calls (python/src/module.cpp), CPU only. The input
// decodes into scene key=value pairs over the registry's names (valid-ish numbers, lists, ranges, choices
// and raw bytes), resolved for each Purpose, then the cheap calls on a resolved scene (brdf::evaluate,
// fresnel, albedo, ndfIntegral, parameterColumns, sceneToml and back); BounceSettings through
// checkBounceSettings (and a tiny studyBounces); FitOptions through checkFitOptions / checkFitScenes.
// Every bad input must throw hilite::InputError; another exception, a crash or a sanitizer report is a bug.
// No GL and nothing slow: file parameters (Kind::Path), the GPU and the backend are left out, sizes capped.

#include "brdf/integrate.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"
#include "hilite/experiments/bounces.hpp"
#include "hilite/experiments/fit.hpp"
#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"
#include "hilite/scene/scene_file.hpp"

#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace hilite;

const std::vector<const scene::Param*>& fuzzedParams() {
    static const std::vector<const scene::Param*> ps = [] {
        std::vector<const scene::Param*> out;
        for (const scene::Param& p : scene::registry())
            if (p.kind != scene::Kind::Path && p.name != "gpu" && p.name != "gl_backend") out.push_back(&p);
        return out;
    }();
    return ps;
}

const std::string& pick(FuzzedDataProvider& in, const std::vector<std::string>& v) {
    return v[in.ConsumeIntegralInRange<size_t>(0, v.size() - 1)];
}

double number(FuzzedDataProvider& in) {
    static const double special[] = {0,
                                     -0.0,
                                     1,
                                     -1,
                                     0.5,
                                     0.1,
                                     1e-7,
                                     2,
                                     45,
                                     89.999999,
                                     90,
                                     179,
                                     360,
                                     1e308,
                                     -1e308,
                                     1e-308,
                                     5e-324,
                                     2147483647,
                                     2147483648.0,
                                     9.3e18,
                                     std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity()};
    if (in.ConsumeBool()) return in.PickValueInArray(special);
    return in.ConsumeFloatingPoint<double>();
}

std::string numberText(FuzzedDataProvider& in) {
    switch (in.ConsumeIntegralInRange<int>(0, 4)) {
        case 0: return std::to_string(in.ConsumeIntegral<int64_t>());
        case 1: return std::to_string(in.ConsumeIntegralInRange<int>(-2, 100));
        default: {
            char buf[64];
            std::snprintf(buf, sizeof buf, in.ConsumeBool() ? "%.17g" : "%g", number(in));
            return buf;
        }
    }
}

std::string valueText(FuzzedDataProvider& in, const scene::Param& p) {
    switch (in.ConsumeIntegralInRange<int>(0, 7)) {
        case 0: return numberText(in);
        case 1: return numberText(in) + "," + numberText(in) + "," + numberText(in);  // a list, an rgb
        case 2: return numberText(in) + ":" + numberText(in) + ":" + numberText(in);  // a range
        case 3: return numberText(in) + "," + numberText(in);
        case 4:
            if (!p.choices.empty()) return pick(in, p.choices);
            return in.ConsumeBool() ? "auto" : (in.ConsumeBool() ? "true" : "false");
        case 5: return p.def;
        default: return in.ConsumeRandomLengthString(24);
    }
}

dvec3 direction(FuzzedDataProvider& in) {
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) return dvec3(number(in), number(in), number(in));
    const double t = in.ConsumeFloatingPointInRange<double>(0, M_PI),
                 f = in.ConsumeFloatingPointInRange<double>(0, 2 * M_PI);
    return dvec3(std::sin(t) * std::cos(f), std::sin(t) * std::sin(f), std::cos(t));
}

void onResolved(FuzzedDataProvider& in, const scene::Values& values, const scene::Resolved& r, scene::Purpose purpose) {
    (void)scene::parameterColumns(r);
    if (purpose != scene::Purpose::Brdf) return;
    const brdf::Params& p = r.scene.brdf;
    for (int i = 0; i < 4; ++i) (void)brdf::evaluate(p, direction(in), direction(in));
    const size_t n = std::min<size_t>(r.angles.size(), 2);
    for (size_t i = 0; i < n; ++i) {
        double c, s;
        cosSinDeg(r.angles[i], c, s);
        (void)brdf::fresnel(p, c);
        if (in.ConsumeIntegralInRange<int>(0, 7) == 0) (void)brdf::albedo(p, r.angles[i], r.scene.light.azimuthDeg);
    }
    try {
        const brdf::Params f = scene::resolveFresnel(values, in.ConsumeBool());
        (void)brdf::fresnel(f, std::cos(number(in)));
    } catch (const InputError&) {
    }
    if (brdf::isMicrofacet(p.model) && in.ConsumeIntegralInRange<int>(0, 3) == 0) (void)brdf::ndfIntegral(p);
}

void bounces(FuzzedDataProvider& in, const scene::Values& values) {
    experiments::BounceSettings s;
    const auto kind = micro::parseTracedSurface(
        in.ConsumeBool() ? std::string(in.ConsumeBool() ? "hermite" : "bilinear") : in.ConsumeRandomLengthString(12));
    if (!kind) return;  // the module refuses it itself
    s.options.surface = *kind;
    s.options.paths = in.ConsumeBool() ? in.ConsumeIntegralInRange<long>(-2, 300) : in.ConsumeIntegral<long>();
    s.options.batches = in.ConsumeBool() ? in.ConsumeIntegralInRange<int>(-2, 20) : in.ConsumeIntegral<int>();
    s.options.seed = in.ConsumeIntegral<uint64_t>();
    s.texels = in.ConsumeBool() ? in.ConsumeIntegralInRange<int>(-2, 100) : in.ConsumeIntegral<int>();
    s.bumpsPerTile = in.ConsumeBool() ? in.ConsumeIntegralInRange<int>(-2, 100) : in.ConsumeIntegral<int>();
    try {
        experiments::checkBounceSettings(s, in.ConsumeBool());
    } catch (const InputError&) {
        return;
    }
    try {
        const scene::Resolved r = experiments::resolveBounceScene(values);
        if (s.texels <= 64 && s.options.paths <= 200 && r.angles.size() <= 2)
            (void)experiments::studyBounces(values, s);
    } catch (const InputError&) {
    }
}

void fit(FuzzedDataProvider& in, const scene::Values& values) {
    static const std::vector<std::string> models{"phong",   "blinn",     "beckmann", "ggx",  "gaussian", "ward",
                                                 "lambert", "tabulated", "measured", "brdf", ""};
    experiments::FitOptions o;
    if (in.ConsumeBool()) {
        o.models.clear();
        for (int i = in.ConsumeIntegralInRange<int>(0, 4); i > 0; --i)
            o.models.push_back(in.ConsumeBool() ? pick(in, models) : in.ConsumeRandomLengthString(10));
    }
    if (in.ConsumeBool()) {
        o.thresholds.clear();
        for (int i = in.ConsumeIntegralInRange<int>(0, 6); i > 0; --i) o.thresholds.push_back(number(in));
    }
    for (int i = in.ConsumeIntegralInRange<int>(0, 6); i > 0; --i) o.weights.push_back(number(in));
    o.anisotropy = in.ConsumeBool();
    o.f0 = in.ConsumeBool();
    static const std::vector<std::string> geometry{"", "smith", "none", "cook-torrance", "kelemen"};
    static const std::vector<std::string> fresnel{"", "none", "schlick", "conductor", "dielectric", "spectral"};
    o.geometry = in.ConsumeBool() ? pick(in, geometry) : in.ConsumeRandomLengthString(10);
    o.fresnel = in.ConsumeBool() ? pick(in, fresnel) : in.ConsumeRandomLengthString(10);
    o.maxEvaluations = in.ConsumeBool() ? in.ConsumeIntegralInRange<int>(-2, 200) : in.ConsumeIntegral<int>();
    try {
        experiments::checkFitOptions(o);
        experiments::checkFitScenes(values, o);
    } catch (const InputError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    const auto& params = fuzzedParams();
    scene::Values values;
    for (int i = in.ConsumeIntegralInRange<int>(0, 8); i > 0; --i) {
        const scene::Param& p = *params[in.ConsumeIntegralInRange<size_t>(0, params.size() - 1)];
        values.set(p.name, valueText(in, p));
    }
    for (scene::Purpose purpose : {scene::Purpose::Measure, scene::Purpose::Render, scene::Purpose::Brdf}) {
        try {
            const scene::Resolved r = scene::resolve(values, purpose);
            onResolved(in, values, r, purpose);
        } catch (const InputError&) {
        }
    }
    try {
        (void)scene::parseSceneToml(scene::sceneToml(values), "fuzz.toml");
    } catch (const InputError&) {
    }
    switch (in.ConsumeIntegralInRange<int>(0, 2)) {
        case 0: bounces(in, values); break;
        case 1: fit(in, values); break;
        default: break;
    }
    return 0;
}
