// Bad scene files in-process, as `hilite render --scene FILE` reads and resolves them: one line naming the
// file, line and key. That nothing is written on a refusal: tests/cli/test_cli.cpp.

#define HILITE_IN_PROCESS_SCENE_ONLY
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace hilite;
using namespace hilite::testing;

TEST_CASE("scene files: bad input names the file, line and key in one line") {
    hilite_test::TempDir t("hilite-scene-errors");
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
        const std::string file = t.write(c.name, c.text);
        const std::string why =
            inputError([&] { scene::resolve(flags("", file), scene::Purpose::Render); });  // render --scene FILE
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.expect) != std::string::npos);
    }
}
