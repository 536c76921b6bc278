#pragma once
// The highlight of explicit micro-geometry: framed like the analytic BRDF it should converge to
// (the same NDF and Fresnel, G = 1), then rendered once with the bump field and measured like any render.

#include "hilite/measurement/measure_scene.hpp"

namespace hilite::measurement {

/// The smooth twin of a bump scene: the same material, flat, implicit G (the BRDF the bumps converge to).
render::Scene analyticScene(const render::Scene& bumpy);
/// Framing by the analytic scene's automatic framing (or the fixed field of view), final render with bumps.
Measurement measureBumps(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup);
/// measureBumps for a scene with bumps, measureGl otherwise.
Measurement measureAny(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup);

}  // namespace hilite::measurement
