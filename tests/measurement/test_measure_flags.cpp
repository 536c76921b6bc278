// `hilite measure`'s flags in-process: the rows its --json prints, the warnings it gives on stderr and the
// one-line refusals, through the library exactly as src/cli/measure_cmd.cpp calls it (tests/cli keeps the
// end-to-end cases: exit codes, stdout, nothing written).

#include "render/renderer.hpp"
#include "support/in_process.hpp"

#include <doctest/doctest.h>

#include "support/near.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

using namespace hilite;
using namespace hilite::testing;

namespace {

std::string tmpPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("hilite-measure-" + std::to_string(getpid()) + "-" + name))
        .string();
}

}  // namespace

TEST_CASE("measure JSON lines carry the contract's fields") {
    const auto rows = measureJson(flags("--model ggx --roughness 0.1 --incidence 0:60:30 --size 128"));
    CHECK(rows.size() == 3);
    const std::string out = jsonLines(rows);
    for (const char* field :
         {"\"model\"", "\"incidence_deg\"", "\"aspect\"", "\"eccentricity\"", "\"major_deg\"", "\"minor_deg\"",
          "\"orientation_deg\"", "\"centroid_u_deg\"", "\"centroid_v_deg\"", "\"fwhm_u_deg\"", "\"fwhm_v_deg\"",
          "\"peak\"", "\"flags\"", "\"renders\"", "\"size\"", "\"render_ms\"", "\"measure_ms\""}) {
        CAPTURE(field);
        CHECK(out.find(field) != std::string::npos);
    }
}

TEST_CASE("measure bad input is refused in one line") {
    for (const char* args : {"--threshold 1.5", "--threshold 0", "--incidence 0:95:5", "--incidence 10:0:5",
                             "--incidence 0:10:-1", "--incidence a,b", "--boundary fuzzy", "--gl-backend glx",
                             "--gpu -1", "--gl-backend egl-device --gpu 1000", "--gl-backend osmesa --gpu 0"}) {
        CAPTURE(args);
        const std::string why = measureRefusal(flags(args));
        CAPTURE(why);
        CHECK(oneLine(why));
    }
}

TEST_CASE("measure roughness policy: 0 is a mirror, (0, 1e-7) is raised with a warning, never silently") {
    SUBCASE("roughness 0: a warning on stderr, the measurement says mirror") {
        StderrCapture err;
        const std::string out = jsonLines(measureJson(flags("--model ggx --roughness 0 --incidence 45 --size 64")));
        CHECK(err.str().find("warning: --roughness 0 is a perfect mirror") != std::string::npos);
        CHECK(out.find("\"flags\":[\"mirror\"]") != std::string::npos);
        const std::string ref =
            jsonLines(measureJson(flags("--model beckmann --roughness 0 --incidence 45 --reference")));
        CHECK(ref.find("\"flags\":[\"mirror\"]") != std::string::npos);
    }
    SUBCASE("roughness 1e-9: raised to 1e-7, said on stderr, and the row carries 1e-7") {
        StderrCapture err;
        const std::string out =
            jsonLines(measureJson(flags("--model ggx --roughness 1e-9 --incidence 45 --reference")));
        CHECK(err.str().find("--roughness 1e-09 raised to 1e-07") != std::string::npos);
        CHECK(out.find("\"roughness\":1e-07") != std::string::npos);
    }
    SUBCASE("roughness-y 0 on an anisotropic lobe is a mirror too") {
        const std::string out =
            jsonLines(measureJson(flags("--model ggx --roughness 0.1 --roughness-y 0 --incidence 30")));
        CHECK(out.find("\"mirror\"") != std::string::npos);
    }
    SUBCASE("the GL path says effectively_mirror below float resolution, the reference measures it") {
        const std::string gl = jsonLines(measureJson(flags("--model ggx --roughness 1e-7 --incidence 45 --size 128")));
        CHECK(gl.find("effectively_mirror") != std::string::npos);
        const std::string ref =
            jsonLines(measureJson(flags("--model ggx --roughness 1e-7 --incidence 45 --reference")));
        CHECK(ref.find("\"flags\":[]") != std::string::npos);
    }
    SUBCASE("a model without roughness takes no warning for it") {
        StderrCapture err;
        measureJson(flags("--model phong --roughness 0 --incidence 45 --reference"));
        CHECK(err.str().find("warning") == std::string::npos);
    }
}

TEST_CASE("measure says what a highlight is framed about (retroreflection)") {
    const std::string out = jsonLines(measureJson(flags("--model retro --exponent 1000 --incidence 60 --size 64")));
    CHECK(out.find("\"framed_about\":\"peak (retroreflection: toward the light, 2 theta_i = 120 deg") !=
          std::string::npos);
    CHECK((out.find("\"peak_offset_deg\":120") != std::string::npos ||
           out.find("\"peak_offset_deg\":119.9999") != std::string::npos));
    const std::string g = jsonLines(measureJson(flags("--model ggx --incidence 60 --size 64")));
    CHECK(g.find("\"framed_about\":\"mirror direction\"") != std::string::npos);
}

