// hilite run / merge end to end on a small experiment: rows, fields, resume and shards. Refused experiment files
// and the shipped experiments' validation, in-process: tests/experiments/test_run_checks.cpp.

#include "support/run_hilite.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "support/near.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

int sh(const std::string& cmd) {
    const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const std::string kExperiment = R"([experiment]
name = "small"
[scene.camera]
size = "96"
[[sweep]]
key = "material.model"
values = ["phong", "ggx"]
[[sweep]]
key = "light.incidence"
values = [0, 30, 60, 75]
[match]
material.model = "ggx"
material.roughness = 0.1
)";

struct Csv {
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
};

Csv readCsv(const std::string& path) {
    Csv csv;
    std::ifstream in(path);
    std::string line;
    auto split = [](const std::string& l) {
        std::vector<std::string> out;
        std::stringstream ss(l);
        for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
        if (!l.empty() && l.back() == ',') out.push_back("");
        return out;
    };
    std::getline(in, line);
    csv.header = split(line);
    while (std::getline(in, line)) {
        const auto f = split(line);
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < csv.header.size() && i < f.size(); ++i) row[csv.header[i]] = f[i];
        csv.rows.push_back(row);
    }
    return csv;
}

/// Rows without the timing columns, which differ between any two runs.
std::vector<std::map<std::string, std::string>> comparable(Csv csv) {
    for (auto& r : csv.rows) r.erase("render_ms"), r.erase("measure_ms");
    return csv.rows;
}

/// A scratch directory holding the small experiment as small.toml.
struct Dir : hilite_test::TempDir {
    Dir() : TempDir("hilite-run") { write("small.toml", kExperiment); }
};

}  // namespace

TEST_CASE("cli::run a small experiment writes the expected rows") {
    Dir d;
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " -o " + (d / "out")) == 0);
    const Csv csv = readCsv(d / "out/results.csv");
    REQUIRE(csv.rows.size() == 8);
    for (const char* field : {"config", "model", "incidence_deg", "aspect", "eccentricity", "major_deg", "minor_deg",
                              "flags", "render_ms", "measure_ms", "roughness", "exponent", "threshold"})
        CHECK(std::find(csv.header.begin(), csv.header.end(), field) != csv.header.end());
    double previous = -1;
    for (const auto& r : csv.rows) {
        const double aspect = std::stod(r.at("aspect")), ecc = std::stod(r.at("eccentricity"));
        if (r.at("model") == "phong") CHECK_NEAR(aspect, 1.0, 0.005);
        if (r.at("model") == "ggx") {
            CHECK(ecc > previous);
            previous = ecc;
        }
    }
    CHECK(fs::exists(d / "out/summary.md"));
    CHECK(fs::exists(d / "out/results.jsonl"));
}

TEST_CASE("cli::run killed part-way and resumed writes the same rows as an uninterrupted run") {
    Dir d;
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " -o " + (d / "full")) == 0);
    // Simulate a kill after 3 rows, the 4th torn mid-line.
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " -o " + (d / "cut")) == 0);
    for (const char* f : {"results.jsonl", "results.csv"}) {
        std::ifstream in(d / (std::string("cut/") + f));
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        size_t pos = 0;
        const int keep = std::string(f) == "results.csv" ? 4 : 3;  // the CSV has a header line
        for (int i = 0; i < keep; ++i) pos = text.find('\n', pos) + 1;
        std::ofstream(d / (std::string("cut/") + f), std::ios::trunc) << text.substr(0, pos + 20);
    }
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " -o " + (d / "cut") + " --resume") == 0);
    CHECK(comparable(readCsv(d / "cut/results.csv")) == comparable(readCsv(d / "full/results.csv")));
}

