#pragma once
// The flags of `hilite measure` and their resolution into a scene, shared with `hilite run`
// (an experiment's configuration is a list of these flags).

#include "cli/options.hpp"
#include "experiments/measure_scene.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::cli {

struct MeasureFlags {
    SceneFlags scene;
    double threshold = 0.5;
    int minPixels = 8;
    std::string boundary = "subpixel";
    int supersample = 1;           ///< n: n x n jittered renders of the final frame
    std::string renderer = "gl";   ///< gl (float shader) | cpu (the double twin on every core)
    std::string crop = "on";       ///< automatic framing: shade only the region's box of the final frame
    std::string tolerance;         ///< "" = off; else the aspect error to reach, settings chosen by the tool
    bool json = false;
    bool reference = false;
};

struct ResolvedMeasure {
    render::Scene scene;  ///< incidence: the first of `angles`
    std::vector<double> angles;
    experiments::MeasureSetup setup;
    double tolerance = 0;  ///< > 0: --tolerance given
};

/// Allowed --tolerance: below 1e-5 the double reference itself (1e-5 where the horizon cuts) cannot
/// confirm it; above 0.1 the aspect says little.
constexpr double kMinTolerance = 1e-5, kMaxTolerance = 0.1;

void addMeasureFlags(CLI::App& app, MeasureFlags& f);
/// Validates every flag (InputError naming the flag and its range).
ResolvedMeasure resolveMeasure(const MeasureFlags& f);
/// One result as the JSON object `measure --json` prints (the contract's field names).
nlohmann::json measurementRow(const render::Scene& s, const experiments::Measurement& m, const MeasureFlags& f,
                              int width, int height, const std::string& method);
/// Measures the scene of `r` as the flags ask (reference, tolerance, or the GL/CPU path): one JSON row.
/// `renderer` may be null when no GL is needed.
nlohmann::json measureRow(render::Renderer* renderer, const ResolvedMeasure& r, const MeasureFlags& f);

}  // namespace hilite::cli
