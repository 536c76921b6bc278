#include "experiments/experiment.hpp"

#include "brdf/materials.hpp"
#include "core/install_paths.hpp"
#include "core/text.hpp"
#include "hilite/core/error.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/scene/scene_file.hpp"
#include "io/image_io.hpp"

#include "experiments/reports.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

namespace hilite::experiments {

namespace fs = std::filesystem;

namespace {

std::string readText(const std::string& path) { return scene::readTextFile(path, "experiment"); }

std::string line(const std::string& file, const toml::node& n) {
    return file + ":" + std::to_string(n.source().begin.line);
}

/// toml++'s name of a value's type, for "expected a string (got an integer)".
std::string typeName(const toml::node& n) {
    switch (n.type()) {
        case toml::node_type::table: return "a table";
        case toml::node_type::array: return "an array";
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a number";
        case toml::node_type::boolean: return "a boolean";
        default: return "a date or time";
    }
}

/// One table of an experiment file with a fixed set of keys: an unknown key is refused (with a did-you-mean
/// hint, as scene files do), and each typed read refuses a value of another type, naming file:line: table.key.
class Fields {
public:
    Fields(const toml::table& t, const std::string& file, std::string table, std::vector<std::string> allowed)
        : m_t(t), m_file(file), m_table(std::move(table)), m_allowed(std::move(allowed)) {
        for (const auto& [k, v] : t) {
            const std::string key(k.str());
            if (std::find(m_allowed.begin(), m_allowed.end(), key) != m_allowed.end()) continue;
            const std::string hint = didYouMean(key, m_allowed);
            throw InputError(line(file, v) + ": " + m_table + "." + key + ": unknown key" +
                             (hint.empty() ? "" : ", did you mean '" + hint + "'?") + " (allowed: " + join(m_allowed) +
                             ")");
        }
    }
    const toml::node* node(const std::string& key) const { return m_t.get(key); }
    /// "file:line: table.key", the line of the value (of the table when the key is absent).
    std::string at(const std::string& key) const {
        const toml::node* n = node(key);
        return line(m_file, n ? *n : static_cast<const toml::node&>(m_t)) + ": " + m_table + "." + key;
    }
    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        throw InputError(at(key) + ": " + message);
    }
    std::optional<std::string> string(const std::string& key) const {
        const toml::node* n = node(key);
        if (!n) return std::nullopt;
        if (!n->is_string()) fail(key, "expected a string (got " + typeName(*n) + ")");
        return n->as_string()->get();
    }
    std::string string(const std::string& key, const std::string& fallback) const {
        return string(key).value_or(fallback);
    }
    bool boolean(const std::string& key, bool fallback) const {
        const toml::node* n = node(key);
        if (!n) return fallback;
        if (!n->is_boolean()) fail(key, "expected true or false (got " + typeName(*n) + ")");
        return n->as_boolean()->get();
    }
    const toml::array* array(const std::string& key) const {
        const toml::node* n = node(key);
        if (n && !n->is_array()) fail(key, "expected an array [...] (got " + typeName(*n) + ")");
        return n ? n->as_array() : nullptr;
    }
    std::vector<double> numbers(const std::string& key) const {
        std::vector<double> out;
        if (const auto* a = array(key))
            for (const auto& x : *a) {
                const auto v = x.is_number() ? x.value<double>() : std::nullopt;
                if (!v || !std::isfinite(*v)) fail(key, "expected finite numbers (got " + typeName(x) + ")");
                out.push_back(*v);
            }
        return out;
    }
    std::vector<std::string> strings(const std::string& key) const {
        std::vector<std::string> out;
        if (const auto* a = array(key))
            for (const auto& x : *a) {
                if (!x.is_string()) fail(key, "expected strings (got " + typeName(x) + ")");
                out.push_back(x.as_string()->get());
            }
        return out;
    }
    /// The name of a file the experiment writes: in the output folder, with the picture extension.
    std::string outputFile(const std::string& key, const std::string& fallback) const {
        const std::string name = string(key, fallback);
        const std::string why = outputNameError(name, kPictureExtension);
        if (!why.empty())
            fail(key, "'" + printable(name) + "': " + why + " (a file name in the output folder, e.g. plot.png)");
        return name;
    }
    const std::string& file() const { return m_file; }
    const std::string& table() const { return m_table; }
    const toml::table& raw() const { return m_t; }

private:
    const toml::table& m_t;
    const std::string& m_file;
    std::string m_table;
    std::vector<std::string> m_allowed;
};

/// The pictures the reports write, each claimed with where it was named: two plots named alike would
/// overwrite each other's picture, data and script (stem.png, stem.dat, stem.gp). The result files
/// (results.csv, results.jsonl, experiment.toml, summary.md) are safe by the fixed .png extension.
class Names {
public:
    void claim(const std::string& file, const std::string& where, const std::string& what = "") {
        const std::string stem = file.substr(0, file.rfind('.'));
        const auto [it, fresh] = m_used.emplace(stem, where);
        if (!fresh)
            throw InputError(where + ": " + what + "'" + file + "' is also written by " + it->second +
                             " (each picture needs its own name)");
    }

private:
    std::map<std::string, std::string> m_used;  ///< stem -> "file:line: table.key" that named it
};

nlohmann::json typed(const std::string& v) {
    const auto d = parseNumber(v);
    if (d && std::isfinite(*d)) return *d;
    return v;
}

nlohmann::json scalar(const toml::node& v, const std::string& where) {
    if (auto x = v.value_exact<std::string>()) return *x;
    if (auto x = v.value_exact<bool>()) return *x;
    if (auto x = v.value<double>(); x && v.is_number() && std::isfinite(*x)) return *x;
    throw InputError(where + ": a tag is a string, a finite number or a boolean (got " + typeName(v) + ")");
}

/// "the scene tables material, light, ..." for messages, from the registry.
std::string sceneTables() {
    std::vector<std::string> names;
    for (scene::Table t : scene::tables()) names.emplace_back(scene::toString(t));
    return "the scene tables " + join(names);
}

/// Scene tables of a case (or of its `reference`), each key checked against the schema.
scene::Values caseValues(const toml::table& t, const std::string& file, const std::string& what,
                         std::initializer_list<const char*> special) {
    scene::Values out;
    for (const auto& [k, v] : t) {
        const std::string key(k.str());
        if (std::find_if(special.begin(), special.end(), [&](const char* s) { return key == s; }) != special.end())
            continue;
        if (!v.is_table())
            throw InputError(line(file, v) + ": " + what + "." + key + ": unknown key (allowed: " +
                             (special.size() ? "name, tags, reference and " : "") + sceneTables() + ")");
        // Key by key from the file's own nodes: a copied table would lose their lines (messages said "file:0").
        for (const auto& [name, value] : *v.as_table())
            scene::setKey(out, file, key + "." + std::string(name.str()), value);
    }
    return out;
}

/// `cases = [{ name = "...", tags = {...}, reference = {...}, material = {...}, ... }, ...]`.
std::vector<SweepCase> parseCases(const toml::array& cases, const std::string& file, const std::string& key) {
    std::vector<SweepCase> out;
    for (const auto& c : cases) {
        const auto* t = c.as_table();
        if (!t)
            throw InputError(line(file, c) + ": sweep.cases: each case is a table { name = \"...\", ... } (got " +
                             typeName(c) + ")");
        SweepCase sc;
        const toml::node* nameNode = t->get("name");
        if (!nameNode || !nameNode->is_string() || nameNode->as_string()->get().empty())
            throw InputError(line(file, nameNode ? *nameNode : c) + ": sweep.cases.name: a case of " + key +
                             " needs name = \"...\" (a non-empty string)");
        sc.name = nameNode->as_string()->get();
        for (const auto& o : out)
            if (o.name == sc.name)
                throw InputError(line(file, c) + ": sweep.cases.name: two cases of " + key + " named '" + sc.name +
                                 "'");
        const std::string what = "sweep.cases";
        sc.tags = nlohmann::json::object();
        for (const char* k : {"tags", "reference"})  // both are tables; anything else would be dropped silently
            if ((*t)[k] && !(*t)[k].is_table())
                throw InputError(line(file, *(*t)[k].node()) + ": " + what + "." + k +
                                 ": expected a table { ... } (got " + typeName(*(*t)[k].node()) + ")");
        if (const auto* tags = (*t)["tags"].as_table())
            for (const auto& [k, v] : *tags) {
                const std::string tag(k.str());
                if (tag == "config" || tag == key)  // the index column, or the axis's own column
                    throw InputError(line(file, v) + ": sweep.cases.tags." + tag + ": a tag cannot be named like the " +
                                     (tag == "config" ? "configuration index column" : "axis"));
                sc.tags[tag] = scalar(v, line(file, v) + ": sweep.cases.tags." + tag);
            }
        if (const auto* ref = (*t)["reference"].as_table())
            sc.reference = caseValues(*ref, file, what + ".reference", {});
        sc.values = caseValues(*t, file, what, {"name", "tags", "reference"});
        out.push_back(sc);
    }
    return out;
}

/// The values of a sweep axis or of a contact sheet's rows or columns: one scene assignment each.
void addValues(SweepAxis& axis, const toml::array& values, const std::string& file) {
    for (const auto& v : values) {
        scene::Values one;
        scene::setKey(one, file, axis.key, v);
        if (one.given().empty())  // an empty list of NAME=VALUE assignments: nothing to sweep
            throw InputError(line(file, v) + ": " + axis.key + ": an empty value");
        axis.values.push_back(one.given().begin()->second.text);
        axis.entries.push_back(one);
    }
}

/// `folder = DIR` with `own_ndf = { geometry = ..., fresnel = ..., ... }` (material keys): a case axis, column
/// `source`, with a case per file (the measured material, named by the file's stem) and, for each RGL .bsdf, one
/// more: the microfacet model of the file's own NDF (model tabulated, ndf_table = the file, and own_ndf's keys),
/// named "STEM own NDF". Tags: material_file (the file's name) and variant ("measured" or "own NDF").
SweepAxis ownNdfAxis(const Fields& f, const std::string& file, const std::string& dir,
                     const std::vector<std::string>& names) {
    if (!f.node("own_ndf")->is_table())
        f.fail("own_ndf", "expected a table of material keys, e.g. { geometry = \"smith\", fresnel = \"schlick\" }");
    toml::table wrapped;
    wrapped.insert("material", *f.node("own_ndf")->as_table());
    const scene::Values terms = caseValues(wrapped, file, "sweep.own_ndf", {});
    for (const char* k : {"model", "ndf_table", "measured", "brdf"})
        if (terms.given().count(k))
            f.fail("own_ndf", std::string("sets ") + k + " itself (model tabulated, ndf_table)");
    SweepAxis axis;
    axis.key = "source";
    const std::string origin = f.at("folder");
    for (const std::string& n : names) {
        const std::string path = (dir.back() == '/' ? dir : dir + "/") + n;
        const std::string stem = fs::path(n).stem().string();
        SweepCase measured;
        measured.name = stem;
        measured.values.set("measured", path, origin);
        measured.tags = {{"material_file", n}, {"variant", "measured"}};
        axis.cases.push_back(measured);
        if (fs::path(n).extension() != ".bsdf") continue;
        SweepCase own;
        own.name = stem + " own NDF";
        own.values = terms;
        own.values.set("model", "tabulated", f.at("own_ndf"));
        own.values.set("ndf_table", path, origin);
        own.tags = {{"material_file", n}, {"variant", "own NDF"}};
        axis.cases.push_back(own);
    }
    for (const auto& c : axis.cases) axis.values.push_back(c.name);
    return axis;
}

SweepAxis parseAxis(const toml::table& t, const std::string& file) {
    const Fields f(t, file, "sweep", {"key", "values", "range", "cases", "folder", "own_ndf"});
    SweepAxis axis;
    const auto key = f.string("key");
    if (!key || key->empty()) f.fail("key", "needs key = \"table.key\" (a scene key, e.g. light.incidence)");
    axis.key = *key;
    int given = 0;
    for (const char* k : {"values", "range", "cases", "folder"}) given += f.node(k) != nullptr;
    if (given != 1)
        f.fail(given ? "values" : "key",
               std::string(given ? "give only one of" : "needs one of") +
                   " values = [...], range = [start, stop, step], cases = [{ name = ..., ... }] "
                   "or folder = \"DIR\" (a file key's files)");
    if (f.node("folder")) {
        // Every file of the key's kind in a folder beside the experiment file, in name order (a MERL table folder
        // for fit_models): .binary (MERL) and .bsdf (RGL) for material.measured, .brdf for material.brdf.
        const scene::Param* p = scene::find(axis.key.substr(axis.key.find('.') + 1));
        const bool measured = axis.key == "material.measured", brdfKey = axis.key == "material.brdf";
        if (!p || !(measured || brdfKey))
            f.fail("folder",
                   "lists files for material.measured (.binary, .bsdf) or material.brdf (.brdf), not " + axis.key);
        const std::string folder = *f.string("folder");
        if (folder.empty()) f.fail("folder", "an empty folder name");
        const auto slash = file.rfind('/');
        const std::string base = slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
        const std::string dir = folder.front() == '/' ? folder : base + folder;
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            f.fail("folder",
                   "'" + printable(dir) + "' is not a folder" +
                       (measured ? " (hilite ships no measured data: MERL tables from https://www.merl.com/brdf/, "
                                   "RGL .bsdf files from https://rgl.epfl.ch/materials; see README)"
                                 : ""));
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir, ec))
            if (const std::string ext = entry.path().extension().string();
                entry.is_regular_file(ec) && (measured ? ext == ".binary" || ext == ".bsdf" : ext == ".brdf"))
                names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        if (names.empty())
            f.fail("folder",
                   "'" + printable(dir) + "' holds no " + (measured ? ".binary or .bsdf" : ".brdf") + " file" +
                       (measured ? " (MERL tables: https://www.merl.com/brdf/, or hilite brdf tabulate; RGL materials: "
                                   "https://rgl.epfl.ch/materials)"
                                 : ""));
        const std::string origin = f.at("folder");
        if (f.node("own_ndf")) return ownNdfAxis(f, file, dir, names);
        for (const std::string& n : names) {
            const std::string path = (dir.back() == '/' ? dir : dir + "/") + n;
            scene::Values one;
            one.set(p->name, path, origin);
            axis.values.push_back(path);
            axis.entries.push_back(one);
        }
        return axis;
    }
    if (f.node("own_ndf")) f.fail("own_ndf", "only with folder = \"DIR\" of material.measured files");
    if (f.node("range")) {
        const std::vector<double> r = f.numbers("range");
        if (r.size() != 3 || !(r[2] > 0) || r[1] < r[0])
            f.fail("range", "range = [start, stop, step], start <= stop, step > 0");
        const double count = std::floor((r[1] - r[0]) / r[2] + 1e-9) + 1;
        if (!std::isfinite(count) || count > double(kMaxConfigurations))
            f.fail("range", "gives more than " + std::to_string(kMaxConfigurations) + " values");
        const long n = long(count) - 1;
        const std::string origin = f.at("range");
        for (long i = 0; i <= n; ++i) {
            scene::Values one;
            scene::setKey(one, file, axis.key, toml::value<double>(r[0] + double(i) * r[2]));
            const auto& [name, value] = *one.given().begin();  // a range's values all come from its line
            scene::Values relabelled;
            relabelled.set(name, value.text, origin);
            axis.values.push_back(value.text);
            axis.entries.push_back(relabelled);
        }
    } else if (f.node("values")) {
        addValues(axis, *f.array("values"), file);
        if (axis.entries.empty()) f.fail("values", "no values");
    } else {
        // A case axis and its tags are row columns of their own: one named like a fixed column (config, a
        // parameter, a measurement field) would overwrite it in the row (config: the index --resume reads).
        std::vector<std::string> fixed = {"config"};
        for (const auto& c : scene::columns()) fixed.push_back(c);
        for (const auto& c : measurement::measurementColumns()) fixed.push_back(c);
        auto isFixed = [&](const std::string& name) {
            return std::find(fixed.begin(), fixed.end(), name) != fixed.end();
        };
        if (isFixed(axis.key))
            f.fail("key", "'" + axis.key + "' is a column of every row; name a case axis otherwise (e.g. setting)");
        axis.cases = parseCases(*f.array("cases"), file, axis.key);
        if (axis.cases.empty()) f.fail("cases", "no cases");
        for (const auto& c : axis.cases)
            for (const auto& [tag, v] : c.tags.items())
                if (isFixed(tag))
                    f.fail("cases",
                           "case '" + c.name + "': tag '" + tag + "' is a column of every row; name it otherwise");
        for (const auto& c : axis.cases) axis.values.push_back(c.name);
    }
    return axis;
}

}  // namespace

