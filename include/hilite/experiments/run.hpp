#pragma once
// Running an experiment into a result folder, and merging shards: what `hilite run` and `hilite merge` do,
// as library calls (the CLI and the Python module's hilite.run are thin callers). Every input is checked
// and every .brdf probed before the folder is made; the folder is locked while it is written; --resume and
// merge prove the rows already there belong to the same experiment.

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hilite::experiments {

struct RunOptions {
    std::string experiment;      ///< a file, or the name of one shipped in experiments/
    std::string out;             ///< "" = results/<experiment name>
    bool resume = false;         ///< keep the completed rows already in `out`, run the rest
    int shardK = 1, shardN = 1;  ///< configurations i with i mod N = K - 1
    std::string backend;         ///< "" = $HILITE_GL_BACKEND, else auto
    std::string outName = "-o";  ///< how messages name the output folder (the flag, or a keyword)
    /// Only check: the file, every configuration, every .brdf it names and the output folder, as a run does
    /// before it writes; then return, nothing measured or written (RunSummary::configurations says how many).
    bool check = false;
    /// fsync results.jsonl after every row; by default rows are made durable together, at most every 100 ms and at
    /// the end (a killed run loses no written row either way; a power loss the rows of the last interval)
    bool fsyncEachRow = false;
    /// Called after each row (rows measured now, rows to measure now, seconds so far); may be empty.
    std::function<void(size_t, size_t, double)> progress;
};

struct RunSummary {
    std::string name, dir;      ///< the experiment's name and the folder written
    size_t configurations = 0;  ///< in the whole experiment
    size_t measured = 0;        ///< rows measured by this call (the rest were resumed, or other shards')
    double seconds = 0;
    bool finalized = false;  ///< plots and summary.md written (not for a shard of several)
};

/// "K/N" of --shard into k, n (1/1 for ""); InputError naming `name` otherwise.
void parseShard(const std::string& text, int& k, int& n, const std::string& name = "--shard");
/// Runs the experiment (InputError / SystemError as the CLI reports them).
RunSummary runExperiment(const RunOptions& o);

/// A run whose rows are measured elsewhere (hilite.run(..., client=) maps them over Dask workers): opened as
/// runExperiment opens its folder (every check, every .brdf probed, the lock, --resume's rows kept), fed rows in
/// any order, each checked (a configuration of this run not yet written, and its fingerprint), appended and made
/// durable by group commit; finish() writes the folder a single run writes, rows in configuration order.
class DistributedRun {
public:
    explicit DistributedRun(const RunOptions& o);  ///< o.check and o.progress are not used
    ~DistributedRun();                             ///< the rows appended stay, made durable; the lock is released
    DistributedRun(const DistributedRun&) = delete;
    DistributedRun& operator=(const DistributedRun&) = delete;

    const std::string& experimentPath() const;  ///< the experiment's file, absolute: what the workers load
    const std::string& dir() const;             ///< the result folder
    std::vector<size_t> todo() const;           ///< this run's configurations without a row yet, ascending
    /// One row as ConfigurationMeasurer::measure gives it. InputError (nothing written): not a row, a
    /// configuration this run does not measure or has written, or measured with other settings (fingerprint).
    void append(const std::string& row);
    size_t appended() const;  ///< rows appended by this run
    /// Every configuration has its row: results rewritten in configuration order, plots and summary.md
    /// written (not for a shard of several). InputError naming how many rows are missing otherwise.
    RunSummary finish();

private:
    struct Impl;
    std::unique_ptr<Impl> m;
};

/// A worker's side of a DistributedRun: the experiment loaded and checked once (every configuration), then
/// configurations measured by index, each row exactly as `hilite run` writes it (one JSON line, no newline).
class ConfigurationMeasurer {
public:
    ConfigurationMeasurer(const std::string& experiment, const std::string& backend = "");
    ~ConfigurationMeasurer();
    ConfigurationMeasurer(const ConfigurationMeasurer&) = delete;
    ConfigurationMeasurer& operator=(const ConfigurationMeasurer&) = delete;
    size_t configurations() const;
    std::string measure(size_t index);  ///< InputError for an index out of range

private:
    struct Impl;
    std::unique_ptr<Impl> m;
};

struct MergeSummary {
    std::string dir;
    size_t rows = 0, expected = 0, shards = 0;
};
/// Joins shard folders into `out` as a single run writes it; rows.size() < expected: some are missing.
MergeSummary mergeShards(const std::vector<std::string>& shards, const std::string& out,
                         const std::string& backend = "", const std::string& outName = "-o");

}  // namespace hilite::experiments
