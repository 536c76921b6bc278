#pragma once
// The slope moments of a bump field, per mip level: the prefilter of the bump render for pixels that cover
// many bumps. LEAN mapping (Olano & Baker 2010, "LEAN mapping"): a footprint's slopes are summarised by their
// first and second moments, E[s] and E[s s^T], which average linearly, so a box-filtered pyramid of them gives
// any footprint's realised mean slope and slope covariance; its lobe is the Gaussian slope distribution with
// those moments (a Beckmann lobe with the footprint's own covariance). Built from the realised geometry only:
// no analytic D enters. Exact in distribution for the Beckmann fields (a Gaussian random field has Gaussian
// slopes); wrong for the GGX normal maps (GGX slopes have no finite variance), which the render never prefilters.
//
// Level 0 holds the exact moments of the rendered (bilinear) field over each cell between four texel centres,
// so that level 0 cell (i, j) spans [(i + 0.5)/n, (i + 1.5)/n] x [(j + 0.5)/n, (j + 1.5)/n] (tile lengths); level L
// averages 2^L x 2^L cells, and the last level is the whole tile's slope mean and covariance.

#include "hilite/core/math.hpp"
#include "hilite/micro/bump_field.hpp"

#include <vector>

namespace hilite::micro {

/// First and second slope moments: mean (sx, sy), E[sx^2], E[sy^2], E[sx sy].
struct Moments {
    dvec2 mean{0.0};
    double xx = 0, yy = 0, xy = 0;
    /// Covariance E[s s^T] - mean mean^T as (cxx, cyy, cxy).
    dvec3 covariance() const { return {xx - mean.x * mean.x, yy - mean.y * mean.y, xy - mean.x * mean.y}; }
};

struct SlopeMoments {
    int n = 0;       ///< level 0 side (the field's texels)
    int levels = 0;  ///< log2(n) + 1: the last level is 1 x 1, the whole tile
    /// Per level, row-major: a = (E sx, E sy, E sx^2, E sy^2), 4 floats a texel; b = E sx sy, 1 float a texel.
    std::vector<std::vector<float>> a, b;

    int side(int level) const { return n >> level; }
    /// Bilinear at (x, y) (tile lengths, wrapping) on one level, texel centres at (i + 0.5) / side.
    Moments at(int level, double x, double y) const;
    /// Trilinear: `level` continuous in [0, levels - 1], linear between the two levels around it.
    Moments at(double level, double x, double y) const;
    /// The moments of a footprint: the parallelogram centred at (x, y) with edge vectors ea, eb (tile
    /// lengths). Probes along its longer edge (ceil(long/short) of them, at most kMaxProbes) at the level of
    /// its shorter edge (log2(short * n) - 1/2: a bilinear probe of level L spans ~sqrt(2) 2^L texels), the
    /// twin of footprintMoments() in shaders/micro.glsl.
    Moments footprint(double x, double y, const dvec2& ea, const dvec2& eb) const;
    static constexpr int kMaxProbes = 16;
};

/// The pyramid of a field (double sums, stored as floats; ~0.2 s for 1024^2).
SlopeMoments makeSlopeMoments(const BumpField& f);
/// The pyramid of `spec`'s field, made once per process and kept.
const SlopeMoments& cachedSlopeMoments(const BumpSpec& spec);

}  // namespace hilite::micro
