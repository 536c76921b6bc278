#include "hilite/core/camera.hpp"

namespace hilite {

namespace {

PinholeCamera lookAt(const dvec3& position, const dvec3& target, const dvec3& upHint, double fovDeg, int width,
                     int height) {
    PinholeCamera cam;
    cam.position = position;
    cam.back = glm::normalize(position - target);
    dvec3 up = upHint - glm::dot(upHint, cam.back) * cam.back;
    // Looking straight along the hint (photo view from overhead): any perpendicular up will do.
    if (glm::length(up) < 1e-9) up = std::abs(cam.back.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    cam.up = glm::normalize(up - glm::dot(up, cam.back) * cam.back);
    cam.right = glm::cross(cam.up, cam.back);
    cam.width = width;
    cam.height = height;
    cam.tanHalfX = std::tan(deg2rad(fovDeg) * 0.5);  // the field of view spans the image width
    cam.tanHalfY = cam.tanHalfX * double(height) / double(width);
    return cam;
}

}  // namespace

dvec3 PinholeCamera::ray(double px, double py) const {
    const double x = (2.0 * px / width - 1.0) * tanHalfX;
    const double y = (2.0 * py / height - 1.0) * tanHalfY;
    return glm::normalize(-back + x * right + y * up);
}

bool PinholeCamera::project(const dvec3& r, double& ndcX, double& ndcY) const {
    const double depth = -glm::dot(r, back);
    if (depth <= 0.0) return false;
    ndcX = glm::dot(r, right) / depth / tanHalfX;
    ndcY = glm::dot(r, up) / depth / tanHalfY;
    return true;
}

double PinholeCamera::pixelSolidAngle(int ix, int iy) const {
    const double x = (2.0 * (ix + 0.5) / width - 1.0) * tanHalfX;
    const double y = (2.0 * (iy + 0.5) / height - 1.0) * tanHalfY;
    const double cosGamma = 1.0 / std::sqrt(1.0 + x * x + y * y);
    const double pixelArea = (2.0 * tanHalfX / width) * (2.0 * tanHalfY / height);
    return cosGamma * cosGamma * cosGamma * pixelArea;
}

PinholeCamera PinholeCamera::measurement(const MirrorChart& chart, const dvec3& center, double fovDeg, int width,
                                         int height, double distance) {
    return lookAt(distance * center, dvec3(0.0), chart.eu(), fovDeg, width, height);
}

PinholeCamera PinholeCamera::measurementFrom(const MirrorChart& chart, const dvec3& eye, const dvec3& center,
                                             double fovDeg, int width, int height) {
    return lookAt(eye, eye - center, chart.eu(), fovDeg, width, height);
}

PinholeCamera PinholeCamera::photo(double elevationDeg, double azimuthDeg, double distance, double fovDeg, int width,
                                   int height) {
    const dvec3 dir = sphericalDirectionDeg(90.0 - elevationDeg, azimuthDeg);
    return lookAt(distance * dir, dvec3(0.0), dvec3(0, 0, 1), fovDeg, width, height);
}

}  // namespace hilite
