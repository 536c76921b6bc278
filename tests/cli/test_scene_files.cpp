// Scene files and `hilite explain` from the command line: shipped scenes, round trip, bad files.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace hilite_test;

namespace {

/// The scratch directory of this file's scene files.
struct Tmp : TempDir {
    Tmp() : TempDir("hilite-scenes") {}
};

}  // namespace

TEST_CASE("cli::explain every shipped scene resolves and measures") {
    int count = 0;
    for (const auto& e : fs::directory_iterator(fs::path(HILITE_SOURCE_DIR_STR) / "experiments/scenes")) {
        CAPTURE(e.path().string());
        const auto r = hilite("explain --part effects --scene " + e.path().string());
        CHECK(r.code == 0);
        CHECK(r.out.find("light") != std::string::npos);
        const auto m = hilite("measure --view measure --size 64 --json --scene " + e.path().string());
        CHECK(m.code == 0);
        ++count;
    }
    CHECK(count >= 5);
}

TEST_CASE("cli::explain the resolved scene is a scene file that resolves to itself") {
    Tmp t;
    const auto first = hilite(
        "explain --part scene --model beckmann --roughness 0.2 --fresnel schlick "
        "--f0 0.9,0.6,0.3 --incidence 30 --light point --light-distance 2");
    REQUIRE(first.code == 0);
    const std::string file = t.write("resolved.toml", first.out);
    const auto second = hilite("explain --part scene --scene " + file);
    CHECK(second.code == 0);
    CHECK(second.out == first.out);
}

TEST_CASE("cli::explain prints only the named terms' GLSL") {
    const auto none = hilite("explain --part glsl --model ggx --fresnel none");
    CHECK(none.code == 0);
    CHECK(none.out.find("D_GGX(") != std::string::npos);
    CHECK(none.out.find("F_Schlick") == std::string::npos);
    CHECK(none.out.find("F_Dielectric") == std::string::npos);
    const auto schlick = hilite("explain --part glsl --model ggx --fresnel schlick");
    CHECK(schlick.out.find("VEC3 F_Schlick(") != std::string::npos);
}

TEST_CASE("cli scene files: bad input names the file, line and key, exit 2, nothing written") {
    Tmp t;
    const std::string out = t / "out.png";
    struct Case {
        std::string name, text, expect;
    };
    for (const Case& c : {
             Case{"syntax.toml", "[material]\nroughness = = 1\n", "syntax.toml:2"},
             Case{"unknown.toml", "[material]\nroughnes = 0.1\n", "did you mean 'roughness'"},
             Case{"table.toml", "[materials]\nroughness = 0.1\n", "did you mean 'material'"},
             Case{"wrongtable.toml", "[light]\nroughness = 0.1\n", "belongs in [material]"},
             Case{"type.toml", "[material]\nroughness = \"abc\"\n", "type.toml:2: material.roughness"},
             Case{"range.toml", "[material]\n\nroughness = -0.1\n", "range.toml:3: material.roughness"},
             Case{"nan.toml", "[material]\nroughness = nan\n", "nan.toml:2: material.roughness"},
             Case{"inf.toml", "[light]\nincidence = inf\n", "inf.toml:2: light.incidence"},
             Case{"contradiction.toml", "[material]\nmaterial = \"copper\"\nf0 = 0.5\n", "f0"},
             Case{"nested.toml", "[material]\nroughness = [[1]]\n", "material.roughness"},
         }) {
        CAPTURE(c.name);
        const auto r = hilite("render -o " + out + " --scene " + t.write(c.name, c.text));
        CAPTURE(r.out);
        CHECK(r.code == 2);
        CHECK(r.out.find(c.expect) != std::string::npos);
        CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("cli scene files: flags override the file") {
    Tmp t;
    const std::string file = t.write("s.toml", "[material]\nmodel = \"beckmann\"\nroughness = 0.3\n");
    const auto r = hilite("explain --part scene --roughness 0.05 --scene " + file);
    CHECK(r.out.find("model = \"beckmann\"") != std::string::npos);
    CHECK(r.out.find("roughness = 0.05") != std::string::npos);
}
