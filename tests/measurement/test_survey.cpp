// The hemisphere survey (the global peak and every part of the region, before any framing) and the
// scan-line reference built on it.

#include "hilite/measurement/measure_scene.hpp"
#include "measurement/lobe_survey.hpp"
#include "support/keys.hpp"

#include <doctest/doctest.h>

using namespace hilite;

namespace {

const char* kSweep = "model=ggx roughness=0.1 geometry=smith fresnel=schlick f0=0.04 incidence=";

}  // namespace

TEST_CASE(
    "survey: GGX 0.1 + Smith + Schlick 0.04 has a second part above the horizon at 58-64 deg, one part at 45 and 65") {
    for (auto [t, parts] : {std::pair{45.0, 1}, {58.0, 2}, {60.0, 2}, {64.0, 2}, {65.0, 1}}) {
        const double ti = t;  // a structured binding cannot be captured by CAPTURE's lambda in C++17 (clang)
        CAPTURE(ti);
        const auto r = test::resolveKeys(kSweep + std::to_string(ti));
        const measurement::LobeSurvey s = measurement::surveyLobe(r.scene, 0.5);
        CHECK(int(s.parts.size()) == parts);
        CHECK(s.parts.at(0).holdsPeak);
        if (parts == 2) CHECK(s.parts.at(1).horizon);  // the strip just above the horizon
        CHECK_FALSE(s.peakOnHorizon);
    }
}

TEST_CASE(
    "survey: the global peak on the horizon (GGX 0.1 + Smith + Schlick at 72 deg) and a lobe without one (G = 1)") {
    const auto r = test::resolveKeys(std::string(kSweep) + "72");
    const measurement::LobeSurvey s = measurement::surveyLobe(r.scene, 0.5);
    CHECK(s.peakOnHorizon);
    CHECK(s.peakDirection.z < 1e-6);
    CHECK(s.peakUV.x == doctest::Approx(-deg2rad(18.0)).epsilon(1e-6));  // the horizon below the mirror direction
    const auto g1 =
        test::resolveKeys("model=beckmann roughness=0.1 geometry=none fresnel=schlick f0=0.04 incidence=30");
    CHECK(measurement::surveyLobe(g1.scene, 0.5).unbounded);
    const auto smith =
        test::resolveKeys("model=beckmann roughness=0.1 geometry=smith fresnel=schlick f0=0.04 incidence=30");
    CHECK_FALSE(measurement::surveyLobe(smith.scene, 0.5).unbounded);
}

TEST_CASE("scan-line reference: every part, each with its own ellipse, the peak's first") {
    const auto r = test::resolveKeys(std::string(kSweep) + "60");
    const auto m = measurement::measureReference(r.scene, r.setup.options).shape;
    REQUIRE(m.components == 2);
    REQUIRE(m.parts.size() == 2);
    CHECK(m.parts[0].holds_peak);
    CHECK(m.parts[1].horizon_cut);
    // The parts' moments add to the whole (disjoint parts: the parallel-axis theorem).
    const analysis::AreaMoments all = analysis::combine(m.parts[0].moments, m.parts[1].moments);
    CHECK(all.area == doctest::Approx(m.moments.area).epsilon(1e-12));
    CHECK(all.cuu == doctest::Approx(m.moments.cuu).epsilon(1e-9));
    CHECK(m.has(analysis::Flag::HorizonCut));
    // The main lobe alone is what the old framing measured (aspect 0.409): the whole region is far narrower.
    CHECK(m.parts[0].aspect == doctest::Approx(0.4086).epsilon(1e-3));
    CHECK(m.aspect < 0.26);
}

TEST_CASE(
    "scan-line reference: a region far smaller than its survey box, and one that touches the horizon at a point") {
    // GGX 0.1 + Smith at 89.9 deg: the region is 0.05 deg long around a peak on the horizon (the survey's box: 10 deg).
    auto r = test::resolveKeys("model=ggx roughness=0.1 geometry=smith incidence=89.9");
    auto m = measurement::measureReference(r.scene, r.setup.options).shape;
    CHECK(m.components == 1);
    CHECK(m.area_deg2 > 0);
    CHECK(m.major_deg == doctest::Approx(0.0529).epsilon(0.01));
    CHECK(m.has(analysis::Flag::HorizonCut));
    // 1.7e-7 rad above the horizon: the region meets the horizon only along the line through the peak.
    r = test::resolveKeys("model=ggx roughness=0.1 incidence=89.99999");
    m = measurement::measureReference(r.scene, r.setup.options).shape;
    CHECK(m.has(analysis::Flag::HorizonCut));
}
