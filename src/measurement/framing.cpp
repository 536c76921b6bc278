#include "measurement/framing.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::measurement {

dvec3 liftAboveHorizon(dvec3 c) {
    if (c.z < 1e-6) c = glm::normalize(dvec3(c.x, c.y, 1e-6));
    return c;
}

namespace {

RegionBox boxAbove(const ImageF& img, double frac, double level) {
    RegionBox b;
    for (size_t i = 0; i < img.data.size(); i += 4) b.peak = std::max(b.peak, double(img.data[i]));
    if (!(b.peak > 0)) return b;
    const double t = level > 0 ? level : frac * b.peak;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.pixel(x, y)[0] >= t) {
                b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x);
                b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
            }
    return b;
}

}  // namespace

RegionBox regionBox(const ImageF& img, double frac) { return boxAbove(img, frac, 0.0); }
RegionBox regionBoxAbove(const ImageF& img, double level) { return boxAbove(img, 0.0, level); }

bool reframe(const PinholeCamera& cam, const RegionBox& box, double fill, Frame& f) {
    const bool onBorder = box.x0 == 0 || box.y0 == 0 || box.x1 == cam.width - 1 || box.y1 == cam.height - 1;
    // Box centre and half-extent in image-plane units (unit focal distance), pixel edges included.
    const double cx = 0.5 * (box.x0 + box.x1 + 1), cy = 0.5 * (box.y0 + box.y1 + 1);
    const double hx = 0.5 * (box.x1 - box.x0 + 1) * 2.0 * cam.tanHalfX / cam.width;
    const double hy = 0.5 * (box.y1 - box.y0 + 1) * 2.0 * cam.tanHalfY / cam.height;
    const double half = std::max(hx / cam.tanHalfX, hy / cam.tanHalfY);  // fraction of the half-frame
    if (onBorder) {
        f.fovDeg = std::min(kMaxFovDeg, 2.0 * rad2deg(std::atan(2.0 * cam.tanHalfX)));
        f.center = liftAboveHorizon(-cam.ray(cx, cy));
        return false;
    }
    const bool good = half >= 0.5 * fill && half <= 1.0;
    f.center = liftAboveHorizon(-cam.ray(cx, cy));
    const double tanHalf = std::max(hx, hy * cam.tanHalfX / cam.tanHalfY) / fill;
    f.fovDeg = std::clamp(2.0 * rad2deg(std::atan(tanHalf)), kMinFovDeg, kMaxFovDeg);
    return good;
}

}  // namespace hilite::measurement
