#pragma once
// Disney BRDF Explorer `.brdf` files (the "analytic" kind): a parameter block and a GLSL function
//   vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)
// (L, V towards light and viewer, N the normal, X, Y tangent and bitangent; reflectance without the cosine
// factor, which the host applies). The grammar is BRDF Explorer's own (wdas/brdf, BRDFBase::loadBRDF):
//
//   analytic                         first line (first word)
//   # comment                        any line whose first non-blank character is '#', in every section
//   ::begin parameters               float NAME MIN MAX DEFAULT | bool NAME 0|1 | color NAME R G B
//   ::end parameters
//   ::begin shader                   GLSL, copied line for line (so errors keep the file's line numbers)
//   ::end shader
//   ::begin isFunc ... ::end isFunc  importance sampling for BRDF Explorer's IBL view: ignored, with a note
//
// As in BRDF Explorer, '#' lines inside the shader are comments, so GLSL preprocessor directives in a
// .brdf never reach the compiler (a note says so). Stricter than BRDF Explorer, which skips what it cannot
// read: text outside a section, unknown words on a parameter line, a default outside [MIN, MAX] and
// duplicate names are errors here. Depends on core only.

#include "hilite/core/math.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace hilite::brdf_file {

enum class ParamType { Float, Bool, Color };
const char* toString(ParamType);  ///< "float", "bool", "color": the file's spelling
std::ostream& operator<<(std::ostream&, ParamType);

/// One declared parameter; it becomes a uniform of the same name (float, bool, vec3).
struct Parameter {
    ParamType type = ParamType::Float;
    std::string name;
    double min = 0, max = 0;  ///< float: the declared range, values outside it are rejected
    dvec3 value{0.0};         ///< float, bool (0 or 1): value.x; color: R, G, B. The default until assigned
    int line = 0;             ///< where it is declared
};

struct BrdfFile {
    std::string path;                   ///< as given: names the file in every message
    std::vector<Parameter> parameters;  ///< in declaration order
    int parametersLine = 0;             ///< line of "::begin parameters" (0: the file has none)
    std::string shader;                 ///< the shader section, one line per file line ('#' lines blanked)
    int shaderLine = 0;                 ///< file line of the shader text's first line
    std::vector<std::string> notes;     ///< what was ignored, each "path:line: ..."

    /// The parameter called `name`, or nullptr.
    const Parameter* find(const std::string& name) const;
};

/// Largest .brdf accepted (1 MB): BRDF Explorer's own files are a few kB.
constexpr size_t kMaxFileBytes = 1 << 20;

/// \brief Parses the text of a .brdf file.
/// \param path names the file in messages.
/// Throws InputError "path:line: problem" (one line) on anything it cannot read: a first line other than
/// `analytic`, unclosed or nested sections, bad parameter lines, no shader, no `vec3 BRDF(` in it.
BrdfFile parse(const std::string& text, const std::string& path);
/// Reads and parses `path`; InputError "--brdf: cannot read 'path'" when it cannot be read.
BrdfFile load(const std::string& path);

/// \brief Sets parameter values from "NAME=VALUE" assignments, applied in order (a later one wins).
/// Several may share one string separated by commas: a token holding '=' starts an assignment, a token
/// without one continues the previous value, so "n=100,tint=1,0.5,0.2,metal=1" is n, a colour and a bool.
/// float: a number in the declared [MIN, MAX]; bool: 0, 1, true or false; color: V or R,G,B, finite.
/// Throws InputError "path:line: --param NAME=VALUE: problem" naming the declaration's line (for an
/// unknown name, the line of "::begin parameters"), with a did-you-mean when a name is close.
void assign(BrdfFile& file, const std::string& assignments);

/// Every parameter with its value, "n=100 metal=1 tint=1,0.5,0.2" (numbers in full precision).
std::string valuesText(const BrdfFile& f);
/// The same as assignments accepted by assign(): one "NAME=VALUE" per parameter.
std::vector<std::string> valueAssignments(const BrdfFile& f);

std::ostream& operator<<(std::ostream&, const BrdfFile&);  ///< "brdf=PATH n=100 ..."

}  // namespace hilite::brdf_file
