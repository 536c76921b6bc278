// Runs the configurations of an experiment and makes its pictures and summary.

#include "cli/experiment.hpp"
#include "cli/shader_probe.hpp"
#include "core/error.hpp"
#include "brdf/evaluate.hpp"
#include "experiments/measure_bumps.hpp"
#include "experiments/strip.hpp"
#include "cli/micro_fields.hpp"
#include "io/image_io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace hilite::cli {

namespace {

const std::vector<std::string> kMeasureColumns = {
    "model", "incidence_deg", "aspect", "eccentricity", "major_deg", "minor_deg", "orientation_deg",
    "centroid_u_deg", "centroid_v_deg", "fwhm_u_deg", "fwhm_v_deg", "peak", "peak_u_deg", "peak_v_deg",
    "area_deg2", "cos_incidence", "flags", "renders", "size", "fov_deg", "minor_pixels", "method",
    "matched_parameter", "brdf_params", "framing", "framing_note", "error_estimate", "error_estimate_from",
    "render_ms", "measure_ms",
    // issue 10: what the highlight is measured about (retroreflection: its peak), a tabulated NDF's factor
    "framed_about", "peak_offset_deg", "ndf_table_normalization",
    // issue 10, explicit micro-geometry (empty on flat surfaces): see cli/micro_fields.hpp
    "log2_bump_period_px", "bump_samples_center", "analytic_aspect", "analytic_major_deg", "analytic_minor_deg",
    "aspect_minus_analytic", "major_over_analytic", "minor_over_analytic", "slope_rms", "slope_ks", "bump_filter_used",
    "prefilter_aspect", "prefilter_aspect_minus_analytic", "prefilter_major_over_analytic",
    "prefilter_minor_over_analytic", "next_seed_aspect", "next_seed_aspect_minus_analytic",
    "next_seed_major_over_analytic", "next_seed_minor_over_analytic", "prefilter_block_error",
    "supersample_block_noise", "prefilter_error", "prefilter_blocks", "prefilter_unresolved_blocks"};
const std::vector<std::string> kNotSceneParams = {"help", "scene", "output", "float", "exposure", "json",
                                                  "reference", "gl-backend", "incidence", "shader-timeout"};
/// With --brdf, the built-in model's flags mean nothing: their columns are left empty (null).
const std::vector<std::string> kBrdfFileParams = {"brdf", "param", "tangent-angle"};

std::string num(double v) {
    std::ostringstream s;
    s << std::setprecision(17) << v;
    return s.str();
}

nlohmann::json typed(const std::string& v) {
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (!v.empty() && end == v.c_str() + v.size() && std::isfinite(d)) return d;
    return v;
}

std::string paramName(const CLI::Option& o) {
    std::string n = o.get_lnames().front();
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
}

bool isSceneParam(const CLI::Option& o) {
    return !o.get_lnames().empty() && std::find(kNotSceneParams.begin(), kNotSceneParams.end(),
                                                o.get_lnames().front()) == kNotSceneParams.end();
}

}  // namespace

ExperimentRunner::ExperimentRunner(const Experiment& e, const std::string& backend) : m_exp(e), m_backend(backend) {
    CLI::App app;
    MeasureFlags f;
    addMeasureFlags(app, f);
    m_columns.push_back("config");
    for (const CLI::Option* o : app.get_options())
        if (isSceneParam(*o) && std::find(kMeasureColumns.begin(), kMeasureColumns.end(), paramName(*o)) ==
                                    kMeasureColumns.end())
            m_columns.push_back(paramName(*o));
    m_columns.insert(m_columns.end(), kMeasureColumns.begin(), kMeasureColumns.end());
    // Case axes: the case names and tags come first, after config (what the row is about).
    std::vector<std::string> tagColumns;
    for (const auto& a : e.axes)
        if (!a.cases.empty()) {
            tagColumns.push_back(a.key);
            for (const auto& c : a.cases)
                for (const auto& [k, v] : c.tags.items())
                    if (std::find(tagColumns.begin(), tagColumns.end(), k) == tagColumns.end()) tagColumns.push_back(k);
        }
    m_columns.insert(m_columns.begin() + 1, tagColumns.begin(), tagColumns.end());
    if (e.referenceErrors)
        m_columns.insert(m_columns.end(), {"ref_aspect", "ref_major_deg", "ref_minor_deg", "aspect_error",
                                           "major_error", "minor_error"});
    if (e.timing) m_columns.insert(m_columns.end(), {"time_ms", "repeats", "error_estimate"});
    if (!e.match.empty()) {
        MeasureFlags mf;
        std::vector<SceneArg> args = e.base;
        args.insert(args.end(), e.match.begin(), e.match.end());
        ResolvedMeasure target = resolve(args, mf, nullptr);
        if (target.scene.brdfFile)
            throw InputError(e.path + ": [match]: matching widths needs a CPU twin, and a .brdf file has none "
                                      "(set its parameters by hand)");
        target.scene.light.incidenceDeg = 0;
        m_targetMajorDeg = rad2deg(experiments::twinHalfWidth(target.scene, target.setup.options.threshold));
    }
}

