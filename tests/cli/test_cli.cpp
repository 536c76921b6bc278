// The command line as a user meets it: exit codes, one-line errors, nothing written on bad input.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace hilite_test;

namespace {

std::string tmpPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("hilite-cli-" + std::to_string(getpid()) + "-" + name)).string();
}

}  // namespace

TEST_CASE("cli::render bad input: one line naming the flag, exit 2, nothing written") {
    const std::string out = tmpPath("bad.png");
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c :
         {Case{"--model lambertian", "--model"}, Case{"--roughness -1", "--roughness"},
          Case{"--roughness nan", "--roughness"}, Case{"--roughness inf", "--roughness"},
          Case{"--exponent -5", "--exponent"}, Case{"--exponent nan", "--exponent"},
          Case{"--incidence 91", "--incidence"}, Case{"--incidence -1", "--incidence"}, Case{"--size 0", "--size"},
          Case{"--size 16385", "--size"}, Case{"--size 16384x16384x", "--size"}, Case{"--fresnel maybe", "--fresnel"},
          Case{"--f0 1.5", "--f0"}, Case{"--geometry none2", "--geometry"}, Case{"--view sideways", "--view"},
          Case{"--light spot", "--light"}, Case{"--light-distance 0", "--light-distance"},
          Case{"--intensity -1", "--intensity"}}) {
        CAPTURE(c.args);
        const auto r = hilite(std::string("render ") + c.args + " -o " + out);
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
        CHECK(r.out.find(c.mentions) != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(out));
    }
}

TEST_CASE("cli::render an unwritable output leaves an existing file untouched") {
    const auto r = hilite("render --size 8 -o /nonexistent-dir/x.png");
    CHECK(r.code == 2);
    CHECK(r.out.find("-o") != std::string::npos);
    CHECK(lines(r.out) == 1);

    const std::string good = tmpPath("keep.png");
    std::ofstream(good) << "precious";
    const auto bad = hilite("render --size 8 --roughness -3 -o " + good);
    CHECK(bad.code == 2);
    std::stringstream ss;
    ss << std::ifstream(good).rdbuf();
    CHECK(ss.str() == "precious");
    std::filesystem::remove(good);
}

TEST_CASE("cli::render writes PNG and PFM") {
    const std::string png = tmpPath("ok.png"), pfm = tmpPath("ok.pfm");
    const auto r =
        hilite("render --size 16x8 --model phong --exponent 100 --incidence 30 -o " + png + " --float " + pfm);
    CHECK(r.code == 0);
    CHECK(std::filesystem::file_size(pfm) == std::string("PF\n16 8\n-1.0\n").size() + 16 * 8 * 3 * 4);
    CHECK(std::filesystem::file_size(png) > 8);
    std::filesystem::remove(png);
    std::filesystem::remove(pfm);
}

TEST_CASE("cli::measure JSON lines carry the contract's fields") {
    const auto r = hilite("measure --model ggx --roughness 0.1 --incidence 0:60:30 --size 128 --json", true);
    REQUIRE(r.code == 0);
    CHECK(lines(r.out) == 3);
    for (const char* field :
         {"\"model\"", "\"incidence_deg\"", "\"aspect\"", "\"eccentricity\"", "\"major_deg\"", "\"minor_deg\"",
          "\"orientation_deg\"", "\"centroid_u_deg\"", "\"centroid_v_deg\"", "\"fwhm_u_deg\"", "\"fwhm_v_deg\"",
          "\"peak\"", "\"flags\"", "\"renders\"", "\"size\"", "\"render_ms\"", "\"measure_ms\""}) {
        CAPTURE(field);
        CHECK(r.out.find(field) != std::string::npos);
    }
}

TEST_CASE("cli::measure bad input") {
    for (const char* args : {"--threshold 1.5", "--threshold 0", "--incidence 0:95:5", "--incidence 10:0:5",
                             "--incidence 0:10:-1", "--incidence a,b", "--boundary fuzzy", "--gl-backend glx",
                             "--gpu -1", "--gl-backend egl-device --gpu 1000", "--gl-backend osmesa --gpu 0"}) {
        CAPTURE(args);
        const auto r = hilite(std::string("measure ") + args);
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
    }
}

TEST_CASE("cli help documents every subcommand") {
    const auto r = hilite("--help");
    CHECK(r.code == 0);
    for (const char* sub : {"render", "measure"}) CHECK(r.out.find(sub) != std::string::npos);
    const auto m = hilite("measure --help");
    CHECK(m.out.find("--threshold") != std::string::npos);
}

