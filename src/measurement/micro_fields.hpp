#pragma once
// The row fields of a bump-field measurement (explicit micro-geometry).

#include "hilite/measurement/measure_scene.hpp"
#include "hilite/micro/bump_field.hpp"
#include "hilite/render/scene.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::measurement {

/// log2_bump_period_px, bump_samples_center, the analytic twin's shape (analytic_aspect, _major_deg,
/// _minor_deg: the CPU reference of the same NDF and Fresnel with implicit G under a point-like light), the
/// differences, and the realised slope statistics (slope_rms, slope_ks).
/// bump_filter_used: supersample or moments (the render's resolved --bump-filter, at `width` x `height`).
void addMicroFields(nlohmann::json& row, const render::Scene& s, const Measurement& m, double threshold, int width,
                    int height);

/// With --prefilter-check, where supersampling runs (the centre pixel needs <= 64 patches per axis): the
/// moments prefilter and the next seed rendered in the same frame (measurement/prefilter_check.hpp):
/// prefilter_aspect, _major_over_analytic, _minor_over_analytic, prefilter_block_error, supersample_block_noise,
/// prefilter_error, next_seed_aspect, _major_over_analytic, _minor_over_analytic. Nothing otherwise.
void addPrefilterFields(nlohmann::json& row, render::Renderer& renderer, const render::Scene& s,
                        const MeasureSetup& setup, const Measurement& m);

/// The realised slope statistics of a bump field (computed once per field and cached).
const micro::SlopeStats& realisedSlopes(const micro::BumpSpec& spec);

}  // namespace hilite::measurement