TEST_CASE("cli::run a real SIGKILL part-way, then --resume, gives the uninterrupted rows") {
    Dir d;
    std::ofstream(d / "long.toml")
        << std::string(kExperiment).replace(kExperiment.find("size = \"96\""), 11, "size = \"768\"")
        << "[[sweep]]\nkey = \"measurement.threshold\"\nvalues = [0.3, 0.5, 0.7]\n";
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "long.toml") + " -o " + (d / "full")) == 0);
    const pid_t pid = fork();
    if (pid == 0) {
        execl(HILITE_EXE, HILITE_EXE, "run", (d / "long.toml").c_str(), "-o", (d / "cut").c_str(), nullptr);
        _exit(127);
    }
    // Kill it as soon as a few rows are on disk (or let it finish if it is faster than we are).
    for (int i = 0; i < 2000; ++i) {
        std::ifstream in(d / "cut/results.jsonl");
        const auto rows = std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n');
        if (rows >= 3) break;
        usleep(1000);
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    std::ifstream partial(d / "cut/results.jsonl");
    const auto rowsAtKill = std::count(std::istreambuf_iterator<char>(partial), std::istreambuf_iterator<char>(), '\n');
    MESSAGE("rows on disk when killed: " << rowsAtKill << " of 24");
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "long.toml") + " -o " + (d / "cut") + " --resume") == 0);
    CHECK(comparable(readCsv(d / "cut/results.csv")) == comparable(readCsv(d / "full/results.csv")));
}

namespace {
/// What `cmd` prints (stdout and stderr) on a pseudo-terminal (`script`), or into a pipe.
std::string printed(const std::string& cmd, bool terminal) {
    FILE* p = popen((terminal ? "script -qec '" + cmd + "' /dev/null 2>&1" : cmd + " 2>&1").c_str(), "r");
    std::string out;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    pclose(p);
    return out;
}
}  // namespace

TEST_CASE("cli::run shows a progress line on a terminal only") {
    Dir d;
    const std::string cmd = std::string(HILITE_EXE) + " run " + (d / "small.toml") + " -o " + (d / "tty");
    const std::string out = printed(cmd, true);
    CHECK(out.find("ETA") != std::string::npos);
    CHECK(out.find("[8/8]") != std::string::npos);
    CHECK(printed(cmd, false).find("ETA") == std::string::npos);
}

TEST_CASE("cli::brdf bounces shows its progress on a terminal only: the field, then each incidence's batches") {
    const std::string cmd = std::string(HILITE_EXE) +
                            " brdf bounces --incidence 30 --paths 2000 --batches 4 --texels 128 --bumps-per-tile 8";
    const std::string out = printed(cmd, true);
    CHECK(out.find("field 128^2 [1/1]") != std::string::npos);
    CHECK(out.find("theta 30: traced [4/4]") != std::string::npos);
    CHECK(out.find("theta 30: Smith walk [4/4]") != std::string::npos);
    CHECK(out.find("theta_i = 30 deg") != std::string::npos);
    const std::string piped = printed(cmd, false);
    CHECK(piped.find("ETA") == std::string::npos);
    CHECK(piped.find("theta_i = 30 deg") != std::string::npos);
}

TEST_CASE("cli::merge shards equal a single run, row for row and in summary.md, and so does a resume") {
    Dir d;
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " -o " + (d / "single")) == 0);
    for (int k = 1; k <= 3; ++k)
        REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " --shard " + std::to_string(k) + "/3 -o " +
                   (d / ("s" + std::to_string(k)))) == 0);
    REQUIRE(sh(std::string(HILITE_EXE) + " merge " + (d / "s1") + " " + (d / "s2") + " " + (d / "s3") + " -o " +
               (d / "merged")) == 0);
    CHECK(comparable(readCsv(d / "merged/results.csv")) == comparable(readCsv(d / "single/results.csv")));
    // summary.md too, apart from its timing line: the merge (and a resume of the finished folder) dropped the
    // matched widths of the models it did not match itself, and said "measured in 0.01 s".
    auto summary = [](const std::string& path) {
        std::ifstream in(path);
        std::string text, line;
        bool skipBlank = false;
        while (std::getline(in, line)) {
            if (line.rfind("Time: ", 0) == 0 || (skipBlank && line.empty())) {
                skipBlank = !skipBlank && line.rfind("Time: ", 0) == 0;
                continue;
            }
            skipBlank = false;
            text += line + "\n";
        }
        return text;
    };
    const std::string single = summary(d / "single/summary.md");
    CHECK(single.find("| phong | ") != std::string::npos);  // the matched widths are there to compare
    CHECK(summary(d / "merged/summary.md") == single);
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "small.toml") + " --resume -o " + (d / "single")) == 0);
    CHECK(summary(d / "single/summary.md") == single);
}

