// --tolerance: choose the render size from an error model, measure, check against a finer size.
//
// Error model (from experiments/accuracy_cost and the runs that calibrated it; subpixel boundary, automatic
// framing, GL): with p the pixels across the region's minor axis,
//   - a region bounded by the threshold contour: |aspect error| <= kSecondOrder / p^2 (second order:
//     measured 0.04..0.24 / p^2 over GGX alpha 0.02..0.1, Phong n = 1e4, theta_i 0..85);
//   - a region cut by the horizon: |aspect error| <= kFirstOrder / p (the horizon is taken at a pixel
//     edge: first order, with a sawtooth in the horizon's sub-pixel position; measured up to 0.08 / p).
// The subpixel boundary is on the Pareto front of every scene measured (pixel in/out costs the same time
// and is 5-30x less accurate; supersampling multiplies the time by n^2 for less than the size would give),
// so the only knob chosen here is the size.
// A sphere or disk light's rule is chosen by render::lightRule for a radiance error of E / 4 of the peak (the
// registry's light_rings auto, resolve sets ruleTarget); near the contour that moves the region's edges by about as
// much relative to the lobe's width, so the aspect by at most twice it: 2 x its measured error joins the estimate.
// --spectral-fresnel is read, not chosen: the table moves the aspect by at most 5.5e-8 against the exact sum
// (the copper cases of experiments/accuracy_cost on its 8 scenes), below the smallest tolerance (1e-5).

#include "measurement/tolerance.hpp"

#include "hilite/core/error.hpp"
#include "hilite/render/area_light.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hilite::measurement {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kSecondOrder = 0.25;  ///< aspect error * p^2, the largest seen (see above)
constexpr double kFirstOrder = 0.08;   ///< aspect error * p under a horizon cut, the largest seen
constexpr double kSafety = 2.0;        ///< choose the size predicted to reach E / kSafety
constexpr int kRounds = 4;             ///< (measure, check) rounds before giving up
/// Sizes tried, each ~1.25-1.5x the previous: the check is the next one up.
constexpr int kLadder[] = {64, 96, 128, 160, 192, 256, 320, 384, 512, 640, 768, 1024, 1280, 1536, 2048};
constexpr int kLadderSize = int(sizeof kLadder / sizeof kLadder[0]);

/// The twin's extent of the region about the mirror direction, and whether the horizon bounds it.
struct Extent {
    double aspect = 1;     ///< narrower over wider extent (u against v)
    bool horizon = false;  ///< the region reaches the horizon on the -u side (away from the normal)
};

Extent twinExtent(const render::Scene& scene, double threshold) {
    const auto r = twinRadii(scene, threshold);  // +u, -u, +v, -v
    Extent e;
    const double ru = r[0] + r[1], rv = r[2] + r[3];
    e.aspect = std::min(ru, rv) / std::max(ru, rv);
    // Just past the -u radius (away from the normal) lies the horizon when the horizon ended that ray.
    e.horizon = !twinLobe(scene).visible(-(r[1] * 1.001 + 1e-9), 0.0);
    return e;
}

/// Pixels across the minor axis at a size: automatic framing spans the larger extent over fill of the frame.
double minorPixels(const MeasureSetup& base, int size, const Extent& e) { return base.fill * size * e.aspect; }

/// The first ladder index at or after `from` whose predicted error is at most `target` (the last if none).
int chooseSize(const MeasureSetup& base, const Extent& e, double target, int from, double c, int order) {
    for (int i = from; i < kLadderSize; ++i) {
        const double p = minorPixels(base, kLadder[i], e);
        if (c / std::pow(p, order) <= target) return i;
    }
    return kLadderSize - 1;
}

MeasureSetup withSize(MeasureSetup s, int size) {
    s.width = s.height = size;
    s.fovDeg = 0;  // automatic framing: the model assumes the region fills the frame
    s.options.subpixel = true;
    s.supersample = 1;
    return s;
}

}  // namespace

ToleranceResult measureToTolerance(render::Renderer* renderer, const render::Scene& scene, const ToleranceSetup& t) {
    if (!(t.tolerance > 0)) throw InputError("--tolerance: must be > 0");
    ToleranceResult r;
    // The first draws of a program in a process compile it and JIT llvmpipe's variants (10-80 ms, once
    // per process and effect set): one small measurement first, reported apart as startup_ms, so that
    // total_ms is what choosing, measuring and checking cost.
    auto t0 = Clock::now();
    if (renderer && !t.base.cpu) measure(renderer, scene, withSize(t.base, kLadder[0]));
    r.startup_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    t0 = Clock::now();
    Extent e = twinExtent(scene, t.base.options.threshold);
    const double lightError = 2.0 * render::lightRule(scene).error;  // 0 for a point or directional light
    int order = e.horizon ? 1 : 2;
    double c = e.horizon ? kFirstOrder : kSecondOrder;
    int i = chooseSize(t.base, e, t.tolerance / kSafety, 0, c, order);
    for (r.rounds = 1; r.rounds <= kRounds; ++r.rounds) {
        r.setup = withSize(t.base, kLadder[i]);
        r.predictedError = c / std::pow(minorPixels(t.base, kLadder[i], e), order);
        r.measurement = measure(renderer, scene, r.setup);
        // The measurement knows better than the twin whether the horizon cuts the region.
        if (order == 2 && r.measurement.shape.has(analysis::Flag::HorizonCut)) {
            e.horizon = true, order = 1, c = kFirstOrder;
            const int j = chooseSize(t.base, e, t.tolerance / kSafety, i, c, order);
            if (j > i) {
                i = j;
                continue;
            }
        }
        if (i == kLadderSize - 1) {  // nothing finer to check against: the model's word is all there is
            r.checkSetup = r.setup, r.check = r.measurement;
            r.errorEstimate = r.predictedError + lightError;
            r.met = r.errorEstimate <= t.tolerance;
            break;
        }
        const int k = i + 1;
        r.checkSetup = withSize(t.base, kLadder[k]);
        r.check = measure(renderer, scene, r.checkSetup);
        // Richardson: err(s) ~ C / s^order, so a(s) - a(s') = err(s) (1 - (s/s')^order).
        const double ratio = double(kLadder[k]) / kLadder[i];
        const double diff = std::abs(r.measurement.shape.aspect - r.check.shape.aspect);
        const double shrink = 1.0 - std::pow(1.0 / ratio, order);
        r.errorEstimate = diff / shrink + lightError;
        r.met = r.errorEstimate <= t.tolerance;
        if (r.met) break;
        // Escalate with the constant the check measured (never below the model's).
        const double p = minorPixels(t.base, kLadder[i], e);
        c = std::max(c, (r.errorEstimate - lightError) * std::pow(p, order));
        i = chooseSize(t.base, e, t.tolerance / kSafety, k, c, order);
    }
    r.rounds = std::min(r.rounds, kRounds);
    r.total_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return r;
}

}  // namespace hilite::measurement
