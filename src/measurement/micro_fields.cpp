#include "measurement/micro_fields.hpp"

#include "hilite/measurement/row.hpp"
#include "measurement/measure_bumps.hpp"
#include "measurement/prefilter_check.hpp"
#include "micro/masking.hpp"
#include "render/bump_moments.hpp"
#include "render/bumps.hpp"

#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

namespace hilite::measurement {

const micro::SlopeStats& realisedSlopes(const micro::BumpSpec& spec) {
    static std::map<micro::BumpSpec, micro::SlopeStats> cache;
    auto it = cache.find(spec);
    if (it == cache.end()) it = cache.emplace(spec, micro::slopeStats(micro::cachedBumpField(spec))).first;
    return it->second;
}

namespace {

double num(const nlohmann::json& r, const char* k) { return rowNumber(r, k); }

}  // namespace

void addMicroFields(nlohmann::json& row, const render::Scene& s, const Measurement& m, double threshold, int width,
                    int height) {
    const PinholeCamera cam = measurementCamera(s, m.center, m.fovDeg, width, height);
    row["bump_filter"] = render::toString(s.surface.filter);
    row["bump_filter_used"] = render::usesMoments(s, cam) ? "moments" : "supersample";
    const double period = s.surface.bumpPeriodPx;
    row["log2_bump_period_px"] = std::log2(period);
    // The patches per axis the centre pixel's footprint needs (uncapped: beyond 64 the moments prefilter runs).
    row["bump_samples_center"] = render::centreBumpSamples(s, cam);
    analysis::Options opt;
    opt.threshold = threshold;
    const Measurement a = measureReference(analyticScene(s), opt);
    row["analytic_aspect"] = a.shape.aspect;
    row["analytic_major_deg"] = a.shape.major_deg;
    row["analytic_minor_deg"] = a.shape.minor_deg;
    row["aspect_minus_analytic"] = m.shape.aspect - a.shape.aspect;
    row["major_over_analytic"] = a.shape.major_deg > 0 ? m.shape.major_deg / a.shape.major_deg : NAN;
    row["minor_over_analytic"] = a.shape.minor_deg > 0 ? m.shape.minor_deg / a.shape.minor_deg : NAN;
    const micro::SlopeStats& st = realisedSlopes(render::bumpSpec(s));
    row["slope_rms"] = std::hypot(st.rmsX, st.rmsY);
    row["slope_ks"] = st.ks;
    for (const char* k : {"major_over_analytic", "minor_over_analytic"})
        if (!std::isfinite(row[k].get<double>())) row[k] = nullptr;
}

void addPrefilterFields(nlohmann::json& row, render::Renderer& renderer, const render::Scene& s,
                        const MeasureSetup& setup, const Measurement& m) {
    if (!s.surface.bumps || !s.surface.prefilterCheck) return;
    const PinholeCamera cam = measurementCamera(s, m.center, m.fovDeg, setup.width, setup.height);
    if (render::centreBumpSamples(s, cam) > render::kMaxBumpSamples) return;  // supersampling does not run here
    const PrefilterCheck c = checkPrefilter(renderer, s, setup, m);
    const double a = num(row, "analytic_aspect"), amaj = num(row, "analytic_major_deg"),
                 amin = num(row, "analytic_minor_deg");
    auto put = [&](const std::string& key, double v) { row[key] = std::isfinite(v) ? nlohmann::json(v) : nullptr; };
    for (const auto& [prefix, shape] :
         {std::pair<std::string, const analysis::Shape*>{"prefilter", &c.moments}, {"next_seed", &c.nextSeed}}) {
        put(prefix + "_aspect", shape->aspect);
        put(prefix + "_aspect_minus_analytic", shape->aspect - a);
        put(prefix + "_major_over_analytic", shape->major_deg / amaj);
        put(prefix + "_minor_over_analytic", shape->minor_deg / amin);
    }
    put("prefilter_block_error", c.blockError);
    put("supersample_block_noise", c.blockNoise);
    put("prefilter_error", c.prefilterError);
    row["prefilter_blocks"] = c.blocks;
    row["prefilter_unresolved_blocks"] = c.unresolvedBlocks;
}

}  // namespace hilite::measurement
