// Rows come from the rendered scene: a `measure --json` row carries every registry parameter that applies
// to its scene, with the value as resolved (not as typed), and a swept roughness below the clamp is recorded
// clamped in the experiment's rows. In-process: the rows as `hilite measure` and `hilite run` make them.

#include "hilite/scene/resolve.hpp"

#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace scene = hilite::scene;
using namespace hilite::testing;

TEST_CASE("measure --json rows carry every registry parameter that applies, as resolved") {
    const char* scenes[] = {
        "--model ggx --roughness 0.1",
        "--model ggx --roughness 0.1 --roughness-y 0.3 --tangent-angle 20 --fresnel schlick --f0 0.04 --geometry smith",
        "--model beckmann --roughness 0.2 --material gold --diffuse oren-nayar --sigma 30 --albedo 0.2,0.3,0.4",
        "--model blinn --exponent 500 --fresnel conductor --eta 0.2,0.9,1.1 --k 3,2.5,2",
        "--model phong --exponent 300 --light point --intensity 4 --light-distance 20 --distance 15",
        "--model ggx --roughness 0.1 --threshold 0.25 --fov 40 --boundary pixel --supersample 2",
    };
    for (const char* args : scenes) {
        CAPTURE(args);
        const auto rows = measureJson(flags(std::string(args) + " --incidence 30 --size 64"));
        REQUIRE(rows.size() == 1);
        const auto& row = rows[0];
        const scene::Resolved resolved = scene::resolve(flags(args));
        int applicable = 0;
        for (const scene::Param& p : scene::registry()) {
            if (p.column.empty()) continue;
            CAPTURE(p.name);
            if (p.usedBy(resolved)) {
                ++applicable;
                REQUIRE(row.contains(p.column));
                if (p.column != "incidence_deg") CHECK(row[p.column] == p.value(resolved));
            } else {
                CHECK(!row.contains(p.column));
            }
        }
        CHECK(applicable >= 12);
    }
    // Values the user did not type but the scene rendered: the material's F0 stand-in, the anisotropic axes.
    const auto iron = measureJson(flags("--model ggx --material iron --incidence 30 --size 64")).at(0);
    CHECK(iron["fresnel"] == "schlick");
    CHECK(iron["f0"] == nlohmann::json::array({0.562, 0.565, 0.578}));
    const auto aniso =
        measureJson(flags("--model ggx --roughness 0.1 --roughness-y 0.2 --incidence 30 --size 64")).at(0);
    CHECK(aniso["roughness_y"].get<double>() == 0.2);
    CHECK(aniso["tangent_angle"].get<double>() == 0.0);
}

TEST_CASE("run: a roughness swept below the clamp is recorded as rendered (1e-7), on both axes") {
    hilite_test::TempDir dir("hilite-clamp");
    const std::string exp = dir.write("clamp.toml", R"(
[experiment]
name = "clamp"
[scene.material]
model = "ggx"
roughness_y = 1e-9
[scene.camera]
size = 32
[[sweep]]
key = "material.roughness"
values = [1e-9, 0.1]
[[sweep]]
key = "light.incidence"
values = [30]
)");
    StderrCapture err;
    runExperiment(exp, dir / "out");
    CHECK(err.str().find("raised to 1e-07") != std::string::npos);
    std::ifstream in(dir / "out/results.jsonl");
    std::vector<nlohmann::json> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(nlohmann::json::parse(line));
    REQUIRE(rows.size() == 2);
    CHECK(rows[0]["roughness"].get<double>() == 1e-7);
    CHECK(rows[0]["roughness_y"].get<double>() == 1e-7);
    CHECK(rows[1]["roughness"].get<double>() == 0.1);
    CHECK(rows[1]["roughness_y"].get<double>() == 1e-7);
    // The CSV's roughness_y column holds the same value.
    std::ifstream csv(dir / "out/results.csv");
    std::string header, first;
    std::getline(csv, header);
    std::getline(csv, first);
    CHECK(first.find("1e-07") != std::string::npos);
    CHECK(first.find("1e-09") == std::string::npos);
}
