#include "measurement/diagnose.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/render/area_light.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hilite::measurement {

namespace {

/// Distance from the mirror direction along (du, dv) at which the lobe falls below `level`; -1 if the
/// horizon comes first, or the lobe never falls within pi/2.
double halfWidthAlong(const TwinSampler& f, double du, double dv, double level) {
    double lo = 0, hi = 1e-12, L = 0;  // far below any lobe float or double can hold (roughness >= 1e-7)
    for (;; lo = hi, hi *= 2) {
        if (hi > kPi / 2) return -1;
        if (!f.at(hi * du, hi * dv, L)) return -1;
        if (L < level) break;
    }
    for (int i = 0; i < 20; ++i) {  // to 1e-6 of the bracket: far below the 1e-3 the flags need
        const double mid = 0.5 * (lo + hi);
        (f.at(mid * du, mid * dv, L) && L >= level ? lo : hi) = mid;
    }
    return hi;
}

void replace(analysis::Shape& s, analysis::Flag from, analysis::Flag to) {
    s.flags.erase(from);
    s.flags.insert(to);
}

}  // namespace

LobeWidths twinLobeWidths(const render::Scene& scene, double threshold) {
    const TwinSampler f(scene);
    LobeWidths w;
    w.peak = f.lobe(0, 0);
    if (!(w.peak > 0)) return w;
    w.minor = kPi;
    constexpr int kAzimuths = 16;
    for (int k = 0; k < kAzimuths; ++k) {
        const double psi = 2.0 * kPi * k / kAzimuths;
        const double r = halfWidthAlong(f, std::cos(psi), std::sin(psi), threshold * w.peak);
        if (r < 0) continue;
        w.minor = std::min(w.minor, r);
        w.major = std::max(w.major, r);
    }
    if (w.major == 0) w.minor = 0;  // cut by the horizon on every azimuth: no width of its own
    return w;
}

bool unboundedAtHorizon(const render::Scene& scene, const analysis::Shape& shape) {
    if (!(shape.peak > 0)) return false;
    const dvec3 w = scene.light.chart().direction(deg2rad(shape.peak_u_deg), deg2rad(shape.peak_v_deg));
    const double horizontal = std::hypot(w.x, w.y);
    if (!(w.z > 0 && w.z < 0.05 && horizontal > 0)) return false;
    const dvec3 eye = render::eyePosition(scene);
    auto lobeAt = [&](double z) {
        const dvec3 d = glm::normalize(dvec3(w.x / horizontal, w.y / horizontal, z));
        return brdf::luminance(render::surfaceRadiance(scene, eye, d));
    };
    return lobeAt(1e-6 * w.z) > 100.0 * lobeAt(1e-3 * w.z);
}

bool lightReaches(const render::Scene& scene) {
    const render::Light& l = scene.light;
    switch (l.type) {
        case render::LightType::Point: return l.intensity > 0 && l.position().z > 0;
        case render::LightType::Sphere: return l.intensity > 0;  // resolve keeps the sphere above the plane
        case render::LightType::Disk: return l.irradiance > 0 && l.incidenceDeg - l.angleDeg < 90.0;
        case render::LightType::Directional: break;
    }
    return l.irradiance > 0 && l.direction().z > 0;
}

void diagnose(const render::Scene& scene, double threshold, Path path, analysis::Shape& shape,
              const LobeWidths* widths) {
    using analysis::Flag;
    if (brdf::isDelta(scene.brdf)) {
        // No pixel and no search can sample a delta: the highlight is the mirror image of the light, of
        // reflectance F at the mirror pair's cos (none for a matched index, F = 0).
        const double F = brdf::luminance(brdf::fresnel(scene.brdf, scene.light.direction().z));
        if (lightReaches(scene) && F > 0) replace(shape, Flag::NoHighlight, Flag::Mirror);
        return;
    }
    const LobeWidths w = widths ? *widths : twinLobeWidths(scene, threshold);
    // The double twin's peak says when the path's numbers cannot hold the lobe: pixels are float32, the
    // reference double (a table x 1e300 is inf in float; a 1e-320 table is 0 in float, denormal in double).
    const bool pixels = path != Path::Reference;
    const double most = pixels ? double(std::numeric_limits<float>::max()) : std::numeric_limits<double>::max();
    const double least = pixels ? double(std::numeric_limits<float>::min()) : std::numeric_limits<double>::min();
    if (w.peak > most) shape.flags.insert(Flag::FloatOverflow);
    else if (w.peak > 0 && threshold * w.peak < least) shape.flags.insert(Flag::FloatUnderflow);
    if (analysis::unmeasured(shape)) {
        analysis::setUnmeasured(shape, shape.has(Flag::FloatOverflow) ? Flag::FloatOverflow : Flag::FloatUnderflow);
        return;
    }
    if (path != Path::Reference && scene.light.area() && render::lightRule(scene).error > kLightRuleFlag)
        shape.flags.insert(Flag::LightUndersampled);
    if (unboundedAtHorizon(scene, shape)) shape.flags.insert(Flag::UnboundedAtHorizon);
    if (!(w.peak > 0)) return;
    // The lobe exists, yet no pixel centre of a fixed frame sees it: the frame is too coarse for it.
    if (path != Path::Reference && shape.has(Flag::NoHighlight)) replace(shape, Flag::NoHighlight, Flag::UnderResolved);
    if (path == Path::Gl && w.major > 0 && w.minor < kEffectivelyMirrorHalfWidth)
        shape.flags.insert(Flag::EffectivelyMirror);
}

}  // namespace hilite::measurement
