#pragma once
// The Fresnel colour strip of a material: F(theta) from normal incidence (left) to grazing (right),
// linear RGB written sRGB-encoded; and the numbers that describe its colour shift.

#include "hilite/brdf/params.hpp"

#include <string>

namespace hilite::experiments {

/// Writes the strip as a PNG (atomically). width x height pixels, column x at theta = 90 (x + 0.5) / width.
/// With a `label`, a band below the strip names it and marks theta every 15 degrees.
void writeFresnelStrip(const brdf::Params& p, int width, int height, const std::string& path,
                       const std::string& label = "");

struct StripStats {
    dvec3 normal;               ///< F at 0 degrees
    dvec3 grazing89;            ///< F at 89 degrees
    double redMin = 0;          ///< smallest red over 0..90
    double redMinThetaDeg = 0;  ///< where it is
};
StripStats fresnelStats(const brdf::Params& p);

}  // namespace hilite::experiments
