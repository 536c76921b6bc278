// The GLSL a scene compiles carries only the named terms: the program `hilite explain --part glsl` prints
// (render::programSources of the resolved scene, the measurement view), in-process.

#include "gl/program.hpp"
#include "render/renderer.hpp"
#include "render/shader_source.hpp"
#include "support/in_process.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace hilite;
using namespace hilite::testing;

namespace {

/// The fragment shader `hilite explain --part glsl ARGS` prints.
std::string glsl(const std::string& args) {
    const scene::Resolved r = scene::resolve(flags(args));
    return gl::joinSources(
        render::programSources(r.scene, render::Output::Measure, render::shaderDirectory()).fragment);
}

}  // namespace

TEST_CASE("render: the program holds only the named terms' GLSL") {
    const std::string none = glsl("--model ggx --fresnel none");
    CHECK(none.find("D_GGX(") != std::string::npos);
    CHECK(none.find("F_Schlick") == std::string::npos);
    CHECK(none.find("F_Dielectric") == std::string::npos);
    const std::string schlick = glsl("--model ggx --fresnel schlick");
    CHECK(schlick.find("VEC3 F_Schlick(") != std::string::npos);
}
