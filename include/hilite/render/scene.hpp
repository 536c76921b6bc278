#pragma once
// What is rendered: the plane's BRDF, a distant light, and the view.

#include "hilite/brdf/params.hpp"
#include "hilite/brdf_file/brdf_file.hpp"
#include "hilite/core/camera.hpp"
#include "hilite/core/chart.hpp"
#include "hilite/core/names.hpp"
#include "hilite/render/surface.hpp"

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

namespace hilite::render {

enum class LightType {
    Directional,  ///< distant: irradiance E from one direction, the same at every point of the plane
    Point,        ///< isotropic point: intensity I, irradiance I cos(theta) / d^2 (inverse-square law)
    Sphere,       ///< a uniformly glowing sphere of radius R: the point light's intensity I (power 4 pi I)
    Disk,         ///< distant disk of angular radius delta (the sun): irradiance E normal to it
};
/// --light's spellings, in help order.
inline constexpr Named<LightType> kLightTypes[] = {{LightType::Directional, "directional"},
                                                   {LightType::Point, "point"},
                                                   {LightType::Sphere, "sphere"},
                                                   {LightType::Disk, "disk"}};
inline const char* toString(LightType t) { return nameIn(kLightTypes, t); }

/// The light: its direction from the origin by incidence theta_i and azimuth phi_i. A directional light
/// delivers irradiance E (on a surface facing it), so the plane receives E cos(theta_i); a point light
/// sits at `distance` along that direction and delivers I cos(theta) / d^2 at each point of the plane.
/// A sphere (centre there, radius R) and a disk (distant, angular radius delta) are caps of directions of
/// uniform radiance integrated over (render/area_light.hpp): the seed's point light as their limit.
struct Light {
    LightType type = LightType::Directional;
    double incidenceDeg = 45.0;
    double azimuthDeg = 0.0;
    double irradiance = 1.0;  ///< directional, disk: E
    double intensity = 1.0;   ///< point, sphere: I
    double distance = 10.0;   ///< point, sphere: distance of the centre from the origin
    double radius = 0.1;      ///< sphere: R (< the centre's height above the plane)
    double angleDeg = 0.266;  ///< disk: angular radius delta (the sun's mean: 0.266 deg)
    /// sphere, disk: the GL rule's rings n (n Gauss-Legendre nodes x 4n azimuths; render::kCentreRule: the cap's
    /// centre alone); 0: chosen per scene (render::lightRings) to reach `ruleTarget`.
    int rings = 0;
    /// sphere, disk with rings 0: the largest radiance error of the rule, relative to the lobe's peak, that
    /// the automatic choice accepts (set from --tolerance when one is given).
    double ruleTarget = 1e-3;
    /// sphere, disk: how the CPU twin integrates the cap. 0: exactly (render::areaRadianceExact), as the reference
    /// does; n != 0: the GL rule's n rings (or the centre's, kCentreRule) in double (render::areaRadianceRule), which the GL and CPU paths' framing
    /// searches use (render::withRuleTwin): the lobe that is drawn, at 4n^2 evaluations instead of 80-80,000.
    int twinRings = 0;
    /// sphere, disk: integrate the cap by linearly transformed cosines (render/ltc.hpp: a cosine lobe fitted to
    /// the scene's isotropic BRDF per view elevation, the cap as a polygon) instead of the rule, in GL and in the
    /// framing twin (twinRings != 0); the reference still integrates exactly.
    bool ltc = false;
    /// The measurement chart's centre when it is not the mirror direction (a highlight framed about a peak far
    /// from it, e.g. retroreflection: measurement/peak_frame.hpp). Unset: the mirror direction.
    std::optional<dvec3> chartCenter;
    dvec3 direction() const { return sphericalDirectionDeg(incidenceDeg, azimuthDeg); }
    dvec3 position() const { return distance * direction(); }
    /// A light at infinity: the reflected radiance depends on the exitant direction alone.
    bool distant() const { return type == LightType::Directional || type == LightType::Disk; }
    /// A light with size: its radiance is integrated over a cap of directions.
    bool area() const { return type == LightType::Sphere || type == LightType::Disk; }
    /// The chart about the mirror direction, or about chartCenter (the mirror chart of a light whose mirror
    /// direction is that centre: +u still points toward the normal).
    MirrorChart chart() const {
        if (!chartCenter) return MirrorChart::fromDegrees(incidenceDeg, azimuthDeg);
        const dvec3& c = *chartCenter;
        return MirrorChart(std::atan2(std::hypot(c.x, c.y), c.z), std::atan2(c.y, c.x) + kPi);
    }
};

struct Scene {
    brdf::Params brdf;
    /// A BRDF Explorer .brdf file with its parameter values: when set, its GLSL BRDF() replaces the built-in
    /// model of `brdf` (of which only tangentAngleDeg still applies: it turns the tangent frame X, Y).
    /// It has no CPU twin: surfaceRadiance() and everything built on it refuse such a scene.
    std::shared_ptr<const brdf_file::BrdfFile> brdfFile;
    Light light;
    /// Distance of the eye (the measurement camera) from the origin, on the mirror direction. Only a
    /// point light makes the image depend on it: a distant light's radiance depends on direction alone.
    double eyeDistance = 10.0;
    Surface surface;  ///< flat, or explicit micro-geometry
};

std::ostream& operator<<(std::ostream&, const Scene&);

/// The eye of the measurement view: on the mirror direction (lifted 1e-6 rad above the horizon at
/// grazing incidence), at scene.eyeDistance from the origin.
dvec3 eyePosition(const Scene& s);

/// Radiance reaching an eye at `eye` from the plane along exitant direction `we` (unit, we.z > 0):
/// f(wi, we) E cos(theta_i), with wi and E those of the point the ray meets. Double-precision twin of
/// the shader's main(): for a directional light `eye` is irrelevant. Throws InputError for a .brdf scene.
dvec3 surfaceRadiance(const Scene& s, const dvec3& eye, const dvec3& we);
/// The same with the light's direction s.light.direction() given: a search that evaluates one scene many
/// times computes it once (its degrees' cos and sin were a third of a twin evaluation).
dvec3 surfaceRadiance(const Scene& s, const dvec3& lightDirection, const dvec3& eye, const dvec3& we);
/// Whether the CPU double twin can evaluate the scene (false for a .brdf file).
inline bool hasTwin(const Scene& s) { return !s.brdfFile; }
/// Throws InputError "PATH: no CPU twin for a .brdf file (`what` needs one)" for a .brdf scene.
void requireTwin(const Scene& s, const std::string& what);

}  // namespace hilite::render
