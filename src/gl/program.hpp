#pragma once
// A linked GL program built from pieces of source, each remembering the file and line it came from,
// so a compile error names "shaders/brdf.glsl:42" rather than "0:317".

#include "hilite/core/error.hpp"

#include <map>
#include <string>
#include <vector>

namespace hilite::gl {

/// A shader that failed to compile or link; `log` is the driver's log with "file:line:" locations.
class ShaderError : public SystemError {
public:
    ShaderError(const std::string& what, std::string translatedLog)
        : SystemError(what), log(std::move(translatedLog)) {}
    std::string log;
};

struct SourcePiece {
    std::string file;   ///< as shown in messages, e.g. "shaders/brdf.glsl" or "<generated>"
    int firstLine = 1;  ///< line in `file` of the piece's first line
    std::string text;
};

/// Piece K > 0 is numbered from K * kLineStride + its first line. Mesa reports some errors (a function
/// redefined, a call that matches no overload, a uniform redeclared) with source string 0 whatever #line
/// said, but with the right line, so the line alone must identify the piece. 2^31 / 1e7: 214 pieces.
constexpr int kLineStride = 10000000;
constexpr size_t kMaxPieces = 214;

/// Joins pieces with "#line K*kLineStride+N K" directives (K = piece index) after the first; piece 0 must
/// start with #version. Throws SystemError beyond kMaxPieces pieces or kLineStride lines a piece.
std::string joinSources(const std::vector<SourcePiece>& pieces);
/// Rewrites "K:N(c): error" in a driver log to "file:line: error" using the pieces.
std::string translateLog(const std::string& log, const std::vector<SourcePiece>& pieces);

class Program {
public:
    /// Compiles and links; throws ShaderError whose message names the shader file and line.
    Program(const std::vector<SourcePiece>& vertex, const std::vector<SourcePiece>& fragment);
    ~Program();
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    unsigned int id() const { return m_id; }
    void use() const;
    /// Location of a uniform, -1 if the program has none by that name (not an error: terms switched out).
    int uniform(const char* name) const;

    void set(const char* name, float v) const;
    void set(const char* name, float x, float y) const;
    void set(const char* name, float x, float y, float z) const;
    void setMat4(const char* name, const float* m) const;

private:
    unsigned int m_id = 0;
    mutable std::map<std::string, int> m_locations;
};

}  // namespace hilite::gl
