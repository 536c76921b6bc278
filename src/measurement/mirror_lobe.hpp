#pragma once
// The highlight around the mirror direction (measurement.lobe = mirror, docs/measurement.md): the local maximum
// of the twin's radiance that a climb from the mirror direction reaches, and the part of the region at threshold x
// that maximum that belongs to it. Rays from the peak in the chart find, on each, where the lobe's own hill ends:
// the threshold, or the floor of a valley beyond which the radiance rises again towards a brighter part (GGX 0.3 +
// Smith + Schlick at 40 deg: the strip above the horizon, whose half-maximum region joins the lobe's over a saddle).
// The GL and CPU pixels and the double reference all measure the lobe through the same mask (maskRadius).

#include "hilite/core/math.hpp"
#include "hilite/render/scene.hpp"

#include <vector>

namespace hilite::measurement {

/// Rays about the peak (1 per degree).
constexpr int kMirrorLobeRays = 360;
/// A ray's valley ends the lobe when the radiance rises this fraction of the peak above the lowest value since the
/// peak: a rival hill, not a ripple of a measured table.
constexpr double kValleyRise = 0.05;

struct MirrorLobe {
    /// false: no lobe holds the mirror direction (analysis::Flag::NoMirrorLobe): the region at level leaves the
    /// mirror direction out, no ray ends at the threshold, or valleys end half the rays or more; or no lobe at all
    /// (peak 0)
    bool found = false;
    double peak = 0;             ///< the lobe's maximum (twin, double)
    dvec2 peakUV{0.0};           ///< where, in the scene's chart (rad)
    bool peakOnHorizon = false;  ///< the climb ended on the horizon: the lobe still rises there
    double mirrorValue = 0;      ///< the radiance at the mirror direction
    double level = 0;            ///< threshold x peak
    bool saddleCut = false;      ///< some ray ends at a valley, not at the threshold (analysis::Flag::SaddleCut)
    /// Per ray about peakUV, at angles 2 pi k / rays.size() from +u towards +v (rad): where the region ends on it
    /// (the threshold, the valley's floor, or the horizon), and whether a valley ends it.
    std::vector<double> extent;
    std::vector<char> valley;
    double step = 0;  ///< the rays' sampling step near the peak (rad)

    /// The radius about the peak beyond which the lobe is masked at angle `phi` (rad): a valley's floor (linear
    /// between neighbouring rays that both end at one, else the nearest ray's) or, where the threshold ends the
    /// ray, 1.25 x the largest extent of the 7 nearest rays plus 4 steps (room for the contour between the rays;
    /// the GL pixels and the reference find the contour themselves).
    double maskRadius(double phi) const;
    /// Whether (u, v) lies within the mask.
    bool inMask(double u, double v) const;
    /// Whether a point (u, v) of radiance L can belong to the lobe: within the mask and at most (1 + kValleyRise) x
    /// its peak (higher, the ray to it would have risen past a valley: a rival, such as a measured material's
    /// 1 / cos theta_o growth at the horizon, which the mask can reach where the lobe is wide).
    bool holds(double u, double v, double L) const { return L <= (1.0 + kValleyRise) * peak && inMask(u, v); }
    /// The rays' box in the chart (rad): u0, u1, v0, v1.
    void box(double& u0, double& u1, double& v0, double& v1) const;
};

/// The mirror lobe of a scene with a CPU twin, for the region at `frac` of its peak (kept per thread for the last
/// scene and fraction: the GL path, the reference and the row ask for the same one).
const MirrorLobe& findMirrorLobe(const render::Scene& scene, double frac);

}  // namespace hilite::measurement
