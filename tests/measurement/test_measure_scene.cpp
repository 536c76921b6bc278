// The highlight measured through GL against theory, the reference table of
// ../shared/notes/measurement.md, and the CPU double reference.

#include "hilite/measurement/measure_scene.hpp"

#include "support/gl_fixture.hpp"
#include "support/scenes.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>

using namespace hilite;
using test::makeScene;

namespace {

measurement::Measurement glMeasure(const render::Scene& s, measurement::MeasureSetup setup = {}) {
    return measurement::measureGl(*test::glEnv().renderer, s, setup);
}

}  // namespace

TEST_CASE("measurement::measureGl Phong reflection lobe stays circular") {
    for (double inc = 0; inc <= 80; inc += 10) {
        CAPTURE(inc);
        const auto m = glMeasure(makeScene(brdf::Model::Phong, 1000, inc));
        CHECK_NEAR(m.shape.aspect, 1.0, 0.005);
        CHECK(m.shape.flags.empty());
        CHECK(m.renders <= 5);
    }
}

TEST_CASE("measurement::measureGl GGX NDF lobe matches the reference table") {
    // ../shared/notes/measurement.md: GGX alpha = 0.1, f proportional to D, frac = 0.5.
    struct Row {
        double inc, aspect, major, minor;
    };
    for (const Row r : {Row{0, 1.00000, 7.4175, 7.4175}, Row{30, 0.86593, 7.4170, 6.4226},
                        Row{60, 0.50173, 7.4059, 3.7158}, Row{75, 0.26404, 7.3636, 1.9443}}) {
        CAPTURE(r.inc);
        const auto m = glMeasure(makeScene(brdf::Model::GGX, 0.1, r.inc));
        CHECK_NEAR(m.shape.aspect, r.aspect, 0.005);
        CHECK_NEAR(m.shape.major_deg / r.major, 1.0, 0.01);
        CHECK_NEAR(m.shape.minor_deg / r.minor, 1.0, 0.01);
    }
}

TEST_CASE("measurement::measureGl narrow microfacet lobes narrow as cos theta_i") {
    for (const auto& lobe : {std::pair{brdf::Model::Blinn, 5000.0}, {brdf::Model::Beckmann, 0.02}}) {
        const brdf::Model model = lobe.first;  // (clang: no CAPTURE of structured bindings)
        const double param = lobe.second;
        for (double inc = 0; inc <= 75; inc += 15) {
            const double parameter = param;
            CAPTURE(inc);
            CAPTURE(parameter);
            const auto m = glMeasure(makeScene(model, param, inc));
            CHECK(m.shape.major_deg <= 3.0);
            CHECK_NEAR(m.shape.aspect, std::cos(deg2rad(inc)), 0.02);
        }
    }
}

TEST_CASE("measurement::measureGl eccentricity rises monotonically for microfacet lobes") {
    for (auto [model, param] :
         {std::pair{brdf::Model::GGX, 0.1}, {brdf::Model::Beckmann, 0.1}, {brdf::Model::Blinn, 200.0}}) {
        double previous = -1;
        for (double inc = 0; inc <= 85; inc += 5) {
            const auto m = glMeasure(makeScene(model, param, inc));
            CAPTURE(inc);
            CHECK(m.shape.eccentricity > previous);
            previous = m.shape.eccentricity;
        }
    }
}

TEST_CASE("measurement::measureGl agrees with the CPU double reference") {
    for (const auto& lobe : {std::pair{brdf::Model::Phong, 300.0},
                             {brdf::Model::Blinn, 300.0},
                             {brdf::Model::Beckmann, 0.15},
                             {brdf::Model::GGX, 0.2}}) {
        const brdf::Model model = lobe.first;
        const double param = lobe.second;
        for (double inc : {0.0, 20.0, 45.0, 70.0, 80.0}) {
            for (auto g : {brdf::Geometry::Implicit, brdf::Geometry::Smith}) {
                render::Scene s = makeScene(model, param, inc);
                s.brdf.geometry = g;
                const auto m = glMeasure(s);
                const auto r = measurement::measureReference(s, {});
                const std::string modelName = brdf::toString(model);
                CAPTURE(modelName);
                CAPTURE(inc);
                CHECK_NEAR(m.shape.aspect, r.shape.aspect, 0.005);
                CHECK_NEAR(m.shape.major_deg / r.shape.major_deg, 1.0, 0.01);
            }
        }
    }
}

