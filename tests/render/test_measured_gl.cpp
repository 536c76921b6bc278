// The GL twin of a measured MERL table (shaders/brdf_gl.glsl block Measured, a 3D float texture read by
// texelFetch) against the double CPU lookup (brdf/merl.cpp), pixel by pixel; the program holds the lookup
// alone; and one texture per table however many draws.

#include "brdf/merl.hpp"
#include "render/shader_source.hpp"
#include "support/gl_fixture.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <memory>
#include <string>

using namespace hilite;

namespace {

/// GGX 0.1, Smith, Schlick 0.04, tabulated in memory (the table of the round trip).
std::shared_ptr<const brdf::merl::MeasuredBrdf> ggxTable() {
    static const auto table = [] {
        brdf::Params p;
        p.model = brdf::Model::GGX;
        p.roughness = 0.1;
        p.geometry = brdf::Geometry::Smith;
        p.fresnel = brdf::Fresnel::Schlick;
        p.f0 = dvec3(0.04);
        auto t = std::make_shared<brdf::merl::MeasuredBrdf>(brdf::merl::tabulate(p));
        t->path = "ggx.binary";
        return std::shared_ptr<const brdf::merl::MeasuredBrdf>(t);
    }();
    return table;
}

brdf::Params measured() {
    brdf::Params p;
    p.model = brdf::Model::None;
    p.measured = ggxTable();
    return p;
}

}  // namespace

TEST_CASE("render::Renderer a measured table matches its double twin pixel by pixel") {
    const double worst = test::checkAgainstTwinOverViews(measured(), {0.0, 30.0, 60.0, 80.0}, 1e-4);
    MESSAGE("measured table: worst GL vs twin relative error " << worst);
}

TEST_CASE("render::assemble a measured scene's program holds the table lookup and no analytic term") {
    std::string text;
    for (const auto& piece : render::assemble(measured(), render::Output::Color, render::shaderDirectory()).fragment)
        text += piece.text;
    CHECK(text.find("measuredBrdf(") != std::string::npos);
    CHECK(text.find("uniform sampler3D uMeasured") != std::string::npos);
    for (const char* term : {"D_GGX(", "F_Schlick(", "Lambda_GGX(", "Fd_Lambert(", "Phong_Normalized("}) {
        CAPTURE(term);
        CHECK(text.find(term) == std::string::npos);
    }
    brdf::Params ggx;  // and an analytic scene has no lookup
    std::string plain;
    for (const auto& piece : render::assemble(ggx, render::Output::Color, render::shaderDirectory()).fragment)
        plain += piece.text;
    CHECK(plain.find("uMeasured") == std::string::npos);
}
