// The GLSL terms against their double twins (src/brdf/), pixel by pixel, within 1e-4
// relative: every new NDF, Fresnel, geometry and diffuse term and the classic Phong lobe, each in a
// program assembled with only the blocks it runs.

#include "brdf/energy.hpp"
#include "brdf/ndf_tables.hpp"
#include "brdf/spectral.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "render/shader_source.hpp"
#include "support/gl_fixture.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>

using namespace hilite;
using brdf::Diffuse;
using brdf::Fresnel;
using brdf::Geometry;
using brdf::Model;

namespace {

struct TermCase {
    std::string term;  ///< the term under test (a block name)
    brdf::Params p;
};

brdf::Params base(Model m, Geometry g = Geometry::Implicit) {
    brdf::Params p;
    p.model = m;
    p.geometry = g;
    p.exponent = 60.0;
    p.roughness = 0.2;
    return p;
}

brdf::Params aniso(Model m, Geometry g) {
    brdf::Params p = base(m, g);
    p.roughness = 0.3;
    p.roughnessY = 0.08;
    p.tangentAngleDeg = 30.0;
    return p;
}

brdf::Params withFresnel(brdf::Params p, Fresnel f, const dvec3& eta, const dvec3& k = dvec3(0.0)) {
    p.fresnel = f;
    p.eta = eta;
    p.k = k;
    if (f == Fresnel::Spectral) p.spectrum = brdf::loadSpectrum(HILITE_DATA_DIR, "copper", brdf::kGpuStepNm);
    return p;
}

brdf::Params tabulated(Geometry g) {
    brdf::Params p = base(Model::Tabulated, g);
    static const auto table = brdf::parseNdfTable(test::ggxTableText(0.2), "ggx.csv");
    p.ndfTable = table;
    return p;
}

brdf::Params withDiffuse(brdf::Params p, Diffuse d) {
    p.diffuse = d;
    p.albedo = {0.8, 0.5, 0.2};
    p.sigmaDeg = 30.0;
    return p;
}

/// An energy term switched on, with its tables (brdf/energy.hpp).
brdf::Params withEnergy(brdf::Params p, brdf::Multiscatter ms, Diffuse d = Diffuse::None) {
    p.multiscatter = ms;
    if (d != Diffuse::None) p = withDiffuse(p, d);
    p.energy = brdf::energyTables(p);
    return p;
}

std::vector<TermCase> termCases() {
    const dvec3 silverEta{0.140, 0.124, 0.151}, silverK{4.150, 3.348, 2.479};
    return {
        {"Phong_Classic", base(Model::PhongClassic)},
        {"D_Gaussian", base(Model::Gaussian)},
        {"D_Gaussian m = 0.02 (small-angle theta_h)",
         [] {
             brdf::Params p = base(Model::Gaussian);
             p.roughness = 0.02;
             return p;
         }()},
        {"D_Gaussian + Lambda_Beckmann", base(Model::Gaussian, Geometry::Smith)},
        {"D_BeckmannAniso + Lambda_BeckmannAniso", aniso(Model::Beckmann, Geometry::Smith)},
        {"D_GGXAniso + Lambda_GGXAniso", aniso(Model::GGX, Geometry::Smith)},
        {"G2_SmithSeparable (aniso GGX)", aniso(Model::GGX, Geometry::SmithSeparable)},
        {"G2_SmithSeparable (beckmann)", base(Model::Beckmann, Geometry::SmithSeparable)},
        {"G_CookTorrance", base(Model::GGX, Geometry::CookTorrance)},
        {"G = 1", base(Model::Beckmann, Geometry::None)},
        {"F_Dielectric", withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Dielectric, {1.333, 1.5, 2.417})},
        // eta < 1: the incidences below keep the critical angle (44.4 deg) out of the compared pixels,
        // where F's infinite slope turns float rounding into 4e-4 (see shaders/brdf.glsl F_Dielectric).
        {"F_Dielectric eta < 1", withFresnel(base(Model::GGX), Fresnel::Dielectric, dvec3(0.7))},
        {"F_Conductor", withFresnel(base(Model::Blinn, Geometry::Smith), Fresnel::Conductor, silverEta, silverK)},
        {"F_Spectral (copper, 81 wavelengths, exact)",
         [] {
             brdf::Params p = withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Spectral, dvec3(1.0));
             p.spectralTable = false;
             return p;
         }()},
        {"F_SpectralTable (copper)", withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Spectral, dvec3(1.0))},
        {"Fd_Lambert + D_GGX", withDiffuse(base(Model::GGX, Geometry::Smith), Diffuse::Lambert)},
        {"Fd_OrenNayar", withDiffuse(base(Model::None), Diffuse::OrenNayar)},
        {"Fd_OrenNayar + Phong_Normalized", withDiffuse(base(Model::Phong), Diffuse::OrenNayar)},
        {"Retro_Normalized", base(Model::Retro)},        // its framing: tests/render/test_retro.cpp
        {"D_Tabulated", tabulated(Geometry::Implicit)},  // A GGX table (tests/render/test_ndf_table_gl.cpp)
        {"D_Tabulated + Lambda_Tabulated + F_Schlick",
         withFresnel(tabulated(Geometry::Smith), Fresnel::Schlick, dvec3(1.5))},
        {"MS_KullaConty (GGX, conductor)",
         withEnergy(withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Conductor, silverEta, silverK),
                    brdf::Multiscatter::KullaConty)},
        {"MS_KullaConty (beckmann, F = 1, separable)",
         [] {
             brdf::Params p = base(Model::Beckmann, Geometry::SmithSeparable);
             p.roughness = 0.6;
             return withEnergy(p, brdf::Multiscatter::KullaConty);
         }()},
        {"Fd_Coupled (GGX dielectric)",
         withEnergy(withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Dielectric, dvec3(1.5)),
                    brdf::Multiscatter::None, Diffuse::Coupled)},
        {"Fd_Coupled + MS_KullaConty (copper)",
         withEnergy(withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Spectral, dvec3(1.0)),
                    brdf::Multiscatter::KullaConty, Diffuse::Coupled)},
    };
}

