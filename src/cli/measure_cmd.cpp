// `hilite measure`: the highlight's shape per angle of incidence, as a table or JSON lines.

#include "cli/measure_cmd.hpp"

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "cli/scene_file.hpp"
#include "cli/shader_probe.hpp"
#include "core/error.hpp"
#include "experiments/measure_bumps.hpp"
#include "experiments/measure_scene.hpp"
#include "experiments/peak_frame.hpp"
#include "brdf/ndf_table.hpp"
#include "cli/micro_fields.hpp"
#include "experiments/tolerance.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <tuple>

namespace hilite::cli {

nlohmann::json measurementRow(const render::Scene& s, const experiments::Measurement& m, const MeasureFlags& f, int width,
                   int height, const std::string& method) {
    const measure::Shape& r = m.shape;
    nlohmann::json j;
    if (s.brdfFile) {  // a .brdf file: its name stands for the model, its values for the parameters
        j["model"] = s.brdfFile->path.substr(s.brdfFile->path.rfind('/') + 1);
        j["brdf"] = s.brdfFile->path;
        j["brdf_params"] = brdf_file::valuesText(*s.brdfFile);
    } else {
        j["model"] = brdf::toString(s.brdf.model);
        if (brdf::usesExponent(s.brdf.model)) j["exponent"] = s.brdf.exponent;
        else if (s.brdf.model != brdf::Model::Tabulated) j["roughness"] = s.brdf.roughness;  // a table has no width knob
        if (s.brdf.model == brdf::Model::Tabulated && s.brdf.ndfTable) {  // issue 10: the table and its normalization
            j["ndf_table"] = s.brdf.ndfTable->file;
            j["ndf_table_normalization"] = s.brdf.ndfTable->normalization;
        }
        j["fresnel"] = brdf::toString(s.brdf.fresnel);
        j["geometry"] = brdf::toString(s.brdf.geometry);
    }
    j["incidence_deg"] = s.light.incidenceDeg;
    j["light"] = render::toString(s.light.type);
    // Under a point light each point of the plane has its own wi: the measured lobe is the eye's view.
    j["lobe"] = s.light.type == render::LightType::Point
                    ? "as seen by the eye at distance " + std::to_string(s.eyeDistance) + " (point light)"
                    : std::string("exitant directions (distant light)");
    j["azimuth_deg"] = s.light.azimuthDeg;
    j["threshold"] = f.threshold;
    j["method"] = method;
    double offsetDeg = 0;  // issue 10: a highlight far from the mirror direction is measured about its peak
    j["framed_about"] = experiments::framedAbout(s, f.threshold, offsetDeg);
    j["peak_offset_deg"] = offsetDeg;
    for (auto [key, v] : {std::pair{"aspect", r.aspect}, {"eccentricity", r.eccentricity}, {"major_deg", r.major_deg},
                          {"minor_deg", r.minor_deg}, {"orientation_deg", r.orientation_deg},
                          {"centroid_u_deg", r.centroid_u_deg}, {"centroid_v_deg", r.centroid_v_deg},
                          {"fwhm_u_deg", r.fwhm_u_deg}, {"fwhm_v_deg", r.fwhm_v_deg}, {"peak", r.peak},
                          {"peak_u_deg", r.peak_u_deg}, {"peak_v_deg", r.peak_v_deg}, {"area_deg2", r.area_deg2}})
        j[key] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    j["cos_incidence"] = s.light.direction().z;
    nlohmann::json flags = nlohmann::json::array();
    for (auto fl : r.flags) flags.push_back(measure::toString(fl));
    j["flags"] = flags;
    j["renders"] = m.renders;
    j["size"] = method != "reference" ? std::to_string(width) + "x" + std::to_string(height) : "";
    j["fov_deg"] = m.fovDeg;
    j["minor_pixels"] = std::isfinite(r.minor_pixels) ? nlohmann::json(r.minor_pixels) : nlohmann::json(nullptr);
    j["render_ms"] = m.render_ms;
    j["measure_ms"] = m.measure_ms;
    if (s.surface.bumps) addMicroFields(j, s, m, f.threshold, width, height);  // issue 10: bump period, analytic twin
    j["framing"] = m.framing;
    if (!m.framingNote.empty()) j["framing_note"] = m.framingNote;
    if (m.halfResolution) {
        // No CPU twin for a .brdf: the error is estimated by measuring the same frame at half the size.
        const measure::Shape& h = *m.halfResolution;
        nlohmann::json e;
        for (auto [key, a, b] : {std::tuple{"aspect", r.aspect, h.aspect}, {"eccentricity", r.eccentricity, h.eccentricity},
                                 {"major_deg", r.major_deg, h.major_deg}, {"minor_deg", r.minor_deg, h.minor_deg},
                                 {"centroid_u_deg", r.centroid_u_deg, h.centroid_u_deg},
                                 {"centroid_v_deg", r.centroid_v_deg, h.centroid_v_deg}})
            e[key] = std::isfinite(a - b) ? nlohmann::json(std::abs(a - b)) : nlohmann::json(nullptr);
        j["error_estimate"] = e;
        j["error_estimate_from"] = "resolution convergence (no CPU twin for .brdf)";
        j["error_estimate_sizes"] = std::to_string(width) + "x" + std::to_string(height) + " vs " +
                                    std::to_string(m.halfWidth) + "x" + std::to_string(m.halfHeight);
    }
    return j;
}

void printTableHeader() {
    std::printf("%-9s %6s %8s %8s %9s %9s %7s %8s %8s %8s %8s  %-s\n", "model", "theta", "aspect", "ecc", "major",
                "minor", "orient", "cu", "cv", "fwhm_u", "fwhm_v", "flags");
}

void printTableRow(const nlohmann::json& j) {
    std::string flags;
    for (const auto& fl : j["flags"]) flags += (flags.empty() ? "" : ",") + fl.get<std::string>();
    auto num = [&](const char* k) { return j[k].is_null() ? NAN : j[k].get<double>(); };
    // An angle: 4 decimals, or 3 significant digits below 1e-3 deg (near-mirror lobes would print 0.0000).
    auto deg = [&](const char* k, int width) {
        const double v = num(k);
        char buf[32];
        std::snprintf(buf, sizeof buf, v != 0 && std::abs(v) < 1e-3 ? "%*.2e" : "%*.4f", width, v);
        return std::string(buf);
    };
    if (j.value("framed_about", std::string("mirror direction")) != "mirror direction") {
        char about[96];
        std::snprintf(about, sizeof about, "about the peak, %.4g deg from the mirror direction", num("peak_offset_deg"));
        flags += (flags.empty() ? "" : " ") + std::string("(") + about + ")";
    }
    std::printf("%-9s %6.2f %8.5f %8.5f %s %s %7.2f %s %s %s %s  %s\n", j["model"].get<std::string>().c_str(),
                num("incidence_deg"), num("aspect"), num("eccentricity"), deg("major_deg", 9).c_str(),
                deg("minor_deg", 9).c_str(), num("orientation_deg"), deg("centroid_u_deg", 8).c_str(),
                deg("centroid_v_deg", 8).c_str(), deg("fwhm_u_deg", 8).c_str(), deg("fwhm_v_deg", 8).c_str(),
                flags.c_str());
    if (j.contains("error_estimate") && j["error_estimate"].is_object()) {  // a .brdf: resolution convergence
        auto err = [&](const char* k) {
            return j["error_estimate"][k].is_null() ? NAN : j["error_estimate"][k].get<double>();
        };
        std::printf("  error estimate (resolution convergence, no CPU twin for .brdf): aspect %.1e, major %.1e, "
                    "minor %.1e deg\n",
                    err("aspect"), err("major_deg"), err("minor_deg"));
    }
    if (j.contains("framing_note")) std::printf("  note: %s\n", j["framing_note"].get<std::string>().c_str());
}

namespace {

/// The --tolerance fields: what was asked, what was chosen, what it is estimated to reach, what it cost.
void toleranceFields(nlohmann::json& j, const experiments::ToleranceResult& r) {
    j["error_estimate"] = r.errorEstimate;
    j["predicted_error"] = r.predictedError;
    j["tolerance_met"] = r.met;
    j["settings"] = {{"size", std::to_string(r.setup.width) + "x" + std::to_string(r.setup.height)},
                     {"boundary", r.setup.options.subpixel ? "subpixel" : "pixel"},
                     {"supersample", r.setup.supersample},
                     {"framing", r.setup.fovDeg > 0 ? "fixed" : "auto"},
                     {"renderer", r.setup.cpu ? "cpu" : "gl"}};
    j["check"] = {{"size", std::to_string(r.checkSetup.width) + "x" + std::to_string(r.checkSetup.height)},
                  {"aspect", r.check.shape.aspect}};
    j["rounds"] = r.rounds;
    j["time_ms"] = r.total_ms;
    j["startup_ms"] = r.startup_ms;
}

void printToleranceLine(const nlohmann::json& j) {
    std::printf("  tolerance %g: %s, %s boundary, supersample %d -> error estimate %.2g (%s), %.2f ms\n",
                j["tolerance"].get<double>(), j["settings"]["size"].get<std::string>().c_str(),
                j["settings"]["boundary"].get<std::string>().c_str(), j["settings"]["supersample"].get<int>(),
                j["error_estimate"].get<double>(), j["tolerance_met"].get<bool>() ? "met" : "NOT met",
                j["time_ms"].get<double>());
}

/// The issue-7 knobs: --supersample, --renderer, --crop, --tolerance.
void resolveAccuracyFlags(const MeasureFlags& f, ResolvedMeasure& r);

}  // namespace

ResolvedMeasure resolveMeasure(const MeasureFlags& f) {
    ResolvedMeasure r;
    render::Scene& scene = r.scene;
    scene = sceneOf(f.scene);
    r.angles = parseIncidence(f.scene.incidence, true);
    scene.light.incidenceDeg = r.angles.front();
    experiments::MeasureSetup& setup = r.setup;
    parseSize(f.scene.size, setup.width, setup.height);
    setup.fovDeg = checkRange("--fov", f.scene.fov, 0, 160);
    setup.options.threshold = f.threshold;
    if (!(f.threshold > 0 && f.threshold < 1))
        throw InputError("--threshold: must be in (0, 1) (got " + std::to_string(f.threshold) + ")");
    if (f.minPixels < 1 || f.minPixels > 100000)
        throw InputError("--min-pixels: must be a whole number in [1, 100000] (got " + std::to_string(f.minPixels) + ")");
    setup.options.minPixelsAcross = f.minPixels;
    if (f.boundary != "subpixel" && f.boundary != "pixel")
        throw InputError("--boundary: unknown '" + f.boundary + "' (allowed: subpixel, pixel)");
    setup.options.subpixel = f.boundary == "subpixel";
    parseView(f.scene.view);  // checked, but a measurement always uses the measurement view
    if (f.reference && scene.surface.bumps)
        throw InputError("--reference: the CPU reference evaluates the analytic BRDF (drop --bumps explicit)");
    if (f.reference && scene.brdfFile)
        throw InputError("--reference: no CPU twin for a .brdf file (hilite cannot run its GLSL on the CPU); the GL "
                         "measurement reports error_estimate from resolution convergence instead");
    resolveAccuracyFlags(f, r);
    if (scene.brdfFile && r.setup.cpu)
        throw InputError("--renderer cpu: the CPU path cannot run a .brdf file's GLSL (use --renderer gl)");
    if (scene.brdfFile && r.setup.supersample > 1)
        throw InputError("--supersample: a .brdf file is framed blind and measured at one sample per pixel with the "
                         "sub-pixel boundary (its error estimate comes from resolution convergence)");
    if (scene.brdfFile && r.tolerance > 0)
        throw InputError("--tolerance: needs the CPU twin to estimate errors, which a .brdf file does not have (its "
                         "measurement reports error_estimate from resolution convergence instead)");
    // A bump field renders on the GL path only; the CPU path would silently measure the analytic BRDF instead.
    if (scene.surface.bumps && r.setup.cpu)
        throw InputError("--renderer cpu: the CPU path renders the analytic BRDF, not a bump field (drop --bumps "
                         "explicit, or use --renderer gl)");
    // --tolerance predicts the error of a size from the analytic lobe's convergence; a bump field's image changes
    // with the size itself (its period is set in pixels), so the prediction would not hold.
    if (scene.surface.bumps && r.tolerance > 0)
        throw InputError("--tolerance: calibrated on analytic lobes; a bump field's render changes with the size "
                         "(--bump-period-px is in pixels): choose --size and --bump-samples instead");
    return r;
}

namespace {

void resolveAccuracyFlags(const MeasureFlags& f, ResolvedMeasure& r) {
    experiments::MeasureSetup& setup = r.setup;
    if (f.supersample < 1 || f.supersample > experiments::kMaxSupersample)
        throw InputError("--supersample: must be a whole number in [1, " + std::to_string(experiments::kMaxSupersample) +
                         "] (got " + std::to_string(f.supersample) + ")");
    setup.supersample = f.supersample;
    if (f.renderer != "gl" && f.renderer != "cpu")
        throw InputError("--renderer: unknown '" + f.renderer + "' (allowed: gl, cpu)");
    setup.cpu = f.renderer == "cpu";
    if (f.crop != "on" && f.crop != "off") throw InputError("--crop: unknown '" + f.crop + "' (allowed: on, off)");
    setup.crop = f.crop == "on";
    if (!f.tolerance.empty()) {
        r.tolerance = checkRange("--tolerance", parseNumberFlag("--tolerance", f.tolerance), kMinTolerance, kMaxTolerance);
        if (f.reference) throw InputError("--tolerance: not with --reference (the reference has no settings to choose)");
    }
}

}  // namespace

nlohmann::json measureRow(render::Renderer* renderer, const ResolvedMeasure& r, const MeasureFlags& f) {
    const render::Scene& scene = r.scene;
    const experiments::MeasureSetup& setup = r.setup;
    if (f.reference) {
        const auto m = experiments::measureReference(scene, setup.options);
        return measurementRow(scene, m, f, setup.width, setup.height, "reference");
    }
    if (r.tolerance > 0) {
        experiments::ToleranceSetup t;
        t.tolerance = r.tolerance;
        t.base = setup;
        const experiments::ToleranceResult res = experiments::measureToTolerance(renderer, scene, t);
        nlohmann::json j = measurementRow(scene, res.measurement, f, res.setup.width, res.setup.height,
                                          setup.cpu ? "cpu" : "gl");
        toleranceFields(j, res);
        j["tolerance"] = r.tolerance;
        return j;
    }
    const auto m = experiments::measure(renderer, scene, setup);
    nlohmann::json j = measurementRow(scene, m, f, setup.width, setup.height, setup.cpu ? "cpu" : "gl");
    j["supersample"] = setup.supersample;
    if (renderer) addPrefilterFields(j, *renderer, scene, setup, m);  // issue 10: --prefilter-check
    return j;
}

namespace {

int runMeasure(const MeasureFlags& f) {
    ResolvedMeasure resolved = resolveMeasure(f);
    render::Scene& scene = resolved.scene;
    const experiments::MeasureSetup& setup = resolved.setup;
    std::unique_ptr<gl::Context> context;
    std::unique_ptr<render::Renderer> renderer;
    if (scene.brdfFile)
        for (const std::string& note : scene.brdfFile->notes) std::cerr << "hilite: note: " << note << "\n";
    if (!f.reference && !setup.cpu) {
        probeShader(scene, f.scene.backend, f.scene.shaderTimeout);  // before this process runs it
        context = std::make_unique<gl::Context>(parseBackendFlag(f.scene.backend));
        renderer = std::make_unique<render::Renderer>(*context);
        renderer->setShaderTimeLimit(f.scene.shaderTimeout);
    }
    if (!f.json) printTableHeader();
    for (double angle : resolved.angles) {
        scene.light.incidenceDeg = angle;
        const nlohmann::json j = measureRow(renderer.get(), resolved, f);
        if (f.json) std::cout << j.dump() << "\n" << std::flush;
        else printTableRow(j);
        if (!f.json && j.contains("tolerance")) printToleranceLine(j);
    }
    return 0;
}

}  // namespace

void addMeasureFlags(CLI::App& app, MeasureFlags& flags) {
    MeasureFlags* f = &flags;
    addSceneFlags(app, f->scene, "theta_i in degrees, [0, 90]: one angle (60), a list (0,30,60) or a range START:STOP:STEP (0:85:5)");
    app.add_option("--fov", f->scene.fov, "fixed framing: field of view in degrees, (0, 160]; default: automatic framing");
    app.add_option("--threshold", f->threshold, "region = lobe >= FRAC x peak, FRAC in (0, 1)")->capture_default_str();
    app.add_option("--min-pixels", f->minPixels, "under_resolved below this many pixels across the minor axis")
        ->capture_default_str();
    app.add_option("--boundary", f->boundary, "subpixel (contour pixels count their covered fraction) | pixel (in/out)")
        ->capture_default_str();
    app.add_option("--supersample", f->supersample,
                   "N: render the final frame N x N times with jittered sub-pixel sample points and count each pixel's "
                   "covered fraction (replaces --boundary), N in [1, 8]")
        ->capture_default_str();
    app.add_option("--renderer", f->renderer, "gl (float shader) | cpu (the double-precision twin on every core)")
        ->capture_default_str();
    app.add_option("--crop", f->crop,
                   "on: automatic framing shades, reads and analyses only the region's box of the final frame (same "
                   "numbers, less time) | off: the whole frame")
        ->capture_default_str();
    app.add_option("--tolerance", f->tolerance,
                   "E in [1e-5, 0.1]: choose the cheapest settings (size, sub-pixel boundary) predicted to reach aspect "
                   "error E, check them against the next finer size, report settings, error_estimate and time_ms "
                   "(--json fields; a table adds a line); --size, --boundary, --supersample, --fov are chosen, not "
                   "read");
    app.add_flag("--json", f->json, "one JSON object per line instead of a table");
    app.add_flag("--reference", f->reference, "use the CPU double-precision reference instead of GL");
    assignSections(app, 0);
}

Action addMeasure(CLI::App& app) {
    auto f = std::make_shared<MeasureFlags>();
    addMeasureFlags(app, *f);
    app.footer("Example: hilite measure --model ggx --roughness 0.1 --incidence 0:85:5 --json");
    return [f] { return runMeasure(*f); };
}

}  // namespace hilite::cli
