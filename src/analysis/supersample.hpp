#pragma once
// Supersampling of the measurement view by jittered renders: the same frame rendered n x n
// times, each time with every pixel's sample point moved by one offset of an n x n grid of sub-pixel
// cell centres (the shader's uJitter), combined per pixel:
//   - the threshold is T = frac * (largest L over all n^2 samples of all pixels), so the peak is found
//     on a grid n times finer;
//   - a pixel's coverage is the fraction of its n^2 samples with L >= T (samples that see no surface
//     count as out), and it enters the area moments with weight coverage * w at its position, where w and
//     (u, v) are the means over its samples that see the surface (for the symmetric grid, the pixel
//     centre to O(pixel^2)).
// This replaces the boundary treatment of measureImage (Options::subpixel is not used): with n = 1 it
// is exactly the pixel in/out boundary. A pixel cut by the horizon counts the fraction of it above.
// Memory: 4 n^2 + 32 bytes a pixel.

#include "hilite/analysis/highlight.hpp"

#include "hilite/core/math.hpp"

#include <vector>

namespace hilite::analysis {

/// The n x n sub-pixel offsets (pixels, in (-0.5, 0.5)): cell centres, row by row; n = 1 gives (0, 0).
std::vector<dvec2> jitterGrid(int n);

class Supersampler {
public:
    /// Throws InputError unless width, height >= 1 and samples in [1, 1024].
    Supersampler(int width, int height, int samples);
    /// One jittered render of the frame: width*height*4 floats (L, u, v, w), as measureImage reads.
    void add(const float* pixels);
    int added() const { return m_added; }
    /// The combined measurement (after every sample was added; InputError otherwise).
    Shape measure(const Options& opt) const;

private:
    struct PixelSums {
        double u = 0, v = 0, w = 0;  ///< over the samples that see the surface
        int visible = 0;
    };
    int m_width, m_height, m_samples, m_added = 0;
    std::vector<float> m_L;  ///< pixel-major: sample s of pixel p at p * samples + s; -1 = sees no surface
    std::vector<PixelSums> m_sums;
    float m_peak = 0.f;
    bool m_nonFinite = false;  ///< a visible pixel of some render held inf or NaN
    size_t m_peakPixel = 0;
};

}  // namespace hilite::analysis
