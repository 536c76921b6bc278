// .brdf files in-process, as `hilite measure`, `render`, `explain` and `run` call the library: rows like the
// built-in model's, one-line errors naming the file, line and parameter, scene files and experiments. What
// only the executable shows (notes on stderr, the files render writes, a shader stopped for running too long):
// tests/cli/test_brdf_file_cli.cpp.

#include "gl/program.hpp"
#include "measurement/shader_probe.hpp"
#include "render/renderer.hpp"
#include "render/shader_source.hpp"
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace hilite;
using namespace hilite::testing;

namespace {

const std::string kShipped = std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/";

/// The scratch directory of this file's runs.
struct Dir : hilite_test::TempDir {
    Dir() : TempDir("hilite-brdf-file") {}
};

const std::string kShaderHead = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n";

/// The refusal of `hilite render` with `v` before it renders (src/cli/render_cmd.cpp): the flag check's, the
/// render view's resolve, then the .brdf's probe in a child process; "" when it would render.
std::string renderRefusal(const scene::Values& v) {
    if (std::string c = flagCheck(v); !c.empty()) return c;
    return inputError([&] {
        const scene::Resolved r = scene::resolve(v, scene::Purpose::Render);
        measurement::probeShader(r.scene, r.backend, r.shaderTimeoutS, r.gpu);
    });
}

}  // namespace

TEST_CASE("measure --brdf measures as the built-in model, with an error estimate from convergence") {
    const auto file = measureJson(flags("--brdf " + kShipped + "ggx.brdf --param alpha=0.2 --incidence 0,60,75"));
    const auto builtin = measureJson(flags("--model ggx --roughness 0.2 --incidence 0,60,75"));
    int rows = 0;
    for (; rows < int(std::min(file.size(), builtin.size())); ++rows) {
        const auto &x = file[size_t(rows)], &y = builtin[size_t(rows)];
        CAPTURE(x.dump());
        CHECK(x["model"] == "ggx.brdf");
        CHECK(x["brdf_params"] == "alpha=0.2");
        CHECK(x["framing"] == "blind");
        CHECK(x["error_estimate_from"] == "resolution convergence (no CPU twin for .brdf)");
        CHECK(x["error_estimate"]["minor_deg"].get<double>() < 0.01);
        CHECK_NEAR(x["aspect"].get<double>(), y["aspect"].get<double>(), 0.002);
        CHECK_NEAR(x["major_deg"].get<double>() / y["major_deg"].get<double>(), 1, 0.005);
        CHECK_NEAR(x["minor_deg"].get<double>() / y["minor_deg"].get<double>(), 1, 0.005);
        CHECK_FALSE(y.contains("error_estimate"));
    }
    CHECK(rows == 3);
    CHECK(file.size() == 3);
    CHECK(builtin.size() == 3);
    // The table's error estimate line: tests/cli/test_cli.cpp.
}

TEST_CASE("--brdf refuses an energy term it would drop (--diffuse, --multiscatter), naming both flags") {
    const std::string brdf = kShipped + "ggx.brdf";
    CHECK(refusal(flags("--brdf " + brdf + " --diffuse coupled")) ==
          "--diffuse coupled: not with --brdf (its BRDF() is the whole BRDF; write a diffuse term into the file "
          "instead)");
    CHECK(refusal(flags("--brdf " + brdf + " --diffuse lambert")).rfind("--diffuse lambert: not with --brdf", 0) == 0);
    CHECK(refusal(flags("--brdf " + brdf + " --geometry smith --multiscatter kulla-conty"))
              .rfind("--multiscatter kulla-conty: not with --brdf", 0) == 0);
    CHECK(refusal(flags("--brdf " + brdf + " --diffuse none")) == "");  // none drops nothing
}

