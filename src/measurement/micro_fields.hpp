#pragma once
// The row fields of a bump-field measurement (explicit micro-geometry).

#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/result.hpp"
#include "hilite/micro/bump_field.hpp"
#include "hilite/render/scene.hpp"

#include <optional>

namespace hilite::measurement {

/// The bump period and samples, the analytic twin's shape (the CPU reference of the same NDF and Fresnel with
/// implicit G under a point-like light) and the realised slope statistics; the filter used (supersample or
/// moments: the render's resolved --bump-filter, at `width` x `height`).
MicroFields microFields(const render::Scene& s, const Measurement& m, double threshold, int width, int height);

/// With --prefilter-check, where supersampling runs (the centre pixel needs <= 64 patches per axis): the
/// moments prefilter and the next seed rendered in the same frame (measurement/prefilter_check.hpp). None
/// otherwise.
std::optional<PrefilterFields> prefilterFields(render::Renderer& renderer, const render::Scene& s,
                                               const MeasureSetup& setup, const Measurement& m);

/// The realised slope statistics of a bump field (computed once per field and cached).
const micro::SlopeStats& realisedSlopes(const micro::BumpSpec& spec);

}  // namespace hilite::measurement
