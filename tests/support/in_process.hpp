#pragma once
// The library called in-process exactly as the command line calls it, for tests that need no process of
// their own: flags into scene::Values (as src/cli/scene_flags.cpp sets them), the refusal scene::resolve
// gives (the line `hilite` prints after "hilite: "), and the rows `hilite measure --json` prints, measured in
// one Session per test process (no process start, no GL context per call).
//
// The one place these tests touch the resolve/measure API: a change of its types is fixed here.
//
// The including target links hilite_measurement (hilite_scene alone for flags/refusal: define
// HILITE_IN_PROCESS_SCENE_ONLY before including), and hilite_experiments for the run helpers.

#include "hilite/core/error.hpp"
#include "hilite/experiments/run.hpp"
#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"
#include "hilite/scene/scene_file.hpp"

#ifndef HILITE_IN_PROCESS_SCENE_ONLY
#include "hilite/measurement/session.hpp"
#endif

#include <nlohmann/json.hpp>

#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hilite::testing {

/// The values a command line's registry flags set ("--model ggx --roughness 0.1 --reference"): a switch
/// takes no value, '' is the empty text, a List flag (--param) accumulates. Like the CLI, `sceneFile` (if
/// any) is read first and the flags override it. std::invalid_argument for a flag the registry lacks (a
/// test's typo, not a refusal under test).
inline scene::Values flags(const std::string& args, const std::string& sceneFile = "") {
    scene::Values v = sceneFile.empty() ? scene::Values() : scene::loadSceneFile(sceneFile);
    scene::Values given;
    std::istringstream in(args);
    std::vector<std::string> tokens;
    for (std::string t; in >> t;) tokens.push_back(t == "''" ? "" : t);
    for (size_t i = 0; i < tokens.size(); ++i) {
        const scene::Param* p = tokens[i].rfind("--", 0) == 0 ? scene::find(tokens[i]) : nullptr;
        if (!p) throw std::invalid_argument("not a registry flag: " + tokens[i]);
        if (p->kind == scene::Kind::Switch) {
            given.set(p->name, "true");
        } else {
            if (i + 1 >= tokens.size()) throw std::invalid_argument(tokens[i] + " without its value");
            given.set(p->name, tokens[++i]);
        }
    }
    v.merge(given);
    return v;
}

/// What the CLI's flag check (scene::check, run on each flag as it is parsed) says of the flags' values, as
/// "--flag: problem"; "" when every value passes. Scene-file values are checked by resolve() instead.
inline std::string flagCheck(const scene::Values& v) {
    for (const auto& [name, value] : v.given()) {
        if (!value.origin.empty()) continue;
        const scene::Param* p = scene::find(name);
        if (p && p->kind != scene::Kind::Switch && p->kind != scene::Kind::List) {
            const std::string problem = scene::check(*p, value.text);
            if (!problem.empty()) return p->flag() + ": " + problem;
        }
    }
    return "";
}

/// The text of the InputError `f()` throws (what the CLI prints after "hilite: "); "" when it throws none.
template <class F>
std::string inputError(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

/// The one-line refusal of `v` (the InputError's text, which the CLI prints after "hilite: "): the flag
/// check's, else scene::resolve's; "" when the values resolve.
inline std::string refusal(const scene::Values& v, scene::Purpose purpose = scene::Purpose::Measure) {
    if (std::string c = flagCheck(v); !c.empty()) return c;
    return inputError([&] { scene::resolve(v, purpose); });
}

/// Whether `message` is one non-empty line, as the CLI prints a refusal.
inline bool oneLine(const std::string& message) { return !message.empty() && message.find('\n') == std::string::npos; }

/// What is written to std::cerr (the CLI's stderr: warnings) while it lives.
struct StderrCapture {
    std::ostringstream text;
    std::streambuf* old;
    StderrCapture() : old(std::cerr.rdbuf(text.rdbuf())) {}
    ~StderrCapture() { std::cerr.rdbuf(old); }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;
    std::string str() const { return text.str(); }
};

/// Rows as the JSON lines `--json` prints: one dump per row, each ending in a newline.
inline std::string jsonLines(const std::vector<nlohmann::json>& rows) {
    std::string out;
    for (const auto& j : rows) out += j.dump() + "\n";
    return out;
}

#ifndef HILITE_IN_PROCESS_SCENE_ONLY

/// The test process's measuring session, made once; current again before each use (another context may
/// have been made current in between).
inline measurement::Session& session() {
    static measurement::Session s;
    s.makeCurrent();
    return s;
}

/// The rows `hilite measure --json` prints for `v`, one per incidence angle (src/cli/measure_cmd.cpp).
inline std::vector<nlohmann::json> measureJson(const scene::Values& v) {
    scene::Resolved r = scene::resolve(v);
    measurement::Session& s = session();
    if (!r.reference && !r.setup.cpu) s.rendererFor(r);
    std::vector<nlohmann::json> rows;
    for (double angle : r.angles) {
        r.scene.light.incidenceDeg = angle;
        rows.push_back(measurement::toJson(s.measureOne(r)));
    }
    return rows;
}

/// The refusal of `hilite measure` with `v`: the flag check's, else what resolving, probing and measuring
/// throw as InputError; "" when it measures.
inline std::string measureRefusal(const scene::Values& v) {
    if (std::string c = flagCheck(v); !c.empty()) return c;
    return inputError([&] { measureJson(v); });
}

#endif

/// `hilite run EXPERIMENT -o OUT [--resume] [--check]` (src/cli/run_cmd.cpp); links hilite_experiments.
inline experiments::RunSummary runExperiment(const std::string& experiment, const std::string& out, bool resume = false,
                                             bool check = false) {
    experiments::RunOptions o;
    o.experiment = experiment, o.out = out, o.resume = resume, o.check = check;
    return experiments::runExperiment(o);
}

/// The one-line refusal of `hilite run EXPERIMENT -o OUT [--check]`; "" when it runs.
inline std::string runRefusal(const std::string& experiment, const std::string& out, bool check = false) {
    return inputError([&] { runExperiment(experiment, out, false, check); });
}

}  // namespace hilite::testing