PinholeCamera measureCamera(const render::Scene& s, double fov, int w, int h) {
    const MirrorChart chart = s.light.chart();
    dvec3 c = s.brdf.model == Model::Retro ? s.light.direction() : chart.wr();  // the lobe's axis
    if (c.z < 1e-3) c = glm::normalize(dvec3(c.x, c.y, 1e-3));
    return PinholeCamera::measurement(chart, c, fov, w, h);
}

}  // namespace

TEST_CASE("render::Renderer every reflectance term matches its double twin within 1e-4") {
    auto& env = test::glEnv();
    std::map<std::string, double> worst;
    for (const TermCase& t : termCases())
        for (double incidence : {0.0, 30.0, 60.0, 80.0}) {
            render::Scene s;
            s.brdf = t.p;
            s.light.incidenceDeg = incidence;
            s.light.azimuthDeg = 15.0;  // off the tangent axes of the anisotropic cases
            const auto r = test::compareWithTwin(*env.renderer, s, measureCamera(s, 50, 96, 64));
            CAPTURE(t.term);
            CAPTURE(incidence);
            CHECK(r.allFinite);
            CHECK(r.allNonNegative);
            CHECK(r.compared >= 50);
            CHECK(r.maxRelError < 1e-4);
            worst[t.term] = std::max(worst[t.term], r.maxRelError);
        }
    for (const auto& [term, err] : worst) MESSAGE(term << ": worst GL vs twin relative error " << err);
}

// Measurement programs interpolate the spectral table's luminances (one gather per entry, not three): their
// L must be the twin's luminance, with diffuse and multiple scattering added beside the specular term's F.
TEST_CASE("render::Renderer the measurement output's spectral table: L is the twin's luminance within 1e-4") {
    auto& env = test::glEnv();
    const brdf::Params plain = withFresnel(base(Model::GGX, Geometry::Smith), Fresnel::Spectral, dvec3(1.0));
    const brdf::Params full = withEnergy(plain, brdf::Multiscatter::KullaConty, Diffuse::Coupled);
    for (const brdf::Params& p : {plain, full})
        for (double incidence : {0.0, 45.0, 80.0}) {
            render::Scene s;
            s.brdf = p;
            s.light.incidenceDeg = incidence;
            const PinholeCamera cam = measureCamera(s, 50, 96, 64);
            const ImageF img = env.renderer->render(s, cam, render::Output::Measure);
            double peak = 0, worst = 0;
            std::vector<double> twin(size_t(cam.width) * size_t(cam.height), 0.0);
            for (int y = 0; y < cam.height; ++y)
                for (int x = 0; x < cam.width; ++x) {
                    const dvec3 we = -cam.ray(x + 0.5, y + 0.5);
                    const double t = we.z > 0 ? brdf::luminance(render::surfaceRadiance(s, cam.position, we)) : 0.0;
                    twin[size_t(y) * size_t(cam.width) + size_t(x)] = t;
                    peak = std::max(peak, t);
                }
            int compared = 0;
            for (size_t i = 0; i < twin.size(); ++i)
                if (twin[i] > 1e-3 * peak) {
                    worst = std::max(worst, std::abs(double(img.data[4 * i]) - twin[i]) / twin[i]);
                    ++compared;
                }
            CAPTURE(incidence);
            CHECK(compared >= 50);
            CHECK(worst < 1e-4);
            MESSAGE("spectral table, measurement output, " << incidence << " deg: worst relative error " << worst);
        }
}

