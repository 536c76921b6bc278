#pragma once
// A cheap enclosure of a lobe's value where one is known, for the reference's decisions that only compare a value
// with the threshold (the star-shape checks) or rank values (the coarse peak search): where the enclosure decides,
// the lobe itself is not evaluated. Under a light with size the lobe is an exact integral over the light (8,000
// evaluations near the lobe, 1,400 in its far tail), and most of those decisions are far in the tail.

#include "hilite/analysis/highlight.hpp"

#include <functional>

namespace hilite::analysis {

/// True with lo <= L(u, v) <= hi where a cheap enclosure is known; false where not (the lobe is then evaluated).
/// Only for visible (u, v).
using LobeBounds = std::function<bool(double u, double v, double& lo, double& hi)>;

/// measureReference (highlight.hpp) with the enclosure: the same shape, fewer evaluations of f.lobe.
Shape measureReference(const LobeFunction& f, const LobeBounds& bounds, const Options& opt, double searchRadius,
                       double hint_u = 0, double hint_v = 0);

}  // namespace hilite::analysis
