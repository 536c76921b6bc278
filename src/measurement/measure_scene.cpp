#include "measurement/measure_scene.hpp"

#include "measurement/measure_bumps.hpp"

#include "brdf/evaluate.hpp"
#include "core/error.hpp"
#include "measurement/diagnose.hpp"
#include "measure/supersample.hpp"
#include "render/cpu_view.hpp"
#include "measurement/peak_frame.hpp"
#include "measurement/blind_framing.hpp"
#include "measurement/framing.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace hilite::measurement {

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

std::array<double, 4> twinRadii(const render::Scene& scene, double threshold) {
    render::requireTwin(scene, "the lobe width seed");
    const measure::LobeFunction f = twinLobe(scene);
    const double l0 = f.lobe(0, 0);
    if (!(l0 > 0)) return {deg2rad(30.0), deg2rad(30.0), deg2rad(30.0), deg2rad(30.0)};
    std::array<double, 4> radii{};
    const double du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
        double lo = 0, hi = 1e-9;
        while (hi < kPi / 2 && f.lobe(hi * du[k], hi * dv[k]) >= threshold * l0) lo = hi, hi *= 2;
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            (f.lobe(mid * du[k], mid * dv[k]) >= threshold * l0 ? lo : hi) = mid;
        }
        radii[size_t(k)] = hi;
    }
    return radii;
}

double twinHalfWidth(const render::Scene& scene, double threshold) {
    const auto r = twinRadii(scene, threshold);
    return *std::max_element(r.begin(), r.end());
}

namespace {

/// Draws one render of the measurement view: camera, sub-pixel jitter, crop (empty: the whole frame).
using ViewFn = std::function<void(const PinholeCamera&, dvec2, const PixelRect&, ImageF&)>;

/// The last aiming render and its region's box, from which the final frame was set.
struct Aim {
    PinholeCamera camera;
    RegionBox box;
    bool good = false;  ///< the loop ended on a frame it accepted (else: no box to crop to)
};

/// Automatic framing: seed the frame from the twin's half-width, then let coarse renders correct the
/// aim (off-specular shift, anisotropy, horizon) until the region sits inside the frame and fills most of it.
Aim aimFrame(const ViewFn& view, const render::Scene& scene, const MeasureSetup& setup, Frame& frame, Measurement& m) {
    thread_local ImageF coarse;  // reused across calls: no allocation per measurement
    const double r = twinHalfWidth(scene, setup.options.threshold);
    frame.fovDeg =
        std::clamp(2.0 * rad2deg(std::atan(std::tan(std::min(r, 1.3)) / setup.fill)), kMinFovDeg, kMaxFovDeg);
    Aim aim;
    while (m.renders < setup.maxRenders - 1) {
        // The aiming renders keep the final frame's shape, so what fits them fits the final render.
        const double longest = std::max(setup.width, setup.height);
        const int cw = std::max(8, int(std::lround(setup.coarseSize * setup.width / longest)));
        const int ch = std::max(8, int(std::lround(setup.coarseSize * setup.height / longest)));
        aim.camera = measurementCamera(scene, frame.center, frame.fovDeg, cw, ch);
        auto t0 = Clock::now();
        view(aim.camera, dvec2(0.0), PixelRect{}, coarse);
        m.render_ms += msSince(t0);
        ++m.renders;
        t0 = Clock::now();
        aim.box = regionBox(coarse, setup.options.threshold);
        aim.good = !aim.box.empty() && reframe(aim.camera, aim.box, setup.fill, frame);
        m.measure_ms += msSince(t0);
        if (aim.good || aim.box.empty()) break;
    }
    return aim;
}

/// The pixels of the final frame that can hold the region: the aiming render's box grown by 1.5 of its
/// pixels (a pixel is in by its centre, so the region may reach almost a pixel past the box, and the
/// aim moved by up to half a pixel) plus 2 final pixels (the contour's outer ring and one more), mapped
/// into the final camera (same eye: a homography, so the box's corners bound it). Empty: the whole frame.
PixelRect cropOf(const Aim& aim, const PinholeCamera& fine) {
    const double m = 1.5;
    double x0 = fine.width, y0 = fine.height, x1 = 0, y1 = 0;
    for (double cx : {aim.box.x0 - m, aim.box.x1 + 1 + m})
        for (double cy : {aim.box.y0 - m, aim.box.y1 + 1 + m}) {
            double nx = 0, ny = 0;
            if (!fine.project(aim.camera.ray(cx, cy), nx, ny)) return {};  // behind the final camera: no crop
            const double px = 0.5 * (nx + 1.0) * fine.width, py = 0.5 * (ny + 1.0) * fine.height;
            x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
        }
    const int ix0 = std::max(0, int(std::floor(x0)) - 2), iy0 = std::max(0, int(std::floor(y0)) - 2);
    const int ix1 = std::min(fine.width, int(std::ceil(x1)) + 2), iy1 = std::min(fine.height, int(std::ceil(y1)) + 2);
    if (ix1 - ix0 < 3 || iy1 - iy0 < 3) return {};  // too small to trust: the whole frame
    if (ix0 == 0 && iy0 == 0 && ix1 == fine.width && iy1 == fine.height) return {};
    return {ix0, iy0, ix1 - ix0, iy1 - iy0};
}

/// The final render(s) of the frame and their analysis: one render and measureImage, or n x n jittered
/// renders combined by the Supersampler.
measure::Shape analyse(const ViewFn& view, const PinholeCamera& cam, const PixelRect& crop, const MeasureSetup& setup,
                       Measurement& m) {
    thread_local ImageF img;  // reused: the readback never reallocates (4 MB at 512x512)
    const int n = setup.supersample;
    m.shadedPixels = crop.empty() ? long(cam.width) * cam.height : long(crop.width) * crop.height;
    if (n <= 1) {
        auto t0 = Clock::now();
        view(cam, dvec2(0.0), crop, img);
        m.render_ms += msSince(t0);
        ++m.renders;
        t0 = Clock::now();
        measure::Shape shape = measure::measureImage(img.data.data(), img.width, img.height, setup.options);
        m.measure_ms += msSince(t0);
        return shape;
    }
    const int w = crop.empty() ? cam.width : crop.width, h = crop.empty() ? cam.height : crop.height;
    measure::Supersampler ss(w, h, n * n);
    for (const dvec2 jitter : measure::jitterGrid(n)) {
        auto t0 = Clock::now();
        view(cam, jitter, crop, img);
        m.render_ms += msSince(t0);
        ++m.renders;
        t0 = Clock::now();
        ss.add(img.data.data());
        m.measure_ms += msSince(t0);
    }
    const auto t0 = Clock::now();
    measure::Shape shape = ss.measure(setup.options);
    m.measure_ms += msSince(t0);
    return shape;
}

/// Whether the aiming render resolved the lobe well enough to crop to it: at least 2 of its pixels across
/// the twin's minor axis. A thinner lobe falls between the aiming render's pixel centres in places, so its
/// box can miss whole stretches of the region (measured: anisotropic Beckmann 1e-4 x 1 at 45 deg, 256^2,
/// 1.4 aiming pixels across: the crop kept a 5.0 deg piece of a region that runs past the frame's edge, and
/// hid the `clipped` flag).
bool aimResolves(const LobeWidths& widths, const MeasureSetup& setup, const Frame& frame) {
    const double minor = widths.minor;
    const double pitch = 2.0 * std::tan(deg2rad(frame.fovDeg) / 2) / setup.coarseSize;  // rad per aiming pixel
    return !(minor > 0) || 2.0 * minor >= 2.0 * pitch;
}

Measurement measureWith(const ViewFn& view, Path path, const render::Scene& scene, const MeasureSetup& setup) {
    if (setup.supersample < 1 || setup.supersample > kMaxSupersample)
        throw InputError("--supersample: must be a whole number in [1, " + std::to_string(kMaxSupersample) +
                         "] (got " + std::to_string(setup.supersample) + ")");
    Measurement m;
    m.framing = setup.fovDeg > 0 ? "fixed" : "automatic";
    Frame frame{liftAboveHorizon(scene.light.chart().wr()), setup.fovDeg};
    Aim aim;
    if (setup.fovDeg <= 0) aim = aimFrame(view, scene, setup, frame, m);
    const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, setup.width, setup.height);
    // The twin's widths: for the crop's decision and the diagnoses (computed once: ~1000 twin evaluations).
    const LobeWidths widths = twinLobeWidths(scene, setup.options.threshold);
    const PixelRect crop = setup.crop && aim.good && aimResolves(widths, setup, frame) ? cropOf(aim, cam) : PixelRect{};
    m.shape = analyse(view, cam, crop, setup, m);
    // The region reached the crop's edge: the crop was too tight, not the frame. Measure the whole frame.
    if (!crop.empty() && m.shape.has(measure::Flag::Clipped)) m.shape = analyse(view, cam, PixelRect{}, setup, m);
    diagnose(scene, setup.options.threshold, path, m.shape, &widths);  // mirror, sub-pixel lobes, float limits
    m.fovDeg = frame.fovDeg;
    m.center = frame.center;
    return m;
}

}  // namespace


