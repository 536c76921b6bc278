#pragma once
// Automatic framing of the measurement view, shared by the twin-seeded search (measure_scene.cpp) and the
// blind one for .brdf files (blind_framing.cpp): find where the region {L >= frac * peak} sits in a coarse
// (L, u, v, w) render, then aim at it and zoom so it fills most of the frame.

#include "hilite/core/camera.hpp"
#include "hilite/core/image.hpp"
#include "hilite/core/math.hpp"

namespace hilite::measurement {

constexpr double kMaxFovDeg = 160.0;  ///< a pinhole image beyond ~160 deg spends its pixels on the rim
constexpr double kMinFovDeg = 1e-4;   ///< below this float directions (6e-8 rad) resolve < 30 steps a frame

/// Directions just above the horizon make the camera sit on the plane; keep it 1e-6 rad above.
dvec3 liftAboveHorizon(dvec3 c);

/// Pixel bounding box of the region (L >= frac * peak) in an (L, u, v, w) image.
struct RegionBox {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    double peak = 0;
    bool empty() const { return x1 < 0; }
};
RegionBox regionBox(const ImageF& img, double frac);
/// The same for the region L >= level (an absolute value).
RegionBox regionBoxAbove(const ImageF& img, double level);

/// Where the measurement camera looks (exitant direction at the image centre) and how wide.
struct Frame {
    dvec3 center;
    double fovDeg;
};

/// Re-aims the frame on the region's box and zooms so its half-extent is `fill` of the half-frame.
/// Returns true when the frame was already good (box within [0.5 fill, 1] of the frame, not on the border).
bool reframe(const PinholeCamera& cam, const RegionBox& box, double fill, Frame& f);

}  // namespace hilite::measurement
