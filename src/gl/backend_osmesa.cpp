// OSMesa backend: Mesa's gallium OSMesa (llvmpipe). This file is the only one that includes
// GL/osmesa.h, which drags in GL/gl.h (see ../shared/notes/gl-platform.md). libOSMesa is opened with
// dlopen(RTLD_LOCAL) so its exported gl* symbols never shadow anything, and a machine without it
// (Mesa >= 25.1 removed OSMesa) still starts and falls back to EGL.

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <memory>
#include <string>

#include "gl/context.hpp"
#include "hilite/core/error.hpp"

namespace hilite::gl {

namespace {

using CreateAttribsFn = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrentFn = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
using DestroyFn = void (*)(OSMesaContext);
using GetProcFn = OSMESAproc (*)(const char*);

GetProcFn g_getProc = nullptr;  // the loader glad calls; set while an OSMesa context exists

void (*osmesaLoad(const char* name))() { return reinterpret_cast<void (*)()>(g_getProc(name)); }

class OSMesaBackend final : public BackendImpl {
public:
    OSMesaBackend(void* lib, OSMesaContext ctx, MakeCurrentFn makeCurrentFn, DestroyFn destroy, GetProcFn getProc)
        : m_lib(lib), m_ctx(ctx), m_makeCurrent(makeCurrentFn), m_destroy(destroy), m_getProc(getProc) {}
    ~OSMesaBackend() override {
        m_destroy(m_ctx);
        // The library stays loaded: llvmpipe's worker threads belong to a process-wide screen.
        (void)m_lib;
    }
    void makeCurrent() override {
        // We render into our own FBO; OSMesa only needs some buffer to bind, so give it 1x1 pixel.
        if (!m_makeCurrent(m_ctx, m_dummy, GL_UNSIGNED_BYTE, 1, 1)) throw SystemError("OSMesaMakeCurrent failed");
        g_getProc = m_getProc;
    }
    ProcLoader loader() const override { return &osmesaLoad; }

private:
    void* m_lib;
    OSMesaContext m_ctx;
    MakeCurrentFn m_makeCurrent;
    DestroyFn m_destroy;
    GetProcFn m_getProc;
    unsigned char m_dummy[4] = {0, 0, 0, 0};
};

void* openLibrary(std::string& why) {
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
        if (void* lib = dlopen(name, RTLD_NOW | RTLD_LOCAL)) return lib;
    }
    const char* err = dlerror();
    why = std::string("libOSMesa not found (") + (err ? err : "dlopen failed") + "); install libosmesa6";
    return nullptr;
}

}  // namespace

std::unique_ptr<BackendImpl> createOSMesaBackend(std::string& why) {
    void* lib = openLibrary(why);
    if (!lib) return nullptr;
    auto create = reinterpret_cast<CreateAttribsFn>(dlsym(lib, "OSMesaCreateContextAttribs"));
    auto makeCurrent = reinterpret_cast<MakeCurrentFn>(dlsym(lib, "OSMesaMakeCurrent"));
    auto destroy = reinterpret_cast<DestroyFn>(dlsym(lib, "OSMesaDestroyContext"));
    auto getProc = reinterpret_cast<GetProcFn>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!create || !makeCurrent || !destroy || !getProc) {
        why = "libOSMesa lacks OSMesaCreateContextAttribs (needs Mesa >= 12)";
        return nullptr;
    }
    // Core profile; 4.5 is llvmpipe's maximum here (asking for 4.6 returns NULL), 3.3 the floor we need.
    // No depth bits: the default framebuffer is never drawn; our FBO has its own depth attachment.
    for (int minorVersion : {45, 33}) {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               0,
                               OSMESA_STENCIL_BITS,
                               0,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               minorVersion / 10,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               minorVersion % 10,
                               0};
        if (OSMesaContext ctx = create(attribs, nullptr))
            return std::make_unique<OSMesaBackend>(lib, ctx, makeCurrent, destroy, getProc);
    }
    why = "OSMesaCreateContextAttribs returned NULL for a GL 4.5 and a 3.3 core profile";
    return nullptr;
}

}  // namespace hilite::gl
