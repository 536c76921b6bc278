#pragma once
// Framing a highlight about its peak when the peak is far from the mirror direction (retroreflection,
// whose lobe peaks back toward the light, 2 theta_i from the mirror direction). The automatic framing and the
// reference measure about the chart's centre, the mirror direction; here the twin's lobe is searched over the
// whole visible hemisphere, and when the mirror direction lies outside the highlight region (its lobe value is
// below threshold x peak), the peak is far from it (kFarPeakDeg) and backscattered (nearer the light direction
// than the mirror direction) the measurement chart is centred on the peak instead (render::Light::chartCenter):
// the shape is then that of the region about the peak, undistorted by the azimuthal-equidistant chart's
// stretch far from its centre (rho / sin rho: 1.2 at 60 deg), and its centroid is relative to the peak.

#include "hilite/render/scene.hpp"

#include <optional>
#include <string>

namespace hilite::measurement {

/// A peak is far from the mirror direction beyond this angle: there the azimuthal-equidistant chart about wr
/// stretches lengths across the radius by rho / sin(rho) > 1.02. Off-specular shifts of microfacet lobes stay
/// well inside it (they are bounded by the mirror direction's elevation, and are a few degrees for alpha <= 0.3).
constexpr double kFarPeakDeg = 20.0;

/// A peak with cos theta_o below this (within 2.9 deg of the horizon) whose lobe still rises toward the horizon
/// is the horizon itself, not a maximum of the lobe: it is not framed about.
constexpr double kHorizonPeakCos = 0.05;

struct LobePeak {
    dvec3 direction{0, 0, 1};     ///< exitant direction of the twin's largest lobe value
    double value = 0;             ///< that value (luminance of the radiance)
    double mirrorValue = 0;       ///< the lobe at the mirror direction
    double offsetDeg = 0;         ///< angle between the peak and the mirror direction
    double fromLightDeg = 0;      ///< angle between the peak and the light direction wi
    bool risesToHorizon = false;  ///< the lobe at half the peak's elevation is no lower: the peak is the horizon
};

/// The twin's global peak, from the hemisphere survey (lobe_survey.hpp), and what frameAboutPeak asks of it.
LobePeak findPeak(const render::Scene& scene);

/// The scene with its chart centred on the peak when the highlight must be framed about it (the mirror
/// direction is outside the region L >= threshold x peak, the peak is more than kFarPeakDeg from it and nearer
/// the light direction than the mirror direction);
/// nullopt when the mirror direction is inside or the peak near, when
/// the scene already has a chart centre, when there is no highlight, and for bumps and point lights (framed by
/// the analytic twin, and an eye that sits on the chart's centre, respectively).
std::optional<render::Scene> frameAboutPeak(const render::Scene& scene, double threshold);

/// What a measurement of `scene` is framed about, for the results: "mirror direction", or
/// "peak (retroreflection: toward the light, 2 theta_i = 60 deg from the mirror direction)", or
/// "peak (41.3 deg from the mirror direction)". offsetDeg: the peak's angle from the mirror direction (0 when
/// framed about the mirror direction).
std::string framedAbout(const render::Scene& scene, double threshold, double& offsetDeg);

}  // namespace hilite::measurement
