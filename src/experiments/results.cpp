#include "experiments/results.hpp"

#include "core/files.hpp"
#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "hilite/core/error.hpp"
#include "hilite/scene/registry.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

namespace hilite::experiments {

namespace {

/// One row line longer than this is damage, not a row (the widest rows are a few KiB).
constexpr size_t kMaxRowBytes = 1u << 20;

void addRow(std::vector<nlohmann::json>& rows, const std::string& line, const std::string& name, long lineNo) {
    rows.push_back(parseRow(line, name, lineNo));
}

/// The results file opened for reading (nullptr when missing; a path that is not a regular file refused).
std::shared_ptr<std::ifstream> openRows(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return nullptr;
    requireRegularFile(path, "results");
    auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
    if (!*in) throw InputError("results: cannot read '" + path + "'");
    return in;
}

/// The next complete line of `in` (false at the end, and for a last line without its newline: torn).
bool nextLine(std::ifstream& in, std::string& line, const std::string& path) {
    if (!std::getline(in, line) || in.eof()) {
        if (in.bad()) throw InputError("results: cannot read '" + path + "'");
        return false;
    }
    return true;
}

}  // namespace

nlohmann::json parseRow(const std::string& line, const std::string& name, long lineNo) {
    const std::string at = name + ":" + std::to_string(lineNo) + ": ";
    if (line.size() > kMaxRowBytes) throw InputError(at + "damaged row (longer than 1 MiB)");
    nlohmann::json row;
    try {
        row = nlohmann::json::parse(line);
    } catch (const nlohmann::json::exception& e) {
        std::string why = e.what();
        if (const auto p = why.find("] "); p != std::string::npos) why = why.substr(p + 2);
        throw InputError(at + "damaged row, not JSON (" + why + "); remove the line or run without --resume");
    }
    if (!row.is_object()) throw InputError(at + "damaged row: expected a JSON object");
    const auto it = row.find("config");
    if (it == row.end() || !it->is_number_integer() || it->get<long long>() < 0)
        throw InputError(at + "config: damaged row: expected \"config\", a whole number >= 0");
    return row;
}

std::vector<nlohmann::json> parseRows(const std::string& text, const std::string& name) {
    std::vector<nlohmann::json> rows;
    size_t start = 0;
    long lineNo = 0;
    while (start < text.size()) {
        const size_t end = text.find('\n', start);
        if (end == std::string::npos) break;  // no newline: torn by a kill mid-write
        addRow(rows, text.substr(start, end - start), name, ++lineNo);
        start = end + 1;
    }
    return rows;
}

std::vector<nlohmann::json> readRows(const std::string& path) {
    std::vector<nlohmann::json> rows;
    forEachRow(path, [&](nlohmann::json&& r, long) { rows.push_back(std::move(r)); });
    return rows;
}

void forEachRow(const std::string& path, const std::function<void(nlohmann::json&&, long)>& f) {
    const auto in = openRows(path);
    if (!in) return;
    std::string line;
    for (long lineNo = 1; nextLine(*in, line, path); ++lineNo) f(parseRow(line, path, lineNo), lineNo);
}

Rows Rows::file(const std::string& path) {
    Rows r;
    r.m_path = path;
    forEachRow(path, [&](nlohmann::json&&, long) { ++r.m_size; });
    return r;
}

std::vector<nlohmann::json> Rows::materialize() const { return m_vec ? *m_vec : readRows(m_path); }

Rows::iterator Rows::begin() const {
    iterator it;
    if (m_vec) {
        it.m_vec = m_vec;
        return it;
    }
    it.m_path = m_path;
    it.m_in = openRows(m_path);
    it.m_end = !it.m_in;
    it.read();
    return it;
}

Rows::iterator Rows::end() const {
    iterator it;
    it.m_vec = m_vec;
    it.m_i = m_vec ? m_vec->size() : 0;
    return it;
}

void Rows::iterator::read() {
    if (m_end) return;
    std::string line;
    if (!nextLine(*m_in, line, m_path)) {
        m_end = true;
        m_in.reset();
        m_row = nullptr;
        return;
    }
    m_row = parseRow(line, m_path, ++m_line);
}

Rows::iterator& Rows::iterator::operator++() {
    if (m_vec) ++m_i;
    else read();
    return *this;
}

namespace {

uint64_t fnv1a(const char* data, size_t n, uint64_t h = 1469598103934665603ull) {
    for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
    return h;
}

std::string hex16(uint64_t h) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016" PRIx64, h);
    return hex;
}

/// The contents' hash of a data file (FNV-1a 64), computed once per path, size and modification time in a
/// process; "unreadable" when it cannot be read (resolving the scene refuses it then, naming the key).
std::string contentsHash(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec);
    const auto size = fs::file_size(p, ec);
    if (ec) return "unreadable";
    const auto mtime = fs::last_write_time(p, ec).time_since_epoch().count();
    if (ec) return "unreadable";
    static std::mutex mutex;
    static std::map<std::string, std::string> cache;
    const std::string key = p.string() + "|" + std::to_string(size) + "|" + std::to_string(mtime);
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (auto it = cache.find(key); it != cache.end()) return it->second;
    }
    std::ifstream in(p, std::ios::binary);
    if (!in) return "unreadable";
    uint64_t h = 1469598103934665603ull;
    std::vector<char> buf(1 << 20);
    while (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0) {
        h = fnv1a(buf.data(), size_t(in.gcount()), h);
        if (!in) break;
    }
    const std::string out = hex16(h) + ":" + std::to_string(size);
    const std::lock_guard<std::mutex> lock(mutex);
    return cache.emplace(key, out).first->second;
}

