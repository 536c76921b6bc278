#include "gl/framebuffer.hpp"

#include "gl/check.hpp"
#include "hilite/core/error.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace hilite::gl {

namespace {

/// Whether this GL completes an RGBA32F + depth framebuffer of w x h (allocated, checked, freed).
bool completes(int w, int h) {
    GLuint fbo = 0, rb[2] = {0, 0};
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    const bool ok = glGetError() == GL_NO_ERROR && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteRenderbuffers(2, rb);
    glDeleteFramebuffers(1, &fbo);
    while (glGetError() != GL_NO_ERROR) {
    }
    return ok;
}

}  // namespace

int Framebuffer::maxSize() {
    GLint rb = 0, tex = 0, vp[2] = {0, 0};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &tex);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    return std::min({rb, tex, vp[0], vp[1]});
}

Framebuffer::Framebuffer(int width, int height) : m_width(width), m_height(height) {
    const int limit = maxSize();
    if (width < 1 || height < 1 || width > limit || height > limit)
        throw InputError("framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                         " outside this GL's range 1.." + std::to_string(limit));
    glGenFramebuffers(1, &m_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    glGenRenderbuffers(1, &m_color);
    glBindRenderbuffer(GL_RENDERBUFFER, m_color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m_color);
    glGenRenderbuffers(1, &m_depth);
    glBindRenderbuffer(GL_RENDERBUFFER, m_depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m_depth);
    const GLenum error = glGetError();
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (error == GL_OUT_OF_MEMORY || (status != GL_FRAMEBUFFER_COMPLETE && (width > 4096 || height > 4096))) {
        // The GL's size limits allow it, but it cannot allocate this much (llvmpipe caps one buffer's bytes:
        // 12000x12000 RGBA32F failed, 8192x8192 worked, measured): find the largest square that completes.
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        int lo = 1, hi = std::max(width, height);
        while (hi - lo > 1) {
            const int mid = lo + (hi - lo) / 2;
            (completes(mid, mid) ? lo : hi) = mid;
        }
        throw InputError("--size: " + std::to_string(width) + "x" + std::to_string(height) +
                         " is more than this GL can allocate for its float framebuffer; the largest square that "
                         "works here is " +
                         std::to_string(lo) + "x" + std::to_string(lo));
    }
    if (error != GL_NO_ERROR || status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[64];
        std::snprintf(hex, sizeof hex, "GL error 0x%04x, status 0x%04x", unsigned(error), unsigned(status));
        throw SystemError(std::string("creating the float framebuffer: ") + hex);
    }
}

Framebuffer::~Framebuffer() {
    if (m_depth) glDeleteRenderbuffers(1, &m_depth);
    if (m_color) glDeleteRenderbuffers(1, &m_color);
    if (m_fbo) glDeleteFramebuffers(1, &m_fbo);
}

void Framebuffer::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    glViewport(0, 0, m_width, m_height);
}

void Framebuffer::read(ImageF& out, const PixelRect& rect) const {
    const PixelRect r = rect.empty() ? PixelRect{0, 0, m_width, m_height} : rect;
    if (r.x < 0 || r.y < 0 || r.x + r.width > m_width || r.y + r.height > m_height)
        throw std::logic_error("Framebuffer::read: rectangle outside the framebuffer");
    // Reshaped in place: a sweep's crops differ in size each time, and a new image would be allocated and
    // zeroed per render (a 4 MB memset at 512^2) only for glReadPixels to overwrite it.
    if (out.width != r.width || out.height != r.height || out.channels != 4) {
        out.width = r.width, out.height = r.height, out.channels = 4;
        out.data.resize(size_t(r.width) * size_t(r.height) * 4);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(r.x, r.y, r.width, r.height, GL_RGBA, GL_FLOAT, out.data.data());
    HILITE_GL_CHECK_WHAT("glReadPixels");
}

}  // namespace hilite::gl
