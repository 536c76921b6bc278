// EGL surfaceless backend (EGL_MESA_platform_surfaceless): the successor to OSMesa, same llvmpipe on a
// machine without a GPU. No surface at all: we render into our own FBO with EGL_NO_SURFACE.
// libEGL is opened with dlopen so that a machine without it still runs with OSMesa.

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "gl/context.hpp"

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

}  // namespace

std::unique_ptr<BackendImpl> createEGLBackend(std::string& why) {
    if (!loadApi(why)) return nullptr;
    EGLDisplay dpy = openDisplay(why);
    if (dpy == EGL_NO_DISPLAY) return nullptr;
    if (!g_egl.bindApi(EGL_OPENGL_API)) {
        why = "eglBindAPI(EGL_OPENGL_API) failed";
        return nullptr;
    }
    // EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT, which the surfaceless platform has none of.
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!g_egl.chooseConfig(dpy, configAttribs, &config, 1, &count) || count < 1) {
        why = "no EGL config with desktop OpenGL";
        return nullptr;
    }
    for (EGLint minorVersion : {45, 33}) {
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, minorVersion / 10, EGL_CONTEXT_MINOR_VERSION,
                                  minorVersion % 10, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLContext ctx = g_egl.createContext(dpy, config, EGL_NO_CONTEXT, attribs);
        if (ctx != EGL_NO_CONTEXT) return std::make_unique<EGLBackend>(dpy, ctx);
    }
    why = "eglCreateContext failed for GL 4.5 and 3.3 core (" + eglErrorText() + ")";
    return nullptr;
}

}  // namespace hilite::gl
