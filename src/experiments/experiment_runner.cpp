// Runs the configurations of an experiment: each resolved, measured and written as one row.

#include "experiments/experiment.hpp"

#include "core/text.hpp"
#include "experiments/reports.hpp"
#include "experiments/results.hpp"
#include "hilite/core/error.hpp"
#include "hilite/measurement/row.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace hilite::experiments {

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void addErrors(nlohmann::json& row, const analysis::Shape& ref) {
    row["ref_aspect"] = ref.aspect;
    row["ref_major_deg"] = ref.major_deg;
    row["ref_minor_deg"] = ref.minor_deg;
    const double a = measurement::rowNumber(row, "aspect"), ma = measurement::rowNumber(row, "major_deg"),
                 mi = measurement::rowNumber(row, "minor_deg");
    auto json = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    row["aspect_error"] = json(std::abs(a - ref.aspect));
    row["major_error"] = json(std::abs(ma / ref.major_deg - 1.0));  // relative
    row["minor_error"] = json(std::abs(mi / ref.minor_deg - 1.0));
}

}  // namespace

ExperimentRunner::ExperimentRunner(const Experiment& e, const std::string& backend) : m_exp(e), m_session(backend) {
    m_columns.push_back("config");
    // Case axes: the case names and tags come first, after config (what the row is about).
    for (const auto& a : e.axes)
        if (!a.cases.empty()) {
            m_columns.push_back(a.key);
            for (const auto& c : a.cases)
                for (const auto& [k, v] : c.tags.items())
                    if (std::find(m_columns.begin(), m_columns.end(), k) == m_columns.end()) m_columns.push_back(k);
        }
    for (const auto& c : scene::columns()) m_columns.push_back(c);
    for (const auto& c : measurement::measurementColumns()) m_columns.push_back(c);
    if (e.referenceErrors)
        m_columns.insert(m_columns.end(), {"ref_aspect", "ref_major_deg", "ref_minor_deg", "aspect_error",
                                           "major_error", "minor_error"});
    if (e.timing) m_columns.insert(m_columns.end(), {"time_ms", "repeats", "error_estimate"});
    if (e.bounces)
        for (const auto& c : bounceColumns()) m_columns.push_back(c);
    if (e.matching) {
        scene::Values target = e.base;
        target.merge(e.match);
        scene::Resolved r = scene::resolve(target);
        if (r.scene.brdfFile)
            throw InputError(e.path +
                             ": [match]: matching widths needs a CPU twin, and a .brdf file has none "
                             "(set its parameters by hand)");
        r.scene.light.incidenceDeg = 0;
        m_targetMajorDeg = rad2deg(measurement::twinHalfWidth(r.scene, r.setup.options.threshold));
    }
}

ExperimentRunner::~ExperimentRunner() = default;

void ExperimentRunner::probeAll(const Configurations& configs, int shardK, int shardN) {
    std::set<std::string> seen;
    for (size_t i = size_t(shardK - 1); i < configs.size(); i += size_t(shardN)) {  // this shard's only
        const Configuration c = configs[i];
        if (!c.values.given("brdf")) continue;
        // Only the values the probe depends on decide whether a configuration needs its own probe.
        std::string key;
        for (const char* name : {"brdf", "light", "reference"}) key += c.values.text(name) + "\n";
        for (const auto& a : c.values.list("param")) key += a.text + "\n";
        if (!seen.insert(key).second) continue;
        const scene::Resolved r = scene::resolve(c.values);
        if (!r.reference) m_session.rendererFor(r);
    }
}

double matchedWidth(render::Scene scene, double targetMajorDeg, double threshold) {
    scene.light.incidenceDeg = 0;
    scene::dropEnergyTerms(scene.brdf);  // the bisection sets the width directly (scene/resolve.hpp)
    const bool exponent = brdf::usesExponent(scene.brdf.model);
    // Bisection in log(parameter) on the twin's half-width at normal incidence, where every isotropic
    // lobe is round, so its angular radius is its semi-major axis.
    double lo = std::log(exponent ? 1e-2 : 1e-4), hi = std::log(exponent ? 1e8 : 2.0);
    for (int i = 0; i < 80; ++i) {
        const double mid = 0.5 * (lo + hi);
        (exponent ? scene.brdf.exponent : scene.brdf.roughness) = std::exp(mid);
        const double w = rad2deg(measurement::twinHalfWidth(scene, threshold));
        ((w > targetMajorDeg) == exponent ? lo : hi) = mid;
    }
    return std::exp(0.5 * (lo + hi));
}

void ExperimentRunner::applyMatch(scene::Values& values, nlohmann::json& row) {
    if (!m_exp.matching) return;
    scene::Resolved r = scene::resolve(values);
    if (r.scene.brdfFile)
        throw InputError(m_exp.path + ": [match]: matching widths needs a CPU twin, and " + r.scene.brdfFile->path +
                         " (a .brdf file) has none: set its parameters by hand");
    if (r.scene.brdf.isMeasured())
        throw InputError(m_exp.path + ": [match]: matching widths sets a model's width, and " +
                         r.values.text("measured") + " (a measured table) has none");
    r.scene.light.incidenceDeg = 0;
    scene::dropEnergyTerms(r.scene.brdf);  // the bisection sets the width directly (scene/resolve.hpp)
    const std::string key = brdf::toString(r.scene.brdf.model);
    const bool exponent = brdf::usesExponent(r.scene.brdf.model);
    auto it = m_matched.find(key);
    if (it == m_matched.end()) {
        it = m_matched.emplace(key, matchedWidth(r.scene, m_targetMajorDeg, r.setup.options.threshold)).first;
    }
    std::ostringstream text;
    text.precision(17);
    text << it->second;
    values.set(exponent ? "exponent" : "roughness", text.str(), "[match]");
    row["matched_parameter"] = it->second;
}