/// Every given value as text (List parameters in order), data-file paths made absolute and followed by their
/// contents' hash: the same file however the run named it, and a file edited since is another input.
std::string valuesText(const scene::Values& v) {
    std::string t;
    for (const auto& [name, value] : v.given()) {
        const scene::Param* p = scene::find(name);
        if (p && p->kind == scene::Kind::List) {
            for (const auto& one : v.list(name)) t += name + "[]=" + one.text + "\n";
            continue;
        }
        std::string text = value.text;
        if (p && p->kind == scene::Kind::Path && !text.empty()) {
            std::error_code ec;
            const auto abs = std::filesystem::weakly_canonical(text, ec);
            if (!ec) text = abs.string();
            text += " #" + contentsHash(text);
        }
        t += name + "=" + text + "\n";
    }
    return t;
}

std::string numbersText(const std::vector<double>& v) {
    std::string t;
    for (double x : v) t += exactText(x) + ",";
    return t;
}

/// [fit]: every option of the fit (experiments/fit.hpp FitOptions), so an edited [fit] is another experiment.
std::string fitText(const FitOptions& o) {
    std::string t = "fit: models=";
    for (const auto& m : o.models) t += m + ",";
    return t + " thresholds=" + numbersText(o.thresholds) + " weights=" + numbersText(o.weights) +
           " anisotropy=" + std::to_string(o.anisotropy) + " f0=" + std::to_string(o.f0) + " geometry=" + o.geometry +
           " fresnel=" + o.fresnel + " diffuse=" + o.diffuse + " rank_by=" + o.rankBy +
           " color=" + std::to_string(o.color) + " xtol=" + exactText(o.xtolAbs) +
           " max_evaluations=" + std::to_string(o.maxEvaluations) + "\n";
}

/// [bounces]: every setting of the study (experiments/bounces.hpp BounceSettings).
std::string bouncesText(const BounceSettings& s) {
    const micro::BounceOptions& o = s.options;
    return std::string("bounces: surface=") + micro::toString(o.surface) + " paths=" + std::to_string(o.paths) +
           " batches=" + std::to_string(o.batches) + " seed=" + std::to_string(o.seed) +
           " step=" + exactText(o.stepTexels) + " texels=" + std::to_string(s.texels) +
           " bumps_per_tile=" + std::to_string(s.bumpsPerTile) + "\n";
}

}  // namespace

