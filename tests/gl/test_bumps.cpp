// The explicit micro-geometry render: GL pixels against the double twin, and the highlight of many small
// bumps approaching the analytic BRDF with the same NDF.

#include "experiments/measure_bumps.hpp"
#include "render/bumps.hpp"

#include "gl/gl_fixture.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace hilite;

namespace {

render::Scene bumpScene(double incidence, double periodPx) {
    render::Scene s;
    s.brdf.model = brdf::Model::Beckmann;
    s.brdf.roughness = 0.1;
    s.light.incidenceDeg = incidence;
    s.surface.bumps = true;
    s.surface.bumpPeriodPx = periodPx;
    s.surface.texels = 256;
    s.surface.bumpsPerTile = 16;
    return s;
}

}  // namespace

TEST_CASE("render::bumpPixelRadiance twin matches the GL bump render") {
    render::Scene s = bumpScene(45, 3.0);
    s.surface.samples = 2;
    s.brdf.fresnel = brdf::Fresnel::Schlick;
    s.brdf.f0 = {0.9, 0.6, 0.3};
    const PinholeCamera cam = experiments::measurementCamera(s, s.light.chart().wr(), 25.0, 40, 40);
    const ImageF img = test::glEnv().renderer->render(s, cam, render::Output::Color);
    double peak = 0, maxErr = 0;
    int compared = 0;
    std::vector<dvec3> twin;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            twin.push_back(render::bumpPixelRadiance(s, cam, x, y));
            peak = std::max(peak, twin.back().x);
        }
    REQUIRE(peak > 0);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const dvec3& t = twin[size_t(y * cam.width + x)];
            if (t.x < 1e-2 * peak) continue;
            ++compared;
            maxErr = std::max(maxErr, std::abs(img.pixel(x, y)[0] - t.x) / t.x);
        }
    CAPTURE(compared);
    CHECK(compared > 20);
    CHECK(maxErr < 2e-2);  // float positions on the tile and float Gaussians of a few-sigma exponent
}

TEST_CASE("experiments::measureBumps: glints at large periods, the analytic highlight's shape as bumps shrink") {
    experiments::MeasureSetup setup;
    setup.width = setup.height = 64;
    const render::Scene small = bumpScene(60, 0.5);
    const auto m = experiments::measureBumps(*test::glEnv().renderer, small, setup);
    const auto a = experiments::measureReference(experiments::analyticScene(small), setup.options);
    const auto big = experiments::measureBumps(*test::glEnv().renderer, bumpScene(60, 32), setup);
    // 32 px bumps: the half-maximum region is a glint or two, a few pixels (no highlight of the BRDF's shape);
    // half-pixel bumps: a speckled but whole highlight, its aspect near the analytic BRDF's (the experiment
    // microgeometry measures the convergence at 128^2 and smaller periods).
    CHECK(big.shape.region_pixels < 10);
    CHECK(m.shape.region_pixels > 30);
    CHECK(std::abs(m.shape.aspect - a.shape.aspect) < 0.25);
}
