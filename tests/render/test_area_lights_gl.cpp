// Lights with size in GL: the disk's and the sphere's pixels against the exact double twin, the sphere's
// convergence to the point light (the seed's limit) with its order, the tiny disk as the directional light, and
// the sun's broadening of a narrow lobe with its diagnoses.

#include "gl/program.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/render/area_light.hpp"
#include "measurement/diagnose.hpp"
#include "render/cpu_view.hpp"
#include "render/renderer.hpp"
#include "render/shader_source.hpp"

#include "support/gl_fixture.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace hilite;

namespace {

render::Scene ggx(double alpha, double incidence) {
    render::Scene s;
    s.brdf.model = brdf::Model::GGX;
    s.brdf.roughness = alpha;
    s.light.incidenceDeg = incidence;
    return s;
}

render::Scene withDisk(render::Scene s, double angleDeg, int rings = 0) {
    s.light.type = render::LightType::Disk;
    s.light.angleDeg = angleDeg;
    s.light.rings = rings;
    return s;
}

/// Max per-pixel |a - b| / b over the pixels (luminance channel of the measurement view) above 1e-3 of b's peak.
double maxRelative(const ImageF& a, const ImageF& b) {
    double peak = 0, worst = 0;
    for (size_t i = 0; i < b.data.size(); i += 4) peak = std::max(peak, double(b.data[i]));
    for (size_t i = 0; i < b.data.size(); i += 4)
        if (b.data[i] > 1e-3 * peak) worst = std::max(worst, std::abs(double(a.data[i]) - b.data[i]) / b.data[i]);
    return worst;
}

analysis::Shape measureShape(const render::Scene& s, int size = 256) {
    measurement::MeasureSetup setup;
    setup.width = setup.height = size;
    return measurement::measureGl(*test::glEnv().renderer, s, setup).shape;
}

}  // namespace

TEST_CASE("render::Renderer a disk light's pixels equal the exact twin within 1e-4") {
    auto& env = test::glEnv();
    struct Case {
        std::string what;
        render::Scene scene;
    };
    render::Scene full = ggx(0.1, 30);
    full.brdf.geometry = brdf::Geometry::Smith;
    full.brdf.fresnel = brdf::Fresnel::Schlick;
    full.brdf.f0 = dvec3(0.9, 0.6, 0.3);
    render::Scene sphere = ggx(0.2, 50);
    sphere.light.type = render::LightType::Sphere;
    sphere.light.radius = 0.5;
    sphere.light.rings = 8;
    const std::vector<Case> cases = {
        {"GGX 0.1 + Smith + Schlick at 30 deg, the sun", withDisk(full, 0.266, 8)},
        {"GGX 0.02 at 60 deg, the sun", withDisk(ggx(0.02, 60), 0.266, 8)},
        {"GGX 0.3 at 70 deg, a 10 deg disk", withDisk(ggx(0.3, 70), 10.0, 8)},
        {"GGX 0.2 at 50 deg, sphere R 0.5 at 10", sphere},
    };
    for (const Case& c : cases) {
        CAPTURE(c.what);
        const double fov = c.scene.brdf.roughness < 0.05 ? 8.0 : 40.0;
        const PinholeCamera cam = measurement::measurementCamera(c.scene, c.scene.light.chart().wr(), fov, 64, 64);
        const test::TwinComparison t = test::compareWithTwin(*env.renderer, c.scene, cam);
        render::Scene automatic = c.scene;
        automatic.light.rings = 0;
        const test::TwinComparison a = test::compareWithTwin(*env.renderer, automatic, cam);
        MESSAGE(c.what << ": 8 rings, GL vs exact twin " << t.maxRelError << " over " << t.compared
                       << " pixels; at the " << render::lightRings(automatic)
                       << " rings chosen for 1e-3 of the peak: " << a.maxRelError);
        CHECK(t.compared > 500);
        const auto effects = render::activeEffects(c.scene);  // explain names the light and its rule
        CHECK(std::any_of(effects.begin(), effects.end(), [](const std::string& e) {
            return e.find(" light ") != std::string::npos && e.find("GL rule 8 rings") != std::string::npos;
        }));
        CHECK(t.allFinite);
        CHECK(t.maxRelError < 1e-4);
    }
}

