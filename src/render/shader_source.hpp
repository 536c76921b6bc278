#pragma once
// Assembles the fragment program for one effect set from the real files in shaders/: only the term
// blocks the scene names are copied in, and the dispatch that calls them is generated here, so the
// program text contains exactly the terms it runs.

#include "gl/program.hpp"
#include "hilite/brdf/params.hpp"

#include <map>
#include <string>
#include <vector>

namespace hilite::render {

enum class Output { Color, Measure };

/// Where the shader files are: $HILITE_SHADER_DIR, else $HILITE_SHARE_DIR/shaders, else
/// <exe>/../share/hilite/shaders, else the install prefix compiled in (HILITE_INSTALL_SHADER_DIR: what a
/// program linked against the installed library finds). Never the current directory. Throws
/// SystemError listing the places tried.
std::string shaderDirectory();
/// Where the data files are (data/ of the source tree: metals/, colorimetry/), found the same way:
/// $HILITE_DATA_DIR, else $HILITE_SHARE_DIR/data, else <exe>/../share/hilite/data, else the install prefix.
std::string dataDirectory();

/// The text of a shader file; SystemError naming it when it cannot be read.
std::string readShaderFile(const std::string& path);

/// One "//@block NAME needs A B" ... "//@end" section of a shader file.
struct ShaderBlock {
    std::string name;
    std::string file;  ///< "shaders/brdf.glsl", "shaders/brdf_gl.glsl" or "shaders/micro.glsl"
    std::vector<std::string> needs;
    int firstLine = 1;
    std::string text;
};

/// The blocks of a file, in file order. Throws SystemError naming file:line on a malformed marker.
std::vector<ShaderBlock> parseBlocks(const std::string& text, const std::string& file);

/// Every block a program may be assembled from, read from `dir`: shaders/brdf_gl.glsl (the GLSL prelude
/// and the GLSL-only terms), shaders/brdf.glsl (the terms shared with C++) and shaders/micro.glsl.
std::vector<ShaderBlock> termLibrary(const std::string& dir);
/// The named blocks with their dependencies, dependencies first, each once. SystemError for an unknown name.
std::vector<const ShaderBlock*> closure(const std::vector<ShaderBlock>& blocks, const std::vector<std::string>& names);

/// The term blocks a BRDF needs (before dependency closure), e.g. {"HalfVector", "D_GGX"}: the blocks of
/// its rows in brdf/dispatch.hpp.
std::vector<std::string> termBlocks(const brdf::Params& p);
/// GLSL of the generated dispatch: uniforms and `vec3 brdf(vec3 wi, vec3 wo)`, from the GLSL side of the
/// rows of brdf/dispatch.hpp. It names only the terms switched in (no fresnel() at all for Fresnel::None)
/// and no parameter values.
std::string dispatchSource(const brdf::Params& p);

/// A uniform the terms read, with its values (an array when values.size() > components).
struct TermUniform {
    std::string name;
    int components = 1;  ///< 1, 2 or 3: float, vec2, vec3
    std::vector<float> values;
};
/// The uniforms of the terms beyond uExponent / uRoughness / uF0 (anisotropy, Gaussian k_G, eta, k,
/// spectral arrays, diffuse): all that the parameters define; a program uses those it declares.
std::vector<TermUniform> termUniforms(const brdf::Params& p);
/// Key identifying the compiled program (effect set + output), for the program cache.
std::string effectKey(const brdf::Params& p, Output out);

struct ProgramSources {
    std::vector<gl::SourcePiece> vertex, fragment;
};
/// Reads the files from `dir` and assembles both stages.
ProgramSources assemble(const brdf::Params& p, Output out, const std::string& dir);

}  // namespace hilite::render
