#include "measurement/mirror_lobe.hpp"

#include "hilite/measurement/measure_scene.hpp"
#include "hilite/scene/registry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace hilite::measurement {

namespace {

/// The twin's radiance at chart point q; -1 below the horizon or off the chart (so that it never wins a climb).
double valueAt(const TwinSampler& f, dvec2 q) {
    double L = 0;
    if (!(glm::dot(q, q) < kPi * kPi) || !f.at(q.x, q.y, L)) return -1.0;
    return L;
}

/// Compass search (8 directions) from the mirror direction: a step moves to the highest of its 8 neighbours when
/// that is higher, else halves, down to 1e-10 rad. The step never grows past `first` (a fraction of the lobe's
/// width), so the climb follows the hill it starts on and cannot jump a valley onto a rival; a point below the
/// horizon never wins, so a lobe that still rises there is climbed to the horizon.
std::pair<dvec2, double> climb(const TwinSampler& f, double first) {
    static const dvec2 dirs[8] = {
        {1, 0}, {-1, 0}, {0, 1}, {0, -1}, {0.7071, 0.7071}, {-0.7071, -0.7071}, {0.7071, -0.7071}, {-0.7071, 0.7071}};
    dvec2 q(0.0);
    double best = valueAt(f, q), step = first;
    for (int iter = 0; iter < 100000 && step > 1e-10; ++iter) {
        dvec2 next = q;
        double nextValue = best;
        for (const dvec2& d : dirs) {
            const dvec2 p = q + step * d;
            const double x = valueAt(f, p);
            if (x > nextValue) nextValue = x, next = p;
        }
        if (nextValue > best) best = nextValue, q = next;
        else step *= 0.5;
    }
    return {q, best};
}

struct RayEnd {
    double r = 0;
    bool valley = false;
};

/// Where the lobe's hill ends along one ray from the peak p: marched from the peak (step h0, growing as r / 50),
/// then bisected to the threshold or the horizon; a rise of kValleyRise x peak above the lowest value since the
/// peak ends it at that lowest point instead.
RayEnd walk(const TwinSampler& f, dvec2 p, dvec2 dir, double peak, double level, double h0) {
    double r = 0, low = peak, lowAt = 0;
    for (int i = 0; i < 100000; ++i) {
        const double next = r + std::max(h0, r / 50.0);
        const double L = next > kPi ? -1.0 : valueAt(f, p + next * dir);
        if (L < level) {  // the threshold or the horizon (-1): between r and next
            double lo = r, hi = next;
            for (int k = 0; k < 60 && hi - lo > 1e-14; ++k) {
                const double mid = 0.5 * (lo + hi);
                (valueAt(f, p + mid * dir) >= level ? lo : hi) = mid;
            }
            return {hi, false};
        }
        if (L < low) low = L, lowAt = next;
        if (L > low + kValleyRise * peak) return {lowAt, true};
        r = next;
    }
    return {r, false};
}

MirrorLobe find(const render::Scene& scene, double frac) {
    const TwinSampler f(scene);
    MirrorLobe lobe;
    lobe.mirrorValue = valueAt(f, dvec2(0.0));
    // The lobe's scale: its half-width about the mirror direction (30 deg where the mirror direction is dark).
    const double width = twinHalfWidth(scene, frac);
    const auto [p, peak] = climb(f, std::clamp(width / 8.0, 1e-9, deg2rad(0.5)));
    lobe.peak = std::max(peak, 0.0);
    lobe.peakUV = p;
    lobe.peakOnHorizon = scene.light.chart().direction(p.x, p.y).z < 1e-6;
    lobe.level = frac * lobe.peak;
    if (!(lobe.peak > 0)) return lobe;
    lobe.step = std::max(width / 100.0, 1e-12);
    lobe.extent.resize(kMirrorLobeRays);
    lobe.valley.resize(kMirrorLobeRays);
    bool threshold = false;  // some ray ends at the threshold: the lobe has an edge of its own
    int valleys = 0;
    for (int k = 0; k < kMirrorLobeRays; ++k) {
        const double phi = 2.0 * kPi * k / kMirrorLobeRays;
        const RayEnd e = walk(f, p, {std::cos(phi), std::sin(phi)}, lobe.peak, lobe.level, lobe.step);
        lobe.extent[size_t(k)] = e.r;
        lobe.valley[size_t(k)] = e.valley;
        lobe.saddleCut = lobe.saddleCut || e.valley;
        valleys += e.valley;
        if (!e.valley) {
            const dvec2 q = p + (e.r * 1.0001 + 1e-12) * dvec2(std::cos(phi), std::sin(phi));
            threshold = threshold || valueAt(f, q) >= 0.0;  // ended at the threshold, not at the horizon
        }
    }
    // The mirror direction must lie in the lobe: above its level and, seen from the peak, within its ray's extent.
    const dvec2 d = -p;
    const double r0 = glm::length(d);
    bool holdsMirror = lobe.mirrorValue >= lobe.level;
    if (holdsMirror && r0 > 0) {
        const double phi = std::atan2(d.y, d.x);
        const int k = int(std::lround(phi / (2.0 * kPi) * kMirrorLobeRays) + kMirrorLobeRays) % kMirrorLobeRays;
        holdsMirror = r0 <= lobe.extent[size_t(k)] * 1.01 + lobe.step;
    }
    // A "lobe" that valleys end on most rays is a dip among rivals (a matte paper's faint bump at 40 deg: 283 of
    // 360 rays end at a valley, the region 130 deg across), not a highlight.
    lobe.found = holdsMirror && threshold && 2 * valleys < kMirrorLobeRays;
    return lobe;
}

}  // namespace

