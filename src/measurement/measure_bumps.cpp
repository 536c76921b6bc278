#include "measurement/measure_bumps.hpp"
#include "render/renderer.hpp"

#include <chrono>

namespace hilite::measurement {

render::Scene analyticScene(const render::Scene& bumpy) {
    render::Scene s = bumpy;
    s.surface.bumps = false;
    s.brdf.geometry = brdf::Geometry::Implicit;  // the bump render's G = cos_i cos_o (shaders/micro.glsl)
    return s;
}

Measurement measureBumps(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup) {
    Measurement m = measureGl(renderer, analyticScene(scene), setup);  // the frame only
    const PinholeCamera cam = measurementCamera(scene, m.center, m.fovDeg, setup.width, setup.height);
    thread_local ImageF img;
    auto t0 = std::chrono::steady_clock::now();
    renderer.render(scene, cam, render::Output::Measure, img);
    m.render_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++m.renders;
    t0 = std::chrono::steady_clock::now();
    m.shape = analysis::measureImage(img.data.data(), img.width, img.height, setup.options);
    m.measure_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return m;
}

Measurement measureAny(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup) {
    return scene.surface.bumps ? measureBumps(renderer, scene, setup) : measureGl(renderer, scene, setup);
}

}  // namespace hilite::measurement