std::string fingerprint(const Experiment& e, const Configuration& c) {
    std::string text = valuesText(c.values) + "reference:\n" + valuesText(c.reference) + "tags:" + c.tags.dump() + "\n";
    text += "timing:" + std::to_string(e.timing) + "," + std::to_string(e.repeats) + "," + std::to_string(e.warmup) +
            " reference_errors:" + std::to_string(e.referenceErrors) + " match:" + std::to_string(e.matching) + "\n" +
            valuesText(e.match);
    if (e.fit) text += fitText(*e.fit);
    if (e.bounces) text += bouncesText(*e.bounces);
    return hex16(fnv1a(text.data(), text.size()));  // FNV-1a 64 (Fowler, Noll, Vo): fast, stable across platforms
}

namespace {

/// What a row's columns show changed between the configuration it measured and `c`, or "". The keys the
/// configuration sets are compared first (an edit is most likely there), then every other column.
std::string whatDiffers(const nlohmann::json& row, const Configuration& c) {
    auto differs = [&](const scene::Param& p) -> std::string {
        if (p.column.empty() || !row.contains(p.column) || row[p.column].is_null()) return "";
        const nlohmann::json& was = row[p.column];
        const std::string now = c.values.text(p.name);
        if (now.empty()) return "";
        bool other = false;
        if (was.is_number()) {
            const auto n = parseNumber(now);
            other = n && std::abs(*n - was.get<double>()) > 1e-9 * std::max(1.0, std::abs(*n));
        } else if (was.is_string() && p.kind == scene::Kind::Choice) {
            other = was.get<std::string>() != now;
        }
        if (!other) return "";
        return " was measured with " + p.name + " = " + (was.is_string() ? was.get<std::string>() : csvField(was)) +
               ", the experiment now says " + now;
    };
    for (const auto& [name, value] : c.values.given())
        if (const scene::Param* p = scene::find(name))
            if (auto d = differs(*p); !d.empty()) return d;
    for (const scene::Param& p : scene::registry())
        if (!c.values.given(p.name))
            if (auto d = differs(p); !d.empty()) return d;
    return "";
}

}  // namespace

void checkRows(const std::vector<nlohmann::json>& rows, const std::string& file, const Experiment& e,
               const Configurations& configs) {
    for (size_t i = 0; i < rows.size(); ++i) checkRow(rows[i], file, long(i + 1), e, configs);
}

void checkRow(const nlohmann::json& r, const std::string& file, long lineNo, const Experiment& e,
              const Configurations& configs) {
    const long index = r["config"].get<long>();
    const std::string at = file + ":" + std::to_string(lineNo) + ": row " + std::to_string(lineNo) +
                           " (configuration " + std::to_string(index) + ")";
    if (index < 0 || size_t(index) >= configs.size())
        throw InputError(at + ": the experiment '" + e.path + "' has only " + std::to_string(configs.size()) +
                         " configurations: these results are of another experiment (run without --resume, or "
                         "into another folder)");
    const auto fp = r.find("fingerprint");
    if (fp == r.end() || !fp->is_string())
        throw InputError(at +
                         ": fingerprint: the row has none (written by an older hilite): its configuration "
                         "cannot be checked; run without --resume, or into another folder");
    const Configuration c = configs[size_t(index)];
    const std::string now = fingerprint(e, c);
    if (fp->get<std::string>() == now) return;
    const std::string diff = whatDiffers(r, c);
    throw InputError(at +
                     (diff.empty() ? " was measured with another configuration (fingerprint " + fp->get<std::string>() +
                                         ", the experiment now gives " + now + ")"
                                   : diff) +
                     ": the results are of another or an edited experiment; run without --resume, or into "
                     "another folder");
}

