#pragma once
// Image dumps: PNG (sRGB-encoded 8-bit, for people) and PFM (the exact float values, for programs).
// Every write goes to a temporary file beside the target and is renamed over it only when complete,
// so a failure never leaves a partial file nor touches an existing one.

#include "core/image.hpp"

#include <string>

namespace hilite::io {

/// Exposure for the PNG: radiance is scaled by 2^ev, then (if `normalizeTo` > 0) by 1 / normalizeTo.
struct Exposure {
    double ev = 0.0;
    double normalizeTo = 0.0;  ///< > 0: divide by this first (e.g. the peak, so the peak maps to 2^ev)
};

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
double srgbEncode(double linear);

/// Writes channels 0..2 of `img` (flipped so row 0 is the top of the picture). Throws InputError on failure.
void writePng(const std::string& path, const ImageF& img, const Exposure& exposure);
/// Writes channels 0..2 as a little-endian RGB PFM ("PF", scale -1), rows bottom to top as PFM stores them.
void writePfm(const std::string& path, const ImageF& img);

/// Checks that `path` can be written (its directory exists and is writable) without creating it;
/// throws InputError naming `flag` otherwise. Call before rendering so bad paths fail fast.
void checkWritable(const std::string& path, const std::string& flag);

/// Writes `bytes` to `path` through a temporary file and rename. Throws InputError on failure.
void writeFileAtomic(const std::string& path, const std::string& bytes);

}  // namespace hilite::io
