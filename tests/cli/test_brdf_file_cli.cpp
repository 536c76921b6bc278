// .brdf files from the command line, scene files and experiments: exit codes, one-line errors naming the
// file, line and parameter, nothing written on bad input, and a shader that runs too long stopped.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace hilite_test;

namespace {

/// Lines of output that are not notes ("hilite: note: ...").
std::vector<std::string> errorLines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("hilite: note:", 0) != 0) out.push_back(line);
    return out;
}

const std::string kShipped = std::string(HILITE_SOURCE_DIR_STR) + "/experiments/brdfs/";

/// The scratch directory of this file's runs.
struct Dir : TempDir {
    Dir() : TempDir("hilite-brdf-cli") {}
};

const std::string kShaderHead = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n";

}  // namespace

TEST_CASE("cli::measure --brdf measures as the built-in model, with an error estimate from convergence") {
    const auto file =
        hilite("measure --brdf " + kShipped + "ggx.brdf --param alpha=0.2 --incidence 0,60,75 --json", true);
    const auto builtin = hilite("measure --model ggx --roughness 0.2 --incidence 0,60,75 --json", true);
    REQUIRE(file.code == 0);
    REQUIRE(builtin.code == 0);
    std::istringstream a(file.out), b(builtin.out);
    int rows = 0;
    for (std::string la, lb; std::getline(a, la) && std::getline(b, lb); ++rows) {
        const auto x = nlohmann::json::parse(la), y = nlohmann::json::parse(lb);
        CAPTURE(la);
        CHECK(x["model"] == "ggx.brdf");
        CHECK(x["brdf_params"] == "alpha=0.2");
        CHECK(x["framing"] == "blind");
        CHECK(x["error_estimate_from"] == "resolution convergence (no CPU twin for .brdf)");
        CHECK(x["error_estimate"]["minor_deg"].get<double>() < 0.01);
        CHECK(std::abs(x["aspect"].get<double>() - y["aspect"].get<double>()) < 0.002);
        CHECK(std::abs(x["major_deg"].get<double>() / y["major_deg"].get<double>() - 1) < 0.005);
        CHECK(std::abs(x["minor_deg"].get<double>() / y["minor_deg"].get<double>() - 1) < 0.005);
        CHECK_FALSE(y.contains("error_estimate"));
    }
    CHECK(rows == 3);
    const auto table = hilite("measure --brdf " + kShipped + "phong.brdf --incidence 30", true);
    CHECK(table.code == 0);
    CHECK(table.out.find("error estimate (resolution convergence, no CPU twin for .brdf)") != std::string::npos);
}

TEST_CASE("cli .brdf malformed files: one line with file and line, exit 2, nothing written") {
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
        for (const std::string& cmd :
             {std::string("measure --incidence 30"), "render --size 16 -o " + (d / "out.png")}) {
            CAPTURE(cmd);
            const auto r = hilite(cmd + " --brdf " + path);
            CHECK(r.code == 2);
            const auto lines = errorLines(r.out);
            REQUIRE(lines.size() == 1);
            INFO(lines[0]);
            CHECK(lines[0].rfind("hilite: " + d / c.expected, 0) == 0);
            CHECK_FALSE(fs::exists(d / "out.png"));
        }
    }
}

TEST_CASE("cli --param errors name file, line and parameter, scene files add their own line") {
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
        const auto r = hilite("measure --brdf " + kShipped + "phong.brdf " + c.args);
        CHECK(r.code == 2);
        CHECK(errorLines(r.out).size() == 1);
        CHECK(r.out.rfind("hilite: " + c.expected, 0) == 0);
    }
    const auto noFile = hilite("render --param n=5 --size 8 -o " + (d / "x.png"));
    CHECK(noFile.code == 2);
    CHECK(noFile.out.find("--param: only with --brdf FILE") != std::string::npos);
    const auto reference = hilite("measure --brdf " + kShipped + "phong.brdf --reference");
    CHECK(reference.code == 2);
    CHECK(reference.out.find("--reference: no CPU twin for a .brdf file") != std::string::npos);

    // A scene file: brdf found beside it, params as an array; an error names the scene file's line too.
    fs::create_directories(d.path / "scenes");
    fs::copy_file(kShipped + "ggx.brdf", d.path / "scenes" / "mine.brdf");
    const std::string good = d.write("scenes/good.toml",
                                     "[material]\nbrdf = \"mine.brdf\"\nparam = [\"alpha=0.3\"]\n"
                                     "[light]\nincidence = 40\n");
    const auto ok = hilite("measure --scene " + good + " --json", true);
    REQUIRE(ok.code == 0);
    CHECK(nlohmann::json::parse(ok.out)["brdf_params"] == "alpha=0.3");
    const std::string bad = d.write("scenes/bad.toml", "[material]\nbrdf = \"mine.brdf\"\n\nparam = [\"alpha=30\"]\n");
    const auto r = hilite("measure --scene " + bad);
    CHECK(r.code == 2);
    CHECK(errorLines(r.out).size() == 1);
    CHECK(r.out.rfind("hilite: " + bad + ":4: material.param: " + (d / "scenes/mine.brdf") + ":9: --param alpha=30",
                      0) == 0);
}

