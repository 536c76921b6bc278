#pragma once
// Fitting analytic models to a target's BRDF: which one gets it right. The target (a MERL or RGL table, a
// .brdf file or a built-in model) and each model are compared by two criteria, both reported for every model:
//
// shape (the default ranking): the target and the model are measured by the same measurement (GL, automatic
// framing, every diagnosis) over a sweep of incidence and several thresholds; the residual is the weighted RMS
// over (incidence, threshold) of the log ratios of the semi-axes,
//   r = sqrt( sum_{i,j} w_j [ln(major_m / major_t)^2 + ln(minor_m / minor_t)^2] / (2 sum_{i,j} w_j) ),
// so r = 0.01 means the fitted semi-axes are ~1% off the target's on average. Several thresholds count
// because at one threshold alone f ~ D lobes of matched width have the same shape: the tails tell GGX from
// Beckmann. A sample the target cannot measure (no highlight, mirror, unbounded at the horizon) is left out
// and named; one the model cannot measure where the target could costs as a 100% error (log ratio 1).
// With a fitted F0, the peak's log ratio at the first threshold joins the sum (F0 sets the magnitude).
//
// values: the BRDF itself over the directions a measured table holds, cosine-weighted and compressed in log
// space as Löw et al. 2012 (E2) fit MERL (experiments/fit_values.hpp). A .brdf file has no double evaluation:
// its values residual is null.
//
// Each model is first fitted by values (cheap: double evaluations, no rendering) and that fit seeds the shape
// fit; both use NLopt's BOBYQA (Powell 2009) in log(width), minimising the mean square. Every microfacet model
// carries a geometry term (by default Smith's or the implicit G, whichever the values fit finds closer) and a
// fitted Schlick F0, and a Lambertian albedo where the target has a diffuse part (FitOptions).
//
// Verdicts (FitResult::verdict): the resolution rho of the ranking criterion is what the target's own numbers
// move by when nothing but the measurement changes (shape: the target measured at the fit's size and at 1.5x,
// or 3/4 where 1.5x passes the size limit;
// values: 0). "target_unresolved" when rho exceeds 0.02 (the target's own shape is not settled at this size);
// else "no_model_fits" when the best residual exceeds max(10 rho, 0.01); "tie" when the second model's residual
// is within max(rho, 1e-4) of the first's; else "fits".

#include "hilite/measurement/session.hpp"
#include "hilite/scene/resolve.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::experiments {

struct FitOptions {
    std::vector<std::string> models{"phong", "blinn", "beckmann", "ggx"};
    std::vector<double> thresholds{0.1, 0.25, 0.5, 0.75, 0.9};
    std::vector<double> weights;  ///< one per threshold; empty: 1 each
    bool anisotropy = false;      ///< fit roughness_y too (beckmann, ggx)
    bool f0 = true;               ///< fit a Schlick F0 (microfacet models; not with fresnel "none")
    /// the fitted microfacet models' --geometry; auto: smith or implicit, whichever the values fit finds closer
    std::string geometry = "auto";
    std::string fresnel = "schlick";  ///< the fitted microfacet models' --fresnel: schlick or none
    std::string diffuse = "auto";     ///< a Lambertian albedo: auto (where the values fit finds one), on, off
    std::string rankBy = "shape";     ///< the ranking criterion: shape or values
    /// F0 and the albedo per channel (RGB): refitted by values at the width found (the shape is measured on the
    /// luminance); params f0 and albedo are then [r, g, b]
    bool color = false;
    double xtolAbs = 1e-4;    ///< NLopt's stopping step in log(parameter): 0.01%
    int maxEvaluations = 80;  ///< per model and criterion
};

/// The allowed words of FitOptions' choices (the CLI, experiment files and Python refuse others).
const std::vector<std::string>& fitGeometries();
const std::vector<std::string>& fitDiffuseChoices();
const std::vector<std::string>& fitCriteria();

/// Above this resolution the target's own shape is not settled at the fit's size (its semi-axes move by more
/// than 2% between the size and 1.5x it): verdict "target_unresolved", whatever the residuals.
constexpr double kMaxResolution = 0.02;

/// Below this fitted albedo the target has no diffuse part (diffuse "auto"): the model carries none.
constexpr double kMinFittedAlbedo = 1e-3;