TEST_CASE("cli::run --check refuses what a run refuses and writes nothing") {
    Dir d;
    std::ofstream(d / "bad.toml")
        << "[experiment]\nname = \"bad\"\n[[sweep]]\nkey = \"material.roughness\"\nvalues = [0.1, -1]\n";
    using hilite_test::hilite;
    const hilite_test::Result r = hilite("run " + (d / "bad.toml") + " --check -o " + (d / "out"));
    CHECK(r.code == 2);
    CHECK(hilite_test::lines(r.out) == 1);
    CHECK(r.out.find("material.roughness") != std::string::npos);
    CHECK(!fs::exists(d / "out"));
    const hilite_test::Result ok = hilite("run eccentricity --check -o " + (d / "ecc"));
    CHECK(ok.code == 0);
    CHECK(ok.out.find("eccentricity: 360 configurations, every one valid") != std::string::npos);
    CHECK(!fs::exists(d / "ecc"));
}

TEST_CASE("cli::measure --csv gives the columns and values of an experiment's results.csv") {
    Dir d;
    d.write("two.toml",
            "[experiment]\nname = \"two\"\n[scene.material]\nmodel = \"ggx\"\nroughness = 0.1\n"
            "[scene.camera]\nsize = \"96\"\n[[sweep]]\nkey = \"light.incidence\"\nvalues = [30, 60]\n");
    REQUIRE(sh(std::string(HILITE_EXE) + " run " + (d / "two.toml") + " -o " + (d / "run")) == 0);
    const std::string args = " measure --model ggx --roughness 0.1 --size 96 --incidence 30,60";
    REQUIRE(sh("sh -c '" + std::string(HILITE_EXE) + args + " --csv - > " + (d / "stdout.csv") + "'") == 0);
    REQUIRE(sh(std::string(HILITE_EXE) + args + " --csv " + (d / "file.csv")) == 0);
    const Csv run = readCsv(d / "run/results.csv"), out = readCsv(d / "stdout.csv"), file = readCsv(d / "file.csv");
    CHECK(out.header == file.header);
    CHECK(comparable(out) == comparable(file));
    REQUIRE(out.rows.size() == 2);
    REQUIRE(run.rows.size() == 2);
    // Every column of the run's CSV but `config` is measure's, in the same order, with the same values.
    std::vector<std::string> runColumns(run.header.begin() + 1, run.header.end());
    CHECK(runColumns == out.header);
    const auto a = comparable(out), b = comparable(run);
    for (size_t i = 0; i < 2; ++i)
        for (const auto& kv : a[i]) {
            const std::string column = kv.first;  // a structured binding cannot be captured in C++17 (clang)
            CAPTURE(column);
            CHECK(b[i].at(column) == kv.second);
        }
    // Refused before anything is measured: --csv - with --json, a folder as the file.
    using hilite_test::hilite;
    CHECK(hilite("measure --csv - --json").code == 2);
    const hilite_test::Result dir = hilite("measure --csv " + std::string(d / ""));
    CHECK(dir.code == 2);
    CHECK(dir.out.find("--csv") != std::string::npos);
}

TEST_CASE("cli::every subcommand's --help shows an example") {
    using hilite_test::hilite;
    for (const char* sub :
         {"render", "measure", "explain", "fit", "run", "merge", "brdf", "brdf albedo", "brdf fresnel",
          "brdf normalization", "brdf strip", "brdf tabulate", "brdf bounces", "brdf slice", "brdf inspect", "serve"}) {
        CAPTURE(sub);
        const hilite_test::Result r = hilite(std::string(sub) + " --help");
        CHECK(r.code == 0);
        CHECK(r.out.find("Example") != std::string::npos);
    }
}

TEST_CASE("cli::--help has one option style (TYPE, then the default in words) wrapped to $COLUMNS") {
    // Before: "--paths INT=100000" beside the registry's "--roughness NUM ... (default 0.1)", lines of 300-500
    // characters. An example's command line stays whole (to be copied); every other line fits the width.
    using hilite_test::hilite;
    const std::regex typeDefault("(INT|UINT|FLOAT|NUM|TEXT)=");
    for (const std::string columns : {"72", "120"}) {
        ::setenv("COLUMNS", columns.c_str(), 1);
        const size_t width = std::stoul(columns);
        for (const std::string sub : {"", "render", "measure", "explain", "fit", "run", "merge", "brdf", "brdf albedo",
                                      "brdf fresnel", "brdf normalization", "brdf strip", "brdf tabulate",
                                      "brdf bounces", "brdf slice", "brdf inspect", "serve"}) {
            CAPTURE(columns);
            CAPTURE(sub);
            const hilite_test::Result r = hilite(sub + " --help", true);
            CHECK(r.code == 0);
            std::istringstream lines(r.out);
            for (std::string line; std::getline(lines, line);) {
                CAPTURE(line);
                if (line.find("hilite ") == std::string::npos) CHECK(line.size() <= width);
                // CLI11's "TYPE=DEFAULT" and validator suffixes are gone from the option column.
                CHECK_FALSE(std::regex_search(line, typeDefault));
                CHECK(line.find(":NONEMPTY") == std::string::npos);
            }
        }
    }
    ::unsetenv("COLUMNS");
    const hilite_test::Result bounces = hilite("brdf bounces --help", true);
    CHECK(bounces.out.find("--paths INT") != std::string::npos);
    CHECK(bounces.out.find("(default 100000)") != std::string::npos);
}