TEST_CASE(".brdf malformed files: one line with file and line, for measure and render") {
    Dir d;
    struct Case {
        std::string name, text, expected;
    };
    const std::string shader = "::begin shader\n" + kShaderHead + "    return vec3(n);\n}\n::end shader\n";
    for (const Case& c : {
             Case{"unclosed.brdf", "analytic\n::begin parameters\nfloat n 1 10 2\n" + shader,
                  "unclosed.brdf:4: ::begin shader inside section 'parameters' (opened at line 2"},
             Case{"unclosed_end.brdf",
                  "analytic\n::begin parameters\nfloat n 1 10 2\n::end parameters\n::begin shader\n" + kShaderHead +
                      "return vec3(n);\n}\n",
                  "unclosed_end.brdf:5: section 'shader' is never closed"},
             Case{"badparam.brdf", "analytic\n::begin parameters\nfloat n 1 10\n::end parameters\n" + shader,
                  "badparam.brdf:3: bad parameter line 'float n 1 10': expected float NAME MIN MAX DEFAULT"},
             Case{"badtype.brdf", "analytic\n::begin parameters\nvec2 n 1 10\n::end parameters\n" + shader,
                  "badtype.brdf:3: unknown parameter type 'vec2'"},
             Case{"nobrdf.brdf",
                  "analytic\n::begin parameters\nfloat n 1 10 2\n::end parameters\n::begin shader\n"
                  "vec3 f(vec3 L) { return L; }\n::end shader\n",
                  "nobrdf.brdf:5: the shader (lines 6-6) defines no function vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, "
                  "vec3 Y)"},
             Case{"glsl.brdf",
                  "analytic\n# GLSL error on line 8\n::begin parameters\nfloat n 1 10 2\n::end parameters\n"
                  "::begin shader\n" +
                      kShaderHead + "    return vec3(n * missingName);\n}\n::end shader\n",
                  "glsl.brdf:8:"},
             Case{"signature.brdf", "analytic\n::begin shader\nvec3 BRDF(vec3 L) { return L; }\n::end shader\n",
                  "signature.brdf:2: BRDF cannot be called as vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"},
         }) {
        CAPTURE(c.name);
        const std::string path = d.write(c.name, c.text);
        for (const std::string& why : {measureRefusal(flags("--incidence 30 --brdf " + path)),
                                       renderRefusal(flags("--size 16 --brdf " + path))}) {
            INFO(why);
            CHECK(oneLine(why));
            CHECK(why.rfind(d / c.expected, 0) == 0);
        }
    }
}

TEST_CASE("--param errors name file, line and parameter, scene files add their own line") {
    Dir d;
    struct Case {
        std::string args, expected;
    };
    for (const Case& c : {
             Case{"--param n=1e9",
                  kShipped + "phong.brdf:10: --param n=1e9: outside the declared range [0, 1e+08] of 'float n'"},
             Case{"--param n=-1", kShipped + "phong.brdf:10: --param n=-1: outside the declared range"},
             Case{"--param m=5", kShipped + "phong.brdf:9: --param m=5: no parameter 'm' (did you mean 'n'?)"},
             Case{"--param n", kShipped + "phong.brdf: --param 'n': expected NAME=VALUE"},
         }) {
        CAPTURE(c.args);
        const std::string why = measureRefusal(flags("--brdf " + kShipped + "phong.brdf " + c.args));
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.rfind(c.expected, 0) == 0);
    }
    CHECK(renderRefusal(flags("--param n=5 --size 8")).find("--param: only with --brdf FILE") != std::string::npos);
    CHECK(measureRefusal(flags("--brdf " + kShipped + "phong.brdf --reference"))
              .find("--reference: no CPU twin for a .brdf file") != std::string::npos);

    // A scene file: brdf found beside it, params as an array; an error names the scene file's line too.
    fs::create_directories(d.path / "scenes");
    fs::copy_file(kShipped + "ggx.brdf", d.path / "scenes" / "mine.brdf");
    const std::string good = d.write("scenes/good.toml",
                                     "[material]\nbrdf = \"mine.brdf\"\nparam = [\"alpha=0.3\"]\n"
                                     "[light]\nincidence = 40\n");
    const auto ok = measureJson(flags("", good));
    REQUIRE(ok.size() == 1);
    CHECK(ok[0]["brdf_params"] == "alpha=0.3");
    const std::string bad = d.write("scenes/bad.toml", "[material]\nbrdf = \"mine.brdf\"\n\nparam = [\"alpha=30\"]\n");
    const std::string why = inputError([&] { measureJson(flags("", bad)); });
    CAPTURE(why);
    CHECK(oneLine(why));
    CHECK(why.rfind(bad + ":4: material.param: " + (d / "scenes/mine.brdf") + ":9: --param alpha=30", 0) == 0);
}

