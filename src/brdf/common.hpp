#pragma once
// Numerics shared by the terms: the twin of the GLSL block "common" in shaders/brdf.glsl.

#include "core/math.hpp"

#include <cmath>

namespace hilite::brdf {

/// log(1 - x) for x in [0, 1): exact near 0 where log(1 - x) would lose every digit of x.
inline double log1mStable(double x) { return std::log1p(-x); }

/// cos^n(theta) written as exp(n log(1 - oneMinusCos)), with 1 - cos passed in from a stable form
/// (|a - b|^2 / 2 for unit vectors): for n = 1e6 and cos = 1 - 1e-7 direct pow() is off by 10%.
inline double powCosStable(double oneMinusCos, double n) {
    if (oneMinusCos >= 1.0) return n == 0.0 ? 1.0 : 0.0;  // cos <= 0: the clamped lobe is 0
    return std::exp(n * log1mStable(oneMinusCos));
}

}  // namespace hilite::brdf