namespace {

/// Stand-ins for Slurm's sbatch, squeue and scancel (tests/cli/fake_slurm/): sbatch runs a job at once (an array's
/// tasks in turn, output to --output/--error with %a), holds a job whose afterok dependency failed as pending (as
/// Slurm does), and skips the task $FAKE_SLURM_CANCEL as if scancel'd before it ran, with Slurm's log line.
struct FakeSlurm : Dir {
    FakeSlurm() {
        const std::string bin = HILITE_SOURCE_DIR_STR "/tests/cli/fake_slurm";
        path = "PATH=" + bin + ":$PATH FAKE_SLURM_STATE=" + (*this / "state") + " ";
    }
    std::string path;  ///< the environment prefix of a command line
};

}  // namespace

TEST_CASE(
    "cli::submit runs an experiment as an array job and a merge job: rows equal a single run, resume after a "
    "cancelled task") {
    FakeSlurm d;
    const std::string exe = HILITE_EXE;
    REQUIRE(sh(exe + " run " + (d / "small.toml") + " -o " + (d / "single")) == 0);
    // A task cancelled: --wait reports it, cancels the merge (its afterok can never be met) and exits 1.
    const std::string submit = d.path + "FAKE_SLURM_CANCEL=2 " + exe + " submit " + (d / "small.toml") +
                               " --shards 3 -o " + (d / "cluster") + " --wait --sbatch=--time=5";
    const hilite_test::Result r = hilite_test::command(submit);
    CAPTURE(r.out);
    CHECK(r.code == 1);
    CHECK(r.out.find("small: 8 configurations in 3 shards; array job") != std::string::npos);
    CHECK(r.out.find("CANCELLED") != std::string::npos);  // shard 2's log line, in the status table
    CHECK(r.out.find("the merge was cancelled") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(d / "cluster/results.csv"));
    // status says the same from the folder alone.
    const hilite_test::Result st = hilite_test::hilite("status " + (d / "cluster"), true);
    CHECK(st.code == 0);
    CHECK(st.out.find("small: 5 of 8 rows in 3 shards") != std::string::npos);
    // --resume resubmits shard 2 alone, then the merge: the single run's rows.
    REQUIRE(sh(d.path + exe + " submit --resume -o " + (d / "cluster") + " --wait") == 0);
    std::ifstream calls(d / "state/calls");
    const std::string log((std::istreambuf_iterator<char>(calls)), std::istreambuf_iterator<char>());
    CAPTURE(log);
    CHECK(log.find("--array=1-3") != std::string::npos);
    CHECK(log.find("--array=2 ") != std::string::npos);
    CHECK(log.find("--time=5") != std::string::npos);  // --sbatch passed to every call
    CHECK(comparable(readCsv(d / "cluster/results.csv")) == comparable(readCsv(d / "single/results.csv")));
    const hilite_test::Result done = hilite_test::hilite("status " + (d / "cluster"), true);
    CHECK(done.out.find("small: 8 of 8 rows in 3 shards (100%); merge: done, 8 rows") != std::string::npos);
}

