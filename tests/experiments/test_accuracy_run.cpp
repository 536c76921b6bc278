// `hilite run` of accuracy experiments in-process (the experiments library, as src/cli/run_cmd.cpp calls it):
// case axes, reference errors, timing and the Pareto summary; the shipped accuracy_cost experiment at reduced
// size. The measure accuracy flags: tests/measurement/test_measure_flags.cpp.

#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace hilite::testing;
using hilite_test::TempDir;

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

TEST_CASE("run case axes, reference errors, timing and the Pareto summary") {
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
    runExperiment(d / "acc.toml", d / "out");
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

TEST_CASE("run bad case axes: refused in one line") {
    Dir d;
    for (const std::string& bad :
         {std::string("[[sweep]]\nkey = \"s\"\ncases = [{ material = { model = \"ggx\" } }]\n"),  // no name
          std::string("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", roughness = 0.1 }]\n"),   // not a table
          std::string("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\", material = { rougness = 1 } }]\n"),
          std::string("[[sweep]]\nkey = \"s\"\ncases = [{ name = \"a\" }, { name = \"a\" }]\n"),  // twice
          std::string("[timing]\nrepeats = 0\n"), std::string("[pareto]\nfile = \"x.png\"\n")}) {
        CAPTURE(bad);
        std::ofstream(d / "bad.toml", std::ios::trunc) << bad;
        const std::string why = runRefusal(d / "bad.toml", d / "bad");
        CAPTURE(why);
        CHECK(oneLine(why));
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
    runExperiment(d / "ac.toml", d / "ac");
    const std::string md = readText(d / "ac/summary.md");
    CHECK(md.find("| 0.01 | ") != std::string::npos);
    CHECK(md.find("| 0.001 | ") != std::string::npos);
    CHECK(md.find("| 0.0001 | ") != std::string::npos);
    CHECK(md.find("fixed fov 30 512") != std::string::npos);
}
