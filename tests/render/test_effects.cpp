// "Simulate only what the scene calls for": the assembled program holds exactly the named terms.

#include "render/renderer.hpp"
#include "render/shader_source.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

using namespace hilite;

namespace {

std::string programText(const brdf::Params& p, render::LightType light = render::LightType::Directional) {
    const auto src = render::programSources(p, render::Output::Measure, light, render::shaderDirectory());
    return gl::joinSources(src.fragment);
}

/// Every term block of shaders/brdf.glsl: its name is the function it defines.
std::vector<std::string> allBlocks() {
    std::ifstream in(render::shaderDirectory() + "/brdf.glsl");
    std::stringstream ss;
    ss << in.rdbuf();
    std::vector<std::string> names;
    for (const auto& b : render::parseBlocks(ss.str(), "brdf.glsl")) names.push_back(b.name);
    return names;
}

/// The blocks whose function is defined in the program ("<type> NAME(" appears).
std::set<std::string> definedBlocks(const std::string& text) {
    std::set<std::string> out;
    for (const auto& name : allBlocks())
        for (const char* type : {"REAL ", "VEC3 ", "VEC2 ", "HalfVector "})
            if (text.find(std::string(type) + name + "(") != std::string::npos) out.insert(name);
    return out;
}

}  // namespace

TEST_CASE("render::programSources the program defines the named terms and no others") {
    struct Case {
        std::string what;
        brdf::Params p;
        std::vector<std::string> present, absent;
    };
    brdf::Params ndfOnly;
    ndfOnly.model = brdf::Model::GGX;
    brdf::Params full = ndfOnly;
    full.fresnel = brdf::Fresnel::Schlick;
    full.geometry = brdf::Geometry::Smith;
    brdf::Params phong;
    phong.model = brdf::Model::Phong;
    brdf::Params beckmannDielectric;
    beckmannDielectric.model = brdf::Model::Beckmann;
    beckmannDielectric.fresnel = brdf::Fresnel::Dielectric;
    beckmannDielectric.diffuse = brdf::Diffuse::Lambert;
    const std::vector<Case> cases = {
        {"ggx, fresnel none, implicit G", ndfOnly, {"D_GGX"}, {"F_", "Lambda_", "G2_", "D_Beckmann", "Fd_", "Phong"}},
        {"ggx + schlick + smith",
         full,
         {"D_GGX", "F_Schlick", "Lambda_GGX", "G2_SmithCorrelated"},
         {"F_Dielectric", "F_Conductor", "F_Spectral", "D_Beckmann", "Fd_", "Phong"}},
        {"phong", phong, {"Phong_Normalized"}, {"D_", "F_", "Lambda_", "HalfVector"}},
        {"beckmann + dielectric + lambert",
         beckmannDielectric,
         {"D_Beckmann", "F_Dielectric"},
         {"F_Schlick", "F_Conductor", "D_GGX", "Lambda_"}},
    };
    for (const auto& c : cases) {
        CAPTURE(c.what);
        const std::string text = programText(c.p);
        const auto defined = definedBlocks(text);
        for (const auto& name : c.present) CHECK(defined.count(name) == 1);
        for (const auto& prefix : c.absent)
            for (const auto& name : defined) {
                CAPTURE(name);
                CHECK(name.rfind(prefix, 0) != 0);
            }
        // No tangent frame for an isotropic material, no spectral arrays without measured spectra.
        CHECK(text.find("uTangent") == std::string::npos);
        CHECK(text.find("SPECTRAL") == std::string::npos);
        CHECK(text.find("#define HILITE_LIGHT_POINT") == std::string::npos);
    }
}

TEST_CASE("render::programSources the point light is compiled only when named") {
    brdf::Params p;
    CHECK(programText(p, render::LightType::Point).find("#define HILITE_LIGHT_POINT") != std::string::npos);
    CHECK(programText(p).find("#define HILITE_LIGHT_POINT") == std::string::npos);
}

TEST_CASE("render::activeEffects lists the terms and the light") {
    render::Scene s;
    s.brdf.fresnel = brdf::Fresnel::Schlick;
    const auto e = render::activeEffects(s);
    CHECK(std::find(e.begin(), e.end(), "D_GGX") != e.end());
    CHECK(std::find(e.begin(), e.end(), "F_Schlick") != e.end());
    CHECK(std::find(e.begin(), e.end(), "G2_SmithCorrelated") == e.end());
}