TEST_CASE("cli::measure roughness policy: 0 is a mirror, (0, 1e-7) is raised with a warning, never silently") {
    SUBCASE("roughness 0: a warning on stderr, the measurement says mirror") {
        const auto r = hilite("measure --model ggx --roughness 0 --incidence 45 --json --size 64");
        CHECK(r.code == 0);
        CHECK(r.out.find("warning: --roughness 0 is a perfect mirror") != std::string::npos);
        CHECK(r.out.find("\"flags\":[\"mirror\"]") != std::string::npos);
        const auto ref = hilite("measure --model beckmann --roughness 0 --incidence 45 --json --reference", true);
        CHECK(ref.out.find("\"flags\":[\"mirror\"]") != std::string::npos);
    }
    SUBCASE("roughness 1e-9: raised to 1e-7, said on stderr, and the row carries 1e-7") {
        const auto r = hilite("measure --model ggx --roughness 1e-9 --incidence 45 --json --reference");
        CHECK(r.code == 0);
        CHECK(r.out.find("--roughness 1e-09 raised to 1e-07") != std::string::npos);
        CHECK(r.out.find("\"roughness\":1e-07") != std::string::npos);
    }
    SUBCASE("roughness-y 0 on an anisotropic lobe is a mirror too") {
        const auto r = hilite("measure --model ggx --roughness 0.1 --roughness-y 0 --incidence 30 --json", true);
        CHECK(r.code == 0);
        CHECK(r.out.find("\"mirror\"") != std::string::npos);
    }
    SUBCASE("the GL path says effectively_mirror below float resolution, the reference measures it") {
        const auto gl = hilite("measure --model ggx --roughness 1e-7 --incidence 45 --json --size 128", true);
        CHECK(gl.out.find("effectively_mirror") != std::string::npos);
        const auto ref = hilite("measure --model ggx --roughness 1e-7 --incidence 45 --json --reference", true);
        CHECK(ref.out.find("\"flags\":[]") != std::string::npos);
    }
    SUBCASE("a model without roughness takes no warning for it") {
        const auto r = hilite("measure --model phong --roughness 0 --incidence 45 --json --reference");
        CHECK(r.out.find("warning") == std::string::npos);
    }
}

TEST_CASE("cli::measure says what a highlight is framed about (retroreflection)") {
    const auto r = hilite("measure --model retro --exponent 1000 --incidence 60 --size 64 --json", true);
    CHECK(r.code == 0);
    CHECK(r.out.find("\"framed_about\":\"peak (retroreflection: toward the light, 2 theta_i = 120 deg") !=
          std::string::npos);
    CHECK((r.out.find("\"peak_offset_deg\":120") != std::string::npos ||
           r.out.find("\"peak_offset_deg\":119.9999") != std::string::npos));
    const auto t = hilite("measure --model retro --exponent 1000 --incidence 60 --size 64", true);
    CHECK(t.out.find("about the peak, 120 deg from the mirror direction") != std::string::npos);
    const auto g = hilite("measure --model ggx --incidence 60 --size 64 --json", true);
    CHECK(g.out.find("\"framed_about\":\"mirror direction\"") != std::string::npos);
}

TEST_CASE("cli tabulated NDF: bad tables are one-line errors naming file:line, exit 2, nothing written") {
    const std::string table = tmpPath("ndf.csv"), out = tmpPath("ndf.png");
    struct Case {
        const char* text;
        const char* line;
    };
    for (const Case c : {Case{"0, 1\n10, 0.5\n5, 0.2\n", ":3: "}, Case{"0, 1\n10, -0.5\n", ":2: "},
                         Case{"0, 1\n10, nan\n", ":2: "}, Case{"0, 1\n", ":1: "}}) {
        std::ofstream(table) << c.text;
        CAPTURE(c.text);
        for (const std::string& cmd : {"render --model tabulated --ndf-table " + table + " -o " + out,
                                       "measure --model tabulated --ndf-table " + table}) {
            const auto r = hilite(cmd);
            CHECK(r.code == 2);
            CHECK(lines(r.out) == 1);
            CHECK(r.out.find(table + c.line) != std::string::npos);
            CHECK_FALSE(std::filesystem::exists(out));
        }
    }
    const auto missing = hilite("measure --model tabulated --ndf-table /nonexistent/ndf.csv");
    CHECK(missing.code == 2);
    CHECK(lines(missing.out) == 1);
    CHECK(missing.out.find("/nonexistent/ndf.csv") != std::string::npos);
    CHECK(hilite("measure --model tabulated").code == 2);                 // no table
    CHECK(hilite("measure --model ggx --ndf-table " + table).code == 2);  // a table for another model
    std::ofstream(table) << "theta_h_deg, D\n0, 4\n2, 3\n5, 1\n10, 0\n";
    const auto ok = hilite("measure --model tabulated --ndf-table " + table + " --incidence 30 --size 64 --json", true);
    CHECK(ok.code == 0);
    CHECK(ok.out.find("\"ndf_table_normalization\":") != std::string::npos);
    const auto ex = hilite("explain --model tabulated --ndf-table " + table + " --part effects", true);
    CHECK(ex.out.find("normalized by x") != std::string::npos);
    std::filesystem::remove(table);
}

TEST_CASE("cli a flag combination a path cannot honour is refused, never silently measured another way") {
    struct Case {
        const char* args;
        const char* mentions;
    };
    for (const Case c : {Case{"--model beckmann --bumps explicit --renderer cpu", "--renderer cpu"},
                         Case{"--model beckmann --bumps explicit --tolerance 1e-3", "--tolerance"},
                         Case{"--model beckmann --bumps explicit --reference", "--reference"}}) {
        CAPTURE(c.args);
        const auto r = hilite(std::string("measure --incidence 30 --size 32 ") + c.args);
        CHECK(r.code == 2);
        CHECK(lines(r.out) == 1);
        CHECK(r.out.find(c.mentions) != std::string::npos);
    }
}

TEST_CASE("cli --bump-filter moments refuses ggx bumps (their slopes are not Gaussian)") {
    const auto r = hilite("measure --model ggx --bumps explicit --bump-filter moments --size 32");
    CHECK(r.code == 2);
    CHECK(lines(r.out) == 1);
    CHECK(r.out.find("--bump-filter moments") != std::string::npos);
}
