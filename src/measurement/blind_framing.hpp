#pragma once
// Measuring a highlight without a CPU twin (a .brdf file: hilite cannot run its GLSL on the CPU).
//
// Framing. The built-in search starts from the twin's half-width, because a narrow lobe (Phong n = 1e6 is
// 0.07 deg wide) falls between the pixel centres of any coarse render wide enough to find it. Without a
// twin the search starts wide (160 deg, centred on the mirror direction) and, while a coarse render shows
// nothing at all (peak 0), zooms 8x about the mirror direction, where reflection and microfacet lobes
// peak, down to 1e-4 deg; it gives up there and says so (framingNote). Once something shows, it re-aims
// and zooms on the region exactly as the built-in search does (measurement/framing.hpp).
// What it can miss: a lobe narrower than a coarse pixel away from the mirror direction (the zoom never
// passes over it), and a spike narrower than a coarse pixel on top of a wider lobe (the region of the
// wider lobe is framed; the final render shows the spike only if it resolves it).
//
// Error estimate. The reference measurement (the twin) is unavailable, so the final frame is measured
// again at half the size: |x(N) - x(N/2)| per field is the error estimate. For a measurement whose error
// falls at least as fast as 1/N it bounds the error at N (sub-pixel boundaries converge as 1/N^2, where
// it overestimates about 3x).

#include "hilite/measurement/measure_scene.hpp"

namespace hilite::measurement {

/// \brief Measures the highlight in GL with blind framing (or fixed framing when setup.fovDeg > 0), plus
/// the half-size measurement of the same frame in Measurement::halfResolution.
Measurement measureBlind(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup);

}  // namespace hilite::measurement
