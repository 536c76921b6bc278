// `hilite brdf` as a user meets it: tables and JSON lines with the documented fields, the strip PNG,
// and bad input as one line naming the flag with exit code 2.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using hilite_test::hilite;

namespace {

std::vector<nlohmann::json> jsonLines(const std::string& out) {
    std::vector<nlohmann::json> lines;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    return lines;
}

/// The shared line count, under the name this file uses (its tests name their JSON rows `lines`).
int lineCount(const std::string& s) { return hilite_test::lines(s); }

}  // namespace

TEST_CASE("cli::brdf fresnel --json: theta_deg and rgb per line, copper is spectral") {
    const auto r = hilite("brdf fresnel --material copper --incidence 0:90:30 --json");
    REQUIRE(r.code == 0);
    const auto lines = jsonLines(r.out);
    REQUIRE(lines.size() == 4);
    CHECK(lines[0]["theta_deg"] == 0.0);
    const auto rgb = lines[0]["rgb"];
    CHECK(rgb.size() == 3);
    CHECK(rgb[0].get<double>() > rgb[1].get<double>());
    CHECK(rgb[1].get<double>() > rgb[2].get<double>());
    CHECK(lines[3]["rgb"][2].get<double>() == doctest::Approx(1.0));
    const auto table = hilite("brdf fresnel --material copper --incidence 0");
    CHECK(table.out.find("spectral") != std::string::npos);
    const auto glass = jsonLines(hilite("brdf fresnel --fresnel dielectric --eta 1.5 --incidence 45 --json").out);
    CHECK(glass.at(0)["rgb"][0].get<double>() == doctest::Approx(0.0502399).epsilon(1e-6));
}

TEST_CASE("cli::brdf albedo --json: theta_deg and albedo per line") {
    const auto r = hilite("brdf albedo --model none --diffuse lambert --albedo 0.2,0.4,0.6 --incidence 0,60 --json");
    REQUIRE(r.code == 0);
    const auto lines = jsonLines(r.out);
    REQUIRE(lines.size() == 2);
    CHECK(lines[1]["theta_deg"] == 60.0);
    CHECK(lines[1]["albedo"][2].get<double>() == doctest::Approx(0.6).epsilon(1e-6));
    // Lambert's bihemispherical albedo is rho itself, on every row.
    CHECK(lines[0]["bihemispherical_albedo"][0].get<double>() == doctest::Approx(0.2).epsilon(1e-6));
    CHECK(lines[1]["bihemispherical_albedo"][1].get<double>() == doctest::Approx(0.4).epsilon(1e-6));
    const auto table = hilite("brdf albedo --model none --diffuse lambert --albedo 0.3 --incidence 0");
    CHECK(table.out.find("# bihemispherical albedo") != std::string::npos);
}

TEST_CASE("cli::brdf albedo --multiscatter kulla-conty: the white furnace, single scattering beside it") {
    const auto single = jsonLines(hilite("brdf albedo --roughness 1 --geometry smith --incidence 0,60 --json").out);
    const auto ms = jsonLines(
        hilite("brdf albedo --roughness 1 --geometry smith --multiscatter kulla-conty --incidence 0,60 --json").out);
    REQUIRE(single.size() == 2);
    REQUIRE(ms.size() == 2);
    CHECK(single[0]["albedo"][0].get<double>() == doctest::Approx(0.3068528).epsilon(1e-6));  // 1 - ln 2
    for (const auto& line : ms) CHECK(std::abs(line["albedo"][1].get<double>() - 1.0) < 1e-3);
    const auto explain = hilite("explain --roughness 1 --geometry smith --multiscatter kulla-conty --part effects");
    CHECK(explain.code == 0);
    CHECK(explain.out.find("MS_KullaConty") != std::string::npos);
    CHECK(explain.out.find("Kulla & Conty 2017") != std::string::npos);
    const auto plain = hilite("explain --roughness 1 --geometry smith --part effects");
    CHECK(plain.out.find("KullaConty") == std::string::npos);
    const auto coupled = hilite("explain --fresnel dielectric --geometry smith --diffuse coupled --part effects");
    CHECK(coupled.out.find("Fd_Coupled") != std::string::npos);
}

