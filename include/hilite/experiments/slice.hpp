#pragma once
// Slices of a BRDF, as BRDF Explorer draws them: f(wi, wo) and f cos(theta_o) against the exitant direction,
// in the plane of incidence and across it through the mirror direction, for several BRDFs overlaid (the
// built-in models, measured tables), evaluated in double on the CPU (brdf::evaluate). `hilite brdf slice`
// writes them as CSV, JSON and plots; Python's hilite.brdf.slice returns them as arrays.

#include "hilite/scene/resolve.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::experiments {

/// One BRDF of the plot: a label and its resolved scene (its light's azimuth and the material are read).
struct SliceCurve {
    std::string label;
    scene::Resolved scene;
};

/// The two planes: "in" (the plane of incidence: angle = signed theta_o, positive on the mirror side, so the
/// mirror direction is at +theta_i) and "across" (the great circle through the mirror direction perpendicular
/// to the plane of incidence: angle = the signed angle from the mirror direction, towards +v = n x wi's side).
struct SlicePoint {
    std::string curve, plane;
    double incidenceDeg = 0, angleDeg = 0, thetaODeg = 0;
    double wo[3] = {0, 0, 0};
    double f[3] = {0, 0, 0};  ///< R G B
    double luminance = 0;     ///< of f (the renders' luminance weights)
    double fCos = 0;          ///< luminance x cos(theta_o)
};

/// Every curve at every incidence in both planes, the angle from -90 to 90 deg in steps of stepDeg (in
/// (0, 10], else InputError), the horizon's own points excluded. InputError for a curve without a CPU
/// evaluation (a .brdf file).
std::vector<SlicePoint> brdfSlices(const std::vector<SliceCurve>& curves, const std::vector<double>& incidencesDeg,
                                   double stepDeg);

/// A point as a row (the CSV's and the JSON's fields).
nlohmann::json toJson(const SlicePoint& p);
/// The rows' column names, in order.
const std::vector<std::string>& sliceColumns();

}  // namespace hilite::experiments
