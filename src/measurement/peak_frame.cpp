#include "measurement/peak_frame.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "measurement/lobe_survey.hpp"

#include <cmath>
#include <sstream>

namespace hilite::measurement {

namespace {

double angleDeg(const dvec3& a, const dvec3& b) {
    return rad2deg(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

}  // namespace

LobePeak findPeak(const render::Scene& scene) {
    // The survey's global peak (measurement/lobe_survey.hpp: the whole hemisphere, climbs from the mirror,
    // light and normal directions and from the grid's best local maxima), seen from the mirror direction.
    render::Scene mirror = scene;
    mirror.light.chartCenter.reset();
    const LobeSurvey s = surveyLobe(mirror, 0.5);
    const dvec3 eye = render::eyePosition(mirror), wr = mirror.light.chart().wr(), wi = scene.light.direction();
    LobePeak p;
    p.value = s.peak;
    p.direction = s.peakDirection;
    p.risesToHorizon = s.peakOnHorizon;
    const dvec3 w = glm::normalize(dvec3(wr.x, wr.y, std::max(wr.z, 1e-6)));
    p.mirrorValue = brdf::luminance(render::surfaceRadiance(scene, eye, w));
    p.offsetDeg = angleDeg(p.direction, wr);
    p.fromLightDeg = angleDeg(p.direction, wi);
    return p;
}

std::optional<render::Scene> frameAboutPeak(const render::Scene& scene, double threshold) {
    // Bumps are framed by their analytic twin; under a point light the eye sits on the chart's centre, so the
    // lobe it sees would move with the frame: both stay about the mirror direction.
    // Without a CPU twin (a .brdf file) there is no lobe to search: blind framing finds its region instead.
    if (!render::hasTwin(scene)) return std::nullopt;
    if (scene.light.chartCenter || scene.surface.bumps || !scene.light.distant()) return std::nullopt;
    const LobePeak p = findPeak(scene);
    if (!(p.value > 0) || p.mirrorValue >= threshold * p.value) return std::nullopt;  // wr inside the region
    if (p.offsetDeg <= kFarPeakDeg) return std::nullopt;  // near: the chart about wr measures it undistorted
    // Forward peaks far from wr (a rough lobe with Smith G and Fresnel peaking at the horizon) stay measured
    // about the mirror direction, flagged horizon_cut as before: only backscatter is reframed.
    if (p.fromLightDeg >= p.offsetDeg) return std::nullopt;
    // A peak on the horizon (Beckmann or GGX with roughness 10: D peaks at grazing h, so the lobe rises toward
    // the horizon on the light's side, and the search stops there) is no centre for a chart: half of it would lie below the plane and the
    // region would be a horizon sliver shaped by where the sampling stops (measured at m = 10, 45 deg: GL
    // major axis 73.9 / 71.5 / 70.2 deg at 256 / 512 / 1024 px against the reference's 68.0, fwhm_v 157 deg
    // against 3.1). It stays about the mirror direction, where the reference says not_star_shaped. A lobe with
    // a true maximum near the horizon (retro n = 1e8 at theta_i = 89.9 deg, 0.1 deg up) is framed about it.
    if (p.direction.z < kHorizonPeakCos && p.risesToHorizon) return std::nullopt;
    render::Scene s = scene;
    s.light.chartCenter = p.direction;
    return s;
}

std::string framedAbout(const render::Scene& scene, double threshold, double& offsetDeg) {
    offsetDeg = 0;
    if (!frameAboutPeak(scene, threshold)) return "mirror direction";
    const LobePeak p = findPeak(scene);
    offsetDeg = p.offsetDeg;
    std::ostringstream s;
    s.precision(4);
    if (p.fromLightDeg < 0.5)
        s << "peak (retroreflection: toward the light, 2 theta_i = " << p.offsetDeg
          << " deg from the mirror direction)";
    else s << "peak (" << p.offsetDeg << " deg from the mirror direction)";
    return s.str();
}

}  // namespace hilite::measurement