TEST_CASE("run sweeps a .brdf parameter, rows record it, shards merge, [match] is refused") {
    Dir d;
    fs::create_directories(d.path / "exp" / "brdfs");
    fs::copy_file(kShipped + "blinn.brdf", d.path / "exp" / "brdfs" / "b.brdf");
    const std::string exp = d.write("exp/e.toml",
                                    "[experiment]\nname = \"e\"\n[scene.material]\nbrdf = \"brdfs/b.brdf\"\n"
                                    "param = [\"n=100\"]\n[scene.camera]\nsize = \"64\"\n"
                                    "[[sweep]]\nkey = \"material.param\"\nvalues = [\"n=10\", \"n=1000\"]\n"
                                    "[[sweep]]\nkey = \"light.incidence\"\nvalues = [0, 60]\n");
    runExperiment(exp, d / "single");
    std::ifstream rows(d / "single/results.jsonl");
    std::vector<nlohmann::json> all;
    for (std::string line; std::getline(rows, line);) all.push_back(nlohmann::json::parse(line));
    REQUIRE(all.size() == 4);
    CHECK(all[0]["param"] == "n=100,n=10");  // the base's assignment, then the sweep's: the later wins
    CHECK(all[0]["brdf_params"] == "n=10");
    CHECK(all[3]["brdf_params"] == "n=1000");
    CHECK(all[0]["model"] == "b.brdf");
    CHECK(all[0]["roughness"].is_null());  // the built-in model's flags mean nothing here
    CHECK(all[0]["framing"] == "blind");
    CHECK(all[0]["major_deg"].get<double>() > all[2]["major_deg"].get<double>());  // n = 10 is wider
    // Shards run from another directory and merged: the copy of e.toml still finds brdfs/b.brdf.
    for (int k = 1; k <= 2; ++k) {
        experiments::RunOptions o;  // run EXP --shard K/2 -o sK
        o.experiment = exp, o.out = d / ("s" + std::to_string(k)), o.shardK = k, o.shardN = 2;
        experiments::runExperiment(o);
    }
    const auto merged = experiments::mergeShards({d / "s1", d / "s2"}, d / "merged");
    CHECK(merged.rows == merged.expected);
    std::ifstream m(d / "merged/results.jsonl");
    int n = 0;
    for (std::string line; std::getline(m, line);) ++n;
    CHECK(n == 4);

    // A .brdf that does not build fails before any result file is written.
    d.write("exp/brdfs/broken.brdf",
            "analytic\n::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) "
            "{ return nothing; }\n::end shader\n");
    const std::string broken = d.write("exp/broken.toml",
                                       "[[sweep]]\nkey = \"material.brdf\"\n"
                                       "values = [\"brdfs/b.brdf\", \"brdfs/broken.brdf\"]\n");
    CHECK(runRefusal(broken, d / "broken").find("broken.brdf:3:") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "broken/results.csv"));

    const std::string match = d.write("exp/m.toml",
                                      "[scene.material]\nbrdf = \"brdfs/b.brdf\"\n[match]\nmaterial.model = \"ggx\"\n"
                                      "[[sweep]]\nkey = \"light.incidence\"\nvalues = [0]\n");
    CHECK(runRefusal(match, d / "match").find("[match]: matching widths needs a CPU twin") != std::string::npos);
}

TEST_CASE("explain --brdf shows the file's program and effects, and its scene file measures the same") {
    Dir d;
    const std::string args = "--brdf " + kShipped + "ggx.brdf --param alpha=0.05 --param alpha=0.2";
    const scene::Resolved r = scene::resolve(flags(args));
    std::string effects;  // explain --part effects
    for (const auto& e : render::activeEffects(r.scene)) effects += e + "\n";
    CHECK(effects.find(".brdf file " + kShipped + "ggx.brdf: its BRDF() (alpha=0.2)") != std::string::npos);
    CHECK(effects.find("D_GGX") == std::string::npos);  // no built-in term runs
    const std::string glsl =                            // explain --part glsl
        gl::joinSources(render::programSources(r.scene, render::Output::Measure, render::shaderDirectory()).fragment);
    CHECK(glsl.find("vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )") != std::string::npos);  // the file's text
    CHECK(glsl.find("D_GGX(") == std::string::npos);
    // The resolved scene as a scene file (absolute .brdf path, every --param in order) measures the same.
    const std::string scene = scene::sceneToml(r.values);
    CAPTURE(scene);
    const scene::Values back = scene::parseSceneToml(scene, "resolved.toml");
    REQUIRE(back.list("param").size() == 2);
    CHECK(back.list("param")[0].text == "alpha=0.05");
    CHECK(back.list("param")[1].text == "alpha=0.2");
    CHECK(back.text("brdf") == kShipped + "ggx.brdf");
    d.write("resolved.toml", scene);
    const auto direct = measureJson(flags(args + " --incidence 45 --size 128"));
    const auto viaFile = measureJson(flags("--incidence 45 --size 128", d / "resolved.toml"));
    REQUIRE(direct.size() == 1);
    REQUIRE(viaFile.size() == 1);
    const auto &a = direct[0], &b = viaFile[0];
    CHECK(a["aspect"] == b["aspect"]);
    CHECK(a["major_deg"] == b["major_deg"]);
    CHECK(b["brdf_params"] == "alpha=0.2");
}
