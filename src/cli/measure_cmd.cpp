// `hilite measure`: the highlight's shape per angle of incidence, as a table or JSON lines.

#include "cli/measure_cmd.hpp"

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "cli/scene_file.hpp"
#include "cli/shader_probe.hpp"
#include "core/error.hpp"
#include "experiments/measure_scene.hpp"

#include <nlohmann/json.hpp>

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
        else j["roughness"] = s.brdf.roughness;
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
    j["size"] = method == "gl" ? std::to_string(width) + "x" + std::to_string(height) : "";
    j["fov_deg"] = m.fovDeg;
    j["minor_pixels"] = std::isfinite(r.minor_pixels) ? nlohmann::json(r.minor_pixels) : nlohmann::json(nullptr);
    j["render_ms"] = m.render_ms;
    j["measure_ms"] = m.measure_ms;
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
    std::printf("%-9s %6.2f %8.5f %8.5f %9.4f %9.4f %7.2f %8.4f %8.4f %8.4f %8.4f  %s",
                j["model"].get<std::string>().c_str(), num("incidence_deg"), num("aspect"), num("eccentricity"),
                num("major_deg"), num("minor_deg"), num("orientation_deg"), num("centroid_u_deg"),
                num("centroid_v_deg"), num("fwhm_u_deg"), num("fwhm_v_deg"), flags.c_str());
    if (j.contains("error_estimate")) {
        auto err = [&](const char* k) { return j["error_estimate"][k].is_null() ? NAN : j["error_estimate"][k].get<double>(); };
        std::printf("  error estimate (resolution convergence, no CPU twin for .brdf): aspect %.1e, major %.1e, "
                    "minor %.1e deg",
                    err("aspect"), err("major_deg"), err("minor_deg"));
    }
    if (j.contains("framing_note")) std::printf("  note: %s", j["framing_note"].get<std::string>().c_str());
    std::printf("\n");
}

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
    if (f.scene.view != "measure") throw InputError("--view: measure always uses the measurement view");
    if (f.reference && scene.brdfFile)
        throw InputError("--reference: no CPU twin for a .brdf file (hilite cannot run its GLSL on the CPU); the GL "
                         "measurement reports error_estimate from resolution convergence instead");
    return r;
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
    if (!f.reference) {
        probeShader(scene, f.scene.backend, f.scene.shaderTimeout);  // before this process runs it
        context = std::make_unique<gl::Context>(parseBackendFlag(f.scene.backend));
        renderer = std::make_unique<render::Renderer>(*context);
        renderer->setShaderTimeLimit(f.scene.shaderTimeout);
    }
    if (!f.json) printTableHeader();
    for (double angle : resolved.angles) {
        scene.light.incidenceDeg = angle;
        const experiments::Measurement m = f.reference ? experiments::measureReference(scene, setup.options)
                                                       : experiments::measureGl(*renderer, scene, setup);
        const nlohmann::json j = measurementRow(scene, m, f, setup.width, setup.height, f.reference ? "reference" : "gl");
        if (f.json) std::cout << j.dump() << "\n" << std::flush;
        else printTableRow(j);
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
