#include "hilite/experiments/run.hpp"

#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "experiments/results.hpp"
#include "hilite/core/error.hpp"
#include "io/image_io.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <set>

namespace hilite::experiments {

namespace {

namespace fs = std::filesystem;

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The output folder can be made or written, and the result files in it are replaceable (regular files).
void checkResultFolder(const std::string& dir, const std::string& name) {
    io::checkOutputDir(dir, name);
    if (!fs::is_directory(dir)) return;
    for (const char* file : {"results.jsonl", "results.csv", "experiment.toml", "experiment.origin", "summary.md"})
        io::checkWritable(dir + "/" + file, name);
}

/// Refuses shards whose experiments differ in what any configuration measures (before anything is written).
void checkSameExperiment(const std::string& first, const Experiment& a, const Configurations& ca,
                         const std::string& other) {
    const Experiment b = loadExperimentCopy(other);
    if (b.text == a.text) return;
    const auto cb = b.configurations();
    const std::string why = "merge: '" + other + "' and '" + first + "' are shards of different experiments";
    if (ca.size() != cb.size())
        throw InputError(why + " (" + std::to_string(cb.size()) + " and " + std::to_string(ca.size()) +
                         " configurations)");
    for (size_t i = 0; i < ca.size(); ++i)
        if (fingerprint(b, cb[i]) != fingerprint(a, ca[i]))
            throw InputError(why + " (configuration " + std::to_string(ca[i].index) + " differs)");
}

}  // namespace

void parseShard(const std::string& s, int& k, int& n, const std::string& name) {
    k = 1, n = 1;
    if (s.empty()) return;
    const auto parts = split(s, '/');
    const auto a = parts.size() == 2 ? parseNumber(parts[0]) : std::nullopt;
    const auto b = parts.size() == 2 ? parseNumber(parts[1]) : std::nullopt;
    if (!a || !b || *a != std::floor(*a) || *b != std::floor(*b) || !(*b >= 1 && *b <= 1e6) || *a < 1 || *a > *b)
        throw InputError(name + ": expected K/N with 1 <= K <= N (got '" + s + "')");
    k = int(*a), n = int(*b);
}

RunSummary runExperiment(const RunOptions& o) {
    if (o.shardN < 1 || o.shardK < 1 || o.shardK > o.shardN)
        throw InputError("shard: expected 1 <= K <= N (got " + std::to_string(o.shardK) + "/" +
                         std::to_string(o.shardN) + ")");
    if (o.experiment.empty()) throw InputError("run: empty experiment name (give a file, or a name in experiments/)");
    const Experiment exp = loadExperiment(findExperiment(o.experiment));
    RunSummary s;
    s.name = exp.name;
    s.dir = o.out.empty() ? "results/" + exp.name : o.out;
    const auto configs = exp.configurations();  // validates every configuration before anything runs
    ExperimentRunner runner(exp, o.backend);
    runner.probeAll(configs, o.shardK, o.shardN);  // a .brdf that does not build or runs too long: nothing written
    checkResultFolder(s.dir, o.outName);
    if (o.check) {  // what the run would refuse next: a folder another run holds, rows --resume would not keep
        io::checkUnlocked(s.dir, o.outName);
        if (o.resume) resumedRows(s.dir, exp, configs);
        s.configurations = configs.size();
        return s;
    }
    io::makeOutputDir(s.dir, o.outName);          // only now: bad input leaves not even an empty folder behind
    const io::FolderLock lock(s.dir, o.outName);  // a second run or merge into this folder is refused, not mixed in
    ResultsWriter writer(s.dir, runner.columns(), o.resume, exp, configs,
                         o.fsyncEachRow ? 0.0 : ResultsWriter::kGroupCommitSeconds);
    writeExperimentCopy(exp, s.dir);
    // This shard's configurations only, each built when measured (10^6 held at once took 1.1 GB).
    const size_t first = size_t(o.shardK - 1), stride = size_t(o.shardN);
    size_t todo = 0;
    for (size_t i = first; i < configs.size(); i += stride) todo += !writer.done().count(long(i));
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = first; i < configs.size(); i += stride) {
        if (writer.done().count(long(i))) continue;
        try {
            writer.append(runner.measure(configs[i]));
        } catch (const InputError& e) {  // a file changed after validation: the rows written are kept, say so
            const size_t kept = writer.done().size();  // resumed and appended
            if (kept == 0) throw;
            writer.finish();  // the rows kept made durable before the run stops
            throw InputError(std::string(e.what()) + " (configuration " + std::to_string(i) + "; " +
                             std::to_string(kept) + (kept == 1 ? " row" : " rows") + " kept in " + s.dir +
                             ": fix it and rerun with --resume)");
        }
        ++s.measured;
        if (o.progress) o.progress(s.measured, todo, since(t0));
    }
    writer.finish();
    s.seconds = since(t0);
    s.configurations = configs.size();
    if (o.shardN > 1) return s;
    runner.finalize(s.dir, readRows(s.dir + "/results.jsonl"), s.seconds);
    s.finalized = true;
    return s;
}

MergeSummary mergeShards(const std::vector<std::string>& shards, const std::string& out, const std::string& backend,
                         const std::string& outName) {
    if (out.empty()) throw InputError(outName + ": merge needs an output folder");
    if (shards.empty()) throw InputError("merge: give the shard folders to merge");
    for (const auto& s : shards)
        if (!fs::exists(s + "/experiment.toml"))
            throw InputError("merge: '" + s + "' holds no experiment.toml (not a hilite run output)");
    const Experiment exp = loadExperimentCopy(shards.front());
    const auto configs = exp.configurations();
    std::vector<nlohmann::json> rows;
    for (const auto& s : shards) {
        if (s != shards.front()) checkSameExperiment(shards.front(), exp, configs, s);
        auto shardRows = readRows(s + "/results.jsonl");
        checkRows(shardRows, s + "/results.jsonl", exp, configs);
        for (auto& r : shardRows) rows.push_back(std::move(r));
    }
    std::set<long> seen;
    for (const auto& r : rows)
        if (!seen.insert(r["config"].get<long>()).second)
            throw InputError("merge: configuration " + r["config"].dump() + " appears in more than one shard");
    ExperimentRunner runner(exp, backend);  // checks the backend and [match] before anything is written
    checkResultFolder(out, outName);
    io::makeOutputDir(out, outName);
    const io::FolderLock lock(out, outName);
    ResultsWriter::writeAll(out, runner.columns(), rows);
    writeExperimentCopy(exp, out);
    runner.finalize(out, readRows(out + "/results.jsonl"), -1);
    return {out, rows.size(), configs.size(), shards.size()};
}

}  // namespace hilite::experiments