TEST_CASE("render::Renderer a disk cut by the horizon: GL and the CPU rule agree, both converge to the exact twin") {
    auto& env = test::glEnv();
    render::Scene s = withDisk(ggx(0.3, 87), 8.0, render::kMaxRings);
    const PinholeCamera cam = measurement::measurementCamera(s, s.light.chart().wr(), 60.0, 48, 48);
    ImageF gl, cpu;
    env.renderer->render(s, cam, render::Output::Measure, gl);
    render::renderMeasureCpu(s, cam, cpu);
    const double glVsRule = maxRelative(gl, cpu);
    const test::TwinComparison exact = test::compareWithTwin(*env.renderer, s, cam);
    MESSAGE("8 deg disk at 87 deg (the horizon cuts it): GL vs CPU rule " << glVsRule << ", GL (32 rings) vs exact "
                                                                          << exact.maxRelError);
    CHECK(glVsRule < 1e-4);
    CHECK(exact.maxRelError < 1e-3);
}

TEST_CASE("render::Renderer the centre's rule (light_rings 0): GL and the CPU rule agree, whole and horizon-cut caps") {
    auto& env = test::glEnv();
    render::Scene sphere = ggx(0.3, 50);
    sphere.light.type = render::LightType::Sphere;
    sphere.light.radius = 0.3;
    sphere.light.rings = render::kCentreRule;
    const std::vector<std::pair<std::string, render::Scene>> cases = {
        {"GGX 0.3 at 60 deg, the sun", withDisk(ggx(0.3, 60), 0.266, render::kCentreRule)},
        {"GGX 0.3 at 87 deg, an 8 deg disk the horizon cuts", withDisk(ggx(0.3, 87), 8.0, render::kCentreRule)},
        {"GGX 0.3 at 50 deg, sphere R 0.3 at 10", sphere},
    };
    for (const auto& c : cases) {
        CAPTURE(c.first);
        const PinholeCamera cam = measurement::measurementCamera(c.second, c.second.light.chart().wr(), 60.0, 48, 48);
        ImageF gl, cpu;
        env.renderer->render(c.second, cam, render::Output::Measure, gl);
        render::renderMeasureCpu(c.second, cam, cpu);
        const double e = maxRelative(gl, cpu);
        MESSAGE(c.first << ": the centre's rule, GL vs CPU " << e);
        CHECK(e < 1e-4);
    }
    // A whole cap: the sun's centre rule is the directional light of the same irradiance times 2 / (1 + cos d)
    // (the cap's solid angle over its projected one), pixel for pixel.
    const render::Scene sun = cases[0].second;
    render::Scene directional = sun;
    directional.light.type = render::LightType::Directional;
    const PinholeCamera cam = measurement::measurementCamera(sun, sun.light.chart().wr(), 60.0, 48, 48);
    ImageF a, b;
    env.renderer->render(sun, cam, render::Output::Measure, a);
    env.renderer->render(directional, cam, render::Output::Measure, b);
    const float factor = float(2.0 / (1.0 + std::cos(deg2rad(0.266))));
    for (size_t i = 0; i < b.data.size(); i += 4) b.data[i] *= factor;
    CHECK(maxRelative(a, b) < 1e-5);
}

