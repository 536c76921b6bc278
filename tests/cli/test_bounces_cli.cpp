// `hilite brdf bounces` and experiments with a [bounces] table, as a user meets them: JSON lines with the
// study's columns, a results folder with its section and colour picture, and bad input as one line naming
// the flag or key with exit code 2 and nothing written.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using hilite_test::hilite;

namespace {

/// Small enough for a test (a 128^2 tile, 8 bumps a tile, a few thousand paths): the columns, not the physics.
const char* kSmall = "--texels 128 --bumps-per-tile 8 --paths 3000";

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

const char* kExperiment = R"([experiment]
name = "tiny_gold"

[scene.material]
model = "beckmann"
material = "gold"
roughness = 0.6

[bounces]
paths = 3000
texels = 128
bumps_per_tile = 8
colours = "colours.png"

[[sweep]]
key = "light.incidence"
values = [0, 60]

[[plot]]
file = "chroma.png"
x = "incidence_deg"
y = "traced_chroma2"
)";

}  // namespace

TEST_CASE("cli::brdf bounces --json: one line per incidence with the study's columns") {
    const auto r =
        hilite(std::string("brdf bounces --roughness 0.6 --material gold --incidence 0,60 --json ") + kSmall, true);
    REQUIRE(r.code == 0);
    std::istringstream in(r.out);
    std::vector<nlohmann::json> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    REQUIRE(lines.size() == 2);
    CHECK(lines[1]["theta_deg"] == 60.0);
    for (const auto& j : lines) {
        double orders = 0;
        for (const char* k : {"traced_e1", "traced_e2", "traced_e3", "traced_e4", "traced_e5plus"})
            orders += j.at(k).get<double>();
        CHECK(orders == doctest::Approx(1.0).epsilon(1e-9));  // F = 1: every path leaves after some order
        CHECK(j.at("bounce_paths") == 3000);
        CHECK(j.at("smith_single").get<double>() < 1.0);
        CHECK(j.at("kc_albedo_y").get<double>() > j.at("single_albedo_y").get<double>());  // the compensation adds
        CHECK(j.at("traced_chroma2").get<double>() > j.at("traced_chroma1").get<double>());
    }
    const auto table = hilite(std::string("brdf bounces --roughness 0.6 --incidence 30 --exits ") + kSmall);
    CHECK(table.code == 0);
    CHECK(table.out.find("Kulla-Conty 1 - E(mu)") != std::string::npos);
    CHECK(table.out.find("first reflection") != std::string::npos);
}

TEST_CASE("cli::brdf bounces: bad input is one line naming the flag, exit 2") {
    struct Case {
        const char* args;
        const char* names;
    };
    for (const Case& c :
         {Case{"--model ggx", "--model"}, Case{"--paths 1", "--paths"}, Case{"--texels 100", "--texels"},
          Case{"--texels 128 --bumps-per-tile 64", "--bumps-per-tile"}, Case{"--roughness 3", "--roughness"},
          Case{"--incidence 90", "--incidence"}, Case{"--surface cubic", "--surface"}}) {
        CAPTURE(c.args);
        const auto r = hilite(std::string("brdf bounces ") + c.args);
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        CHECK(r.out.find(c.names) != std::string::npos);
    }
}

TEST_CASE("cli::run with [bounces]: rows with the study's columns, the section and the colour picture") {
    hilite_test::TempDir dir("hilite-bounces");
    const std::string file = dir.write("tiny_gold.toml", kExperiment);
    const auto r = hilite("run " + file + " -o " + dir / "out");
    REQUIRE(r.code == 0);
    const std::string csv = readFile(dir / "out/results.csv");
    CHECK(csv.find("traced_e1") != std::string::npos);
    CHECK(csv.find("kc_chroma_ms") != std::string::npos);
    const std::string md = readFile(dir / "out/summary.md");
    CHECK(md.find("## Light that bounces more than once") != std::string::npos);
    CHECK(md.find("Second-bounce light is more saturated than first-bounce light (C* 2 > C* 1) in 2 of 2 rows") !=
          std::string::npos);
    CHECK(std::filesystem::exists(dir / "out/colours.png"));
    CHECK(std::filesystem::exists(dir / "out/chroma.png"));
}

TEST_CASE("cli::run with [bounces]: a bad table or scene is one line naming the key, nothing written") {
    hilite_test::TempDir dir("hilite-bounces-bad");
    struct Case {
        std::string from, to, names;
    };
    const std::vector<Case> cases = {
        {"paths = 3000", "paths = 1", "bounces.paths"},
        {"texels = 128", "texels = 100", "bounces.texels"},
        {"colours = \"colours.png\"", "colours = \"../x.png\"", "bounces.colours"},
        {"colours = \"colours.png\"", "colours = \"chroma.png\"", "chroma.png"},
        {"paths = 3000", "paths = 3000\nsurface = \"cubic\"", "bounces.surface"},
        {"model = \"beckmann\"", "model = \"ggx\"", "material.model"},
        {"roughness = 0.6", "roughness = 0.6\ngeometry = \"implicit\"", "material.geometry"},
        {"[[plot]]", "[fit]\nmodels = [\"ggx\"]\n\n[[plot]]", "[fit]"},
    };
    for (const auto& c : cases) {
        CAPTURE(c.to);
        std::string text = kExperiment;
        text.replace(text.find(c.from), c.from.size(), c.to);
        const std::string file = dir.write("bad.toml", text);
        const auto r = hilite("run " + file + " -o " + dir / "bad_out");
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        CHECK(r.out.find(c.names) != std::string::npos);
        CHECK(!std::filesystem::exists(dir / "bad_out"));
    }
}
