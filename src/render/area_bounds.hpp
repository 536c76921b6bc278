#pragma once
// A cheap enclosure of the exact reflected luminance under a sphere or disk light, where the lobe's centre lies far
// outside the light (its far tail over the cap, smooth): the rule at 4 and 8 rings (320 evaluations instead of the
// exact integral's 1,400-10,000), the interval 4x their difference (and 1e-6 of the value) wide on each side, given
// only where the two agree within 10%.
// measureReference's star-shape checks and coarse peak search decide by it where it lies wholly on one side.

#include "hilite/render/scene.hpp"

namespace hilite::render {

/// True with lo <= L <= hi (the luminance of areaRadianceExact(s, p, we)) where the enclosure applies; false where
/// it does not (the lobe's centre within four widths of the cap, the horizon cutting the cap, or the two rules apart).
bool areaLuminanceBounds(const Scene& s, const dvec3& p, const dvec3& we, double& lo, double& hi);

}  // namespace hilite::render
