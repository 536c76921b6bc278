#pragma once
// Lights with size: a sphere (radius R, centre at light_distance, intensity I) and a distant disk (angular
// radius delta, irradiance E). Seen from a point of the plane either is a cap of directions of uniform
// radiance L:
//   sphere: about the centre c, sin(alpha) = R / |c - p|, L = I / (pi R^2): its power pi L 4 pi R^2 = 4 pi I
//           is the point light's, and its irradiance pi L sin^2(alpha) cos(theta) = I cos(theta) / |c - p|^2 is
//           exact for a sphere wholly above the plane (the seed's B = pi L, and its point light as R -> 0);
//   disk:   about the light's direction, alpha = delta, L = E / (pi sin^2 delta) (pi L sin^2 delta = E).
// The reflected radiance int_cap f(wi, we) L cos(theta_i) dwi (over the part above the horizon) is computed
// two ways (derivation and measured errors: docs/area-lights.md):
//   - the rule, GL's (shaders/shade.frag) and its double twin: n Gauss-Legendre nodes in u = 1 - cos(beta)
//     (beta from the cap's centre) times 4n azimuths, the radial range cut by the horizon per azimuth;
//   - the exact integral, the twin every number is checked against: polar coordinates about the lobe's own
//     centre (the mirror image of we; we itself for a retroreflector), so a lobe of any width is resolved,
//     by nested adaptive Gauss-Kronrod to a relative kExactTolerance.

#include "hilite/core/math.hpp"
#include "hilite/render/scene.hpp"

#include <functional>
#include <vector>

namespace hilite::render {

/// The exact integral's relative tolerance (each nested level; measured errors: tests/render/test_area_light.cpp).
constexpr double kExactTolerance = 1e-9;
/// The rule's largest ring count: 32 rings x 128 azimuths = 4096 BRDF evaluations per pixel.
constexpr int kMaxRings = 32;
/// The rule of the cap's centre alone: one BRDF evaluation, weighed by the cap's visible solid angle (the midpoint
/// rule: its error ~ (cap radius / lobe width)^2 / 4, within 1e-3 of the peak for the sun's disk on a lobe 0.1
/// wide). `light_rings 0` to a user; -1 here, since 0 means "choose" (Light::rings) or "exact" (twinRings).
constexpr int kCentreRule = -1;
/// Ring counts the automatic choice tries, cheapest first.
constexpr int kRingLadder[] = {kCentreRule, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32};
/// A rule's ring count: kCentreRule or 1..kMaxRings.
inline bool validRings(int n) { return n == kCentreRule || (n >= 1 && n <= kMaxRings); }
/// The rule's points per pixel (4n^2; 1 for the centre's).
inline int rulePoints(int n) { return n == kCentreRule ? 1 : 4 * n * n; }

/// A light with size as seen from one point of the plane.
struct LightCap {
    dvec3 center{0, 0, 1};         ///< unit, towards the cap's centre
    dvec3 a{1, 0, 0}, b{0, 1, 0};  ///< tangent frame at the centre: a points down (a.z <= 0), b is horizontal
    double halfAngle = 0;          ///< alpha (rad)
    double uMax = 0;               ///< 1 - cos(alpha), without the cancellation of small caps
    double radiance = 0;           ///< L
};

/// The cap of a sphere or disk light seen from the plane point p (the disk's is the same from every point).
LightCap lightCap(const Light& light, const dvec3& p);
/// 1 - cos(beta_max): the cap's radial extent toward tangent azimuth phi (from a towards b), cut by the horizon.
double capEdge(const LightCap& cap, double phi);
/// 1 - cos(beta_h): where the horizon ends a ray from a cap centre of height cz, k = cos(phi) a.z (2: never).
double horizonEdge(double cz, double k);
/// The visible fraction of the cap's solid angle (1 unless the horizon cuts it: a disk near grazing).
double capVisibleFraction(const LightCap& cap);

/// The rule's radial nodes x in (0, 1) (ascending) and weights w (summing to 1) for n rings, n in [1, kMaxRings].
struct RingRule {
    std::vector<double> x, w;
};
const RingRule& ringRule(int n);

/// The rule of n rings x 4n azimuths over the cap (or its centre alone, n = kCentreRule, weighed by the visible
/// share of the cap along 4 azimuths): visit(wi, w) at each of its points, whose weighted sum times
/// capRuleScale(n) is the rule's integral (capRule; for several integrands at the same points at once).
void capRulePoints(const LightCap& cap, int n, const std::function<void(const dvec3& wi, double w)>& visit);
/// 2 pi / 4n (the centre's rule: 2 pi / 4).
inline double capRuleScale(int n) { return 2.0 * kPi / (4 * (n == kCentreRule ? 1 : n)); }
/// int_cap g(wi) dwi by the rule of n rings x 4n azimuths (or n = kCentreRule).
dvec3 capRule(const LightCap& cap, int n, const std::function<dvec3(const dvec3&)>& g);

/// int_cap g(wi) dwi exactly (to kExactTolerance): polar coordinates about q (unit, q.z > 0), where g may
/// peak sharply on the angular scale `width`; the cap's edge and the horizon are each ray's limits.
struct CapIntegral {
    dvec3 value{0.0};
    int evaluations = 0;
    bool converged = true;
};
CapIntegral capExact(const LightCap& cap, const dvec3& q, double width, const std::function<dvec3(const dvec3&)>& g);
/// int_cap g(wi) dwi exactly (to kExactTolerance) for g smooth over the cap: its own polar coordinates, the
/// horizon's kinks in azimuth as panel edges (cheaper than capExact where no lobe is sharp inside the cap).
CapIntegral capCentred(const LightCap& cap, const std::function<dvec3(const dvec3&)>& g);

/// Reflected radiance toward we from the plane point p under the scene's sphere or disk light: exact, or by the
/// GL rule of n rings.
dvec3 areaRadianceExact(const Scene& s, const dvec3& p, const dvec3& we);
dvec3 areaRadianceRule(const Scene& s, const dvec3& p, const dvec3& we, int rings);

/// How well the rule of n rings renders the scene's lobe: the largest |rule - exact| luminance over points of
/// the lobe (its centre and 8 rays out to where it falls below 2% of its peak), relative to the largest exact
/// value among them.
struct RuleCheck {
    int rings = 0;
    double error = 0;
};
/// The rings the GL rule renders the scene with (0 for a point or directional light; kCentreRule for the cap's
/// centre alone): light.rings when set,
/// else the cheapest of kRingLadder whose error is within light.ruleTarget (kMaxRings if none is), with that
/// error. Kept per thread for the last scene (every draw asks). With light.ltc: 0 rings and the error of the
/// linearly transformed cosines (render/ltc.hpp) at the same points.
RuleCheck lightRule(const Scene& s);
inline int lightRings(const Scene& s) { return s.light.rings != 0 ? s.light.rings : lightRule(s).rings; }

/// The scene whose CPU twin integrates a sphere or disk light by the GL rule it is drawn with (light.twinRings =
/// lightRings): for the framing searches of a GL or CPU measurement, thousands of twin evaluations, each 4n^2
/// BRDF evaluations instead of the exact integral's 80-80,000 (with light.ltc, twinRings 1: the twin evaluates the
/// same linearly transformed cosines as GL, render::areaRadianceLtc). The scene itself for any other light.
Scene withRuleTwin(const Scene& s);

}  // namespace hilite::render
