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
    bool json = false;
    bool reference = false;
};

struct ResolvedMeasure {
    render::Scene scene;  ///< incidence: the first of `angles`
    std::vector<double> angles;
    experiments::MeasureSetup setup;
};

void addMeasureFlags(CLI::App& app, MeasureFlags& f);
/// Validates every flag (InputError naming the flag and its range).
ResolvedMeasure resolveMeasure(const MeasureFlags& f);
/// One result as the JSON object `measure --json` prints (the contract's field names).
nlohmann::json measurementRow(const render::Scene& s, const experiments::Measurement& m, const MeasureFlags& f,
                              int width, int height, const std::string& method);

}  // namespace hilite::cli
