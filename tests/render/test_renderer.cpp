#include "render/renderer.hpp"

#include "hilite/core/error.hpp"
#include "render/shader_source.hpp"
#include "support/gl_fixture.hpp"

#include <doctest/doctest.h>
#include <glad/gl.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace hilite;

namespace {

render::Scene makeScene(brdf::Model m, double incidence) {
    render::Scene s;
    s.brdf.model = m;
    s.brdf.exponent = 500;
    s.brdf.roughness = 0.15;
    s.light.incidenceDeg = incidence;
    return s;
}

PinholeCamera measureCamera(const render::Scene& s, double fov, int w, int h) {
    const MirrorChart chart = s.light.chart();
    dvec3 c = chart.wr();
    if (c.z < 1e-3) c = glm::normalize(dvec3(c.x, c.y, 1e-3));
    return PinholeCamera::measurement(chart, c, fov, w, h);
}

}  // namespace

TEST_CASE("render::Renderer pixels are finite, non-negative and match the double twin") {
    for (gl::Backend b : test::backends()) {
        const std::string backendName = gl::toString(b);
        CAPTURE(backendName);
        test::GlEnv env(b);
        for (brdf::Model m : {brdf::Model::Phong, brdf::Model::Blinn, brdf::Model::Beckmann, brdf::Model::GGX})
            for (brdf::Geometry g : {brdf::Geometry::Implicit, brdf::Geometry::Smith})
                for (double inc : {0.0, 30.0, 60.0, 75.0, 89.0}) {
                    if (m == brdf::Model::Phong && g == brdf::Geometry::Smith) continue;
                    render::Scene s = makeScene(m, inc);
                    s.brdf.geometry = g;
                    s.brdf.fresnel = inc == 60.0 ? brdf::Fresnel::Schlick : brdf::Fresnel::None;
                    s.brdf.f0 = {0.9, 0.6, 0.3};
                    const std::string modelName = brdf::toString(m);
                    CAPTURE(modelName);
                    const std::string geometryName = brdf::toString(g);
                    CAPTURE(geometryName);
                    CAPTURE(inc);
                    const auto r = test::compareWithTwin(*env.renderer, s, measureCamera(s, 40, 96, 64));
                    CHECK(r.allFinite);
                    CHECK(r.allNonNegative);
                    CHECK(r.compared >= 50);
                    CHECK(r.maxRelError < 1e-4);
                }
    }
}

TEST_CASE("render::Renderer sizes and views") {
    auto& env = test::glEnv();
    for (const auto& size : {std::pair{1, 1}, {7, 3}, {128, 128}, {300, 200}}) {
        const int w = size.first, h = size.second;  // (clang: no CAPTURE of structured bindings)
        render::Scene s = makeScene(brdf::Model::GGX, 45);
        const auto r = test::compareWithTwin(*env.renderer, s, PinholeCamera::photo(45, 180, 10, 40, w, h));
        const int width = w, height = h;
        CAPTURE(width);
        CAPTURE(height);
        CHECK(r.allFinite);
        CHECK(r.allNonNegative);
        CHECK(r.maxRelError < 1e-4);
    }
}

TEST_CASE("render::Renderer the plane covers every downward ray") {
    auto& env = test::glEnv();
    render::Scene s = makeScene(brdf::Model::GGX, 80);
    s.brdf.roughness = 1.0;  // wide lobe: radiance everywhere above the horizon
    const PinholeCamera cam = PinholeCamera::photo(5, 180, 10, 60, 200, 150);
    const ImageF img = env.renderer->render(s, cam, render::Output::Color);
    int mismatches = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const bool seesPlane = cam.ray(x + 0.5, y + 0.5).z < -1e-6;
            const bool covered = img.pixel(x, y)[3] > 0.5f;
            if (seesPlane != covered) ++mismatches;
        }
    CHECK(mismatches == 0);
}

TEST_CASE("render::Renderer at normal incidence the image is mirror-symmetric about the plane of incidence") {
    auto& env = test::glEnv();
    for (brdf::Model m : {brdf::Model::Phong, brdf::Model::GGX, brdf::Model::Beckmann}) {
        render::Scene s = makeScene(m, 0);
        const PinholeCamera cam = measureCamera(s, 30, 128, 96);
        const ImageF img = env.renderer->render(s, cam, render::Output::Color);
        // At theta_i = 0 the camera's image x is the chart's v: the plane of incidence is the centre column.
        double maxRel = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width / 2; ++x) {
                const double a = img.pixel(x, y)[0], b = img.pixel(cam.width - 1 - x, y)[0];
                maxRel = std::max(maxRel, std::abs(a - b) / std::max(1e-30, std::max(a, b)));
            }
        const std::string modelName = brdf::toString(m);
        CAPTURE(modelName);
        CHECK(maxRel < 1e-6);
    }
}

TEST_CASE("render::Renderer a shader syntax error names the file and line") {
    auto& env = test::glEnv();
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("hilite-bad-shaders-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(env.renderer->shaderDir()))
        fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
    // Break the line after "INLINE REAL D_GGX(" in brdf.glsl and remember its number.
    std::ifstream in(dir / "brdf.glsl");
    std::stringstream out;
    int lineNo = 0, broken = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        if (!broken && line.rfind("INLINE REAL D_GGX(", 0) == 0) {
            out << line << "\n    this is not glsl;\n";
            broken = ++lineNo;
            continue;
        }
        out << line << "\n";
    }
    in.close();
    std::ofstream(dir / "brdf.glsl") << out.str();
    REQUIRE(broken > 0);
    render::Renderer bad(*env.context, dir.string());
    std::string message;
    try {
        bad.render(makeScene(brdf::Model::GGX, 30), PinholeCamera::photo(45, 180, 10, 40, 8, 8), render::Output::Color);
    } catch (const SystemError& e) {
        message = e.what();
    }
    fs::remove_all(dir);
    CAPTURE(message);
    CHECK(message.find("shaders/brdf.glsl:" + std::to_string(broken)) != std::string::npos);
}