ExperimentRunner::~ExperimentRunner() = default;

render::Renderer& ExperimentRunner::renderer() {
    if (!m_renderer) {
        m_context = std::make_unique<gl::Context>(parseBackendFlag(m_backend));
        m_renderer = std::make_unique<render::Renderer>(*m_context);
    }
    return *m_renderer;
}

void ExperimentRunner::prepare(const render::Scene& scene, double shaderTimeout) {
    if (!scene.brdfFile) return;
    // Each .brdf file with each set of values passes the probe once (cli/shader_probe.hpp).
    const std::string key = scene.brdfFile->path + "|" + brdf_file::valuesText(*scene.brdfFile) + "|" +
                            render::toString(scene.light.type);
    if (m_probed.insert(key).second) {
        if (m_noted.insert(scene.brdfFile->path).second)
            for (const std::string& note : scene.brdfFile->notes) std::cerr << "hilite: note: " << note << "\n";
        probeShader(scene, m_backend, shaderTimeout);
    }
    renderer().setShaderTimeLimit(shaderTimeout);
}

void ExperimentRunner::probeAll(const std::vector<Configuration>& configs, int shardK, int shardN) {
    std::set<std::string> seen;
    for (const Configuration& c : configs) {
        if (c.index % shardN != shardK - 1) continue;
        // Only the flags the probe depends on decide whether a configuration needs its own probe.
        std::string key;
        for (const SceneArg& a : c.args)
            if (a.flag == "--brdf" || a.flag == "--param" || a.flag == "--light" || a.flag == "--reference")
                key += a.flag + "=" + a.value + "\n";
        if (key.find("--brdf=") == std::string::npos || !seen.insert(key).second) continue;
        MeasureFlags f;
        const ResolvedMeasure r = resolve(c.args, f, nullptr);
        if (!f.reference) prepare(r.scene, f.scene.shaderTimeout);
    }
}

ResolvedMeasure ExperimentRunner::resolve(const std::vector<SceneArg>& args, MeasureFlags& flags,
                                          nlohmann::json* params) const {
    CLI::App app;
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    addMeasureFlags(app, flags);
    std::vector<std::string> argv;
    std::map<std::string, std::string> origins;
    for (const auto& a : args) {
        argv.push_back(a.flag);
        if (!a.value.empty()) argv.push_back(a.value);
        origins[a.flag] = a.origin;
    }
    std::reverse(argv.begin(), argv.end());
    ResolvedMeasure r;
    try {
        app.parse(argv);
        r = resolveMeasure(flags);
    } catch (const CLI::ParseError& e) {
        throw InputError(withOrigin(e.what(), origins));
    } catch (const InputError& e) {
        throw InputError(withOrigin(e.what(), origins));
    }
    if (params)
        for (const CLI::Option* o : app.get_options())
            if (isSceneParam(*o)) {
                std::string v = o->count() ? o->results().back() : o->get_default_str();
                if (o->get_multi_option_policy() == CLI::MultiOptionPolicy::TakeAll) {  // --param: all of them
                    v.clear();
                    for (const auto& x : o->results()) v += (v.empty() ? "" : ",") + x;
                }
                const bool builtinOnly = r.scene.brdfFile && sectionOf(*o) == "material" &&
                                         std::find(kBrdfFileParams.begin(), kBrdfFileParams.end(),
                                                   o->get_lnames().front()) == kBrdfFileParams.end();
                (*params)[paramName(*o)] = builtinOnly ? nlohmann::json(nullptr) : typed(v);
            }
    return r;
}

