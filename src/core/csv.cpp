#include "core/csv.hpp"

#include "core/text.hpp"
#include "hilite/core/error.hpp"

#include <algorithm>
#include <sstream>

namespace hilite {

namespace {

/// The fields of a row: split at ',' and blanks, empty fields between separators kept only for ','.
std::vector<std::string> fieldsOf(const std::string& line) {
    std::vector<std::string> out;
    for (std::string part : split(line, ',')) {
        std::istringstream in(part);
        std::vector<std::string> words;
        for (std::string w; in >> w;) words.push_back(w);
        if (words.empty()) words.push_back("");  // an empty field: refused as not a number
        out.insert(out.end(), words.begin(), words.end());
    }
    return out;
}

}  // namespace

CsvNumbers parseCsvNumbers(const std::string& text, const std::string& name, size_t columns,
                           const std::string& rowName) {
    CsvNumbers t;
    std::istringstream in(text);
    int lineNo = 0;
    bool first = true;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto hash = line.find('#');
        if (hash != std::string::npos && line.find_first_not_of(" \t") == hash)
            t.source += line.substr(hash + 1) + "\n";
        line = line.substr(0, hash);
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        const auto fields = fieldsOf(line);
        std::vector<double> row;
        for (const auto& f : fields)
            if (auto v = parseNumber(f)) row.push_back(*v);
        const bool numbers = row.size() == fields.size();
        if (first && !numbers) {  // the column names
            first = false;
            t.header = line;
            continue;
        }
        first = false;
        if (!numbers || row.size() != columns)
            throw InputError(name + ":" + std::to_string(lineNo) + ": expected " +
                             (rowName.empty() ? std::to_string(columns) + " numbers per row" : rowName) + " (got '" +
                             line + "')");
        t.rows.push_back(row);
        t.lines.push_back(lineNo);
    }
    return t;
}

}  // namespace hilite
