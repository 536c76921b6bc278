#pragma once
// measureImage of variants of one image that differ from it in L at a few pixels (table_error's half tables,
// measurement/in_frame_twin.cpp): the image surveyed once, each variant's L written into the survey's dense L and
// taken out again (the 16-byte pixels are neither copied nor read again per variant), and the moment sums of the
// pixels no variant changes gathered once.

#include "hilite/analysis/highlight.hpp"
#include "hilite/core/math.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace hilite::analysis {

class ImageVariants {
public:
    /// pixels: the (L, u, v, w) image, kept by the caller while this lives. Surveyed here, once.
    ImageVariants(const float* pixels, int width, int height);

    /// The image's L as measureImage reads it: max(0, L) where the pixel sees the surface (w > 0), else -1.
    /// (measure writes a variant's L into it while it runs.)
    const std::vector<float>& luminance() const { return m_dense; }
    float peak() const { return m_peak; }
    /// The first pixel holding the peak (measureImage's: rows bottom-up, then columns); 0 without one.
    size_t peakPixel() const { return m_peakPixel; }
    /// An L of a pixel that sees the surface is an inf or NaN.
    bool nonFinite() const { return m_nonFinite; }

    /// The pixels whose L the variants change (the same for every variant), and the measurement's options (until
    /// it is called: no pixel, the default options).
    void setChanged(std::vector<size_t> at, const Options& opt);
    /// measureImage of the image with L = values[j * stride] at pixel at[j] of setChanged's (ignored where
    /// w <= 0): the same shape to rounding (the pixels that no variant changes are summed once, about the image's
    /// peak). One thread at a time.
    Shape measure(const float* values, size_t stride);
    /// How many measure calls added the fixed pixels' sums (the others summed their whole region).
    long fixedSumsUsed() const { return m_fixedUsed; }

private:
    const float* m_pixels;
    int m_width, m_height;
    std::vector<size_t> m_at, m_atRun;     ///< the patched pixels; the run of 32 that holds each
    std::vector<float> m_dense, m_runMax;  ///< the unpatched image's survey
    std::vector<float> m_runMaxKept;       ///< m_runMax of the pixels left as they are (-1 where none sees the surface)
    float m_peak = 0.f;
    size_t m_peakPixel = 0;
    bool m_nonFinite = false;
    float m_minKept = std::numeric_limits<float>::infinity();  ///< the smallest visible L of the pixels not patched
    bool m_nonFiniteKept = false;                              ///< one of those holds an inf or NaN L
    Options m_opt;
    std::vector<float> m_kept;  ///< m_dense at the changed pixels (measure writes a variant's L there, then these)
    /// The fixed pixels (every pixel but those changed and their 4-neighbours): their moment sums about m_shift at
    /// the image's threshold m_Tf, pixels, flags, and whether one is a contour pixel; valid when m_fixedValid.
    std::vector<uint32_t> m_dependent;  ///< per run of 32: the bits of the pixels that are not fixed
    std::vector<size_t> m_dependentRuns;
    std::array<double, 6> m_fixed{};
    long m_fixedPixels = 0;
    bool m_fixedSky = false, m_fixedBorder = false, m_fixedContour = false, m_fixedValid = false;
    dvec2 m_shift{0.0};
    float m_Tf = 0.f;
    long m_fixedUsed = 0;
    float m_below = 0.f, m_above = 0.f;  ///< the L of the pixels left as they are nearest m_Tf: below, at or above
};

}  // namespace hilite::analysis
