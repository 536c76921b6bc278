#pragma once
// Bihemispherical reflectance: the cosine-weighted average of the directional albedo over every direction
// of incidence, rho_hh = (1/pi) int rho(wi) cos(theta_i) dwi — the seed's single number for how much of
// uniform illumination a surface reflects. Lambert gives rho_hh = rho exactly.

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

namespace hilite::brdf {

/// \brief rho_hh = (1/pi) int_0^{2pi} int_0^{pi/2} rho(theta, phi) cos(theta) sin(theta) dtheta dphi per channel.
/// theta by Gauss-Legendre on two panels split at 60 degrees (the albedo of narrow lobes changes fastest near
/// grazing); phi by the trapezoid rule on 16 azimuths when the BRDF is anisotropic (one azimuth otherwise:
/// an isotropic rho does not depend on phi). Error: that of brdf::albedo (< 1e-6 relative on smooth
/// integrands, < 1e-3 where a lobe's horizon cut makes rho kink), weighted down by cos(theta) at grazing.
dvec3 bihemisphericalAlbedo(const Params& p);

}  // namespace hilite::brdf