void ExperimentRunner::applyMatch(std::vector<SceneArg>& args, nlohmann::json& row) {
    if (m_exp.match.empty()) return;
    MeasureFlags f;
    ResolvedMeasure r = resolve(args, f, nullptr);
    if (r.scene.brdfFile)
        throw InputError(m_exp.path + ": [match]: matching widths needs a CPU twin, and " + r.scene.brdfFile->path +
                         " (a .brdf file) has none: set its parameters by hand");
    r.scene.light.incidenceDeg = 0;
    const std::string key = brdf::toString(r.scene.brdf.model);
    const bool exponent = brdf::usesExponent(r.scene.brdf.model);
    auto it = m_matched.find(key);
    if (it == m_matched.end()) {
        // Bisection in log(parameter) on the twin's half-width at normal incidence, where every isotropic
        // lobe is round, so its angular radius is its semi-major axis.
        double lo = std::log(exponent ? 1e-2 : 1e-4), hi = std::log(exponent ? 1e8 : 2.0);
        for (int i = 0; i < 80; ++i) {
            const double mid = 0.5 * (lo + hi);
            (exponent ? r.scene.brdf.exponent : r.scene.brdf.roughness) = std::exp(mid);
            const double w = rad2deg(experiments::twinHalfWidth(r.scene, r.setup.options.threshold));
            ((w > m_targetMajorDeg) == exponent ? lo : hi) = mid;
        }
        it = m_matched.emplace(key, std::exp(0.5 * (lo + hi))).first;
    }
    args.push_back(SceneArg{exponent ? "--exponent" : "--roughness", num(it->second), "[match]"});
    row["matched_parameter"] = it->second;
}

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

const measure::Shape& ExperimentRunner::reference(const Configuration& c, std::vector<SceneArg> args) {
    args.insert(args.end(), c.reference.begin(), c.reference.end());
    MeasureFlags f;
    const ResolvedMeasure r = resolve(args, f, nullptr);
    std::ostringstream key;  // the scene and the threshold define the reference; the settings do not
    key << r.scene << " incidence=" << r.angles.front() << " threshold=" << r.setup.options.threshold;
    auto it = m_references.find(key.str());
    if (it == m_references.end()) {
        render::Scene scene = r.scene;
        scene.light.incidenceDeg = r.angles.front();
        it = m_references.emplace(key.str(), experiments::measureReference(scene, r.setup.options).shape).first;
    }
    return it->second;
}

void ExperimentRunner::addErrors(nlohmann::json& row, const measure::Shape& ref) const {
    row["ref_aspect"] = ref.aspect;
    row["ref_major_deg"] = ref.major_deg;
    row["ref_minor_deg"] = ref.minor_deg;
    auto num = [&](const char* k) { return row.contains(k) && row[k].is_number() ? row[k].get<double>() : NAN; };
    const double a = num("aspect"), ma = num("major_deg"), mi = num("minor_deg");
    auto json = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    row["aspect_error"] = json(std::abs(a - ref.aspect));
    row["major_error"] = json(std::abs(ma / ref.major_deg - 1.0));  // relative
    row["minor_error"] = json(std::abs(mi / ref.minor_deg - 1.0));
}

nlohmann::json ExperimentRunner::measure(const Configuration& c) {
    nlohmann::json row;
    row["config"] = c.index;
    for (const auto& [k, v] : c.tags.items()) row[k] = v;
    std::vector<SceneArg> args = c.args;
    applyMatch(args, row);
    MeasureFlags f;
    nlohmann::json params;
    ResolvedMeasure r = resolve(args, f, &params);
    if (r.angles.size() != 1)
        throw InputError(m_exp.path + ": light.incidence: one angle per configuration (sweep it with [[sweep]])");
    for (auto& [k, v] : params.items()) row[k] = v;
    if (!f.reference) prepare(r.scene, f.scene.shaderTimeout);
    render::Renderer* gl = f.reference || r.setup.cpu ? nullptr : &renderer();
    // [timing]: warm-up runs (programs compiled, buffers allocated), then the median of the repeats'
    // wall times; the row's numbers are the last repeat's (every repeat measures the same).
    const int warmup = m_exp.timing ? m_exp.warmup : 0, repeats = m_exp.timing ? m_exp.repeats : 1;
    for (int i = 0; i < warmup; ++i) measureRow(gl, r, f);
    nlohmann::json measured;
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        measured = measureRow(gl, r, f);
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        // --tolerance times itself without its one-off warm-up measurement (startup_ms): take its word.
        times.push_back(measured.contains("time_ms") ? measured["time_ms"].get<double>() : wall);
    }
    for (auto& [k, v] : measured.items()) row[k] = v;
    if (m_exp.timing) {
        row["time_ms"] = median(times);
        row["repeats"] = repeats;
    }
    if (m_exp.referenceErrors) addErrors(row, reference(c, args));
    return row;
}

