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

/// GGX alpha 0.1, implicit geometry, no Fresnel, directional light at `incidenceDeg`, 512 x 512, automatic framing.
hilite::experiments::Measurement measureGgx(double incidenceDeg) {
    static hilite::gl::Context context;
    static hilite::render::Renderer renderer(context);
    hilite::render::Scene scene;
    scene.brdf.model = hilite::brdf::Model::GGX;
    scene.brdf.roughness = 0.1;
    scene.brdf.geometry = hilite::brdf::Geometry::Implicit;
    scene.brdf.fresnel = hilite::brdf::Fresnel::None;
    scene.light.type = hilite::render::LightType::Directional;
    scene.light.incidenceDeg = incidenceDeg;
    hilite::experiments::MeasureSetup setup;
    setup.width = setup.height = 512;
    setup.fovDeg = 0.0;  // automatic framing
    return hilite::experiments::measure(&renderer, scene, setup);
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
    const auto m = measureGgx(60.0);
    CAPTURE(m.shape.aspect);
    CHECK(m.framing == "automatic");
    CHECK(std::abs(m.shape.aspect - 0.50166) < 0.002);
}

TEST_CASE("GGX alpha 0.1 at normal incidence: a round highlight") {
    const auto m = measureGgx(0.0);
    CAPTURE(m.shape.aspect);
    CHECK(std::abs(m.shape.aspect - 1.0) < 1e-3);
}