std::vector<std::string> shippedExperiments() {
    std::vector<std::string> dirs;
    for (const SharePlace& place : sharePlaces()) dirs.push_back(place.dir + "/experiments");
    dirs.push_back("experiments");
    for (const std::string& dir : dirs) {
        std::error_code ec;
        std::vector<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(dir, ec))
            if (e.path().extension() == ".toml" && e.is_regular_file(ec)) names.push_back(e.path().stem().string());
        if (names.empty()) continue;
        std::sort(names.begin(), names.end());
        return names;
    }
    return {};
}

std::string findExperiment(const std::string& name) {
    if (access(name.c_str(), R_OK) == 0) return name;
    std::vector<std::string> dirs;
    for (const SharePlace& place : sharePlaces()) dirs.push_back(place.dir + "/experiments");
    dirs.push_back("experiments");
    for (const std::string& dir : dirs)
        for (const std::string& cand : {dir + "/" + name, dir + "/" + name + ".toml"})
            if (access(cand.c_str(), R_OK) == 0) return cand;
    throw InputError("run: no experiment '" + name + "' (give a file, or a name from experiments/)");
}

namespace {

int wholeNumber(const Fields& f, const std::string& key, int lo, int hi, int fallback) {
    const toml::node* v = f.node(key);
    if (!v) return fallback;
    const auto x = v->value_exact<int64_t>();
    if (!x || *x < lo || *x > hi)
        f.fail(key, "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return int(*x);
}

/// A top-level table of the file (e.g. [summary]), nullptr when absent; anything but a table is refused.
const toml::table* table(const toml::table& doc, const std::string& path, const std::string& name) {
    const toml::node* n = doc.get(name);
    if (!n) return nullptr;
    if (!n->is_table())
        throw InputError(line(path, *n) + ": " + name + ": write it as a table [" + name + "] (got " + typeName(*n) +
                         ")");
    return n->as_table();
}

/// A top-level array of tables (e.g. [[plot]]); anything else (a single [plot] table, plot = [1, 2]) is refused.
std::vector<const toml::table*> tables(const toml::table& doc, const std::string& path, const std::string& name) {
    std::vector<const toml::table*> out;
    const toml::node* n = doc.get(name);
    if (!n) return out;
    const auto* a = n->as_array();
    if (a)
        for (const auto& el : *a)
            if (el.is_table()) out.push_back(el.as_table());
    if (!a || out.size() != a->size())
        throw InputError(line(path, *n) + ": " + name + ": write it as [[" + name + "]] tables, one per " + name +
                         " (got " + (a ? "an array of other values" : typeName(*n)) + ")");
    return out;
}

/// [reference], [timing] and [pareto]: the tables of an accuracy/cost study.
/// [fit]: the options of `hilite fit` (experiments/fit.hpp), each checked where it is written.
void parseFit(const toml::table& doc, const std::string& path, Experiment& e) {
    const auto* t = table(doc, path, "fit");
    if (!t) return;
    const Fields f(*t, path, "fit",
                   {"models", "thresholds", "weights", "anisotropy", "f0", "geometry", "fresnel", "diffuse", "rank_by",
                    "color", "max_evaluations"});
    FitOptions o;
    if (f.node("models")) o.models = f.strings("models");
    if (f.node("thresholds")) o.thresholds = f.numbers("thresholds");
    if (f.node("weights")) o.weights = f.numbers("weights");
    o.anisotropy = f.boolean("anisotropy", o.anisotropy);
    o.f0 = f.boolean("f0", o.f0);
    o.geometry = f.string("geometry", o.geometry);
    o.fresnel = f.string("fresnel", o.fresnel);
    o.diffuse = f.string("diffuse", o.diffuse);
    o.rankBy = f.string("rank_by", o.rankBy);
    o.color = f.boolean("color", o.color);
    o.maxEvaluations = wholeNumber(f, "max_evaluations", 1, 10000, o.maxEvaluations);  // documented as an integer
    try {
        checkFitOptions(o);
    } catch (const InputError& err) {  // "--models: ..." as the flag says it: here the key says it
        const std::string m = err.what();
        const auto colon = m.find(": ");
        if (m.rfind("--", 0) != 0 || colon == std::string::npos) f.fail("models", m);
        std::string key = m.substr(2, colon - 2);  // --fit-anisotropy -> anisotropy, --models -> models
        std::replace(key.begin(), key.end(), '-', '_');
        if (key.rfind("fit_", 0) == 0) key = key.substr(4);
        f.fail(key, m.substr(colon + 2));
    }
    for (const char* other : {"match", "reference", "timing", "pareto"})
        if (doc.contains(other))
            throw InputError(path + ": [" + std::string(other) +
                             "]: not with [fit] (a fit row ranks models; it measures "
                             "no single scene)");
    e.fit = o;
}

/// [bounces]: the settings of the studies, each checked where it is written, and the colour picture's name.
void parseBounces(const toml::table& doc, const std::string& path, Experiment& e, Names& names) {
    const auto* t = table(doc, path, "bounces");
    if (!t) return;
    const Fields f(*t, path, "bounces", {"paths", "batches", "seed", "surface", "texels", "bumps_per_tile", "colours"});
    BounceSettings s;
    s.options.paths = wholeNumber(f, "paths", 2, 100000000, int(s.options.paths));
    s.options.batches = wholeNumber(f, "batches", 2, 1000, s.options.batches);
    s.options.seed = uint64_t(wholeNumber(f, "seed", 0, 2147483647, int(s.options.seed)));
    const std::string surface = f.string("surface", micro::toString(s.options.surface));
    const auto kind = micro::parseTracedSurface(surface);
    if (!kind) f.fail("surface", "'" + printable(surface) + "' is not a traced surface (allowed: hermite, bilinear)");
    s.options.surface = *kind;
    s.texels = wholeNumber(f, "texels", 64, 4096, s.texels);
    s.bumpsPerTile = wholeNumber(f, "bumps_per_tile", 1, 512, s.bumpsPerTile);
    try {
        checkBounceSettings(s, false);
    } catch (const InputError& err) {  // "paths: ..." names the key
        const std::string m = err.what();
        const auto colon = m.find(": ");
        f.fail(m.substr(0, colon), m.substr(colon + 2));
    }
    if (f.node("colours")) {
        e.bounceColoursFile = f.outputFile("colours", "");
        names.claim(e.bounceColoursFile, f.at("colours"));
    }
    for (const char* other : {"match", "reference", "timing", "pareto", "fit"})
        if (doc.contains(other))
            throw InputError(path + ": [" + std::string(other) +
                             "]: not with [bounces] (a bounce row traces light "
                             "paths; it measures no highlight)");
    e.bounces = s;
}

void parseErrorTables(const toml::table& doc, const std::string& path, Experiment& e, Names& names) {
    if (const auto* ref = table(doc, path, "reference"))
        e.referenceErrors = Fields(*ref, path, "reference", {"errors"}).boolean("errors", true);
    if (const auto* timing = table(doc, path, "timing")) {
        const Fields f(*timing, path, "timing", {"repeats", "warmup"});
        e.timing = true;
        e.repeats = wholeNumber(f, "repeats", 1, 1000, 5);
        e.warmup = wholeNumber(f, "warmup", 0, 1000, 1);
    }
    for (const auto* t : tables(doc, path, "pareto")) {
        const Fields f(*t, path, "pareto", {"file", "title", "setting", "series", "error", "time", "targets"});
        ParetoSpec spec;
        spec.file = f.outputFile("file", spec.file);
        names.claim(spec.file, f.at("file"));
        spec.title = f.string("title", spec.title);
        spec.setting = f.string("setting", spec.setting);
        spec.series = f.string("series", spec.series);
        spec.error = f.string("error", spec.error);
        spec.time = f.string("time", spec.time);
        spec.targets = f.numbers("targets");
        e.pareto.push_back(spec);
    }
}

}  // namespace

Experiment loadExperiment(const std::string& path) { return parseExperiment(readText(path), path); }

namespace {

/// Every top-level table must be one an experiment has.
void checkTables(const toml::table& doc, const std::string& path) {
    static const std::vector<std::string> allowed = {"experiment",    "scene", "sweep",   "match",     "plot",
                                                     "contact_sheet", "strip", "summary", "reference", "timing",
                                                     "pareto",        "fit",   "bounces"};
    for (const auto& [k, v] : doc) {
        const std::string name(k.str());
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
            const std::string hint = didYouMean(name, allowed);
            throw InputError(line(path, v) + ": " + name + ": unknown table" +
                             (hint.empty() ? std::string() : ", did you mean '" + hint + "'?") +
                             " (allowed: " + join(allowed) + ")");
        }
    }
}

void parsePlots(const toml::table& doc, const std::string& path, Experiment& e, Names& names) {
    for (const auto* t : tables(doc, path, "plot")) {
        const Fields f(*t, path, "plot",
                       {"file", "title", "x", "y", "series", "xlabel", "ylabel", "key", "logx", "logy", "theory"});
        PlotSpec spec;
        spec.file = f.outputFile("file", "plot.png");
        names.claim(spec.file, f.at("file"));
        spec.title = f.string("title", "");
        spec.x = f.string("x", "incidence_deg");
        spec.y = f.string("y", "aspect");
        spec.series = f.string("series", "");
        spec.xlabel = f.string("xlabel", "");
        spec.ylabel = f.string("ylabel", "");
        spec.key = f.string("key", spec.key);
        const auto& keys = plotKeys();
        if (std::find(keys.begin(), keys.end(), spec.key) == keys.end())
            f.fail("key", "unknown legend position (allowed: " + join(keys) + ")");
        spec.logx = f.boolean("logx", false);
        spec.logy = f.boolean("logy", false);
        if (const auto* th = f.array("theory"))
            for (const auto& c : *th) {
                const auto* pair = c.as_array();
                if (!pair || pair->size() != 2 || !(*pair)[0].is_string() || !(*pair)[1].is_string())
                    throw InputError(line(path, c) +
                                     ": plot.theory: each curve is [\"title\", \"expression of x\"] (two strings)");
                const std::string expr = (*pair)[1].as_string()->get();
                const std::string why = theoryError(expr);
                if (!why.empty())
                    throw InputError(
                        line(path, c) + ": plot.theory: '" + printable(expr) + "': " + why +
                        " (allowed: muparser syntax in the variable x, constants pi and _e, functions such "
                        "as sin, cos, tan, asin, acos, atan, sqrt, exp, ln, log10, abs, min, max)");
                spec.theory.emplace_back((*pair)[0].as_string()->get(), expr);
            }
        e.plots.push_back(spec);
    }
}

/// A contact sheet's rows or columns: `key` and its values, one scene assignment each.
SweepAxis sheetAxis(const Fields& f, const std::string& keyName, const std::string& fallbackKey,
                    const std::string& valuesName) {
    SweepAxis axis;
    axis.key = f.string(keyName, fallbackKey);
    const toml::array* values = f.array(valuesName);
    if (!values || values->empty()) f.fail(valuesName, "needs " + valuesName + " = [...] (values of " + axis.key + ")");
    constexpr size_t kMaxTiles = 64;  // a sheet row of 64 tiles of 256 px is already 16384 px wide
    if (values->size() > kMaxTiles) f.fail(valuesName, "at most " + std::to_string(kMaxTiles) + " values");
    addValues(axis, *values, f.file());
    return axis;
}

void parseSheet(const toml::table& doc, const std::string& path, Experiment& e, Names& names) {
    if (const auto* sheet = table(doc, path, "contact_sheet")) {
        const Fields f(*sheet, path, "contact_sheet",
                       {"file", "size", "fov", "row_key", "rows", "column_key", "columns"});
        e.sheetFile = f.outputFile("file", e.sheetFile);
        names.claim(e.sheetFile, f.at("file"));
        if (const toml::node* size = f.node("size"))  // "512x256" or 256, as in a scene file's [camera]
            if (!(size->is_string() || size->is_integer()) || !scene::valueText(*size, e.sheetSize))
                f.fail("size", "expected a size, 256 or \"256x192\" (got " + typeName(*size) + ")");
        if (const toml::node* fov = f.node("fov")) {  // the photo views' field of view, as camera.fov takes it
            std::string text;
            if (!(fov->is_string() || fov->is_number()) || !scene::valueText(*fov, text))
                f.fail("fov", "expected auto or a number in (0, 179] (got " + typeName(*fov) + ")");
            if (const std::string err = scene::check(*scene::find("fov"), text); !err.empty()) f.fail("fov", err);
            e.sheetFov = text;
        }
        // rows = "sweep": the values (or cases) of the sweep over row_key, whatever a folder holds.
        const toml::node* rowsNode = f.node("rows");
        const bool fromSweep = rowsNode && rowsNode->is_string() && rowsNode->as_string()->get() == "sweep";
        SweepAxis rows;
        if (fromSweep) {
            rows.key = f.string("row_key", "material.model");
            const auto axis =
                std::find_if(e.axes.begin(), e.axes.end(), [&](const SweepAxis& a) { return a.key == rows.key; });
            if (axis == e.axes.end())
                f.fail("rows", "\"sweep\" takes the rows from the sweep over " + rows.key + ", and none sweeps it");
            rows.values = axis->values;
            if (axis->cases.empty()) rows.entries = axis->entries;
            else
                for (const auto& c : axis->cases) rows.entries.push_back(c.values);
            if (rows.values.size() > 64) f.fail("rows", "the sweep over " + rows.key + " has more than 64 values");
        } else {
            rows = sheetAxis(f, "row_key", "material.model", "rows");
        }
        const SweepAxis cols = sheetAxis(f, "column_key", "light.incidence", "columns");
        e.sheetRowKey = rows.key, e.sheetColumnKey = cols.key;
        e.sheetRows = rows.values, e.sheetRowValues = rows.entries;
        e.sheetColumns = cols.values, e.sheetColumnValues = cols.entries;
        // Every tile's scene and the tile size now, not after every row was measured.
        scene::Values sizeValue;
        sizeValue.set("size", e.sheetSize, f.at("size"));
        scene::resolve(sizeValue, scene::Purpose::Render);
        for (const auto& r : e.sheetRowValues)
            for (const auto& c : e.sheetColumnValues) {
                scene::Values v = e.base;
                v.merge(r);
                v.merge(c);
                if (!e.sheetFov.empty()) v.set("fov", e.sheetFov, f.at("fov"));
                if (scene::resolve(v).angles.size() != 1)
                    throw InputError(v.where("incidence") + ": one angle per contact sheet tile");
            }
    }
}

void parseStrips(const toml::table& doc, const std::string& path, Experiment& e, Names& names) {
    for (const auto* t : tables(doc, path, "strip")) {
        const Fields f(*t, path, "strip", {"material", "file"});
        const auto material = f.string("material");
        if (!material) f.fail("material", "needs material = \"NAME\"");
        if (!brdf::findMaterial(*material)) {
            const std::string hint = didYouMean(*material, brdf::materialNames());
            f.fail("material", "unknown '" + *material + "'" + (hint.empty() ? "" : ", did you mean '" + hint + "'?") +
                                   " (allowed: " + join(brdf::materialNames()) + ")");
        }
        e.strips.emplace_back(*material, f.outputFile("file", *material + "_strip.png"));
        names.claim(e.strips.back().second, f.at("file"));
        names.claim(*material + "_fresnel.png", f.at("material"), "its Fresnel plot ");
    }
}

void parseSummary(const toml::table& doc, const std::string& path, Experiment& e) {
    if (const auto* summary = table(doc, path, "summary")) {
        const Fields f(*summary, path, "summary", {"series", "x", "at", "sections"});
        e.summarySeries = f.string("series", "");
        e.summaryX = f.string("x", e.summaryX);
        e.summaryAt = f.numbers("at");
        if (f.node("sections")) {
            for (const auto& name : f.strings("sections")) {
                if (!isReportSection(name))
                    f.fail("sections", "unknown section '" + name + "' (allowed: " + join(reportSections()) + ")");
                e.sections.push_back(name);
            }
        } else if (!e.summarySeries.empty()) {
            e.sections.push_back("shape");
        }
    }
}

}  // namespace

