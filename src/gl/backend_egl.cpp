// EGL backends: surfaceless (EGL_MESA_platform_surfaceless), the successor to OSMesa, same llvmpipe on a
// machine without a GPU; and device (EGL_EXT_device_enumeration + EGL_EXT_platform_device), a display per
// enumerated device: a GPU where there is one, Mesa's software device (llvmpipe) elsewhere. No surface at
// all: we render into our own FBO with EGL_NO_SURFACE. libEGL is opened with dlopen so that a machine
// without it still runs with OSMesa.

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "gl/context.hpp"
#include "hilite/core/error.hpp"

namespace hilite::gl {

namespace {

struct EglApi {
    PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
    PFNEGLQUERYSTRINGPROC queryString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLTERMINATEPROC terminate = nullptr;
    PFNEGLBINDAPIPROC bindApi = nullptr;
    PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
    PFNEGLCREATECONTEXTPROC createContext = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
    PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
    PFNEGLGETERRORPROC getError = nullptr;
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;            // EGL_EXT_device_enumeration
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;  // EGL_EXT_device_query
};

EglApi g_egl;  // loaded once; glad's loader goes through g_egl.getProcAddress

void (*eglLoad(const char* name))() { return reinterpret_cast<void (*)()>(g_egl.getProcAddress(name)); }

template <class Fn>
Fn sym(void* lib, const char* name) {
    return reinterpret_cast<Fn>(dlsym(lib, name));
}

bool loadApi(std::string& why) {
    if (g_egl.getProcAddress) return true;
    void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        why = "libEGL.so.1 not found; install libegl1 libegl-mesa0";
        return false;
    }
    EglApi api;
    api.getProcAddress = sym<PFNEGLGETPROCADDRESSPROC>(lib, "eglGetProcAddress");
    api.queryString = sym<PFNEGLQUERYSTRINGPROC>(lib, "eglQueryString");
    api.initialize = sym<PFNEGLINITIALIZEPROC>(lib, "eglInitialize");
    api.terminate = sym<PFNEGLTERMINATEPROC>(lib, "eglTerminate");
    api.bindApi = sym<PFNEGLBINDAPIPROC>(lib, "eglBindAPI");
    api.chooseConfig = sym<PFNEGLCHOOSECONFIGPROC>(lib, "eglChooseConfig");
    api.createContext = sym<PFNEGLCREATECONTEXTPROC>(lib, "eglCreateContext");
    api.destroyContext = sym<PFNEGLDESTROYCONTEXTPROC>(lib, "eglDestroyContext");
    api.makeCurrent = sym<PFNEGLMAKECURRENTPROC>(lib, "eglMakeCurrent");
    api.getError = sym<PFNEGLGETERRORPROC>(lib, "eglGetError");
    if (!api.getProcAddress || !api.queryString || !api.initialize || !api.createContext || !api.makeCurrent) {
        why = "libEGL.so.1 lacks core EGL 1.4 entry points";
        return false;
    }
    api.getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(api.getProcAddress("eglGetPlatformDisplayEXT"));
    api.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(api.getProcAddress("eglQueryDevicesEXT"));
    api.queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(api.getProcAddress("eglQueryDeviceStringEXT"));
    g_egl = api;
    return true;
}

class EGLBackend final : public BackendImpl {
public:
    EGLBackend(EGLDisplay dpy, EGLContext ctx) : m_dpy(dpy), m_ctx(ctx) {}
    ~EGLBackend() override {
        g_egl.makeCurrent(m_dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        g_egl.destroyContext(m_dpy, m_ctx);
        // The display is not terminated: it lives for the process (see openDisplay).
    }
    void makeCurrent() override {
        if (!g_egl.makeCurrent(m_dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, m_ctx))
            throw SystemError("eglMakeCurrent failed");
    }
    ProcLoader loader() const override { return &eglLoad; }

private:
    EGLDisplay m_dpy;
    EGLContext m_ctx;
};

std::string eglErrorText() {
    return "EGL error 0x" + [] {
        char buf[16];
        std::snprintf(buf, sizeof buf, "%04x", unsigned(g_egl.getError ? g_egl.getError() : 0));
        return std::string(buf);
    }();
}

/// The surfaceless display, initialised once and kept for the process: eglTerminate unloads the
/// driver, and a terminate/initialise per context both costs a driver load and leaves the driver's
/// allocations unreachable (LeakSanitizer reports them against an unloaded module it cannot name).
EGLDisplay openDisplay(std::string& why) {
    static EGLDisplay display = EGL_NO_DISPLAY;
    if (display != EGL_NO_DISPLAY) return display;
    const char* clientExt = g_egl.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExt || !std::strstr(clientExt, "EGL_MESA_platform_surfaceless") || !g_egl.getPlatformDisplay) {
        why = "EGL has no EGL_MESA_platform_surfaceless (install libegl-mesa0)";
        return EGL_NO_DISPLAY;
    }
    EGLDisplay dpy = g_egl.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !g_egl.initialize(dpy, &major, &minor)) {
        why = "eglInitialize on the surfaceless platform failed (" + eglErrorText() + ")";
        return EGL_NO_DISPLAY;
    }
    return display = dpy;
}

