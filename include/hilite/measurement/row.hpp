#pragma once
// The result row: one JSON object per measurement, written by one function for `measure --json`, `run`,
// `merge` and the library. It carries every registry parameter that applies to the scene, as resolved and
// rendered (scene::parameterColumns), then every measurement field.

#include "hilite/measurement/measure_scene.hpp"
#include "hilite/scene/resolve.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace hilite::measurement {

/// The row of a measurement `m` of `r`'s scene at `width` x `height` by `method` (gl, cpu, reference).
nlohmann::json row(const scene::Resolved& r, const Measurement& m, int width, int height, const std::string& method);

/// Measures `r`'s scene (at r.scene.light.incidenceDeg) as its values ask: the double reference, the cheapest
/// settings for a tolerance, or the GL / CPU path; one row. `renderer` may be null when no GL is needed.
nlohmann::json measureRow(render::Renderer* renderer, const scene::Resolved& r);

/// A row's number field, NaN when absent or not a number.
double rowNumber(const nlohmann::json& row, const char* key);

/// Every measurement field a row can carry, in the order results.csv lists them after the parameters.
const std::vector<std::string>& measurementColumns();

}  // namespace hilite::measurement