/// A loop whose body chains 64 sines. llvmpipe caps the loop iterations of one shader invocation at 65535
/// (LP_MAX_TGSI_LOOP_ITERATIONS, shared by all loops), so no loop runs for ever there; a heavy body still
/// makes it ~20 ms per 8 pixels: the probe's 16 renders of 8x8 take ~20 s.
std::string heavyLoop(const std::string& acc) {
    std::string s = "        for (int i = 0; i < 2000000000; ++i) {\n";
    for (int k = 0; k < 64; ++k)
        s += "            " + acc + " = sin(" + acc + " * 1.001 + " + std::to_string(k) + ".0);\n";
    return s + "        }\n";
}

TEST_CASE("cli a shader that runs too long is stopped and reported") {
    Dir d;
    SUBCASE("on the probe: slow everywhere") {
        const std::string path =
            d.write("slow.brdf", "analytic\n::begin shader\n" + kShaderHead + "    float acc = L.x;\n" +
                                     heavyLoop("acc") + "    return vec3(acc);\n}\n::end shader\n");
        for (const std::string& cmd : {std::string("measure"), "render --size 64 -o " + (d / "out.png")}) {
            CAPTURE(cmd);
            const auto r = hilite(cmd + " --brdf " + path + " --shader-timeout 1");
            CHECK(r.code == 2);
            CHECK(errorLines(r.out).size() == 1);
            CHECK(r.out.rfind("hilite: " + path +
                                  ": shader took longer than 1 s on a probe render (8x8 pixels, in a "
                                  "child process); stopped",
                              0) == 0);
            CHECK(r.seconds < 10);
            CHECK_FALSE(fs::exists(d / "out.png"));
        }
    }
    SUBCASE("in the real render: slow only within 0.11 deg of the mirror direction, where the probe never looks") {
        // The probe's closest pixel centre is 0.18 deg from the mirror direction (8x8 over 2 deg).
        const std::string path =
            d.write("mirror.brdf", "analytic\n::begin shader\n" + kShaderHead +
                                       "    vec3 R = 2.0 * dot(N, L) * N - L;\n"
                                       "    float acc = 1.0;\n"
                                       "    if (dot(V, R) > cos(2e-3))\n" +
                                       heavyLoop("acc") + "    return vec3(acc);\n}\n::end shader\n");
        // 8 s, not less: under load (ctest -j2 beside builds) the probe's child (start, compile of the heavy loop,
        // 8x8 render) took more than 3 s, and the probe, not the real render, was reported.
        const auto r = hilite("render --brdf " + path + " --view measure --fov 0.5 --size 256 --shader-timeout 8 -o " +
                              (d / "out.png"));
        CHECK(r.code == 2);
        CHECK(errorLines(r.out).size() == 1);
        CHECK(r.out.rfind("hilite: " + path + ": shader took longer than 8 s on a 256x256 render; stopped", 0) == 0);
        CHECK(r.seconds < 30);
        CHECK_FALSE(fs::exists(d / "out.png"));
    }
}

TEST_CASE("cli .brdf notes, render output and GLSL 1.x style") {
    Dir d;
    const std::string path = d.write("style.brdf",
                                     "analytic\n::begin parameters\nfloat n 1 1000 100\nbool divide 1\n"
                                     "color tint 1 .5 .25\n::end parameters\n::begin shader\n"
                                     "#define UNUSED 1\nconst float PI = 3.14159265358979;\n" +
                                         kShaderHead +
                                         "    vec3 H = normalize(L+V);\n"
                                         "    float val = pow(max(0,dot(N,H)),n) * (n+2)/(2*PI);\n"
                                         "    if (divide) val = val / dot(N,L);\n"
                                         "    return tint * val;\n}\n::end shader\n"
                                         "::begin isFunc\nvec3 sampleBRDF() { return vec3(0); }\n::end isFunc\n");
    const auto r = hilite("render --brdf " + path + " --param tint=1,1,1,divide=0 --size 32 --view photo -o " +
                          (d / "out.png") + " --float " + (d / "out.pfm"));
    CHECK(r.code == 0);
    CHECK(r.out.find("hilite: note: " + path + ":8: '#define UNUSED 1' is a comment") != std::string::npos);
    CHECK(r.out.find("hilite: note: " + path + ":17: isFunc section ignored") != std::string::npos);
    CHECK(r.out.find("brdf=" + path + " n=100 divide=0 tint=1,1,1") != std::string::npos);
    CHECK(fs::exists(d / "out.png"));
    CHECK(fs::file_size(d / "out.pfm") > 32 * 32 * 12);
}

