#include "hilite/measurement/row.hpp"

#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/rgl.hpp"
#include "hilite/render/area_light.hpp"
#include "measurement/in_frame_twin.hpp"
#include "measurement/micro_fields.hpp"
#include "measurement/peak_frame.hpp"
#include "measurement/tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace hilite::measurement {

namespace {

using nlohmann::json;

json finite(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

void shapeFields(json& j, const analysis::Shape& r) {
    for (auto [key, v] : {std::pair{"aspect", r.aspect},
                          {"eccentricity", r.eccentricity},
                          {"major_deg", r.major_deg},
                          {"minor_deg", r.minor_deg},
                          {"orientation_deg", r.orientation_deg},
                          {"centroid_u_deg", r.centroid_u_deg},
                          {"centroid_v_deg", r.centroid_v_deg},
                          {"fwhm_u_deg", r.fwhm_u_deg},
                          {"fwhm_v_deg", r.fwhm_v_deg},
                          {"peak", r.peak},
                          {"peak_u_deg", r.peak_u_deg},
                          {"peak_v_deg", r.peak_v_deg},
                          {"area_deg2", r.area_deg2}})
        j[key] = finite(v);
    json flags = json::array();
    for (auto fl : r.flags) flags.push_back(analysis::toString(fl));
    j["flags"] = flags;
    j["minor_pixels"] = finite(r.minor_pixels);
    j["components"] = r.components;
    if (!r.parts.empty()) {  // each part's own ellipse, the part holding the peak first
        json parts = json::array();
        for (const analysis::PartShape& p : r.parts)
            parts.push_back({{"aspect", finite(p.aspect)},
                             {"eccentricity", finite(p.eccentricity)},
                             {"major_deg", finite(p.major_deg)},
                             {"minor_deg", finite(p.minor_deg)},
                             {"orientation_deg", finite(p.orientation_deg)},
                             {"centroid_u_deg", finite(p.centroid_u_deg)},
                             {"centroid_v_deg", finite(p.centroid_v_deg)},
                             {"area_deg2", finite(p.area_deg2)},
                             {"horizon_cut", p.horizon_cut},
                             {"holds_peak", p.holds_peak},
                             {"measured", p.measured}});
        j["parts"] = parts;
    }
}

/// Without a CPU twin (a .brdf file) the error is estimated by measuring the same frame at half the size.
void errorEstimate(json& j, const Measurement& m, int width, int height) {
    const analysis::Shape &r = m.shape, &h = *m.halfResolution;
    json e;
    for (auto [key, a, b] : {std::tuple{"aspect", r.aspect, h.aspect},
                             {"eccentricity", r.eccentricity, h.eccentricity},
                             {"major_deg", r.major_deg, h.major_deg},
                             {"minor_deg", r.minor_deg, h.minor_deg},
                             {"centroid_u_deg", r.centroid_u_deg, h.centroid_u_deg},
                             {"centroid_v_deg", r.centroid_v_deg, h.centroid_v_deg}})
        e[key] = std::isfinite(a - b) ? json(std::abs(a - b)) : json(nullptr);
    j["error_estimate"] = e;
    j["error_estimate_from"] = "resolution convergence (no CPU twin for .brdf)";
    j["error_estimate_sizes"] = std::to_string(width) + "x" + std::to_string(height) + " vs " +
                                std::to_string(m.halfWidth) + "x" + std::to_string(m.halfHeight);
}

/// A measured table's interpolation error, measured: the same measurement of the table at half its resolution
/// along each axis in turn (brdf/merl.hpp halfResolution), the larger change of the two halvings (even bins
/// interpolated, odd bins interpolated) per axis, the three added. Halving the spacing of a lookup of order h^2
/// or more changes it by 3x its error or more; per axis, so that errors along different axes do not cancel, and
/// both parities, since a contour's error depends on where it crosses the bins (one halving of all three axes
/// at once gave 0.8x the true error of GGX 0.1 at 20 deg, one parity per axis 0.45x of its minor axis at 10).
/// A GL row measured in one frame about the mirror direction measures the halves in that frame (one render each,
/// no framing: 7 -> 1.x measurements' time), and with the full table's light rule, so that the change is the table's
/// alone; the reference, the cpu path and the measurements of several parts or about a far peak measure them anew.
/// Where the row kept its final render (measureRow), the halves come from it without rendering
/// (measureInFrameByTwin: the twins' change at the pixels that can move the region), else by a render each.
TableError tableError(render::Renderer* renderer, const scene::Resolved& r, const MeasureSetup& setup,
                      const Measurement& measured, bool aboutMirror) {
    const analysis::Shape& full = measured.shape;
    const bool sameFrame = renderer && !r.reference && !setup.cpu && aboutMirror && measured.inFrame;
    std::vector<render::Scene> halves;  // axis-major, then parity
    for (int axis = 0; axis < 3; ++axis)
        for (int parity = 0; parity < 2; ++parity) {
            render::Scene s = r.scene;
            if (r.scene.brdf.rgl) s.brdf.rgl = brdf::rgl::halfResolution(r.scene.brdf.rgl, axis, parity);
            else s.brdf.measured = brdf::merl::halfResolution(r.scene.brdf.measured, axis, parity);
            if (s.light.area() && !r.reference) s.light.rings = render::lightRings(r.scene);
            halves.push_back(std::move(s));
        }
    std::vector<std::optional<analysis::Shape>> fromImage(halves.size());
    if (sameFrame) {
        const std::optional<PixelChanges> fast = tableHalvesChanges(r.scene);
        fromImage =
            measureInFrameByTwin(r.scene, halves.size(), fast ? *fast : twinChanges(r.scene, halves), setup, measured);
    }
    double e[4] = {0, 0, 0, 0};
    for (int axis = 0; axis < 3; ++axis) {
        double worst[4] = {0, 0, 0, 0};
        for (int parity = 0; parity < 2; ++parity) {
            const size_t at = size_t(2 * axis + parity);
            const render::Scene& s = halves[at];
            const analysis::Shape h = fromImage[at] ? *fromImage[at]
                                      : r.reference ? measureReference(s, setup.options).shape
                                      : sameFrame   ? measureInFrame(*renderer, s, setup, measured).shape
                                                    : measure(renderer, s, setup).shape;
            const double d[4] = {full.aspect - h.aspect, full.eccentricity - h.eccentricity,
                                 full.major_deg - h.major_deg, full.minor_deg - h.minor_deg};
            for (int k = 0; k < 4; ++k) worst[k] = std::max(worst[k], std::abs(d[k]));
        }
        for (int k = 0; k < 4; ++k) e[k] += worst[k];
    }
    // The aspect's error also through its semi-axes' (a bound on a ratio from bounds on its terms): in one halving
    // both axes move together and the aspect hides the change (GGX 0.1 at 20 deg: 0.8x its true error alone).
    if (full.major_deg > 0 && full.minor_deg > 0) {
        const double a = full.aspect * (e[2] / full.major_deg + e[3] / full.minor_deg);
        e[0] = std::max(e[0], a);
    }
    // The eccentricity's error from the aspect's as the change of sqrt(1 - a^2) over the aspect's interval, not
    // its first-order slope a / e, which is unbounded on a round highlight (7.4e6 there); it lies in [0, 1], so
    // it is never off by more than max(e, 1 - e).
    e[1] = std::min(std::max(e[1], eccentricityChange(full.aspect, e[0])),
                    std::max(full.eccentricity, 1.0 - full.eccentricity));
    return TableError{e[0], e[1], e[2], e[3]};
}

void tableErrorJson(json& j, const TableError& t) {
    j["table_error"] = {{"aspect", finite(t.aspect)},
                        {"eccentricity", finite(t.eccentricity)},
                        {"major_deg", finite(t.major_deg)},
                        {"minor_deg", finite(t.minor_deg)}};
    j["table_error_from"] =
        "the same measurement of the table at half its resolution along each axis (even or odd bins interpolated, "
        "the larger): the sum over the axes of |full - half|";
}

/// The tolerance fields: what was asked, what was chosen, what it is estimated to reach, what it cost.
void toleranceJson(json& j, const ToleranceFields& r) {
    j["error_estimate"] = r.errorEstimate;
    j["predicted_error"] = r.predictedError;
    j["tolerance_met"] = r.met;
    j["settings"] = {{"size", std::to_string(r.setup.width) + "x" + std::to_string(r.setup.height)},
                     {"boundary", r.setup.options.subpixel ? "subpixel" : "pixel"},
                     {"supersample", r.setup.supersample},
                     {"framing", r.setup.fovDeg > 0 ? "fixed" : "auto"},
                     {"renderer", r.setup.cpu ? "cpu" : "gl"}};
    j["check"] = {{"size", std::to_string(r.checkSetup.width) + "x" + std::to_string(r.checkSetup.height)},
                  {"aspect", r.checkAspect}};
    j["rounds"] = r.rounds;
    j["time_ms"] = r.total_ms;
    j["startup_ms"] = r.startup_ms;
}

/// log2_bump_period_px, bump_samples_center, the analytic twin's shape and the differences from it, the
/// realised slope statistics.
void microJson(json& j, const MicroFields& f, const analysis::Shape& m) {
    const analysis::Shape& a = f.analytic;
    j["bump_filter"] = f.filter;
    j["bump_filter_used"] = f.filterUsed;
    j["log2_bump_period_px"] = f.log2PeriodPx;
    j["bump_samples_center"] = f.samplesCenter;
    j["analytic_aspect"] = a.aspect;
    j["analytic_major_deg"] = a.major_deg;
    j["analytic_minor_deg"] = a.minor_deg;
    j["aspect_minus_analytic"] = m.aspect - a.aspect;
    j["major_over_analytic"] = a.major_deg > 0 ? finite(m.major_deg / a.major_deg) : json(nullptr);
    j["minor_over_analytic"] = a.minor_deg > 0 ? finite(m.minor_deg / a.minor_deg) : json(nullptr);
    j["slope_rms"] = f.slopeRms;
    j["slope_ks"] = f.slopeKs;
}

/// prefilter_ and next_seed_ aspect, its difference from the analytic twin's and the axes' ratios to it; the
/// block comparison.
void prefilterJson(json& j, const PrefilterFields& p, const MicroFields& f) {
    const analysis::Shape& a = f.analytic;
    for (const auto& [prefix, shape] :
         {std::pair<std::string, const analysis::Shape*>{"prefilter", &p.moments}, {"next_seed", &p.nextSeed}}) {
        j[prefix + "_aspect"] = finite(shape->aspect);
        j[prefix + "_aspect_minus_analytic"] = finite(shape->aspect - a.aspect);
        j[prefix + "_major_over_analytic"] = finite(shape->major_deg / a.major_deg);
        j[prefix + "_minor_over_analytic"] = finite(shape->minor_deg / a.minor_deg);
    }
    j["prefilter_block_error"] = finite(p.blockError);
    j["supersample_block_noise"] = finite(p.blockNoise);
    j["prefilter_error"] = finite(p.error);
    j["prefilter_blocks"] = p.blocks;
    j["prefilter_unresolved_blocks"] = p.unresolvedBlocks;
}

/// The result of `m`, measured by `method` at `width` x `height`, with what the scene alone decides.
Result resultOf(const scene::Resolved& r, const Measurement& m, int width, int height, const std::string& method) {
    const render::Scene& s = r.scene;
    Result out;
    out.resolved = r;
    out.method = method;
    out.width = width;
    out.height = height;
    out.measurement = m;
    if (s.light.area())  // what of the light is integrated, and how well the GL rule (and the cpu path's twin) does it
        out.light = LightFields{s.light.type == render::LightType::Disk
                                    ? render::capVisibleFraction(render::lightCap(s.light, s.light.position()))
                                    : 1.0,  // a sphere above the plane is wholly above every point's horizon
                                method == "reference" ? std::nullopt : std::optional(render::lightRule(s).error)};
    // a highlight far from the mirror direction is measured about its peak
    // (the mirror lobe is measured in the mirror direction's chart, about whatever peak it has)
    if (r.setup.options.lobe == analysis::Lobe::Mirror) out.framedAbout = "mirror direction", out.peakOffsetDeg = 0;
    else  // what framed the measurement: the GL and cpu paths search the drawn rule's lobe, the reference the exact one
        out.framedAbout = framedAbout(method == "reference" ? s : render::withRuleTwin(s), r.setup.options.threshold,
                                      out.peakOffsetDeg);
    if (s.surface.bumps) out.micro = microFields(s, m, r.setup.options.threshold, width, height);
    return out;
}

}  // namespace

double eccentricityChange(double aspect, double aspectError) {
    // sqrt(1 - a^2) falls as a rises: its largest change over the interval is at one of the interval's ends.
    const auto ecc = [](double a) { return std::sqrt(std::max(0.0, 1.0 - a * a)); };
    const double a = std::clamp(aspect, 0.0, 1.0), d = std::abs(aspectError), e = ecc(a);
    return std::max(std::abs(ecc(std::max(0.0, a - d)) - e), std::abs(ecc(std::min(1.0, a + d)) - e));
}

json toJson(const Result& res) {
    const scene::Resolved& r = res.resolved;
    const render::Scene& s = r.scene;
    const Measurement& m = res.measurement;
    const std::string& method = res.method;
    json j = scene::parameterColumns(r);
    if (s.brdfFile) j["brdf_params"] = brdf_file::valuesText(*s.brdfFile);  // every value, defaults included
    if (s.brdf.model == brdf::Model::Tabulated && s.brdf.ndfTable && !s.brdfFile)
        j["ndf_table_normalization"] = s.brdf.ndfTable->normalization;
    // Under a point light each point of the plane has its own wi: the measured lobe is the eye's view.
    j["lobe_domain"] = !s.light.distant() ? "as seen by the eye at distance " + std::to_string(s.eyeDistance) + " (" +
                                                render::toString(s.light.type) + " light)"
                                          : std::string("exitant directions (distant light)");
    j["method"] = method;
    if (res.light) {
        j["light_visible"] = res.light->visible;
        j["light_rule_error"] = res.light->ruleError ? json(*res.light->ruleError) : json(nullptr);
    }
    j["framed_about"] = res.framedAbout;
    j["peak_offset_deg"] = res.peakOffsetDeg;
    shapeFields(j, m.shape);
    j["cos_incidence"] = s.light.direction().z;
    j["renders"] = m.renders;
    j["size"] = method != "reference" ? std::to_string(res.width) + "x" + std::to_string(res.height) : "";
    j["fov_deg"] = m.fovDeg;
    j["render_ms"] = m.render_ms;
    j["measure_ms"] = m.measure_ms;
    if (res.micro) microJson(j, *res.micro, m.shape);
    j["framing"] = m.framing;
    if (!m.framingNote.empty()) j["framing_note"] = m.framingNote;
    if (m.halfResolution) errorEstimate(j, m, res.width, res.height);
    if (res.prefilter && res.micro) prefilterJson(j, *res.prefilter, *res.micro);
    if (res.tolerance) toleranceJson(j, *res.tolerance);
    if (res.tableError) tableErrorJson(j, *res.tableError);
    if (res.gl) {  // what rendered it: a GPU or llvmpipe (the strings GL_RENDERER and GL_VENDOR give)
        j["gl_backend"] = res.gl->backend;
        j["gl_renderer"] = res.gl->renderer;
        j["gl_vendor"] = res.gl->vendor;
    }
    return j;
}

Result measureRow(render::Renderer* renderer, const scene::Resolved& r) {
    const render::Scene& scene = r.scene;
    const MeasureSetup& setup = r.setup;
    if (r.reference) {
        Result res = resultOf(r, measureReference(scene, setup.options), setup.width, setup.height, "reference");
        if (scene.brdf.isMeasured() && !analysis::unmeasured(res.measurement.shape))
            res.tableError = tableError(renderer, r, setup, res.measurement, res.framedAbout == "mirror direction");
        return res;
    }
    const std::string method = setup.cpu ? "cpu" : "gl";
    if (r.tolerance > 0) {
        ToleranceSetup t;
        t.tolerance = r.tolerance;
        t.base = setup;
        const ToleranceResult tr = measureToTolerance(renderer, scene, t);
        Result res = resultOf(r, tr.measurement, tr.setup.width, tr.setup.height, method);
        res.tolerance =
            ToleranceFields{tr.errorEstimate,      tr.predictedError, tr.met,      tr.setup,     tr.checkSetup,
                            tr.check.shape.aspect, tr.rounds,         tr.total_ms, tr.startup_ms};
        if (scene.brdf.isMeasured() && !analysis::unmeasured(res.measurement.shape))
            res.tableError = tableError(renderer, r, tr.setup, res.measurement, res.framedAbout == "mirror direction");
        return res;
    }
    // A table's row keeps its final render for table_error's halves (measureInFrameByTwin), then lets it go.
    MeasureSetup kept = setup;
    kept.keepImage = setup.keepImage || (scene.brdf.isMeasured() && !setup.cpu);
    Measurement m = measure(renderer, scene, kept);
    ImageF image = std::move(m.image);  // moved past resultOf's copy
    Result res = resultOf(r, m, setup.width, setup.height, method);
    res.measurement.image = std::move(image);
    if (renderer) res.prefilter = prefilterFields(*renderer, scene, setup, res.measurement);  // --prefilter-check
    if (scene.brdf.isMeasured() && !analysis::unmeasured(res.measurement.shape))
        res.tableError = tableError(renderer, r, setup, res.measurement, res.framedAbout == "mirror direction");
    if (!setup.keepImage) res.measurement.image = ImageF();
    return res;
}

double rowNumber(const nlohmann::json& row, const char* key) {
    return row.contains(key) && row[key].is_number() ? row[key].get<double>() : NAN;
}

const std::vector<std::string>& measurementColumns() {
    static const std::vector<std::string> columns = {
        "aspect", "eccentricity", "major_deg", "minor_deg", "orientation_deg", "centroid_u_deg", "centroid_v_deg",
        "fwhm_u_deg", "fwhm_v_deg", "peak", "peak_u_deg", "peak_v_deg", "area_deg2", "cos_incidence", "flags",
        "components", "renders", "size", "fov_deg", "minor_pixels", "method", "matched_parameter", "brdf_params",
        "framing", "framing_note", "error_estimate", "error_estimate_from", "table_error", "table_error_from",
        "render_ms", "measure_ms",
        // what the highlight is measured about (retroreflection: its peak), a tabulated NDF's factor
        "framed_about", "peak_offset_deg", "ndf_table_normalization",
        // a sphere or disk light: the part of it above the horizon, the GL rule's radiance error (render/area_light.hpp)
        "light_visible", "light_rule_error",
        // explicit micro-geometry (empty on flat surfaces): measurement/micro_fields.hpp
        "log2_bump_period_px", "bump_samples_center", "analytic_aspect", "analytic_major_deg", "analytic_minor_deg",
        "aspect_minus_analytic", "major_over_analytic", "minor_over_analytic", "slope_rms", "slope_ks",
        "bump_filter_used", "prefilter_aspect", "prefilter_aspect_minus_analytic", "prefilter_major_over_analytic",
        "prefilter_minor_over_analytic", "next_seed_aspect", "next_seed_aspect_minus_analytic",
        "next_seed_major_over_analytic", "next_seed_minor_over_analytic", "prefilter_block_error",
        "supersample_block_noise", "prefilter_error", "prefilter_blocks", "prefilter_unresolved_blocks"};
    return columns;
}

}  // namespace hilite::measurement
