// `hilite brdf` in-process: what its subcommands compute, through the library as src/cli/brdf_cmd.cpp calls
// it (each subcommand's defaults under the flags, scene::resolve with Purpose::Brdf, scene::resolveFresnel),
// and the refusals of the flags it reads. The tables and JSON lines it prints, and the refusals of its own
// options (--roughness lists, -o): tests/cli/test_cli.cpp and test_hostile.cpp.

#include "brdf/bihemispherical.hpp"
#include "brdf/integrate.hpp"
#include "brdf/merl.hpp"
#include "brdf/spectral.hpp"
#include "core/text.hpp"
#include "experiments/strip.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "render/renderer.hpp"
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace hilite;
using namespace hilite::testing;

namespace {

/// The values of `hilite brdf SUB ARGS`: the subcommand's default incidence (and size) under the flags.
scene::Values brdfValues(const std::string& sub, const std::string& args) {
    scene::Values v = flags(args);
    if (sub == "albedo") v.setDefault("incidence", "0:85:5");
    if (sub == "fresnel") v.setDefault("incidence", "0:90:5");
    if (sub == "normalization" || sub == "strip") v.setDefault("incidence", "0");
    if (sub == "strip") v.setDefault("size", "512x64");
    return v;
}

/// `hilite brdf fresnel ARGS`: F (r, g, b) per incidence angle.
std::vector<dvec3> fresnelRows(const std::string& args, std::vector<double>* thetas = nullptr) {
    const scene::Values v = brdfValues("fresnel", args);
    const brdf::Params p = scene::resolveFresnel(v, false);
    const auto angles = scene::resolve(v, scene::Purpose::Brdf).angles;
    if (thetas) *thetas = angles;
    std::vector<dvec3> rows;
    for (double t : angles) rows.push_back(brdf::fresnel(p, std::cos(t * M_PI / 180)));
    return rows;
}

/// `hilite brdf albedo ARGS`: the directional albedo per incidence angle.
std::vector<dvec3> albedoRows(const std::string& args) {
    const scene::Resolved r = scene::resolve(brdfValues("albedo", args), scene::Purpose::Brdf);
    std::vector<dvec3> rows;
    for (double t : r.angles) rows.push_back(brdf::albedo(r.scene.brdf, t, r.scene.light.azimuthDeg));
    return rows;
}

/// What `hilite explain ARGS --part effects` prints.
std::string effects(const std::string& args) {
    std::string out;
    for (const auto& e : render::activeEffects(scene::resolve(flags(args)).scene)) out += e + "\n";
    return out;
}

/// `hilite brdf normalization --model M --roughness|--exponent V`: int D(h) (n.h) dw_h.
double normalization(const std::string& model, double v) {
    scene::Values s = brdfValues("normalization", "--model " + model);
    const bool exponent = model == "blinn";
    s.set(exponent ? "exponent" : "roughness", exactText(v), exponent ? "--exponent" : "--roughness");
    return brdf::ndfIntegral(scene::resolve(s, scene::Purpose::Brdf).scene.brdf);
}

}  // namespace

TEST_CASE("brdf fresnel: F per incidence angle, copper is spectral") {
    std::vector<double> thetas;
    const auto rows = fresnelRows("--material copper --incidence 0:90:30", &thetas);
    REQUIRE(rows.size() == 4);
    CHECK(thetas[0] == 0.0);
    const dvec3 rgb = rows[0];
    CHECK(rgb.x > rgb.y);
    CHECK(rgb.y > rgb.z);
    CHECK(rows[3].z == doctest::Approx(1.0));
    const scene::Values copper = brdfValues("fresnel", "--material copper --incidence 0");
    CHECK((scene::resolveFresnel(copper, false).fresnel == brdf::Fresnel::Spectral));
    const auto glass = fresnelRows("--fresnel dielectric --eta 1.5 --incidence 45");
    CHECK(glass.at(0).x == doctest::Approx(0.0502399).epsilon(1e-6));
}

TEST_CASE("brdf albedo: albedo per incidence angle, and the bihemispherical albedo") {
    const std::string args = "--model none --diffuse lambert --albedo 0.2,0.4,0.6 --incidence 0,60";
    const auto rows = albedoRows(args);
    REQUIRE(rows.size() == 2);
    CHECK(rows[1].z == doctest::Approx(0.6).epsilon(1e-6));
    // Lambert's bihemispherical albedo is rho itself.
    const dvec3 hh =
        brdf::bihemisphericalAlbedo(scene::resolve(brdfValues("albedo", args), scene::Purpose::Brdf).scene.brdf);
    CHECK(hh.x == doctest::Approx(0.2).epsilon(1e-6));
    CHECK(hh.y == doctest::Approx(0.4).epsilon(1e-6));
}

