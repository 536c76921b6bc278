#include "render/cpu_view.hpp"

#include "core/parallel.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "hilite/render/area_light.hpp"
#include "hilite/render/ltc.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

namespace hilite::render {

namespace {

/// The shader's ray through the sample point: unnormalized d (its length gives cos(gamma) for the pixel's solid
/// angle) and the exitant direction.
struct SampleRay {
    double len;
    dvec3 we;
};
SampleRay sampleRay(const PinholeCamera& cam, double px, double py) {
    const double x = (2.0 * px / cam.width - 1.0) * cam.tanHalfX;
    const double y = (2.0 * py / cam.height - 1.0) * cam.tanHalfY;
    const dvec3 d = -cam.back + x * cam.right + y * cam.up;
    const double len = glm::length(d);
    return {len, -d / len};
}

/// The shade.frag main()'s L in double; none where no surface radiance reaches the sample (the shader writes
/// (0, 0, 0, 0) there; an area light's cap is cut ray by ray instead).
std::optional<double> luminanceAlong(const Scene& scene, const PinholeCamera& cam, const dvec3& we, int rings) {
    if (we.z <= 0.0) return std::nullopt;
    const dvec3 p = cam.position - (cam.position.z / we.z) * we;  // the point seen (point and sphere lights)
    const dvec3 wi = scene.light.distant() ? scene.light.direction() : glm::normalize(scene.light.position() - p);
    if (wi.z <= 0.0 && !scene.light.area()) return std::nullopt;
    if (scene.light.area() && !scene.light.ltc && rings == 0) rings = lightRings(scene);
    return brdf::luminance(
        scene.light.area() ? (scene.light.ltc ? areaRadianceLtc(scene, p, we) : areaRadianceRule(scene, p, we, rings))
                           : surfaceRadiance(scene, cam.position, we));
}

}  // namespace

dvec3 sampleExitant(const PinholeCamera& cam, double px, double py) { return sampleRay(cam, px, py).we; }

double measureLuminanceCpu(const Scene& scene, const PinholeCamera& cam, double px, double py, int rings) {
    return luminanceAlong(scene, cam, sampleRay(cam, px, py).we, rings).value_or(0.0);
}

void measurePixelCpu(const Scene& scene, const PinholeCamera& cam, const MirrorChart& chart, double px, double py,
                     float* out, int rings) {
    const SampleRay r = sampleRay(cam, px, py);
    const std::optional<double> L = luminanceAlong(scene, cam, r.we, rings);
    if (!L) {
        std::fill(out, out + 4, 0.f);
        return;
    }
    const dvec2 uv = chart.coords(r.we);
    const double cosGamma = 1.0 / r.len;
    const double pixelArea = (2.0 * cam.tanHalfX / cam.width) * (2.0 * cam.tanHalfY / cam.height);
    const double w = chart.areaPerSolidAngle(r.we) * cosGamma * cosGamma * cosGamma * pixelArea;
    out[0] = float(*L);
    out[1] = float(uv.x);
    out[2] = float(uv.y);
    out[3] = float(w);
}

void renderMeasureCpu(const Scene& scene, const PinholeCamera& camera, ImageF& image, dvec2 jitter,
                      const PixelRect& crop, int threads) {
    const PixelRect r = crop.empty() ? PixelRect{0, 0, camera.width, camera.height} : crop;
    if (r.x < 0 || r.y < 0 || r.x + r.width > camera.width || r.y + r.height > camera.height)
        throw std::logic_error("renderMeasureCpu: crop outside the image");
    if (image.width != r.width || image.height != r.height || image.channels != 4) image = ImageF(r.width, r.height, 4);
    const MirrorChart chart = scene.light.chart();
    const int rings = lightRings(scene);  // the GL rule's (0 for a point or directional light)
    int n = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    // Below ~16 rows per thread, starting a thread costs more than its rows (~50 us).
    n = std::clamp(r.height / 16, 1, n);
    parallelFor(  // interleaved rows: the lobe's cost is uneven
        r.height,
        [&](int row) {
            for (int col = 0; col < r.width; ++col)
                measurePixelCpu(scene, camera, chart, r.x + col + 0.5 + jitter.x, r.y + row + 0.5 + jitter.y,
                                image.pixel(col, row), rings);
        },
        n);
}

}  // namespace hilite::render