TEST_CASE(
    "render::Renderer the rule fixed in its program (the centre, 1 ring) and read from uRings agree with the CPU") {
    // llvmpipe runs a loop of uniform length as a loop: the centre's rule and 1 ring's 4 points have programs of
    // their own (HILITE_CENTRE_RULE, HILITE_RULE_RINGS 1); 2 rings and more read uRings.
    auto& env = test::glEnv();
    for (const int rings : {render::kCentreRule, 1, 2, 3}) {
        CAPTURE(rings);
        for (const render::Scene& s : {withDisk(ggx(0.1, 60), 0.266, rings), withDisk(ggx(0.3, 87), 8.0, rings)}) {
            CAPTURE(s.light.incidenceDeg);
            const std::string glsl =
                gl::joinSources(render::programSources(s, render::Output::Measure, render::shaderDirectory()).fragment);
            CHECK((glsl.find("#define HILITE_CENTRE_RULE 1") != std::string::npos) == (rings == render::kCentreRule));
            CHECK((glsl.find("#define HILITE_RULE_RINGS 1") != std::string::npos) == (rings == 1));
            const PinholeCamera cam = measurement::measurementCamera(s, s.light.chart().wr(), 40.0, 48, 48);
            ImageF gl, cpu;
            env.renderer->render(s, cam, render::Output::Measure, gl);
            render::renderMeasureCpu(s, cam, cpu);
            CHECK(maxRelative(gl, cpu) < 1e-4);
        }
    }
}

TEST_CASE("render::Renderer the sphere light converges to the point light as R -> 0, second order") {
    // Per-pixel relative error of the sphere against the point light of the same intensity and position, the
    // measurement view of GGX 0.1 at 45 deg, both at distance 10. The rule is held at 8 rings (exact to far below
    // the differences measured). Theory: the cap's mean of f cos differs from its centre's by O(alpha^2).
    auto& env = test::glEnv();
    render::Scene point = ggx(0.1, 45);
    point.light.type = render::LightType::Point;
    const PinholeCamera cam = measurement::measurementCamera(point, point.light.chart().wr(), 40.0, 96, 96);
    ImageF ref;
    env.renderer->render(point, cam, render::Output::Measure, ref);
    std::vector<double> logR, logE;
    for (double R : {0.4, 0.2, 0.1, 0.05, 0.025}) {
        render::Scene s = point;
        s.light.type = render::LightType::Sphere;
        s.light.radius = R;
        s.light.rings = 8;
        ImageF img;
        env.renderer->render(s, cam, render::Output::Measure, img);
        const double e = maxRelative(img, ref);
        MESSAGE("R = " << R << ": max per-pixel relative error " << e);
        logR.push_back(std::log(R));
        logE.push_back(std::log(e));
    }
    const double n = double(logR.size());
    const double mx = std::accumulate(logR.begin(), logR.end(), 0.0) / n,
                 my = std::accumulate(logE.begin(), logE.end(), 0.0) / n;
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < logR.size(); ++i)
        sxy += (logR[i] - mx) * (logE[i] - my), sxx += (logR[i] - mx) * (logR[i] - mx);
    const double order = sxy / sxx;
    MESSAGE("order of convergence of the sphere light to the point light: " << order);
    CHECK(order > 1.9);
    CHECK(order < 2.1);
}

TEST_CASE("measurement::measureGl a tiny disk measures as the directional light, and the sun broadens a narrow lobe") {
    for (double inc : {30.0, 60.0, 80.0}) {
        CAPTURE(inc);
        const render::Scene dir = ggx(0.1, inc);
        const analysis::Shape a = measureShape(dir), b = measureShape(withDisk(dir, 1e-4));
        CHECK_NEAR(a.aspect, b.aspect, 1e-3);
        CHECK(b.flags.empty());
        // 1e-20 deg: L = E / (pi sin^2 delta) ~ 1e43 is past float's range (before: peak 0, under_resolved).
        const analysis::Shape c = measureShape(withDisk(dir, 1e-20));
        CHECK_NEAR(a.aspect, c.aspect, 1e-3);
        CHECK(c.peak == doctest::Approx(a.peak).epsilon(1e-4));
        CHECK(c.flags.empty());
    }
    // GGX 0.02 at 80 deg: the sun's disk (0.266 deg) is comparable with the lobe's minor half-width (0.26 deg):
    // it rounds the highlight; the automatic rule's aspect is within 1e-3 of 16 rings' (the price list compares
    // both with the exact reference: experiments/accuracy_cost).
    const render::Scene road = ggx(0.02, 80);
    const analysis::Shape dir = measureShape(road), sun = measureShape(withDisk(road, 0.266)),
                          fine = measureShape(withDisk(road, 0.266, 16));
    MESSAGE("GGX 0.02 at 80: aspect " << dir.aspect << " (directional) -> " << sun.aspect << " (sun), at 16 rings "
                                      << fine.aspect);
    CHECK(sun.aspect - dir.aspect > 0.02);
    CHECK_NEAR(sun.aspect, fine.aspect, 1e-3);
    CHECK(sun.flags.empty());
}

