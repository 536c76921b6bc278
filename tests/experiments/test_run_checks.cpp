// `hilite run`'s checks in-process (the experiments library as src/cli/run_cmd.cpp calls it): bad experiment
// files, GL backends and shards are refused before anything is written; every shipped experiment validates and
// runs a shard. The run end to end (rows, resume after SIGKILL, progress, merge, --check's words):
// tests/cli/test_run.cpp.

#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace hilite;
using namespace hilite::testing;

namespace {

struct Dir : hilite_test::TempDir {
    Dir() : TempDir("hilite-run-checks") {}
};

/// The refusal of `hilite run EXPERIMENT [--shard SHARD] [--gl-backend BACKEND] -o OUT`; "" when it runs.
std::string refusal(const std::string& experiment, const std::string& out, const std::string& shard = "",
                    const std::string& backend = "") {
    return inputError([&] {
        experiments::RunOptions o;
        experiments::parseShard(shard, o.shardK, o.shardN);
        o.experiment = experiment, o.out = out, o.backend = backend;
        experiments::runExperiment(o);
    });
}

}  // namespace

TEST_CASE("run bad experiment files are refused in one line, nothing written") {
    Dir d;
    std::ofstream(d / "bad.toml") << "[[sweep]]\nkey = \"material.rougness\"\nvalues = [0.1]\n";
    CHECK(oneLine(refusal(d / "bad.toml", d / "bad")));
    std::ofstream(d / "bad2.toml") << "[[sweep]]\nkey = \"light.incidence\"\nvalues = [100]\n";
    CHECK(oneLine(refusal(d / "bad2.toml", d / "bad2")));
    CHECK_FALSE(fs::exists(d / "bad2/results.csv"));
    CHECK_FALSE(fs::exists(d / "bad2"));  // not even the output folder
    // An unknown GL backend is refused before anything is written (it was found at the first render).
    CHECK(oneLine(refusal("eccentricity", d / "gb", "", "bogus")));
    CHECK_FALSE(fs::exists(d / "gb"));
    for (const char* shard : {"1/2x", "3/2", "0/1", "1.5/2", "x"}) {  // a malformed --shard is refused, not truncated
        CAPTURE(shard);
        CHECK(oneLine(refusal("eccentricity", d / "sh", shard)));
        CHECK_FALSE(fs::exists(d / "sh"));
    }
}

TEST_CASE("run [match] with a sweep of the width it sets is refused in one line, nothing written") {
    // Before: the matched roughness silently replaced the swept one in every row.
    Dir d;
    const std::string head =
        "[[sweep]]\nkey = \"light.incidence\"\nrange = [0, 80, 40]\n[match]\nmaterial.model = "
        "\"ggx\"\nmaterial.roughness = 0.1\n";
    std::ofstream(d / "values.toml") << head << "[[sweep]]\nkey = \"material.roughness\"\nvalues = [0.05, 0.2]\n";
    std::ofstream(d / "cases.toml") << head
                                    << "[[sweep]]\nkey = \"case\"\ncases = [{ name = \"a\", material = { model = "
                                       "\"phong\", exponent = 100 } }]\n";
    for (const char* f : {"values", "cases"}) {
        CAPTURE(f);
        const std::string why = refusal(d / (std::string(f) + ".toml"), d / f);
        CAPTURE(why);
        CHECK(oneLine(why));
        CHECK(why.find("[match] sets each model's") != std::string::npos);
        CHECK_FALSE(fs::exists(d / f));
    }
    // Without the sweep of the width, [match] runs (the shipped eccentricity experiment does).
    std::ofstream(d / "ok.toml") << head;
    CHECK(refusal(d / "ok.toml", d / "ok").empty());
}

TEST_CASE("experiments shipped in experiments/ all validate") {
    for (const auto& e : fs::directory_iterator(fs::path(HILITE_SOURCE_DIR_STR) / "experiments")) {
        if (e.path().extension() != ".toml") continue;
        CAPTURE(e.path().string());
        Dir d;
        std::string file = e.path().string();
        if (e.path().stem() == "real_materials") {
            // Its folder of .bsdf files is not part of the project: without it, the refusal says where to get them;
            // with ../shared, a copy beside a link to it validates (tests/experiments/test_real_materials.cpp runs it).
            const std::string shared = std::string(HILITE_SOURCE_DIR_STR) + "/../shared/data/measured";
            if (!fs::exists(fs::path(HILITE_SOURCE_DIR_STR) / "experiments" / "measured")) {
                if (!fs::exists(shared)) {
                    const std::string why = runRefusal(file, d / "c", true);
                    CHECK(why.find("rgl.epfl.ch/materials") != std::string::npos);
                    MESSAGE("skipped: real_materials needs " << shared
                                                             << " (the RGL files are not part of the project)");
                    continue;
                }
                fs::copy_file(e.path(), d / "real_materials.toml");
                fs::create_directory_symlink(fs::absolute(shared), d / "measured");
                file = d / "real_materials.toml";
            }
        }
        // --check: the whole file, every configuration and the folder, nothing written.
        CHECK(runRefusal(file, d / "c", true) == "");
        CHECK(!fs::exists(d / "c"));
        // --shard 1/100000 measures at most one configuration and writes every report from it. The bounce studies
        // and the fits run a whole study in one configuration: tests/experiments/test_bounces.cpp and test_fit.cpp
        // run their reports on small tables.
        const std::string name = e.path().stem().string();
        if (name == "burnished_gold" || name == "rough_dielectric" || name == "fit_models") continue;
        CHECK(refusal(file, d / "x", "1/100000") == "");
    }
}
