// `hilite brdf bounces` and experiments with a [bounces] table in-process (the experiments library as
// src/cli/bounces_cmd.cpp and run_cmd.cpp call it): the study's columns, a results folder with its section and
// colour picture, and bad input as one line naming the flag or key, nothing written. The table the command
// prints: tests/brdf/test_brdf_cmd.cpp.

#include "hilite/experiments/bounces.hpp"
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace hilite;
using namespace hilite::testing;

namespace {

/// `hilite brdf bounces ARGS`'s values: its defaults under the flags.
scene::Values bounceValues(const std::string& args) {
    scene::Values v = flags(args);
    v.setDefault("incidence", "0,30,60,75");
    v.setDefault("model", "beckmann");
    return v;
}

/// The lines of `hilite brdf bounces ARGS --json --texels 128 --bumps-per-tile 8 --paths 3000`: small enough for
/// a test (a 128^2 tile, 8 bumps a tile, a few thousand paths): the columns, not the physics.
std::vector<nlohmann::json> bounceLines(const std::string& args) {
    experiments::BounceSettings s;
    s.texels = 128, s.bumpsPerTile = 8, s.options.paths = 3000;
    experiments::checkBounceSettings(s, true);
    const scene::Values values = bounceValues(args);
    experiments::resolveBounceScene(values);
    std::vector<nlohmann::json> lines;
    for (const auto& study : experiments::studyBounces(values, s))
        lines.push_back(nlohmann::json::parse(experiments::bounceRow(study).dump()));
    return lines;
}

/// The refusal of `hilite brdf bounces ARGS` with `settings`, before the first path: "" when it would trace.
std::string bounceRefusal(const std::string& args, const experiments::BounceSettings& settings) {
    const scene::Values values = bounceValues(args);
    if (std::string c = flagCheck(values); !c.empty()) return c;
    return inputError([&] {
        experiments::checkBounceSettings(settings, true);
        experiments::resolveBounceScene(values);
    });
}

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

TEST_CASE("brdf bounces: one line per incidence with the study's columns") {
    const auto lines = bounceLines("--roughness 0.6 --material gold --incidence 0,60");
    REQUIRE(lines.size() == 2);
    CHECK(lines[1]["theta_deg"] == 60.0);
    for (const auto& j : lines) {
        double orders = 0;
        for (const char* k : {"traced_e1", "traced_e2", "traced_e3", "traced_e4", "traced_e5plus"})
            orders += j.at(k).get<double>();
        CHECK(orders == doctest::Approx(1.0).epsilon(1e-9));  // F = 1: every path leaves after some order
        CHECK(j.at("bounce_paths") == 3000);
        CHECK(j.at("bounce_seed") == 1);  // the paths' seed is a column (the field's is bump_seed)
        CHECK(j.at("smith_single").get<double>() < 1.0);
        CHECK(j.at("kc_albedo_y").get<double>() > j.at("single_albedo_y").get<double>());  // the compensation adds
        CHECK(j.at("traced_chroma2").get<double>() > j.at("traced_chroma1").get<double>());
    }
    // The table (--exits too): tests/brdf/test_brdf_cmd.cpp.
}

TEST_CASE("brdf bounces: bad input is one line naming the flag") {
    struct Case {
        const char* args;
        const char* names;
    };
    for (const Case& c : {Case{"--model ggx", "--model"}, Case{"--roughness 3", "--roughness"},
                          Case{"--incidence 90", "--incidence"}}) {
        CAPTURE(c.args);
        const std::string why = bounceRefusal(c.args, experiments::BounceSettings());
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.names) != std::string::npos);
    }
    struct Setting {
        long paths;
        int texels, bumpsPerTile;
        const char* names;
    };
    const experiments::BounceSettings defaults;
    for (const Setting& s : {Setting{1, defaults.texels, defaults.bumpsPerTile, "--paths"},
                             Setting{defaults.options.paths, 100, defaults.bumpsPerTile, "--texels"},
                             Setting{defaults.options.paths, 128, 64, "--bumps-per-tile"}}) {
        CAPTURE(s.names);
        experiments::BounceSettings settings;  // --paths, --texels, --bumps-per-tile
        settings.options.paths = s.paths, settings.texels = s.texels, settings.bumpsPerTile = s.bumpsPerTile;
        const std::string why = bounceRefusal("", settings);
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(s.names) != std::string::npos);
    }
    CHECK_FALSE(micro::parseTracedSurface("cubic"));  // --surface cubic: the command names the flag
}

TEST_CASE("run with [bounces]: rows with the study's columns, the section and the colour picture") {
    hilite_test::TempDir dir("hilite-bounces");
    const std::string file = dir.write("tiny_gold.toml", kExperiment);
    runExperiment(file, dir / "out");
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

TEST_CASE("run with [bounces]: a bad table or scene is one line naming the key, nothing written") {
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
        const std::string why = runRefusal(file, dir / "bad_out");
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.names) != std::string::npos);
        CHECK(!std::filesystem::exists(dir / "bad_out"));
    }
}

TEST_CASE("studyBounces checks its settings as the CLI does: InputError, not a crash") {
    const scene::Values values = bounceValues("--roughness 0.6 --incidence 30");
    struct Case {
        void (*edit)(experiments::BounceSettings&);
        const char* key;
    };
    const Case cases[] = {{[](experiments::BounceSettings& s) { s.texels = 1000; }, "texels: "},  // not a power of 2
                          {[](experiments::BounceSettings& s) { s.options.paths = 0; }, "paths: "},
                          {[](experiments::BounceSettings& s) { s.options.batches = 1; }, "batches: "},
                          {[](experiments::BounceSettings& s) { s.bumpsPerTile = 0; }, "bumps_per_tile: "},
                          {[](experiments::BounceSettings& s) { s.options.seed = uint64_t(-1); }, "seed: "}};
    for (const Case& c : cases) {
        experiments::BounceSettings s;
        s.texels = 128, s.bumpsPerTile = 8, s.options.paths = 3000;
        c.edit(s);
        const std::string r = inputError([&] { experiments::studyBounces(values, s); });
        CAPTURE(r);
        CHECK(r.rfind(c.key, 0) == 0);
        CHECK(r.find('\n') == std::string::npos);
    }
}

TEST_CASE("studyBounces tells its progress: the field, then each incidence's batches, traced and walked") {
    experiments::BounceSettings s;
    s.texels = 128, s.bumpsPerTile = 8, s.options.paths = 800, s.options.batches = 4;
    std::vector<std::string> told;
    experiments::studyBounces(bounceValues("--roughness 0.6 --incidence 0,60"), s,
                              [&](const std::string& stage, long done, long total) {
                                  told.push_back(stage + " " + std::to_string(done) + "/" + std::to_string(total));
                              });
    std::vector<std::string> expected = {"field 128^2 0/1", "field 128^2 1/1"};
    for (const char* theta : {"0", "60"})
        for (const char* stage : {"traced", "Smith walk"})
            for (int k = 0; k <= 4; ++k)
                expected.push_back(std::string("theta ") + theta + ": " + stage + " " + std::to_string(k) + "/4");
    CHECK(told == expected);
}
