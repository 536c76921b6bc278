#include "gl/context.hpp"

#include "gl/check.hpp"
#include "hilite/core/error.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <ostream>

namespace hilite::gl {

const char* toString(Backend b) {
    switch (b) {
        case Backend::Auto: return "auto";
        case Backend::OSMesa: return "osmesa";
        case Backend::EGL: return "egl";
        case Backend::EGLDevice: return "egl-device";
    }
    return "?";
}

std::ostream& operator<<(std::ostream& os, Backend b) { return os << toString(b); }

std::optional<Backend> parseBackend(const std::string& s) {
    for (Backend b : {Backend::Auto, Backend::OSMesa, Backend::EGL, Backend::EGLDevice})
        if (s == toString(b)) return b;
    return std::nullopt;
}

std::vector<std::string> backendNames() { return {"auto", "osmesa", "egl", "egl-device"}; }

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

std::unique_ptr<BackendImpl> tryCreate(Backend b, int device, std::string& why) {
    if (b == Backend::EGLDevice) return createEGLDeviceBackend(device, why);
    return b == Backend::OSMesa ? createOSMesaBackend(why) : createEGLBackend(why);
}

/// A software rasterizer's GL_RENDERER (Mesa: "llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe").
bool softwareRenderer(const std::string& renderer) {
    return renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
}

}  // namespace

int firstHardwareDevice() {
    std::string why;
    const auto devices = eglDevices(why);
    for (size_t i = 0; i < devices.size(); ++i)
        if (!devices[i].software) return int(i);
    return -1;
}

Context::Context(Backend backend, int device) {
    if (backend == Backend::EGLDevice || (backend == Backend::Auto && device >= 0)) {
        std::string why;
        const size_t count = eglDevices(why).size();
        if (device >= 0 && size_t(device) >= count)
            throw InputError("--gpu: must be a device index in [0, " + std::to_string(count) + ") (got " +
                             std::to_string(device) + (count ? ")" : "; EGL lists no device: " + why + ")"));
    }
    std::string failures;
    struct Try {
        Backend backend;
        int device;
    };
    std::vector<Try> order;
    if (backend == Backend::Auto) {
        const int hw = device >= 0 ? device : firstHardwareDevice();
        if (hw >= 0) order.push_back({Backend::EGLDevice, hw});
        if (device < 0) {  // --gpu names a device: no fallback to another renderer
            order.push_back({Backend::OSMesa, -1});
            order.push_back({Backend::EGL, -1});
        }
    } else if (backend == Backend::EGLDevice) {
        const int hw = firstHardwareDevice();
        order.push_back({backend, device >= 0 ? device : hw >= 0 ? hw : 0});
    } else {
        order.push_back({backend, -1});
    }
    for (const Try& t : order) {
        std::string why;
        m_impl = tryCreate(t.backend, t.device, why);
        if (m_impl) {
            m_info.backend = t.backend;
            makeCurrent();
            // auto wants a GPU from EGL device: a driver that renders in software is passed over.
            if (backend == Backend::Auto && device < 0 && t.backend == Backend::EGLDevice &&
                softwareRenderer(glString(GL_RENDERER))) {
                failures += std::string(failures.empty() ? "" : "; ") + "egl-device " + std::to_string(t.device) +
                            ": renders in software (" + glString(GL_RENDERER) + ")";
                m_impl.reset();
                continue;
            }
            m_info.backend = t.backend;
            m_info.device = t.device;
            break;
        }
        failures += std::string(failures.empty() ? "" : "; ") + toString(t.backend) + ": " + why;
    }
    if (!m_impl) throw SystemError("cannot create an OpenGL context (" + failures + ")");
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

namespace {
thread_local const Context* t_current = nullptr;     ///< the Context last made current on this thread
std::atomic<const Context*> g_entryPoints{nullptr};  ///< whose entry points glad holds (they are per process)
}  // namespace

Context::~Context() {
    if (t_current == this) t_current = nullptr;
    const Context* self = this;
    g_entryPoints.compare_exchange_strong(self, nullptr);
}

void Context::makeCurrent() {
    t_current = nullptr;  // until both steps succeed
    m_impl->makeCurrent();
    // The GL pointers are per process: reload them for this context's library.
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(m_impl->loader())))
        throw SystemError(std::string("cannot load OpenGL entry points through ") + toString(m_info.backend));
    t_current = this;
    g_entryPoints = this;
}

void Context::ensureCurrent() {
    if (t_current != this || g_entryPoints != this) makeCurrent();
}

std::vector<Backend> Context::available() {
    std::vector<Backend> out;
    for (Backend b : {Backend::OSMesa, Backend::EGL, Backend::EGLDevice}) {
        std::string why;
        if (tryCreate(b, b == Backend::EGLDevice ? std::max(firstHardwareDevice(), 0) : -1, why)) out.push_back(b);
    }
    return out;
}

}  // namespace hilite::gl
