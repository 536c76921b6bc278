// experiments/results.hpp: the fingerprint a result row carries (every setting that reaches the row and the
// contents of every data file it reads, so --resume and merge refuse rows of an edited experiment or file), and
// the CSV fields of a row.

#include "experiments/experiment.hpp"
#include "experiments/plot.hpp"
#include "experiments/results.hpp"
#include "io/image_io.hpp"
#include "support/in_process.hpp"
#include "support/temp_dir.hpp"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace hilite;
using namespace hilite::testing;

namespace {

std::string firstFingerprint(const std::string& text) {
    const experiments::Experiment e = experiments::parseExperiment(text, "exp.toml");
    for (const experiments::Configuration& c : e.configurations()) return experiments::fingerprint(e, c);
    return "";
}

const char* kFit = R"([experiment]
name = "fp_fit"

[scene.material]
model = "ggx"
roughness = 0.1

[scene.light]
incidence = "0,60"

[fit]
)";

const char* kBounces = R"([experiment]
name = "fp_bounces"

[scene.material]
model = "beckmann"
roughness = 0.6

[scene.light]
incidence = "30"

[bounces]
)";

/// An NDF table (theta_h_deg, D): a Gaussian bump of width `w` degrees.
std::string ndfTable(double w) {
    std::string t = "theta_h_deg, D\n";
    for (int i = 0; i <= 90; ++i) t += std::to_string(i) + ", " + std::to_string(std::exp(-(i * i) / (w * w))) + "\n";
    return t;
}

/// Rewrites a file as an editor would, its modification time moved on by 2 s: a rewrite within the file system's
/// timestamp tick, at the same size, would look unchanged to the hash cache (a real edit moves the time).
void rewrite(const hilite_test::TempDir& dir, const std::string& name, const std::string& text) {
    const auto before = std::filesystem::last_write_time(dir.path / name);
    dir.write(name, text);
    std::filesystem::last_write_time(dir.path / name, before + std::chrono::seconds(2));
}

}  // namespace

TEST_CASE("fingerprint: every [fit] option is part of it") {
    const std::string base = firstFingerprint(kFit);
    REQUIRE(base.size() == 16);
    CHECK(firstFingerprint(kFit) == base);  // the same experiment: the same fingerprint
    for (const char* edit :
         {"models = [\"ggx\", \"beckmann\"]", "thresholds = [0.25, 0.5]", "weights = [1, 1, 1, 1, 2]",
          "anisotropy = true\nmodels = [\"ggx\"]", "f0 = false\nmodels = [\"ggx\"]", "geometry = \"smith\"",
          "fresnel = \"none\"", "diffuse = \"off\"", "rank_by = \"values\"", "color = true", "max_evaluations = 40"}) {
        CAPTURE(edit);
        CHECK(firstFingerprint(std::string(kFit) + edit + "\n") != base);
    }
}

TEST_CASE("[fit] max_evaluations is an integer, as documented") {
    const experiments::Experiment e =
        experiments::parseExperiment(std::string(kFit) + "max_evaluations = 10\n", "e.toml");
    REQUIRE(e.fit);
    CHECK(e.fit->maxEvaluations == 10);
    for (const char* bad : {"max_evaluations = 0", "max_evaluations = 10.5", "max_evaluations = [10]"}) {
        CAPTURE(bad);
        const std::string r =
            inputError([&] { experiments::parseExperiment(std::string(kFit) + bad + "\n", "e.toml"); });
        CHECK(r.find("max_evaluations: a whole number in [1, 10000]") != std::string::npos);
    }
}

TEST_CASE("fingerprint: every [bounces] setting is part of it") {
    const std::string base = firstFingerprint(kBounces);
    REQUIRE(base.size() == 16);
    for (const char* edit :
         {"paths = 4000", "batches = 8", "seed = 2", "surface = \"bilinear\"", "texels = 512", "bumps_per_tile = 32"}) {
        CAPTURE(edit);
        CHECK(firstFingerprint(std::string(kBounces) + edit + "\n") != base);
    }
}

TEST_CASE("fingerprint: a data file's contents are part of it, not how the run names the file") {
    const hilite_test::TempDir dir("hilite-fingerprint");
    const std::string table = dir.write("ndf.csv", ndfTable(10.0));
    auto experiment = [&](const std::string& path) {
        return std::string(
                   "[experiment]\nname = \"fp_file\"\n[scene.material]\nmodel = \"tabulated\"\nndf_table = \"") +
               path + "\"\n[scene.light]\nincidence = \"30\"\n";
    };
    const std::string before = firstFingerprint(experiment(table));
    CHECK(firstFingerprint(experiment(dir.path.string() + "/./ndf.csv")) == before);
    rewrite(dir, "ndf.csv", ndfTable(12.0));  // the same path, other contents
    CHECK(firstFingerprint(experiment(table)) != before);
}

