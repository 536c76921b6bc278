// measurement::Result (measurement/result.hpp): the typed fields of a measurement agree with its row, toJson.

#include "hilite/measurement/result.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/measurement/session.hpp"
#include "support/keys.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace hilite;

namespace {

/// A row's number, NaN for null (how toJson writes a non-finite one).
double number(const nlohmann::json& j, const char* key) {
    REQUIRE(j.contains(key));
    return j[key].is_null() ? NAN : j[key].get<double>();
}

/// The row's shape fields are the typed shape's, its flags in the same order.
void checkShape(const analysis::Shape& s, const nlohmann::json& j) {
    auto same = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; };
    CHECK(same(number(j, "aspect"), s.aspect));
    CHECK(same(number(j, "eccentricity"), s.eccentricity));
    CHECK(same(number(j, "major_deg"), s.major_deg));
    CHECK(same(number(j, "minor_deg"), s.minor_deg));
    CHECK(same(number(j, "orientation_deg"), s.orientation_deg));
    CHECK(same(number(j, "centroid_u_deg"), s.centroid_u_deg));
    CHECK(same(number(j, "peak"), s.peak));
    CHECK(same(number(j, "area_deg2"), s.area_deg2));
    CHECK(j["components"].get<int>() == s.components);
    std::vector<std::string> flags;
    for (analysis::Flag f : s.flags) flags.push_back(analysis::toString(f));
    CHECK(j["flags"].get<std::vector<std::string>>() == flags);
    CHECK(j.contains("parts") == !s.parts.empty());
}

}  // namespace

TEST_CASE("measurement::Result the typed fields agree with the row") {
    measurement::Session session;
    SUBCASE("GL: shape, method, size, scene, GL info") {
        const scene::Resolved r = test::resolveKeys("model=ggx roughness=0.1 incidence=60 size=128");
        const measurement::Result res = session.measureOne(r);
        const nlohmann::json j = measurement::toJson(res);
        checkShape(res.shape(), j);
        CHECK(res.method == "gl");
        CHECK(j["method"] == res.method);
        CHECK(res.width == 128);
        CHECK(j["size"] == "128x128");
        CHECK(number(j, "incidence_deg") == res.resolved.scene.light.incidenceDeg);
        CHECK(number(j, "renders") == res.measurement.renders);
        CHECK(j["framing"] == res.measurement.framing);
        CHECK(j["framed_about"] == res.framedAbout);
        REQUIRE(res.gl);
        CHECK(j["gl_renderer"] == res.gl->renderer);
        CHECK(!res.tolerance);
        CHECK(!res.micro);
        CHECK(!res.light);
        CHECK(!j.contains("settings"));
        CHECK(!j.contains("light_visible"));
        CHECK(measurement::toJson(res) == j);  // a function of the result alone: nothing measured again
    }
    SUBCASE("reference under a disk light cut by the horizon: flags, light fields, no size") {
        const measurement::Result res =
            session.measureOne(test::resolveKeys("model=ggx roughness=0.1 incidence=85 light=disk reference=true"));
        const nlohmann::json j = measurement::toJson(res);
        checkShape(res.shape(), j);
        CHECK(res.shape().has(analysis::Flag::HorizonCut));
        CHECK(j["size"] == "");
        CHECK(!res.gl);
        CHECK(!j.contains("gl_renderer"));
        REQUIRE(res.light);
        CHECK(number(j, "light_visible") == res.light->visible);
        CHECK(!res.light->ruleError);
        CHECK(j["light_rule_error"].is_null());
    }
    SUBCASE("tolerance: the chosen settings and the estimate") {
        const measurement::Result res =
            session.measureOne(test::resolveKeys("model=ggx roughness=0.1 incidence=40 tolerance=0.01 renderer=cpu"));
        const nlohmann::json j = measurement::toJson(res);
        REQUIRE(res.tolerance);
        CHECK(number(j, "error_estimate") == res.tolerance->errorEstimate);
        CHECK(j["tolerance_met"] == res.tolerance->met);
        CHECK(j["rounds"] == res.tolerance->rounds);
        CHECK(j["settings"]["size"] ==
              std::to_string(res.tolerance->setup.width) + "x" + std::to_string(res.tolerance->setup.height));
        CHECK(res.width == res.tolerance->setup.width);
        CHECK(number(j["check"], "aspect") == res.tolerance->checkAspect);
    }
    SUBCASE("explicit bumps: the analytic twin and the slopes") {
        const measurement::Result res =
            session.measureOne(test::resolveKeys("model=beckmann bumps=explicit incidence=30 size=128"));
        const nlohmann::json j = measurement::toJson(res);
        checkShape(res.shape(), j);
        REQUIRE(res.micro);
        CHECK(number(j, "analytic_aspect") == res.micro->analytic.aspect);
        CHECK(number(j, "aspect_minus_analytic") == res.shape().aspect - res.micro->analytic.aspect);
        CHECK(number(j, "slope_rms") == res.micro->slopeRms);
        CHECK(j["bump_filter_used"] == res.micro->filterUsed);
        CHECK(!j.contains("prefilter_aspect"));
    }
}

TEST_CASE("measurement::toJson keeps the flags' order and writes non-finite shape fields as null") {
    measurement::Session session;
    measurement::Result res = session.measureOne(test::resolveKeys("model=ggx roughness=0.1 incidence=30 size=64"));
    res.measurement.shape.flags = {analysis::Flag::UnderResolved, analysis::Flag::Clipped};
    res.measurement.shape.aspect = NAN;
    const nlohmann::json j = measurement::toJson(res);
    CHECK(j["flags"] == nlohmann::json::array({"under_resolved", "clipped"}));
    CHECK(j["aspect"].is_null());
}

TEST_CASE("measurement::Session measures in its own context after another one was made current") {
    scene::Values v;
    v.set("model", "ggx");
    v.set("incidence", "60");
    v.set("size", "128");
    const scene::Resolved r = scene::resolve(v);
    measurement::Session session;
    const double before = session.measureOne(r).shape().aspect;
    {
        // Another context, made current and then destroyed, as an experiment run in the same process does; the
        // session is not told (no makeCurrent() call).
        scene::Values other = v;
        other.set("incidence", "30");
        measurement::Session second;
        CHECK(second.measureOne(scene::resolve(other)).shape().aspect > before);
    }
    CHECK(session.measureOne(r).shape().aspect == before);
}
