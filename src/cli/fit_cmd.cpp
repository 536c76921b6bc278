// `hilite fit`: fit analytic models to a target (a MERL or RGL table, a .brdf file or a built-in model)
// over a sweep of incidence and thresholds, and rank them (experiments/fit.hpp).

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "core/text.hpp"
#include "hilite/core/error.hpp"
#include "hilite/experiments/fit.hpp"
#include "io/image_io.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace hilite::cli {

namespace {

std::string numbersText(const std::vector<double>& v) {
    std::vector<std::string> t;
    for (double x : v) t.push_back(exactText(x));
    return join(t, ",");
}

struct FitFlags {
    SceneOptions scene;
    experiments::FitOptions options;  // the defaults: the library's, as Python's and experiment files'
    std::string target, models = join(options.models, ","), thresholds = numbersText(options.thresholds), weights,
                        output;
    bool json = false;
};

std::vector<double> numbers(const std::string& flag, const std::string& text) {
    std::vector<double> out;
    for (const std::string& item : split(text, ',')) {
        const auto v = parseNumber(item);
        if (!v)
            throw InputError(flag + ": '" + item + "' is not a number (give a comma-separated list, e.g. 0.1,0.5,0.9)");
        out.push_back(*v);
    }
    return out;
}

std::string paramsText(const nlohmann::ordered_json& p) {
    std::string s;
    for (const auto& [k, v] : p.items()) {
        char buf[64];
        if (v.is_string()) std::snprintf(buf, sizeof buf, "%s=%s", k.c_str(), v.get<std::string>().c_str());
        else if (v.is_array())
            std::snprintf(buf, sizeof buf, "%s=%.4g,%.4g,%.4g", k.c_str(), v[0].get<double>(), v[1].get<double>(),
                          v[2].get<double>());
        else std::snprintf(buf, sizeof buf, "%s=%.6g", k.c_str(), v.get<double>());
        s += (s.empty() ? "" : " ") + std::string(buf);
    }
    return s;
}

std::string residualText(double v) {
    char buf[32];
    if (std::isfinite(v)) std::snprintf(buf, sizeof buf, "%.3e", v);
    else std::snprintf(buf, sizeof buf, "-");
    return buf;
}

/// "; at its search bound: roughness, f0" (empty when no parameter is).
std::string atBoundText(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "; at its search bound: " : ", ") + n;
    return s;
}

void printTable(const experiments::FitResult& r) {
    std::printf("target: %s; %zu incidences x %zu thresholds (", r.target.c_str(), r.angles.size(),
                r.thresholds.size());
    for (size_t j = 0; j < r.thresholds.size(); ++j)
        std::printf("%s%g weight %g", j ? ", " : "", r.thresholds[j], r.weights[j]);
    std::printf(
        ")\nshape: weighted RMS of ln(fit / target) of the semi-axes; values: RMS of ln(1 + f cos theta_i), "
        "fit against target, over the measured directions%s\nranked by %s\n\n",
        r.hasValues ? "" : " (none: a .brdf file has no double evaluation)", r.rankBy.c_str());
    std::printf("%-4s %-14s %-44s %10s %10s %6s %8s  %s\n", "rank", "model", "params", "shape", "values", "evals",
                "time_s", "stop");
    for (const auto& m : r.fits)
        std::printf("%-4d %-14s %-44s %10s %10s %6d %8.2f  %s%s\n", m.rank, m.model.c_str(),
                    paramsText(m.params).c_str(), residualText(m.shapeResidual).c_str(),
                    residualText(m.valuesResidual).c_str(), m.evaluations, m.ms / 1000.0, m.stop.c_str(),
                    (atBoundText(m.atBound) + (m.tie ? " (tie)" : "")).c_str());
    std::printf(
        "\nverdict: %s (best %s residual %s; the target's resolution %.2e; no model fits above %.2e, a tie "
        "within %.2e)\n",
        r.verdict.c_str(), r.rankBy.c_str(), residualText(r.fits.front().residual).c_str(), r.resolution, r.tolerance,
        r.tieMargin);
    std::printf("\naspect at threshold %g (fit - target per model):\n%6s %9s", r.aspectThreshold, "theta", "target");
    for (const auto& m : r.fits) std::printf(" %14s", m.model.c_str());
    std::printf("\n");
    const size_t nt = r.thresholds.size();
    const size_t jt = experiments::aspectIndex(r);
    std::vector<std::vector<double>> d;
    for (const auto& m : r.fits) d.push_back(experiments::aspectResiduals(r, m));
    for (size_t i = 0; i < r.angles.size(); ++i) {
        const auto& t = r.samples[i * nt + jt];
        if (t.usable) std::printf("%6.2f %9.5f", r.angles[i], t.aspect);
        else std::printf("%6.2f %9s", r.angles[i], t.why.c_str());
        for (const auto& di : d) {
            if (std::isfinite(di[i])) std::printf(" %+14.5f", di[i]);
            else std::printf(" %14s", "-");
        }
        std::printf("\n");
    }
}

