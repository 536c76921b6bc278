// `hilite run EXPERIMENT` and `hilite merge`: an experiment is a base scene plus sweep axes over any
// scene key; each configuration is measured and streamed to results.{jsonl,csv}; then plots, a contact
// sheet of photo views and summary.md are made from the rows. Shards run deterministic slices; merge
// joins them into what a single run writes.

#include "cli/commands.hpp"
#include "experiments/experiment.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "experiments/results.hpp"
#include "io/image_io.hpp"

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

/// The output folder can be made or written, and the result files in it are replaceable (regular files).
void checkResultFolder(const std::string& dir) {
    io::checkOutputDir(dir, "-o");
    if (!fs::is_directory(dir)) return;
    for (const char* name : {"results.jsonl", "results.csv", "experiment.toml", "experiment.origin", "summary.md"})
        io::checkWritable(dir + "/" + name, "-o");
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
    if (f.experiment.empty()) throw InputError("run: empty experiment name (give a file, or a name in experiments/)");
    const Experiment exp = experiments::loadExperiment(experiments::findExperiment(f.experiment));
    const std::string dir = f.out.empty() ? "results/" + exp.name : f.out;
    const auto configs = exp.configurations();  // validates every configuration before anything runs
    ExperimentRunner runner(exp, f.backend);
    runner.probeAll(configs, shardK, shardN);  // a .brdf that does not build or runs too long: nothing written
    checkResultFolder(dir);
    io::makeOutputDir(dir, "-o");  // only now: bad input leaves not even an empty folder behind
    const io::FolderLock lock(dir, "-o");  // a second run or merge into this folder is refused, not mixed in
    experiments::ResultsWriter writer(dir, runner.columns(), f.resume, exp, configs);
    experiments::writeExperimentCopy(exp, dir);
    // This shard's configurations only, each built when measured (10^6 held at once took 1.1 GB).
    const size_t first = size_t(shardK - 1), stride = size_t(shardN);
    size_t todo = 0;
    for (size_t i = first; i < configs.size(); i += stride) todo += !writer.done().count(long(i));
    const auto t0 = std::chrono::steady_clock::now();
    size_t finished = 0;
    for (size_t i = first; i < configs.size(); i += stride) {
        if (writer.done().count(long(i))) continue;
        writer.append(runner.measure(configs[i]));
        progress(++finished, todo,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    writer.finish();
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

/// Refuses shards whose experiments differ in what any configuration measures (before anything is written).
void checkSameExperiment(const std::string& first, const Experiment& a, const experiments::Configurations& ca,
                         const std::string& other) {
    const Experiment b = experiments::loadExperimentCopy(other);
    if (b.text == a.text) return;
    const auto cb = b.configurations();
    const std::string why = "merge: '" + other + "' and '" + first + "' are shards of different experiments";
    if (ca.size() != cb.size())
        throw InputError(why + " (" + std::to_string(cb.size()) + " and " + std::to_string(ca.size()) + " configurations)");
    for (size_t i = 0; i < ca.size(); ++i)
        if (experiments::fingerprint(b, cb[i]) != experiments::fingerprint(a, ca[i]))
            throw InputError(why + " (configuration " + std::to_string(ca[i].index) + " differs)");
}

int runMerge(const MergeFlags& f) {
    if (f.out.empty()) throw InputError("-o: merge needs an output folder");
    for (const auto& s : f.shards) {
        const std::string copy = s + "/experiment.toml";
        if (!fs::exists(copy)) throw InputError("merge: '" + s + "' holds no experiment.toml (not a hilite run output)");
    }
    const Experiment exp = experiments::loadExperimentCopy(f.shards.front());
    const auto configs = exp.configurations();
    std::vector<nlohmann::json> rows;
    for (const auto& s : f.shards) {
        if (s != f.shards.front()) checkSameExperiment(f.shards.front(), exp, configs, s);
        auto shardRows = experiments::readRows(s + "/results.jsonl");
        experiments::checkRows(shardRows, s + "/results.jsonl", exp, configs);
        for (auto& r : shardRows) rows.push_back(std::move(r));
    }
    std::set<long> seen;
    for (const auto& r : rows)
        if (!seen.insert(r["config"].get<long>()).second)
            throw InputError("merge: configuration " + r["config"].dump() + " appears in more than one shard");
    ExperimentRunner runner(exp, f.backend);  // checks the backend and [match] before anything is written
    checkResultFolder(f.out);
    io::makeOutputDir(f.out, "-o");
    const io::FolderLock lock(f.out, "-o");
    experiments::ResultsWriter::writeAll(f.out, runner.columns(), rows);
    experiments::writeExperimentCopy(exp, f.out);
    const size_t expected = configs.size();
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
    app.add_option("-o,--output", f->out, "output folder (default results/<experiment name>)")->check(nonEmpty());
    app.add_flag("--resume", f->resume, "keep the completed rows already in the output folder and run the rest");
    app.add_option("--shard", f->shard, "run only configurations i with i mod N = K-1 (K/N, 1-based)");
    app.add_option("--gl-backend", f->backend, "auto | osmesa | egl");
    app.footer("Example: hilite run eccentricity   (writes results/eccentricity/)");
    return [f] { return runExperiment(*f); };
}

Action addMerge(CLI::App& app) {
    auto f = std::make_shared<MergeFlags>();
    app.add_option("shards", f->shards, "output folders of hilite run --shard K/N")->required();
    app.add_option("-o,--output", f->out, "folder for the merged results")->required()->check(nonEmpty());
    app.add_option("--gl-backend", f->backend, "auto | osmesa | egl");
    app.footer("Example: hilite merge results/s1 results/s2 -o results/eccentricity");
    return [f] { return runMerge(*f); };
}

}  // namespace hilite::cli
