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

MicroFields microFields(const render::Scene& s, const Measurement& m, double threshold, int width, int height) {
    const PinholeCamera cam = measurementCamera(s, m.center, m.fovDeg, width, height);
    MicroFields f;
    f.filter = render::toString(s.surface.filter);
    f.filterUsed = render::usesMoments(s, cam) ? "moments" : "supersample";
    f.log2PeriodPx = std::log2(s.surface.bumpPeriodPx);
    // The patches per axis the centre pixel's footprint needs (uncapped: beyond 64 the moments prefilter runs).
    f.samplesCenter = render::centreBumpSamples(s, cam);
    analysis::Options opt;
    opt.threshold = threshold;
    f.analytic = measureReference(analyticScene(s), opt).shape;
    const micro::SlopeStats& st = realisedSlopes(render::bumpSpec(s));
    f.slopeRms = std::hypot(st.rmsX, st.rmsY);
    f.slopeKs = st.ks;
    return f;
}

std::optional<PrefilterFields> prefilterFields(render::Renderer& renderer, const render::Scene& s,
                                               const MeasureSetup& setup, const Measurement& m) {
    if (!s.surface.bumps || !s.surface.prefilterCheck) return std::nullopt;
    const PinholeCamera cam = measurementCamera(s, m.center, m.fovDeg, setup.width, setup.height);
    if (render::centreBumpSamples(s, cam) > render::kMaxBumpSamples) return std::nullopt;  // no supersampling here
    const PrefilterCheck c = checkPrefilter(renderer, s, setup, m);
    return PrefilterFields{c.moments,        c.nextSeed, c.blockError,      c.blockNoise,
                           c.prefilterError, c.blocks,   c.unresolvedBlocks};
}

}  // namespace hilite::measurement
