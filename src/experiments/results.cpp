#include "experiments/results.hpp"

#include "core/error.hpp"
#include "io/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace hilite::experiments {

std::vector<nlohmann::json> readRows(const std::string& path) {
    std::vector<nlohmann::json> rows;
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    size_t start = 0;
    while (start < text.size()) {
        const size_t end = text.find('\n', start);
        if (end == std::string::npos) break;  // no newline: torn by a kill mid-write
        try {
            rows.push_back(nlohmann::json::parse(text.substr(start, end - start)));
        } catch (const nlohmann::json::exception&) {
            break;  // a damaged line ends what can be trusted
        }
        start = end + 1;
    }
    return rows;
}

std::string csvField(const nlohmann::json& v) {
    if (v.is_null()) return "";
    if (v.is_number_float()) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.10g", v.get<double>());
        return buf;
    }
    if (v.is_number() || v.is_boolean()) return v.dump();
    if (v.is_array()) {
        std::string s;
        for (const auto& x : v) s += (s.empty() ? "" : ";") + (x.is_string() ? x.get<std::string>() : x.dump());
        return s;
    }
    std::string s = v.is_string() ? v.get<std::string>() : v.dump();
    if (s.find_first_of(",\"\n") != std::string::npos) {
        std::string q = "\"";
        for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    }
    return s;
}

namespace {

std::string csvLine(const std::vector<std::string>& columns, const nlohmann::json& row) {
    std::string line;
    for (size_t i = 0; i < columns.size(); ++i) {
        if (i) line += ',';
        line += row.contains(columns[i]) ? csvField(row[columns[i]]) : "";
    }
    return line + "\n";
}

std::string header(const std::vector<std::string>& columns) {
    std::string h;
    for (const auto& c : columns) h += (h.empty() ? "" : ",") + c;
    return h + "\n";
}

}  // namespace

void ResultsWriter::writeAll(const std::string& dir, const std::vector<std::string>& columns,
                             std::vector<nlohmann::json> rows) {
    std::sort(rows.begin(), rows.end(),
              [](const nlohmann::json& a, const nlohmann::json& b) { return a["config"] < b["config"]; });
    std::string jsonl, csv = header(columns);
    for (const auto& r : rows) {
        jsonl += r.dump() + "\n";
        csv += csvLine(columns, r);
    }
    io::writeFileAtomic(dir + "/results.jsonl", jsonl);
    io::writeFileAtomic(dir + "/results.csv", csv);
}

ResultsWriter::ResultsWriter(const std::string& dir, const std::vector<std::string>& columns, bool resume)
    : m_columns(columns) {
    std::vector<nlohmann::json> kept;
    if (resume) kept = readRows(dir + "/results.jsonl");
    for (const auto& r : kept) m_done.insert(r["config"].get<long>());
    // Rewrite both files from the complete rows (in their original order), then append to them.
    std::string jsonl, csv = header(columns);
    for (const auto& r : kept) {
        jsonl += r.dump() + "\n";
        csv += csvLine(columns, r);
    }
    io::writeFileAtomic(dir + "/results.jsonl", jsonl);
    io::writeFileAtomic(dir + "/results.csv", csv);
    m_jsonl = std::fopen((dir + "/results.jsonl").c_str(), "ab");
    m_csv = std::fopen((dir + "/results.csv").c_str(), "ab");
    if (!m_jsonl || !m_csv) throw InputError("cannot append to the results in " + dir);
}

ResultsWriter::~ResultsWriter() {
    if (m_jsonl) std::fclose(m_jsonl);
    if (m_csv) std::fclose(m_csv);
}

void ResultsWriter::append(const nlohmann::json& row) {
    // One fwrite per line, then flush: a kill leaves at worst one torn last line, dropped on resume.
    const std::string j = row.dump() + "\n", c = csvLine(m_columns, row);
    std::fwrite(j.data(), 1, j.size(), m_jsonl);
    std::fflush(m_jsonl);
    std::fwrite(c.data(), 1, c.size(), m_csv);
    std::fflush(m_csv);
}

}  // namespace hilite::experiments
