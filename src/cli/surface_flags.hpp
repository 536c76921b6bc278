#pragma once
// The [surface] table / flags (issue 10): explicit micro-geometry instead of the analytic BRDF.

#include "render/surface.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace hilite::cli {

struct SurfaceFlags {
    std::string bumps = "none";  ///< none | explicit
    double bumpPeriodPx = 4.0;
    long long bumpSeed = 1;
    int bumpSamples = 0;
    double sun = 0.1;
    std::string bumpFilter = "auto";  ///< auto | supersample | moments
    bool prefilterCheck = false;
};

void addSurfaceFlags(CLI::App& app, SurfaceFlags& f);
/// Validated (InputError naming the flag and its range).
render::Surface surfaceOf(const SurfaceFlags& f);

}  // namespace hilite::cli