TEST_CASE("cli::run sweeps a .brdf parameter, rows record it, shards merge, [match] is refused") {
    Dir d;
    fs::create_directories(d.path / "exp" / "brdfs");
    fs::copy_file(kShipped + "blinn.brdf", d.path / "exp" / "brdfs" / "b.brdf");
    const std::string exp = d.write("exp/e.toml",
                                    "[experiment]\nname = \"e\"\n[scene.material]\nbrdf = \"brdfs/b.brdf\"\n"
                                    "param = [\"n=100\"]\n[scene.camera]\nsize = \"64\"\n"
                                    "[[sweep]]\nkey = \"material.param\"\nvalues = [\"n=10\", \"n=1000\"]\n"
                                    "[[sweep]]\nkey = \"light.incidence\"\nvalues = [0, 60]\n");
    const std::string hiliteExe(HILITE_EXE);
    REQUIRE(hilite("run " + exp + " -o " + (d / "single")).code == 0);
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
    for (int k = 1; k <= 2; ++k)
        REQUIRE(
            hilite("run " + exp + " --shard " + std::to_string(k) + "/2 -o " + (d / ("s" + std::to_string(k)))).code ==
            0);
    const auto merged = hilite("merge " + (d / "s1") + " " + (d / "s2") + " -o " + (d / "merged"));
    CHECK(merged.code == 0);
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
    const auto b = hilite("run " + broken + " -o " + (d / "broken"));
    CHECK(b.code == 2);
    CHECK(b.out.find("broken.brdf:3:") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "broken/results.csv"));

    const std::string match = d.write("exp/m.toml",
                                      "[scene.material]\nbrdf = \"brdfs/b.brdf\"\n[match]\nmaterial.model = \"ggx\"\n"
                                      "[[sweep]]\nkey = \"light.incidence\"\nvalues = [0]\n");
    const auto r = hilite("run " + match + " -o " + (d / "match"));
    CHECK(r.code == 2);
    CHECK(r.out.find("[match]: matching widths needs a CPU twin") != std::string::npos);
}

TEST_CASE("cli::explain --brdf shows the file's program and effects, and its scene file measures the same") {
    Dir d;
    const std::string flags = "--brdf " + kShipped + "ggx.brdf --param alpha=0.05 --param alpha=0.2";
    const auto effects = hilite("explain " + flags + " --part effects", true);
    CHECK(effects.code == 0);
    CHECK(effects.out.find(".brdf file " + kShipped + "ggx.brdf: its BRDF() (alpha=0.2)") != std::string::npos);
    CHECK(effects.out.find("D_GGX") == std::string::npos);  // no built-in term runs
    const auto glsl = hilite("explain " + flags + " --part glsl", true);
    CHECK(glsl.out.find("vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )") !=
          std::string::npos);  // the file's text
    CHECK(glsl.out.find("D_GGX(") == std::string::npos);
    // The resolved scene is a scene file (absolute .brdf path, every --param in order) that measures the same.
    const auto scene = hilite("explain " + flags + " --part scene", true);
    CHECK(scene.out.find("param = [\"alpha=0.05\", \"alpha=0.2\"]") != std::string::npos);
    d.write("resolved.toml", scene.out);
    const auto direct = hilite("measure " + flags + " --incidence 45 --size 128 --json", true);
    const auto viaFile = hilite("measure --scene " + (d / "resolved.toml") + " --incidence 45 --size 128 --json", true);
    REQUIRE(direct.code == 0);
    REQUIRE(viaFile.code == 0);
    const auto a = nlohmann::json::parse(direct.out), b = nlohmann::json::parse(viaFile.out);
    CHECK(a["aspect"] == b["aspect"]);
    CHECK(a["major_deg"] == b["major_deg"]);
    CHECK(b["brdf_params"] == "alpha=0.2");
}
