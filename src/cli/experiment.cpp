#include "cli/experiment.hpp"

#include "core/error.hpp"
#include "io/image_io.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace hilite::cli {

namespace {


std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read experiment '" + path + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string line(const std::string& file, const toml::node& n) {
    return file + ":" + std::to_string(n.source().begin.line);
}

nlohmann::json typed(const std::string& v) {
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (!v.empty() && end == v.c_str() + v.size() && std::isfinite(d)) return d;
    return v;
}

SweepAxis parseAxis(const toml::table& t, const std::string& file, const CLI::App& app, std::vector<std::vector<SceneArg>>& args) {
    SweepAxis axis;
    const auto key = t["key"].value<std::string>();
    if (!key) throw InputError(line(file, t) + ": sweep: needs key = \"table.key\"");
    axis.key = *key;
    std::vector<SceneArg> out;
    if (const auto* range = t["range"].as_array()) {
        std::vector<double> r;
        for (const auto& x : *range)
            if (auto v = x.value<double>()) r.push_back(*v);
        if (r.size() != 3 || !(r[2] > 0) || r[1] < r[0])
            throw InputError(line(file, *range) + ": sweep " + axis.key + ": range = [start, stop, step], step > 0");
        const double count = std::floor((r[1] - r[0]) / r[2] + 1e-9) + 1;
        if (!std::isfinite(count) || count > double(kMaxConfigurations))
            throw InputError(line(file, *range) + ": sweep " + axis.key + ": range gives more than " +
                             std::to_string(kMaxConfigurations) + " values");
        const long n = long(count) - 1;
        for (long i = 0; i <= n; ++i) {
            const toml::value<double> v(r[0] + double(i) * r[2]);
            out.push_back(sceneArg(file, axis.key, v, app));
            out.back().origin = line(file, *range) + ": " + axis.key;
        }
    } else if (const auto* values = t["values"].as_array()) {
        for (const auto& v : *values) out.push_back(sceneArg(file, axis.key, v, app));
    } else {
        throw InputError(line(file, t) + ": sweep " + axis.key + ": needs values = [...] or range = [start, stop, step]");
    }
    if (out.empty()) throw InputError(line(file, t) + ": sweep " + axis.key + ": no values");
    for (const auto& a : out) axis.values.push_back(a.value);
    axis.args = out;
    args.push_back(out);
    return axis;
}

/// A throwaway CLI app with the measure flags: the schema every scene key is checked against.
struct Schema {
    CLI::App app;
    MeasureFlags flags;
    Schema() {
        app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
        addMeasureFlags(app, flags);
    }
};

}  // namespace

std::string findExperiment(const std::string& name) {
    if (access(name.c_str(), R_OK) == 0) return name;
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    std::string exeDir = n > 0 ? std::string(buf, size_t(n)) : "";
    exeDir = exeDir.substr(0, exeDir.rfind('/'));
    for (const std::string& dir : {exeDir + "/../share/hilite/experiments", std::string("experiments")})
        for (const std::string& cand : {dir + "/" + name, dir + "/" + name + ".toml"})
            if (access(cand.c_str(), R_OK) == 0) return cand;
    throw InputError("run: no experiment '" + name + "' (give a file, or a name from experiments/)");
}

Experiment loadExperiment(const std::string& path) { return parseExperiment(readText(path), path); }

