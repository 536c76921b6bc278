#pragma once
// What a measured file says of itself and what a user checks first (`hilite brdf inspect FILE`): the format,
// description and incidences, where values are missing, the directional albedo against theta_i, the peak's
// offset from the mirror direction per incidence, and the reciprocity error over sampled pairs of directions.

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace hilite::brdf {

struct IncidenceInspection {
    double thetaDeg = 0;
    dvec3 albedo{0.0};  ///< directional albedo, int f cos theta_o dw_o (brdf::albedo)
    /// The brightest f cos theta_o (the luminance of the quantity a gonio-reflectometer records, finite at the
    /// horizon where f itself is not) on a scan of the hemisphere (0.25 deg in theta_o, 0.5 deg in phi_o): its
    /// direction and its angle from the mirror direction.
    double peakThetaODeg = 0, peakPhiODeg = 0, peakOffsetDeg = 0;
};

struct Reciprocity {
    int pairs = 0;  ///< pairs of directions, both within 80 deg of the normal, where either value is > 1e-3 x median
    double median = 0, p95 = 0, max = 0;  ///< |Y(f(a, b)) - Y(f(b, a))| / max of the two
};

struct Inspection {
    std::string format;  ///< "rgl" or "merl"
    std::string path, description;
    std::vector<double> thetaINodesDeg, phiINodesDeg;  ///< RGL: the incidences the tables were measured at
    std::string resolution;                            ///< the tables' sizes, in words
    std::size_t missing = 0, total = 0;                ///< nodes (RGL: `valid` bits unset) or bins (MERL: no data)
    double mostNegative = 0;                           ///< RGL: the most negative rgb value (clipped to 0)
    Reciprocity reciprocity;
    std::vector<IncidenceInspection> incidences;
};

/// Requires p.isMeasured(). thetasDeg: the incidences to report, at the light's azimuth.
Inspection inspect(const Params& p, const std::vector<double>& thetasDeg, double azimuthDeg);

}  // namespace hilite::brdf
