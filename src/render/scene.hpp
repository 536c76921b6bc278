#pragma once
// What is rendered: the plane's BRDF, a distant light, and the view.

#include "brdf/params.hpp"
#include "core/camera.hpp"
#include "core/chart.hpp"

#include <iosfwd>

namespace hilite::render {

/// A distant (directional) light: direction by incidence theta_i and azimuth phi_i, irradiance E on a
/// surface facing it. The plane receives E cos(theta_i).
struct DirectionalLight {
    double incidenceDeg = 45.0;
    double azimuthDeg = 0.0;
    double irradiance = 1.0;
    dvec3 direction() const { return sphericalDirectionDeg(incidenceDeg, azimuthDeg); }
    MirrorChart chart() const { return MirrorChart::fromDegrees(incidenceDeg, azimuthDeg); }
};

struct Scene {
    brdf::Params brdf;
    DirectionalLight light;
};

std::ostream& operator<<(std::ostream&, const Scene&);

}  // namespace hilite::render
