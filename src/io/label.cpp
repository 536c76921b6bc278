#include "io/label.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <vector>

namespace hilite::io {

void drawText(ImageF& img, int x, int yTop, const std::string& text, int scale, float value) {
    // stb_easy_font: 4 vertices (x, y, z, colour: 16 bytes) per quad, y down. Its "about 270 bytes a character"
    // is an average: a '0' takes 8 quads (512 bytes), and a full buffer silently drops the rest ("30" drew as
    // "3" and half a "0"). No glyph has more than 30 segments: 30 quads a character always fit.
    std::vector<char> buffer(text.size() * 30 * 64 + 64);
    std::string copy = text;
    const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(), int(buffer.size()));
    for (int q = 0; q < quads; ++q) {
        const float* v = reinterpret_cast<const float*>(buffer.data() + q * 64);
        const float x0 = std::min(v[0], v[8]), x1 = std::max(v[0], v[8]);
        const float y0 = std::min(v[1], v[9]), y1 = std::max(v[1], v[9]);
        for (int py = int(std::lround(y0 * float(scale))); py < int(std::lround(y1 * float(scale))); ++py)
            for (int px = int(std::lround(x0 * float(scale))); px < int(std::lround(x1 * float(scale))); ++px) {
                const int ix = x + px, iy = img.height - 1 - (yTop + py);
                if (ix < 0 || iy < 0 || ix >= img.width || iy >= img.height) continue;
                float* p = img.pixel(ix, iy);
                for (int c = 0; c < std::min(3, img.channels); ++c) p[c] = value;
                if (img.channels == 4) p[3] = 1.0f;
            }
    }
}

int textWidth(const std::string& text, int scale) {
    std::string copy = text;
    return stb_easy_font_width(copy.data()) * scale;
}

int textHeight(int scale) { return 12 * scale; }

}  // namespace hilite::io