/// One measurement of the sweep: a (incidence, threshold) pair.
struct FitSample {
    double incidence = 0, threshold = 0;
    double major = 0, minor = 0, aspect = 0, peak = 0;  ///< degrees, as the row's major_deg, minor_deg
    bool usable = false;
    std::string why;    ///< not usable: the row's flags that rule it out
    std::string flags;  ///< all the row's flags, comma-separated
};

struct ModelFit {
    std::string model;  ///< as FitOptions::models names it
    /// by registry name: {"roughness": 0.1, "f0": 0.04, "geometry": "smith"} or {"exponent": 200}; the numbers
    /// fitted, the geometry chosen
    nlohmann::ordered_json params;
    double residual = 0;        ///< by the ranking criterion (FitResult::rankBy)
    double shapeResidual = 0;   ///< the shape criterion's (NaN: no sample measured)
    double valuesResidual = 0;  ///< the values criterion's (NaN: the target has no double evaluation)
    int rank = 0;               ///< 1: the smallest residual
    bool tie = false;           ///< within the tie margin of rank 1 (rank 1 itself when any other is)
    int evaluations = 0;        ///< measured sweeps (each thresholds x incidences measurements)
    int valueEvaluations = 0;   ///< values-criterion evaluations
    double ms = 0;              ///< wall time of this model's fit
    std::string stop;           ///< NLopt's reason to stop the shape fit ("xtol reached", ...)
    /// The fitted parameters that ended at their search bound (within 1e-3 of the range), by registry name: the
    /// target wanted a value beyond it, so the number given is the bound's, not the target's. F0 and the albedo
    /// have physical bounds (F0 = 1 is a target without Fresnel): only F0 below 1e-3, a lobe switched off, is named
    std::vector<std::string> atBound;
    std::vector<FitSample> samples;  ///< at the fitted parameters, in the target's order
};

struct FitResult {
    std::string target;  ///< what was fitted, in words ("measured:gold.binary", "ggx roughness=0.1")
    std::string rankBy = "shape";
    std::vector<double> angles, thresholds, weights;
    std::vector<FitSample> samples;  ///< the target's, incidence-major
    std::vector<ModelFit> fits;      ///< ranked: fits[0] has rank 1
    double aspectThreshold = 0.5;    ///< the threshold of the aspect residuals (the one nearest 0.5)
    bool hasValues = true;           ///< the target has a double evaluation (not a .brdf file)
    double resolution = 0;           ///< rho of the ranking criterion (see the verdicts above)
    double tolerance = 0;            ///< max(10 rho, 0.01): no model fits above it
    double tieMargin = 0;            ///< max(rho, 1e-4)
    std::string verdict;             ///< "fits", "tie", "no_model_fits" or "target_unresolved"
};

/// Checks the options (InputError naming the flag): models known and fittable, thresholds in (0, 1),
/// weights as many as thresholds and >= 0 with a positive sum, anisotropy only where a model takes it, the
/// choices among their words.
void checkFitOptions(const FitOptions& o);

/// Resolves the target's scenes and each model's (at its starting width) as fitModels will: InputError for any
/// that does not resolve, before anything is measured.
void checkFitScenes(const scene::Values& target, const FitOptions& o);

/// Fits every model of `o` to the target scene `target` (its material is the target: --measured, --brdf or
/// --model ...; the light, camera and measurement keys apply to every model too). Every scene is resolved
/// before the first measurement (InputError).
FitResult fitModels(measurement::Session& session, const scene::Values& target, const FitOptions& o);

/// The index of r.aspectThreshold in r.thresholds (the samples' column of the aspect residuals).
size_t aspectIndex(const FitResult& r);

/// The model's aspect minus the target's at each incidence, at r.aspectThreshold (NaN where either sample
/// is not usable).
std::vector<double> aspectResiduals(const FitResult& r, const ModelFit& m);

/// One JSON object per model: model, params, at_bound, residual, shape_residual, values_residual, rank, rank_by,
/// tie, verdict, resolution, tolerance, evaluations, time_ms, stop, incidence_deg and aspect_residual (per angle,
/// at aspect_threshold), and the target.
nlohmann::ordered_json toJson(const FitResult& r, const ModelFit& m);

/// Writes fit.json (one object per model per line), fit.csv (every sample of the target and of each fit),
/// and fit_aspect.png / fit_residual.png (gnuplot: aspect against incidence, target and each fit; the
/// aspect residual) into `dir`, each atomically. Returns false with `why` when only the plots failed.
bool writeFitFolder(const std::string& dir, const FitResult& r, std::string& why);

}  // namespace hilite::experiments
