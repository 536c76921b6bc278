#include "measurement/blind_framing.hpp"
#include "render/renderer.hpp"

#include "measurement/framing.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace hilite::measurement {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// Each coarse render that shows nothing narrows the view this much about the mirror direction: 8x is
/// 8 steps from 160 to 1e-4 deg, and a lobe found at one step spans under 8 coarse pixels (64 across), so
/// the next reframe still sees its shape.
constexpr double kZoom = 8.0;

std::string degrees(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

/// Renders into `img` and counts the render.
void renderInto(render::Renderer& renderer, const render::Scene& scene, const PinholeCamera& cam, ImageF& img,
                Measurement& m) {
    const auto t0 = Clock::now();
    renderer.render(scene, cam, render::Output::Measure, img);
    m.render_ms += msSince(t0);
    ++m.renders;
}

/// Searches the frame with coarse renders only; returns why it gave up ("" when it found the region).
std::string searchBlind(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup, Frame& frame,
                        Measurement& m) {
    const dvec3 mirror = liftAboveHorizon(scene.light.chart().wr());
    thread_local ImageF coarse;
    for (int i = 0; i < setup.maxBlindRenders; ++i) {
        const PinholeCamera cam =
            measurementCamera(scene, frame.center, frame.fovDeg, setup.coarseSize, setup.coarseSize);
        renderInto(renderer, scene, cam, coarse, m);
        const auto t0 = Clock::now();
        const RegionBox box = regionBox(coarse, setup.options.threshold);
        if (box.empty()) {
            // Nothing above 0 anywhere: a lobe narrower than a coarse pixel may sit between the pixel
            // centres. Zoom about the mirror direction.
            m.measure_ms += msSince(t0);
            if (frame.fovDeg <= kMinFovDeg * (1 + 1e-9))
                return "no highlight found: zoomed toward the mirror direction down to a " + degrees(frame.fovDeg) +
                       " deg field of view (" + std::to_string(m.renders) + " renders)";
            const double tanHalf = std::tan(deg2rad(0.5 * frame.fovDeg)) / kZoom;
            frame = {mirror, std::max(kMinFovDeg, 2.0 * rad2deg(std::atan(tanHalf)))};
            continue;
        }
        const bool good = reframe(cam, box, setup.fill, frame);
        m.measure_ms += msSince(t0);
        if (good) return "";
    }
    return "";  // still reframing: the final render's flags (clipped, covers_frame) say what is left
}

}  // namespace

Measurement measureBlind(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup) {
    Measurement m;
    m.framing = setup.fovDeg > 0 ? "fixed" : "blind";
    Frame frame{liftAboveHorizon(scene.light.chart().wr()), setup.fovDeg > 0 ? setup.fovDeg : kMaxFovDeg};
    if (setup.fovDeg <= 0) {
        if (!(scene.light.direction().z > 0)) m.framingNote = "no light on the plane: it is at or below the horizon";
        else m.framingNote = searchBlind(renderer, scene, setup, frame, m);
    }
    // Final render, then the same frame at half the size for the error estimate.
    thread_local ImageF img, half;
    const PinholeCamera cam = measurementCamera(scene, frame.center, frame.fovDeg, setup.width, setup.height);
    renderInto(renderer, scene, cam, img, m);
    auto t0 = Clock::now();
    m.shape = analysis::measureImage(img.data.data(), img.width, img.height, setup.options);
    m.measure_ms += msSince(t0);
    m.halfWidth = std::max(1, (setup.width + 1) / 2);
    m.halfHeight = std::max(1, (setup.height + 1) / 2);
    const PinholeCamera halfCam = measurementCamera(scene, frame.center, frame.fovDeg, m.halfWidth, m.halfHeight);
    renderInto(renderer, scene, halfCam, half, m);
    t0 = Clock::now();
    m.halfResolution = analysis::measureImage(half.data.data(), half.width, half.height, setup.options);
    m.measure_ms += msSince(t0);
    m.fovDeg = frame.fovDeg;
    m.center = frame.center;
    return m;
}

}  // namespace hilite::measurement
