#include "cli/experiment.hpp"

#include "core/error.hpp"
#include "brdf/materials.hpp"
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

/// A scalar TOML value as JSON (tags are strings, numbers or booleans).
nlohmann::json scalar(const toml::node& v, const std::string& where) {
    if (auto x = v.value_exact<std::string>()) return *x;
    if (auto x = v.value_exact<bool>()) return *x;
    if (auto x = v.value<double>()) return *x;
    throw InputError(where + ": a tag is a string, a number or a boolean");
}

/// Scene tables of a case (or of its `reference`), each key checked against the schema.
std::vector<SceneArg> caseArgs(const toml::table& t, const std::string& file, const std::string& what,
                               const CLI::App& app, std::initializer_list<const char*> special) {
    toml::table scene;
    for (const auto& [k, v] : t) {
        const std::string key(k.str());
        if (std::find_if(special.begin(), special.end(), [&](const char* s) { return key == s; }) != special.end())
            continue;
        if (!v.is_table())
            throw InputError(line(file, v) + ": " + what + ": " + key +
                             ": unknown key (allowed: name, tags, reference and the scene tables material, light, "
                             "camera, measurement)");
        scene.insert(key, *v.as_table());
    }
    return sceneArgs(scene, file, app);
}

/// `cases = [{ name = "...", tags = {...}, reference = {...}, material = {...}, ... }, ...]`.
std::vector<SweepCase> parseCases(const toml::array& cases, const std::string& file, const std::string& key,
                                  const CLI::App& app) {
    std::vector<SweepCase> out;
    for (const auto& c : cases) {
        const auto* t = c.as_table();
        if (!t) throw InputError(line(file, c) + ": sweep " + key + ": each case is a table { name = \"...\", ... }");
        SweepCase sc;
        const auto name = (*t)["name"].value<std::string>();
        if (!name || name->empty()) throw InputError(line(file, c) + ": sweep " + key + ": a case needs name = \"...\"");
        sc.name = *name;
        for (const auto& o : out)
            if (o.name == sc.name) throw InputError(line(file, c) + ": sweep " + key + ": two cases named '" + sc.name + "'");
        const std::string what = "sweep " + key + " case '" + sc.name + "'";
        sc.tags = nlohmann::json::object();
        for (const char* k : {"tags", "reference"})  // both are tables; anything else would be dropped silently
            if ((*t)[k] && !(*t)[k].is_table())
                throw InputError(line(file, *(*t)[k].node()) + ": " + what + ": " + k + " = { ... } (a table)");
        if (const auto* tags = (*t)["tags"].as_table())
            for (const auto& [k, v] : *tags) sc.tags[std::string(k.str())] = scalar(v, line(file, v) + ": " + what);
        if (const auto* ref = (*t)["reference"].as_table()) sc.reference = caseArgs(*ref, file, what + " reference", app, {});
        sc.args = caseArgs(*t, file, what, app, {"name", "tags", "reference"});
        out.push_back(sc);
    }
    return out;
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
    } else if (const auto* cases = t["cases"].as_array()) {
        axis.cases = parseCases(*cases, file, axis.key, app);
        if (axis.cases.empty()) throw InputError(line(file, t) + ": sweep " + axis.key + ": no cases");
        for (const auto& c : axis.cases) axis.values.push_back(c.name);
        return axis;
    } else {
        throw InputError(line(file, t) + ": sweep " + axis.key +
                         ": needs values = [...], range = [start, stop, step] or cases = [{ name = ..., ... }]");
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

namespace {

int wholeNumber(const toml::node_view<toml::node>& v, const std::string& file, const std::string& key, int lo, int hi,
                int fallback) {
    if (!v) return fallback;
    const auto x = v.value_exact<int64_t>();
    if (!x || *x < lo || *x > hi)
        throw InputError(line(file, *v.node()) + ": " + key + ": a whole number in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]");
    return int(*x);
}

/// [reference], [timing] and [pareto]: the tables of an accuracy/cost study (issue 7).
void parseErrorTables(toml::table& doc, const std::string& path, Experiment& e) {
    if (const auto* ref = doc["reference"].as_table()) e.referenceErrors = (*ref)["errors"].value_or(true);
    if (doc["timing"].as_table()) {
        e.timing = true;
        e.repeats = wholeNumber(doc["timing"]["repeats"], path, "timing.repeats", 1, 1000, 5);
        e.warmup = wholeNumber(doc["timing"]["warmup"], path, "timing.warmup", 0, 1000, 1);
    }
    if (const auto* pareto = doc["pareto"].as_array()) {
        for (const auto& p : *pareto) {
            const auto* t = p.as_table();
            if (!t) throw InputError(line(path, p) + ": [[pareto]] entries are tables");
            ParetoSpec spec;
            spec.file = (*t)["file"].value_or(spec.file);
            spec.title = (*t)["title"].value_or(spec.title);
            spec.setting = (*t)["setting"].value_or(spec.setting);
            spec.series = (*t)["series"].value_or(spec.series);
            spec.error = (*t)["error"].value_or(spec.error);
            spec.time = (*t)["time"].value_or(spec.time);
            if (const auto* targets = (*t)["targets"].as_array())
                for (const auto& x : *targets) spec.targets.push_back(x.value_or(0.0));
            e.pareto.push_back(spec);
        }
    } else if (doc["pareto"]) {
        throw InputError(line(path, *doc["pareto"].node()) + ": pareto: write it as [[pareto]] (one per plot)");
    }
}

}  // namespace

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
                                                         "contact_sheet", "strip", "summary", "reference", "timing", "pareto"};
        const std::string table(k.str());
        if (std::find(allowed.begin(), allowed.end(), table) == allowed.end()) {
            const std::string hint = didYouMean(table, allowed);
            throw InputError(line(path, v) + ": " + table + ": unknown table" +
                             (hint.empty() ? std::string() : " (did you mean '" + hint + "'?)") +
                             "; allowed: experiment, scene, sweep, match, plot, contact_sheet, strip, summary, reference, "
                             "timing, pareto");
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
            spec.logx = t["logx"].value_or(false);
            spec.logy = t["logy"].value_or(false);
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
    if (const auto* strips = doc["strip"].as_array())
        for (const auto& st : *strips) {
            const auto* t = st.as_table();
            const auto material = t ? (*t)["material"].value<std::string>() : std::nullopt;
            if (!material) throw InputError(line(path, st) + ": [[strip]] needs material = \"NAME\"");
            if (!brdf::findMaterial(*material)) {
                std::string all;
                for (const auto& m : brdf::materialNames()) all += (all.empty() ? "" : ", ") + m;
                throw InputError(line(path, st) + ": strip.material: unknown '" + *material + "' (allowed: " + all + ")");
            }
            e.strips.emplace_back(*material, (*t)["file"].value_or(*material + "_strip.png"));
        }
    if (const auto* summary = doc["summary"].as_table()) {
        e.summarySeries = (*summary)["series"].value_or(std::string());
        e.summaryX = (*summary)["x"].value_or(e.summaryX);
        if (const auto* at = (*summary)["at"].as_array())
            for (const auto& x : *at) e.summaryAt.push_back(x.value_or(0.0));
    }
    parseErrorTables(doc, path, e);
    return e;
}

