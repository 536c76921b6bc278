// The accuracy knobs from the command line: the accuracy flags of `measure` (--tolerance, --supersample, --renderer,
// --crop) and `hilite run` with case axes, reference errors, timing and the Pareto summary; the shipped
// accuracy_cost experiment at reduced size.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace hilite_test;

namespace {

/// The scratch directory of this file's runs.
struct Dir : TempDir {
    Dir() : TempDir("hilite-accuracy") {}
};

std::string readText(const std::string& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("cli::measure accuracy flags: bad values, one line naming the flag and its range, exit 2") {
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c :
         {Case{"--tolerance 0", "--tolerance: must be a finite number in [1e-05, 0.1]"},
          Case{"--tolerance 0.5", "[1e-05, 0.1]"}, Case{"--tolerance nan", "--tolerance"},
          Case{"--tolerance abc", "--tolerance"}, Case{"--tolerance 1e-3 --reference", "--tolerance"},
          Case{"--supersample 0", "--supersample: must be a whole number in [1, 8]"}, Case{"--supersample 9", "[1, 8]"},
          Case{"--renderer vulkan", "--renderer"}, Case{"--crop maybe", "--crop"}}) {
        CAPTURE(c.args);
        const Result r = hilite(std::string("measure --incidence 30 ") + c.args);
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
        CHECK(r.out.find(c.mentions) != std::string::npos);
    }
}

TEST_CASE("cli::measure --tolerance reports settings, error estimate and time") {
    const Result r = hilite("measure --model ggx --roughness 0.02 --incidence 80 --tolerance 1e-3 --json", true);
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["tolerance"].get<double>() == 1e-3);
    CHECK(j["error_estimate"].get<double>() <= 1e-3);
    CHECK(j["tolerance_met"].get<bool>());
    CHECK(j["time_ms"].get<double>() > 0);
    for (const char* k : {"size", "boundary", "supersample", "framing", "renderer"}) CHECK(j["settings"].contains(k));
    CHECK(j["check"].contains("size"));
    // The table form prints the same on a line of its own.
    const Result t = hilite("measure --model ggx --roughness 0.1 --incidence 60 --tolerance 1e-2", true);
    CHECK(t.code == 0);
    CHECK(t.out.find("tolerance 0.01:") != std::string::npos);
}

TEST_CASE("cli::measure --renderer cpu and --supersample") {
    const Result cpu = hilite("measure --incidence 60 --size 128 --renderer cpu --json", true);
    const Result gl = hilite("measure --incidence 60 --size 128 --json", true);
    REQUIRE(cpu.code == 0);
    REQUIRE(gl.code == 0);
    const auto c = nlohmann::json::parse(cpu.out), g = nlohmann::json::parse(gl.out);
    CHECK(c["method"] == "cpu");
    CHECK(std::abs(c["aspect"].get<double>() - g["aspect"].get<double>()) < 0.005);
    const Result ss = hilite("measure --incidence 60 --size 64 --supersample 3 --json", true);
    REQUIRE(ss.code == 0);
    CHECK(nlohmann::json::parse(ss.out)["renders"].get<int>() >= 10);  // aiming + 9 jittered
}

