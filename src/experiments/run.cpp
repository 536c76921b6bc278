#include "hilite/experiments/run.hpp"

#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "experiments/results.hpp"
#include "hilite/core/error.hpp"
#include "io/image_io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <queue>
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

namespace {

void checkOptions(const RunOptions& o) {
    if (o.shardN < 1 || o.shardK < 1 || o.shardK > o.shardN)
        throw InputError("shard: expected 1 <= K <= N (got " + std::to_string(o.shardK) + "/" +
                         std::to_string(o.shardN) + ")");
    if (o.experiment.empty()) throw InputError("run: empty experiment name (give a file, or a name in experiments/)");
}

/// An experiment opened for a run: loaded, its configurations validated (a shard's only), this shard's .brdf files probed, the
/// output folder checked; open() then makes the folder, locks it and starts its result files. Not movable (the
/// configurations and the runner refer to `exp`).
struct OpenedRun {
    explicit OpenedRun(const RunOptions& o)
        : options(o),
          exp((checkOptions(o), loadExperiment(findExperiment(o.experiment)))),
          configs(exp.configurations(o.shardK, o.shardN)),  // validates this run's configurations before it runs
          runner(exp, o.backend),
          dir(o.out.empty() ? "results/" + exp.name : o.out) {
        runner.probeAll(configs, o.shardK, o.shardN);  // a .brdf that does not build or runs too long: nothing written
        checkResultFolder(dir, o.outName);
    }
    OpenedRun(const OpenedRun&) = delete;
    OpenedRun& operator=(const OpenedRun&) = delete;

    void open() {
        io::makeOutputDir(dir, options.outName);  // only now: bad input leaves not even an empty folder behind
        lock = std::make_unique<io::FolderLock>(dir, options.outName);  // a second run or merge is refused
        writer = std::make_unique<ResultsWriter>(dir, runner.columns(), options.resume, exp, configs,
                                                 options.fsyncEachRow ? 0.0 : ResultsWriter::kGroupCommitSeconds);
        writeExperimentCopy(exp, dir);
    }
    bool ours(size_t i) const { return i % size_t(options.shardN) == size_t(options.shardK - 1); }
    size_t shardSize() const {
        const size_t first = size_t(options.shardK - 1), n = size_t(options.shardN);
        return configs.size() > first ? (configs.size() - first + n - 1) / n : 0;
    }

    RunOptions options;
    Experiment exp;
    Configurations configs;
    ExperimentRunner runner;
    std::string dir;
    std::unique_ptr<io::FolderLock> lock;
    std::unique_ptr<ResultsWriter> writer;
};

/// One shard's results.jsonl, read in configuration order: straight through when it was written in order (a
/// run that was not resumed), else through an index of (configuration, line offset) sorted once.
class ShardCursor {
public:
    ShardCursor(std::string path, bool sorted) : m_path(std::move(path)), m_in(m_path, std::ios::binary) {
        if (!m_in) throw InputError("merge: cannot read '" + m_path + "'");
        if (sorted) return;
        std::string line;
        for (std::streamoff at = m_in.tellg(); std::getline(m_in, line) && !m_in.eof(); at = m_in.tellg())
            m_index.emplace_back(parseRow(line, m_path, long(m_index.size() + 1))["config"].get<long>(), at);
        std::sort(m_index.begin(), m_index.end());
        m_in.clear();
        m_indexed = true;
    }
    /// The next row in configuration order; false at the end.
    bool next(nlohmann::json& row) {
        std::string line;
        if (m_indexed) {
            if (m_next == m_index.size()) return false;
            m_in.seekg(m_index[m_next++].second);
            std::getline(m_in, line);
        } else if (!std::getline(m_in, line) || m_in.eof()) {
            return false;  // the end, or a torn last line (checked before: dropped, as readRows drops it)
        }
        row = parseRow(line, m_path, ++m_line);
        return true;
    }

private:
    std::string m_path;
    std::ifstream m_in;
    std::vector<std::pair<long, std::streamoff>> m_index;
    size_t m_next = 0;
    long m_line = 0;
    bool m_indexed = false;
};

/// Writes dir/results.{jsonl,csv} atomically from the (checked) rows of `files` in configuration order: a
/// k-way merge, one row of each file in memory ((file, written in order): one out of order goes through its
/// index). A file may be dir/results.jsonl itself: it is read to its end before the rename replaces it.
void writeInOrder(const std::string& dir, const std::vector<std::string>& columns,
                  const std::vector<std::pair<std::string, bool>>& files) {
    std::vector<std::unique_ptr<ShardCursor>> cursors;
    std::vector<nlohmann::json> head(files.size());
    using Item = std::pair<long, size_t>;  // (configuration, file)
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (size_t k = 0; k < files.size(); ++k) {
        cursors.push_back(std::make_unique<ShardCursor>(files[k].first, files[k].second));
        if (cursors[k]->next(head[k])) queue.emplace(head[k]["config"].get<long>(), k);
    }
    io::AtomicFileWriter jsonl(dir + "/results.jsonl"), csv(dir + "/results.csv");
    csv.write(csvHeaderLine(columns));
    while (!queue.empty()) {
        const size_t k = queue.top().second;
        queue.pop();
        jsonl.write(head[k].dump() + "\n");
        csv.write(csvRowLine(columns, head[k]));
        if (cursors[k]->next(head[k])) queue.emplace(head[k]["config"].get<long>(), k);
    }
    jsonl.commit();
    csv.commit();
}

}  // namespace

