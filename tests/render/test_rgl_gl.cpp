// The GL twin of an RGL material (shaders/brdf_gl.glsl block Rgl: the tables in a float texture buffer, read by
// texelFetch) against the double CPU lookup (brdf/rgl.cpp), pixel by pixel, on a synthetic material and on the
// real files of ../shared where present; the program holds the lookup alone.

#include "brdf/rgl.hpp"
#include "render/shader_source.hpp"
#include "support/gl_fixture.hpp"
#include "support/rgl_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

using namespace hilite;

namespace {

brdf::Params rglParams(std::shared_ptr<const brdf::rgl::Material> m) {
    brdf::Params p;
    p.model = brdf::Model::None;
    p.rgl = std::move(m);
    return p;
}

}  // namespace

TEST_CASE("render::Renderer an RGL material matches its double twin pixel by pixel (synthetic)") {
    const auto m = std::make_shared<const brdf::rgl::Material>(
        brdf::rgl::parse(hilite_test::tensorFile(hilite_test::syntheticRgl(7)), "synthetic.bsdf"));
    MESSAGE("synthetic RGL material: worst GL vs twin relative error "
            << test::checkAgainstTwinOverViews(rglParams(m), {0.0, 20.0, 45.0, 70.0}, 1e-3));
}

TEST_CASE("render::Renderer the real RGL files match their double twin pixel by pixel") {
    const std::string dir = hilite_test::sharedMeasured();
    for (const char* name : {"cg_sunflower_rgb.bsdf", "satin_rosaline_rgb.bsdf", "paper_white_rgb.bsdf"}) {
        const std::string file = dir + "/" + name;
        if (!std::filesystem::exists(file)) {
            MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
            continue;
        }
        CAPTURE(file);
        MESSAGE(std::string(name) << ": worst GL vs twin relative error "
                                  << test::checkAgainstTwinOverViews(rglParams(brdf::rgl::load(file)),
                                                                     {0.0, 20.0, 45.0, 70.0}, 1e-3));
    }
}

TEST_CASE("render::assemble an RGL scene's program holds the lookup and no analytic term") {
    const auto m = std::make_shared<const brdf::rgl::Material>(
        brdf::rgl::parse(hilite_test::tensorFile(hilite_test::syntheticRgl()), "synthetic.bsdf"));
    std::string text;
    for (const auto& piece : render::assemble(rglParams(m), render::Output::Color, render::shaderDirectory()).fragment)
        text += piece.text;
    CHECK(text.find("rglBrdf(") != std::string::npos);
    CHECK(text.find("uniform samplerBuffer uRgl") != std::string::npos);
    for (const char* term : {"D_GGX(", "F_Schlick(", "Lambda_GGX(", "Fd_Lambert(", "measuredBrdf("}) {
        CAPTURE(term);
        CHECK(text.find(term) == std::string::npos);
    }
}
