#include "experiments/experiment.hpp"

#include "brdf/materials.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "io/image_io.hpp"
#include "scene/scene_file.hpp"

#include "experiments/reports.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace hilite::experiments {

namespace {

std::string readText(const std::string& path) { return scene::readTextFile(path, "experiment"); }

std::string line(const std::string& file, const toml::node& n) {
    return file + ":" + std::to_string(n.source().begin.line);
}

nlohmann::json typed(const std::string& v) {
    const auto d = parseNumber(v);
    if (d && std::isfinite(*d)) return *d;
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
scene::Values caseValues(const toml::table& t, const std::string& file, const std::string& what,
                         std::initializer_list<const char*> special) {
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
    return scene::sceneValues(scene, file);
}

/// `cases = [{ name = "...", tags = {...}, reference = {...}, material = {...}, ... }, ...]`.
std::vector<SweepCase> parseCases(const toml::array& cases, const std::string& file, const std::string& key) {
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
        if (const auto* ref = (*t)["reference"].as_table()) sc.reference = caseValues(*ref, file, what + " reference", {});
        sc.values = caseValues(*t, file, what, {"name", "tags", "reference"});
        out.push_back(sc);
    }
    return out;
}

SweepAxis parseAxis(const toml::table& t, const std::string& file) {
    SweepAxis axis;
    const auto key = t["key"].value<std::string>();
    if (!key) throw InputError(line(file, t) + ": sweep: needs key = \"table.key\"");
    axis.key = *key;
    auto add = [&](const toml::node& v, const std::string& origin) {
        scene::Values one;
        scene::setKey(one, file, axis.key, v);
        if (!origin.empty()) {  // a range's values all come from its line
            const auto& [name, value] = *one.given().begin();
            scene::Values relabelled;
            relabelled.set(name, value.text, origin);
            one = relabelled;
        }
        axis.values.push_back(one.given().begin()->second.text);
        axis.entries.push_back(one);
    };
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
            add(v, line(file, *range) + ": " + axis.key);
        }
    } else if (const auto* values = t["values"].as_array()) {
        for (const auto& v : *values) add(v, "");
    } else if (const auto* cases = t["cases"].as_array()) {
        axis.cases = parseCases(*cases, file, axis.key);
        if (axis.cases.empty()) throw InputError(line(file, t) + ": sweep " + axis.key + ": no cases");
        for (const auto& c : axis.cases) axis.values.push_back(c.name);
        return axis;
    } else {
        throw InputError(line(file, t) + ": sweep " + axis.key +
                         ": needs values = [...], range = [start, stop, step] or cases = [{ name = ..., ... }]");
    }
    if (axis.entries.empty()) throw InputError(line(file, t) + ": sweep " + axis.key + ": no values");
    return axis;
}

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

/// [reference], [timing] and [pareto]: the tables of an accuracy/cost study.
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