TEST_CASE("render::assemble a program holds exactly the terms it runs") {
    const std::string dir = render::shaderDirectory();
    auto fragment = [&](const brdf::Params& p) {
        std::string text;
        for (const auto& piece : render::assemble(p, render::Output::Color, dir).fragment) text += piece.text;
        return text;
    };
    const std::vector<std::string> terms = {
        "Phong_Normalized(",     "Phong_Classic(",      "D_BlinnPhong(",      "D_Beckmann(",       "D_GGX(",
        "D_Gaussian(",           "D_BeckmannAniso(",    "D_GGXAniso(",        "F_Schlick(",        "F_Dielectric(",
        "F_Conductor(",          "F_Spectral(",         "Lambda_GGX(",        "Lambda_Beckmann(",  "Lambda_GGXAniso(",
        "Lambda_BeckmannAniso(", "G2_SmithCorrelated(", "G2_SmithSeparable(", "G_CookTorrance(",   "Fd_Lambert(",
        "Fd_OrenNayar(",         "Retro_Normalized(",   "D_Tabulated(",       "Lambda_Tabulated(", "F_SpectralTable(",
        "MS_KullaConty(",        "Fd_Coupled("};
    for (const TermCase& t : termCases()) {
        const std::string text = fragment(t.p);
        const auto blocks = render::termBlocks(t.p);
        CAPTURE(t.term);
        for (const std::string& term : terms) {
            const std::string name = term.substr(0, term.size() - 1);
            bool named = std::find(blocks.begin(), blocks.end(), name) != blocks.end();
            // A block's dependencies come along: F_Spectral calls F_Conductor, the anisotropic Beckmann
            // Lambda shares nothing with Lambda_Beckmann but its rational fit.
            if (name == "F_Conductor" && t.p.fresnel == Fresnel::Spectral && !t.p.spectralTable) named = true;
            CAPTURE(name);
            CHECK((text.find(term) != std::string::npos) == named);
        }
    }
    brdf::Params none = base(Model::GGX);
    const std::string text = fragment(none);
    CHECK(text.find("fresnel") == std::string::npos);
    CHECK(text.find("F_") == std::string::npos);
    // Without the energy terms the program holds none of their text: it is the program it was before them.
    for (const char* word : {"multiscatter", "energyE", "HILITE_ENERGY", "Fd_Coupled"}) {
        CAPTURE(word);
        CHECK(text.find(word) == std::string::npos);
    }
}

TEST_CASE("render::termUniforms and the program cache: one program per effect set") {
    auto& env = test::glEnv();
    render::Renderer r(*env.context);
    render::Scene s;
    s.brdf = aniso(Model::GGX, Geometry::Smith);
    const PinholeCamera cam = PinholeCamera::photo(45, 180, 10, 40, 16, 16);
    r.render(s, cam, render::Output::Color);
    s.brdf.roughnessY = 0.5;
    s.brdf.tangentAngleDeg = -10;
    r.render(s, cam, render::Output::Color);
    CHECK(r.programCount() == 1);
    s.brdf.roughnessY.reset();  // isotropic: another program
    r.render(s, cam, render::Output::Color);
    CHECK(r.programCount() == 2);
}

TEST_CASE("render::dataDirectory finds the data beside the executable, or $HILITE_DATA_DIR") {
    const std::string besideExe = render::dataDirectory();
    CHECK(besideExe.find("share/hilite/data") != std::string::npos);
    ::setenv("HILITE_DATA_DIR", HILITE_DATA_DIR, 1);
    CHECK(render::dataDirectory() == HILITE_DATA_DIR);
    ::setenv("HILITE_DATA_DIR", "/nonexistent", 1);  // not a data directory: the next place is used
    CHECK(render::dataDirectory() == besideExe);
    ::unsetenv("HILITE_DATA_DIR");
}
