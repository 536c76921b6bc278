// .brdf files from the command line: notes on stderr and the files render writes, and a shader that runs too
// long stopped (exit 2, one line, nothing written). Rows, refusals, scene files and experiments with .brdf files,
// in-process: tests/experiments/test_brdf_file_run.cpp.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

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

/// The scratch directory of this file's runs.
struct Dir : TempDir {
    Dir() : TempDir("hilite-brdf-cli") {}
};

const std::string kShaderHead = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n";

}  // namespace

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