TEST_CASE("measurement::measureGl a tiny sphere measures as the point light, in GL and the double reference") {
    render::Scene point = ggx(0.1, 45);
    point.light.type = render::LightType::Point;
    const analysis::Shape a = measureShape(point);
    // 1e-18: sin^2(alpha) = 1e-38 underflows float (before: aspect 0, peak 0, under_resolved); 1e-30: L = I /
    // (pi R^2) is past float's range too; 1e-100, the smallest radius accepted, in the reference as well.
    for (double R : {1e-18, 1e-30, 1e-100}) {
        CAPTURE(R);
        render::Scene s = point;
        s.light.type = render::LightType::Sphere;
        s.light.radius = R;
        const analysis::Shape g = measureShape(s);
        CHECK_NEAR(g.aspect, a.aspect, 1e-4);
        CHECK(g.peak == doctest::Approx(a.peak).epsilon(1e-4));
        CHECK(g.flags.empty());
        const analysis::Shape r = measurement::measureReference(s, {}).shape;
        CHECK_NEAR(r.aspect, a.aspect, 1e-3);
        CHECK(r.flags.empty());
    }
}

TEST_CASE("measurement::measureGl diagnoses: a rule too sparse for the lobe, and a mirror under the sun") {
    // GGX 2e-3 under the sun at 1 ring: the lobe falls between the 4 points of the rule.
    render::Scene s = withDisk(ggx(2e-3, 45), 0.266, 1);
    CHECK(measureShape(s, 128).has(analysis::Flag::LightUndersampled));
    // A perfect mirror reflects the sun's image, which no quadrature of a delta can draw: named, not measured.
    render::Scene mirror = withDisk(ggx(0.0, 60), 0.266);
    CHECK(measureShape(mirror, 64).has(analysis::Flag::Mirror));
}

TEST_CASE("measurement::measureGl extreme lights: a disk centred on the horizon, a sphere almost touching the plane") {
    auto& env = test::glEnv();
    // Half of a 2 deg disk lies below the horizon at theta_i = 90 deg: the rule cuts each ray there (its kink in
    // azimuth makes it converge algebraically), the exact twin integrates the visible half.
    render::Scene horizon = withDisk(ggx(0.3, 90), 2.0, 16);
    CHECK(render::capVisibleFraction(render::lightCap(horizon.light, dvec3(0.0))) ==
          doctest::Approx(0.5).epsilon(1e-5));
    const PinholeCamera cam = measurement::measurementCamera(horizon, horizon.light.chart().wr(), 60.0, 32, 32);
    ImageF gl, cpu;
    env.renderer->render(horizon, cam, render::Output::Measure, gl);
    render::renderMeasureCpu(horizon, cam, cpu);
    const test::TwinComparison exact = test::compareWithTwin(*env.renderer, horizon, cam);
    MESSAGE("2 deg disk centred on the horizon at 16 rings: GL vs CPU rule " << maxRelative(gl, cpu) << ", GL vs exact "
                                                                             << exact.maxRelError);
    CHECK(maxRelative(gl, cpu) < 1e-4);
    CHECK(exact.maxRelError < 2e-3);
    // (Measured as a whole by `hilite measure --light disk --light-angle 2 --incidence 90` in ~3 s: the survey of
    // the hemisphere integrates the cut disk exactly at every sample; here its pixels suffice.)
    // A sphere of radius 1.7 whose centre is 1.74 above the plane: from below it the cap is 78 deg wide, a GGX 0.1
    // lobe a few degrees across inside it, far between 16 rings' nodes: named, not measured silently.
    render::Scene sphere = ggx(0.1, 80);
    sphere.light.type = render::LightType::Sphere;
    sphere.light.radius = 1.7;
    sphere.light.rings = 4;
    const render::RuleCheck rule = render::lightRule(sphere);
    MESSAGE("sphere R 1.7 at 80 deg, 4 rings: rule error " << rule.error << " of the peak");
    CHECK(rule.error >
          measurement::kLightRuleFlag);  // what diagnose() turns into the flag (the test above measures it)
}

