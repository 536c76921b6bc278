#pragma once
// Shared pieces of the GL tests: one context per backend, and the comparison of rendered pixels
// against the CPU double twin evaluated at each pixel's exitant direction.

#include "gl/context.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/camera.hpp"
#include "render/renderer.hpp"

#include <doctest/doctest.h>

#include <ostream>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace hilite::test {

/// The backends this machine has (probed once per process).
inline const std::vector<gl::Backend>& backends() {
    static const std::vector<gl::Backend> b = gl::Context::available();
    return b;
}

/// A context + renderer on the default backend, shared by the tests of one executable.
struct GlEnv {
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<render::Renderer> renderer;
    explicit GlEnv(gl::Backend b = gl::Backend::Auto)
        : context(std::make_unique<gl::Context>(b)), renderer(std::make_unique<render::Renderer>(*context)) {}
};
inline GlEnv& glEnv() {
    static GlEnv env;
    env.context->makeCurrent();
    return env;
}

struct TwinComparison {
    int compared = 0;        ///< pixels above 1e-3 of the peak
    double maxRelError = 0;  ///< max |gl - twin| / twin over those pixels and channels
    bool allFinite = true;
    bool allNonNegative = true;
    double peak = 0;
};

/// Renders the colour output and compares every pixel whose twin value exceeds 1e-3 of the peak.
inline TwinComparison compareWithTwin(render::Renderer& r, const render::Scene& scene, const PinholeCamera& cam) {
    const ImageF img = r.render(scene, cam, render::Output::Color);
    TwinComparison out;
    std::vector<dvec3> twin(size_t(cam.width) * size_t(cam.height));
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const dvec3 we = -cam.ray(x + 0.5, y + 0.5);
            dvec3 t = we.z > 0 ? render::surfaceRadiance(scene, cam.position, we) : dvec3(0.0);
            twin[size_t(y) * size_t(cam.width) + size_t(x)] = t;
            out.peak = std::max({out.peak, t.x, t.y, t.z});
        }
    for (size_t i = 0; i < twin.size(); ++i) {
        const float* px = img.data.data() + 4 * i;
        for (int c = 0; c < 3; ++c) {
            const double g = px[c], t = twin[i][c];
            if (!std::isfinite(g)) out.allFinite = false;
            if (g < 0) out.allNonNegative = false;
            if (t > 1e-3 * out.peak) {
                out.maxRelError = std::max(out.maxRelError, std::abs(g - t) / t);
                if (c == 0) ++out.compared;
            }
        }
    }
    return out;
}

/// compareWithTwin for the material `brdf` lit at each incidence (azimuth 15 deg) and viewed about the mirror
/// direction (kept 1e-3 above the horizon) with a 20 and a 90 deg field of view (the peak, and the lobe's tails
/// out to the horizon), 96 x 64: each view's checks made (finite, non-negative, 50 pixels compared, relative
/// error below maxRelError); returns the worst relative error.
inline double checkAgainstTwinOverViews(const brdf::Params& brdf, const std::vector<double>& incidences,
                                        double maxRelError) {
    auto& env = glEnv();
    double worst = 0;
    for (double incidence : incidences)
        for (double fov : {20.0, 90.0}) {
            render::Scene s;
            s.brdf = brdf;
            s.light.incidenceDeg = incidence;
            s.light.azimuthDeg = 15.0;
            const MirrorChart chart = s.light.chart();
            dvec3 c = chart.wr();
            if (c.z < 1e-3) c = glm::normalize(dvec3(c.x, c.y, 1e-3));
            const auto r = compareWithTwin(*env.renderer, s, PinholeCamera::measurement(chart, c, fov, 96, 64));
            CAPTURE(incidence);
            CAPTURE(fov);
            CHECK(r.allFinite);
            CHECK(r.allNonNegative);
            CHECK(r.compared >= 50);
            CHECK(r.maxRelError < maxRelError);
            worst = std::max(worst, r.maxRelError);
        }
    return worst;
}

}  // namespace hilite::test
