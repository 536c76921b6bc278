#pragma once
// The error of the bump render's moments prefilter against supersampling, measured where both run:
// the same frame rendered three times, supersampled, with the moments prefilter, and supersampled with the
// next seed (a second realisation of the same statistics, for the noise floor).
//
// Pixel by pixel the two renders cannot agree: supersampling shows every glint (speckle), the prefilter the
// footprint's Gaussian slope lobe. So the comparison is of block means (8 x 8 pixels, ~64 times the bumps of a
// pixel), inside the highlight (blocks whose prefiltered mean is at least half the largest) where supersampling
// resolves the bumps (every corner pixel needs at most kMaxBumpSamples patches per axis; toward the horizon the
// footprints grow and the capped patches blur the lobe):
//   block_error = rms(L_ss - L_moments) / mean(L_moments),   block_noise = rms(L_ss - L_ss') / sqrt(2) / mean,
// and the prefilter's own error sqrt(block_error^2 - block_noise^2) (0 when the noise explains it all): the
// part of the difference that a second realisation of the supersampled surface does not show.

#include "hilite/measurement/measure_scene.hpp"

namespace hilite::measurement {

struct PrefilterCheck {
    analysis::Shape supersampled, moments, nextSeed;  ///< the three renders' highlights
    double blockError = 0, blockNoise = 0, prefilterError = 0;
    int blocks = 0;                   ///< blocks compared
    int unresolvedBlocks = 0;         ///< highlight blocks left out: supersampling capped there
    static constexpr int kBlock = 8;  ///< pixels per block side
};

/// Renders `scene` (explicit bumps) in the frame of `m` (its centre and field of view) three ways and compares.
PrefilterCheck checkPrefilter(render::Renderer& renderer, const render::Scene& scene, const MeasureSetup& setup,
                              const Measurement& m);

}  // namespace hilite::measurement
