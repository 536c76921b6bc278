#pragma once
// Experiment files (TOML): [experiment] name/title/description, [scene] a base scene (the tables of a
// scene file), [[sweep]] axes (key + values or range), optional [match] (lobe widths matched at normal
// incidence), [[plot]], [contact_sheet] and [summary]. See experiments/*.toml and the README.

#include "experiments/pareto.hpp"
#include "experiments/plot.hpp"
#include "gl/context.hpp"
#include "hilite/experiments/bounces.hpp"
#include "hilite/experiments/fit.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/session.hpp"
#include "hilite/scene/resolve.hpp"
#include "render/renderer.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace hilite::experiments {

struct Configuration {
    long index = 0;
    scene::Values values;     ///< base scene, then one value per sweep axis
    nlohmann::json sweep;     ///< the axis values of this configuration ("light.incidence": 30, ...)
    nlohmann::json tags;      ///< case axes: their names and tags, written to the row as columns
    scene::Values reference;  ///< case axes: what the reference scene changes (e.g. the exact Fresnel)
};

/// One value of a case axis: a named group of scene keys (e.g. a scene, or a setting of the knobs).
struct SweepCase {
    std::string name;
    scene::Values values;     ///< the case's scene keys
    scene::Values reference;  ///< `reference = { ... }`: keys changed only for the reference
    nlohmann::json tags;      ///< `tags = { knob = "size" }`: extra row columns
};

struct SweepAxis {
    std::string key;                     ///< "light.incidence"; for a case axis the column of the case names
    std::vector<std::string> values;     ///< as the command line spells them; for a case axis the case names
    std::vector<scene::Values> entries;  ///< one assignment per value, with its origin (file:line)
    std::vector<SweepCase> cases;        ///< non-empty: a case axis (`cases = [...]` instead of values/range)
};

struct Experiment {
    std::string path, text;  ///< the file and its text (copied beside the results for merge)
    std::string name, title, description;
    scene::Values base;
    std::vector<SweepAxis> axes;
    scene::Values match;    ///< no values given: no width matching
    bool matching = false;  ///< [match] present
    std::vector<PlotSpec> plots;
    std::string sheetFile = "contact_sheet.png", sheetRowKey, sheetColumnKey, sheetSize = "256x192";
    std::string sheetFov;  ///< [contact_sheet] fov: the photo views' field of view ("" = the view's default, 40 deg)
    std::vector<std::string> sheetRows, sheetColumns;
    std::vector<scene::Values> sheetRowValues, sheetColumnValues;
    std::vector<std::pair<std::string, std::string>> strips;  ///< [[strip]]: material, PNG file
    std::string summarySeries, summaryX = "incidence_deg";
    std::vector<double> summaryAt;
    /// Report sections the file asks for by name ([summary] sections = [...]): "shape" (the aspect against
    /// cos theta_i headline table), "microgeometry" (bump convergence); by default "shape" with a series.
    std::vector<std::string> sections;
    bool referenceErrors = false;  ///< [reference] errors = true: each row's error against the double reference
    int repeats = 1, warmup = 0;   ///< [timing]: each configuration measured warmup + repeats times
    bool timing = false;           ///< [timing] present: rows get time_ms, the median of the repeats
    std::vector<ParetoSpec> pareto;
    /// [fit]: each configuration is a fit target (experiments/fit.hpp), its row the ranking of the models.
    std::optional<FitOptions> fit;
    /// [bounces]: each configuration is a bounce study (experiments/bounces.hpp), its row energy and colour per
    /// bounce order; `colours` names the PNG of each order's colour ("" = none).
    std::optional<BounceSettings> bounces;
    std::string bounceColoursFile;

    /// Every configuration, validated (a bad value anywhere fails before anything runs); validation longer
    /// than a second reports its progress on stderr. With a shard K/N, only the configurations i with
    /// i mod N = K - 1 are validated, the ones a `run --shard K/N` writes (`submit` validates them all first:
    /// each array task would otherwise repeat the whole experiment's validation, 12.7 s for 10^6).
    class Configurations configurations(int shardK = 1, int shardN = 1) const;
};

