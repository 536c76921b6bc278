// The installed hilite from a downstream project: a GGX highlight measured through the public header.

#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <hilite/hilite.hpp>
#include <hilite/version.hpp>

#include "core/error.hpp"
#include "render/shader_source.hpp"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

namespace {

/// GGX alpha 0.1, implicit geometry, no Fresnel, directional light at `incidenceDeg`, 512 x 512, automatic
/// framing: the scene named by the registry's parameters, as a scene file or the command line would.
nlohmann::json measureGgx(double incidenceDeg) {
    static hilite::measurement::Session session;  // one GL context for every measurement
    hilite::scene::Values values;
    values.set("model", "ggx");
    values.set("roughness", "0.1");
    values.set("geometry", "implicit");
    values.set("fresnel", "none");
    values.set("size", "512");
    values.set("incidence", std::to_string(incidenceDeg));
    return session.measureOne(hilite::scene::resolve(values));
}

/// Sets (or unsets) an environment variable for a scope.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : m_name(name) {
        if (const char* old = std::getenv(name)) m_old = old;
        value ? setenv(name, value, 1) : unsetenv(name);
    }
    ~ScopedEnv() { m_old ? setenv(m_name, m_old->c_str(), 1) : unsetenv(m_name); }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* m_name;
    std::optional<std::string> m_old;
};

}  // namespace

TEST_CASE("the installed version is the package's") {
    CHECK(std::string(HILITE_VERSION_STRING) == EXPECTED_VERSION);
    CHECK(std::string(hilite::kVersionString) ==
          std::to_string(HILITE_VERSION_MAJOR) + "." + std::to_string(HILITE_VERSION_MINOR) + "." +
              std::to_string(HILITE_VERSION_PATCH));
}

TEST_CASE("HILITE_SHARE_DIR names the installed shaders and data") {
    const char* share = std::getenv("HILITE_SHARE_DIR");
    REQUIRE(share != nullptr);
    CHECK(std::string(share) == EXPECTED_SHARE_DIR);
    CHECK(hilite::render::shaderDirectory() == std::string(share) + "/shaders");
    CHECK(hilite::render::dataDirectory() == std::string(share) + "/data");
}

TEST_CASE("without HILITE_SHARE_DIR the library looks in the install prefix compiled in") {
    const std::string configured = CONFIGURED_SHARE_DIR;
    if (configured.empty()) return;  // not told where hilite was configured to go
    const ScopedEnv noShare("HILITE_SHARE_DIR", nullptr), noShaders("HILITE_SHADER_DIR", nullptr);
    // This executable is not in <prefix>/bin, so only the compiled-in prefix can hold them: found there, or
    // named among the places looked in when nothing is installed at the configured prefix.
    std::string found, error;
    try {
        found = hilite::render::shaderDirectory();
    } catch (const hilite::SystemError& e) {
        error = e.what();
    }
    CAPTURE(error);
    if (error.empty())
        CHECK(found == configured + "/shaders");
    else
        CHECK(error.find(configured + "/shaders") != std::string::npos);
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
