#pragma once
// What is rendered: the plane's BRDF, a distant light, and the view.

#include "brdf/params.hpp"
#include "brdf_file/brdf_file.hpp"
#include "core/camera.hpp"
#include "core/chart.hpp"
#include "render/surface.hpp"

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

namespace hilite::render {

enum class LightType {
    Directional,  ///< distant: irradiance E from one direction, the same at every point of the plane
    Point,        ///< isotropic point: intensity I, irradiance I cos(theta) / d^2 (inverse-square law)
};
const char* toString(LightType);

/// The light: its direction from the origin by incidence theta_i and azimuth phi_i. A directional light
/// delivers irradiance E (on a surface facing it), so the plane receives E cos(theta_i); a point light
/// sits at `distance` along that direction and delivers I cos(theta) / d^2 at each point of the plane.
struct Light {
    LightType type = LightType::Directional;
    double incidenceDeg = 45.0;
    double azimuthDeg = 0.0;
    double irradiance = 1.0;  ///< directional E
    double intensity = 1.0;   ///< point I
    double distance = 10.0;   ///< point: distance from the origin
    /// The measurement chart's centre when it is not the mirror direction (a highlight framed about a peak far
    /// from it, e.g. retroreflection: experiments/peak_frame.hpp). Unset: the mirror direction.
    std::optional<dvec3> chartCenter;
    dvec3 direction() const { return sphericalDirectionDeg(incidenceDeg, azimuthDeg); }
    dvec3 position() const { return distance * direction(); }
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
/// Whether the CPU double twin can evaluate the scene (false for a .brdf file).
inline bool hasTwin(const Scene& s) { return !s.brdfFile; }
/// Throws InputError "PATH: no CPU twin for a .brdf file (`what` needs one)" for a .brdf scene.
void requireTwin(const Scene& s, const std::string& what);

}  // namespace hilite::render
