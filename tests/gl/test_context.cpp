#include "gl/context.hpp"

#include "brdf/spectral.hpp"
#include "hilite/core/error.hpp"
#include "support/gl_fixture.hpp"

#include "render/renderer.hpp"
#include "render/shader_source.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>

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
    SUBCASE("auto prefers a hardware EGL device, then OSMesa") {
        gl::Context ctx(gl::Backend::Auto);
        const bool gpu = gl::firstHardwareDevice() >= 0 && ctx.info().backend == gl::Backend::EGLDevice;
        CHECK((gpu || ctx.info().backend == test::backends().front()));
        if (!gpu) CHECK(ctx.info().renderer.find("llvmpipe") != std::string::npos);
    }
    SUBCASE("backend names parse") {
        CHECK((gl::parseBackend("egl") == gl::Backend::EGL));
        CHECK((gl::parseBackend("egl-device") == gl::Backend::EGLDevice));
        CHECK_FALSE(gl::parseBackend("glx").has_value());
    }
}

namespace {

/// Renders GGX + Smith + copper's spectral Fresnel (table) and Phong in both outputs on a fresh context.
std::vector<float> renderOn(gl::Backend b, int device) {
    gl::Context context(b, device);
    render::Renderer renderer(context);
    std::vector<float> pixels;
    for (brdf::Model m : {brdf::Model::GGX, brdf::Model::Phong})
        for (render::Output out : {render::Output::Measure, render::Output::Color}) {
            render::Scene s;
            s.brdf.model = m;
            s.brdf.geometry = brdf::Geometry::Smith;
            s.brdf.fresnel = brdf::Fresnel::Spectral;
            s.brdf.spectrum = brdf::loadSpectrum(render::dataDirectory(), "copper", brdf::kGpuStepNm);
            s.light.incidenceDeg = 60;
            const PinholeCamera cam = PinholeCamera::photo(30, 180, 10, 40, 96, 64);
            const ImageF img = renderer.render(s, cam, out);
            pixels.insert(pixels.end(), img.data.begin(), img.data.end());
        }
    return pixels;
}

}  // namespace

TEST_CASE("gl::Context egl-device renders the same bytes as OSMesa on llvmpipe") {
    std::string why;
    const std::vector<gl::EglDevice> devices = gl::eglDevices(why);
    const auto software =
        std::find_if(devices.begin(), devices.end(), [](const gl::EglDevice& d) { return d.software; });
    const bool osmesa = std::count(test::backends().begin(), test::backends().end(), gl::Backend::OSMesa) > 0;
    if (devices.empty()) {
        MESSAGE("skipped: no EGL device to compare (" << why << ")");
        return;
    }
    if (software == devices.end() || !osmesa) {
        MESSAGE("skipped: " << (osmesa ? "EGL lists no Mesa software device (llvmpipe)" : "no OSMesa to compare with"));
        return;
    }
    const int index = int(software - devices.begin());
    {
        gl::Context ctx(gl::Backend::EGLDevice, index);
        CHECK((ctx.info().backend == gl::Backend::EGLDevice));
        CHECK(ctx.info().device == index);
        CHECK(ctx.info().renderer.find("llvmpipe") != std::string::npos);
    }
    const std::vector<float> a = renderOn(gl::Backend::OSMesa, -1), b = renderOn(gl::Backend::EGLDevice, index);
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() == size_t(4 * 96 * 64 * 4));
    CHECK(*std::max_element(a.begin(), a.end()) > 0.0f);  // something was drawn
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST_CASE("gl::Context --gpu beyond the devices is an input error naming the flag") {
    std::string why;
    const int count = int(gl::eglDevices(why).size());
    try {
        gl::Context ctx(gl::Backend::EGLDevice, count);
        FAIL("a context on a device that does not exist");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("--gpu") != std::string::npos);
        CHECK(std::string(e.what()).find("[0, " + std::to_string(count) + ")") != std::string::npos);
    }
}

TEST_CASE("gl::translateLog names each piece's file and line in Mesa's K:N(C) locations, and leaves the rest") {
    using hilite::gl::SourcePiece;
    const std::vector<SourcePiece> pieces = {{"<generated>", 1, "#version 450\n"}, {"shaders/brdf.glsl", 40, "x\n"}};
    const long n = 1L * hilite::gl::kLineStride + 43;  // piece 1, its line 43
    const std::string log = "1:" + std::to_string(n) +
                            "(7): error: 'foo' undeclared\n"
                            "0:3(12): warning: unused\n"
                            "no location here: 5:x(1) and 12:(3)\n"
                            "at 0:" +
                            std::to_string(n) + "(2): error: redefined\n";
    CHECK(hilite::gl::translateLog(log, pieces) ==
          "shaders/brdf.glsl:43:7: error: 'foo' undeclared\n"
          "<generated>:3:12: warning: unused\n"
          "no location here: 5:x(1) and 12:(3)\n"
          "at shaders/brdf.glsl:43:2: error: redefined\n");
}
