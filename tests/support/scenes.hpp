#pragma once
// Shared scene builders of the GL and experiment tests.

#include "hilite/brdf/params.hpp"
#include "hilite/render/scene.hpp"

namespace hilite::test {

/// The default scene with built-in model `m`, `param` its exponent or roughness (usesExponent), lit at `incidence` deg.
inline render::Scene makeScene(brdf::Model m, double param, double incidence) {
    render::Scene s;
    s.brdf.model = m;
    (brdf::usesExponent(m) ? s.brdf.exponent : s.brdf.roughness) = param;
    s.light.incidenceDeg = incidence;
    return s;
}

}  // namespace hilite::test
