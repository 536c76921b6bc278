// The scene rows' runners: both outputs at every pixel of the row's camera (GL against the double twin),
// and the measurement of each path.

#include "hard/hard_cases.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "measurement/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace hilite::hard {

namespace {

constexpr double kCompareFloor = 1e-3;  ///< pixels above this fraction of the peak are compared (as gl_fixture.hpp)

PinholeCamera rowCamera(const SceneCase& c) {
    const render::Scene& s = c.scene;
    const Camera& k = c.camera;
    const dvec3 wr = s.light.chart().wr();
    switch (k.view) {
        case View::Lobe: {
            // The seed of automatic framing (measurement::measureGl): the twin's half-width fills 0.8 of the frame.
            const double r = measurement::twinHalfWidth(s, c.setup.options.threshold);
            const double fov = std::clamp(2.0 * rad2deg(std::atan(std::tan(std::min(r, 1.3)) / 0.8)), 1e-4, 160.0);
            return measurement::measurementCamera(s, wr, fov, k.size, k.size);
        }
        case View::Fixed: return measurement::measurementCamera(s, wr, k.fovDeg, k.size, k.size);
        case View::Photo:
            return PinholeCamera::photo(k.elevationDeg, s.light.azimuthDeg + 180.0, s.eyeDistance, k.fovDeg, k.size,
                                        k.size);
    }
    return {};
}

/// The double twin of one pixel of both outputs: colour (R, G, B, 1) and measurement (L, u, v, w), both 0
/// where the pixel sees no lit side of the plane (sky, the plane from below, or the horizon), as the shader.
struct TwinPixel {
    glm::dvec4 color{0.0}, meas{0.0};
    bool visible = false;
};

TwinPixel twinPixel(const render::Scene& s, const MirrorChart& chart, const PinholeCamera& cam, int x, int y) {
    TwinPixel p;
    const dvec3 we = -cam.ray(x + 0.5, y + 0.5);
    if (!(cam.position.z > 0.0 && we.z > 0.0)) return p;  // from above, a ray going down meets the plane
    const dvec3 rgb = render::surfaceRadiance(s, cam.position, we);
    const dvec2 uv = chart.coords(we);
    p.color = {rgb, 1.0};
    p.meas = {brdf::luminance(rgb), uv.x, uv.y, chart.areaPerSolidAngle(we) * cam.pixelSolidAngle(x, y)};
    p.visible = true;
    return p;
}

void countValue(PixelCheck& k, double v, bool mustBeNonNegative) {
    ++k.values;
    if (!std::isfinite(v)) ++k.nonFinite;
    else if (mustBeNonNegative && v < 0) ++k.negative;
}

double relative(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

double widthOf(const SceneCase& c) { return measurement::twinLobeWidths(c.scene, c.setup.options.threshold).minor; }

}  // namespace

double pixelTolerance(double minorHalfWidth) {
    if (!(minorHalfWidth > 0)) return 1e-4;  // no lobe at the mirror direction, or no width of its own
    // Narrower than float directions resolve: GL flags it effectively_mirror and claims no agreement.
    if (minorHalfWidth < measurement::kEffectivelyMirrorHalfWidth) return INFINITY;
    return std::max(1e-4, 16.0 * measurement::kFloatDirectionStep / minorHalfWidth);
}

SceneOutcome runSceneGl(render::Renderer& renderer, const SceneCase& c) {
    SceneOutcome out;
    const PinholeCamera cam = rowCamera(c);
    const MirrorChart chart = c.scene.light.chart();
    const ImageF color = renderer.render(c.scene, cam, render::Output::Color);
    const ImageF meas = renderer.render(c.scene, cam, render::Output::Measure);
    std::vector<TwinPixel> twin;
    double peakColor = 0, peakL = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            twin.push_back(twinPixel(c.scene, chart, cam, x, y));
            const TwinPixel& t = twin.back();
            peakColor = std::max({peakColor, t.color.x, t.color.y, t.color.z});
            peakL = std::max(peakL, t.meas.x);
        }
    PixelCheck& k = out.pixels;
    for (size_t i = 0; i < twin.size(); ++i) {
        const float* g = color.data.data() + 4 * i;
        const float* m = meas.data.data() + 4 * i;
        for (int j = 0; j < 4; ++j) countValue(k, g[j], true);
        for (int j = 0; j < 4; ++j) countValue(k, m[j], j == 0 || j == 3);  // L and w; u, v have signs
        const TwinPixel& t = twin[i];
        if (!t.visible || g[3] != 1.f || !(m[3] > 0.f)) continue;  // only where both see the lit plane
        bool compared = false;
        for (int j = 0; j < 3; ++j)
            if (t.color[j] > kCompareFloor * peakColor) {
                k.maxRelError = std::max(k.maxRelError, relative(g[j], t.color[j]));
                compared = true;
            }
        if (t.meas.x > kCompareFloor * peakL) {
            k.maxRelError = std::max(k.maxRelError, relative(m[0], t.meas.x));
            compared = true;
        }
        k.compared += compared;
        k.maxUvError = std::max({k.maxUvError, std::abs(m[1] - t.meas.y), std::abs(m[2] - t.meas.z)});
        k.maxWeightError = std::max(k.maxWeightError, relative(m[3], t.meas.w));
    }
    out.measurement = measurement::measureGl(renderer, c.scene, c.setup);
    out.minorHalfWidth = widthOf(c);
    out.tolerance = c.tolerance > 0 ? c.tolerance : pixelTolerance(out.minorHalfWidth);
    return out;
}

SceneOutcome runSceneDouble(const SceneCase& c) {
    SceneOutcome out;
    const PinholeCamera cam = rowCamera(c);
    const MirrorChart chart = c.scene.light.chart();
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const TwinPixel t = twinPixel(c.scene, chart, cam, x, y);
            for (int j = 0; j < 4; ++j) countValue(out.pixels, t.color[j], true);
            for (int j = 0; j < 4; ++j) countValue(out.pixels, t.meas[j], j == 0 || j == 3);
        }
    out.measurement = measurement::measureReference(c.scene, c.setup.options);
    out.minorHalfWidth = widthOf(c);
    return out;
}

bool shapeFinite(const analysis::Shape& s) {
    if (analysis::unmeasured(s)) return true;  // float_overflow/underflow: NaN on purpose (null in the row)
    for (double v : {s.peak, s.peak_u_deg, s.peak_v_deg, s.aspect, s.eccentricity, s.major_deg, s.minor_deg,
                     s.orientation_deg, s.centroid_u_deg, s.centroid_v_deg, s.area_deg2})
        if (!std::isfinite(v)) return false;
    // peak_on_horizon: a width whose line leaves the hemisphere at the peak is NaN on purpose (null in the row)
    for (double v : {s.fwhm_u_deg, s.fwhm_v_deg})
        if (!std::isfinite(v) && !(std::isnan(v) && s.has(analysis::Flag::PeakOnHorizon))) return false;
    return true;
}

bool numbersOrDiagnosis(const analysis::Shape& s) {
    using analysis::Flag;
    if (s.has(Flag::NoHighlight) || s.has(Flag::Mirror) || s.has(Flag::UnderResolved) || analysis::unmeasured(s))
        return true;
    return s.peak > 0 && s.major_deg > 0;
}

std::string flagList(const analysis::FlagSet& flags) {
    std::ostringstream s;
    const char* sep = "";
    for (analysis::Flag f : flags) s << std::exchange(sep, ", ") << analysis::toString(f);
    return flags.empty() ? "none" : s.str();
}

}  // namespace hilite::hard
