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

/// A results.jsonl's rows without their timing fields (*_ms): what two runs of one experiment share.
std::vector<nlohmann::json> rowsWithoutTimes(const fs::path& file) {
    std::vector<nlohmann::json> rows;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        auto r = nlohmann::json::parse(line);
        for (auto it = r.begin(); it != r.end();)
            it = it.key().size() > 3 && it.key().compare(it.key().size() - 3, 3, "_ms") == 0 ? r.erase(it)
                                                                                             : std::next(it);
        rows.push_back(r);
    }
    return rows;
}

/// The two-model, three-angle sweep the distributed-run and merge tests share.
const char* const kSweep =
    "[scene.camera]\nsize = \"64\"\n[[sweep]]\nkey = \"material.model\"\n"
    "values = [\"phong\", \"ggx\"]\n[[sweep]]\nkey = \"light.incidence\"\n"
    "values = [0, 40, 70]\n";

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

TEST_CASE("a distributed run: rows measured elsewhere, in any order, make the folder a single run makes") {
    // What hilite.run(..., client=) does on Dask workers (python/tests/test_dask.py), here in one process.
    Dir d;
    std::ofstream(d / "e.toml") << kSweep;
    experiments::RunOptions o;
    o.experiment = d / "e.toml", o.out = d / "single";
    experiments::runExperiment(o);
    o.out = d / "spread";
    {
        experiments::DistributedRun run(o);
        const std::vector<size_t> todo = run.todo();
        REQUIRE(todo.size() == 6);
        experiments::ConfigurationMeasurer worker(run.experimentPath());
        CHECK(worker.configurations() == 6);
        CHECK(oneLine(inputError([&] { worker.measure(6); })));
        for (auto i = todo.rbegin(); i != todo.rend(); ++i) run.append(worker.measure(*i));  // last first
        CHECK(inputError([&] { run.append(worker.measure(2)); }).find("has its row already") != std::string::npos);
        CHECK(inputError([&] { run.append("{\"config\": 1}"); }).find("fingerprint") != std::string::npos);
        const experiments::RunSummary s = run.finish();
        CHECK(s.measured == 6);
        CHECK(s.finalized);
    }
    CHECK(rowsWithoutTimes(d / "spread/results.jsonl") == rowsWithoutTimes(d / "single/results.jsonl"));
    CHECK(fs::exists(d / "spread/summary.md"));
    // A shard's run takes only its own configurations; missing rows are named, the written ones kept.
    o.out = d / "half";
    o.shardK = 2, o.shardN = 2;
    experiments::DistributedRun half(o);
    CHECK(half.todo() == std::vector<size_t>{1, 3, 5});
    experiments::ConfigurationMeasurer worker(half.experimentPath());
    CHECK(inputError([&] { half.append(worker.measure(0)); }).find("is not one this run (shard 2/2)") !=
          std::string::npos);
    half.append(worker.measure(3));
    CHECK(inputError([&] { half.finish(); }).find("2 of 3 configurations have no row yet") != std::string::npos);
}

TEST_CASE("merge streams the shards in configuration order, also a resumed shard out of order") {
    Dir d;
    std::ofstream(d / "e.toml") << kSweep;
    experiments::RunOptions o;
    o.experiment = d / "e.toml", o.out = d / "single";
    experiments::runExperiment(o);
    o.shardN = 2;
    for (int k : {1, 2}) {
        o.shardK = k, o.out = d / ("s" + std::to_string(k));
        experiments::runExperiment(o);
    }
    auto lines = [](const fs::path& f) {
        std::vector<std::string> out;
        std::ifstream in(f);
        for (std::string l; std::getline(in, l);) out.push_back(l);
        return out;
    };
    // Shard 1 as a resume leaves it: rows out of order, and a torn last line (dropped).
    auto s1 = lines(d / "s1/results.jsonl");
    REQUIRE(s1.size() == 3);
    std::ofstream(d / "s1/results.jsonl") << s1[2] << "\n" << s1[0] << "\n" << s1[1] << "\n" << s1[0].substr(0, 30);
    const auto m = experiments::mergeShards({d / "s1", d / "s2"}, d / "merged");
    CHECK(m.rows == 6);
    CHECK(rowsWithoutTimes(d / "merged/results.jsonl") == rowsWithoutTimes(d / "single/results.jsonl"));
    CHECK(lines(d / "merged/results.csv").size() == 7);
    // A configuration in two shards is refused before anything is written.
    std::ofstream(d / "s1/results.jsonl") << s1[0] << "\n" << lines(d / "s2/results.jsonl")[0] << "\n";
    const std::string why = inputError([&] { experiments::mergeShards({d / "s1", d / "s2"}, d / "dup"); });
    CHECK(why.find("configuration 1 appears more than once") != std::string::npos);
    CHECK(oneLine(why));
    CHECK_FALSE(fs::exists(d / "dup"));
}

TEST_CASE("a shard validates its own configurations: a bad one elsewhere stops only the shard that holds it") {
    // Each array task of `hilite submit` repeated the whole experiment's validation (15 s for 10^6); submit
    // validates every configuration once before it submits.
    Dir d;
    std::ofstream(d / "e.toml") << "[scene.camera]\nsize = \"64\"\n[[sweep]]\nkey = \"light.incidence\"\n"
                                   "values = [0, 60, 100]\n";
    CHECK(refusal(d / "e.toml", d / "s1", "1/3").empty());
    CHECK(fs::exists(d / "s1/results.jsonl"));
    const std::string why = refusal(d / "e.toml", d / "s3", "3/3");
    CHECK(why.find("light.incidence: must be a finite number in [0, 90] (got 100)") != std::string::npos);
    CHECK_FALSE(fs::exists(d / "s3"));
    CHECK_FALSE(refusal(d / "e.toml", d / "all").empty());
    CHECK_FALSE(fs::exists(d / "all"));
}