const analysis::Shape& ExperimentRunner::reference(const Configuration& c, scene::Values values) {
    values.merge(c.reference);
    const scene::Resolved r = scene::resolve(values);
    // The scene and the threshold define the reference; the settings do not, nor the GL rule over a light with size
    // (the reference integrates it exactly).
    render::Scene exact = r.scene;
    exact.light.rings = 0;
    exact.light.ruleTarget = render::Light{}.ruleTarget;
    exact.light.ltc = false;
    std::ostringstream key;
    key << exact << " incidence=" << r.angles.front() << " threshold=" << r.setup.options.threshold;
    auto it = m_references.find(key.str());
    if (it == m_references.end())
        it = m_references.emplace(key.str(), measurement::measureReference(exact, r.setup.options).shape).first;
    return it->second;
}

nlohmann::json ExperimentRunner::measure(const Configuration& c) {
    nlohmann::json row;
    row["config"] = c.index;
    row["fingerprint"] = fingerprint(m_exp, c);  // what --resume and merge check the row against
    for (const auto& [k, v] : c.tags.items()) row[k] = v;
    scene::Values values = c.values;
    if (m_exp.fit) return fitRow(values, row);
    if (m_exp.bounces) return bounceRow(values, row);
    applyMatch(values, row);
    const scene::Resolved r = scene::resolve(values);
    if (r.angles.size() != 1)
        throw InputError(m_exp.path + ": light.incidence: one angle per configuration (sweep it with [[sweep]])");
    render::Renderer* gl = r.reference || r.setup.cpu ? nullptr : &m_session.rendererFor(r);
    // [timing]: warm-up runs (programs compiled, buffers allocated), then the median of the repeats'
    // wall times; the row's numbers are the last repeat's (every repeat measures the same).
    const int warmup = m_exp.timing ? m_exp.warmup : 0, repeats = m_exp.timing ? m_exp.repeats : 1;
    for (int i = 0; i < warmup; ++i) measurement::measureRow(gl, r);
    nlohmann::json measured;
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        measured = measurement::toJson(measurement::measureRow(gl, r));
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        // --tolerance times itself without its one-off warm-up measurement (startup_ms): take its word.
        times.push_back(measured.contains("time_ms") ? measured["time_ms"].get<double>() : wall);
    }
    for (auto& [k, v] : measured.items()) row[k] = v;
    if (m_exp.timing) {
        row["time_ms"] = median(times);
        row["repeats"] = repeats;
    }
    if (m_exp.referenceErrors) addErrors(row, reference(c, values));
    nameNonFinite(row);
    return row;
}

nlohmann::json ExperimentRunner::fitRow(const scene::Values& values, nlohmann::json& row) {
    const auto t0 = std::chrono::steady_clock::now();
    const FitResult res = fitModels(m_session, values, *m_exp.fit);
    const nlohmann::json columns = scene::parameterColumns(scene::resolve(values));
    for (auto& [k, v] : columns.items())
        if (k != "incidence_deg") row[k] = v;  // the fit sweeps incidence: no one angle is the row's
    row["target"] = res.target;
    row["verdict"] = res.verdict;
    row["resolution"] = res.resolution;
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    for (const ModelFit& f : res.fits) {  // ranked; named as FitOptions::models names them (the columns)
        const std::string& name = f.model;
        row[name + "_residual"] = number(f.residual);
        row[name + "_shape_residual"] = number(f.shapeResidual);
        row[name + "_values_residual"] = number(f.valuesResidual);
        row[name + "_rank"] = f.rank;
        row[name + "_params"] = f.params.dump();
        std::string atBound;  // the parameters at their search bound (fit.hpp: ModelFit::atBound)
        for (const std::string& p : f.atBound) atBound += (atBound.empty() ? "" : ",") + p;
        row[name + "_at_bound"] = atBound;
        if (f.rank == 1) {
            row["best_model"] = name;
            row["best_residual"] = number(f.residual);
            row["best_params"] = f.params.dump();
        }
    }
    row["fit_time_ms"] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    nameNonFinite(row);
    return row;
}

nlohmann::json ExperimentRunner::bounceRow(const scene::Values& values, nlohmann::json& row) {
    const std::vector<BounceStudy> studies = studyBounces(values, *m_exp.bounces);  // one angle: validated
    const nlohmann::json columns = scene::parameterColumns(resolveBounceScene(values));
    const nlohmann::json fields = bounceFields(studies.front());
    for (auto& [k, v] : columns.items()) row[k] = v;
    for (auto& [k, v] : fields.items()) row[k] = v;
    nameNonFinite(row);
    return row;
}

ImageF ExperimentRunner::photo(const scene::Values& values, int width, int height) {
    const scene::Resolved r = scene::resolve(values);
    return m_session.rendererFor(r).render(r.scene, scene::viewCamera(r, scene::View::Photo, width, height),
                                           render::Output::Color);
}

void ExperimentRunner::finalize(const std::string& dir, const Rows& rows, double seconds) {
    writeReports(*this, dir, rows, seconds);
}

}  // namespace hilite::experiments