namespace {

/// Every top-level table must be one an experiment has.
void checkTables(const toml::table& doc, const std::string& path) {
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
}

void parsePlots(toml::table& doc, const std::string& path, Experiment& e) {
    if (const auto* plots = doc["plot"].as_array())
        for (const auto& p : *plots) {
            if (!p.is_table()) throw InputError(line(path, p) + ": [[plot]] entries are tables");
            const auto& t = *p.as_table();
            PlotSpec spec;
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
}

void parseSheet(toml::table& doc, const std::string& path, Experiment& e) {
    if (const auto* sheet = doc["contact_sheet"].as_table()) {
        e.sheetFile = (*sheet)["file"].value_or(e.sheetFile);
        e.sheetSize = (*sheet)["size"].value_or(e.sheetSize);
        e.sheetRowKey = (*sheet)["row_key"].value_or(std::string("material.model"));
        e.sheetColumnKey = (*sheet)["column_key"].value_or(std::string("light.incidence"));
        toml::table rt{{"key", e.sheetRowKey}}, ct{{"key", e.sheetColumnKey}};
        if (auto* r = (*sheet)["rows"].as_array()) rt.insert("values", *r);
        if (auto* c = (*sheet)["columns"].as_array()) ct.insert("values", *c);
        const SweepAxis rows = parseAxis(rt, path), cols = parseAxis(ct, path);
        e.sheetRows = rows.values, e.sheetRowValues = rows.entries;
        e.sheetColumns = cols.values, e.sheetColumnValues = cols.entries;
    }
}

void parseStrips(toml::table& doc, const std::string& path, Experiment& e) {
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
}

void parseSummary(toml::table& doc, const std::string& path, Experiment& e) {
    if (const auto* summary = doc["summary"].as_table()) {
        e.summarySeries = (*summary)["series"].value_or(std::string());
        e.summaryX = (*summary)["x"].value_or(e.summaryX);
        if (const auto* at = (*summary)["at"].as_array())
            for (const auto& x : *at) e.summaryAt.push_back(x.value_or(0.0));
        if (const auto* sections = (*summary)["sections"].as_array())
            for (const auto& x : *sections) {
                const auto name = x.value<std::string>();
                if (!name || !isReportSection(*name))
                    throw InputError(line(path, x) + ": summary.sections: unknown section (allowed: " +
                                     join(reportSections()) + ")");
                e.sections.push_back(*name);
            }
        else if (!e.summarySeries.empty())
            e.sections.push_back("shape");
    }
}

}  // namespace

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
    checkTables(doc, path);
    const std::string stem = path.substr(path.rfind('/') + 1);
    e.name = doc["experiment"]["name"].value_or(stem.substr(0, stem.rfind('.')));
    e.title = doc["experiment"]["title"].value_or(e.name);
    e.description = doc["experiment"]["description"].value_or(std::string());
    if (const auto* scene = doc["scene"].as_table()) e.base = scene::sceneValues(*scene, path);
    if (const auto* match = doc["match"].as_table()) {
        e.match = scene::sceneValues(*match, path);
        e.matching = !e.match.given().empty();
    }
    if (const auto* sweeps = doc["sweep"].as_array())
        for (const auto& s : *sweeps) {
            if (!s.is_table()) throw InputError(line(path, s) + ": [[sweep]] entries are tables");
            e.axes.push_back(parseAxis(*s.as_table(), path));
        }
    parsePlots(doc, path, e);
    parseSheet(doc, path, e);
    parseStrips(doc, path, e);
    parseSummary(doc, path, e);
    parseErrorTables(doc, path, e);
    return e;
}

std::vector<Configuration> Experiment::configurations() const {
    double total = 1;
    for (const auto& a : axes) total *= double(a.values.size());
    if (total > double(kMaxConfigurations))
        throw InputError(path + ": the sweep axes give " + std::to_string(long(total)) + " configurations (at most " +
                         std::to_string(kMaxConfigurations) + ")");
    std::vector<Configuration> configs;
    std::vector<size_t> idx(axes.size(), 0);
    for (long index = 0;; ++index) {
        Configuration c;
        c.index = index;
        c.values = base;
        for (size_t a = 0; a < axes.size(); ++a) {
            c.sweep[axes[a].key] = typed(axes[a].values[idx[a]]);
            if (axes[a].cases.empty()) {
                c.values.merge(axes[a].entries[idx[a]]);
                continue;
            }
            const SweepCase& sc = axes[a].cases[idx[a]];
            c.values.merge(sc.values);
            c.reference.merge(sc.reference);
            c.tags[axes[a].key] = sc.name;
            for (const auto& [k, v] : sc.tags.items()) c.tags[k] = v;
        }
        configs.push_back(c);
        size_t a = axes.size();
        while (a > 0 && ++idx[a - 1] == axes[a - 1].values.size()) idx[--a] = 0;
        if (a == 0) break;
    }
    // Validate every configuration now, so a bad value fails before any row is written (the reference scene
    // must be valid too).
    for (const auto& c : configs) {
        scene::Values all = c.values;
        all.merge(c.reference);
        scene::resolve(all);
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

}  // namespace hilite::experiments