TEST_CASE("render::Renderer linearly transformed cosines: GL equals its double twin (the framing's) within 1e-3") {
    // Measured: 8.3e-5 (the sun on GGX 0.1 at 60 deg), 6.7e-5 (GGX 0.02 at 80), 3.6e-5 (a sphere), 4.5e-5 (an 8 deg
    // disk the horizon cuts: the shader's clipped path), 2.1e-6 (a 0.01 deg disk and one of 1e-30 deg, drawn as the
    // lobe at the cap's centre times its solid angle; 1 - cos(1e-30 deg) is 0 in float).
    // Their error against the exact light: tests/render/test_ltc.cpp and docs/speed.md.
    auto& env = test::glEnv();
    struct Case {
        std::string what;
        render::Scene scene;
    };
    render::Scene sphere = ggx(0.1, 50);  // two fits in all (each ~1 s)
    sphere.light.type = render::LightType::Sphere;
    sphere.light.radius = 0.5;
    const std::vector<Case> cases = {
        {"GGX 0.1 at 60 deg, the sun", withDisk(ggx(0.1, 60), 0.266)},
        {"GGX 0.02 at 80 deg, the sun", withDisk(ggx(0.02, 80), 0.266)},
        {"GGX 0.1 at 50 deg, sphere R 0.5 at 10", sphere},
        {"GGX 0.1 at 86 deg, an 8 deg disk the horizon cuts (the clipped path)", withDisk(ggx(0.1, 86), 8.0)},
        {"GGX 0.1 at 60 deg, a 0.01 deg disk (a point of the lobe)", withDisk(ggx(0.1, 60), 0.01)},
        {"GGX 0.1 at 60 deg, a 1e-30 deg disk (1 - cos is 0 in float)", withDisk(ggx(0.1, 60), 1e-30)},
    };
    for (Case c : cases) {
        CAPTURE(c.what);
        c.scene.light.ltc = true;
        const double fov = c.scene.brdf.roughness < 0.05 ? 8.0 : 40.0;
        const PinholeCamera cam = measurement::measurementCamera(c.scene, c.scene.light.chart().wr(), fov, 64, 64);
        const test::TwinComparison twin = test::compareWithTwin(*env.renderer, render::withRuleTwin(c.scene), cam);
        MESSAGE(c.what << ": LTC in GL vs its double twin " << twin.maxRelError << " over " << twin.compared
                       << " pixels (per pixel, relative)");
        CHECK(twin.compared > 500);
        CHECK(twin.allFinite);
        CHECK(twin.allNonNegative);
        CHECK(twin.maxRelError < 1e-3);
        const auto effects = render::activeEffects(c.scene);  // explain names the rule that runs
        CHECK(std::any_of(effects.begin(), effects.end(), [](const std::string& e) {
            return e.find("linearly transformed cosines") != std::string::npos;
        }));
    }
}
