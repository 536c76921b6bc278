// The command line as a user meets it: exit codes, one-line errors, nothing written on bad input. What `measure`
// measures, warns and refuses is tested in-process: tests/measurement/test_measure_flags.cpp.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace hilite_test;

namespace {

std::string tmpPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("hilite-cli-" + std::to_string(getpid()) + "-" + name)).string();
}

}  // namespace

TEST_CASE("cli::render bad input: one line naming the flag, exit 2, nothing written") {
    const std::string out = tmpPath("bad.png");
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c :
         {Case{"--model lambertian", "--model"}, Case{"--roughness -1", "--roughness"},
          Case{"--roughness nan", "--roughness"}, Case{"--roughness inf", "--roughness"},
          Case{"--exponent -5", "--exponent"}, Case{"--exponent nan", "--exponent"},
          Case{"--incidence 91", "--incidence"}, Case{"--incidence -1", "--incidence"}, Case{"--size 0", "--size"},
          Case{"--size 16385", "--size"}, Case{"--size 16384x16384x", "--size"}, Case{"--fresnel maybe", "--fresnel"},
          Case{"--f0 1.5", "--f0"}, Case{"--geometry none2", "--geometry"}, Case{"--view sideways", "--view"},
          Case{"--light spot", "--light"}, Case{"--light-distance 0", "--light-distance"},
          Case{"--intensity -1", "--intensity"}}) {
        CAPTURE(c.args);
        const auto r = hilite(std::string("render ") + c.args + " -o " + out);
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
        CHECK(r.out.find(c.mentions) != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(out));
    }
}

TEST_CASE("cli::render an unwritable output leaves an existing file untouched") {
    const auto r = hilite("render --size 8 -o /nonexistent-dir/x.png");
    CHECK(r.code == 2);
    CHECK(r.out.find("-o") != std::string::npos);
    CHECK(lines(r.out) == 1);

    const std::string good = tmpPath("keep.png");
    std::ofstream(good) << "precious";
    const auto bad = hilite("render --size 8 --roughness -3 -o " + good);
    CHECK(bad.code == 2);
    std::stringstream ss;
    ss << std::ifstream(good).rdbuf();
    CHECK(ss.str() == "precious");
    std::filesystem::remove(good);
}

TEST_CASE("cli::render writes PNG and PFM") {
    const std::string png = tmpPath("ok.png"), pfm = tmpPath("ok.pfm");
    const auto r =
        hilite("render --size 16x8 --model phong --exponent 100 --incidence 30 -o " + png + " --float " + pfm);
    CHECK(r.code == 0);
    CHECK(std::filesystem::file_size(pfm) == std::string("PF\n16 8\n-1.0\n").size() + 16 * 8 * 3 * 4);
    CHECK(std::filesystem::file_size(png) > 8);
    std::filesystem::remove(png);
    std::filesystem::remove(pfm);
}

TEST_CASE("cli help documents every subcommand") {
    const auto r = hilite("--help");
    CHECK(r.code == 0);
    for (const char* sub : {"render", "measure"}) CHECK(r.out.find(sub) != std::string::npos);
    const auto m = hilite("measure --help");
    CHECK(m.out.find("--threshold") != std::string::npos);
}