void ExperimentRunner::finalize(const std::string& dir, const std::vector<nlohmann::json>& rows, double seconds) {
    std::vector<std::string> notes;
    for (const auto& p : m_exp.plots) {
        std::string why;
        if (!experiments::plot(dir, p, rows, why)) notes.push_back("plot " + p.file + " not made: " + why);
    }
    // Contact sheet: photo views, one row per sheet row value, one column per column value.
    const bool sheet = !m_exp.sheetRows.empty() && !m_exp.sheetColumns.empty();
    if (sheet) {
        int tw = 256, th = 192;
        parseSize(m_exp.sheetSize, tw, th);
        const int gap = 4, cols = int(m_exp.sheetColumns.size()), nrows = int(m_exp.sheetRows.size());
        ImageF sheetImg(cols * tw + (cols - 1) * gap, nrows * th + (nrows - 1) * gap, 4);
        for (int ri = 0; ri < nrows; ++ri)
            for (int ci = 0; ci < cols; ++ci) {
                std::vector<SceneArg> args = m_exp.base;
                auto flagOf = [](std::string key) {
                    key = key.substr(key.find('.') + 1);
                    std::replace(key.begin(), key.end(), '_', '-');
                    return "--" + key;
                };
                args.push_back({flagOf(m_exp.sheetRowKey), m_exp.sheetRows[size_t(ri)], "[contact_sheet]"});
                args.push_back({flagOf(m_exp.sheetColumnKey), m_exp.sheetColumns[size_t(ci)], "[contact_sheet]"});
                nlohmann::json ignored;
                applyMatch(args, ignored);
                MeasureFlags f;
                ResolvedMeasure r = resolve(args, f, nullptr);
                prepare(r.scene, f.scene.shaderTimeout);
                const PinholeCamera cam = viewCamera(f.scene, View::Photo, r.scene, tw, th);
                const ImageF tile = renderer().render(r.scene, cam, render::Output::Color);
                double peak = 0;
                for (size_t i = 0; i < tile.data.size(); i += 4) peak = std::max(peak, double(tile.data[i + 1]));
                const double scale = peak > 0 ? 1.0 / peak : 1.0;  // each tile exposed to its own peak
                for (int y = 0; y < th; ++y)
                    for (int x = 0; x < tw; ++x)
                        for (int c = 0; c < 4; ++c)
                            sheetImg.pixel(ci * (tw + gap) + x, (nrows - 1 - ri) * (th + gap) + y)[c] =
                                float(tile.pixel(x, y)[c] * (c < 3 ? scale : 1.0));
            }
        io::writePng(dir + "/" + m_exp.sheetFile, sheetImg, {});
    }
    // Fresnel strips: the material's colour from normal incidence to grazing, and F against theta.
    std::ostringstream stripNotes;
    for (const auto& [material, file] : m_exp.strips) {
        SceneFlags sf;
        sf.material = material;
        const brdf::Params p = brdfParams(sf);
        experiments::writeFresnelStrip(p, 512, 64, dir + "/" + file);
        std::vector<nlohmann::json> frows;
        for (int t = 0; t <= 90; ++t) {
            double c, s;
            cosSinDeg(t, c, s);
            const dvec3 F = brdf::fresnel(p, c);
            for (int ch = 0; ch < 3; ++ch) frows.push_back({{"theta_deg", t}, {"channel", std::string(1, "rgb"[ch])}, {"F", F[ch]}});
        }
        experiments::PlotSpec spec;
        spec.file = material + "_fresnel.png";
        spec.title = "Fresnel reflectance of " + material + " (" + brdf::toString(p.fresnel) + "), linear sRGB";
        spec.x = "theta_deg", spec.y = "F", spec.series = "channel", spec.key = "top left";
        std::string why;
        if (!experiments::plot(dir, spec, frows, why)) notes.push_back("plot " + spec.file + " not made: " + why);
        const auto st = experiments::fresnelStats(p);
        stripNotes << std::setprecision(4) << "![" << material << " strip](" << file << ")\n\n![" << material
                   << " Fresnel](" << spec.file << ")\n\n" << material << " (" << brdf::toString(p.fresnel)
                   << "): F(0) = (" << st.normal.x << ", " << st.normal.y << ", " << st.normal.z << "), red dips to "
                   << st.redMin << " at " << st.redMinThetaDeg << " deg, F(89) = (" << st.grazing89.x << ", "
                   << st.grazing89.y << ", " << st.grazing89.z << ").\n\n";
    }
    // summary.md
    std::ostringstream md;
    md << "# " << m_exp.title << "\n\n" << m_exp.description << "\n\n";
    md << rows.size() << " configurations";
    if (seconds >= 0) md << ", measured in " << std::fixed << std::setprecision(2) << seconds << " s";
    md << std::defaultfloat << ". Rows: [results.csv](results.csv), [results.jsonl](results.jsonl).\n\n";
    if (!m_matched.empty()) {
        md << "Lobe widths matched at normal incidence to a semi-major axis of " << std::setprecision(5)
           << m_targetMajorDeg << " deg:\n\n| model | parameter |\n|---|---|\n";
        for (const auto& [k, v] : m_matched) md << "| " << k << " | " << std::setprecision(6) << v << " |\n";
        md << "\n";
    }
    for (const auto& p : m_exp.plots) md << "![" << p.title << "](" << p.file << ")\n\n";
    md << stripNotes.str();
    if (sheet)
        md << "![contact sheet](" << m_exp.sheetFile << ")\n\nContact sheet: photo views, rows = " << m_exp.sheetRowKey
           << " (top to bottom), columns = " << m_exp.sheetColumnKey << " (left to right); each tile is exposed to its own peak.\n\n";
    if (!m_exp.summarySeries.empty()) {
        md << "## Headline numbers\n\n| " << m_exp.summarySeries << " | " << m_exp.summaryX
           << " | aspect | cos | eccentricity | semi-major (deg) | semi-minor (deg) | centroid u (deg) | flags |\n"
           << "|---|---|---|---|---|---|---|---|---|\n";
        std::map<std::string, std::pair<double, double>> worst;  // series -> max |aspect-1|, max |aspect-cos|
        std::vector<std::string> order;
        for (const auto& r : rows) {
            if (!r.contains(m_exp.summarySeries) || r["aspect"].is_null()) continue;
            const std::string s = r[m_exp.summarySeries].is_string() ? r[m_exp.summarySeries].get<std::string>()
                                                                      : r[m_exp.summarySeries].dump();
            if (!worst.count(s)) order.push_back(s), worst[s] = {0, 0};
            const double x = r.value(m_exp.summaryX, 0.0), a = r["aspect"].get<double>();
            if (r["flags"].empty() && x <= 80) {
                worst[s].first = std::max(worst[s].first, std::abs(a - 1));
                worst[s].second = std::max(worst[s].second, std::abs(a - r.value("cos_incidence", 1.0)));
            }
            if (std::find(m_exp.summaryAt.begin(), m_exp.summaryAt.end(), x) == m_exp.summaryAt.end()) continue;
            std::string flags;
            for (const auto& fl : r["flags"]) flags += (flags.empty() ? "" : ", ") + fl.get<std::string>();
            md << std::setprecision(5) << "| " << s << " | " << x << " | " << a << " | " << r.value("cos_incidence", 0.0)
               << " | " << r.value("eccentricity", 0.0) << " | " << r.value("major_deg", 0.0) << " | "
               << r.value("minor_deg", 0.0) << " | " << r.value("centroid_u_deg", 0.0) << " | " << flags << " |\n";
        }
        md << "\nOver the rows without flags at " << m_exp.summaryX << " <= 80:\n\n| " << m_exp.summarySeries
           << " | max abs(aspect - 1) | max abs(aspect - cos theta_i) |\n|---|---|---|\n";
        for (const auto& s : order)
            md << std::setprecision(3) << "| " << s << " | " << worst[s].first << " | " << worst[s].second << " |\n";
    }
    md << microSummary(rows);  // issue 10: bump-field rows only
    for (const auto& spec : m_exp.pareto) {
        const auto points = experiments::paretoPoints(spec, rows);
        std::string why;
        if (!experiments::plotPareto(dir, spec, points, why)) notes.push_back("plot " + spec.file + " not made: " + why);
        md << experiments::paretoMarkdown(spec, points);
    }
    if (m_exp.timing)
        md << "Times: wall clock of one whole measurement (framing, renders, readback, analysis) in the running "
              "process, the median of "
           << m_exp.repeats << " repeats after " << m_exp.warmup << " warm-up run(s) per row.\n";
    for (const auto& n : notes) md << "\nNote: " << n << "\n";
    io::writeFileAtomic(dir + "/summary.md", md.str());
}

}  // namespace hilite::cli
