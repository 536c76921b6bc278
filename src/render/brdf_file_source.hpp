#pragma once
// The fragment program of a scene whose BRDF is a BRDF Explorer .brdf file. Pieces, in order:
//   <generated config>           #version 410 core (BRDF Explorer's version) and the output/light defines
//   <generated .brdf dispatch>   the prototype vec3 brdf(vec3 wi, vec3 wo)
//   shaders/shade.frag           the per-pixel shading, unchanged
//   PATH                         "uniform float n;" etc., each on the line of its declaration
//   PATH                         the shader section at its own lines
//   <generated .brdf wrapper>    brdf(wi, wo) = max(BRDF(wi, wo, N = +z, X, Y), 0), X, Y turned by the
//                                tangent angle
// The .brdf's text comes after hilite's, so a name both define (a uniform, a function) is reported at the
// .brdf's own line; its '#' lines were comments already (brdf_file::parse), so it cannot #define anything
// into hilite's code. BRDF Explorer compiles these shaders as GLSL 4.10 (its templates say #version 410),
// and so does hilite: shade.frag is 4.10-clean, and the vertex stage (4.50) links with it.

#include "hilite/brdf_file/brdf_file.hpp"
#include "render/shader_source.hpp"

#include <string>

namespace hilite::render {

/// Both stages for a .brdf file, reading plane.vert and shade.frag from `dir`.
ProgramSources assembleBrdfFile(const brdf_file::BrdfFile& f, Output out, const std::string& dir);

/// Program cache key: the file's path, parameter declarations and shader text (never the values).
std::string brdfFileKey(const brdf_file::BrdfFile& f, Output out);

/// \brief One line for a .brdf program that failed to build, from the driver's translated log.
/// Errors in the file give "PATH:LINE:COL: error: ..." (the first, and how many more); a BRDF that cannot
/// be called with BRDF Explorer's signature says so; a name that hilite's shader also defines is named.
std::string brdfBuildError(const brdf_file::BrdfFile& f, const ProgramSources& src, const std::string& log);

}  // namespace hilite::render
