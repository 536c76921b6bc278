#include "gl/program.hpp"

#include "gl/check.hpp"
#include "hilite/core/error.hpp"

#include <glad/gl.h>

#include <cctype>
#include <sstream>

namespace hilite::gl {

std::string joinSources(const std::vector<SourcePiece>& pieces) {
    if (pieces.size() > kMaxPieces)
        throw SystemError("shader: more than " + std::to_string(kMaxPieces) + " source pieces");
    std::string out;
    for (size_t i = 0; i < pieces.size(); ++i) {
        if (pieces[i].firstLine < 1 || pieces[i].firstLine >= kLineStride / 2)
            throw SystemError("shader: piece " + pieces[i].file + " starts at line " +
                              std::to_string(pieces[i].firstLine));
        // Piece 0 holds #version, which must come first; later pieces announce where they come from.
        if (i > 0)
            out +=
                "#line " + std::to_string(long(i) * kLineStride + pieces[i].firstLine) + " " + std::to_string(i) + "\n";
        out += pieces[i].text;
        if (!out.empty() && out.back() != '\n') out += '\n';
    }
    return out;
}

namespace {

/// The first "K:N(C)" of a log line (Mesa's location: source string, line, column), or at = npos. By hand, not
/// std::regex: GCC 12's <regex> warns (-Wmaybe-uninitialized, in libstdc++) in the sanitizer build.
struct Location {
    size_t at = std::string::npos, length = 0;
    std::string k, n, c;
};
Location findLocation(const std::string& s) {
    auto digitsFrom = [&](size_t i) {
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
        return i;
    };
    for (size_t i = 0; i < s.size(); ++i) {
        // A match starting inside a number would have started at its first digit (leftmost, as regex_search).
        if (!std::isdigit(static_cast<unsigned char>(s[i])) ||
            (i > 0 && std::isdigit(static_cast<unsigned char>(s[i - 1]))))
            continue;
        const size_t a = digitsFrom(i);
        if (a >= s.size() || s[a] != ':') continue;
        const size_t b = digitsFrom(a + 1);
        if (b == a + 1 || b >= s.size() || s[b] != '(') continue;
        const size_t c = digitsFrom(b + 1);
        if (c == b + 1 || c >= s.size() || s[c] != ')') continue;
        return {i, c + 1 - i, s.substr(i, a - i), s.substr(a + 1, b - a - 1), s.substr(b + 1, c - b - 1)};
    }
    return {};
}

}  // namespace

std::string translateLog(const std::string& log, const std::vector<SourcePiece>& pieces) {
    // Mesa writes "K:N(C): error: ...": K the source-string number set by #line, N the line.
    std::string out;
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);) {
        const Location m = findLocation(line);
        if (m.at != std::string::npos) {
            size_t k = std::stoul(m.k);
            long n = std::stol(m.n);
            if (n >= kLineStride) k = size_t(n / kLineStride), n %= kLineStride;  // the line names the piece
            if (k < pieces.size()) {
                if (k == 0) n += pieces[0].firstLine - 1;
                line = line.substr(0, m.at) + pieces[k].file + ":" + std::to_string(n) + ":" + m.c +
                       line.substr(m.at + m.length);
            }
        }
        out += line + "\n";
    }
    return out;
}

namespace {

GLuint compile(GLenum type, const std::vector<SourcePiece>& pieces) {
    const std::string src = joinSources(pieces);
    GLuint shader = glCreateShader(type);
    const char* text = src.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetShaderInfoLog(shader, len, nullptr, log.data());
        glDeleteShader(shader);
        const char* kind = type == GL_VERTEX_SHADER ? "vertex" : "fragment";
        const std::string translated = translateLog(log.c_str(), pieces);
        throw ShaderError(std::string(kind) + " shader failed to compile:\n" + translated, translated);
    }
    return shader;
}

}  // namespace

Program::Program(const std::vector<SourcePiece>& vertex, const std::vector<SourcePiece>& fragment) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    m_id = glCreateProgram();
    glAttachShader(m_id, vs);
    glAttachShader(m_id, fs);
    glLinkProgram(m_id);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(m_id, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(m_id, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(m_id, len, nullptr, log.data());
        glDeleteProgram(m_id);
        m_id = 0;
        const std::string translated = translateLog(log.c_str(), fragment);
        throw ShaderError(
            "shader program failed to link (" + vertex.back().file + " + " + fragment.back().file + "):\n" + translated,
            translated);
    }
    HILITE_GL_CHECK_WHAT("glLinkProgram");
}

Program::~Program() {
    if (m_id) glDeleteProgram(m_id);
}

void Program::use() const { glUseProgram(m_id); }

int Program::uniform(const char* name) const {
    auto it = m_locations.find(name);
    if (it != m_locations.end()) return it->second;
    const int loc = glGetUniformLocation(m_id, name);
    m_locations.emplace(name, loc);
    return loc;
}

void Program::set(const char* name, float v) const { glUniform1f(uniform(name), v); }
void Program::set(const char* name, float x, float y) const { glUniform2f(uniform(name), x, y); }
void Program::set(const char* name, float x, float y, float z) const { glUniform3f(uniform(name), x, y, z); }
void Program::setMat4(const char* name, const float* m) const { glUniformMatrix4fv(uniform(name), 1, GL_FALSE, m); }

}  // namespace hilite::gl
