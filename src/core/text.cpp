#include "core/text.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>

namespace hilite {

std::optional<double> parseNumber(const std::string& text) {
    const char* first = text.data();
    const char* last = text.data() + text.size();
    if (first != last && *first == '+') {
        ++first;
        if (first != last && *first == '-') return std::nullopt;  // "+-1"
    }
    if (first == last) return std::nullopt;
    double v = 0;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || end != last) return std::nullopt;
    return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string cur;
    std::istringstream in(s);
    while (std::getline(in, cur, sep)) out.push_back(cur);
    if (!s.empty() && s.back() == sep) out.push_back("");
    return out;
}

std::string join(const std::vector<std::string>& items, const std::string& sep) {
    std::string out;
    for (const auto& i : items) out += (out.empty() ? "" : sep) + i;
    return out;
}

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string exactText(double v) {
    for (int digits = 15; digits <= 17; ++digits) {
        std::ostringstream s;
        s.precision(digits);
        s << v;
        if (digits == 17 || parseNumber(s.str()) == v) return s.str();
    }
    return "";
}

std::string rangeText(double lo, double hi, bool openLo, bool openHi) {
    auto bound = [](double v) {
        const std::string shortText = fmt(v);
        return parseNumber(shortText) == v ? shortText : exactText(v);
    };
    return std::string(openLo ? "(" : "[") + bound(lo) + ", " + bound(hi) + (openHi ? ")" : "]");
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
    auto distance = [](const std::string& a, const std::string& b) {
        std::vector<size_t> row(b.size() + 1);
        for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
        for (size_t i = 1; i <= a.size(); ++i) {
            size_t diag = row[0];
            row[0] = i;
            for (size_t j = 1; j <= b.size(); ++j) {
                const size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
                diag = up;
            }
        }
        return row[b.size()];
    };
    std::string best;
    size_t bestD = std::max<size_t>(3, word.size() / 3) + 1;
    for (const auto& c : candidates) {
        const size_t d = distance(word, c);
        if (d < bestD) bestD = d, best = c;
    }
    return best;
}

std::string printable(std::string s) {
    if (s.size() > 80) s = s.substr(0, 77) + "...";
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return s;
}

}  // namespace hilite