TEST_CASE("brdf albedo --multiscatter kulla-conty: the white furnace, single scattering beside it") {
    const auto single = albedoRows("--roughness 1 --geometry smith --incidence 0,60");
    const auto ms = albedoRows("--roughness 1 --geometry smith --multiscatter kulla-conty --incidence 0,60");
    REQUIRE(single.size() == 2);
    REQUIRE(ms.size() == 2);
    CHECK(single[0].x == doctest::Approx(0.3068528).epsilon(1e-6));  // 1 - ln 2
    for (const auto& line : ms) CHECK_NEAR(line.y, 1.0, 1e-3);
    const std::string explain = effects("--roughness 1 --geometry smith --multiscatter kulla-conty");
    CHECK(explain.find("MS_KullaConty") != std::string::npos);
    CHECK(explain.find("Kulla & Conty 2017") != std::string::npos);
    CHECK(effects("--roughness 1 --geometry smith").find("KullaConty") == std::string::npos);
    CHECK(effects("--fresnel dielectric --geometry smith --diffuse coupled").find("Fd_Coupled") != std::string::npos);
}

TEST_CASE("brdf normalization: the NDF's integral") {
    CHECK(normalization("ggx", 1) == doctest::Approx(1.0).epsilon(1e-6));
    // The JSON lines' fields (roughness, exponent, integral; null where a model has none): tests/cli/test_cli.cpp.
}

TEST_CASE("brdf strip writes the PNG") {
    hilite_test::TempDir dir("hilite-strip");
    const std::string png = dir / "strip.png";
    const scene::Values v = brdfValues("strip", "--material gold --size 64x8");
    const brdf::Params p = scene::resolveFresnel(v, false);
    const scene::Resolved r = scene::resolve(v, scene::Purpose::Brdf);
    CHECK(r.setup.width == 64);
    CHECK(r.setup.height == 8);
    experiments::writeFresnelStrip(p, r.setup.width, r.setup.height, png);
    REQUIRE(std::filesystem::exists(png));
    std::ifstream in(png, std::ios::binary);
    char sig[8] = {};
    in.read(sig, 8);
    CHECK(std::string(sig + 1, 3) == "PNG");
}

TEST_CASE("brdf bad input: one line naming the flag") {
    struct Case {
        const char* args;
        const char* mentions;
    };
    // fresnel and strip read the Fresnel term (resolveFresnel), albedo the whole BRDF (resolve for Brdf).
    for (const Case c :
         {Case{"--material unobtainium", "--material"}, Case{"--eta -1", "--eta"},
          Case{"--fresnel conductor --k nan", "--k"}, Case{"--eta 1,2", "--eta"}, Case{"", "--fresnel"},
          Case{"--fresnel spectral", "--fresnel"}, Case{"--material iron --fresnel conductor", "--fresnel"},
          Case{"--material copper --fresnel dielectric", "--fresnel"},
          Case{"--material glass --incidence 91", "--incidence"}}) {
        CAPTURE(c.args);
        const scene::Values v = brdfValues("fresnel", c.args);
        const std::string why = !flagCheck(v).empty() ? flagCheck(v) : inputError([&] {
            scene::resolveFresnel(v, false);
            scene::resolve(v, scene::Purpose::Brdf);
        });
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.mentions) != std::string::npos);
    }
    {  // fresnel --material glass --spectral: measured spectra for copper and gold only
        const std::string why =
            inputError([] { scene::resolveFresnel(brdfValues("fresnel", "--material glass"), true); });
        CHECK(oneLine(why));
        CHECK(why.find("--spectral") != std::string::npos);
    }
    for (const Case c :
         {Case{"--model lambertian", "--model"}, Case{"--roughness 0", "--roughness"},
          Case{"--model blinn --roughness-y 0.1", "--roughness-y"}, Case{"--roughness-y inf", "--roughness-y"},
          Case{"--tangent-angle 1e9", "--tangent-angle"}, Case{"--diffuse chalk", "--diffuse"},
          Case{"--albedo 1.5", "--albedo"}, Case{"--sigma 100", "--sigma"}, Case{"--geometry ct", "--geometry"},
          Case{"--multiscatter heitz", "--multiscatter"},
          Case{"--multiscatter kulla-conty", "--multiscatter"},  // implicit G: not Smith's loss
          Case{"--multiscatter kulla-conty --geometry smith --roughness-y 0.3", "--multiscatter"},
          Case{"--model phong --multiscatter kulla-conty --geometry smith", "--multiscatter"},
          Case{"--diffuse coupled --geometry none", "--diffuse"}}) {
        CAPTURE(c.args);
        const std::string why = refusal(brdfValues("albedo", c.args), scene::Purpose::Brdf);
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.mentions) != std::string::npos);
    }
    // render with the same terms: --k without a conductor (src/cli/render_cmd.cpp resolves for Render).
    const std::string k = refusal(flags("--size 16 --fresnel dielectric --k 2"), scene::Purpose::Render);
    CHECK(oneLine(k));
    CHECK(k.find("--k") != std::string::npos);
}