TEST_CASE("tabulated NDF: bad tables are one-line refusals naming file:line, for render and measure") {
    const std::string table = tmpPath("ndf.csv");
    struct Case {
        const char* text;
        const char* line;
    };
    for (const Case c : {Case{"0, 1\n10, 0.5\n5, 0.2\n", ":3: "}, Case{"0, 1\n10, -0.5\n", ":2: "},
                         Case{"0, 1\n10, nan\n", ":2: "}, Case{"0, 1\n", ":1: "}}) {
        std::ofstream(table) << c.text;
        CAPTURE(c.text);
        const scene::Values v = flags("--model tabulated --ndf-table " + table);
        for (const scene::Purpose purpose : {scene::Purpose::Render, scene::Purpose::Measure}) {
            const std::string why = refusal(v, purpose);
            CAPTURE(why);
            CHECK(oneLine(why));
            CHECK(why.find(table + c.line) != std::string::npos);
        }
    }
    const std::string missing = refusal(flags("--model tabulated --ndf-table /nonexistent/ndf.csv"));
    CHECK(oneLine(missing));
    CHECK(missing.find("/nonexistent/ndf.csv") != std::string::npos);
    CHECK(refusal(flags("--model tabulated")) != "");                 // no table
    CHECK(refusal(flags("--model ggx --ndf-table " + table)) != "");  // a table for another model
    std::ofstream(table) << "theta_h_deg, D\n0, 4\n2, 3\n5, 1\n10, 0\n";
    const std::string ok =
        jsonLines(measureJson(flags("--model tabulated --ndf-table " + table + " --incidence 30 --size 64")));
    CHECK(ok.find("\"ndf_table_normalization\":") != std::string::npos);
    std::string effects;  // what `hilite explain --part effects` prints
    for (const auto& e : render::activeEffects(scene::resolve(flags("--model tabulated --ndf-table " + table)).scene))
        effects += e + "\n";
    CHECK(effects.find("normalized by x") != std::string::npos);
    std::filesystem::remove(table);
}

TEST_CASE("a flag combination a path cannot honour is refused, never silently measured another way") {
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c : {Case{"--model beckmann --bumps explicit --renderer cpu", "--renderer cpu"},
                         Case{"--model beckmann --bumps explicit --tolerance 1e-3", "--tolerance"},
                         Case{"--model beckmann --bumps explicit --reference", "--reference"}}) {
        CAPTURE(c.args);
        const std::string why = measureRefusal(flags(std::string("--incidence 30 --size 32 ") + c.args));
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.mentions) != std::string::npos);
    }
}

TEST_CASE("--bump-filter moments refuses ggx bumps (their slopes are not Gaussian)") {
    const std::string why = measureRefusal(flags("--model ggx --bumps explicit --bump-filter moments --size 32"));
    CHECK(oneLine(why));
    CHECK(why.find("--bump-filter moments") != std::string::npos);
}

TEST_CASE("measure accuracy flags: bad values, one line naming the flag and its range") {
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c :
         {Case{"--tolerance 0", "--tolerance: must be a finite number in [1e-05, 0.1]"},
          Case{"--tolerance 0.5", "[1e-05, 0.1]"}, Case{"--tolerance nan", "--tolerance"},
          Case{"--tolerance abc", "--tolerance"}, Case{"--tolerance 1e-3 --reference", "--tolerance"},
          Case{"--supersample 0", "--supersample: must be a whole number in [1, 8]"}, Case{"--supersample 9", "[1, 8]"},
          Case{"--renderer vulkan", "--renderer"}, Case{"--crop maybe", "--crop"}}) {
        CAPTURE(c.args);
        const std::string why = measureRefusal(flags(std::string("--incidence 30 ") + c.args));
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find(c.mentions) != std::string::npos);
    }
}

TEST_CASE("measure --tolerance reports settings, error estimate and time") {
    const auto rows = measureJson(flags("--model ggx --roughness 0.02 --incidence 80 --tolerance 1e-3"));
    REQUIRE(rows.size() == 1);
    const auto& j = rows[0];
    CHECK(j["tolerance"].get<double>() == 1e-3);
    CHECK(j["error_estimate"].get<double>() <= 1e-3);
    CHECK(j["tolerance_met"].get<bool>());
    CHECK(j["time_ms"].get<double>() > 0);
    for (const char* k : {"size", "boundary", "supersample", "framing", "renderer"}) CHECK(j["settings"].contains(k));
    CHECK(j["check"].contains("size"));
    // The table's line of its own: tests/cli/test_cli.cpp.
}

