// The public umbrella header through hilite::hilite (as installed, but from the build tree), its generated
// version, and the $HILITE_SHARE_DIR lookup that a program linked against the installed library relies on.

#include <hilite/hilite.hpp>

#include "hilite/core/error.hpp"
#include "render/shader_source.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <optional>
#include <string>

namespace {

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

TEST_CASE("hilite/version.hpp is the CMake project version") {
    CHECK(std::string(HILITE_VERSION_STRING) == HILITE_PROJECT_VERSION);
    CHECK(std::string(hilite::kVersionString) == HILITE_PROJECT_VERSION);
    CHECK(std::to_string(HILITE_VERSION_MAJOR) + "." + std::to_string(HILITE_VERSION_MINOR) + "." +
              std::to_string(HILITE_VERSION_PATCH) ==
          HILITE_PROJECT_VERSION);
}

TEST_CASE("$HILITE_SHARE_DIR overrides the share files beside the executable") {
    const ScopedEnv noShaders("HILITE_SHADER_DIR", nullptr), noData("HILITE_DATA_DIR", nullptr);
    const std::string besideExe = hilite::render::shaderDirectory();
    {
        const ScopedEnv share("HILITE_SHARE_DIR", HILITE_TEST_SHARE_DIR);
        CHECK(hilite::render::shaderDirectory() == std::string(HILITE_TEST_SHARE_DIR) + "/shaders");
        CHECK(hilite::render::dataDirectory() == std::string(HILITE_TEST_SHARE_DIR) + "/data");
        // The specific variable still wins over the general one.
        const ScopedEnv shaders("HILITE_SHADER_DIR", besideExe.c_str());
        CHECK(hilite::render::shaderDirectory() == besideExe);
    }
    {
        // A share directory without the files is passed over (and named if nothing else holds them).
        const ScopedEnv share("HILITE_SHARE_DIR", "/nonexistent/hilite-share");
        CHECK(hilite::render::shaderDirectory() == besideExe);
    }
}
