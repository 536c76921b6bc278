#pragma once
// Fitting analytic models to a target's highlight: which BRDF gets it right. The target (a MERL table, a
// .brdf file or a built-in model) and each model are measured by the same measurement (GL, automatic
// framing, every diagnosis) over a sweep of incidence and several thresholds; each model's parameters are
// those that minimise the residual below, found by NLopt's BOBYQA (Powell 2009) in log(parameter).
//
// Residual: the weighted RMS over (incidence, threshold) of the log ratios of the semi-axes,
//   r = sqrt( sum_{i,j} w_j [ln(major_m / major_t)^2 + ln(minor_m / minor_t)^2] / (2 sum_{i,j} w_j) ),
// so r = 0.01 means the fitted semi-axes are ~1% off the target's on average. Several thresholds count
// because at one threshold alone f ~ D lobes of matched width have the same shape: the tails tell GGX from
// Beckmann. A sample the target cannot measure (no highlight, mirror, unbounded at the horizon) is left out
// and named; one the model cannot measure where the target could costs as a 100% error (log ratio 1).
// With f0, the peak's log ratio at the first threshold joins the sum (Schlick F0 sets the magnitude only).

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
    bool f0 = false;              ///< fit a Schlick F0 (microfacet models) against the peak
    std::string geometry;         ///< the fitted models' --geometry ("" = the registry's default)
    std::string fresnel;          ///< the fitted models' --fresnel ("" = none; schlick with f0)
    double xtolAbs = 1e-4;        ///< NLopt's stopping step in log(parameter): 0.01%
    int maxEvaluations = 80;      ///< per model
};

/// One measurement of the sweep: a (incidence, threshold) pair.
struct FitSample {
    double incidence = 0, threshold = 0;
    double major = 0, minor = 0, aspect = 0, peak = 0;  ///< degrees, as the row's major_deg, minor_deg
    bool usable = false;
    std::string why;  ///< not usable: the row's flags that rule it out
};

struct ModelFit {
    std::string model;
    nlohmann::ordered_json params;  ///< by registry name: {"roughness": 0.1} or {"exponent": 200}
    double residual = 0;
    int rank = 0;                    ///< 1: the smallest residual
    int evaluations = 0;             ///< measured sweeps (each thresholds x incidences measurements)
    double ms = 0;                   ///< wall time of this model's fit
    std::string stop;                ///< NLopt's reason to stop ("xtol reached", ...)
    std::vector<FitSample> samples;  ///< at the fitted parameters, in the target's order
};

struct FitResult {
    std::string target;  ///< what was fitted, in words ("measured:gold.binary", "ggx roughness=0.1")
    std::vector<double> angles, thresholds, weights;
    std::vector<FitSample> samples;  ///< the target's, incidence-major
    std::vector<ModelFit> fits;      ///< in FitOptions::models order (rank says the ranking)
    double aspectThreshold = 0.5;    ///< the threshold of the aspect residuals (the one nearest 0.5)
};

/// Checks the options (InputError naming the flag): models known and fittable, thresholds in (0, 1),
/// weights as many as thresholds and >= 0 with a positive sum, anisotropy/f0 only where a model takes them.
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

/// One JSON object per model: model, params, residual, rank, evaluations, time_ms, stop, incidence_deg and
/// aspect_residual (per angle, at aspect_threshold), and the target.
nlohmann::ordered_json toJson(const FitResult& r, const ModelFit& m);

/// Writes fit.json (one object per model per line), fit.csv (every sample of the target and of each fit),
/// and fit_aspect.png / fit_residual.png (gnuplot: aspect against incidence, target and each fit; the
/// aspect residual) into `dir`, each atomically. Returns false with `why` when only the plots failed.
bool writeFitFolder(const std::string& dir, const FitResult& r, std::string& why);

}  // namespace hilite::experiments
