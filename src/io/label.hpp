#pragma once
// Text in pictures: contact sheets and strips carry their row and column values, so a tile can be read
// without the caption. Glyphs from stb_easy_font (a public-domain vector font of quads).

#include "hilite/core/image.hpp"

#include <string>

namespace hilite::io {

/// Draws `text` into `img` (rows bottom-up, as rendered) with its top-left corner at (x, yTop) counted from
/// the top, `scale` image pixels per font unit, in linear `value` on every colour channel.
void drawText(ImageF& img, int x, int yTop, const std::string& text, int scale = 2, float value = 1.0f);
/// Width and height in image pixels that drawText covers.
int textWidth(const std::string& text, int scale = 2);
int textHeight(int scale = 2);

}  // namespace hilite::io
