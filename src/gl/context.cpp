#include "gl/context.hpp"

#include "core/error.hpp"
#include "gl/check.hpp"

#include <glad/gl.h>

#include <cstdlib>
#include <cstring>
#include <ostream>

namespace hilite::gl {

const char* toString(Backend b) {
    switch (b) {
        case Backend::Auto: return "auto";
        case Backend::OSMesa: return "osmesa";
        case Backend::EGL: return "egl";
    }
    return "?";
}

std::ostream& operator<<(std::ostream& os, Backend b) { return os << toString(b); }

std::optional<Backend> parseBackend(const std::string& s) {
    for (Backend b : {Backend::Auto, Backend::OSMesa, Backend::EGL})
        if (s == toString(b)) return b;
    return std::nullopt;
}

Backend backendFromEnvironment() {
    const char* env = std::getenv("HILITE_GL_BACKEND");
    if (!env || !*env) return Backend::Auto;
    if (auto b = parseBackend(env)) return *b;
    throw InputError(std::string("HILITE_GL_BACKEND: unknown backend '") + env + "' (allowed: auto, osmesa, egl)");
}

namespace {

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

std::unique_ptr<BackendImpl> tryCreate(Backend b, std::string& why) {
    return b == Backend::OSMesa ? createOSMesaBackend(why) : createEGLBackend(why);
}

}  // namespace

Context::Context(Backend backend) {
    std::string failures;
    const std::vector<Backend> order =
        backend == Backend::Auto ? std::vector<Backend>{Backend::OSMesa, Backend::EGL} : std::vector<Backend>{backend};
    for (Backend b : order) {
        std::string why;
        m_impl = tryCreate(b, why);
        if (m_impl) {
            m_info.backend = b;
            break;
        }
        failures += std::string(failures.empty() ? "" : "; ") + toString(b) + ": " + why;
    }
    if (!m_impl) throw SystemError("cannot create an OpenGL context (" + failures + ")");
    makeCurrent();
    m_info.vendor = glString(GL_VENDOR);
    m_info.renderer = glString(GL_RENDERER);
    m_info.version = glString(GL_VERSION);
    m_info.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
    glGetIntegerv(GL_MAJOR_VERSION, &m_info.major);
    glGetIntegerv(GL_MINOR_VERSION, &m_info.minor);
    HILITE_GL_CHECK();
    if (m_info.major * 10 + m_info.minor < 33)
        throw SystemError("OpenGL " + m_info.version + " from " + toString(m_info.backend) + ": need 3.3 or newer");
}

Context::~Context() = default;

void Context::makeCurrent() {
    m_impl->makeCurrent();
    // The GL pointers are per process: reload them for this context's library.
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(m_impl->loader())))
        throw SystemError(std::string("cannot load OpenGL entry points through ") + toString(m_info.backend));
}

std::vector<Backend> Context::available() {
    std::vector<Backend> out;
    for (Backend b : {Backend::OSMesa, Backend::EGL}) {
        std::string why;
        if (tryCreate(b, why)) out.push_back(b);
    }
    return out;
}

}  // namespace hilite::gl
