#include "cli/surface_flags.hpp"

#include "cli/options.hpp"
#include "core/error.hpp"

namespace hilite::cli {

void addSurfaceFlags(CLI::App& app, SurfaceFlags& f) {
    app.add_option("--bumps", f.bumps,
                   "none (flat: the analytic BRDF) | explicit (the material's beckmann/ggx NDF as a seeded bump field "
                   "of mirror facets, lit by a soft sun)")
        ->capture_default_str();
    app.add_option("--bump-period-px", f.bumpPeriodPx,
                   "bump period in pixels of the view (at the image centre, across it), in [1/256, 4096]")
        ->capture_default_str();
    app.add_option("--bump-seed", f.bumpSeed, "seed of the bump field, in [0, 2^53]")->capture_default_str();
    app.add_option("--bump-samples", f.bumpSamples,
                   "sub-pixel patches per axis, in [0, 64]; 0 = automatic (4 per bump period across the footprint)")
        ->capture_default_str();
    app.add_option("--sun", f.sun, "the light's angular standard deviation per axis (Gaussian sun), degrees, [0.01, 5]")
        ->capture_default_str();
    app.add_option("--bump-filter", f.bumpFilter,
                   "how a pixel integrates its bumps: supersample (Gaussian mirror patches) | moments (the footprint's "
                   "realised slope moments, LEAN mapping: a prefilter; beckmann bumps) | auto (supersample while the "
                   "centre pixel needs <= 64 patches per axis, moments beyond; ggx bumps: always supersample)")
        ->capture_default_str();
    app.add_flag("--prefilter-check", f.prefilterCheck,
                 "measure also renders the same frame with the moments prefilter and with the next seed, and reports "
                 "the prefilter's error against supersampling (prefilter_* fields)");
}

render::Surface surfaceOf(const SurfaceFlags& f) {
    render::Surface s;
    if (f.bumps != "none" && f.bumps != "explicit")
        throw InputError("--bumps: unknown '" + f.bumps + "' (allowed: none, explicit)");
    s.bumps = f.bumps == "explicit";
    s.bumpPeriodPx = checkRange("--bump-period-px", f.bumpPeriodPx, render::kMinBumpPeriodPx, render::kMaxBumpPeriodPx);
    s.seed = uint64_t(checkRange("--bump-seed", double(f.bumpSeed), 0, 9007199254740992.0));
    s.samples = int(checkRange("--bump-samples", f.bumpSamples, 0, render::kMaxBumpSamples));
    s.sunDeg = checkRange("--sun", f.sun, render::kMinSunDeg, render::kMaxSunDeg);
    if (f.bumpFilter == "auto") s.filter = render::BumpFilter::Auto;
    else if (f.bumpFilter == "supersample") s.filter = render::BumpFilter::Supersample;
    else if (f.bumpFilter == "moments") s.filter = render::BumpFilter::Moments;
    else throw InputError("--bump-filter: unknown '" + f.bumpFilter + "' (allowed: auto, supersample, moments)");
    s.prefilterCheck = f.prefilterCheck;
    return s;
}

}  // namespace hilite::cli
