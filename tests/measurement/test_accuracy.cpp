// The accuracy knobs against the double reference: the CPU double path against GL, the crop,
// size and supersampling, and --tolerance. Numbers only: nothing here is timed.

#include "hilite/measurement/measure_scene.hpp"
#include "measurement/tolerance.hpp"
#include "render/cpu_view.hpp"

#include "support/gl_fixture.hpp"
#include "support/scenes.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>

using namespace hilite;
using test::makeScene;

namespace {

/// The hard and the ordinary: narrow lobes, grazing incidence, a horizon cut.
std::vector<render::Scene> scenes() {
    return {makeScene(brdf::Model::GGX, 0.1, 60), makeScene(brdf::Model::GGX, 0.02, 80),
            makeScene(brdf::Model::GGX, 0.02, 85), makeScene(brdf::Model::Phong, 1e4, 60),
            makeScene(brdf::Model::Beckmann, 0.3, 75)};
}

double aspectError(const measurement::Measurement& m, const render::Scene& s) {
    return std::abs(m.shape.aspect - measurement::measureReference(s, {}).shape.aspect);
}

measurement::MeasureSetup sized(int size) {
    measurement::MeasureSetup setup;
    setup.width = setup.height = size;
    return setup;
}

}  // namespace

// The chart in GLSL is a polynomial, not llvmpipe's atan (shade.frag, chartCoords): u, v and the pixel's area
// as the double chart has them to float's rounding, in narrow frames and in a 110 deg one (measured with atan:
// u, v 1.4e-4 px and w 2.1e-5 off; with the polynomial 7e-5 px (float rays) and 6e-7).
TEST_CASE("render::renderMeasureCpu gives the GL measurement view's pixels") {
    render::Renderer& r = *test::glEnv().renderer;
    struct Case {
        render::Scene s;
        double fov;
    };
    for (const Case& k :
         {Case{makeScene(brdf::Model::GGX, 0.1, 60), 30.0}, Case{makeScene(brdf::Model::Phong, 1e4, 30), 3.0},
          Case{makeScene(brdf::Model::GGX, 0.5, 20), 110.0}}) {
        const render::Scene& s = k.s;
        for (const dvec2 jitter : {dvec2(0.0), dvec2(0.375, -0.125)}) {
            CAPTURE(s);
            CAPTURE(jitter.x);
            const double fov = k.fov;
            const PinholeCamera cam = measurement::measurementCamera(s, s.light.chart().wr(), fov, 48, 40);
            const PixelRect crop{5, 7, 30, 25};
            ImageF gl, cpu;
            r.render(s, cam, render::Output::Measure, gl, jitter, crop);
            render::renderMeasureCpu(s, cam, cpu, jitter, crop, 2);
            REQUIRE(gl.width == 30);
            REQUIRE(cpu.height == 25);
            double peak = 0;
            for (size_t i = 0; i < cpu.data.size(); i += 4) peak = std::max(peak, double(cpu.data[i]));
            double worstL = 0, worstUV = 0, worstW = 0;
            for (size_t i = 0; i < cpu.data.size(); i += 4) {
                if (cpu.data[i + 3] == 0.f) {
                    CHECK(gl.data[i + 3] == 0.f);  // the same pixels see the sky
                    continue;
                }
                if (cpu.data[i] > 1e-3 * peak)
                    worstL = std::max(worstL, std::abs(double(gl.data[i]) / cpu.data[i] - 1.0));
                worstUV = std::max({worstUV, std::abs(double(gl.data[i + 1]) - cpu.data[i + 1]),
                                    std::abs(double(gl.data[i + 2]) - cpu.data[i + 2])});
                worstW = std::max(worstW, std::abs(double(gl.data[i + 3]) / cpu.data[i + 3] - 1.0));
            }
            const double pitch = 2.0 * cam.tanHalfX / cam.width;  // about a pixel's width in (u, v)
            CHECK(worstL < 1e-4);
            CHECK(worstUV < 2e-4 * pitch);  // float rays
            CHECK(worstW < 3e-6);
            MESSAGE("GL vs CPU view, fov " << fov << ": L " << worstL << ", u v " << worstUV / pitch << " px, w "
                                           << worstW);
        }
    }
}

