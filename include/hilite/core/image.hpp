#pragma once
// A row-major float image with interleaved channels, row 0 at the bottom (OpenGL's readback order).

#include <cstddef>
#include <vector>

namespace hilite {

/// A rectangle of pixels (x, y: its lower-left pixel; row 0 at the bottom). Empty (width 0): the whole image.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool empty() const { return width <= 0 || height <= 0; }
};

struct ImageF {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> data;

    ImageF() = default;
    ImageF(int w, int h, int c) : width(w), height(h), channels(c), data(size_t(w) * size_t(h) * size_t(c), 0.f) {}

    float* pixel(int x, int y) { return data.data() + (size_t(y) * size_t(width) + size_t(x)) * size_t(channels); }
    const float* pixel(int x, int y) const {
        return data.data() + (size_t(y) * size_t(width) + size_t(x)) * size_t(channels);
    }
};

}  // namespace hilite
