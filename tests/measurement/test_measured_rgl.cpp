// An RGL material (--measured FILE.bsdf, told apart from a MERL table by its content) where a model goes,
// in-process as `hilite measure`, `explain` and `run` call it: the row, the effects, the table_error, GL
// against the CPU twin on the real files of ../shared (where present), a folder sweep, and bad files refused.

#include "brdf/rgl.hpp"
#include "render/renderer.hpp"
#include "support/in_process.hpp"
#include "support/rgl_file.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace hilite;
using namespace hilite::testing;

namespace {

/// The synthetic material written to a file (the name says nothing: the content tells RGL from MERL).
struct Synthetic {
    hilite_test::TempDir dir{"hilite-rgl-measure"};
    std::string file = dir / "synthetic.table";
    Synthetic() { std::ofstream(file, std::ios::binary) << hilite_test::tensorFile(hilite_test::syntheticRgl(7)); }
};

}  // namespace

TEST_CASE("measured rgl: the row says measured:FILE and has a table_error, and explain names the RGL material") {
    Synthetic t;
    const auto all = measureJson(flags("--measured " + t.file + " --incidence 30 --size 128"));
    REQUIRE(all.size() == 1);
    const auto& row = all[0];
    CHECK(row["model"] == "measured:synthetic.table");
    CHECK(row["measured"] == t.file);
    for (const char* unused : {"roughness", "fresnel", "geometry", "diffuse", "f0", "exponent"}) {
        CAPTURE(unused);
        CHECK(!row.contains(unused));
    }
    REQUIRE(row.contains("table_error"));
    CHECK(row["table_error"]["aspect"].is_number());
    std::string effects;
    for (const auto& e : render::activeEffects(scene::resolve(flags("--measured " + t.file)).scene))
        effects += e + "\n";
    CHECK(effects.find("measured RGL material " + t.file + " (synthetic)") != std::string::npos);
    CHECK(effects.find("indexed by the light direction") != std::string::npos);
}

TEST_CASE("measured rgl: the GL measurement of the real files agrees with the CPU twin's at 0-80 deg") {
    const std::string dir = hilite_test::sharedMeasured();
    for (const char* name : {"cg_sunflower_rgb.bsdf", "satin_rosaline_rgb.bsdf"}) {
        const std::string file = dir + "/" + name;
        if (!std::filesystem::exists(file)) {
            MESSAGE("skipped: " << file << " is missing (the RGL files are not part of the project; see README)");
            continue;
        }
        const std::string args = "--measured " + file + " --incidence 0,20,40,60,80 --renderer ";
        const auto gl = measureJson(flags(args + "gl")), cpu = measureJson(flags(args + "cpu"));
        REQUIRE(gl.size() == 5);
        REQUIRE(cpu.size() == 5);
        double worst = 0;
        for (size_t i = 0; i < 5; ++i) {
            CAPTURE(file);
            CAPTURE(gl[i]["incidence_deg"]);
            CHECK(gl[i]["method"] == "gl");
            CHECK(gl[i]["flags"] == cpu[i]["flags"]);
            for (const char* k : {"aspect", "major_deg", "minor_deg", "centroid_u_deg"}) {
                CAPTURE(k);
                const double d = std::abs(double(gl[i][k]) - double(cpu[i][k]));
                CHECK(d < 2e-3 * std::max(1.0, std::abs(double(cpu[i][k]))));
                if (std::string(k) == "aspect") worst = std::max(worst, d);
            }
        }
        MESSAGE(std::string(name) << ": worst |aspect GL - aspect CPU twin| over 0-80 deg " << worst);
    }
}

TEST_CASE("measured rgl: a folder sweep takes .bsdf files beside .binary ones") {
    Synthetic t;
    std::filesystem::create_directory(t.dir / "tables");
    std::filesystem::copy_file(t.file, t.dir / "tables/a.bsdf");
    std::filesystem::copy_file(t.file, t.dir / "tables/b.bsdf");
    { std::ofstream(t.dir / "tables/notes.txt") << "not a table"; }
    const std::string exp = t.dir / "e.toml";
    std::ofstream(exp) << "[experiment]\nname = \"rgl\"\n[scene]\nlight.incidence = 30\n"
                          "camera.size = 64\n[[sweep]]\nkey = \"material.measured\"\nfolder = \"tables\"\n";
    const auto s = runExperiment(exp, t.dir / "out");
    CHECK(s.configurations == 2);
    CHECK(s.measured == 2);
}

TEST_CASE("measured rgl: bad files are refused in one line naming --measured and the file") {
    Synthetic t;
    std::string damaged = hilite_test::tensorFile(hilite_test::syntheticRgl());
    const std::string truncated = t.dir / "truncated.bsdf", fifo = t.dir / "fifo.bsdf";
    std::ofstream(truncated, std::ios::binary) << damaged.substr(0, damaged.size() - 7);
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    for (const std::string& file : {truncated, fifo, t.dir.path.string()}) {
        CAPTURE(file);
        const std::string why = measureRefusal(flags("--measured " + file + " --size 64"));
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find("--measured: '" + file + "'") == 0);
    }
    const std::string why = measureRefusal(flags("--measured " + t.file + " --model ggx"));
    CHECK(why.find("--model: not with --measured") != std::string::npos);
}

TEST_CASE("measured rgl: --ndf-table FILE.bsdf measures as the microfacet model whose NDF the file holds") {
    // A file holding GGX 0.2's NDF and projected area: the tabulated model built from it is GGX 0.2.
    hilite_test::TempDir dir("hilite-rgl-ndf-measure");
    const std::string file = dir / "ggx-ndf.bsdf";
    std::ofstream(file, std::ios::binary) << hilite_test::tensorFile(hilite_test::syntheticGgxNdf(0.2));
    const std::string terms = " --geometry smith --fresnel schlick --f0 0.04 --incidence 0,30,60 --reference";
    const auto table = measureJson(flags("--model tabulated --ndf-table " + file + terms));
    const auto ggx = measureJson(flags("--model ggx --roughness 0.2" + terms));
    for (size_t i = 0; i < table.size(); ++i) {
        CAPTURE(i);
        CHECK(table[i]["aspect"].get<double>() == doctest::Approx(ggx[i]["aspect"].get<double>()).epsilon(3e-3));
        CHECK(table[i]["major_deg"].get<double>() == doctest::Approx(ggx[i]["major_deg"].get<double>()).epsilon(3e-3));
        CHECK(table[i]["ndf_table_normalization"].get<double>() == doctest::Approx(1.0).epsilon(2e-3));
    }
    // A damaged file is refused in one line naming the flag.
    const std::string bad = dir / "truncated.bsdf";
    const std::string bytes = hilite_test::tensorFile(hilite_test::syntheticGgxNdf(0.2));
    std::ofstream(bad, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const std::string why = refusal(flags("--model tabulated --ndf-table " + bad));
    CHECK(oneLine(why));
    CHECK(why.find("--ndf-table") != std::string::npos);
}

TEST_CASE("measured rgl: a spectral file measures through --measured, reduced to RGB with hilite's colorimetry") {
    hilite_test::TempDir dir("hilite-rgl-spectral");
    const std::string file = dir / "flat-spectral.bsdf";
    std::ofstream(file, std::ios::binary)
        << hilite_test::tensorFile(hilite_test::syntheticSpectral([](double) { return 1.0; }, 7));
    const auto rows = measureJson(flags("--measured " + file + " --incidence 30 --size 128"));
    REQUIRE(rows.size() == 1);
    CHECK(rows[0]["model"] == "measured:flat-spectral.bsdf");
    CHECK(rows[0]["aspect"].is_number());
}
