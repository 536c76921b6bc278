#pragma once
// The typed result of one measurement: the scene as measured, the shape with its flags (the analysis's and
// the scene-aware diagnoses of measurement/diagnose.hpp), and what else the measurement found, each part
// present only where the scene asks for it. toJson makes the result row from it: the one writer of the row
// that `measure --json`, `run`, `merge`, Python and the library print.

#include "hilite/measurement/measure_scene.hpp"
#include "hilite/scene/resolve.hpp"
#include "hilite/scene/setup.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace hilite::measurement {

/// A sphere or disk light: how much of it is integrated, and how well.
struct LightFields {
    double visible = 1;               ///< the part of the light above the plane's horizon
    std::optional<double> ruleError;  ///< the GL rule's radiance error (render/area_light.hpp); none: reference
};

/// Explicit micro-geometry (--bumps explicit): the render's bump filter and the analytic twin's shape.
struct MicroFields {
    std::string filter;                ///< --bump-filter as resolved
    std::string filterUsed;            ///< supersample or moments, at the final render's size
    double log2PeriodPx = 0;           ///< log2 of the bump period in pixels
    int samplesCenter = 0;             ///< patches per axis the centre pixel's footprint needs (uncapped)
    analysis::Shape analytic;          ///< the CPU reference of the same NDF and Fresnel with implicit G
    double slopeRms = 0, slopeKs = 0;  ///< the realised slope statistics
};

/// --prefilter-check: the moments prefilter and the next seed rendered in the measurement's frame.
struct PrefilterFields {
    analysis::Shape moments, nextSeed;
    double blockError = 0, blockNoise = 0, error = 0;
    int blocks = 0, unresolvedBlocks = 0;
};

/// --tolerance: what was chosen, what it is estimated to reach, what it cost.
struct ToleranceFields {
    double errorEstimate = 0;   ///< estimated |aspect - exact aspect|
    double predictedError = 0;  ///< the error model's prediction for the chosen settings
    bool met = false;           ///< errorEstimate <= tolerance
    MeasureSetup setup;         ///< the chosen settings
    MeasureSetup checkSetup;    ///< the finer setting it was checked against
    double checkAspect = 0;     ///< the check's aspect
    int rounds = 0;
    double total_ms = 0, startup_ms = 0;
};

/// A measured table's interpolation error per field (row.cpp tableError).
struct TableError {
    double aspect = 0, eccentricity = 0, major_deg = 0, minor_deg = 0;
};

/// The largest change of the eccentricity sqrt(1 - a^2) while the aspect a moves by up to `aspectError` within
/// [0, 1]: the eccentricity's share of table_error, in [0, 1] (0.6 +- 0.2: 0.2, the end at 0.8).
double eccentricityChange(double aspect, double aspectError);

/// What rendered a GL measurement (GL_RENDERER, GL_VENDOR).
struct GlInfo {
    std::string backend, renderer, vendor;
};

struct Result {
    scene::Resolved resolved;   ///< the scene as measured, at resolved.scene.light.incidenceDeg
    std::string method;         ///< gl, cpu or reference
    int width = 0, height = 0;  ///< the final render's size (with a tolerance: the size chosen)
    Measurement measurement;    ///< the shape (flags and diagnoses included), renders, framing, timings
    std::string framedAbout;    ///< the mirror direction, or the peak far from it
    double peakOffsetDeg = 0;   ///< the peak's angle from the mirror direction (0 when framed about it)
    std::optional<LightFields> light;
    std::optional<MicroFields> micro;
    std::optional<PrefilterFields> prefilter;
    std::optional<ToleranceFields> tolerance;
    std::optional<TableError> tableError;
    std::optional<GlInfo> gl;

    const analysis::Shape& shape() const { return measurement.shape; }
};

/// The result row: every registry parameter that applies to the scene (scene::parameterColumns), then every
/// measurement field present (measurementColumns).
nlohmann::json toJson(const Result& result);

}  // namespace hilite::measurement