double MirrorLobe::maskRadius(double phi) const {
    const int K = int(extent.size());
    if (K == 0) return 0;
    double x = phi / (2.0 * kPi) * K;
    x -= K * std::floor(x / K);
    const int k0 = int(std::floor(x)) % K, k1 = (k0 + 1) % K;
    const double t = x - std::floor(x);
    if (valley[size_t(k0)] && valley[size_t(k1)]) return (1 - t) * extent[size_t(k0)] + t * extent[size_t(k1)];
    const int n = t < 0.5 ? k0 : k1;
    if (valley[size_t(n)]) return extent[size_t(n)];
    double most = 0;
    for (int j = -3; j <= 3; ++j) most = std::max(most, extent[size_t(((n + j) % K + K) % K)]);
    return 1.25 * most + 4.0 * step;
}

bool MirrorLobe::inMask(double u, double v) const {
    const dvec2 d(u - peakUV.x, v - peakUV.y);
    return glm::length(d) <= maskRadius(std::atan2(d.y, d.x));
}

void MirrorLobe::box(double& u0, double& u1, double& v0, double& v1) const {
    u0 = u1 = peakUV.x, v0 = v1 = peakUV.y;
    const int K = int(extent.size());
    for (int k = 0; k < K; ++k) {
        const double phi = 2.0 * kPi * k / K;
        const dvec2 q = peakUV + extent[size_t(k)] * dvec2(std::cos(phi), std::sin(phi));
        u0 = std::min(u0, q.x), u1 = std::max(u1, q.x), v0 = std::min(v0, q.y), v1 = std::max(v1, q.y);
    }
}

const MirrorLobe& findMirrorLobe(const render::Scene& scene, double frac) {
    struct Last {
        std::string key;
        render::Scene scene;  // holds a measured table the key names by its address
        MirrorLobe lobe;
    };
    thread_local Last last;
    char fracText[32];
    std::snprintf(fracText, sizeof fracText, "|%.17g", frac);
    std::string key = scene::sceneKey(scene) + fracText;
    if (key != last.key) {
        last.lobe = find(scene, frac);
        last.key = std::move(key);
        last.scene = scene;
    }
    return last.lobe;
}

}  // namespace hilite::measurement