Experiment parseExperiment(const std::string& text, const std::string& path) {
    Experiment e;
    e.path = path;
    e.text = text;
    toml::table doc;
    try {
        doc = toml::parse(e.text, path);
    } catch (const toml::parse_error& err) {
        throw InputError(path + ":" + std::to_string(err.source().begin.line) + ": TOML syntax error: " +
                         std::string(err.description()));
    }
    for (const auto& [k, v] : doc) {
        static const std::vector<std::string> allowed = {"experiment", "scene", "sweep", "match", "plot",
                                                         "contact_sheet", "summary"};
        const std::string table(k.str());
        if (std::find(allowed.begin(), allowed.end(), table) == allowed.end()) {
            const std::string hint = didYouMean(table, allowed);
            throw InputError(line(path, v) + ": " + table + ": unknown table" +
                             (hint.empty() ? std::string() : " (did you mean '" + hint + "'?)") +
                             "; allowed: experiment, scene, sweep, match, plot, contact_sheet, summary");
        }
    }
    const std::string stem = path.substr(path.rfind('/') + 1);
    e.name = doc["experiment"]["name"].value_or(stem.substr(0, stem.rfind('.')));
    e.title = doc["experiment"]["title"].value_or(e.name);
    e.description = doc["experiment"]["description"].value_or(std::string());
    Schema schema;
    if (const auto* scene = doc["scene"].as_table()) e.base = sceneArgs(*scene, path, schema.app);
    if (const auto* match = doc["match"].as_table()) e.match = sceneArgs(*match, path, schema.app);
    std::vector<std::vector<SceneArg>> ignored;
    if (const auto* sweeps = doc["sweep"].as_array())
        for (const auto& s : *sweeps) {
            if (!s.is_table()) throw InputError(line(path, s) + ": [[sweep]] entries are tables");
            e.axes.push_back(parseAxis(*s.as_table(), path, schema.app, ignored));
        }
    if (const auto* plots = doc["plot"].as_array())
        for (const auto& p : *plots) {
            const auto& t = *p.as_table();
            experiments::PlotSpec spec;
            spec.file = t["file"].value_or(std::string("plot.png"));
            spec.title = t["title"].value_or(std::string());
            spec.x = t["x"].value_or(std::string("incidence_deg"));
            spec.y = t["y"].value_or(std::string("aspect"));
            spec.series = t["series"].value_or(std::string());
            spec.xlabel = t["xlabel"].value_or(std::string());
            spec.ylabel = t["ylabel"].value_or(std::string());
            spec.key = t["key"].value_or(spec.key);
            if (const auto* th = t["theory"].as_array())
                for (const auto& c : *th)
                    if (const auto* pair = c.as_array(); pair && pair->size() == 2)
                        spec.theory.emplace_back((*pair)[0].value_or(std::string()), (*pair)[1].value_or(std::string()));
            e.plots.push_back(spec);
        }
    if (const auto* sheet = doc["contact_sheet"].as_table()) {
        e.sheetFile = (*sheet)["file"].value_or(e.sheetFile);
        e.sheetSize = (*sheet)["size"].value_or(e.sheetSize);
        e.sheetRowKey = (*sheet)["row_key"].value_or(std::string("material.model"));
        e.sheetColumnKey = (*sheet)["column_key"].value_or(std::string("light.incidence"));
        std::vector<std::vector<SceneArg>> rows, cols;
        toml::table rt{{"key", e.sheetRowKey}}, ct{{"key", e.sheetColumnKey}};
        if (auto* r = (*sheet)["rows"].as_array()) rt.insert("values", *r);
        if (auto* c = (*sheet)["columns"].as_array()) ct.insert("values", *c);
        e.sheetRows = parseAxis(rt, path, schema.app, rows).values;
        e.sheetColumns = parseAxis(ct, path, schema.app, cols).values;
    }
    if (const auto* summary = doc["summary"].as_table()) {
        e.summarySeries = (*summary)["series"].value_or(std::string());
        e.summaryX = (*summary)["x"].value_or(e.summaryX);
        if (const auto* at = (*summary)["at"].as_array())
            for (const auto& x : *at) e.summaryAt.push_back(x.value_or(0.0));
    }
    return e;
}

std::vector<Configuration> Experiment::configurations() const {
    // Each axis' flag arguments as parsed (validated, relative .brdf paths already resolved once).
    std::vector<std::vector<SceneArg>> axisArgs;
    for (const auto& a : axes) axisArgs.push_back(a.args);
    double total = 1;
    for (const auto& a : axisArgs) total *= double(a.size());
    if (total > double(kMaxConfigurations))
        throw InputError(path + ": the sweep axes give " + std::to_string(long(total)) + " configurations (at most " +
                         std::to_string(kMaxConfigurations) + ")");
    std::vector<Configuration> configs;
    std::vector<size_t> idx(axes.size(), 0);
    for (long index = 0;; ++index) {
        Configuration c;
        c.index = index;
        c.args = base;
        for (size_t a = 0; a < axes.size(); ++a) {
            c.args.push_back(axisArgs[a][idx[a]]);
            c.sweep[axes[a].key] = typed(axes[a].values[idx[a]]);
        }
        configs.push_back(c);
        size_t a = axes.size();
        while (a > 0 && ++idx[a - 1] == axisArgs[a - 1].size()) idx[--a] = 0;
        if (a == 0) break;
    }
    // Validate every configuration now, so a bad value fails before any row is written.
    for (const auto& c : configs) {
        Schema s;
        std::vector<std::string> argv;
        for (const auto& a : c.args) {
            argv.push_back(a.flag);
            if (!a.value.empty()) argv.push_back(a.value);
        }
        std::map<std::string, std::string> origins;
        for (const auto& a : c.args) origins[a.flag] = a.origin;
        std::reverse(argv.begin(), argv.end());
        try {
            s.app.parse(argv);
            resolveMeasure(s.flags);
        } catch (const CLI::ParseError& err) {
            throw InputError(withOrigin(err.what(), origins));
        } catch (const InputError& err) {
            throw InputError(withOrigin(err.what(), origins));
        }
    }
    return configs;
}

void writeExperimentCopy(const Experiment& e, const std::string& dir) {
    io::writeFileAtomic(dir + "/experiment.toml", e.text);
    std::error_code ec;
    const auto origin = std::filesystem::absolute(e.path, ec);
    io::writeFileAtomic(dir + "/experiment.origin", (ec ? e.path : origin.lexically_normal().string()) + "\n");
}

Experiment loadExperimentCopy(const std::string& dir) {
    const std::string copy = dir + "/experiment.toml";
    std::ifstream in(dir + "/experiment.origin");
    std::string origin;
    if (!std::getline(in, origin) || origin.empty()) return loadExperiment(copy);
    return parseExperiment(readText(copy), origin);
}

}  // namespace hilite::cli
