#include "gl/context.hpp"

#include "core/error.hpp"
#include "gl_fixture.hpp"

#include <doctest/doctest.h>

using namespace hilite;

TEST_CASE("gl::Context") {
    REQUIRE_FALSE(test::backends().empty());
    for (gl::Backend b : test::backends()) {
        const std::string backendName = gl::toString(b);
        CAPTURE(backendName);
        SUBCASE("reports GL >= 3.3 core on llvmpipe") {
            gl::Context ctx(b);
            const auto& info = ctx.info();
            CHECK((info.backend == b));
            CHECK(info.major * 10 + info.minor >= 33);
            CHECK(info.renderer.find("llvmpipe") != std::string::npos);
        }
    }
    SUBCASE("auto prefers OSMesa when it is there") {
        gl::Context ctx(gl::Backend::Auto);
        CHECK((ctx.info().backend == test::backends().front()));
    }
    SUBCASE("backend names parse") {
        CHECK((gl::parseBackend("egl") == gl::Backend::EGL));
        CHECK_FALSE(gl::parseBackend("glx").has_value());
    }
}
