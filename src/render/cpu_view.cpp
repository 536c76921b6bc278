#include "render/cpu_view.hpp"

#include "core/parallel.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "hilite/render/area_light.hpp"
#include "hilite/render/ltc.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>
#include <vector>

namespace hilite::render {

void measurePixelCpu(const Scene& scene, const PinholeCamera& cam, const MirrorChart& chart, double px, double py,
                     float* out, int rings) {
    // The shader's main() in double: the ray through the sample point, unnormalized so that its
    // length gives cos(gamma) for the pixel's solid angle.
    const double x = (2.0 * px / cam.width - 1.0) * cam.tanHalfX;
    const double y = (2.0 * py / cam.height - 1.0) * cam.tanHalfY;
    const dvec3 d = -cam.back + x * cam.right + y * cam.up;
    const double len = glm::length(d);
    const dvec3 we = -d / len;
    const dvec3 p = cam.position - (cam.position.z / we.z) * we;  // the point seen (point and sphere lights)
    const dvec3 wi = scene.light.distant() ? scene.light.direction() : glm::normalize(scene.light.position() - p);
    // No surface radiance reaches this sample (as in shade.frag; an area light's cap is cut ray by ray instead).
    if (we.z <= 0.0 || (wi.z <= 0.0 && !scene.light.area())) {
        std::fill(out, out + 4, 0.f);
        return;
    }
    if (scene.light.area() && !scene.light.ltc && rings < 1) rings = lightRings(scene);
    const double L = brdf::luminance(
        scene.light.area() ? (scene.light.ltc ? areaRadianceLtc(scene, p, we) : areaRadianceRule(scene, p, we, rings))
                           : surfaceRadiance(scene, cam.position, we));
    const dvec2 uv = chart.coords(we);
    const double cosGamma = 1.0 / len;
    const double pixelArea = (2.0 * cam.tanHalfX / cam.width) * (2.0 * cam.tanHalfY / cam.height);
    const double w = chart.areaPerSolidAngle(we) * cosGamma * cosGamma * cosGamma * pixelArea;
    out[0] = float(L);
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