std::vector<std::string> rowColumns(const Experiment& e) {
    std::vector<std::string> out = {"config"};
    auto add = [&](const std::string& c) {
        if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
    };
    for (const auto& a : e.axes)
        if (!a.cases.empty()) {
            add(a.key);
            for (const auto& c : a.cases)
                for (const auto& [k, v] : c.tags.items()) add(k);
        }
    for (const auto& c : scene::columns()) add(c);
    for (const auto& c : measurement::measurementColumns()) add(c);
    if (e.referenceErrors)
        for (const char* c :
             {"ref_aspect", "ref_major_deg", "ref_minor_deg", "aspect_error", "major_error", "minor_error"})
            add(c);
    if (e.timing)
        for (const char* c : {"time_ms", "repeats", "error_estimate"}) add(c);
    if (e.fit) {
        for (const char* c :
             {"target", "verdict", "resolution", "best_model", "best_residual", "best_params", "fit_time_ms"})
            add(c);
        for (const std::string& m : e.fit->models)
            for (const char* c : {"_residual", "_shape_residual", "_values_residual", "_rank", "_params", "_at_bound"})
                add(m + c);
    }
    if (e.bounces)
        for (const auto& c : bounceColumns()) add(c);
    return out;
}

namespace {

/// The row fields plots, the summary and Pareto sections read must be columns the rows will have.
void checkFields(const Experiment& e, const toml::table& doc) {
    const std::vector<std::string> columns = rowColumns(e);
    auto check = [&](const std::string& field, const toml::table& t, const std::string& table, const std::string& key,
                     bool optional) {
        if ((optional && field.empty()) || std::find(columns.begin(), columns.end(), field) != columns.end()) return;
        const toml::node* n = t.get(key);
        const std::string hint = didYouMean(field, columns);
        throw InputError(line(e.path, n ? *n : static_cast<const toml::node&>(t)) + ": " + table + "." + key + ": '" +
                         field + "' is not a row field" + (hint.empty() ? "" : ", did you mean '" + hint + "'?") +
                         " (allowed: the columns of results.csv: " + join(columns) + ")");
    };
    const auto plots = tables(doc, e.path, "plot");
    for (size_t i = 0; i < plots.size(); ++i) {
        check(e.plots[i].x, *plots[i], "plot", "x", false);
        check(e.plots[i].y, *plots[i], "plot", "y", false);
        check(e.plots[i].series, *plots[i], "plot", "series", true);
    }
    const auto pareto = tables(doc, e.path, "pareto");
    for (size_t i = 0; i < pareto.size(); ++i) {
        check(e.pareto[i].setting, *pareto[i], "pareto", "setting", false);
        check(e.pareto[i].series, *pareto[i], "pareto", "series", false);
        check(e.pareto[i].error, *pareto[i], "pareto", "error", false);
        check(e.pareto[i].time, *pareto[i], "pareto", "time", false);
    }
    if (const auto* s = table(doc, e.path, "summary")) {
        check(e.summarySeries, *s, "summary", "series", true);
        check(e.summaryX, *s, "summary", "x", false);
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
        throw InputError(path + ":" + std::to_string(err.source().begin.line) +
                         ": TOML syntax error: " + std::string(err.description()));
    }
    checkTables(doc, path);
    const std::string file = path.substr(path.rfind('/') + 1);
    const std::string stem = file.substr(0, file.rfind('.'));
    if (const auto* exp = table(doc, path, "experiment")) {
        const Fields f(*exp, path, "experiment", {"name", "title", "description"});
        e.name = f.string("name", stem);
        const std::string why = outputNameError(e.name, "");
        if (!why.empty())
            f.fail("name", "'" + printable(e.name) + "': " + why + " (the name of its folder under results/)");
        e.title = f.string("title", e.name);
        e.description = f.string("description", "");
    } else {
        e.name = e.title = stem;
        if (!outputNameError(e.name, "").empty())
            throw InputError(
                path + ": experiment.name: the file's name gives no folder name; give [experiment] name = \"...\"");
    }
    if (const auto* scene = table(doc, path, "scene")) e.base = scene::sceneValues(*scene, path);
    if (const auto* match = table(doc, path, "match")) {
        e.match = scene::sceneValues(*match, path);
        e.matching = !e.match.given().empty();
    }
    for (const auto* s : tables(doc, path, "sweep")) e.axes.push_back(parseAxis(*s, path));
    // [match] sets each model's width: a sweep of that width would be overwritten row by row (54 rows at
    // roughness 0.10000000004572847 under labels 0.05 and 0.2, no warning).
    if (e.matching)
        for (const SweepAxis& a : e.axes) {
            std::vector<const scene::Values*> sets;
            for (const auto& v : a.entries) sets.push_back(&v);
            for (const auto& c : a.cases) sets.push_back(&c.values);
            for (const scene::Values* v : sets)
                for (const char* width : {"roughness", "exponent"})
                    if (v->given(width))
                        throw InputError(path + ": [match] sets each model's " + width +
                                         " (its width), which [[sweep]] " + a.key +
                                         " sweeps: the rows would carry the matched " + width +
                                         ", not the swept one; drop [match] or that sweep");
        }
    Names names;
    parsePlots(doc, path, e, names);
    parseSheet(doc, path, e, names);
    parseStrips(doc, path, e, names);
    parseSummary(doc, path, e);
    parseErrorTables(doc, path, e, names);
    parseFit(doc, path, e);
    parseBounces(doc, path, e, names);
    checkFields(e, doc);
    return e;
}

Configurations::Configurations(const Experiment& e) : m_e(&e) {
    double total = 1;
    for (const auto& a : e.axes) total *= double(a.values.size());
    if (total > double(kMaxConfigurations))
        throw InputError(e.path + ": the sweep axes give " + std::to_string(long(total)) + " configurations (at most " +
                         std::to_string(kMaxConfigurations) + ")");
    m_size = size_t(total);
}

Configuration Configurations::operator[](size_t index) const {
    const auto& axes = m_e->axes;
    Configuration c;
    c.index = long(index);
    c.values = m_e->base;
    // Mixed radix, the last axis fastest: the order the rows have always had.
    std::vector<size_t> idx(axes.size(), 0);
    for (size_t a = axes.size(), rest = index; a-- > 0;) {
        idx[a] = rest % axes[a].values.size();
        rest /= axes[a].values.size();
    }
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
    return c;
}

Configurations Experiment::configurations(int shardK, int shardN) const {
    const Configurations configs(*this);
    const size_t first = size_t(std::max(1, shardK) - 1), stride = size_t(std::max(1, shardN));
    // Validate every configuration now, so a bad value fails before any row is written (the reference scene
    // must be valid too). One at a time: nothing of a resolved scene is kept.
    const auto start = std::chrono::steady_clock::now();
    auto last = start;
    bool reported = false;
    for (size_t i = first; i < configs.size(); i += stride) {
        const Configuration c = configs[i];
        scene::Values all = c.values;
        all.merge(c.reference);
        if (fit)  // a fit sweeps the incidences itself: its target's and models' scenes checked now
            checkFitScenes(all, *fit);
        else if (bounces && resolveBounceScene(all).angles.size() != 1)
            throw InputError(all.where("incidence") + ": one angle per configuration (sweep it with [[sweep]])");
        else if (!bounces &&
                 scene::resolve(all).angles.size() != 1)  // a list or range of angles: one row cannot hold them
            throw InputError(all.where("incidence") + ": one angle per configuration (sweep it with [[sweep]])");
        const size_t done = (i - first) / stride + 1, todo = (configs.size() - first + stride - 1) / stride;
        if ((done & 1023) == 0 || done == todo) {
            const auto now = std::chrono::steady_clock::now();
            if (now - last >= std::chrono::seconds(1) || (reported && done == todo)) {
                std::cerr << "hilite: " << path << ": validated " << done << " of " << todo
                          << (stride > 1 ? " configurations of the shard\n" : " configurations\n");
                last = now;
                reported = true;
            }
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

}  // namespace hilite::experiments
