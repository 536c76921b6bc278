#pragma once
// An offscreen OpenGL context (RAII) behind a small interface, one backend per source file:
// OSMesa (backend_osmesa.cpp), EGL surfaceless and EGL device (backend_egl.cpp): Mesa's llvmpipe here,
// the GPU's driver through EGL device where there is one.
// Both libraries are opened at run time (dlopen), so a machine without one still runs with the other;
// GL entry points are loaded through the backend's GetProcAddress (glad), never linked from libGL.
// One context is current per process at a time: creating a context loads the GL pointers for it.

#include "hilite/gl/backend.hpp"

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hilite::gl {

struct ContextInfo {
    Backend backend = Backend::Auto;
    int device = -1;  ///< egl-device: the index among eglDevices(); -1 for the other backends
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
std::unique_ptr<BackendImpl> createEGLDeviceBackend(int index, std::string& why);

/// A device EGL enumerates (EGL_EXT_device_enumeration), as EGL_EXT_device_query describes it.
struct EglDevice {
    std::string extensions;  ///< the device's own extension string
    std::string drmFile;     ///< EGL_DRM_DEVICE_FILE_EXT ("/dev/dri/card0"), "" without EGL_EXT_device_drm
    bool software = false;   ///< EGL_MESA_device_software: Mesa's llvmpipe, not a GPU
};
/// The devices of this machine, in EGL's order (the --gpu index); empty with `why` set when libEGL or
/// the device extensions are missing. Enumerated once per process.
std::vector<EglDevice> eglDevices(std::string& why);
/// The index of the first device that is not Mesa's software device, or -1.
int firstHardwareDevice();

class Context {
public:
    /// Creates and makes current a context. Auto prefers a hardware EGL device (one that is not Mesa's
    /// software device and whose GL renderer is not llvmpipe or softpipe), then OSMesa, then EGL
    /// surfaceless. `device`: egl-device's index (-1: the first hardware device, else 0); InputError
    /// naming --gpu when no such device exists. Throws SystemError saying why every backend tried failed.
    explicit Context(Backend backend = Backend::Auto, int device = -1);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const ContextInfo& info() const { return m_info; }
    /// Makes the context current on this thread and loads its GL entry points.
    void makeCurrent();
    /// makeCurrent() unless this context was the last one made current on this thread and the entry points
    /// loaded are its own (another Context made since, e.g. an experiment's, makes it needed again).
    void ensureCurrent();

    /// The backends that can create a context on this machine (each tried once, then released).
    static std::vector<Backend> available();

private:
    std::unique_ptr<BackendImpl> m_impl;
    ContextInfo m_info;
};

}  // namespace hilite::gl