RunSummary runExperiment(const RunOptions& o) {
    OpenedRun run(o);
    RunSummary s;
    s.name = run.exp.name;
    s.dir = run.dir;
    const auto& configs = run.configs;
    if (o.check) {  // what the run would refuse next: a folder another run holds, rows --resume would not keep
        io::checkUnlocked(s.dir, o.outName);
        if (o.resume) resumedRows(s.dir, run.exp, configs);
        s.configurations = configs.size();
        return s;
    }
    run.open();
    ResultsWriter& writer = *run.writer;
    // This shard's configurations only, each built when measured (10^6 held at once took 1.1 GB).
    const size_t first = size_t(o.shardK - 1), stride = size_t(o.shardN);
    size_t todo = 0;
    for (size_t i = first; i < configs.size(); i += stride) todo += !writer.done().count(long(i));
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = first; i < configs.size(); i += stride) {
        if (writer.done().count(long(i))) continue;
        try {
            writer.append(run.runner.measure(configs[i]));
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
    run.runner.finalize(s.dir, Rows::file(s.dir + "/results.jsonl"), s.seconds);
    s.finalized = true;
    return s;
}

struct DistributedRun::Impl {
    explicit Impl(const RunOptions& o) : run(o) {}
    OpenedRun run;
    std::string path;
    size_t appended = 0;
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    bool finished = false;
};

DistributedRun::DistributedRun(const RunOptions& o) : m(std::make_unique<Impl>(o)) {
    m->path = fs::absolute(m->run.exp.path).lexically_normal().string();
    m->run.open();
}

DistributedRun::~DistributedRun() {
    if (!m || m->finished) return;
    try {
        m->run.writer->finish();  // the rows appended made durable before the lock goes
    } catch (...) {
    }
}

const std::string& DistributedRun::experimentPath() const { return m->path; }
const std::string& DistributedRun::dir() const { return m->run.dir; }
size_t DistributedRun::appended() const { return m->appended; }

std::vector<size_t> DistributedRun::todo() const {
    std::vector<size_t> out;
    const RunOptions& o = m->run.options;
    for (size_t i = size_t(o.shardK - 1); i < m->run.configs.size(); i += size_t(o.shardN))
        if (!m->run.writer->done().count(long(i))) out.push_back(i);
    return out;
}

void DistributedRun::append(const std::string& text) {
    if (m->finished) throw InputError("run: this run has finished; no row can be added");
    const std::string name = "a row from a worker";
    auto rows = parseRows(text.empty() || text.back() != '\n' ? text + "\n" : text, name);
    if (rows.size() != 1) throw InputError(name + ": expected one JSON row, got " + std::to_string(rows.size()));
    const long index = rows[0]["config"].get<long>();
    if (index >= 0 && size_t(index) < m->run.configs.size() && !m->run.ours(size_t(index)))
        throw InputError(name + ": configuration " + std::to_string(index) + " is not one this run (shard " +
                         std::to_string(m->run.options.shardK) + "/" + std::to_string(m->run.options.shardN) +
                         ") measures");
    checkRows(rows, name, m->run.exp, m->run.configs);  // another or an edited experiment's row is refused
    if (m->run.writer->done().count(index))
        throw InputError(name + ": configuration " + std::to_string(index) + " has its row already");
    m->run.writer->append(rows[0]);
    ++m->appended;
}

RunSummary DistributedRun::finish() {
    if (m->finished) throw InputError("run: this run has finished already");
    OpenedRun& run = m->run;
    const size_t all = run.shardSize(), missing = todo().size();
    if (missing)
        throw InputError("run: " + std::to_string(missing) + " of " + std::to_string(all) +
                         " configurations have no row yet; the " + std::to_string(all - missing) +
                         " written are kept in " + run.dir + " (rerun with resume)");
    run.writer->finish();
    m->finished = true;
    RunSummary s;
    s.name = run.exp.name, s.dir = run.dir, s.configurations = run.configs.size(), s.measured = m->appended;
    s.seconds = since(m->t0);
    // Rows arrive in the order the workers finish: written again in configuration order, as a single run's.
    writeInOrder(run.dir, run.runner.columns(), {{run.dir + "/results.jsonl", false}});
    if (run.options.shardN > 1) return s;
    run.runner.finalize(run.dir, Rows::file(run.dir + "/results.jsonl"), s.seconds);
    s.finalized = true;
    return s;
}

struct ConfigurationMeasurer::Impl {
    Impl(const std::string& experiment, const std::string& backend)
        : exp(loadExperiment(findExperiment(experiment))), configs(exp.configurations()), runner(exp, backend) {}
    Experiment exp;
    Configurations configs;
    ExperimentRunner runner;
};

ConfigurationMeasurer::ConfigurationMeasurer(const std::string& experiment, const std::string& backend) {
    if (experiment.empty()) throw InputError("run: empty experiment name (give a file, or a name in experiments/)");
    m = std::make_unique<Impl>(experiment, backend);
}
ConfigurationMeasurer::~ConfigurationMeasurer() = default;
size_t ConfigurationMeasurer::configurations() const { return m->configs.size(); }

std::string ConfigurationMeasurer::measure(size_t index) {
    if (index >= m->configs.size())
        throw InputError("run: configuration " + std::to_string(index) + " out of range (the experiment has " +
                         std::to_string(m->configs.size()) + ")");
    return m->runner.measure(m->configs[index]).dump();
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
    // Every row checked first, streamed (one in memory at a time): nothing is written when any is refused.
    std::vector<bool> seen(configs.size());
    std::vector<bool> sorted(shards.size(), true);
    size_t total = 0;
    for (size_t k = 0; k < shards.size(); ++k) {
        if (k) checkSameExperiment(shards.front(), exp, configs, shards[k]);
        long last = -1;
        const std::string file = shards[k] + "/results.jsonl";
        forEachRow(file, [&](nlohmann::json&& r, long line) {
            checkRow(r, file, line, exp, configs);
            const long c = r["config"].get<long>();
            if (seen[size_t(c)])
                throw InputError("merge: configuration " + std::to_string(c) + " appears more than once (" + file +
                                 ":" + std::to_string(line) + ")");
            seen[size_t(c)] = true;
            sorted[k] = sorted[k] && c > last;
            last = c;
            ++total;
        });
    }
    ExperimentRunner runner(exp, backend);  // checks the backend and [match] before anything is written
    checkResultFolder(out, outName);
    io::makeOutputDir(out, outName);
    const io::FolderLock lock(out, outName);
    std::vector<std::pair<std::string, bool>> files;
    for (size_t k = 0; k < shards.size(); ++k)
        if (fs::exists(shards[k] + "/results.jsonl")) files.emplace_back(shards[k] + "/results.jsonl", sorted[k]);
    writeInOrder(out, runner.columns(), files);
    writeExperimentCopy(exp, out);
    runner.finalize(out, Rows::file(out + "/results.jsonl"), -1);
    return {out, total, configs.size(), shards.size()};
}

}  // namespace hilite::experiments
