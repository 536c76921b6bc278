#include "experiments/measure_scene.hpp"

#include "brdf/evaluate.hpp"
#include "experiments/peak_frame.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hilite::experiments {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// Directions just above the horizon make the camera sit on the plane; keep it 1e-6 rad above.
dvec3 liftAboveHorizon(dvec3 c) {
    if (c.z < 1e-6) c = glm::normalize(dvec3(c.x, c.y, 1e-6));
    return c;
}

constexpr double kMaxFovDeg = 160.0;   // a pinhole image beyond ~160 deg spends its pixels on the rim
constexpr double kMinFovDeg = 1e-4;    // below this float directions (6e-8 rad) resolve < 30 steps a frame

/// Pixel bounding box of the region (L >= frac * peak) in an (L, u, v, w) image.
struct RegionBox {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    double peak = 0;
    bool empty() const { return x1 < 0; }
};

RegionBox regionBox(const ImageF& img, double frac) {
    RegionBox b;
    for (size_t i = 0; i < img.data.size(); i += 4) b.peak = std::max(b.peak, double(img.data[i]));
    if (!(b.peak > 0)) return b;
    const double t = frac * b.peak;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.pixel(x, y)[0] >= t) {
                b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x);
                b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
            }
    return b;
}

struct Frame {
    dvec3 center;
    double fovDeg;
};

/// Re-aims the frame on the region's box and zooms so its half-extent is `fill` of the half-frame.
/// Returns true when the frame was already good (box within [0.5 fill, 1] of the frame, not on the border).
bool reframe(const PinholeCamera& cam, const RegionBox& box, double fill, Frame& f) {
    const bool onBorder = box.x0 == 0 || box.y0 == 0 || box.x1 == cam.width - 1 || box.y1 == cam.height - 1;
    // Box centre and half-extent in image-plane units (unit focal distance), pixel edges included.
    const double cx = 0.5 * (box.x0 + box.x1 + 1), cy = 0.5 * (box.y0 + box.y1 + 1);
    const double hx = 0.5 * (box.x1 - box.x0 + 1) * 2.0 * cam.tanHalfX / cam.width;
    const double hy = 0.5 * (box.y1 - box.y0 + 1) * 2.0 * cam.tanHalfY / cam.height;
    const double half = std::max(hx / cam.tanHalfX, hy / cam.tanHalfY);  // fraction of the half-frame
    if (onBorder) {
        f.fovDeg = std::min(kMaxFovDeg, 2.0 * rad2deg(std::atan(2.0 * cam.tanHalfX)));
        f.center = liftAboveHorizon(-cam.ray(cx, cy));
        return false;
    }
    const bool good = half >= 0.5 * fill && half <= 1.0;
    f.center = liftAboveHorizon(-cam.ray(cx, cy));
    const double tanHalf = std::max(hx, hy * cam.tanHalfX / cam.tanHalfY) / fill;
    f.fovDeg = std::clamp(2.0 * rad2deg(std::atan(tanHalf)), kMinFovDeg, kMaxFovDeg);
    return good;
}

}  // namespace

PinholeCamera measurementCamera(const render::Scene& scene, const dvec3& center, double fovDeg, int w, int h) {
    return PinholeCamera::measurementFrom(scene.light.chart(), render::eyePosition(scene), liftAboveHorizon(center),
                                          fovDeg, w, h);
}

measure::LobeFunction twinLobe(const render::Scene& scene) {
    const MirrorChart chart = scene.light.chart();
    const dvec3 eye = render::eyePosition(scene);
    measure::LobeFunction f;
    f.lobe = [=](double u, double v) {
        const dvec3 we = chart.direction(u, v);
        if (we.z <= 0.0) return 0.0;
        return brdf::luminance(render::surfaceRadiance(scene, eye, we));
    };
    f.visible = [=](double u, double v) { return chart.direction(u, v).z > 0.0; };
    return f;
}

double twinHalfWidth(const render::Scene& scene, double threshold) {
    const measure::LobeFunction f = twinLobe(scene);
    const double l0 = f.lobe(0, 0);
    if (!(l0 > 0)) return deg2rad(30.0);
    double widest = 0;
    for (auto [du, dv] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
        double lo = 0, hi = 1e-9;
        while (hi < kPi / 2 && f.lobe(hi * du, hi * dv) >= threshold * l0) lo = hi, hi *= 2;
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            (f.lobe(mid * du, mid * dv) >= threshold * l0 ? lo : hi) = mid;
        }
        widest = std::max(widest, hi);
    }
    return widest;
}

Measurement measureGl(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup) {
    // A peak far from the mirror direction (retroreflection): framed and measured about the peak.
    if (const auto framed = frameAboutPeak(scene, setup.options.threshold)) return measureGl(renderer, *framed, setup);
    Measurement m;
    Frame frame{liftAboveHorizon(scene.light.chart().wr()), setup.fovDeg};
    // Per-thread buffers: reused across calls, so the readback never reallocates (4 MB at 512x512).
    thread_local ImageF coarse, img;
    if (setup.fovDeg <= 0) {
        // Seed from the twin's half-width, then let coarse renders correct the aim (off-specular shift,
        // anisotropy, horizon) until the region sits inside the frame and fills most of it.
        const double r = twinHalfWidth(scene, setup.options.threshold);
        frame.fovDeg = std::clamp(2.0 * rad2deg(std::atan(std::tan(std::min(r, 1.3)) / setup.fill)), kMinFovDeg,
                                  kMaxFovDeg);
        while (m.renders < setup.maxRenders - 1) {
            // The aiming renders keep the final frame's shape, so what fits them fits the final render.
            const double longest = std::max(setup.width, setup.height);
            const int cw = std::max(8, int(std::lround(setup.coarseSize * setup.width / longest)));
            const int ch = std::max(8, int(std::lround(setup.coarseSize * setup.height / longest)));
            const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, cw, ch);
            auto t0 = Clock::now();
            renderer.render(scene, cam, render::Output::Measure, coarse);
            m.render_ms += msSince(t0);
            ++m.renders;
            t0 = Clock::now();
            const RegionBox box = regionBox(coarse, setup.options.threshold);
            const bool good = box.empty() || reframe(cam, box, setup.fill, frame);
            m.measure_ms += msSince(t0);
            if (good) break;
        }
    }
    const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, setup.width, setup.height);
    auto t0 = Clock::now();
    renderer.render(scene, cam, render::Output::Measure, img);
    m.render_ms += msSince(t0);
    ++m.renders;
    t0 = Clock::now();
    m.shape = measure::measureImage(img.data.data(), img.width, img.height, setup.options);
    m.measure_ms += msSince(t0);
    m.fovDeg = frame.fovDeg;
    m.center = frame.center;
    return m;
}

Measurement measureReference(const render::Scene& scene, const measure::Options& options) {
    if (const auto framed = frameAboutPeak(scene, options.threshold)) return measureReference(*framed, options);
    Measurement m;
    const auto t0 = Clock::now();
    const double r = twinHalfWidth(scene, options.threshold);
    m.shape = measure::measureReference(twinLobe(scene), options, std::min(4.0 * r, kPi / 2));
    m.measure_ms = msSince(t0);
    return m;
}

}  // namespace hilite::experiments
