#pragma once
// Result files of an experiment, streamed row by row so a killed run keeps every completed row:
// results.jsonl (one JSON object per configuration) and results.csv (the same rows, fixed columns).
// Each row is appended whole and flushed; a partial last line (a kill mid-write) is dropped on resume.

#include <nlohmann/json.hpp>

#include <cstdio>
#include <set>
#include <string>
#include <vector>

namespace hilite::experiments {

/// Reads the complete rows of a results.jsonl (a torn last line is ignored). Missing file: empty.
std::vector<nlohmann::json> readRows(const std::string& jsonlPath);

/// CSV text of one value: numbers as %.10g, strings quoted when needed, arrays joined with ';'.
std::string csvField(const nlohmann::json& v);

class ResultsWriter {
public:
    /// Opens dir/results.{jsonl,csv}. With `resume`, keeps the complete rows already there (rewriting
    /// both files from them, by rename) and reports their configs in done(); otherwise starts empty.
    ResultsWriter(const std::string& dir, const std::vector<std::string>& columns, bool resume);
    ~ResultsWriter();
    ResultsWriter(const ResultsWriter&) = delete;
    ResultsWriter& operator=(const ResultsWriter&) = delete;

    const std::set<long>& done() const { return m_done; }
    /// Appends one row to both files and flushes them.
    void append(const nlohmann::json& row);

    /// Writes rows (sorted by "config") to dir/results.{jsonl,csv} atomically: what `merge` produces.
    static void writeAll(const std::string& dir, const std::vector<std::string>& columns,
                         std::vector<nlohmann::json> rows);

private:
    std::vector<std::string> m_columns;
    std::FILE* m_jsonl = nullptr;
    std::FILE* m_csv = nullptr;
    std::set<long> m_done;
};

}  // namespace hilite::experiments