TEST_CASE("fingerprint: --resume after a data file changed is refused, naming the row") {
    const hilite_test::TempDir dir("hilite-fingerprint-resume");
    const std::string table = dir.write("ndf.csv", ndfTable(10.0));
    const std::string exp = dir.write("e.toml", std::string("[experiment]\nname = \"fp_resume\"\n[scene.material]\n"
                                                            "model = \"tabulated\"\nndf_table = \"ndf.csv\"\n"
                                                            "[scene.camera]\nsize = \"64\"\n[[sweep]]\n"
                                                            "key = \"light.incidence\"\nvalues = [0, 30]\n"));
    const std::string out = dir / "out";
    runExperiment(exp, out);
    CHECK(runExperiment(exp, out, true).measured == 0);  // unchanged: nothing left to measure
    rewrite(dir, "ndf.csv", ndfTable(12.0));
    const std::string refusal = inputError([&] { runExperiment(exp, out, true); });
    CHECK(refusal.find("results.jsonl:1: row 1 (configuration 0)") != std::string::npos);
    CHECK(refusal.find("run without --resume") != std::string::npos);
}

TEST_CASE("results.csv: a field with a comma, a quote or a line break is quoted (RFC 4180), lists too") {
    using experiments::csvField;
    CHECK(csvField(nlohmann::json::array({"horizon_cut", "non_finite:aspect,peak"})) ==
          "\"horizon_cut;non_finite:aspect,peak\"");
    CHECK(csvField(nlohmann::json::array({"horizon_cut", "clipped"})) == "horizon_cut;clipped");
    CHECK(csvField("say \"hi\"") == "\"say \"\"hi\"\"\"");
    CHECK(csvField("a\rb") == "\"a\rb\"");
    CHECK(csvField(0.5) == "0.5");
    CHECK(csvField(nullptr) == "");
}

TEST_CASE("results: group commit makes rows durable together (an fsync per 100 ms, every row written at once)") {
    // Before: an fsync per row (2-9 ms a row on a busy ext4 disk, beside a 1.5 ms measurement).
    const hilite_test::TempDir dir("hilite-group-commit");
    const experiments::Experiment e = experiments::parseExperiment(kFit, "exp.toml");
    const experiments::Configurations configs = e.configurations();
    const std::vector<std::string> columns{"config", "aspect"};
    auto write = [&](const std::string& sub, double interval) {
        const std::string folder = dir / sub;
        std::filesystem::create_directories(folder);
        experiments::ResultsWriter w(folder, columns, false, e, configs, interval);
        for (int i = 0; i < 200; ++i) {
            w.append({{"config", i}, {"aspect", 0.5}});
            // Every appended row is in the file at once (a SIGKILL now loses none), synced or not.
            if (i == 100) CHECK(experiments::readRows(folder + "/results.jsonl").size() == 101);
        }
        const size_t beforeFinish = w.syncs();
        w.finish();
        CHECK(w.syncs() == beforeFinish + 1);
        CHECK(experiments::readRows(folder + "/results.jsonl").size() == 200);
        return beforeFinish;
    };
    // An interval no run of 200 rows reaches: no fsync until finish(); an interval of 0: one per row. (The default
    // interval, 100 ms, is a time: the tests assert none.)
    CHECK(write("grouped", 3600.0) == 0);
    CHECK(write("each", 0.0) == 200);
    CHECK(experiments::ResultsWriter::kGroupCommitSeconds == 0.1);
}

TEST_CASE("run --check refuses what the run would: a folder another run holds, rows --resume would not keep") {
    const hilite_test::TempDir dir("hilite-check-lock");
    const std::string table = dir.write("ndf.csv", ndfTable(10.0));
    const std::string exp = dir.write("e.toml", std::string("[experiment]\nname = \"fp_check\"\n[scene.material]\n"
                                                            "model = \"tabulated\"\nndf_table = \"ndf.csv\"\n"
                                                            "[scene.camera]\nsize = \"64\"\n[[sweep]]\n"
                                                            "key = \"light.incidence\"\nvalues = [0, 30]\n"));
    const std::string out = dir / "out";
    runExperiment(exp, out);
    CHECK(runRefusal(exp, out, true) == "");  // --check of a finished folder: valid
    {
        const io::FolderLock held(out, "-o");  // as a run in progress holds it
        const std::string r = runRefusal(exp, out, true);
        CHECK(r.find("is being written by another hilite run or merge") != std::string::npos);
    }
    CHECK(runRefusal(exp, out, true) == "");
    rewrite(dir, "ndf.csv", ndfTable(12.0));
    experiments::RunOptions o;
    o.experiment = exp, o.out = out, o.resume = true, o.check = true;
    const std::string r = inputError([&] { experiments::runExperiment(o); });
    CHECK(r.find("results.jsonl:1: row 1 (configuration 0)") != std::string::npos);
}