/// A desktop GL core context (4.5, else 3.3) on an initialised display, used with EGL_NO_SURFACE.
std::unique_ptr<BackendImpl> createContextOn(EGLDisplay dpy, std::string& why) {
    if (!g_egl.bindApi(EGL_OPENGL_API)) {
        why = "eglBindAPI(EGL_OPENGL_API) failed";
        return nullptr;
    }
    // EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT, which neither platform has: ask for pbuffer configs (the
    // context never gets a surface), else any config with desktop GL.
    const EGLint pbuffer[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    const EGLint any[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if ((!g_egl.chooseConfig(dpy, pbuffer, &config, 1, &count) || count < 1) &&
        (!g_egl.chooseConfig(dpy, any, &config, 1, &count) || count < 1)) {
        why = "no EGL config with desktop OpenGL";
        return nullptr;
    }
    for (EGLint minorVersion : {45, 33}) {
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  minorVersion / 10,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  minorVersion % 10,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
        EGLContext ctx = g_egl.createContext(dpy, config, EGL_NO_CONTEXT, attribs);
        if (ctx != EGL_NO_CONTEXT) return std::make_unique<EGLBackend>(dpy, ctx);
    }
    why = "eglCreateContext failed for GL 4.5 and 3.3 core (" + eglErrorText() + ")";
    return nullptr;
}

/// The enumerated devices, queried once (null with `why` when EGL or its device extensions are missing).
const std::vector<EGLDeviceEXT>* devices(std::string& why) {
    static std::vector<EGLDeviceEXT> list;
    static const std::string failure = []() -> std::string {
        std::string err;
        if (!loadApi(err)) return err;
        const char* ext = g_egl.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!ext || !std::strstr(ext, "EGL_EXT_device_enumeration") || !std::strstr(ext, "EGL_EXT_platform_device") ||
            !g_egl.queryDevices || !g_egl.getPlatformDisplay)
            return "EGL lacks EGL_EXT_device_enumeration / EGL_EXT_platform_device";
        EGLint n = 0;
        if (!g_egl.queryDevices(0, nullptr, &n) || n <= 0) return "eglQueryDevicesEXT lists no device";
        list.resize(size_t(n));
        if (!g_egl.queryDevices(n, list.data(), &n) || n <= 0) return "eglQueryDevicesEXT lists no device";
        list.resize(size_t(n));
        return "";
    }();
    why = failure;
    return failure.empty() ? &list : nullptr;
}

std::string deviceString(EGLDeviceEXT d, EGLint name) {
    const char* s = g_egl.queryDeviceString ? g_egl.queryDeviceString(d, name) : nullptr;
    return s ? s : "";
}

}  // namespace

std::vector<EglDevice> eglDevices(std::string& why) {
    std::vector<EglDevice> out;
    const auto* list = devices(why);
    if (!list) return out;
    for (EGLDeviceEXT d : *list) {
        EglDevice e;
        e.extensions = deviceString(d, EGL_EXTENSIONS);
        // Mesa marks its llvmpipe device EGL_MESA_device_software; a GPU has a DRM node instead.
        e.software = e.extensions.find("EGL_MESA_device_software") != std::string::npos;
        if (e.extensions.find("EGL_EXT_device_drm") != std::string::npos)
            e.drmFile = deviceString(d, EGL_DRM_DEVICE_FILE_EXT);
        out.push_back(e);
    }
    return out;
}

std::unique_ptr<BackendImpl> createEGLDeviceBackend(int index, std::string& why) {
    const auto* list = devices(why);
    if (!list) return nullptr;
    if (index < 0 || size_t(index) >= list->size()) {
        why = "no EGL device " + std::to_string(index) + " (" + std::to_string(list->size()) + " listed)";
        return nullptr;
    }
    // One display per device, initialised once and kept for the process (as openDisplay, for the same reasons).
    static std::vector<EGLDisplay> displays;
    displays.resize(list->size(), EGL_NO_DISPLAY);
    EGLDisplay& dpy = displays[size_t(index)];
    if (dpy == EGL_NO_DISPLAY) {
        EGLDisplay d = g_egl.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, (*list)[size_t(index)], nullptr);
        EGLint major = 0, minor = 0;
        if (d == EGL_NO_DISPLAY || !g_egl.initialize(d, &major, &minor)) {
            why = "eglInitialize on EGL device " + std::to_string(index) + " failed (" + eglErrorText() + ")";
            return nullptr;
        }
        dpy = d;
    }
    return createContextOn(dpy, why);
}

std::unique_ptr<BackendImpl> createEGLBackend(std::string& why) {
    if (!loadApi(why)) return nullptr;
    EGLDisplay dpy = openDisplay(why);
    if (dpy == EGL_NO_DISPLAY) return nullptr;
    return createContextOn(dpy, why);
}

}  // namespace hilite::gl
