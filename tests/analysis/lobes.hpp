#pragma once
// Test lobes for the measurement: tiny CPU versions of the BRDFs of ../shared/notes/measurement.md
// (kept here, in the tests, so that measure never depends on brdf), and a CPU twin of the GL
// measurement view that turns a lobe into the (L, u, v, w) image measureImage reads.

#include "hilite/analysis/highlight.hpp"

#include "hilite/core/chart.hpp"
#include "hilite/core/image.hpp"
#include "hilite/core/math.hpp"

#include <functional>

namespace hilite::test {

/// A lobe as a function of the exitant direction we (unit, local frame, n = +z).
using DirLobe = std::function<double(const dvec3& we)>;

/// D_GGX(n.h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)
double D_GGX(double NoH, double alpha);
/// Lambda_GGX(theta) = (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2
double Lambda_GGX(double cosTheta, double alpha);

/// Microfacet lobe shaped by the NDF alone: L = D_GGX(n.h), h = normalize(wi + we).
DirLobe ggxNdfLobe(const MirrorChart& chart, double alpha);
/// Full specular microfacet BRDF, F = 1: D G2 / (4 cos(theta_i) cos(theta_o)), height-correlated Smith G2.
DirLobe ggxBrdfLobe(const MirrorChart& chart, double alpha);
/// Phong reflection lobe: max(0, we.wr)^n.
DirLobe phongLobe(const MirrorChart& chart, double n);

/// The lobe on the chart: L(direction(u, v)) above the horizon, 0 below.
analysis::LobeFunction chartLobe(const MirrorChart& chart, DirLobe lobe);

/// The measurement view rendered on the CPU: PinholeCamera::measurement(chart, center, fov, W, H);
/// per pixel we = -ray through its centre; below the horizon (0,0,0,0), else
/// (L, u, v, areaPerSolidAngle * pixelSolidAngle). `jitter` moves every sample point (pixels; supersampling).
ImageF renderView(const MirrorChart& chart, const DirLobe& lobe, const dvec3& center, double fovDeg, int width,
                  int height, dvec2 jitter = dvec2(0.0));

}  // namespace hilite::test
