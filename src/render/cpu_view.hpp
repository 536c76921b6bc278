#pragma once
// The measurement view rendered on the CPU by the double-precision twin: for every pixel, the exitant
// direction of its camera ray, render::surfaceRadiance (brdf::evaluate in double; a sphere or disk light by the
// GL's rule, render::areaRadianceRule) and the chart
// coordinates, exactly the channels shaders/shade.frag writes for Output::Measure. The GL path's
// float shader against this path is one of the accuracy knobs; both feed analysis::measureImage.

#include "hilite/core/camera.hpp"
#include "hilite/core/image.hpp"
#include "hilite/render/scene.hpp"

namespace hilite::render {

/// \brief Renders (L, u, v, w) per pixel in double (stored as float), on `threads` threads.
/// \param jitter sample offset from each pixel centre, in pixels (the shader's uJitter).
/// \param crop a non-empty crop renders only those pixels: `image` is then crop.width x crop.height.
/// \param threads 0: every core (std::thread::hardware_concurrency).
/// Pixels that see no surface (we.z <= 0) or whose light is below the plane are (0, 0, 0, 0), as in GL.
void renderMeasureCpu(const Scene& scene, const PinholeCamera& camera, ImageF& image, dvec2 jitter = dvec2(0.0),
                      const PixelRect& crop = {}, int threads = 0);

/// The exitant direction (from the surface towards the eye) of the ray through a sample point, as the shader's.
dvec3 sampleExitant(const PinholeCamera& camera, double px, double py);

/// The L of one sample point in double (measurePixelCpu's first channel before rounding to float): for sums of
/// small differences between twins, such as a measured table against its half-resolution copies.
double measureLuminanceCpu(const Scene& scene, const PinholeCamera& camera, double px, double py, int rings = 0);

/// The (L, u, v, w) of one sample point (px, py) in pixel units (pixel centres at i + 0.5); `rings`: a sphere or
/// disk light's rule (render::lightRings: the GL rule's, so that both paths integrate the light alike).
void measurePixelCpu(const Scene& scene, const PinholeCamera& camera, const MirrorChart& chart, double px, double py,
                     float* out, int rings = 0);

}  // namespace hilite::render