int runFit(FitFlags& f) {
    scene::Values values = commandValues(f.scene);
    if (!f.target.empty()) {
        const std::string ext = std::filesystem::path(f.target).extension().string();
        if (ext == ".binary" || ext == ".bsdf") values.set("measured", f.target, "--target");
        else if (ext == ".brdf") values.set("brdf", f.target, "--target");
        else
            throw InputError("--target: '" + f.target +
                             "' must be a MERL .binary table or a BRDF Explorer .brdf file "
                             "(or give the target as --model ...)");
    }
    f.options.models = split(f.models, ',');
    f.options.thresholds = numbers("--thresholds", f.thresholds);
    if (!f.weights.empty()) f.options.weights = numbers("--weights", f.weights);
    experiments::checkFitOptions(f.options);
    if (!f.output.empty()) {  // checked before anything is measured: a folder that can be made, files replaceable
        io::checkOutputDir(f.output, "-o");
        if (std::filesystem::is_directory(f.output))  // files of an earlier fit there: replaceable ones only
            for (const char* file : {"fit.json", "fit.csv", "fit_aspect.png", "fit_residual.png"})
                io::checkWritable(f.output + "/" + file, "-o");
    }
    measurement::Session session;
    const experiments::FitResult r = experiments::fitModels(session, values, f.options);
    if (!f.output.empty()) {
        io::makeOutputDir(f.output, "-o");
        std::string why;
        if (!experiments::writeFitFolder(f.output, r, why))
            std::cerr << "hilite: warning: fit plots not made: " << why << "\n";
    }
    if (f.json) {
        for (const auto& m : r.fits) std::cout << experiments::toJson(r, m).dump() << "\n";
    } else {
        printTable(r);
        if (!f.output.empty())
            std::printf("\nwrote %s/fit.json, fit.csv, fit_aspect.png, fit_residual.png\n", f.output.c_str());
    }
    return 0;
}

}  // namespace

Action addFit(CLI::App& app) {
    auto f = std::make_shared<FitFlags>();
    f->scene.defaults["incidence"] = "0:85:5";
    f->scene.defaults["size"] = "256";
    addParamFlags(app, f->scene);
    const char* g = "Fit";
    app.add_option("--target", f->target,
                   "what to fit: a MERL .binary table or a .brdf file (else the material flags, e.g. --model ggx "
                   "--roughness 0.1)")
        ->group(g);
    app.add_option("--models", f->models,
                   "models to fit, comma-separated: phong, phong-classic, retro, blinn, gaussian, beckmann, ggx")
        ->capture_default_str()
        ->group(g);
    app.add_option("--thresholds", f->thresholds, "thresholds of the measured regions, each in (0, 1)")
        ->capture_default_str()
        ->group(g);
    app.add_option("--weights", f->weights, "a weight >= 0 per threshold (default 1 each)")->group(g);
    app.add_flag("--fit-anisotropy", f->options.anisotropy, "fit roughness_y too (beckmann, ggx)")->group(g);
    app.add_flag("--fit-f0,!--no-fit-f0", f->options.f0,
                 "fit a Schlick F0 (microfacet models; default on, --no-fit-f0: F0 0.04)")
        ->group(g);
    app.add_option(
           "--fit-geometry", f->options.geometry,
           "the fitted microfacet models' --geometry; auto: smith or implicit, whichever fits the values better")
        ->capture_default_str()
        ->check(CLI::IsMember(experiments::fitGeometries()))
        ->group(g);
    app.add_option("--fit-fresnel", f->options.fresnel, "the fitted microfacet models' --fresnel")
        ->capture_default_str()
        ->check(CLI::IsMember({"schlick", "none"}))
        ->group(g);
    app.add_option("--fit-diffuse", f->options.diffuse,
                   "a Lambertian albedo in every fitted model: auto (where the values fit finds one >= 0.001), on, "
                   "off")
        ->capture_default_str()
        ->check(CLI::IsMember(experiments::fitDiffuseChoices()))
        ->group(g);
    app.add_flag("--fit-color", f->options.color,
                 "F0 and the albedo per channel (RGB), refitted by values at the width found")
        ->group(g);
    app.add_option("--rank-by", f->options.rankBy,
                   "the ranking criterion: shape (the highlight's semi-axes) or values (the BRDF over the measured "
                   "directions); both are reported")
        ->capture_default_str()
        ->check(CLI::IsMember(experiments::fitCriteria()))
        ->group(g);
    app.add_option("--max-evaluations", f->options.maxEvaluations, "per model: measured sweeps at most")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000))
        ->group(g);
    app.add_option("-o,--output", f->output, "folder for fit.json, fit.csv and the plots")->check(nonEmpty())->group(g);
    app.add_flag("--json", f->json, "one JSON object per model instead of the table")->group("Output");
    app.footer(
        "Example: hilite fit --target gold-metallic-paint.binary --models phong,blinn,beckmann,ggx -o results/fit\n"
        "         hilite fit --target paper_white_rgb.bsdf --lobe mirror --rank-by values\n"
        "         hilite fit --model ggx --roughness 0.1 --models phong,ggx --json");
    return [f] { return runFit(*f); };
}

}  // namespace hilite::cli
