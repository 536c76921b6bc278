#include "experiments/measure_scene.hpp"

#include "brdf/evaluate.hpp"
#include "experiments/blind_framing.hpp"
#include "experiments/framing.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hilite::experiments {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

PinholeCamera measurementCamera(const render::Scene& scene, const dvec3& center, double fovDeg, int w, int h) {
    return PinholeCamera::measurementFrom(scene.light.chart(), render::eyePosition(scene), liftAboveHorizon(center),
                                          fovDeg, w, h);
}

measure::LobeFunction twinLobe(const render::Scene& scene) {
    render::requireTwin(scene, "the CPU lobe");
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
    render::requireTwin(scene, "the lobe width seed");
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
    if (!render::hasTwin(scene)) return measureBlind(renderer, scene, setup);
    Measurement m;
    m.framing = setup.fovDeg > 0 ? "fixed" : "automatic";
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
            const PinholeCamera cam =
                measurementCamera(scene, frame.center, frame.fovDeg, setup.coarseSize, setup.coarseSize);
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
    render::requireTwin(scene, "--reference");
    Measurement m;
    m.framing = "reference";
    const auto t0 = Clock::now();
    const double r = twinHalfWidth(scene, options.threshold);
    m.shape = measure::measureReference(twinLobe(scene), options, std::min(4.0 * r, kPi / 2));
    m.measure_ms = msSince(t0);
    return m;
}

}  // namespace hilite::experiments
