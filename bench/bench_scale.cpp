// Costs of running experiments at scale (docs/scaling.md; bench/scaling.py runs these and writes the page):
//   --benchmark_filter=RunRows       rows of a sweep through runExperiment (written, group commit or an fsync
//                                    per row) against the same configurations measured in process, not written
//   --benchmark_filter=ClientAppend  rows a Dask client checks and appends (DistributedRun::append), alone
//   --benchmark_filter=Merge         `hilite merge` of S shards x R rows (generated, fingerprints real): wall time
//                                    and the merge process's peak resident memory (counter peak_MB: its VmHWM,
//                                    read every 20 ms until it exits)
// Wall-clock times (UseRealTime): llvmpipe renders on its own threads.

#include "experiments/experiment.hpp"
#include "experiments/results.hpp"
#include "hilite/experiments/run.hpp"

#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

using namespace hilite;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
    const char* t = std::getenv("TMPDIR");
    fs::path p = fs::path(t && *t ? t : "/tmp") / ("hilite-bench-scale-" + std::to_string(getuid()));
    fs::create_directories(p);
    return p;
}

/// A sweep of `n` configurations (models x incidences) at the default 512^2 frame.
std::string sweepFile(int n) {
    const fs::path f = scratch() / ("sweep" + std::to_string(n) + ".toml");
    std::ofstream out(f);
    out << "[experiment]\nname = \"bench_rows\"\n[[sweep]]\nkey = \"material.model\"\nvalues = [\"ggx\", "
           "\"beckmann\", \"blinn\", \"phong\"]\n[[sweep]]\nkey = \"light.incidence\"\nrange = [0, "
        << 85.0 * (n / 4 - 1) / (n / 4) << ", " << 85.0 / (n / 4) << "]\n";
    return f.string();
}

// ---- Rows written: group commit, an fsync per row, against measuring alone ----

