#pragma once
// Assembles the fragment program for one effect set from the real files in shaders/: only the term
// blocks the scene names are copied in, and the dispatch that calls them is generated here, so the
// program text contains exactly the terms it runs.

#include "brdf/params.hpp"
#include "gl/program.hpp"

#include <map>
#include <string>
#include <vector>

namespace hilite::render {

enum class Output { Color, Measure };

/// Where the shader files are: $HILITE_SHADER_DIR, else <exe>/../share/hilite/shaders, else the
/// install prefix. Never the current directory. Throws SystemError listing the places tried.
std::string shaderDirectory();

/// One "//@block NAME needs A B" ... "//@end" section of a shader file.
struct ShaderBlock {
    std::string name;
    std::vector<std::string> needs;
    int firstLine = 1;
    std::string text;
};

/// The blocks of a file, in file order. Throws SystemError naming file:line on a malformed marker.
std::vector<ShaderBlock> parseBlocks(const std::string& text, const std::string& file);

/// The term blocks a BRDF needs (before dependency closure), e.g. {"D_GGX", "HalfVector"}.
std::vector<std::string> termBlocks(const brdf::Params& p);
/// GLSL of the generated dispatch: uniforms and `vec3 brdf(vec3 wi, vec3 wo)`.
std::string dispatchSource(const brdf::Params& p);
/// Key identifying the compiled program (effect set + output), for the program cache.
std::string effectKey(const brdf::Params& p, Output out);

struct ProgramSources {
    std::vector<gl::SourcePiece> vertex, fragment;
};
/// Reads the files from `dir` and assembles both stages.
ProgramSources assemble(const brdf::Params& p, Output out, const std::string& dir);

}  // namespace hilite::render
