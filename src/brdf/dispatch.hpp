#pragma once
// The model dispatch, written once: one row per term and model, holding the shaders/brdf.glsl block it
// calls, its GLSL call (in the names of the dispatch that src/render/shader_source.cpp generates: hv, ht,
// w, VoH, wi, wo and the uniforms), the uniforms that call reads, and the same call in C++ on Params
// (used by brdf/evaluate.cpp). Which row a BRDF takes is decided here alone, so a mapping such as
// Blinn-Phong's Beckmann Lambda (blinnExponentToBeckmann) is chosen in one place for both languages.

#include "hilite/brdf/params.hpp"
#include "hilite/brdf/terms.hpp"

#include <vector>

namespace hilite::brdf {

/// A row of the dispatch. `Fn` is the C++ call's signature, per kind of term.
template <class Fn>
struct TermRow {
    const char* block;                  ///< the term's block ("" when the row calls none), as termBlocks lists it
    std::vector<const char*> needs;     ///< further blocks the GLSL call uses (beyond the block's own needs)
    const char* glsl;                   ///< the GLSL expression
    std::vector<const char*> uniforms;  ///< declarations of the uniforms it reads, "float uRoughness"
    Fn cpp;                             ///< the C++ twin of the expression
};

/// Reflection lobes (Phong, classic Phong, retro) and the literature's models (abc, sgd, lafortune, each with its
/// own F and G): `glsl` is the value from what `setup` sets (d, hv), wi, wo.
struct LobeRow : TermRow<dvec3 (*)(const Params&, const dvec3& wi, const dvec3& wo)> {
    const char* setup;  ///< GLSL statement setting what the call reads (vec3 d, HalfVector hv; "" for none)
};
/// D(h): hv the half vector, ht = h in the tangent frame (anisotropic rows only).
using DistributionRow = TermRow<double (*)(const Params&, const HalfVector& hv, const dvec3& ht)>;
/// Smith Lambda(w), w in the local frame (the anisotropic rows move it to the tangent frame).
using LambdaRow = TermRow<double (*)(const Params&, const dvec3& w)>;
/// F(VoH).
using FresnelRow = TermRow<dvec3 (*)(const Params&, double VoH)>;
/// D G / (4 cos_i cos_o) from D; `glsl` is a statement updating s = D in place. lambdaI, lambdaO: Lambda(wi),
/// Lambda(wo) of the model's LambdaRow, computed by the caller for the Smith rows only (usesSmith), else 0.
using GeometryRow = TermRow<double (*)(const HalfVector& hv, const dvec3& wi, const dvec3& wo, double D, double lambdaI,
                                       double lambdaO)>;
/// The diffuse term from wi, wo.
using DiffuseRow = TermRow<dvec3 (*)(const Params&, const dvec3& wi, const dvec3& wo)>;
/// The multiple-scattering term from wi, wo (reads Params::energy).
using MultiscatterRow = TermRow<dvec3 (*)(const Params&, const dvec3& wi, const dvec3& wo)>;

/// Anisotropic roughness on a model that has an anisotropic form: the *Aniso rows and a tangent frame.
bool anisotropicTerms(const Params& p);
/// Smith geometry (correlated or separable): a Lambda row is called.
bool usesSmith(const Params& p);

/// The rows a BRDF calls. lobeRow: Phong, PhongClassic, Retro, ABC, SGD, Lafortune. distributionRow, lambdaRow: microfacet
/// models. Throws std::logic_error for a model without such a row.
const LobeRow& lobeRow(Model m);
const DistributionRow& distributionRow(const Params& p);
const LambdaRow& lambdaRow(const Params& p);
const FresnelRow& fresnelRow(Fresnel f);
/// The row the BRDF calls: fresnelRow(p.fresnel), or the spectral table's row (Params::spectralTable).
const FresnelRow& fresnelRow(const Params& p);
const GeometryRow& geometryRow(Geometry g);
const DiffuseRow& diffuseRow(Diffuse d);
const MultiscatterRow& multiscatterRow(Multiscatter m);

}  // namespace hilite::brdf
