// `hilite explain` from the command line: the scene it prints is a scene file that resolves to itself. Shipped
// scenes, flags over a file: tests/measurement/test_scene_files.cpp; bad files: tests/scene/test_scene_file_errors.cpp;
// the GLSL: tests/render/test_program_terms.cpp.

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