TEST_CASE("cli::brdf normalization --json: roughness, exponent, integral per line") {
    const auto r = hilite("brdf normalization --model ggx --roughness 0.02,1 --json");
    REQUIRE(r.code == 0);
    const auto lines = jsonLines(r.out);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0]["roughness"] == 0.02);
    CHECK(lines[0]["exponent"].is_null());
    CHECK(lines[1]["integral"].get<double>() == doctest::Approx(1.0).epsilon(1e-6));
    const auto blinn = jsonLines(hilite("brdf normalization --model blinn --exponent 1,10000 --json").out);
    REQUIRE(blinn.size() == 2);
    CHECK(blinn[1]["exponent"] == 10000.0);
    CHECK(blinn[1]["roughness"].is_null());
}

TEST_CASE("cli::brdf strip writes the PNG") {
    const std::string png =
        (std::filesystem::temp_directory_path() / ("hilite-strip-" + std::to_string(getpid()) + ".png")).string();
    const auto r = hilite("brdf strip --material gold --size 64x8 -o " + png);
    CHECK(r.code == 0);
    REQUIRE(std::filesystem::exists(png));
    std::ifstream in(png, std::ios::binary);
    char sig[8] = {};
    in.read(sig, 8);
    CHECK(std::string(sig + 1, 3) == "PNG");
    std::filesystem::remove(png);
}

TEST_CASE("cli::brdf bad input: one line naming the flag, exit 2") {
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c : {Case{"fresnel --material unobtainium", "--material"},
                         Case{"fresnel --eta -1", "--eta"},
                         Case{"fresnel --fresnel conductor --k nan", "--k"},
                         Case{"fresnel --eta 1,2", "--eta"},
                         Case{"fresnel", "--fresnel"},
                         Case{"fresnel --material glass --spectral", "--spectral"},
                         Case{"fresnel --fresnel spectral", "--fresnel"},
                         Case{"fresnel --material iron --fresnel conductor", "--fresnel"},
                         Case{"fresnel --material copper --fresnel dielectric", "--fresnel"},
                         Case{"fresnel --material glass --incidence 91", "--incidence"},
                         Case{"albedo --model lambertian", "--model"},
                         Case{"albedo --roughness 0", "--roughness"},
                         Case{"albedo --model blinn --roughness-y 0.1", "--roughness-y"},
                         Case{"albedo --roughness-y inf", "--roughness-y"},
                         Case{"albedo --tangent-angle 1e9", "--tangent-angle"},
                         Case{"albedo --diffuse chalk", "--diffuse"},
                         Case{"albedo --albedo 1.5", "--albedo"},
                         Case{"albedo --sigma 100", "--sigma"},
                         Case{"albedo --geometry ct", "--geometry"},
                         Case{"albedo --multiscatter heitz", "--multiscatter"},
                         Case{"albedo --multiscatter kulla-conty", "--multiscatter"},  // implicit G: not Smith's loss
                         Case{"albedo --multiscatter kulla-conty --geometry smith --roughness-y 0.3", "--multiscatter"},
                         Case{"albedo --model phong --multiscatter kulla-conty --geometry smith", "--multiscatter"},
                         Case{"albedo --diffuse coupled --geometry none", "--diffuse"},
                         Case{"normalization --model phong", "--model"},
                         Case{"normalization --roughness 0.1,-2", "--roughness"},
                         Case{"normalization --model blinn --exponent nan", "--exponent"},
                         Case{"strip --material gold", "-o"},
                         Case{"strip --material gold --size 0 -o /tmp/x.png", "--size"},
                         Case{"strip --material gold -o /nonexistent-dir/x.png", "-o"}}) {
        CAPTURE(c.args);
        const auto r = hilite(std::string("brdf ") + c.args);
        CHECK(r.code == 2);
        CHECK(lineCount(r.out) == 1);
        CHECK(r.out.find(c.mentions) != std::string::npos);
    }
}

TEST_CASE("cli::render takes the reflectance terms") {
    const std::string png =
        (std::filesystem::temp_directory_path() / ("hilite-render4-" + std::to_string(getpid()) + ".png")).string();
    const auto r = hilite(
        "render --size 16 --model ggx --roughness 0.2 --roughness-y 0.05 --tangent-angle 30 "
        "--material copper --geometry smith-separable --diffuse oren-nayar --sigma 20 -o " +
        png);
    CAPTURE(r.out);
    CHECK(r.code == 0);
    CHECK(r.out.find("material=copper wavelengths=81") != std::string::npos);
    std::filesystem::remove(png);
    const auto bad = hilite("render --size 16 --fresnel dielectric --k 2 -o " + png);
    CHECK(bad.code == 2);
    CHECK(bad.out.find("--k") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(png));
}
