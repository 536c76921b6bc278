#pragma once
// Linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines"): a cheap integral of a sphere or disk light (light_rule = ltc) instead of the rule.
//
// The fit (per isotropic BRDF, cached in process): at kLtcElevations view elevations theta_e (uniform in
// sqrt(1 - cos theta_e) up to kLtcMaxElevationDeg) the BRDF-cosine F(wi) = lum f(wi, we) cos(theta_i) / norm, norm =
// int lum f cos (kept apart per channel: the magnitude), is matched by D(wi) = D_o(M^-1 wi / |M^-1 wi|) |M^-1| /
// |M^-1 wi|^3, D_o the clamped cosine / pi, M = [[a, 0, b], [0, c, 0], [d, 0, 1]] in the view's frame (x towards
// we's azimuth): Nelder-Mead over (log a, log c, b, d), from the previous elevation's solution, minimising
// int |D - F|^3 dwi on a deterministic polar grid graded about the mirror direction (our own fit, after the paper's
// method; no published table or code). The 3-parameter form about the lobe's mean direction, M = [X Y Z] [[a, 0, b],
// [0, c, 0], [0, 0, 1]], whose cosine's horizon is perpendicular to Z, was worse at grazing (GGX 0.1 at 85 deg
// under the sun: aspect error 0.172 against 0.109; worst minor axis error 2.39 against 0.98 on the price list).
//
// The evaluation: the cap as a regular spherical polygon of kLtcVertices vertices of the cap's area (tangent
// radius scaled by sqrt(2 pi / (N sin(2 pi / N)))), clipped to the plane's horizon, transformed by M^-1 (interpolated
// linearly in the grid), clipped to the cosine's horizon, the clamped cosine's integral as the paper's sum of edge
// integrals. Vertices are kept as the cap's centre plus offsets, so that a tiny cap (the sun: 0.266 deg) loses no
// digits in float (shaders/shade.frag's ltcRadiance is the same code).

#include "hilite/render/scene.hpp"

#include <array>
#include <string>
#include <vector>

namespace hilite::render {

/// View elevations of the fit and the cap polygon's vertices (shade.frag's HILITE_LTC_* must agree).
constexpr int kLtcElevations = 32;
constexpr double kLtcMaxElevationDeg = 89.0;
constexpr int kLtcVertices = 16;

/// The fitted table of one BRDF.
struct LtcTable {
    /// Per elevation: M^-1 in the view's frame (x towards we's azimuth, z the normal), normalised to m11 = 1:
    /// (m00, m02, m20, m22); m01 = m10 = m12 = m21 = 0.
    std::vector<std::array<double, 4>> minv;
    std::vector<dvec3> norm;       ///< int f cos dwi per channel (the magnitude)
    std::vector<double> fitError;  ///< int |D - F| dwi (L1 distance of the unit-mass lobes) per elevation
    double seconds = 0;            ///< the fit's time
    int objectiveEvaluations = 0;  ///< the fit's cost in evaluations of int |D - F|^3
};

/// Why LTC cannot represent the scene ("" if it can): a .brdf file, an anisotropic or measured BRDF, a
/// retroreflector, explicit bumps.
std::string ltcRefusal(const Scene& s);
/// The fitted table of the scene's BRDF (fitted on first use, cached per BRDF in process; thread-safe).
/// InputError (naming light_rule) if ltcRefusal is not "".
const LtcTable& ltcTable(const Scene& s);
/// The fit itself, uncached (its time is the knob's price: bench/bench_speed.cpp BM_LtcFit).
LtcTable ltcFit(const brdf::Params& p);
/// The grid coordinate of view elevation cos(theta_e): in [0, kLtcElevations - 1].
double ltcGridCoordinate(double cosTheta);

/// Reflected radiance toward we from the plane point p under the scene's sphere or disk light by LTC (double;
/// GL computes the same in float).
/// `vertices`: the cap's polygon (GL draws kLtcVertices; others measure the polygon's own error, and never take
/// the small cap's limit: a cap whose mapped polygon is under 0.01 rad is D at its centre times its solid angle).
dvec3 areaRadianceLtc(const Scene& s, const dvec3& p, const dvec3& we, int vertices = kLtcVertices);
/// int_P D_o over a cap's polygon (the cap about unit c with offsets of tangent radius t along the tangent frame
/// a, b), after M^-1 (row-major 3x3) and both horizon clips: exposed for tests.
double ltcCapIntegral(const dvec3& c, const dvec3& a, const dvec3& b, double t, const std::array<double, 9>& minv,
                      int vertices = kLtcVertices);
/// The polygon's tangent radius over the cap's: sqrt(h / sin(h)), h = 2 pi / vertices (a regular polygon of the
/// disk's area).
double ltcPolygonScale(int vertices = kLtcVertices);

}  // namespace hilite::render