void BM_RunRows(benchmark::State& state) {
    const int n = int(state.range(0));
    const int mode = int(state.range(1));  // 0: measured only, 1: run (group commit), 2: run --fsync-each-row
    const std::string file = sweepFile(n);
    for (auto _ : state) {
        if (mode == 0) {
            const experiments::Experiment e = experiments::loadExperiment(file);
            const auto configs = e.configurations();
            experiments::ExperimentRunner runner(e, "");
            for (size_t i = 0; i < configs.size(); ++i) benchmark::DoNotOptimize(runner.measure(configs[i]));
        } else {
            experiments::RunOptions o;
            o.experiment = file;
            o.out = (scratch() / "rows-out").string();
            fs::remove_all(o.out);
            o.fsyncEachRow = mode == 2;
            benchmark::DoNotOptimize(experiments::runExperiment(o));  // no plots: summary.md only
        }
    }
    state.counters["rows/s"] = benchmark::Counter(double(n) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RunRows)->ArgsProduct({{400}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// ---- Merge of S shards x R rows ----

/// S shard folders of R rows each of a sweep of S x R configurations, as `hilite run --shard K/S` writes them:
/// one measured row copied, with each configuration's own index, fingerprint and swept values. Kept in the
/// scratch folder (made once: 10^6 fingerprints take a while).
fs::path shards(int s, int r) {
    const fs::path dir = scratch() / ("merge-" + std::to_string(s) + "x" + std::to_string(r));
    if (fs::exists(dir / "done")) return dir;
    fs::remove_all(dir);
    const long total = long(s) * r;
    const int side = 1000;
    std::ostringstream text;
    text << "[experiment]\nname = \"bench_merge\"\n[[sweep]]\nkey = \"material.roughness\"\nvalues = [";
    const long outer = (total + side - 1) / side;
    for (long i = 0; i < outer; ++i) text << (i ? ", " : "") << 0.01 + 0.4 * double(i) / double(outer);
    text << "]\n[[sweep]]\nkey = \"light.incidence\"\nvalues = [";
    for (int i = 0; i < side; ++i) text << (i ? ", " : "") << 80.0 * i / side;
    text << "]\n";
    fs::create_directories(dir);
    std::ofstream(dir / "merge.toml") << text.str();
    const experiments::Experiment e = experiments::loadExperiment((dir / "merge.toml").string());
    const auto configs = e.configurations();
    nlohmann::json row;
    {
        experiments::ExperimentRunner runner(e, "");
        row = runner.measure(configs[0]);
    }
    std::vector<std::ofstream> out;
    for (int k = 1; k <= s; ++k) {
        const fs::path sd = dir / ("shard" + std::to_string(k));
        fs::create_directories(sd);
        experiments::writeExperimentCopy(e, sd.string());
        out.emplace_back(sd / "results.jsonl");
    }
    for (long i = 0; i < s * long(r); ++i) {
        const experiments::Configuration c = configs[size_t(i)];
        row["config"] = i;
        row["fingerprint"] = experiments::fingerprint(e, c);
        row["roughness"] = std::stod(c.values.text("roughness"));
        row["incidence_deg"] = std::stod(c.values.text("incidence"));
        out[size_t(i % s)] << row.dump() << "\n";
    }
    for (auto& o : out) o.close();
    std::ofstream(dir / "done") << "ok\n";
    return dir;
}

fs::path hiliteExe() { return fs::read_symlink("/proc/self/exe").parent_path() / "hilite"; }

void BM_Merge(benchmark::State& state) {
    const int s = int(state.range(0)), r = int(state.range(1));
    const fs::path dir = shards(s, r);
    double peakMb = 0;
    for (auto _ : state) {
        fs::remove_all(dir / "merged");
        std::vector<std::string> args = {hiliteExe().string(), "merge"};
        for (int k = 1; k <= s; ++k) args.push_back((dir / ("shard" + std::to_string(k))).string());
        args.insert(args.end(), {"-o", (dir / "merged").string()});
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        pid_t pid = 0;
        posix_spawn_file_actions_t quiet;  // its "merged N of N rows" line off the benchmark's output
        posix_spawn_file_actions_init(&quiet);
        posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
        const int spawned = posix_spawn(&pid, argv[0], &quiet, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&quiet);
        if (spawned != 0) {
            state.SkipWithError("cannot start hilite merge");
            return;
        }
        // The merge's own peak: VmHWM of its address space, read until it exits (ru_maxrss would count this
        // process's memory too: Linux keeps the larger across posix_spawn's exec).
        int status = 0;
        for (;;) {
            std::ifstream proc("/proc/" + std::to_string(pid) + "/status");
            for (std::string line; std::getline(proc, line);)
                if (line.rfind("VmHWM:", 0) == 0) peakMb = std::max(peakMb, std::stod(line.substr(6)) / 1024.0);
            if (waitpid(pid, &status, WNOHANG) == pid) break;
            usleep(20000);
        }
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            state.SkipWithError("hilite merge failed");
            return;
        }
    }
    state.counters["peak_MB"] = peakMb;
    state.counters["rows/s"] =
        benchmark::Counter(double(s) * r * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Merge)
    ->Args({200, 50})
    ->Args({200, 500})
    ->Args({200, 5000})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// ---- The Dask client's side: rows appended to a DistributedRun ----

/// What caps a Dask run's rate: the client checks each row the workers send (parse, the configuration's
/// fingerprint) and appends it (group commit). Measured alone, on rows made beforehand.
void BM_ClientAppend(benchmark::State& state) {
    const int n = int(state.range(0));
    const fs::path dir = shards(1, n);
    std::vector<std::string> rows;
    {
        std::ifstream in(dir / "shard1" / "results.jsonl");
        for (std::string line; std::getline(in, line);) rows.push_back(line);
    }
    for (auto _ : state) {
        state.PauseTiming();
        experiments::RunOptions o;
        o.experiment = (dir / "merge.toml").string();
        o.out = (scratch() / "append-out").string();
        fs::remove_all(o.out);
        auto run = std::make_unique<experiments::DistributedRun>(o);
        state.ResumeTiming();
        for (const auto& r : rows) run->append(r);
        state.PauseTiming();
        run.reset();
        state.ResumeTiming();
    }
    state.counters["rows/s"] = benchmark::Counter(double(n) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ClientAppend)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
