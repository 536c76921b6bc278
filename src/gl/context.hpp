#pragma once
// An offscreen OpenGL context (RAII) behind a small interface, one backend per source file:
// OSMesa (backend_osmesa.cpp) and EGL surfaceless (backend_egl.cpp), both Mesa's llvmpipe here.
// Both libraries are opened at run time (dlopen), so a machine without one still runs with the other;
// GL entry points are loaded through the backend's GetProcAddress (glad), never linked from libGL.
// One context is current per process at a time: creating a context loads the GL pointers for it.

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hilite::gl {

enum class Backend { Auto, OSMesa, EGL };
const char* toString(Backend);
std::ostream& operator<<(std::ostream&, Backend);
std::optional<Backend> parseBackend(const std::string&);  ///< "auto", "osmesa", "egl"
/// The backend asked for by the environment variable HILITE_GL_BACKEND, or Auto.
Backend backendFromEnvironment();

struct ContextInfo {
    Backend backend = Backend::Auto;
    std::string vendor, renderer, version, glslVersion;
    int major = 0, minor = 0;
};

/// What a backend does; implemented once per source file.
class BackendImpl {
public:
    virtual ~BackendImpl() = default;
    virtual void makeCurrent() = 0;
    using ProcLoader = void (*(*)(const char*))();
    virtual ProcLoader loader() const = 0;
};

/// Each returns nullptr and sets `why` when the backend cannot give a GL >= 3.3 core context.
std::unique_ptr<BackendImpl> createOSMesaBackend(std::string& why);
std::unique_ptr<BackendImpl> createEGLBackend(std::string& why);

class Context {
public:
    /// Creates and makes current a context; Auto prefers OSMesa and falls back to EGL.
    /// Throws SystemError saying why every backend tried failed.
    explicit Context(Backend backend = Backend::Auto);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const ContextInfo& info() const { return m_info; }
    void makeCurrent();

    /// The backends that can create a context on this machine (each tried once, then released).
    static std::vector<Backend> available();

private:
    std::unique_ptr<BackendImpl> m_impl;
    ContextInfo m_info;
};

}  // namespace hilite::gl
