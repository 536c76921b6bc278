#pragma once
// The values criterion of `hilite fit` (experiments/fit.hpp): the BRDF itself compared over the directions a
// measured table holds, as the measured-data literature fits (Ngan, Durand & Matusik 2005; Löw et al. 2012).
//
// Directions: MERL's binning (brdf/merl.hpp), the bin centres of every 2nd theta_h bin (its square-root spacing
// puts them where the highlight is), every 3rd theta_d bin and every 6th phi_d bin, phi_h = 0 (0, 45, 90 and
// 135 deg with anisotropy), both directions above the horizon and within 80 deg of the normal (Ngan et al. cut
// the data beyond 80 deg: the gantry's grazing samples are unreliable). The residual is the RMS over them of
//   ln(1 + cos(theta_i) f_model) - ln(1 + cos(theta_i) f_target)
// on the luminance of f: Löw et al.'s compressed, cosine-weighted error (their E2), which keeps the peak of a
// narrow lobe from outweighing every other direction and is near the relative error where f cos(theta_i) >> 1.

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

#include <vector>

namespace hilite::experiments::values {

struct Directions {
    std::vector<dvec3> wi, wo;
};

/// The directions above (isotropic: phi_h = 0; anisotropic: four phi_h).
Directions grid(bool anisotropic);

/// cos(theta_i) x luminance(f) (channel < 0) or f's channel 0..2 at each direction; NaN where f is not finite or
/// negative (no data).
std::vector<double> sample(const brdf::Params& p, const Directions& d, int channel = -1);

/// The RMS of ln(1 + model) - ln(1 + target) over the directions where both are numbers (NaN if none).
double residual(const std::vector<double>& model, const std::vector<double>& target);

}  // namespace hilite::experiments::values
