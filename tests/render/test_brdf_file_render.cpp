// .brdf files in GL: the shipped files render the built-in models' pixels, parameters reach their uniforms,
// BRDF Explorer's GLSL style compiles, and GLSL errors name the .brdf file's own lines.

#include "render/renderer.hpp"

#include "hilite/core/error.hpp"
#include "support/gl_fixture.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace hilite;

namespace {

std::shared_ptr<const brdf_file::BrdfFile> fromText(const std::string& text, const std::string& assignments = "") {
    auto f = std::make_shared<brdf_file::BrdfFile>(brdf_file::parse(text, "t.brdf"));
    if (!assignments.empty()) brdf_file::assign(*f, assignments);
    return f;
}

std::shared_ptr<const brdf_file::BrdfFile> shipped(const std::string& name, const std::string& assignments) {
    auto f = std::make_shared<brdf_file::BrdfFile>(
        brdf_file::load(std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/" + name + ".brdf"));
    brdf_file::assign(*f, assignments);
    return f;
}

PinholeCamera camera(const render::Scene& s, double fov, int w, int h) {
    const MirrorChart chart = s.light.chart();
    dvec3 c = chart.wr();
    if (c.z < 1e-3) c = glm::normalize(dvec3(c.x, c.y, 1e-3));
    return PinholeCamera::measurement(chart, c, fov, w, h);
}

/// The InputError message of rendering `text` ("" if none).
std::string buildError(const std::string& text) {
    render::Scene s;
    s.brdfFile = fromText(text);
    try {
        (void)test::glEnv().renderer->render(s, camera(s, 30, 8, 8), render::Output::Color);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const std::string kHead = "analytic\n::begin parameters\nfloat n 1 100 10\n::end parameters\n::begin shader\n";

}  // namespace

TEST_CASE("render::Renderer shipped .brdf files give the built-in models' pixels") {
    struct Case {
        const char* file;
        const char* assignments;
        brdf::Model model;
        double param;
    };
    for (const Case& c :
         {Case{"phong", "n=1000", brdf::Model::Phong, 1000}, Case{"phong", "n=50", brdf::Model::Phong, 50},
          Case{"blinn", "n=300", brdf::Model::Blinn, 300}, Case{"beckmann", "m=0.15", brdf::Model::Beckmann, 0.15},
          Case{"ggx", "alpha=0.1", brdf::Model::GGX, 0.1}, Case{"ggx", "alpha=0.01", brdf::Model::GGX, 0.01}}) {
        for (double inc : {0.0, 45.0, 80.0}) {
            CAPTURE(c.file);
            CAPTURE(c.param);
            CAPTURE(inc);
            render::Scene builtin;
            builtin.brdf.model = c.model;
            (brdf::usesExponent(c.model) ? builtin.brdf.exponent : builtin.brdf.roughness) = c.param;
            builtin.light.incidenceDeg = inc;
            render::Scene file = builtin;
            file.brdfFile = shipped(c.file, c.assignments);
            // Field of view a few half-widths across: compare where the lobe is, against the built-in's twin.
            const double fov = std::min(
                60.0, 6.0 * rad2deg(std::sqrt(2.0 * std::log(2.0) /
                                              (brdf::usesExponent(c.model) ? c.param : 2.0 / (c.param * c.param)))));
            const PinholeCamera cam = camera(builtin, fov, 96, 64);
            const ImageF img = test::glEnv().renderer->render(file, cam, render::Output::Color);
            double peak = 0, maxRel = 0;
            int compared = 0;
            std::vector<double> twin(size_t(cam.width * cam.height));
            for (int y = 0; y < cam.height; ++y)
                for (int x = 0; x < cam.width; ++x) {
                    const dvec3 we = -cam.ray(x + 0.5, y + 0.5);
                    const double t = we.z > 0 ? render::surfaceRadiance(builtin, cam.position, we).x : 0.0;
                    twin[size_t(y * cam.width + x)] = t;
                    peak = std::max(peak, t);
                }
            for (size_t i = 0; i < twin.size(); ++i)
                if (twin[i] > 1e-3 * peak) {
                    maxRel = std::max(maxRel, std::abs(img.data[4 * i] - twin[i]) / twin[i]);
                    ++compared;
                }
            CHECK(compared >= 50);
            CHECK(maxRel < 1e-4);
        }
    }
}

TEST_CASE("render::Renderer .brdf parameters are uniforms: float, bool, color, tangent frame") {
    const std::string text =
        "analytic\n::begin parameters\nfloat k 0 10 2\nbool twice 0\ncolor tint 1 0.5 0.25\n"
        "::end parameters\n::begin shader\n"
        "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n"
        "    return tint * k * (twice ? 2.0 : 1.0) * (1.0 + X.y + 2.0 * Y.x * Y.x);\n}\n"
        "::end shader\n";
    render::Scene s;
    s.light.incidenceDeg = 0;  // E cos(theta_i) = 1: pixels are f itself
    auto value = [&](const std::string& assignments, double tangentDeg) {
        s.brdfFile = fromText(text, assignments);
        s.brdf.tangentAngleDeg = tangentDeg;
        const ImageF img = test::glEnv().renderer->render(s, camera(s, 30, 4, 4), render::Output::Color);
        return dvec3(img.pixel(1, 1)[0], img.pixel(1, 1)[1], img.pixel(1, 1)[2]);
    };
    const dvec3 base = value("", 0);
    CHECK(base.x == doctest::Approx(2.0));
    CHECK(base.y == doctest::Approx(1.0));
    CHECK(base.z == doctest::Approx(0.5));
    CHECK(value("k=3,twice=1,tint=0.5", 0).x == doctest::Approx(3.0));
    // X = (cos, sin, 0), Y = (-sin, cos, 0): at 30 degrees X.y = 0.5 and Y.x^2 = 0.25.
    CHECK(value("", 30).x == doctest::Approx(2.0 * (1.0 + 0.5 + 0.5)).epsilon(1e-5));
    CHECK(test::glEnv().renderer->programCount() >= 1);
}

TEST_CASE("render::Renderer compiles BRDF Explorer's GLSL style") {
    // GLSL 1.x-4.1 habits: integer literals in float expressions, vec3(0), uniform bool in a ternary, a
    // global const PI (hilite's own PI is not in a .brdf program), helper functions, pow with max.
    const std::string text = kHead +
                             "const float PI = 3.14159265358979323846;\n"
                             "float sqr(float x) { return x*x; }\n"
                             "vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )\n{\n"
                             "    float NdotL = dot(N, L);\n"
                             "    if (NdotL < 0 || dot(N, V) < 0) return vec3(0);\n"
                             "    vec3 H = normalize(L+V);\n"
                             "    float val = pow(max(0,dot(N,H)),n) * (n+2)/(2*PI);\n"
                             "    float shared = 1.0, buffer = 1.0;  // keywords since GLSL 4.30, names in 4.10\n"
                             "    return vec3(sqr(1) * val * shared * buffer);\n}\n::end shader\n";
    CHECK(buildError(text) == "");
    // Negative and NaN results become 0, as BRDF Explorer clamps.
    render::Scene s;
    s.brdfFile = fromText(
        kHead +
        "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(-1.0, sqrt(-n), 2.0); }\n::end shader\n");
    const ImageF img = test::glEnv().renderer->render(s, camera(s, 30, 4, 4), render::Output::Color);
    CHECK(img.pixel(2, 2)[0] == 0.f);
    CHECK(img.pixel(2, 2)[1] == 0.f);
    CHECK(img.pixel(2, 2)[2] > 0.f);
}

TEST_CASE("render::Renderer GLSL errors in a .brdf name its own lines") {
    SUBCASE("an undeclared name on line 8") {
        const std::string e = buildError(kHead +
                                         "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n"
                                         "    float a = dot(N, L);\n    return vec3(a * undeclaredThing);\n}\n"
                                         "::end shader\n");
        INFO(e);
        CHECK(e.rfind("t.brdf:8:", 0) == 0);
        CHECK(e.find("undeclaredThing") != std::string::npos);
        CHECK(e.find('\n') == std::string::npos);
    }
    SUBCASE("a syntax error, with more errors after it") {
        const std::string e = buildError(kHead +
                                         "float f(float x) { return x }\n"
                                         "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(f(n)); }\n"
                                         "::end shader\n");
        INFO(e);
        CHECK(e.rfind("t.brdf:6:", 0) == 0);
    }
    SUBCASE("a parameter named like a GLSL keyword: the declaration's line") {
        const std::string e = buildError(
            "analytic\n::begin parameters\nfloat n 0 1 0\nfloat sample 0 1 0\n::end parameters\n"
            "::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(n); }\n"
            "::end shader\n");
        INFO(e);
        CHECK(e.rfind("t.brdf:4:", 0) == 0);
    }
    SUBCASE("BRDF with another signature") {
        const std::string e = buildError(kHead + "vec3 BRDF(vec3 L, vec3 V) { return L * n; }\n::end shader\n");
        INFO(e);
        CHECK(e.rfind("t.brdf:5: BRDF cannot be called as vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)", 0) == 0);
    }
    SUBCASE("a name hilite's shader defines") {
        const std::string e = buildError(kHead +
                                         "float luminance(vec3 c) { return c.x; }\n"
                                         "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(n); }\n"
                                         "::end shader\n");
        INFO(e);
        CHECK(e.rfind("t.brdf:6:", 0) == 0);
        CHECK(e.find("'luminance' is a name of hilite's shader") != std::string::npos);
        const std::string u = buildError(
            "analytic\n::begin parameters\nfloat uWi 0 1 0\n::end parameters\n::begin shader\n"
            "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(uWi); }\n"
            "::end shader\n");
        INFO(u);
        CHECK(u.rfind("t.brdf:3:", 0) == 0);
    }
}

// A .brdf file's GLSL may discard: its frames are cleared, so a discarded pixel reads 0, not an earlier frame.
TEST_CASE("render::Renderer a .brdf that discards leaves 0, not the previous frame") {
    auto& env = test::glEnv();
    render::Scene bright;
    bright.brdf.model = brdf::Model::GGX;
    bright.brdf.roughness = 1.0;
    render::Scene s;
    s.brdfFile = fromText(kHead +
                          "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n"
                          "    if (V.y > 0.0) discard;\n    return vec3(1.0);\n}\n::end shader\n");
    const PinholeCamera cam = camera(bright, 60, 48, 32);
    ImageF img;
    env.renderer->render(bright, cam, render::Output::Color, img);
    env.renderer->render(s, cam, render::Output::Color, img);
    int discarded = 0, kept = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const float* p = img.pixel(x, y);
            if (p[3] == 0.f) {
                ++discarded;
                CHECK(p[0] == 0.f);
            } else {
                ++kept;
            }
        }
    CHECK(discarded > 100);
    CHECK(kept > 100);
}