TEST_CASE("measure --renderer cpu and --supersample") {
    const auto c = measureJson(flags("--incidence 60 --size 128 --renderer cpu")).at(0);
    const auto g = measureJson(flags("--incidence 60 --size 128")).at(0);
    CHECK(c["method"] == "cpu");
    CHECK_NEAR(c["aspect"].get<double>(), g["aspect"].get<double>(), 0.005);
    const auto ss = measureJson(flags("--incidence 60 --size 64 --supersample 3")).at(0);
    CHECK(ss["renders"].get<int>() >= 10);  // aiming + 9 jittered
}

TEST_CASE("a .brdf with an infinite peak is float_overflow, not aspect 1 and major 0") {
    // 1 / (1 - R.V) is inf at the mirror direction (before: aspect 1, major 0, peak null, no flag).
    const std::string file = tmpPath("inf-peak.brdf");
    std::ofstream(file) << "analytic\n::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)\n{\n"
                           "    vec3 R = reflect(-L, N);\n    return vec3(1.0 / max(0.0, 1.0 - dot(R, V)));\n}\n"
                           "::end shader\n";
    const auto rows = measureJson(flags("--brdf " + file + " --incidence 30 --size 64"));
    std::filesystem::remove(file);
    REQUIRE(rows.size() == 1);
    CHECK(rows[0]["flags"] == nlohmann::json::array({"float_overflow"}));
    for (const char* k : {"aspect", "major_deg", "minor_deg"}) CHECK(rows[0][k].is_null());
}

/// A tabulated NDF of `rows` (theta_h_deg, D) at 30 deg, measured by the reference and by GL: one row each.
std::pair<std::vector<nlohmann::json>, std::vector<nlohmann::json>> ringAt30(const std::string& name,
                                                                             const std::string& rows) {
    const std::string file = tmpPath(name);
    std::ofstream(file) << "theta_h_deg, D\n" << rows;
    const std::string args = "--model tabulated --ndf-table " + file + " --incidence 30";
    auto ref = measureJson(flags(args + " --reference"));
    auto gl = measureJson(flags(args));
    std::filesystem::remove(file);
    REQUIRE(ref.size() == 1);
    REQUIRE(gl.size() == 1);
    return {ref, gl};
}

TEST_CASE("a thin ring of a tabulated NDF off the mirror direction: the reference finds it as GL does") {
    // D > 0 only at theta_h 0.5-0.7 deg: dark at every survey grid sample and at the mirror direction (before:
    // the reference said no_highlight, peak 0, while GL measured major 1.698 deg).
    const auto [ref, gl] = ringAt30("ring.csv", "0, 0\n0.5, 0\n0.6, 10\n0.7, 0\n90, 0\n");
    CHECK(ref[0]["flags"].empty());
    CHECK(ref[0]["peak"].get<double>() > 0);
    CHECK(ref[0]["major_deg"].get<double>() == doctest::Approx(gl[0]["major_deg"].get<double>()).epsilon(0.02));
}

TEST_CASE("a ring of a tabulated NDF 30 deg off the mirror direction: the reference names its budget, not an error") {
    // D > 0 only at theta_h 30-30.4 deg, at 30 deg: the region grows past every box enlargement; before, the
    // reference threw "internal error: measureLines: the region keeps growing past its boxes" (exit 3).
    const std::string file = tmpPath("ring30.csv");
    std::ofstream(file) << "theta_h_deg, D\n0, 0\n30, 0\n30.2, 10\n30.4, 0\n90, 0\n";
    const auto ref = measureJson(flags("--model tabulated --ndf-table " + file + " --incidence 30 --reference"));
    std::filesystem::remove(file);
    REQUIRE(ref.size() == 1);
    const auto& f = ref[0]["flags"];
    CHECK(std::find(f.begin(), f.end(), "not_converged") != f.end());
}

TEST_CASE("a ring of a tabulated NDF that the survey splits in 12 parts: GL measures it at the lobe's own level") {
    // D = 1 at theta_h 10-11 deg, at 30 deg: one ring, which the survey's grid splits in 12 parts. GL took the
    // level from the brightest pixel of the first part's view, a 1 deg^2 sliver (5.0; the ring reaches 10.0):
    // 2 components, area 262 deg^2, aspect 0.8677 against the reference's 1, 250.7 and 0.8660.
    const auto [ref, gl] = ringAt30("ring10.csv", "0, 0\n9.9, 0\n10, 1\n11, 1\n11.1, 0\n90, 0\n");
    CHECK(gl[0]["flags"] == ref[0]["flags"]);
    CHECK(gl[0]["components"] == ref[0]["components"]);
    CHECK(gl[0]["peak"].get<double>() == doctest::Approx(ref[0]["peak"].get<double>()).epsilon(1e-4));
    CHECK(gl[0]["aspect"].get<double>() == doctest::Approx(ref[0]["aspect"].get<double>()).epsilon(0.002));
    CHECK(gl[0]["area_deg2"].get<double>() == doctest::Approx(ref[0]["area_deg2"].get<double>()).epsilon(0.005));
}
