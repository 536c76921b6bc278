#pragma once
// The rows of a result folder as the reports read them (plots, summary.md): held, or streamed from
// results.jsonl one row at a time on each pass, so that a run or a merge of 10^6 rows holds none at once.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace hilite::experiments {

/// Calls f(row, line number) for each complete row of a results.jsonl, checked as readRows checks them,
/// streamed: one row in memory at a time (10^5 rows held as JSON took 0.6 GB). Missing file: no call.
void forEachRow(const std::string& jsonlPath, const std::function<void(nlohmann::json&&, long)>& f);

/// The rows the reports read (plots, summary.md): a vector held by the caller, or a results.jsonl read again,
/// one row at a time, on each pass over them (a merge or a run of 10^6 rows holds none at once).
class Rows {
public:
    Rows(const std::vector<nlohmann::json>& rows) : m_vec(&rows), m_size(rows.size()) {}  // NOLINT: implicit
    /// The rows of a results.jsonl (read once here to count and check them).
    static Rows file(const std::string& jsonlPath);
    size_t size() const { return m_size; }
    bool empty() const { return m_size == 0; }
    /// All rows at once, for the few reports that need them by index (a bounce study's handful).
    std::vector<nlohmann::json> materialize() const;

    class iterator {
    public:
        using iterator_category = std::input_iterator_tag;
        using value_type = nlohmann::json;
        using difference_type = std::ptrdiff_t;
        using pointer = const nlohmann::json*;
        using reference = const nlohmann::json&;
        reference operator*() const { return m_vec ? (*m_vec)[m_i] : m_row; }
        pointer operator->() const { return &**this; }
        iterator& operator++();
        bool operator==(const iterator& o) const { return m_vec ? m_i == o.m_i : m_end == o.m_end; }
        bool operator!=(const iterator& o) const { return !(*this == o); }

    private:
        friend class Rows;
        void read();
        const std::vector<nlohmann::json>* m_vec = nullptr;
        size_t m_i = 0;
        std::shared_ptr<std::ifstream> m_in;
        std::string m_path;
        long m_line = 0;
        nlohmann::json m_row;
        bool m_end = true;
    };
    iterator begin() const;
    iterator end() const;

private:
    Rows() = default;
    const std::vector<nlohmann::json>* m_vec = nullptr;
    std::string m_path;
    size_t m_size = 0;
};

}  // namespace hilite::experiments
