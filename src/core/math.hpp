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

/// Unit vector of spherical angles in the local frame (n = +z): theta from the normal, phi from +x.
inline dvec3 sphericalDirection(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace hilite