std::vector<Configuration> Experiment::configurations() const {
    // Each axis' flag arguments as parsed (validated, relative .brdf paths already resolved once).
    std::vector<std::vector<SceneArg>> axisArgs;
    // Each axis' flag arguments (validated when the file was read, with their file:line); a case axis has
    // its own per case.
    for (const auto& a : axes) {
        if (!a.cases.empty()) axisArgs.push_back(std::vector<SceneArg>(a.cases.size()));  // placeholders: see below
        else axisArgs.push_back(a.args);
    }
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
            c.sweep[axes[a].key] = typed(axes[a].values[idx[a]]);
            if (axes[a].cases.empty()) {
                c.args.push_back(axisArgs[a][idx[a]]);
                continue;
            }
            const SweepCase& sc = axes[a].cases[idx[a]];
            c.args.insert(c.args.end(), sc.args.begin(), sc.args.end());
            c.reference.insert(c.reference.end(), sc.reference.begin(), sc.reference.end());
            c.tags[axes[a].key] = sc.name;
            for (const auto& [k, v] : sc.tags.items()) c.tags[k] = v;
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
        std::vector<SceneArg> all = c.args;  // the reference scene must be valid too
        all.insert(all.end(), c.reference.begin(), c.reference.end());
        for (const auto& a : all) {
            argv.push_back(a.flag);
            if (!a.value.empty()) argv.push_back(a.value);
        }
        std::map<std::string, std::string> origins;
        for (const auto& a : all) origins[a.flag] = a.origin;
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
