#pragma once
// Result files of an experiment, streamed row by row so a killed run keeps every completed row:
// results.jsonl (one JSON object per configuration) and results.csv (the same rows, fixed columns).
// Each row is appended whole as it is measured (a killed process loses none: its writes are in the kernel);
// results.jsonl is fsync'd by group commit, at most every 100 ms and at the end (a power loss costs the rows of
// the last interval, measured again by --resume), or after every row when asked. A partial last line (a kill or
// a full disk mid-write) is dropped on resume. Each JSON row carries the fingerprint of the configuration it
// measured, so --resume and merge never keep a row of another (or an edited) experiment.

#include "experiments/rows.hpp"
#include "io/image_io.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace hilite::experiments {

struct Configuration;
class Configurations;
struct Experiment;

/// Reads the complete rows of a results.jsonl, streamed (no size cap). A torn last line (no newline: a kill
/// mid-write) is dropped; any other line that is not a JSON object with an integer "config" >= 0 is refused
/// (InputError "<path>:<line>: ..."). Missing file: empty. A path that is not a regular file: refused.
std::vector<nlohmann::json> readRows(const std::string& jsonlPath);

/// One line of a results.jsonl as a row, checked as readRows checks it (InputError "<name>:<lineNo>: ...").
nlohmann::json parseRow(const std::string& line, const std::string& name, long lineNo);

/// The rows of `text` as readRows reads a file (`name` stands for the file in messages): what the fuzzer drives.
std::vector<nlohmann::json> parseRows(const std::string& text, const std::string& name);

/// A measured number that is not finite is never printed as nan/inf: it becomes null in the row and a
/// "non_finite:<fields>" flag names it (the measurement broke down there; the other flags may say why).
void nameNonFinite(nlohmann::json& row);

/// CSV text of one value: numbers as %.10g, arrays joined with ';', text quoted when it holds a comma, quote or
/// line break (RFC 4180).
std::string csvField(const nlohmann::json& v);
/// The header line and one row's line of a CSV with these columns (a column the row lacks is empty), as
/// results.csv writes them.
std::string csvHeaderLine(const std::vector<std::string>& columns);
std::string csvRowLine(const std::vector<std::string>& columns, const nlohmann::json& row);

/// The fingerprint of what configuration `c` of `e` measures (16 hex digits, FNV-1a 64 of a canonical text:
/// every scene value the configuration sets, data-file paths made absolute with their contents' hash, its case's
/// reference keys and tags, and the experiment's [timing], [reference], [match], [fit] and [bounces] settings;
/// not the experiment file's text, comments or the order of its keys).
std::string fingerprint(const Experiment& e, const Configuration& c);

/// Checks that every row of `rows` (read from `file`) was measured by the configuration of `configs` it
/// names, by fingerprint. Throws InputError naming file:line, the configuration and, where a row column
/// shows it, the value that differs ("... was measured with roughness = 0.1, the experiment now says 0.2").
void checkRows(const std::vector<nlohmann::json>& rows, const std::string& file, const Experiment& e,
               const Configurations& configs);
/// checkRows for one row, line `lineNo` of `file`.
void checkRow(const nlohmann::json& row, const std::string& file, long lineNo, const Experiment& e,
              const Configurations& configs);

/// The rows --resume keeps of `dir`/results.jsonl: read, checked against the experiment (checkRows) and each
/// configuration at most once; InputError naming the file and line otherwise. Nothing is written.
std::vector<nlohmann::json> resumedRows(const std::string& dir, const Experiment& e, const Configurations& configs);

class ResultsWriter {
public:
    /// Opens dir/results.{jsonl,csv}. With `resume`, keeps the complete rows already there (rewriting
    /// both files from them, by rename) and reports their configs in done(); otherwise starts empty.
    /// Kept rows must pass checkRows against `configs`.
    /// results.jsonl is fsync'd when `syncInterval` seconds have passed since the last fsync (0: after every row),
    /// and by finish().
    ResultsWriter(const std::string& dir, const std::vector<std::string>& columns, bool resume, const Experiment& e,
                  const Configurations& configs, double syncInterval = kGroupCommitSeconds);
    /// Group commit's interval: rows appended within it are made durable together.
    static constexpr double kGroupCommitSeconds = 0.1;
    ResultsWriter(const ResultsWriter&) = delete;
    ResultsWriter& operator=(const ResultsWriter&) = delete;

    const std::set<long>& done() const { return m_done; }
    /// Appends one row to both files, each written whole, results.jsonl fsync'd when the interval has passed
    /// (SystemError on failure: the rows appended before stay intact, and --resume measures the rest).
    void append(const nlohmann::json& row);

    /// fsync's both files (results.csv, which --resume rebuilds from results.jsonl, only here). Call before the
    /// run reports success.
    void finish();

    /// fsyncs of results.jsonl since the writer opened (what group commit saves is visible in tests).
    size_t syncs() const { return m_syncs; }

private:
    std::vector<std::string> m_columns;
    std::unique_ptr<io::DurableAppender> m_jsonl, m_csv;
    std::set<long> m_done;
    std::string m_dir;
    double m_syncInterval;
    std::chrono::steady_clock::time_point m_lastSync;
    size_t m_syncs = 0;
};

}  // namespace hilite::experiments