TEST_CASE("render takes the reflectance terms") {
    const scene::Resolved r = scene::resolve(flags("--size 16 --model ggx --roughness 0.2 --roughness-y 0.05 "
                                                   "--tangent-angle 30 --material copper --geometry smith-separable "
                                                   "--diffuse oren-nayar --sigma 20"),
                                             scene::Purpose::Render);
    const brdf::Params& p = r.scene.brdf;
    CHECK((p.fresnel == brdf::Fresnel::Spectral));
    REQUIRE(p.spectrum);
    CHECK(p.spectrum->name == "copper");
    CHECK(p.spectrum->size() == 81);
    CHECK((p.geometry == brdf::Geometry::SmithSeparable));
    CHECK((p.diffuse == brdf::Diffuse::OrenNayar));
    CHECK(p.anisotropic());
    // The log line render prints ("material=copper wavelengths=81"): tests/cli/test_cli.cpp.
}

TEST_CASE("brdf tabulate: GGX 0.1 smith schlick as a MERL table equal to brdf::evaluate at its bin centres") {
    hilite_test::TempDir dir("hilite-tabulate");
    const std::string out = dir / "ggx.binary";
    const brdf::Params resolved =
        scene::resolve(flags("--model ggx --roughness 0.1 --geometry smith --fresnel schlick --f0 0.04"),
                       scene::Purpose::Brdf)
            .scene.brdf;
    { std::ofstream(out, std::ios::binary) << brdf::merl::encode(brdf::merl::tabulate(resolved)); }
    REQUIRE(std::filesystem::file_size(out) == brdf::merl::kFileBytes);
    namespace merl = brdf::merl;
    const merl::MeasuredBrdf m = merl::read(out);
    brdf::Params p;
    p.model = brdf::Model::GGX;
    p.roughness = 0.1;
    p.geometry = brdf::Geometry::Smith;
    p.fresnel = brdf::Fresnel::Schlick;
    p.f0 = dvec3(0.04);
    CHECK(m.raw == merl::tabulate(p).raw);  // the flags resolve to these terms, and the file holds their table
    int checked = 0;
    for (int ih : {0, 3, 20, 45, 80})
        for (int id : {0, 30, 60})
            for (int ip : {0, 90, 179}) {
                dvec3 wi, wo;
                merl::fromHalfDiff(merl::thetaHalfAt(ih + 0.5), merl::thetaDiffAt(id + 0.5), merl::phiDiffAt(ip + 0.5),
                                   wi, wo);
                if (wi.z <= 0 || wo.z <= 0) continue;
                const dvec3 want = brdf::evaluate(p, wi, wo), got = m.evaluate(wi, wo, merl::Interpolation::Nearest);
                for (int c = 0; c < 3; ++c) CHECK_NEAR(got[c], want[c], 2.3e-16 * want[c]);
                ++checked;
            }
    CHECK(checked > 30);
}

TEST_CASE("brdf tabulate: anisotropic or bad terms are refused in one line") {
    // As src/cli/brdf_cmd.cpp's runTabulate: the terms resolve, and a MERL table is isotropic.
    const scene::Values aniso = flags("--model ggx --roughness 0.1 --roughness-y 0.3");
    CHECK(scene::resolve(aniso, scene::Purpose::Brdf).scene.brdf.anisotropic());
    CHECK(aniso.where("roughness_y") == "--roughness-y");
    const std::string bad = refusal(flags("--model ggx --roughness -1"), scene::Purpose::Brdf);
    CHECK(oneLine(bad));
    CHECK(bad.find("--roughness") != std::string::npos);
    // The message naming --roughness-y, and the -o refusals with nothing written: tests/cli/test_hostile.cpp.
}