void nameNonFinite(nlohmann::json& row) {
    std::string bad;
    for (auto& [k, v] : row.items())
        if (v.is_number_float() && !std::isfinite(v.get<double>())) {
            bad += (bad.empty() ? "" : ",") + k;
            v = nullptr;
        }
    if (bad.empty()) return;
    if (!row.contains("flags") || !row["flags"].is_array()) row["flags"] = nlohmann::json::array();
    row["flags"].push_back("non_finite:" + bad);
}

std::string csvField(const nlohmann::json& v) {
    if (v.is_null()) return "";
    if (v.is_number_float()) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.10g", v.get<double>());
        return buf;
    }
    if (v.is_number() || v.is_boolean()) return v.dump();
    std::string s;
    if (v.is_array())  // flags: "horizon_cut;non_finite:a,b", quoted below like any text with a comma
        for (const auto& x : v) s += (s.empty() ? "" : ";") + (x.is_string() ? x.get<std::string>() : x.dump());
    else s = v.is_string() ? v.get<std::string>() : v.dump();
    if (s.find_first_of(",\"\n\r") != std::string::npos) {  // RFC 4180
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

std::vector<nlohmann::json> resumedRows(const std::string& dir, const Experiment& e, const Configurations& configs) {
    std::vector<nlohmann::json> kept = readRows(dir + "/results.jsonl");
    checkRows(kept, dir + "/results.jsonl", e, configs);  // before anything is rewritten
    std::set<long> seen;
    for (const auto& r : kept)
        if (!seen.insert(r["config"].get<long>()).second)
            throw InputError(dir + "/results.jsonl: configuration " + r["config"].dump() + " appears twice");
    return kept;
}

ResultsWriter::ResultsWriter(const std::string& dir, const std::vector<std::string>& columns, bool resume,
                             const Experiment& e, const Configurations& configs, double syncInterval)
    : m_columns(columns), m_dir(dir), m_syncInterval(syncInterval), m_lastSync(std::chrono::steady_clock::now()) {
    const std::vector<nlohmann::json> kept = resume ? resumedRows(dir, e, configs) : std::vector<nlohmann::json>{};
    for (const auto& r : kept) m_done.insert(r["config"].get<long>());
    // Rewrite both files from the complete rows (in their original order), then append to them.
    std::string jsonl, csv = header(columns);
    for (const auto& r : kept) {
        jsonl += r.dump() + "\n";
        csv += csvLine(columns, r);
    }
    io::writeFileAtomic(dir + "/results.jsonl", jsonl);
    io::writeFileAtomic(dir + "/results.csv", csv);
    m_jsonl = std::make_unique<io::DurableAppender>(dir + "/results.jsonl");
    m_csv = std::make_unique<io::DurableAppender>(dir + "/results.csv");
}

void ResultsWriter::append(const nlohmann::json& row) {
    // One write per line: a kill or a full disk leaves at worst one torn last line, dropped on resume. The JSON
    // row first: it is what --resume trusts; the CSV is rewritten from it. An fsync per row cost 2-9 ms on a busy
    // ext4 disk, the measurement itself 1.5 ms: rows are made durable together (group commit, as databases do).
    try {
        m_jsonl->append(row.dump() + "\n", false);
        m_csv->append(csvLine(m_columns, row), false);
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - m_lastSync).count() >= m_syncInterval) {
            m_jsonl->sync();
            ++m_syncs;
            m_lastSync = std::chrono::steady_clock::now();
        }
    } catch (const SystemError& e) {
        throw SystemError(std::string(e.what()) + "; the " + std::to_string(m_done.size()) +
                          " rows written before are intact: free space and rerun with --resume to finish");
    }
    m_done.insert(row["config"].get<long>());
}

void ResultsWriter::finish() {
    m_jsonl->sync();
    ++m_syncs;
    m_csv->sync();
}

std::string csvHeaderLine(const std::vector<std::string>& columns) { return header(columns); }
std::string csvRowLine(const std::vector<std::string>& columns, const nlohmann::json& row) {
    return csvLine(columns, row);
}

}  // namespace hilite::experiments