TEST_CASE("measurement::measureCpu agrees with measureGl") {
    for (const render::Scene& s : scenes()) {
        CAPTURE(s);
        const auto gl = measurement::measureGl(*test::glEnv().renderer, s, sized(256));
        const auto cpu = measurement::measureCpu(s, sized(256));
        CHECK_NEAR(gl.shape.aspect, cpu.shape.aspect, 0.005);
        CHECK_NEAR(gl.shape.aspect, cpu.shape.aspect, 1e-4);  // what it actually is: float vs double pixels
        CHECK(gl.shape.flags == cpu.shape.flags);
    }
}

TEST_CASE("measurement::measureGl the crop changes the time, not the numbers") {
    for (const render::Scene& s : scenes()) {
        CAPTURE(s);
        measurement::MeasureSetup whole = sized(256);
        whole.crop = false;
        const auto a = measurement::measureGl(*test::glEnv().renderer, s, sized(256));
        const auto b = measurement::measureGl(*test::glEnv().renderer, s, whole);
        CHECK(a.shadedPixels < b.shadedPixels);
        CHECK(a.shape.aspect == doctest::Approx(b.shape.aspect).epsilon(1e-9));
        CHECK(a.shape.major_deg == doctest::Approx(b.shape.major_deg).epsilon(1e-9));
        CHECK(a.shape.minor_deg == doctest::Approx(b.shape.minor_deg).epsilon(1e-9));
        CHECK(a.shape.flags == b.shape.flags);
    }
}

TEST_CASE("measurement::measureGl size and supersampling reduce the error against the reference") {
    render::Renderer& r = *test::glEnv().renderer;
    SUBCASE("size, sub-pixel boundary (second order)") {
        for (const render::Scene& s : {makeScene(brdf::Model::GGX, 0.1, 60), makeScene(brdf::Model::GGX, 0.02, 80)}) {
            CAPTURE(s);
            const double e64 = aspectError(measurement::measureGl(r, s, sized(64)), s);
            const double e256 = aspectError(measurement::measureGl(r, s, sized(256)), s);
            CHECK(e256 < e64 / 4);
        }
    }
    SUBCASE("supersampling, against the pixel boundary it replaces") {
        const render::Scene s = makeScene(brdf::Model::GGX, 0.1, 60);
        measurement::MeasureSetup pixel = sized(128);
        pixel.options.subpixel = false;
        measurement::MeasureSetup ss4 = pixel;
        ss4.supersample = 4;
        const auto m = measurement::measureGl(r, s, ss4);
        CHECK(m.renders == 1 + 16);  // one aiming render, 16 jittered
        CHECK(aspectError(m, s) < aspectError(measurement::measureGl(r, s, pixel), s) / 2);
    }
}

TEST_CASE("measurement::measureToTolerance") {
    for (const double tolerance : {1e-2, 1e-3}) {
        for (const render::Scene& s : scenes()) {
            CAPTURE(s);
            CAPTURE(tolerance);
            measurement::ToleranceSetup t;
            t.tolerance = tolerance;
            const auto res = measurement::measureToTolerance(test::glEnv().renderer.get(), s, t);
            CHECK(res.met);
            CHECK(res.errorEstimate <= tolerance);
            CHECK(aspectError(res.measurement, s) <= tolerance);
            CHECK(res.checkSetup.width > res.setup.width);  // checked against a finer size
        }
    }
    SUBCASE("a tighter tolerance never picks a coarser size") {
        const render::Scene s = makeScene(brdf::Model::GGX, 0.02, 80);
        measurement::ToleranceSetup t;
        t.tolerance = 1e-2;
        const int coarse = measurement::measureToTolerance(test::glEnv().renderer.get(), s, t).setup.width;
        t.tolerance = 1e-4;
        CHECK(measurement::measureToTolerance(test::glEnv().renderer.get(), s, t).setup.width >= coarse);
    }
}
