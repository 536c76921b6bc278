#pragma once
// Diagnoses the measurement can only make knowing the scene: the double twin knows the lobe, the pixels do
// not. A delta lobe (roughness 0) is a `mirror`, not `no_highlight`; a lobe that falls between the pixel
// centres of a fixed frame is `under_resolved`, not `no_highlight`; a lobe narrower than float32 directions
// resolve is `effectively_mirror` in GL; a lobe that grows without bound towards the horizon (G = 1) is
// `unbounded_at_horizon`: its measured peak is wherever the sampling stopped.

#include "hilite/analysis/highlight.hpp"
#include "hilite/render/scene.hpp"

namespace hilite::measurement {

/// The spacing of float32 directions near a unit vector: the components of a unit vector near 1 are
/// rounded to 2^-24 (half an ulp of 1), so the shader knows each exitant direction, and the chart
/// coordinates it writes, only to about this many radians.
constexpr double kFloatDirectionStep = 5.9604644775390625e-8;  // 2^-24

/// Below this minor half-width (rad) GL flags `effectively_mirror`: 8 float direction steps, as
/// `under_resolved` asks 8 pixels across. Measured by `hilite_hard_report sweep` (GGX and Beckmann,
/// roughness 1e-7 to 5e-6, theta_i 0, 45, 80; GL 512^2 automatic framing against the double reference,
/// docs/hard_cases.md): all 21 lobes at or above 8 steps agree within the project's GL-vs-reference
/// tolerance (semi-axes 0.7% < 1%, aspect 0.0048 < 0.005); below it 15 of 21 do not, by up to 52%. Normal
/// incidence is the exception the flag does not try to see: with wi = n the shader's arithmetic stays exact
/// and even 2 steps measure within 4e-4.
constexpr double kEffectivelyMirrorHalfWidth = 8.0 * kFloatDirectionStep;  // 4.8e-7 rad
/// A sphere or disk light's rule whose radiance error (render::lightRule, relative to the lobe's peak) exceeds this
/// is `light_undersampled`: near the contour a 1% error of the peak moves it by about 1% of the lobe's width.
constexpr double kLightRuleFlag = 1e-2;

/// The twin's lobe about the mirror direction.
struct LobeWidths {
    double peak = 0;   ///< lobe value at the mirror direction (0: no lobe there)
    double minor = 0;  ///< narrowest half-width (rad) at `threshold` of `peak`
    double major = 0;  ///< widest half-width (rad)
};

/// Half-widths of the twin's lobe along 16 azimuths about the mirror direction. An azimuth on which the
/// horizon comes before the threshold does not count: there the horizon, not the lobe, ends the region.
LobeWidths twinLobeWidths(const render::Scene& scene, double threshold);

/// Whether the twin's lobe grows without bound towards the horizon below the measured peak: the peak lies
/// within 0.05 (cos theta_o) of the horizon and, on its azimuth, the lobe rises more than 100-fold between
/// 1e-3 and 1e-6 of the peak's height (as 1 / cos theta_o: 1000-fold; a bounded lobe: about 1-fold).
bool unboundedAtHorizon(const render::Scene& scene, const analysis::Shape& shape);

/// Whether any light reaches the plane (irradiance > 0 from above the horizon).
bool lightReaches(const render::Scene& scene);

/// Who measured: GL pixels (float32), CPU pixels (double), or the double reference (no pixels).
enum class Path { Gl, Cpu, Reference };

/// Adds the diagnoses above to a measurement of `scene` by `path` (replacing no_highlight where the lobe
/// exists). `threshold`: the measurement's fraction of the peak.
/// `widths`: twinLobeWidths(scene, threshold) when the caller has it already (it costs ~1000 twin evaluations).
void diagnose(const render::Scene& scene, double threshold, Path path, analysis::Shape& shape,
              const LobeWidths* widths = nullptr);

}  // namespace hilite::measurement
