// The installed hilite from a downstream project: a GGX highlight measured through the public header.

#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <hilite/hilite.hpp>
#include <hilite/version.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

namespace {

/// GGX alpha 0.1, implicit geometry, no Fresnel, directional light at `incidenceDeg`, 512 x 512, automatic
/// framing: the scene named by the registry's parameters, as a scene file or the command line would.
/// `other`: measure those values instead (at the same incidence), on the same Session.
nlohmann::json measureGgx(double incidenceDeg, hilite::scene::Values* other = nullptr) {
    static hilite::measurement::Session session;  // one GL context for every measurement
    session.makeCurrent();  // another test case's Session may have made its own context current since
    if (other) {
        other->set("incidence", std::to_string(incidenceDeg));
        return hilite::measurement::toJson(session.measureOne(hilite::scene::resolve(*other)));
    }
    hilite::scene::Values values;
    values.set("model", "ggx");
    values.set("roughness", "0.1");
    values.set("geometry", "implicit");
    values.set("fresnel", "none");
    values.set("size", "512");
    values.set("incidence", std::to_string(incidenceDeg));
    return hilite::measurement::toJson(session.measureOne(hilite::scene::resolve(values)));
}

}  // namespace

TEST_CASE("the installed version is the package's") {
    CHECK(std::string(HILITE_VERSION_STRING) == EXPECTED_VERSION);
    CHECK(std::string(hilite::kVersionString) == std::to_string(HILITE_VERSION_MAJOR) + "." +
                                                     std::to_string(HILITE_VERSION_MINOR) + "." +
                                                     std::to_string(HILITE_VERSION_PATCH));
}

TEST_CASE("the library loaded is the one the headers belong to") {
    CHECK(std::string(hilite::libraryVersion()) == hilite::kVersionString);
}

TEST_CASE("no environment variable tells the library where its files are") {
    // The measurements below find shaders, data and the probe helper relative to libhilite.so.
    CHECK(std::getenv("HILITE_SHARE_DIR") == nullptr);
    CHECK(std::getenv("HILITE_SHADER_DIR") == nullptr);
    CHECK(std::getenv("HILITE_DATA_DIR") == nullptr);
}

TEST_CASE("GGX alpha 0.1 at 60 degrees: the known aspect") {
    const auto row = measureGgx(60.0);
    CAPTURE(row.dump());
    CHECK(row["framing"] == "automatic");
    CHECK(row["roughness"].get<double>() == 0.1);
    CHECK(std::abs(row["aspect"].get<double>() - 0.50166) < 0.002);
}

TEST_CASE("GGX alpha 0.1 at normal incidence: a round highlight") {
    const auto row = measureGgx(0.0);
    CAPTURE(row.dump());
    CHECK(std::abs(row["aspect"].get<double>() - 1.0) < 1e-3);
}

TEST_CASE("a bad value is an InputError naming the parameter and the allowed range") {
    hilite::scene::Values values;
    values.set("roughness", "-1");
    try {
        hilite::scene::resolve(values);
        FAIL("no error");
    } catch (const hilite::InputError& e) {
        CHECK(std::string(e.what()) == "--roughness: must be a finite number in [0, 10] (got -1)");
    }
}

TEST_CASE("the typed pipeline: a Scene measured with a MeasureSetup") {
    hilite::measurement::Session session;
    const auto r = hilite::scene::resolve(hilite::scene::Values{});  // every default: GGX 0.1 at 45 deg
    const auto m = hilite::measurement::measure(&session.rendererFor(r), r.scene, r.setup);
    CHECK(m.shape.aspect > 0.6);
    CHECK(m.shape.aspect < 0.8);
}

TEST_CASE("a .brdf measured by the installed library, its probe run by the installed helper") {
    // The prefix holds no hilite executable and PATH names none (run_downstream.cmake): the probe's child
    // is <prefix>/libexec/hilite-probe. ggx.brdf is GGX's NDF alone, so its aspect is the built-in lobe's.
    hilite::scene::Values values;
    values.set("brdf", std::string(EXPECTED_SHARE_DIR) + "/experiments/brdfs/ggx.brdf");
    values.set("incidence", "60");
    const double ggx = measureGgx(60.0)["aspect"].get<double>();
    const auto row = measureGgx(60.0, &values);  // the same Session: one GL context per thread
    CAPTURE(row.dump());
    CHECK(row["flags"].empty());
    CHECK(std::abs(row["aspect"].get<double>() - ggx) < 2e-3);
}
