// Retroreflection: a lobe about the light direction, 2 theta_i from the mirror direction. The
// automatic framing finds its peak and measures the highlight about it; ordinary lobes stay about the mirror.

#include "brdf/ndf_table.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "measurement/peak_frame.hpp"

#include "support/gl_fixture.hpp"
#include "support/scenes.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>

using namespace hilite;

namespace {

/// The shared test scene (support/scenes.hpp) with the light at azimuth 25 deg.
render::Scene makeScene(brdf::Model m, double param, double incidence) {
    render::Scene s = test::makeScene(m, param, incidence);
    s.light.azimuthDeg = 25.0;
    return s;
}

double angleDeg(const dvec3& a, const dvec3& b) {
    return rad2deg(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

}  // namespace

TEST_CASE("measurement::findPeak and frameAboutPeak") {
    SUBCASE("retroreflection: the peak is the light direction; framed about it beyond a lobe width from the mirror") {
        for (double inc : {10.5, 30.0, 60.0, 75.0}) {
            const render::Scene s = makeScene(brdf::Model::Retro, 1000, inc);
            const auto p = measurement::findPeak(s);
            CAPTURE(inc);
            CHECK(angleDeg(p.direction, s.light.direction()) < 1e-6);
            CHECK(p.offsetDeg == doctest::Approx(2 * inc).epsilon(1e-9));
            const auto framed = measurement::frameAboutPeak(s, 0.5);
            REQUIRE(framed);
            CHECK(angleDeg(framed->light.chart().wr(), s.light.direction()) < 1e-6);
            CHECK(angleDeg(framed->light.direction(), s.light.direction()) == 0.0);  // the light itself stays
            double offset = 0;
            CHECK(measurement::framedAbout(s, 0.5, offset).find("retroreflection") != std::string::npos);
            CHECK(offset == doctest::Approx(2 * inc).epsilon(1e-9));
        }
        // At 0.5 deg the peak (1 deg from the mirror) is inside a lobe of half-width 2.13 deg about the mirror
        // direction, at normal incidence the two coincide, and up to 20 deg away (theta_i = 10) the chart about
        // the mirror direction measures the lobe with less than 2% stretch: nothing to reframe.
        CHECK_FALSE(measurement::frameAboutPeak(makeScene(brdf::Model::Retro, 1000, 0.5), 0.5));
        CHECK_FALSE(measurement::frameAboutPeak(makeScene(brdf::Model::Retro, 1000, 0.0), 0.5));
        CHECK_FALSE(measurement::frameAboutPeak(makeScene(brdf::Model::Retro, 1000, 9.5), 0.5));
    }
    SUBCASE("lobes about the mirror direction stay there, off-specular shifts included") {
        render::Scene g = makeScene(brdf::Model::GGX, 0.3, 70);
        g.brdf.geometry = brdf::Geometry::Smith;
        const auto p = measurement::findPeak(g);
        CHECK(p.offsetDeg > 1.0);                          // the off-specular peak ...
        CHECK_FALSE(measurement::frameAboutPeak(g, 0.5));  // ... with the mirror direction still in the region
        double offset = 1;
        CHECK(measurement::framedAbout(g, 0.5, offset) == "mirror direction");
        CHECK(offset == 0.0);
        CHECK_FALSE(measurement::frameAboutPeak(makeScene(brdf::Model::Phong, 1000, 60), 0.5));
        // The shipped hand-painted NDF at 80 deg with Smith G and Schlick F: the peak moves 10 deg toward grazing
        // and the mirror direction drops out of the half-maximum region, yet the peak is near: measured about wr.
        render::Scene h = makeScene(brdf::Model::Tabulated, 0.1, 80);
        h.brdf.ndfTable =
            brdf::parseNdfTable("0, 10\n1, 9.5\n2, 8\n3, 5\n4, 3.5\n6, 3\n9, 2\n12, 0.5\n15, 0\n", "h.csv");
        h.brdf.geometry = brdf::Geometry::Smith;
        h.brdf.fresnel = brdf::Fresnel::Schlick;
        const auto q = measurement::findPeak(h);
        CHECK(q.mirrorValue < 0.5 * q.value);
        CHECK(q.offsetDeg < measurement::kFarPeakDeg);
        CHECK_FALSE(measurement::frameAboutPeak(h, 0.5));
        // GGX alpha 0.3 with Smith G and Schlick F at 45 deg: f E cos_i peaks at the horizon, 45 deg from the
        // mirror direction, but forward: measured about wr (flagged horizon_cut), as before.
        render::Scene r = makeScene(brdf::Model::GGX, 0.3, 45);
        r.brdf.geometry = brdf::Geometry::Smith;
        r.brdf.fresnel = brdf::Fresnel::Schlick;
        const auto f = measurement::findPeak(r);
        CHECK(f.offsetDeg > 40.0);
        CHECK(f.fromLightDeg > f.offsetDeg);
        CHECK_FALSE(measurement::frameAboutPeak(r, 0.5));
    }
}

TEST_CASE("measurement::measureGl retroreflection: framed and measured about the peak") {
    measurement::MeasureSetup setup;
    setup.width = setup.height = 128;
    auto& renderer = *test::glEnv().renderer;
    for (double inc : {30.0, 60.0, 75.0}) {
        const render::Scene s = makeScene(brdf::Model::Retro, 1000, inc);
        const auto m = measurement::measureGl(renderer, s, setup);
        const auto ref = measurement::measureReference(s, setup.options);
        CAPTURE(inc);
        CHECK(m.shape.flags.empty());
        // A cos^n lobe about wi is round about its axis: the Phong lobe's 2.1331 deg (measurement.md), aspect 1.
        CHECK(ref.shape.major_deg == doctest::Approx(2.1331).epsilon(1e-4));
        CHECK_NEAR(m.shape.aspect, 1.0, 2e-3);
        CHECK(m.shape.major_deg == doctest::Approx(ref.shape.major_deg).epsilon(2e-3));
        CHECK(m.shape.minor_deg == doctest::Approx(ref.shape.minor_deg).epsilon(2e-3));
        CHECK_NEAR(m.shape.centroid_u_deg, 0.0, 0.01);  // relative to the peak
        CHECK_NEAR(m.shape.centroid_v_deg, 0.0, 0.01);
        CHECK(angleDeg(m.center, s.light.direction()) < 0.05);  // the frame looks back at the light
    }
    SUBCASE("a narrow lobe 0.1 deg above the horizon is a true maximum: framed about it, not about the mirror") {
        // (Beckmann/GGX roughness 10, whose lobe rises all the way to the horizon, stay about the mirror
        // direction: tests/hard. Here the lobe falls on both sides of its peak, 0.0067 deg wide.)
        const render::Scene s = makeScene(brdf::Model::Retro, 1e8, 89.9);
        const auto p = measurement::findPeak(s);
        CHECK_FALSE(p.risesToHorizon);
        REQUIRE(measurement::frameAboutPeak(s, 0.5));
        const auto m = measurement::measureGl(renderer, s, setup);
        const auto ref = measurement::measureReference(s, setup.options);
        CHECK_FALSE(m.shape.has(analysis::Flag::NoHighlight));
        CHECK_NEAR(m.shape.aspect, 1.0, 2e-3);
        CHECK(m.shape.major_deg == doctest::Approx(ref.shape.major_deg).epsilon(2e-3));
    }
    SUBCASE("about the mirror direction the frame misses it: nothing to measure there") {
        render::Scene s = makeScene(brdf::Model::Retro, 1000, 60);
        s.light.chartCenter = s.light.chart().wr();  // a chart already set: no reframing
        CHECK(measurement::measureGl(renderer, s, setup).shape.has(analysis::Flag::NoHighlight));
    }
}