TEST_CASE("cli::submit --resume after a task cancelled past its shard's last row: the stuck merge is submitted anew") {
    // Slurm keeps the merge pending for ever behind a cancelled task even when every shard is complete (the real
    // single-node test met it when the scancel came after the shard's last row); --resume refused it as running.
    // Slurm names the reason DependencyNeverSatisfied only at its next scheduling pass; before it (LATE) the merge
    // waits on "Dependency" and the array's ended tasks say it never runs (CI met that window once rows got fast).
    for (const std::string late : {"", "FAKE_SLURM_LATE=1 "}) {
        CAPTURE(late);
        FakeSlurm d;
        const std::string exe = HILITE_EXE;
        REQUIRE(sh(exe + " run " + (d / "small.toml") + " -o " + (d / "single")) == 0);
        REQUIRE(sh(d.path + "FAKE_SLURM_CANCEL=2 " + exe + " submit " + (d / "small.toml") + " --shards 3 -o " +
                   (d / "cluster")) == 0);
        REQUIRE(sh(exe + " run " + (d / "small.toml") + " --shard 2/3 --resume -o " + (d / "cluster/shards/2")) == 0);
        REQUIRE(sh(d.path + late + exe + " submit --resume -o " + (d / "cluster") + " --wait") == 0);
        CHECK(comparable(readCsv(d / "cluster/results.csv")) == comparable(readCsv(d / "single/results.csv")));
    }
}

TEST_CASE("cli::submit --resume refuses while every task completed and the merge only waits for Slurm's pass") {
    FakeSlurm d;
    const std::string exe = HILITE_EXE;
    REQUIRE(sh(d.path + "FAKE_SLURM_HOLD=1 " + exe + " submit " + (d / "small.toml") + " --shards 3 -o " +
               (d / "cluster")) == 0);
    const std::string merge = nlohmann::json::parse(std::ifstream(d / "cluster/slurm/submit.json"))["merge_job"];
    REQUIRE(std::filesystem::exists(d / ("state/" + merge + ".pending")));
    const hilite_test::Result r = hilite_test::command(d.path + exe + " submit --resume -o " + (d / "cluster"));
    CAPTURE(r.out);
    CHECK(r.code == 2);
    CHECK(r.out.find("is queued or running and every shard is complete: wait for it") != std::string::npos);
    CHECK(std::filesystem::exists(d / ("state/" + merge + ".pending")));  // the merge left as it is
}

TEST_CASE("cli::submit refuses bad input in one line, exit 2, nothing written, and --dry-run writes the scripts only") {
    FakeSlurm d;
    const std::string exe = HILITE_EXE;
    struct Case {
        std::string args, message;
    };
    const Case bad[] = {
        {" --shards 0 -o " + (d / "a"), "--shards: expected 1 to 8"},
        {" --shards 9 -o " + (d / "a"), "--shards: expected 1 to 8"},
        {" --shards 2 -o " + (d / "a") + " --engine pbs", "--engine: unknown 'pbs'"},
        {" --shards 2 -o " + (d / "a%j"), "which Slurm reads as a file-name pattern"},
    };
    for (const Case& c : bad) {
        CAPTURE(c.args);
        const hilite_test::Result r = hilite_test::hilite("submit " + (d / "small.toml") + c.args);
        CHECK(r.code == 2);
        CHECK(hilite_test::lines(r.out) == 1);
        CHECK(r.out.find(c.message) != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(d / "a"));
    }
    // No sbatch on PATH: refused unless --dry-run.
    std::filesystem::create_directories(d / "empty");
    const std::string noSlurm =
        "PATH=" + (d / "empty") + " " + exe + " submit " + (d / "small.toml") + " --shards 2 -o " + (d / "a");
    CHECK(sh(noSlurm) == 2);
    CHECK_FALSE(std::filesystem::exists(d / "a"));
    REQUIRE(sh(noSlurm + " --dry-run") == 0);
    CHECK(std::filesystem::exists(d / "a/slurm/array.sbatch"));
    CHECK(std::filesystem::exists(d / "a/slurm/merge.sbatch"));
    CHECK_FALSE(std::filesystem::exists(d / "state/calls"));  // nothing submitted
    // A folder already submitted is refused without --resume.
    const hilite_test::Result again =
        hilite_test::hilite("submit " + (d / "small.toml") + " --shards 2 -o " + (d / "a") + " --dry-run");
    CHECK(again.code == 2);
    CHECK(again.out.find("already holds a submitted run") != std::string::npos);
    // A file name is data in the scripts, never shell code.
    d.write("it's $(touch pwned).toml", kExperiment);
    const std::string quoted = "'" + (d / "it'\\''s $(touch pwned).toml") + "'";  // one word for the test's shell
    REQUIRE(sh(d.path + exe + " submit " + quoted + " --shards 2 -o " + (d / "q") + " --wait") == 0);
    CHECK_FALSE(std::filesystem::exists(d / "q/slurm/pwned"));
    CHECK_FALSE(std::filesystem::exists("pwned"));
    CHECK(comparable(readCsv(d / "q/results.csv")).size() == 8);
}