TEST_CASE("cli::measure's table prints what the row says: the framing (retroreflection), the tolerance line") {
    // The rows' framed_about, peak_offset_deg and tolerance fields: tests/measurement/test_measure_flags.cpp.
    const auto t = hilite("measure --model retro --exponent 1000 --incidence 60 --size 64", true);
    CHECK(t.code == 0);
    CHECK(t.out.find("about the peak, 120 deg from the mirror direction") != std::string::npos);
    const auto tol = hilite("measure --model ggx --roughness 0.1 --incidence 60 --tolerance 1e-2", true);
    CHECK(tol.code == 0);
    CHECK(tol.out.find("tolerance 0.01:") != std::string::npos);
    const auto brdf = hilite(
        "measure --brdf " + std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/phong.brdf --incidence 30", true);
    CHECK(brdf.code == 0);
    CHECK(brdf.out.find("error estimate (resolution convergence, no CPU twin for .brdf)") != std::string::npos);
}

TEST_CASE("cli::brdf prints tables and JSON lines with the documented fields, and says what it wrote") {
    // What the subcommands compute: tests/brdf/test_brdf_cmd.cpp, tests/experiments/test_bounces.cpp.
    const auto fresnel = hilite("brdf fresnel --material copper --incidence 0:90:30 --json");
    REQUIRE(fresnel.code == 0);
    CHECK(lines(fresnel.out) == 4);
    CHECK(fresnel.out.rfind("{\"theta_deg\":0.0,\"rgb\":[", 0) == 0);
    CHECK(hilite("brdf fresnel --material copper --incidence 0").out.find("spectral") != std::string::npos);
    const auto albedo =
        hilite("brdf albedo --model none --diffuse lambert --albedo 0.2,0.4,0.6 --incidence 0,60 --json");
    REQUIRE(albedo.code == 0);
    CHECK(lines(albedo.out) == 2);
    CHECK(albedo.out.find("{\"theta_deg\":60.0,\"albedo\":[") != std::string::npos);
    CHECK(albedo.out.find("\"bihemispherical_albedo\":[") != std::string::npos);
    const auto table = hilite("brdf albedo --model none --diffuse lambert --albedo 0.3 --incidence 0");
    CHECK(table.out.find("# bihemispherical albedo") != std::string::npos);
    const auto ggx = hilite("brdf normalization --model ggx --roughness 0.02,1 --json");
    REQUIRE(ggx.code == 0);
    CHECK(lines(ggx.out) == 2);
    CHECK(ggx.out.rfind("{\"roughness\":0.02,\"exponent\":null,\"integral\":", 0) == 0);
    const auto blinn = hilite("brdf normalization --model blinn --exponent 1,10000 --json");
    CHECK(lines(blinn.out) == 2);
    CHECK(blinn.out.find("{\"roughness\":null,\"exponent\":10000.0,\"integral\":") != std::string::npos);
    const auto bounces = hilite(
        "brdf bounces --roughness 0.6 --incidence 30 --exits --texels 128 --bumps-per-tile 8 "
        "--paths 3000");
    CHECK(bounces.code == 0);
    CHECK(bounces.out.find("Kulla-Conty 1 - E(mu)") != std::string::npos);
    CHECK(bounces.out.find("first reflection") != std::string::npos);
    const std::string merl = tmpPath("ggx.binary");
    const auto tabulate =
        hilite("brdf tabulate --model ggx --roughness 0.1 --geometry smith --fresnel schlick --f0 0.04 -o " + merl);
    CHECK(tabulate.code == 0);
    CHECK(lines(tabulate.out) == 1);
    CHECK(tabulate.out.find("wrote " + merl + ": MERL table 90 x 90 x 180") == 0);
    CHECK(std::filesystem::file_size(merl) == 34992012);
    std::filesystem::remove(merl);
    const std::string png = tmpPath("terms.png");
    const auto render = hilite(
        "render --size 16 --model ggx --roughness 0.2 --roughness-y 0.05 --tangent-angle 30 "
        "--material copper --geometry smith-separable --diffuse oren-nayar --sigma 20 -o " +
        png);
    CHECK(render.code == 0);
    CHECK(render.out.find("material=copper wavelengths=81") != std::string::npos);
    std::filesystem::remove(png);
}

TEST_CASE(
    "cli::measure --light-rings 0 is the cap's centre alone: auto takes it for a wide lobe, a narrow one is flagged") {
    // The rule's error: tests/render/test_area_light.cpp; its price: docs/speed.md (the price list's "sun centre").
    const auto wide = hilite("measure --light disk --roughness 0.3 --incidence 60 --size 64 --json", true);
    REQUIRE(wide.code == 0);
    CHECK(wide.out.find("\"light_rings\":0") != std::string::npos);
    CHECK(wide.out.find("\"light_rule\":\"rings\"") != std::string::npos);
    CHECK(wide.out.find("light_undersampled") == std::string::npos);
    const auto narrow =
        hilite("measure --light disk --light-rings 0 --roughness 0.02 --incidence 60 --size 64 --json", true);
    REQUIRE(narrow.code == 0);
    CHECK(narrow.out.find("\"light_rings\":0") != std::string::npos);
    CHECK(narrow.out.find("light_undersampled") != std::string::npos);
    const auto told = hilite("explain --light disk --light-rings 0 --roughness 0.3", true);
    REQUIRE(told.code == 0);
    CHECK(told.out.find("the cap's centre alone (light_rings 0), 1 point per pixel (as given") != std::string::npos);
}

TEST_CASE("cli::measure --light-rule ltc reaches the row: its column, its rule's error, the flag it earns") {
    // The knob's accuracy and price: tests/render/test_ltc.cpp, docs/speed.md. A bad value: tests/cli/test_hostile.cpp.
    const auto t =
        hilite("measure --light disk --light-rule ltc --roughness 0.1 --incidence 60 --size 64 --json", true);
    REQUIRE(t.code == 0);
    CHECK(t.out.find("\"light_rule\":\"ltc\"") != std::string::npos);
    CHECK(t.out.find("\"light_rings\":0") != std::string::npos);
    CHECK(t.out.find("light_undersampled") != std::string::npos);  // LTC's error, 3.0e-2 of the peak here
    const auto rule = hilite("measure --light disk --roughness 0.1 --incidence 60 --size 64 --json", true);
    REQUIRE(rule.code == 0);
    CHECK(rule.out.find("\"light_rule\":\"rings\"") != std::string::npos);
    CHECK(rule.out.find("light_undersampled") == std::string::npos);
}
