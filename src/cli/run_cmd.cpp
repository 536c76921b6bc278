// `hilite run EXPERIMENT` and `hilite merge`: an experiment is a base scene plus sweep axes over any
// scene key; each configuration is measured and streamed to results.{jsonl,csv}; then plots, a contact
// sheet of photo views and summary.md are made from the rows. Shards run deterministic slices; merge
// joins them into what a single run writes.

#include "cli/commands.hpp"
#include "experiments/experiment.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "experiments/results.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

namespace fs = std::filesystem;
using experiments::Experiment;
using experiments::ExperimentRunner;

struct RunFlags {
    std::string experiment, out, shard;
    bool resume = false;
    std::string backend;
};

void parseShard(const std::string& s, int& k, int& n) {
    k = 1, n = 1;
    if (s.empty()) return;
    const auto parts = split(s, '/');
    const auto a = parts.size() == 2 ? parseNumber(parts[0]) : std::nullopt;
    const auto b = parts.size() == 2 ? parseNumber(parts[1]) : std::nullopt;
    if (!a || !b || *a != std::floor(*a) || *b != std::floor(*b) || !(*b >= 1 && *b <= 1e6) || *a < 1 || *a > *b)
        throw InputError("--shard: expected K/N with 1 <= K <= N (got '" + s + "')");
    k = int(*a), n = int(*b);
}

void progress(size_t done, size_t total, double seconds) {
    static const bool tty = isatty(fileno(stderr));
    if (!tty) return;
    const double eta = done ? seconds / double(done) * double(total - done) : 0;
    std::fprintf(stderr, "\r[%zu/%zu] %5.1f%%  elapsed %.1fs  ETA %.1fs   ", done, total,
                 total ? 100.0 * double(done) / double(total) : 100.0, seconds, eta);
    if (done == total) std::fprintf(stderr, "\n");
}

int runExperiment(const RunFlags& f) {
    int shardK = 1, shardN = 1;
    parseShard(f.shard, shardK, shardN);
    const Experiment exp = experiments::loadExperiment(experiments::findExperiment(f.experiment));
    const std::string dir = f.out.empty() ? "results/" + exp.name : f.out;
    const auto configs = exp.configurations();  // validates every configuration before anything runs
    ExperimentRunner runner(exp, f.backend);
    runner.probeAll(configs, shardK, shardN);  // a .brdf that does not build or runs too long: nothing written
    fs::create_directories(dir);  // only now: bad input leaves not even an empty folder behind
    if (access(dir.c_str(), W_OK) != 0) throw InputError("-o: cannot write to '" + dir + "'");
    experiments::ResultsWriter writer(dir, runner.columns(), f.resume);
    experiments::writeExperimentCopy(exp, dir);
    size_t todo = 0;
    for (const auto& c : configs) todo += (c.index % shardN == shardK - 1 && !writer.done().count(c.index));
    const auto t0 = std::chrono::steady_clock::now();
    size_t finished = 0;
    for (const auto& c : configs) {
        if (c.index % shardN != shardK - 1 || writer.done().count(c.index)) continue;
        writer.append(runner.measure(c));
        progress(++finished, todo,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (shardN > 1) {
        std::cout << "shard " << shardK << "/" << shardN << ": " << finished << " rows in " << seconds << " s -> "
                  << dir << "/results.jsonl (join the shards with hilite merge)\n";
        return 0;
    }
    runner.finalize(dir, experiments::readRows(dir + "/results.jsonl"), seconds);
    std::cout << exp.name << ": " << configs.size() << " configurations (" << finished << " measured now) in "
              << seconds << " s -> " << dir << "/summary.md\n";
    return 0;
}

struct MergeFlags {
    std::vector<std::string> shards;
    std::string out, backend;
};

int runMerge(const MergeFlags& f) {
    if (f.out.empty()) throw InputError("-o: merge needs an output folder");
    std::vector<nlohmann::json> rows;
    std::string experimentFile;
    for (const auto& s : f.shards) {
        const std::string copy = s + "/experiment.toml";
        if (!fs::exists(copy)) throw InputError("merge: '" + s + "' holds no experiment.toml (not a hilite run output)");
        if (experimentFile.empty()) experimentFile = copy;
        for (auto& r : experiments::readRows(s + "/results.jsonl")) rows.push_back(std::move(r));
    }
    const Experiment exp = experiments::loadExperimentCopy(experimentFile.substr(0, experimentFile.rfind('/')));
    std::set<long> seen;
    for (const auto& r : rows)
        if (!seen.insert(r["config"].get<long>()).second)
            throw InputError("merge: configuration " + r["config"].dump() + " appears in more than one shard");
    ExperimentRunner runner(exp, f.backend);  // checks the backend and [match] before anything is written
    fs::create_directories(f.out);
    experiments::ResultsWriter::writeAll(f.out, runner.columns(), rows);
    experiments::writeExperimentCopy(exp, f.out);
    const size_t expected = exp.configurations().size();
    runner.finalize(f.out, experiments::readRows(f.out + "/results.jsonl"), -1);
    std::cout << "merged " << rows.size() << " of " << expected << " rows from " << f.shards.size() << " shards -> "
              << f.out << "\n";
    return rows.size() == expected ? 0 : 2;
}

}  // namespace

Action addRun(CLI::App& app) {
    auto f = std::make_shared<RunFlags>();
    app.add_option("experiment", f->experiment, "experiment file, or the name of one shipped in experiments/")
        ->required();
    app.add_option("-o,--output", f->out, "output folder (default results/<experiment name>)");
    app.add_flag("--resume", f->resume, "keep the completed rows already in the output folder and run the rest");
    app.add_option("--shard", f->shard, "run only configurations i with i mod N = K-1 (K/N, 1-based)");
    app.add_option("--gl-backend", f->backend, "auto | osmesa | egl");
    app.footer("Example: hilite run eccentricity   (writes results/eccentricity/)");
    return [f] { return runExperiment(*f); };
}

Action addMerge(CLI::App& app) {
    auto f = std::make_shared<MergeFlags>();
    app.add_option("shards", f->shards, "output folders of hilite run --shard K/N")->required();
    app.add_option("-o,--output", f->out, "folder for the merged results")->required();
    app.add_option("--gl-backend", f->backend, "auto | osmesa | egl");
    app.footer("Example: hilite merge results/s1 results/s2 -o results/eccentricity");
    return [f] { return runMerge(*f); };
}

}  // namespace hilite::cli
