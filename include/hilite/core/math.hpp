#pragma once
// Small numeric helpers shared by every layer. Depends on nothing but GLM and std.

#include <glm/glm.hpp>

#include <cmath>

namespace hilite {

using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 1.0 / kPi;

inline double deg2rad(double d) { return d * (kPi / 180.0); }
inline double rad2deg(double r) { return r * (180.0 / kPi); }

/// sqrt of a value that is mathematically >= 0 but may come out slightly negative from rounding.
inline double safeSqrt(double x) { return std::sqrt(std::max(0.0, x)); }

/// cos and sin of an angle in degrees, exact at multiples of 90: cos(deg2rad(90)) is 6.1e-17 in double,
/// not 0, and a light at exactly 90 degrees must deliver exactly no irradiance.
inline void cosSinDeg(double deg, double& c, double& s) {
    const double r = std::remainder(deg, 360.0);  // in [-180, 180]
    if (r == 0.0) c = 1.0, s = 0.0;
    else if (r == 90.0) c = 0.0, s = 1.0;
    else if (r == -90.0) c = 0.0, s = -1.0;
    else if (r == 180.0 || r == -180.0) c = -1.0, s = 0.0;
    else c = std::cos(deg2rad(r)), s = std::sin(deg2rad(r));
}

/// Unit vector of spherical angles in degrees (theta from the normal, phi from +x), exact on the axes.
inline dvec3 sphericalDirectionDeg(double thetaDeg, double phiDeg) {
    double ct, st, cp, sp;
    cosSinDeg(thetaDeg, ct, st);
    cosSinDeg(phiDeg, cp, sp);
    return {st * cp, st * sp, ct};
}

/// Unit vector of spherical angles in the local frame (n = +z): theta from the normal, phi from +x.
inline dvec3 sphericalDirection(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace hilite
