#pragma once
// Measuring a resolved scene to its typed result, and the columns of the result row (result.hpp toJson: one
// JSON object per measurement, written by one function for `measure --json`, `run`, `merge` and the library).

#include "hilite/measurement/result.hpp"
#include "hilite/scene/resolve.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::measurement {

/// Measures `r`'s scene (at r.scene.light.incidenceDeg) as its values ask: the double reference, the cheapest
/// settings for a tolerance, or the GL / CPU path; one result. `renderer` may be null when no GL is needed.
Result measureRow(render::Renderer* renderer, const scene::Resolved& r);

/// A row's number field, NaN when absent or not a number.
double rowNumber(const nlohmann::json& row, const char* key);

/// Every measurement field a row can carry, in the order results.csv lists them after the parameters.
const std::vector<std::string>& measurementColumns();

}  // namespace hilite::measurement