TEST_CASE("render::Renderer compiles one program per effect set") {
    auto& env = test::glEnv();
    render::Renderer r(*env.context);
    render::Scene s = makeScene(brdf::Model::GGX, 30);
    const PinholeCamera cam = PinholeCamera::photo(45, 180, 10, 40, 16, 16);
    r.render(s, cam, render::Output::Color);
    s.light.incidenceDeg = 60;
    s.brdf.roughness = 0.3;
    r.render(s, cam, render::Output::Color);
    CHECK(r.programCount() == 1);
    s.brdf.fresnel = brdf::Fresnel::Schlick;
    r.render(s, cam, render::Output::Color);
    CHECK(r.programCount() == 2);
}

TEST_CASE("render::Renderer point light: every pixel matches the double twin") {
    auto& env = test::glEnv();
    for (double inc : {0.0, 40.0, 75.0}) {
        render::Scene s = makeScene(brdf::Model::GGX, inc);
        s.light.type = render::LightType::Point;
        s.light.distance = 3.0;
        s.light.intensity = 9.0;
        s.eyeDistance = 4.0;
        CAPTURE(inc);
        const auto measureView = test::compareWithTwin(
            *env.renderer, s,
            PinholeCamera::measurementFrom(s.light.chart(), render::eyePosition(s), s.light.chart().wr(), 60, 96, 64));
        CHECK(measureView.allFinite);
        CHECK(measureView.allNonNegative);
        CHECK(measureView.compared >= 50);
        CHECK(measureView.maxRelError < 1e-4);
        const auto photo = test::compareWithTwin(*env.renderer, s, PinholeCamera::photo(30, 180, 4, 50, 96, 64));
        CHECK(photo.maxRelError < 1e-4);
    }
}

TEST_CASE("render::Renderer a cropped render leaves no scissor or viewport behind for other users of the context") {
    auto& env = test::glEnv();
    const render::Scene s = makeScene(brdf::Model::GGX, 30);
    ImageF img;
    env.renderer->render(s, measureCamera(s, 20, 64, 64), render::Output::Measure, img, dvec2(0.0),
                         PixelRect{40, 40, 8, 8});
    CHECK(img.width == 8);
    CHECK(glIsEnabled(GL_SCISSOR_TEST) == GL_FALSE);  // (found by the hard-case report: its 1x1 terms read 0)
    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);
    CHECK(viewport[2] == 64);
    CHECK(viewport[3] == 64);
}

// Frames are not cleared (the shader writes every pixel, 0 for the sky): a frame drawn over a brighter one of
// the same size, whole or cropped, holds exactly what it holds drawn alone, and its sky is 0.
TEST_CASE("render::Renderer every pixel is written: no earlier frame shows through, sky or crop") {
    auto& env = test::glEnv();
    render::Scene bright = makeScene(brdf::Model::GGX, 0);
    bright.brdf.roughness = 1.0;  // radiance on every pixel of a downward view
    render::Scene s = makeScene(brdf::Model::GGX, 80);
    const PinholeCamera down = measureCamera(bright, 60, 96, 64);
    const PinholeCamera horizon = PinholeCamera::photo(5, 180, 10, 60, 96, 64);  // half of it is sky
    for (render::Output out : {render::Output::Measure, render::Output::Color}) {
        const ImageF alone = env.renderer->render(s, horizon, out);
        int sky = 0, skyNonZero = 0;
        for (int y = 0; y < horizon.height; ++y)
            for (int x = 0; x < horizon.width; ++x)
                if (horizon.ray(x + 0.5, y + 0.5).z > 1e-6) {
                    ++sky;
                    for (int c = 0; c < 4; ++c) skyNonZero += alone.pixel(x, y)[c] != 0.f;
                }
        CHECK(sky > 1000);
        CHECK(skyNonZero == 0);
        const PixelRect crop{10, 5, 60, 50};
        for (bool cropped : {false, true}) {
            ImageF over;
            env.renderer->render(bright, down, out, over);
            env.renderer->render(s, horizon, out, over, dvec2(0.0), cropped ? crop : PixelRect{});
            int differ = 0;
            for (int y = 0; y < over.height; ++y)
                for (int x = 0; x < over.width; ++x)
                    for (int c = 0; c < 4; ++c)
                        differ +=
                            over.pixel(x, y)[c] != alone.pixel(cropped ? x + crop.x : x, cropped ? y + crop.y : y)[c];
            CAPTURE(cropped);
            CHECK(differ == 0);
        }
    }
}

// The work a measurement does while a render is drawn (the twin's widths, measurement/measure_scene.cpp) runs
// once, on the calling thread, and the pixels are the render's own.
TEST_CASE("render::Renderer work given to a render runs once while it is drawn and leaves its pixels alone") {
    auto& env = test::glEnv();
    const render::Scene s = makeScene(brdf::Model::GGX, 60);
    const PinholeCamera cam = measureCamera(s, 20, 64, 48);
    const ImageF alone = env.renderer->render(s, cam, render::Output::Measure);
    ImageF img;
    int runs = 0;
    env.renderer->render(s, cam, render::Output::Measure, img, dvec2(0.0), PixelRect{}, [&] { ++runs; });
    CHECK(runs == 1);
    REQUIRE(img.data.size() == alone.data.size());
    CHECK(img.data == alone.data);
}
