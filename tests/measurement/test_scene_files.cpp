// Scene files in-process, as `hilite explain` and `hilite measure` read them (the scene file's values, the
// flags over them): every shipped scene resolves and measures; flags override the file. The explain output
// itself (a resolved scene that is a scene file resolving to itself): tests/cli/test_scene_files.cpp.

#include "render/renderer.hpp"
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace hilite;
using namespace hilite::testing;

TEST_CASE("scene files: every shipped scene resolves and measures") {
    int count = 0;
    for (const auto& e : fs::directory_iterator(fs::path(HILITE_SOURCE_DIR_STR) / "experiments/scenes")) {
        CAPTURE(e.path().string());
        std::string effects;  // what `hilite explain --part effects --scene FILE` prints
        for (const auto& line : render::activeEffects(scene::resolve(flags("", e.path().string())).scene))
            effects += line + "\n";
        CHECK(effects.find("light") != std::string::npos);
        const auto rows = measureJson(flags("--view measure --size 64", e.path().string()));
        CHECK(!rows.empty());
        ++count;
    }
    CHECK(count >= 5);
}

TEST_CASE("scene files: flags override the file") {
    hilite_test::TempDir t("hilite-scenes");
    const std::string file = t.write("s.toml", "[material]\nmodel = \"beckmann\"\nroughness = 0.3\n");
    const scene::Resolved r = scene::resolve(flags("--roughness 0.05", file));
    CHECK(r.values.text("model") == "beckmann");
    CHECK(r.values.text("roughness") == "0.05");
    CHECK((r.scene.brdf.model == brdf::Model::Beckmann));
    CHECK(r.scene.brdf.roughness == 0.05);
}
