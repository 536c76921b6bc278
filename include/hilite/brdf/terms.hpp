#pragma once
// Reflectance terms in double precision: shaders/brdf.glsl itself, the one source of the GLSL and C++
// terms (same names, argument order and split), compiled here as C++ with the prelude below. The GLSL
// prelude is the block "prelude" of shaders/brdf_gl.glsl. See docs/terms.md.
// C++-only: gaussianNormalization (below, ndf.cpp), the tabulated NDF (brdf/ndf_table.hpp) and the spectral
// Fresnel (brdf/spectral.hpp).

#include "hilite/core/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hilite::brdf {

// ---- Prelude (C++) ----
using glm::dot;
using std::clamp;
using std::exp;
using std::log;
using std::max;
using std::min;
using std::sqrt;

/// log(1 - x) for x in [0, 1), exact near 0 (GLSL, without log1p: a series below 1e-2).
inline double log1mStable(double x) { return std::log1p(-x); }
/// theta from its sine and cosine: atan2 in double (GLSL: half-angle steps and a series, its atan being coarse).
inline double angleFromSinCos(double s, double c) { return std::atan2(s, c); }

#define REAL double
#define VEC2 dvec2
#define VEC3 dvec3
#define INLINE inline
#define REAL_MIN std::numeric_limits<double>::min()

#include "hilite/shaders/brdf.glsl"  // shaders/brdf.glsl: a copy in <build>/include, or <prefix>/include

#undef REAL
#undef VEC2
#undef VEC3
#undef INLINE
#undef REAL_MIN

// ---- C++ only ----

/// k_G of D_Gaussian = 1 / (2 pi int_0^{pi/2} exp(-(theta/m)^2) cos(theta) sin(theta) dtheta): no closed form
/// on the hemisphere, so integrated numerically (relative error < 1e-12) and cached per m. m = 0 (a delta, k_G
/// infinite) returns 0, so that no product with it becomes inf or NaN. See docs/terms.md, gaussianNormalization.
double gaussianNormalization(double m);

/// K of D_SGD = 1 / (alpha Gamma(1 - p, alpha)), so that int D cos theta_h dw = 1 (with t = tan^2 theta_h the
/// integral is int_0^inf exp(-alpha - t / alpha) (alpha + t / alpha)^-p dt): Gamma(1 - p, alpha) integrated in
/// ln s (relative error < 1e-13 for alpha in [1e-7, 10], p in [0, 10]; p = 0 and 1/2 have closed forms, tested).
/// Cached per thread for the last (alpha, p).
double sgdNormalization(double alpha, double p);

/// int (1 + B (1 - cos theta_h))^-C cos theta_h dw_h over the hemisphere, the ABC lobe's shape (A = 1) in
/// closed form: 2 pi / B^2 [(1 + B) I(-C) - I(1 - C)], I(q) = int_1^{1+B} t^q dt; a series for B < 1/2, where
/// the closed form cancels. 1 / it is the A that normalizes the shape as an NDF.
double abcShapeIntegral(double B, double C);

}  // namespace hilite::brdf