TEST_CASE("measurement::measureGl converges to the reference as resolution grows") {
    const render::Scene s = makeScene(brdf::Model::GGX, 0.1, 60);
    const auto ref = measurement::measureReference(s, {});
    std::vector<double> errors;
    for (int size : {32, 64, 128, 256, 512}) {
        measurement::MeasureSetup setup;
        setup.width = setup.height = size;
        setup.options.subpixel = false;  // the plain pixel in/out definition converges too, just slower
        const auto m = glMeasure(s, setup);
        errors.push_back(std::abs(m.shape.minor_deg - ref.shape.minor_deg) / ref.shape.minor_deg);
    }
    CAPTURE(errors[0]);
    CAPTURE(errors.back());
    CHECK(errors.back() < errors.front() / 4);
    CHECK(errors.back() < 2e-3);
}

TEST_CASE("measurement::measureGl diagnostics") {
    SUBCASE("cut by the horizon: GGX alpha 0.3 at 85 degrees") {
        CHECK(glMeasure(makeScene(brdf::Model::GGX, 0.3, 85)).shape.has(analysis::Flag::HorizonCut));
    }
    SUBCASE("under-resolved: fixed framing, size 32, a narrow lobe") {
        measurement::MeasureSetup setup;
        setup.fovDeg = 30;
        setup.width = setup.height = 32;
        CHECK(glMeasure(makeScene(brdf::Model::Blinn, 1e5, 30), setup).shape.has(analysis::Flag::UnderResolved));
    }
    SUBCASE("no highlight: the light at exactly 90 degrees") {
        const auto m = glMeasure(makeScene(brdf::Model::GGX, 0.1, 90));
        CHECK(m.shape.has(analysis::Flag::NoHighlight));
        CHECK(m.shape.peak == 0.0);
    }
    SUBCASE("clipped: fixed framing too tight") {
        measurement::MeasureSetup setup;
        setup.fovDeg = 5;
        CHECK(glMeasure(makeScene(brdf::Model::GGX, 0.1, 30), setup).shape.has(analysis::Flag::Clipped));
    }
    SUBCASE("automatic framing is not clipped and takes few renders") {
        const auto m = glMeasure(makeScene(brdf::Model::Beckmann, 0.05, 60));
        CHECK_FALSE(m.shape.has(analysis::Flag::Clipped));
        CHECK(m.renders <= 3);
    }
}

TEST_CASE("measurement::measureGl point light: the eye's view, against the reference and the distant limit") {
    render::Scene s = makeScene(brdf::Model::GGX, 0.1, 45);
    s.light.type = render::LightType::Point;
    s.light.distance = 3;
    s.eyeDistance = 3;
    const auto m = glMeasure(s);
    const auto r = measurement::measureReference(s, {});
    CHECK_NEAR(m.shape.aspect, r.shape.aspect, 0.005);
    CHECK_NEAR(m.shape.major_deg / r.shape.major_deg, 1.0, 0.01);
    // Light and eye at the same distance: both directions turn as the eye's ray moves along the plane,
    // so the half vector moves half as fast and the highlight spans about half the angle.
    const auto directional = glMeasure(makeScene(brdf::Model::GGX, 0.1, 45));
    CHECK(m.shape.major_deg < 0.6 * directional.shape.major_deg);
    // A point light far away (intensity scaled with d^2) is a distant light.
    s.light.distance = 1e6;
    s.light.intensity = 1e12;
    const auto far = glMeasure(s);
    CHECK_NEAR(far.shape.aspect, directional.shape.aspect, 1e-3);
    CHECK_NEAR(far.shape.major_deg / directional.shape.major_deg, 1.0, 1e-3);
    CHECK_NEAR(far.shape.peak / directional.shape.peak, 1.0, 1e-3);
}

TEST_CASE("measurement::measureGl automatic framing fits non-square frames") {
    render::Scene s = makeScene(brdf::Model::GGX, 0.08, 70);
    s.brdf.geometry = brdf::Geometry::Smith;
    for (auto [w, h] : {std::pair{384, 256}, {256, 384}, {512, 128}}) {
        measurement::MeasureSetup setup;
        setup.width = w;
        setup.height = h;
        const auto m = glMeasure(s, setup);
        const int width = w;
        CAPTURE(width);
        CHECK_FALSE(m.shape.has(analysis::Flag::Clipped));
        CHECK_NEAR(m.shape.aspect, measurement::measureReference(s, {}).shape.aspect, 0.005);
    }
}
