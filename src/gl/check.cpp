#include "gl/check.hpp"

#include "hilite/core/error.hpp"

#include <glad/gl.h>

#include <string>

namespace hilite::gl {

const char* errorName(unsigned int code) {
    switch (code) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        default: return "GL_UNKNOWN_ERROR";
    }
}

namespace {
/// "src/render/renderer.cpp" rather than the build machine's absolute path.
std::string sourceName(const char* file) {
    const std::string f(file);
    const auto pos = f.rfind("/src/");
    return pos == std::string::npos ? f : f.substr(pos + 1);
}
}  // namespace

void checkErrors(const char* what, const char* file, int line) {
    std::string errors;
    for (int i = 0; i < 16; ++i) {  // glGetError queues one flag per kind; 16 drains any implementation
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        errors += std::string(errors.empty() ? "" : ", ") + errorName(e);
    }
    if (!errors.empty())
        throw SystemError(errors + " after " + what + " at " + sourceName(file) + ":" + std::to_string(line));
}

}  // namespace hilite::gl