TEST_CASE("cli::run case axes, reference errors, timing and the Pareto summary") {
    Dir d;
    std::ofstream(d / "acc.toml") << R"([experiment]
name = "acc"
[[sweep]]
key = "scene"
cases = [
  { name = "ggx 60", material = { model = "ggx", roughness = 0.1 }, light = { incidence = 60 } },
  { name = "phong 30", material = { model = "phong", exponent = 1000 }, light = { incidence = 30 } },
]
[[sweep]]
key = "setting"
cases = [
  { name = "size 64", tags = { knob = "size" }, camera = { size = 64 } },
  { name = "size 256", tags = { knob = "size" }, camera = { size = 256 } },
  { name = "pixel 64", tags = { knob = "boundary" }, camera = { size = 64 }, measurement = { boundary = "pixel" } },
  { name = "schlick", tags = { knob = "fresnel" }, camera = { size = 64 }, material = { material = "glass", fresnel = "schlick" }, reference = { material = { fresnel = "dielectric" } } },
]
[reference]
errors = true
[timing]
repeats = 2
warmup = 1
[[pareto]]
file = "pareto.png"
targets = [1e-2, 1e-3]
)";
    REQUIRE(hilite("run " + (d / "acc.toml") + " -o " + (d / "out")).code == 0);
    std::vector<nlohmann::json> rows;
    std::ifstream in(d / "out/results.jsonl");
    for (std::string l; std::getline(in, l);) rows.push_back(nlohmann::json::parse(l));
    REQUIRE(rows.size() == 8);
    for (const auto& r : rows) {
        CAPTURE(r.dump());
        for (const char* k : {"scene", "setting", "knob", "aspect_error", "major_error", "minor_error", "ref_aspect",
                              "time_ms", "repeats"})
            CHECK(r.contains(k));
        CHECK(r["aspect_error"].get<double>() < 0.05);
        // Rows carry the parameters their scene uses: a Phong lobe has no Fresnel term, so no fresnel column.
        if (r["setting"] == "size 256" || r["setting"] == "size 64")
            CHECK(r.value("fresnel", std::string(r["model"] == "phong" ? "none" : "absent")) == "none");
    }
    // Schlick is measured against the exact dielectric: its reference differs from the F = 1 one.
    CHECK(rows[3]["ref_aspect"] != rows[0]["ref_aspect"]);
    const std::string csvHeader = readText(d / "out/results.csv").substr(0, 400);
    CHECK(csvHeader.rfind("config,scene,setting,knob,", 0) == 0);
    const std::string md = readText(d / "out/summary.md");
    CHECK(md.find("cheapest setting reaching it") != std::string::npos);
    // Which setting is cheapest depends on the measured times (machine load): any of the cases may win.
    CHECK(std::regex_search(md, std::regex("\\| 0\\.01 \\| (size 64|size 256|pixel 64|schlick) \\|")));
    CHECK(fs::exists(d / "out/pareto.dat"));
}

TEST_CASE("cli::run bad case axes: one line, exit 2") {
    Dir d;
    for (const std::string& bad :
         {std::string("[[sweep]]\nkey = \"s\"\ncases = [{ material = { model = \"ggx\" } }]\n"),  // no name
          std::string("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", roughness = 0.1 }]\n"),   // not a table
          std::string("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", material = { rougness = 1 } }]\n"),
          std::string("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\" }, { name = \"a\" }]\n"),  // twice
          std::string("[timing]\nrepeats = 0\n"), std::string("[pareto]\nfile = \"x.png\"\n")}) {
        CAPTURE(bad);
        std::ofstream(d / "bad.toml", std::ios::trunc) << bad;
        const Result r = hilite("run " + (d / "bad.toml") + " -o " + (d / "bad"));
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
    }
}

TEST_CASE("experiments/accuracy_cost runs at reduced size") {
    // The shipped file with the settings above 512^2 and the slow spectral and sun-disk references dropped (each case
    // is one line), one timing repeat: every other knob, the reference errors and the Pareto summary run.
    std::istringstream in(readText(std::string(HILITE_SOURCE_DIR_STR) + "/experiments/accuracy_cost.toml"));
    std::ostringstream out;
    int dropped = 0;
    for (std::string l; std::getline(in, l);) {
        if (std::regex_search(l, std::regex("1024|2048|copper|sun|tolerance 1e-4|4x4 512|ggx 0.1 @30|ggx 0.02 @45"))) {
            ++dropped;
            continue;
        }
        l = std::regex_replace(l, std::regex("^repeats = \\d+"), "repeats = 1");
        out << std::regex_replace(l, std::regex("^warmup = \\d+"), "warmup = 0") << "\n";
    }
    REQUIRE(dropped > 5);
    Dir d;
    std::ofstream(d / "ac.toml") << out.str();
    REQUIRE(hilite("run " + (d / "ac.toml") + " -o " + (d / "ac")).code == 0);
    const std::string md = readText(d / "ac/summary.md");
    CHECK(md.find("| 0.01 | ") != std::string::npos);
    CHECK(md.find("| 0.001 | ") != std::string::npos);
    CHECK(md.find("| 0.0001 | ") != std::string::npos);
    CHECK(md.find("fixed fov 30 512") != std::string::npos);
}