/// The configurations of an experiment, each built from the axes when asked for: 10^6 held at once took
/// 1.1 GB. Index i is configuration i (the last axis varies fastest). The experiment must outlive it.
class Configurations {
public:
    explicit Configurations(const Experiment& e);
    size_t size() const { return m_size; }
    Configuration operator[](size_t index) const;

    class iterator {
    public:
        iterator(const Configurations* c, size_t i) : m_c(c), m_i(i) {}
        Configuration operator*() const { return (*m_c)[m_i]; }
        iterator& operator++() { return ++m_i, *this; }
        bool operator!=(const iterator& o) const { return m_i != o.m_i; }

    private:
        const Configurations* m_c;
        size_t m_i;
    };
    iterator begin() const { return {this, 0}; }
    iterator end() const { return {this, m_size}; }

private:
    const Experiment* m_e;
    size_t m_size = 1;
};

/// The columns of the experiment's rows: config, the case axes and their tags, every registry column, every
/// measurement field, then the [reference] and [timing] columns (what plots, the summary and [[pareto]] may read).
std::vector<std::string> rowColumns(const Experiment& e);

/// A path, or the name of a file shipped in experiments/ (found beside the executable like the shaders).
std::string findExperiment(const std::string& nameOrPath);
/// The names of the experiments shipped in the share folder's experiments/ (as `hilite run NAME` takes them).
std::vector<std::string> shippedExperiments();
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

/// The width parameter (exponent or roughness, as the model takes) of `scene`'s model whose twin's semi-major
/// axis at normal incidence is `targetMajorDeg` at the threshold: [match]'s bisection (hilite serve's pair too).
double matchedWidth(render::Scene scene, double targetMajorDeg, double threshold);

class ExperimentRunner {
public:
    ExperimentRunner(const Experiment& e, const std::string& backend);
    ~ExperimentRunner();
    /// The fixed CSV columns: config, the case tags, every registry column, every measurement field.
    const std::vector<std::string>& columns() const { return m_columns; }
    /// Probes every .brdf shader (file and values) the configurations i with i mod shardN = shardK - 1 use,
    /// so that a shader that does not build or runs too long fails before any result file is written.
    void probeAll(const Configurations& configs, int shardK, int shardN);
    /// Measures one configuration: one JSON row.
    nlohmann::json measure(const Configuration& c);
    /// Plots, contact sheet, strips and summary.md from the complete rows. seconds < 0: unknown (merge).
    void finalize(const std::string& dir, const Rows& rows, double seconds);

    /// [match]: each model's width parameter tuned so that its semi-major axis at normal incidence equals the
    /// target's; sets it in `values` and `row["matched_parameter"]`.
    void applyMatch(scene::Values& values, nlohmann::json& row);
    /// [fit]: the configuration is a fit target; its row ranks the models (experiments/fit.hpp).
    nlohmann::json fitRow(const scene::Values& values, nlohmann::json& row);
    /// [bounces]: the configuration is a bounce study; its row holds the study's fields.
    nlohmann::json bounceRow(const scene::Values& values, nlohmann::json& row);
    /// A photo view of the scene `values` resolve to (the contact sheet's tiles).
    ImageF photo(const scene::Values& values, int width, int height);
    const Experiment& experiment() const { return m_exp; }
    double targetMajorDeg() const { return m_targetMajorDeg; }
    const std::map<std::string, double>& matched() const { return m_matched; }

private:
    /// The double reference of a configuration's scene (with its case's reference keys), cached by scene.
    const analysis::Shape& reference(const Configuration& c, scene::Values values);

    const Experiment& m_exp;
    std::vector<std::string> m_columns;
    double m_targetMajorDeg = 0;
    std::map<std::string, double> m_matched;              ///< model -> matched width parameter
    std::map<std::string, analysis::Shape> m_references;  ///< reference scene -> its measurement
    measurement::Session m_session;
};

}  // namespace hilite::experiments
