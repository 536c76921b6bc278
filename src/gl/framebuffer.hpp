#pragma once
// The project's own float framebuffer: an RGBA32F colour attachment and a 24-bit depth attachment.
// Values below 0 and above 1 survive; readback is float, in the attachment's own format (the fast path).

#include "hilite/core/image.hpp"

namespace hilite::gl {

class Framebuffer {
public:
    /// Throws InputError if the size exceeds the GL limit, SystemError if incomplete.
    Framebuffer(int width, int height);
    ~Framebuffer();
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    int width() const { return m_width; }
    int height() const { return m_height; }
    void bind() const;
    /// Reads the colour attachment as 4 floats per pixel into `out` (resized as needed): the whole
    /// attachment, or only `rect` (then `out` is rect.width x rect.height).
    void read(ImageF& out, const PixelRect& rect = {}) const;

    /// Largest width/height this context allows (min of renderbuffer size and viewport dims).
    static int maxSize();

private:
    int m_width, m_height;
    unsigned int m_fbo = 0, m_color = 0, m_depth = 0;
};

}  // namespace hilite::gl
