#pragma once
// Pinhole camera over the plane z = 0, shared by the GL renderer (as uniforms) and the CPU twin.
// A pixel's exitant direction is minus its camera ray: for a distant light the reflected radiance
// depends on that direction alone, so the image is a map of directions.

#include "hilite/core/chart.hpp"
#include "hilite/core/math.hpp"

namespace hilite {

struct PinholeCamera {
    dvec3 position{0, 0, 1};
    dvec3 right{1, 0, 0}, up{0, 1, 0}, back{0, 0, 1};  ///< right-handed: right x up = back
    double tanHalfX = 1, tanHalfY = 1;                 ///< image half extents at unit focal distance
    int width = 1, height = 1;

    /// Camera ray (unit) through pixel (px, py), given in pixel units with centres at i + 0.5.
    dvec3 ray(double px, double py) const;
    /// Image-plane coordinates in [-1, 1] of a direction (the inverse of ray()); false if behind.
    bool project(const dvec3& ray, double& ndcX, double& ndcY) const;
    /// Solid angle of pixel (ix, iy): cos^3(gamma) * pixel area at unit focal distance.
    double pixelSolidAngle(int ix, int iy) const;

    /// The measurement view: camera on direction `center` (unit, above the plane) at `distance`
    /// from the origin, looking at it; image up is the chart's +u (towards the normal) projected,
    /// so the plane of incidence is vertical and the horizon is at the top.
    static PinholeCamera measurement(const MirrorChart& chart, const dvec3& center, double fovDeg, int width,
                                     int height, double distance = 1.0);
    /// The same view from an eye at `eye` (above the plane): the pixel at the image centre has exitant
    /// direction `center`. Under a point light the radiance depends on where the eye is.
    static PinholeCamera measurementFrom(const MirrorChart& chart, const dvec3& eye, const dvec3& center, double fovDeg,
                                         int width, int height);
    /// The photo view: a camera at `elevationDeg` above the plane and `distance` from the origin,
    /// at azimuth `azimuthDeg` (of the camera position), looking at the origin; world +z is up.
    static PinholeCamera photo(double elevationDeg, double azimuthDeg, double distance, double fovDeg, int width,
                               int height);
};

}  // namespace hilite
