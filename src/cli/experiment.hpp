#pragma once
// Experiment files (TOML): [experiment] name/title/description, [scene] a base scene (the tables of a
// scene file), [[sweep]] axes (key + values or range), optional [match] (lobe widths matched at normal
// incidence), [[plot]], [contact_sheet] and [summary]. See experiments/*.toml and the README.

#include "cli/measure_cmd.hpp"
#include "cli/scene_file.hpp"
#include "experiments/pareto.hpp"
#include "experiments/plot.hpp"
#include "gl/context.hpp"
#include "render/renderer.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace hilite::cli {

struct Configuration {
    long index = 0;
    std::vector<SceneArg> args;       ///< base scene, then one value per sweep axis
    nlohmann::json sweep;             ///< the axis values of this configuration ("light.incidence": 30, ...)
    nlohmann::json tags;              ///< case axes: their names and tags, written to the row as columns
    std::vector<SceneArg> reference;  ///< case axes: what the reference scene changes (e.g. the exact Fresnel)
};

/// One value of a case axis: a named group of scene keys (e.g. a scene, or a setting of the knobs).
struct SweepCase {
    std::string name;
    std::vector<SceneArg> args;       ///< the case's scene keys
    std::vector<SceneArg> reference;  ///< `reference = { ... }`: keys changed only for the reference
    nlohmann::json tags;              ///< `tags = { knob = "size" }`: extra row columns
};

struct SweepAxis {
    std::string key;                  ///< "light.incidence"; for a case axis the column of the case names
    std::vector<std::string> values;  ///< as flag values; for a case axis the case names
    std::vector<SceneArg> args;       ///< one flag argument per value, with its origin (file:line)
    std::vector<int> lines;
    std::vector<SweepCase> cases;     ///< non-empty: a case axis (`cases = [...]` instead of values/range)
};

using experiments::ParetoSpec;

struct Experiment {
    std::string path, text;  ///< the file and its text (copied beside the results for merge)
    std::string name, title, description;
    std::vector<SceneArg> base;
    std::vector<SweepAxis> axes;
    std::vector<SceneArg> match;  ///< empty: no width matching
    std::vector<experiments::PlotSpec> plots;
    std::string sheetFile = "contact_sheet.png", sheetRowKey, sheetColumnKey, sheetSize = "256x192";
    std::vector<std::string> sheetRows, sheetColumns;
    std::vector<std::pair<std::string, std::string>> strips;  ///< [[strip]]: material, PNG file
    std::string summarySeries, summaryX = "incidence_deg";
    std::vector<double> summaryAt;
    bool referenceErrors = false;  ///< [reference] errors = true: each row's error against the double reference
    int repeats = 1, warmup = 0;   ///< [timing]: each configuration measured warmup + repeats times
    bool timing = false;           ///< [timing] present: rows get time_ms, the median of the repeats
    std::vector<ParetoSpec> pareto;

    /// Every configuration, validated (a bad value anywhere fails before anything runs).
    std::vector<Configuration> configurations() const;
};

/// A path, or the name of a file shipped in experiments/ (found beside the executable like the shaders).
std::string findExperiment(const std::string& nameOrPath);
Experiment loadExperiment(const std::string& path);
/// The same from text; `name` stands for the file in messages.
Experiment parseExperiment(const std::string& text, const std::string& name);
/// A sweep larger than this is refused: its rows would not fit a results file anyone reads.
constexpr size_t kMaxConfigurations = 1000000;
/// Writes dir/experiment.toml (the text, verbatim) and dir/experiment.origin (the original file's absolute
/// path, against which merge resolves the relative .brdf paths of the copy).
void writeExperimentCopy(const Experiment& e, const std::string& dir);
/// The experiment a run's output folder holds (its copy, read as if from experiment.origin when present).
Experiment loadExperimentCopy(const std::string& dir);

class ExperimentRunner {
public:
    ExperimentRunner(const Experiment& e, const std::string& backend);
    ~ExperimentRunner();
    /// The fixed CSV columns: config, the sweep keys, every scene parameter, every measurement field.
    const std::vector<std::string>& columns() const { return m_columns; }
    /// Probes every .brdf shader (file and values) the configurations i with i mod shardN = shardK - 1 use,
    /// so that a shader that does not build or runs too long fails before any result file is written.
    void probeAll(const std::vector<Configuration>& configs, int shardK, int shardN);
    /// Measures one configuration: one JSON row.
    nlohmann::json measure(const Configuration& c);
    /// Plots, contact sheet and summary.md from the complete rows. seconds < 0: unknown (merge).
    void finalize(const std::string& dir, const std::vector<nlohmann::json>& rows, double seconds);

private:
    ResolvedMeasure resolve(const std::vector<SceneArg>& args, MeasureFlags& flags, nlohmann::json* params) const;
    void applyMatch(std::vector<SceneArg>& args, nlohmann::json& row);
    /// The double reference of a configuration's scene (with its case's reference keys), cached by scene.
    const measure::Shape& reference(const Configuration& c, std::vector<SceneArg> args);
    void addErrors(nlohmann::json& row, const measure::Shape& ref) const;
    render::Renderer& renderer();
    /// Before a .brdf scene is rendered: its notes (once per file), the probe (once per file and values)
    /// and the renderer's time limit.
    void prepare(const render::Scene& scene, double shaderTimeout);

    const Experiment& m_exp;
    std::string m_backend;
    std::vector<std::string> m_columns;
    double m_targetMajorDeg = 0;
    std::map<std::string, double> m_matched;  ///< model -> matched width parameter
    std::map<std::string, measure::Shape> m_references;  ///< reference scene -> its measurement
    std::unique_ptr<gl::Context> m_context;
    std::unique_ptr<render::Renderer> m_renderer;
    std::set<std::string> m_probed, m_noted;
};

}  // namespace hilite::cli
