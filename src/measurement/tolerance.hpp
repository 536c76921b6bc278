#pragma once
// `hilite measure --tolerance E`: the cheapest settings predicted to reach an aspect error E
// for one scene, checked against a finer setting.

#include "hilite/measurement/measure_scene.hpp"

namespace hilite::measurement {

struct ToleranceSetup {
    double tolerance = 1e-3;  ///< the aspect error to reach (absolute)
    MeasureSetup base;        ///< threshold, min pixels, renderer (cpu); size and boundary are chosen
};

struct ToleranceResult {
    Measurement measurement;    ///< at the chosen settings
    MeasureSetup setup;         ///< the chosen settings
    double errorEstimate = 0;   ///< estimated |aspect - exact aspect| of `measurement`
    double predictedError = 0;  ///< what the error model predicted for the chosen settings before measuring
    Measurement check;          ///< the finer setting it was checked against
    MeasureSetup checkSetup;
    int rounds = 0;         ///< (measure, check) rounds taken
    bool met = false;       ///< errorEstimate <= tolerance
    double total_ms = 0;    ///< wall time of choosing, measuring and checking (prediction included)
    double startup_ms = 0;  ///< compiling the scene's program first, when this process had not yet
};

/// Chooses, measures, checks; escalates when the check finds the error above E (at most a few rounds,
/// up to 2048^2). `renderer` may be null with base.cpu.
ToleranceResult measureToTolerance(render::Renderer* renderer, const render::Scene& scene, const ToleranceSetup& t);

}  // namespace hilite::measurement