Measurement measureGl(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup) {
    // No CPU twin (a .brdf file): framed from coarse renders alone, error from resolution convergence.
    if (!render::hasTwin(scene)) return measureBlind(renderer, scene, setup);
    // A peak far from the mirror direction (retroreflection): framed and measured about the peak.
    if (const auto framed = frameAboutPeak(scene, setup.options.threshold)) return measureGl(renderer, *framed, setup);
    return measureWith(
        [&](const PinholeCamera& cam, dvec2 jitter, const PixelRect& crop, ImageF& img) {
            renderer.render(scene, cam, render::Output::Measure, img, jitter, crop);
        },
        Path::Gl, scene, setup);
}

Measurement measureCpu(const render::Scene& scene, const MeasureSetup& setup) {
    if (const auto framed = frameAboutPeak(scene, setup.options.threshold)) return measureCpu(*framed, setup);
    return measureWith(
        [&](const PinholeCamera& cam, dvec2 jitter, const PixelRect& crop, ImageF& img) {
            render::renderMeasureCpu(scene, cam, img, jitter, crop, setup.threads);
        },
        Path::Cpu, scene, setup);
}

Measurement measure(render::Renderer* renderer, const render::Scene& scene, const MeasureSetup& setup) {
    if (setup.cpu) return measureCpu(scene, setup);
    if (!renderer) throw std::logic_error("measurement::measure: the GL path needs a renderer");
    return measureAny(*renderer, scene, setup);  // bump fields go through measureBumps
}

Measurement measureReference(const render::Scene& scene, const measure::Options& options) {
    render::requireTwin(scene, "--reference");
    if (const auto framed = frameAboutPeak(scene, options.threshold)) return measureReference(*framed, options);
    Measurement m;
    m.framing = "reference";
    const auto t0 = Clock::now();
    const double r = twinHalfWidth(scene, options.threshold);
    m.shape = measure::measureReference(twinLobe(scene), options, std::min(4.0 * r, kPi / 2));
    diagnose(scene, options.threshold, Path::Reference, m.shape);
    m.measure_ms = msSince(t0);
    return m;
}

}  // namespace hilite::measurement
