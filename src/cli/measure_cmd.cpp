// `hilite measure`: the highlight's shape per angle of incidence, as a table or JSON lines.

#include "cli/measure_cmd.hpp"

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "cli/scene_file.hpp"
#include "core/error.hpp"
#include "experiments/measure_bumps.hpp"
#include "experiments/measure_scene.hpp"
#include "experiments/peak_frame.hpp"
#include "brdf/ndf_table.hpp"
#include "cli/micro_fields.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace hilite::cli {

nlohmann::json measurementRow(const render::Scene& s, const experiments::Measurement& m, const MeasureFlags& f, int width,
                   int height, const std::string& method) {
    const measure::Shape& r = m.shape;
    nlohmann::json j;
    j["model"] = brdf::toString(s.brdf.model);
    if (brdf::usesExponent(s.brdf.model)) j["exponent"] = s.brdf.exponent;
    else if (s.brdf.model != brdf::Model::Tabulated) j["roughness"] = s.brdf.roughness;  // a table has no width knob
    if (s.brdf.model == brdf::Model::Tabulated && s.brdf.ndfTable) {  // issue 10: the table and its normalization
        j["ndf_table"] = s.brdf.ndfTable->file;
        j["ndf_table_normalization"] = s.brdf.ndfTable->normalization;
    }
    j["fresnel"] = brdf::toString(s.brdf.fresnel);
    j["geometry"] = brdf::toString(s.brdf.geometry);
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
    j["size"] = method == "gl" ? std::to_string(width) + "x" + std::to_string(height) : "";
    j["fov_deg"] = m.fovDeg;
    j["minor_pixels"] = std::isfinite(r.minor_pixels) ? nlohmann::json(r.minor_pixels) : nlohmann::json(nullptr);
    j["render_ms"] = m.render_ms;
    j["measure_ms"] = m.measure_ms;
    if (s.surface.bumps) addMicroFields(j, s, m, f.threshold, width, height);  // issue 10: bump period, analytic twin
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
    if (j.value("framed_about", std::string("mirror direction")) != "mirror direction") {
        char about[96];
        std::snprintf(about, sizeof about, "about the peak, %.4g deg from the mirror direction", num("peak_offset_deg"));
        flags += (flags.empty() ? "" : " ") + std::string("(") + about + ")";
    }
    std::printf("%-9s %6.2f %8.5f %8.5f %9.4f %9.4f %7.2f %8.4f %8.4f %8.4f %8.4f  %s\n",
                j["model"].get<std::string>().c_str(), num("incidence_deg"), num("aspect"), num("eccentricity"),
                num("major_deg"), num("minor_deg"), num("orientation_deg"), num("centroid_u_deg"),
                num("centroid_v_deg"), num("fwhm_u_deg"), num("fwhm_v_deg"), flags.c_str());
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
    parseView(f.scene.view);  // checked, but a measurement always uses the measurement view
    if (f.reference && scene.surface.bumps)
        throw InputError("--reference: the CPU reference evaluates the analytic BRDF (drop --bumps explicit)");
    return r;
}

namespace {

int runMeasure(const MeasureFlags& f) {
    ResolvedMeasure resolved = resolveMeasure(f);
    render::Scene& scene = resolved.scene;
    const experiments::MeasureSetup& setup = resolved.setup;

    std::unique_ptr<gl::Context> context;
    std::unique_ptr<render::Renderer> renderer;
    if (!f.reference) {
        context = std::make_unique<gl::Context>(parseBackendFlag(f.scene.backend));
        renderer = std::make_unique<render::Renderer>(*context);
    }
    if (!f.json) printTableHeader();
    for (double angle : resolved.angles) {
        scene.light.incidenceDeg = angle;
        const experiments::Measurement m = f.reference ? experiments::measureReference(scene, setup.options)
                                                       : experiments::measureAny(*renderer, scene, setup);
        nlohmann::json j = measurementRow(scene, m, f, setup.width, setup.height, f.reference ? "reference" : "gl");
        if (renderer) addPrefilterFields(j, *renderer, scene, setup, m);  // issue 10: --prefilter-check
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
