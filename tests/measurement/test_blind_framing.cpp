// Measuring without a CPU twin: the shipped .brdf files measure as their built-in models, blind framing
// finds narrow lobes and says when it gives up, and the resolution-convergence error estimate bounds the
// error against the double reference.

#include "measurement/blind_framing.hpp"

#include "support/gl_fixture.hpp"
#include "support/scenes.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <string>

using namespace hilite;

namespace {

std::shared_ptr<const brdf_file::BrdfFile> shipped(const std::string& name, const std::string& assignments) {
    auto f = std::make_shared<brdf_file::BrdfFile>(
        brdf_file::load(std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/" + name + ".brdf"));
    brdf_file::assign(*f, assignments);
    return f;
}

render::Scene fromText(const std::string& shader, double incidence) {
    render::Scene s;
    s.brdfFile = std::make_shared<brdf_file::BrdfFile>(
        brdf_file::parse("analytic\n::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n" + shader +
                             "\n}\n::end shader\n",
                         "t.brdf"));
    s.light.incidenceDeg = incidence;
    return s;
}

render::Renderer& renderer() { return *test::glEnv().renderer; }

}  // namespace

TEST_CASE("measurement::measureBlind each shipped .brdf file measures as its built-in model") {
    struct Case {
        const char* file;
        const char* assignments;
        brdf::Model model;
        double param;
    };
    for (const Case& c :
         {Case{"phong", "n=1000", brdf::Model::Phong, 1000}, Case{"blinn", "n=1000", brdf::Model::Blinn, 1000},
          Case{"beckmann", "m=0.1", brdf::Model::Beckmann, 0.1}, Case{"ggx", "alpha=0.1", brdf::Model::GGX, 0.1}}) {
        for (double inc : {0.0, 30.0, 60.0, 75.0}) {
            CAPTURE(c.file);
            CAPTURE(inc);
            const render::Scene s = test::makeScene(c.model, c.param, inc);
            render::Scene f = s;
            f.brdfFile = shipped(c.file, c.assignments);
            const auto a = measurement::measureGl(renderer(), s, {});
            const auto b = measurement::measureGl(renderer(), f, {});  // no twin: blind framing
            CHECK(a.framing == "automatic");
            CHECK(b.framing == "blind");
            CHECK(b.framingNote.empty());
            CHECK(b.shape.flags.empty());
            CHECK_NEAR(b.shape.aspect, a.shape.aspect, 0.002);
            CHECK_NEAR(b.shape.major_deg / a.shape.major_deg, 1.0, 0.005);
            CHECK_NEAR(b.shape.minor_deg / a.shape.minor_deg, 1.0, 0.005);
            REQUIRE(b.halfResolution);
            CHECK(b.halfWidth == 256);
        }
    }
}

TEST_CASE("measurement::measureBlind agrees with twin-seeded framing on built-in lobes") {
    struct Case {
        brdf::Model model;
        double param, incidence;
    };
    // Phong n = 1e6 is 0.07 deg wide: it falls between the pixel centres of the first wide render.
    for (const Case& c :
         {Case{brdf::Model::Phong, 1e6, 30}, Case{brdf::Model::Blinn, 5000, 60}, Case{brdf::Model::GGX, 0.1, 45},
          Case{brdf::Model::GGX, 0.3, 85}, Case{brdf::Model::Beckmann, 0.4, 20}}) {
        CAPTURE(c.param);
        CAPTURE(c.incidence);
        const render::Scene s = test::makeScene(c.model, c.param, c.incidence);
        const auto twin = measurement::measureGl(renderer(), s, {});
        const auto blind = measurement::measureBlind(renderer(), s, {});
        CHECK(blind.framingNote.empty());
        CHECK_FALSE(blind.shape.has(analysis::Flag::Clipped));
        CHECK(blind.shape.flags == twin.shape.flags);
        CHECK_NEAR(blind.shape.aspect, twin.shape.aspect, 0.002);
        CHECK_NEAR(blind.shape.major_deg / twin.shape.major_deg, 1.0, 0.005);
        CHECK_NEAR(blind.shape.minor_deg / twin.shape.minor_deg, 1.0, 0.005);
        CHECK(blind.renders <= measurement::MeasureSetup{}.maxBlindRenders + 2);
    }
}

TEST_CASE("measurement::measureBlind error estimate from resolution convergence bounds the error") {
    for (double inc : {0.0, 45.0, 70.0}) {
        CAPTURE(inc);
        const render::Scene s = test::makeScene(brdf::Model::GGX, 0.1, inc);
        const auto ref = measurement::measureReference(s, {});
        for (int size : {64, 128, 512}) {
            CAPTURE(size);
            measurement::MeasureSetup setup;
            setup.width = setup.height = size;
            const auto m = measurement::measureBlind(renderer(), s, setup);
            REQUIRE(m.halfResolution);
            const analysis::Shape& h = *m.halfResolution;
            CHECK_NEAR(m.shape.aspect, ref.shape.aspect, std::abs(m.shape.aspect - h.aspect) + 1e-6);
            CHECK_NEAR(m.shape.major_deg, ref.shape.major_deg, std::abs(m.shape.major_deg - h.major_deg) + 1e-6);
            CHECK_NEAR(m.shape.minor_deg, ref.shape.minor_deg, std::abs(m.shape.minor_deg - h.minor_deg) + 1e-6);
        }
    }
}

TEST_CASE("measurement::measureBlind gives up and says so") {
    SUBCASE("a BRDF that is 0 everywhere") {
        const auto m = measurement::measureBlind(renderer(), fromText("return vec3(0.0);", 30), {});
        CHECK(m.shape.has(analysis::Flag::NoHighlight));
        CHECK(m.framingNote.find("no highlight found: zoomed toward the mirror direction down to a 0.0001 deg") == 0);
        CHECK(m.renders <= measurement::MeasureSetup{}.maxBlindRenders + 2);
    }
    SUBCASE("the light at the horizon") {
        const auto m = measurement::measureBlind(renderer(), fromText("return vec3(1.0);", 90), {});
        CHECK(m.shape.has(analysis::Flag::NoHighlight));
        CHECK(m.framingNote == "no light on the plane: it is at or below the horizon");
    }
    SUBCASE("a twin-based measurement refuses a .brdf scene") {
        CHECK_THROWS_AS(measurement::measureReference(fromText("return vec3(1.0);", 30), {}), InputError);
        CHECK_THROWS_AS(measurement::twinHalfWidth(fromText("return vec3(1.0);", 30), 0.5), InputError);
    }
}