TEST_CASE("run: a data file that turns bad after validation stops the run, keeps the rows and names --resume") {
    const hilite_test::TempDir dir("hilite-turns-bad");
    std::filesystem::create_directories(dir.path / "tables");
    const std::string a = dir.write("tables/a.csv", ndfTable(10.0));
    const std::string b = dir.write("tables/b.csv", ndfTable(12.0));
    const std::string exp = dir.write("e.toml",
                                      "[experiment]\nname = \"turns_bad\"\n[scene.material]\nmodel = \"tabulated\"\n"
                                      "[scene.light]\nincidence = \"30\"\n[scene.camera]\nsize = \"64\"\n[[sweep]]\n"
                                      "key = \"material.ndf_table\"\nvalues = [\"tables/a.csv\", \"tables/b.csv\"]\n");
    experiments::RunOptions o;
    o.experiment = exp, o.out = dir / "out";
    o.progress = [&](size_t done, size_t, double) {
        if (done == 1) dir.write("tables/b.csv", "theta_h_deg, D\n0, x\n");  // after every file was validated
    };
    const std::string r = inputError([&] { experiments::runExperiment(o); });
    CAPTURE(r);
    CHECK(r.find("b.csv") != std::string::npos);
    CHECK(r.find("; 1 row kept in " + o.out + ": fix it and rerun with --resume)") != std::string::npos);
    CHECK(experiments::readRows(o.out + "/results.jsonl").size() == 1);
    (void)a, (void)b;
}

TEST_CASE("a plot draws flagged rows as a separate, labelled series off the lines") {
    // Before, a row flagged horizon_cut sat on its series' line: a zig-zag of horizon strips read as data.
    hilite_test::TempDir dir("hilite-plot-flags");
    std::vector<nlohmann::json> rows;
    for (int i = 0; i < 5; ++i) {
        nlohmann::json r;
        r["incidence_deg"] = 20 * i;
        r["aspect"] = 1.0 - 0.1 * i;
        r["roughness"] = 0.1;
        r["flags"] = i == 2 || i == 3 ? nlohmann::json::array({"horizon_cut"}) : nlohmann::json::array();
        rows.push_back(r);
    }
    experiments::PlotSpec spec;
    spec.file = "aspect.png", spec.title = "t", spec.x = "incidence_deg", spec.y = "aspect", spec.series = "roughness";
    std::string why;
    experiments::plot(dir.path.string(), spec, rows,
                      why);  // the data and the script are written with or without gnuplot
    std::ifstream datIn(std::string(dir / "aspect.dat")), gpIn(std::string(dir / "aspect.gp"));
    const std::string dat((std::istreambuf_iterator<char>(datIn)), std::istreambuf_iterator<char>());
    const std::string gp((std::istreambuf_iterator<char>(gpIn)), std::istreambuf_iterator<char>());
    INFO(dat);
    INFO(gp);
    const auto flaggedAt = dat.find("# flagged (2): horizon_cut\n");
    REQUIRE(flaggedAt != std::string::npos);
    const std::string series = dat.substr(0, flaggedAt), flagged = dat.substr(flaggedAt);
    // Two flagged rows in a row leave one blank line (two would end gnuplot's data block), then the line goes on.
    CHECK(dat.find("0 1.0\n20 0.9\n\n80 0.6\n\n\n# flagged") != std::string::npos);
    CHECK(series.find("40 0.8") == std::string::npos);  // off the line
    CHECK(flagged.find("40 0.8\n60 0.7") != std::string::npos);
    CHECK(gp.find("index 1 using 1:2 with points pt 6") != std::string::npos);
    CHECK(gp.find("title 'flagged (2): horizon_cut'") != std::string::npos);
}

TEST_CASE("a plot says which lines lie on others") {
    // Before, Blinn-Phong's and Beckmann's fitted aspects hid each other and the legend did not say so.
    hilite_test::TempDir dir("hilite-plot-coincide");
    std::vector<nlohmann::json> rows;
    for (int i = 0; i < 5; ++i)
        for (const char* m : {"phong", "blinn", "beckmann"}) {
            nlohmann::json r;
            r["incidence_deg"] = 20 * i;
            r["model"] = m;
            // phong stays at 1; blinn and beckmann 1e-4 apart on a plot 0.4 high: one line
            r["aspect"] = std::string(m) == "phong" ? 1.0 : 1.0 - 0.1 * i + (std::string(m) == "blinn" ? 1e-4 : 0.0);
            rows.push_back(r);
        }
    experiments::PlotSpec spec;
    spec.file = "aspect.png", spec.title = "t", spec.x = "incidence_deg", spec.y = "aspect", spec.series = "model";
    std::string why;
    experiments::plot(dir.path.string(), spec, rows, why);
    std::ifstream gpIn(std::string(dir / "aspect.gp"));
    const std::string gp((std::istreambuf_iterator<char>(gpIn)), std::istreambuf_iterator<char>());
    INFO(gp);
    CHECK(gp.find("title 'beckmann (on blinn)'") != std::string::npos);
    CHECK(gp.find("title 'blinn'") != std::string::npos);
    CHECK(gp.find("title 'phong'") != std::string::npos);  // apart from both
}
